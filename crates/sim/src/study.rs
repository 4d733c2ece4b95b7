//! Studies: many runs of one run file, over a grid of parameters and seeds, with their
//! aggregates (`haff study`, `haff.study` in Python).
//!
//! ```toml
//! base = "gas.toml"                  # a run file, or an inline [base] table with its sections
//! seeds = 8                          # replicas per point: system.seed = base seed + replica
//! [vary]                             # the cross product of these lists (dotted keys)
//! "collision.restitution" = [0.5, 0.7, 0.9]
//! "system.packing_fraction" = [0.05, 0.1]
//! [[zip]]                            # lists that vary together (one axis, equal lengths)
//! "run.collisions_per_particle" = [50, 100]
//! "run.samples" = [20, 40]
//! ```
//!
//! The points are the cross product of the axes (each `[vary]` key, then each `[[zip]]`
//! table, in the file's order; the last axis varies fastest). Every run is a complete
//! `haff run` in `DIR/runs/<point>/<seed>/` ([`run_dir`]) with its manifest and
//! check-points, so that a study killed at any moment continues with the same command:
//! finished runs are kept, interrupted ones resume from their check-points bit for bit
//! ([`execute`]). The aggregates ([`aggregate`]) are computed from the runs' own files.

mod aggregate;
mod execute;
mod figures;

pub use aggregate::{aggregate, Aggregates, ENSEMBLE_HEADER};
pub use execute::{
    execute, open_study_dir, run_one, RunOutcome, StudyProgress, CHECKPOINT_SECONDS, STUDY_MANIFEST,
};

use crate::description::RunDescription;
use crate::error::{Error, Result};
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The most replicas per point and runs per study.
pub const MAX_SEEDS: u64 = 100_000;
pub const MAX_RUNS: usize = 1_000_000;

/// A study file, as written.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyFile {
    /// The run file (relative to the study file) or an inline table of its sections.
    pub base: Base,
    /// Replicas per point (1 ..= 100000): seeds base seed + 0, 1, ...
    #[serde(default = "one")]
    pub seeds: u64,
    /// Dotted keys of the run file and their lists of values (the cross product).
    #[serde(default)]
    pub vary: IndexMap<String, Vec<toml::Value>>,
    /// Keys whose lists vary together: each table is one axis.
    #[serde(default)]
    pub zip: Vec<IndexMap<String, Vec<toml::Value>>>,
}

fn one() -> u64 {
    1
}

/// The base run: a file or the sections inline.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Base {
    File(PathBuf),
    Inline(toml::Table),
}

/// One point of a study: its index and the value of each varied key.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Point {
    pub index: usize,
    pub values: IndexMap<String, toml::Value>,
}

/// A study: its base run table, its points and replicas, checked.
#[derive(Debug, Clone)]
pub struct Study {
    pub file: StudyFile,
    /// The base run file's table (the file read, or the inline table).
    pub base: toml::Table,
    /// Where the base came from (error messages).
    pub base_origin: PathBuf,
    /// The seed of replica 0 (the base's `system.seed`, default 1).
    pub first_seed: u64,
    pub points: Vec<Point>,
}

