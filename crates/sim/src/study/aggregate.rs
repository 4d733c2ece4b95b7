//! A study's aggregates, computed from its runs' own files (so that a study resumed in
//! another process, or run by workers elsewhere, aggregates the same): `ensemble.csv`
//! (every column of `timeseries.csv` averaged over the replicas of each point at each
//! sample, with its standard error) and `study.json` (the study, every run's state and
//! wall time, and the summaries' scalar results with mean and standard error per point)
//! and a figure per quantity ([`figures`]).

use super::execute::RunOutcome;
use super::figures::{self, Final};
use super::{run_dir, Study};
use crate::error::{Error, Result};
use crate::output::{number, write_csv_file, write_json_file};
use serde_json::{json, Map, Value};
use std::collections::BTreeMap;
use std::path::Path;

/// The columns of `ensemble.csv` after `point` and the varied keys.
pub const ENSEMBLE_HEADER: [&str; 7] = [
    "sample",
    "time",
    "collisions_per_particle",
    "quantity",
    "mean",
    "standard_error",
    "replicas",
];

/// What [`aggregate`] wrote.
#[derive(Debug, Clone)]
pub struct Aggregates {
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
    pub study: Value,
}

/// Mean and standard error of the mean (sample standard deviation over sqrt(n); NaN for
/// fewer than two values: no error bar from one replica).
pub fn mean_and_error(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    if values.len() < 2 {
        return (mean, f64::NAN);
    }
    let variance = values.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0);
    (mean, (variance / n).sqrt())
}

/// A CSV cell for a varied value (strings bare, no commas).
fn cell(value: &toml::Value) -> String {
    match value {
        toml::Value::Float(x) => number(*x),
        toml::Value::Integer(i) => i.to_string(),
        toml::Value::String(s) => s.replace(',', ";"),
        toml::Value::Boolean(b) => b.to_string(),
        other => other.to_string().replace(',', ";"),
    }
}

/// A run's `timeseries.csv`: its header and rows of numbers.
fn read_series(path: &Path) -> Result<(Vec<String>, Vec<Vec<f64>>)> {
    let file = path.join("timeseries.csv");
    let bad = |message: String| Error::RunFile {
        path: file.clone(),
        message,
    };
    let text = std::fs::read_to_string(&file).map_err(|e| bad(e.to_string()))?;
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .ok_or_else(|| bad("empty".into()))?
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .enumerate()
        .map(|(i, line)| {
            line.split(',')
                .map(|c| {
                    c.parse::<f64>()
                        .map_err(|_| bad(format!("line {}: `{c}` is not a number", i + 2)))
                })
                .collect::<Result<Vec<f64>>>()
        })
        .collect::<Result<Vec<_>>>()?;
    Ok((header, rows))
}

/// The scalar results of a run's `summary.json` (numeric leaves as dotted paths, without
/// the run's parameters and its timings).
fn summary_scalars(path: &Path) -> BTreeMap<String, f64> {
    fn leaves(value: &Value, prefix: String, out: &mut BTreeMap<String, f64>) {
        match value {
            Value::Object(map) => {
                for (k, v) in map {
                    let key = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    leaves(v, key, out);
                }
            }
            Value::Number(n) => {
                if let Some(x) = n.as_f64() {
                    out.insert(prefix, x);
                }
            }
            _ => {}
        }
    }
    let mut out = BTreeMap::new();
    let Some(summary) = std::fs::read_to_string(path.join("summary.json"))
        .ok()
        .and_then(|t| serde_json::from_str::<Value>(&t).ok())
    else {
        return out;
    };
    leaves(&summary, String::new(), &mut out);
    out.retain(|k, _| {
        !(k.starts_with("parameters.") || k.contains("seconds") || k.ends_with("_per_second"))
    });
    out
}

