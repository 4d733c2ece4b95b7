//! The JSON Schema of the run file (`sim::schema`, printed by `haff schema`) judged by an
//! independent validator, the `jsonschema` crate, against haff's own reading of run files.
//!
//! The oracle is haff: `RunDescription::from_toml` (serde: unknown keys and names, wrong
//! types, refused by name) and the checks of a run before it starts (`sim::validate`, then
//! the laws and walls built as a run builds them). The schema is a necessary condition, so:
//! - a run file haff accepts satisfies the schema (converted TOML -> JSON), and
//! - a run file haff refuses while reading it fails the schema too.
//!
//! The files: every run file of the repository (`git ls-files '*.toml'` less the Cargo,
//! pyproject, book and taplo files, study files and rod-chain files) and a few written here
//! for the sections and names none of those uses. Their mutants: each key misspelled, each
//! value of another type, each string misspelled, each number moved to the edges of ranges
//! (for numbers only the first implication is checked: haff accepts => the schema accepts;
//! the schema does not know the ranges that depend on other keys).

use serde_json::Value as Json;
use sim::RunDescription;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use toml::Value;

fn repository() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

fn validator() -> &'static jsonschema::Validator {
    static VALIDATOR: OnceLock<jsonschema::Validator> = OnceLock::new();
    VALIDATOR.get_or_init(|| jsonschema::validator_for(&sim::schema::run_file_schema()).unwrap())
}

/// What haff makes of a run file.
#[derive(Debug, PartialEq)]
enum Verdict {
    Accepted,
    /// Refused by `from_toml`, with the message.
    RefusedReading(String),
    /// Refused by validation or the building of the laws and walls.
    RefusedChecking(String),
}

fn judge(text: &str) -> Verdict {
    let description = match RunDescription::from_toml(text, Path::new("mutant.toml")) {
        Ok(d) => d,
        Err(e) => return Verdict::RefusedReading(e.to_string()),
    };
    let checked = sim::validate(&description).and_then(|plan| {
        sim::law::of_plan(&plan)?;
        let speed = sim::validate::wall_impact_speed(&plan);
        for (i, wall) in plan.walls.iter().enumerate() {
            wall.build(i, speed)?;
        }
        Ok(())
    });
    match checked {
        Ok(()) => Verdict::Accepted,
        Err(e) => Verdict::RefusedChecking(e.to_string()),
    }
}

/// The schema's errors for a run file (empty: it satisfies the schema).
fn schema_errors(table: &toml::Table) -> Vec<String> {
    let json = serde_json::to_value(table).unwrap();
    validator()
        .iter_errors(&json)
        .map(|e| format!("{} at {}", e, e.instance_path()))
        .collect()
}

/// The run files of the repository, by path, and those written here.
fn run_files() -> Vec<(String, String)> {
    let root = repository();
    let listed = std::process::Command::new("git")
        .args(["ls-files", "*.toml"])
        .current_dir(&root)
        .output()
        .expect("git lists the repository's files");
    let skipped = [
        "Cargo.toml",
        "pyproject.toml",
        "book.toml",
        ".taplo.toml",
        "taplo.toml",
    ];
    let mut files: Vec<(String, String)> = String::from_utf8(listed.stdout)
        .unwrap()
        .lines()
        .filter(|p| !skipped.iter().any(|s| p.rsplit('/').next() == Some(*s)))
        .filter_map(|p| {
            let text = std::fs::read_to_string(root.join(p)).ok()?;
            let table: toml::Table = text.parse().ok()?;
            // Study files (`base`) and rod-chain files (`[chain]`) have shapes of their own.
            (!table.contains_key("base") && !table.contains_key("chain"))
                .then(|| (p.to_string(), text))
        })
        .collect();
    assert!(files.len() >= 40, "run files found: {}", files.len());
    files.extend(written_here());
    files
}