impl Study {
    /// Reads and checks a study file (relative `base` paths from its directory).
    pub fn from_path(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::RunFile {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        Self::from_toml(&text, path)
    }

    /// Parses and checks a study given as TOML text read from `origin`.
    pub fn from_toml(text: &str, origin: &Path) -> Result<Self> {
        let file: StudyFile = crate::description::parse_toml(text, origin)?;
        let folder = origin.parent().unwrap_or(Path::new("."));
        Self::new(file, folder)
    }

    /// A study whose relative base path starts from `folder`, its axes checked; the runs
    /// are checked by [`Study::check_runs`] (or listed by [`Study::invalid_points`]).
    pub fn new(file: StudyFile, folder: &Path) -> Result<Self> {
        if !(1..=MAX_SEEDS).contains(&file.seeds) {
            return Err(Error::out_of_range(
                "seeds",
                file.seeds,
                &format!("1 ..= {MAX_SEEDS} replicas per point"),
            ));
        }
        let (base, base_origin) = match &file.base {
            Base::Inline(table) => (table.clone(), PathBuf::from("[base]")),
            Base::File(path) => {
                let path = folder.join(path);
                let text = std::fs::read_to_string(&path)
                    .map_err(|e| Error::input("base", format!("{}: {e}", path.display())))?;
                let table: toml::Table =
                    text.parse().map_err(|e: toml::de::Error| Error::RunFile {
                        path: path.clone(),
                        message: e.to_string().replace('\n', " "),
                    })?;
                (table, path)
            }
        };
        let first_seed = match lookup(&base, "system.seed") {
            None => 1,
            Some(toml::Value::Integer(s)) if *s >= 0 => *s as u64,
            Some(other) => {
                return Err(Error::input(
                    "base: system.seed",
                    format!("{other} is not a seed (an integer >= 0)"),
                ))
            }
        };
        let axes = axes(&file)?;
        let points = expand(&axes)?;
        let study = Study {
            file,
            base,
            base_origin,
            first_seed,
            points,
        };
        if study.runs() > MAX_RUNS {
            return Err(Error::out_of_range(
                "seeds",
                study.runs(),
                &format!("at most {MAX_RUNS} runs (points times seeds)"),
            ));
        }
        Ok(study)
    }

    /// Replicas per point.
    pub fn seeds(&self) -> u64 {
        self.file.seeds
    }

    /// Points times replicas.
    pub fn runs(&self) -> usize {
        self.points.len() * self.file.seeds as usize
    }

    /// The varied keys in the order of the axes.
    pub fn keys(&self) -> Vec<String> {
        self.points
            .first()
            .map(|p| p.values.keys().cloned().collect())
            .unwrap_or_default()
    }

    /// The seed of `replica`.
    pub fn seed(&self, replica: u64) -> u64 {
        self.first_seed + replica
    }

    /// The run table of `point` and `replica`: the base with the point's values and the
    /// replica's seed.
    pub fn run_table(&self, point: &Point, replica: u64) -> Result<toml::Table> {
        let mut table = self.base.clone();
        for (key, value) in &point.values {
            set(&mut table, key, value.clone())?;
        }
        set(
            &mut table,
            "system.seed",
            toml::Value::Integer(self.seed(replica) as i64),
        )?;
        Ok(table)
    }

    /// The checked run description of `point` and `replica` (errors name the point and
    /// the key).
    pub fn run_description(&self, point: &Point, replica: u64) -> Result<RunDescription> {
        let named = |e: Error| name_point(e, point, &self.base_origin);
        let table = self.run_table(point, replica).map_err(named)?;
        let text = toml::to_string(&table).map_err(|e| named(Error::input("base", e)))?;
        let description = RunDescription::from_toml(&text, &self.base_origin).map_err(named)?;
        let plan = crate::validate(&description).map_err(named)?;
        // The law's own checks (its parameters' ranges) as a run makes them.
        crate::law::of_plan(&plan).map_err(named)?;
        Ok(description)
    }

    /// Validates the run of every point (the first replica's: replicas differ by the seed
    /// alone); the first error names its point and key.
    pub fn check_runs(&self) -> Result<()> {
        for point in &self.points {
            self.run_description(point, 0)?;
        }
        Ok(())
    }

    /// The points whose runs do not validate, with the error of each (for a study that
    /// goes on without them).
    pub fn invalid_points(&self) -> Vec<(usize, String)> {
        self.points
            .iter()
            .filter_map(|p| {
                self.run_description(p, 0)
                    .err()
                    .map(|e| (p.index, e.to_string()))
            })
            .collect()
    }

    /// The hash that names the study: CRC-32 of every run's description (so that a
    /// changed base file makes another study).
    pub fn hash(&self) -> String {
        let tables: Vec<_> = self
            .points
            .iter()
            .map(|p| self.run_table(p, 0).ok())
            .collect();
        crate::outdir::run_hash(&(self.file.seeds, self.first_seed, tables))
    }
}

/// `DIR/runs/<point>/<seed>`: the point's index (3 digits at least) and the seed.
pub fn run_dir(dir: &Path, point: usize, seed: u64) -> PathBuf {
    dir.join("runs")
        .join(format!("{point:03}"))
        .join(seed.to_string())
}

/// An error of a point's run, naming the point and its values.
fn name_point(error: Error, point: &Point, origin: &Path) -> Error {
    let values: Vec<String> = point
        .values
        .iter()
        .map(|(k, v)| format!("{k} = {v}"))
        .collect();
    let at = format!("point {} ({})", point.index, values.join(", "));
    match error {
        Error::Input { key, message } => Error::Input {
            key: format!("{at}: {key}"),
            message,
        },
        Error::RunFile { message, .. } => Error::Input {
            key: at,
            message: format!("{}: {message}", origin.display()),
        },
        other => Error::input(at, other),
    }
}

/// One axis: keys and their values, one list per key, all of one length.
struct Axis {
    keys: Vec<String>,
    values: Vec<Vec<toml::Value>>,
}

fn axes(file: &StudyFile) -> Result<Vec<Axis>> {
    let mut axes = Vec::new();
    let mut seen = std::collections::HashSet::new();
    let mut check_key = |key: &str, field: String| -> Result<()> {
        if key.split('.').count() < 2 || key.split('.').any(|part| part.is_empty()) {
            return Err(Error::input(
                field,
                format!("`{key}` is not a dotted key of the run file (section.key)"),
            ));
        }
        if key == "system.seed" {
            return Err(Error::input(
                field,
                "system.seed is the replicas' (seeds = N: base seed + 0 .. N-1)",
            ));
        }
        if !seen.insert(key.to_string()) {
            return Err(Error::input(field, format!("`{key}` is varied twice")));
        }
        Ok(())
    };
    for (key, values) in &file.vary {
        check_key(key, format!("vary.\"{key}\""))?;
        if values.is_empty() {
            return Err(Error::input(
                format!("vary.\"{key}\""),
                "an empty list (give at least one value)",
            ));
        }
        axes.push(Axis {
            keys: vec![key.clone()],
            values: values.iter().map(|v| vec![v.clone()]).collect(),
        });
    }
    for (z, table) in file.zip.iter().enumerate() {
        let mut lengths = table.values().map(Vec::len);
        let Some(length) = lengths.next() else {
            return Err(Error::input(format!("zip[{z}]"), "an empty table"));
        };
        for (key, values) in table {
            check_key(key, format!("zip[{z}].\"{key}\""))?;
            if values.len() != length || length == 0 {
                return Err(Error::input(
                    format!("zip[{z}].\"{key}\""),
                    format!(
                        "{} values: the lists of a [[zip]] table vary together and need one \
                         length ({length}, not 0)",
                        values.len()
                    ),
                ));
            }
        }
        axes.push(Axis {
            keys: table.keys().cloned().collect(),
            values: (0..length)
                .map(|i| table.values().map(|v| v[i].clone()).collect())
                .collect(),
        });
    }
    Ok(axes)
}

/// The cross product of the axes, the last varying fastest (one point without axes).
fn expand(axes: &[Axis]) -> Result<Vec<Point>> {
    let count = axes
        .iter()
        .try_fold(1usize, |n, a| n.checked_mul(a.values.len()))
        .filter(|&n| n <= MAX_RUNS)
        .ok_or_else(|| {
            Error::out_of_range("vary", "too many points", &format!("at most {MAX_RUNS}"))
        })?;
    Ok((0..count)
        .map(|index| {
            let mut values = IndexMap::new();
            let mut rest = index;
            let mut picks = vec![0; axes.len()];
            for (a, axis) in axes.iter().enumerate().rev() {
                picks[a] = rest % axis.values.len();
                rest /= axis.values.len();
            }
            for (axis, &pick) in axes.iter().zip(&picks) {
                for (key, value) in axis.keys.iter().zip(&axis.values[pick]) {
                    values.insert(key.clone(), value.clone());
                }
            }
            Point { index, values }
        })
        .collect())
}

/// The value at a dotted key of a table, if any.
fn lookup<'a>(table: &'a toml::Table, key: &str) -> Option<&'a toml::Value> {
    let mut parts = key.split('.');
    let mut value = table.get(parts.next()?)?;
    for part in parts {
        value = value.as_table()?.get(part)?;
    }
    Some(value)
}