/// Writes `DIR/ensemble.csv` and `DIR/study.json` from the complete runs among
/// `outcomes` (and the points left out as `invalid`).
pub fn aggregate(
    study: &Study,
    dir: &Path,
    outcomes: &[RunOutcome],
    invalid: &[(usize, String)],
) -> Result<Aggregates> {
    let keys = study.keys();
    let mut header = vec!["point".to_string()];
    header.extend(keys.iter().cloned());
    header.extend(ENSEMBLE_HEADER.iter().map(|c| c.to_string()));
    let mut rows = Vec::new();
    let mut finals = Vec::new();
    let mut points = Vec::new();
    for point in &study.points {
        let complete: Vec<&RunOutcome> = outcomes
            .iter()
            .filter(|o| o.point == point.index && o.state == "complete")
            .collect();
        let mut summary = json!({});
        if !complete.is_empty() {
            let series = complete
                .iter()
                .map(|o| read_series(&run_dir(dir, point.index, o.seed)))
                .collect::<Result<Vec<_>>>()?;
            let columns = &series[0].0;
            if let Some((other, _)) = series.iter().find(|(h, _)| h != columns) {
                return Err(Error::input(
                    format!("point {}", point.index),
                    format!(
                        "its runs' timeseries.csv differ in columns ({} and {})",
                        columns.join(","),
                        other.join(",")
                    ),
                ));
            }
            let at = |name: &str| columns.iter().position(|c| c == name);
            let (time, cpp) = (at("time"), at("collisions_per_particle"));
            let samples = series.iter().map(|(_, r)| r.len()).min().unwrap_or(0);
            let values: Vec<String> = point.values.values().map(cell).collect();
            for s in 0..samples {
                let column =
                    |c: usize| -> Vec<f64> { series.iter().map(|(_, r)| r[s][c]).collect() };
                let mean_of =
                    |c: Option<usize>| c.map_or(f64::NAN, |c| mean_and_error(&column(c)).0);
                let (t, k) = (mean_of(time), mean_of(cpp));
                for (c, quantity) in columns.iter().enumerate() {
                    if Some(c) == time || Some(c) == cpp {
                        continue;
                    }
                    let (mean, error) = mean_and_error(&column(c));
                    finals.push(Final {
                        point: point.index,
                        sample: s,
                        quantity: quantity.clone(),
                        mean,
                        error,
                    });
                    let mut row = vec![point.index.to_string()];
                    row.extend(values.iter().cloned());
                    row.extend([
                        s.to_string(),
                        number(t),
                        number(k),
                        quantity.clone(),
                        number(mean),
                        number(error),
                        series.len().to_string(),
                    ]);
                    rows.push(row);
                }
            }
            let scalars: Vec<BTreeMap<String, f64>> = complete
                .iter()
                .map(|o| summary_scalars(&run_dir(dir, point.index, o.seed)))
                .collect();
            let mut results = Map::new();
            for key in scalars[0].keys() {
                let values: Vec<f64> = scalars.iter().filter_map(|m| m.get(key).copied()).collect();
                if values.len() == scalars.len() {
                    let (mean, error) = mean_and_error(&values);
                    results.insert(
                        key.clone(),
                        json!({"mean": finite(mean), "standard_error": finite(error)}),
                    );
                }
            }
            summary = Value::Object(results);
        }
        points.push(json!({
            "point": point.index,
            "values": point.values,
            "replicas": complete.len(),
            "summary": summary,
        }));
    }
    let walls: Vec<f64> = outcomes.iter().filter_map(|o| o.wall_seconds).collect();
    let study_json = json!({
        "study": study.file,
        "keys": keys,
        "seeds": study.seeds(),
        "first_seed": study.first_seed,
        "runs_total": study.runs(),
        "runs_complete": outcomes.iter().filter(|o| o.state == "complete").count(),
        "runs_failed": outcomes.iter().filter(|o| o.state != "complete").count(),
        "run_wall_seconds": walls.iter().sum::<f64>(),
        "invalid_points": invalid.iter().map(|(p, e)| json!({"point": p, "error": e})).collect::<Vec<_>>(),
        "points": points,
        "runs": outcomes,
    });
    let refs: Vec<&str> = header.iter().map(String::as_str).collect();
    write_csv_file(&dir.join("ensemble.csv"), &refs, rows.clone())?;
    write_json_file(&dir.join("study.json"), &study_json)?;
    figures::write(study, dir, &finals)?;
    Ok(Aggregates {
        header,
        rows,
        study: study_json,
    })
}

/// JSON has no NaN: null.
fn finite(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}