/// Run files for what no repository file has: shear, a vibrating dash-pot wall, rough
/// spheres, a particle file.
fn written_here() -> Vec<(String, String)> {
    let dir = std::env::temp_dir().join(format!("haff-schema-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let lattice = dir.join("lattice.csv");
    let c = sim::particles::Configuration {
        dimension: 2,
        sides: vec![12.0, 12.0],
        positions: (0..36)
            .map(|i| [1.0 + 2.0 * (i % 6) as f64, 1.0 + 2.0 * (i / 6) as f64, 0.0])
            .collect(),
        velocities: Some(
            (0..36)
                .map(|i| [(i as f64).sin(), (i as f64).cos(), 0.0])
                .collect(),
        ),
        diameters: Some(vec![1.2; 36]),
        masses: None,
        species: None,
        spins: None,
        time: None,
    };
    sim::particles::write(&lattice, sim::particles::Format::Csv, &c).unwrap();
    let files = [
        "[system]\ndimension = 3\nparticles = 100\npacking_fraction = 0.1\ninertia = 0.4\n\
         rotational_temperature = 0.5\n\
         [collision]\nlaw = \"viscoelastic\"\nbeta = 0.05\nform = \"pade:3/6\"\n\
         tangential_restitution = 0.5\nfriction = 0.3\n\
         [run]\ncollisions_per_particle = 3\nsamples = 3\nspacing = \"linear\"\n\
         [output]\npressure = true\n\
         [shear]\nrate = 0.5\n"
            .to_string(),
        "[system]\ndimension = 2\nparticles = 60\nbox = [20.0, 40.0]\n\
         [collision]\nlaw = \"dashpot\"\ndamping_ratio = 0.1\ncriterion = \"naive\"\n\
         [run]\ncollisions_per_particle = 3\nsamples = 3\n\
         [output]\nprofiles = { axis = \"y\", bins = 4 }\nmsd = true\n\
         snapshots = { every = 1, format = [\"vtk\", \"xyz\"] }\n\
         [field]\ngravity = [0.0, -0.5]\nrest_height = 1e-3\n\
         [[wall]]\naxis = \"y\"\nside = \"low\"\nkind = \"vibrating\"\namplitude = 0.3\n\
         frequency = 1.0\nwaveform = \"sawtooth\"\nlaw = \"dashpot\"\ndamping_ratio = 0.2\n\
         criterion = \"naive\"\n\
         [[wall]]\naxis = \"y\"\nside = \"high\"\nkind = \"restitution\"\nlaw = \"viscoelastic\"\n\
         beta = 0.1\nform = \"exact\"\n"
            .to_string(),
        format!(
            "[system]\ndimension = 2\n\
             initial = {{ file = {:?}, format = \"csv\", frame = -1, momentum = \"remove\", \
             density = 1.0 }}\n\
             [collision]\nlaw = \"constant\"\nrestitution = 0.8\n\
             [run]\ncollisions_per_particle = 3\nsamples = 3\n",
            lattice.display().to_string()
        ),
    ];
    files
        .into_iter()
        .enumerate()
        .map(|(i, text)| (format!("written-here-{i}.toml"), text))
        .collect()
}

/// A step of the path to a value in a TOML document.
#[derive(Debug, Clone)]
enum Step {
    Key(String),
    Index(usize),
}

fn dotted(path: &[Step]) -> String {
    let names: Vec<&str> = path
        .iter()
        .filter_map(|s| match s {
            Step::Key(k) => Some(k.as_str()),
            Step::Index(_) => None,
        })
        .collect();
    names.join(".")
}

/// The paths of every value of `table` (keys of tables, entries of arrays).
fn paths(table: &toml::Table) -> Vec<Vec<Step>> {
    fn walk(value: &Value, path: Vec<Step>, out: &mut Vec<Vec<Step>>) {
        match value {
            Value::Table(t) => {
                for (k, v) in t {
                    let mut p = path.clone();
                    p.push(Step::Key(k.clone()));
                    out.push(p.clone());
                    walk(v, p, out);
                }
            }
            Value::Array(a) => {
                for (i, v) in a.iter().enumerate() {
                    let mut p = path.clone();
                    p.push(Step::Index(i));
                    out.push(p.clone());
                    walk(v, p, out);
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(&Value::Table(table.clone()), Vec::new(), &mut out);
    out
}

fn at<'a>(value: &'a mut Value, path: &[Step]) -> &'a mut Value {
    path.iter().fold(value, |v, step| match step {
        Step::Key(k) => v.get_mut(k.as_str()).unwrap(),
        Step::Index(i) => v.get_mut(*i).unwrap(),
    })
}

/// A mutant of a run file: what was changed, where, and the document.
struct Mutant {
    what: &'static str,
    path: Vec<Step>,
    table: toml::Table,
}

/// Every mutant of `table` but the numbers: keys misspelled, values of another type,
/// strings misspelled.
fn mutants(table: &toml::Table) -> Vec<Mutant> {
    let mut out = Vec::new();
    for path in paths(table) {
        let mut doc = Value::Table(table.clone());
        let value = at(&mut doc, &path).clone();
        if let Some(Step::Key(key)) = path.last() {
            // The key with its last letter dropped: `restitutio`, `systm`-like slips.
            let mut doc = Value::Table(table.clone());
            let parent = at(&mut doc, &path[..path.len() - 1])
                .as_table_mut()
                .unwrap();
            let slip = if key.len() > 1 {
                key[..key.len() - 1].to_string()
            } else {
                format!("{key}x")
            };
            let v = parent.remove(key).unwrap();
            parent.insert(slip, v);
            out.push(Mutant {
                what: "misspelled key",
                path: path.clone(),
                table: doc.as_table().unwrap().clone(),
            });
        }
        let other = match &value {
            Value::String(_) => Value::Integer(7),
            Value::Integer(_) | Value::Float(_) => Value::String("7".into()),
            Value::Boolean(b) => Value::String(b.to_string()),
            Value::Array(_) | Value::Table(_) | Value::Datetime(_) => Value::Boolean(true),
        };
        let mut doc = Value::Table(table.clone());
        *at(&mut doc, &path) = other;
        out.push(Mutant {
            what: "wrong type",
            path: path.clone(),
            table: doc.as_table().unwrap().clone(),
        });
        if let Value::String(s) = &value {
            let mut doc = Value::Table(table.clone());
            *at(&mut doc, &path) = Value::String(format!("{s}q"));
            out.push(Mutant {
                what: "misspelled value",
                path: path.clone(),
                table: doc.as_table().unwrap().clone(),
            });
        }
    }
    out
}

/// Every mutant of `table` with a number moved to the edge of a range.
fn number_mutants(table: &toml::Table) -> Vec<Mutant> {
    let integers: [i64; 12] = [
        -1,
        0,
        1,
        2,
        3,
        4,
        5,
        101,
        10_001,
        1_000_001,
        100_000_001,
        4_294_967_296,
    ];
    let floats: [f64; 17] = [
        -1e31, -2.0, -1.0, -0.5, 0.0, 1e-31, 1e-13, 1e-5, 0.5, 0.7, 0.95, 1.0, 1.5, 2.0, 100.5,
        1e7, 1e31,
    ];
    let mut out = Vec::new();
    for path in paths(table) {
        let mut doc = Value::Table(table.clone());
        let candidates: Vec<Value> = match at(&mut doc, &path) {
            Value::Integer(_) => integers.iter().map(|&i| Value::Integer(i)).collect(),
            Value::Float(_) => floats.iter().map(|&x| Value::Float(x)).collect(),
            _ => continue,
        };
        for value in candidates {
            let mut doc = Value::Table(table.clone());
            *at(&mut doc, &path) = value;
            out.push(Mutant {
                what: "number",
                path: path.clone(),
                table: doc.as_table().unwrap().clone(),
            });
        }
    }
    out
}

/// The dotted keys of the schema whose values are closed sets of names (an enumeration,
/// constants or a pattern), found by walking the schema from its root.
fn closed_keys(schema: &Json) -> BTreeSet<String> {
    let defs = schema["$defs"].as_object().unwrap();
    let resolve = |s: &Json| -> Json {
        match s.get("$ref").and_then(Json::as_str) {
            Some(r) => defs[r.trim_start_matches("#/$defs/")].clone(),
            None => s.clone(),
        }
    };
    fn closed(s: &Json, resolve: &dyn Fn(&Json) -> Json) -> bool {
        let s = resolve(s);
        ["enum", "const", "pattern"]
            .iter()
            .any(|k| s.get(k).is_some())
            || ["anyOf", "oneOf"].iter().any(|k| {
                s.get(k)
                    .and_then(Json::as_array)
                    .is_some_and(|a| a.iter().any(|x| closed(x, resolve)))
            })
            || s.get("items").is_some_and(|i| closed(i, resolve))
    }
    fn tables(s: &Json, resolve: &dyn Fn(&Json) -> Json) -> Vec<Json> {
        let s = resolve(s);
        let mut out = Vec::new();
        if s.get("properties").is_some() {
            out.push(s.clone());
        }
        for k in ["anyOf", "oneOf"] {
            for x in s.get(k).and_then(Json::as_array).into_iter().flatten() {
                out.extend(tables(x, resolve));
            }
        }
        if let Some(items) = s.get("items") {
            out.extend(tables(items, resolve));
        }
        out
    }
    fn walk(
        table: &Json,
        prefix: &str,
        resolve: &dyn Fn(&Json) -> Json,
        out: &mut BTreeSet<String>,
    ) {
        for (key, s) in table["properties"].as_object().unwrap() {
            let path = if prefix.is_empty() {
                key.clone()
            } else {
                format!("{prefix}.{key}")
            };
            let inner = tables(s, resolve);
            if inner.is_empty() && closed(s, resolve) {
                out.insert(path.clone());
            }
            for t in inner {
                walk(&t, &path, resolve, out);
            }
        }
    }
    let mut out = BTreeSet::new();
    walk(schema, "", &resolve, &mut out);
    out
}

#[test]
fn the_schema_is_a_json_schema_of_draft_2020_12() {
    let schema = sim::schema::run_file_schema();
    assert_eq!(
        schema["$schema"],
        "https://json-schema.org/draft/2020-12/schema"
    );
    assert_eq!(schema["title"], sim::schema::TITLE);
    jsonschema::meta::validate(&schema).unwrap();
}

#[test]
fn the_schema_agrees_with_haff_on_every_run_file_and_its_mutants() {
    // Paths in run files (particle files, tables) are relative to the working directory:
    // the repository's root, as for `haff run docs/data/...`.
    std::env::set_current_dir(repository()).unwrap();
    let files = run_files();
    let mut misspelled_sections = BTreeSet::new();
    let mut misspelled_names = BTreeSet::new();
    let (mut judged, mut refused_by_both) = (0, 0);
    let mut failures = Vec::new();
    let mut read_only = Vec::new();
    for (name, text) in &files {
        // A file that needs the output of another run (`system.initial.run`) is only read:
        // its mutants are judged by the reading alone.
        let checkable = match judge(text) {
            Verdict::Accepted => true,
            Verdict::RefusedChecking(_) if text.contains("initial") => false,
            other => panic!("{name} is a valid run file: {other:?}"),
        };
        if !checkable {
            read_only.push(name.clone());
        }
        let table: toml::Table = text.parse().unwrap();
        let errors = schema_errors(&table);
        assert!(errors.is_empty(), "{name} fails the schema: {errors:#?}");
        for mutant in mutants(&table) {
            let text = toml::to_string(&mutant.table).unwrap();
            let verdict = judge(&text);
            let errors = schema_errors(&mutant.table);
            judged += 1;
            let key = dotted(&mutant.path);
            let wrong = match &verdict {
                Verdict::Accepted => !errors.is_empty(),
                Verdict::RefusedReading(_) => errors.is_empty(),
                Verdict::RefusedChecking(_) => false,
            };
            if wrong {
                failures.push(format!(
                    "{name}, {} `{key}`: haff {verdict:?}, schema {errors:?}",
                    mutant.what
                ));
            }
            if !errors.is_empty() && verdict != Verdict::Accepted {
                refused_by_both += 1;
                match mutant.what {
                    "misspelled key" if mutant.path.len() == 1 => {
                        misspelled_sections.insert(key);
                    }
                    "misspelled value" => {
                        misspelled_names.insert(key);
                    }
                    _ => {}
                }
            }
        }
        for mutant in number_mutants(&table).into_iter().filter(|_| checkable) {
            let errors = schema_errors(&mutant.table);
            if errors.is_empty() {
                continue;
            }
            judged += 1;
            let text = toml::to_string(&mutant.table).unwrap();
            let verdict = judge(&text);
            if verdict == Verdict::Accepted {
                failures.push(format!(
                    "{name}, `{}` = {}: haff accepts it, the schema refuses: {errors:?}",
                    dotted(&mutant.path),
                    at(&mut Value::Table(mutant.table.clone()), &mutant.path)
                ));
            } else {
                refused_by_both += 1;
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    let schema = sim::schema::run_file_schema();
    let sections: BTreeSet<String> = schema["properties"]
        .as_object()
        .unwrap()
        .keys()
        .cloned()
        .collect();
    assert_eq!(
        misspelled_sections, sections,
        "every section misspelled somewhere"
    );
    let names = closed_keys(&schema);
    let missing: Vec<&String> = names.difference(&misspelled_names).collect();
    assert!(
        missing.is_empty(),
        "no file gives these names to misspell: {missing:?}"
    );
    eprintln!(
        "{} run files ({} read only: {read_only:?}); {judged} mutants judged, {refused_by_both} \
         refused by both",
        files.len(),
        read_only.len()
    );
}