/// Sets a dotted key of a table, making the tables on the way; fails where a part of the
/// path is not a table.
fn set(table: &mut toml::Table, key: &str, value: toml::Value) -> Result<()> {
    let parts: Vec<&str> = key.split('.').collect();
    let (last, path) = parts.split_last().expect("split yields one part at least");
    let mut here = table;
    for (i, part) in path.iter().enumerate() {
        let entry = here
            .entry(part.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        here = entry.as_table_mut().ok_or_else(|| {
            Error::input(
                key,
                format!("`{}` is not a table of the run file", parts[..=i].join(".")),
            )
        })?;
    }
    here.insert(last.to_string(), value);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const BASE: &str = "[system]\nparticles = 100\npacking_fraction = 0.05\nseed = 7\n\
                        [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
                        [run]\ncollisions_per_particle = 2\nsamples = 3\n";

    fn study(extra: &str) -> Result<Study> {
        let text = format!(
            "seeds = 2\n{extra}\n[base]\n{}",
            BASE.replace("[", "[base.")
        );
        let study = Study::from_toml(&text, Path::new("study.toml"))?;
        study.check_runs()?;
        Ok(study)
    }

    /// Points are the cross product in the file's order, the last axis fastest; a zip
    /// table is one axis; replicas take the base seed plus their index.
    #[test]
    fn points_are_the_cross_product_in_file_order() {
        let s = study(
            "[vary]\n\"collision.restitution\" = [0.5, 0.7, 0.9]\n\
             \"system.packing_fraction\" = [0.05, 0.1]\n\
             [[zip]]\n\"run.samples\" = [3, 4]\n\"run.collisions_per_particle\" = [2, 3]\n",
        )
        .unwrap();
        assert_eq!(s.points.len(), 12);
        assert_eq!(
            s.keys(),
            [
                "collision.restitution",
                "system.packing_fraction",
                "run.samples",
                "run.collisions_per_particle"
            ]
        );
        let p = &s.points[7]; // 7 = 1 * 4 + 1 * 2 + 1
        assert_eq!(p.values["collision.restitution"].as_float(), Some(0.7));
        assert_eq!(p.values["system.packing_fraction"].as_float(), Some(0.1));
        assert_eq!(p.values["run.samples"].as_integer(), Some(4));
        assert_eq!(
            p.values["run.collisions_per_particle"].as_integer(),
            Some(3)
        );
        let d = s.run_description(p, 1).unwrap();
        assert_eq!(d.system.seed, 8);
        assert_eq!(s.runs(), 24);
        assert_eq!(run_dir(Path::new("d"), 7, 8), Path::new("d/runs/007/8"));
    }

    /// Bad studies are refused naming the field; a point whose run does not validate is
    /// named with its values and the run's key.
    #[test]
    fn bad_studies_name_the_field_and_the_point() {
        let error = |extra: &str| study(extra).unwrap_err().to_string();
        assert!(error("[vary]\n\"collision.restitution\" = []").contains("vary"));
        assert!(error("[vary]\n\"restitution\" = [0.5]").contains("dotted key"));
        assert!(error("[vary]\n\"system.seed\" = [1, 2]").contains("replicas"));
        assert!(
            error("[[zip]]\n\"run.samples\" = [3]\n\"collision.restitution\" = [0.5, 0.6]")
                .contains("zip[0]")
        );
        let e = error("[vary]\n\"collision.restitution\" = [0.5, 1.5]");
        assert!(e.contains("point 1") && e.contains("restitution"), "{e}");
        let e = error("[vary]\n\"collision.restitution.x\" = [0.5]");
        assert!(e.contains("not a table"), "{e}");
        let e = Study::from_toml("seeds = 0\nbase = \"x.toml\"", Path::new("s.toml"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("seeds"), "{e}");
        let e = Study::from_toml("base = \"missing.toml\"", Path::new("s.toml"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("missing.toml"), "{e}");
        let e = Study::from_toml("base = \"x.toml\"\nsede = 3", Path::new("s.toml"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("sede"), "{e}");
    }
}
