//! A study's figures (`DIR/figures/<quantity>.png`, in [`crate::plot`]'s style): each
//! quantity of `timeseries.csv` at the last sample, its mean over the replicas with the
//! standard error as an error bar, against the first varied key that takes several
//! numbers (one curve per value of the other varied keys, those zipped with it left out);
//! against the point's index when no key does.

use super::Study;
use crate::error::{Error, Result};
use crate::plot::Figure;
use std::collections::BTreeMap;
use std::path::Path;

/// One row of `ensemble.csv` as the figures need it.
pub(super) struct Final {
    pub point: usize,
    pub sample: usize,
    pub quantity: String,
    pub mean: f64,
    pub error: f64,
}

/// A measurement and its error bar: (x, mean, standard error).
type Bar = (f64, f64, f64);

/// A TOML number as f64 (None for other values).
fn numeric(value: &toml::Value) -> Option<f64> {
    match value {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

/// The key of the x axis: the first varied key whose values are numbers, at least two
/// of them distinct.
fn axis_key(study: &Study) -> Option<String> {
    study.keys().into_iter().find(|key| {
        let values: Option<Vec<f64>> = study
            .points
            .iter()
            .map(|p| p.values.get(key).and_then(numeric))
            .collect();
        values.is_some_and(|v| v.iter().any(|x| *x != v[0]))
    })
}

/// Writes `dir/figures/<quantity>.png` for every quantity among `rows`, each at the last
/// sample its point has.
pub(super) fn write(study: &Study, dir: &Path, rows: &[Final]) -> Result<()> {
    let axis = axis_key(study);
    let x_of = |point: usize| match &axis {
        Some(key) => study.points[point].values.get(key).and_then(numeric),
        None => Some(point as f64),
    };
    // The label of a point's curve: the other varied keys' values.
    // The axis key and the keys zipped with it vary along the axis: not in the labels.
    let along: Vec<&String> = match &axis {
        Some(key) => study
            .file
            .zip
            .iter()
            .find(|table| table.contains_key(key))
            .map_or(vec![key], |table| table.keys().collect()),
        None => Vec::new(),
    };
    let curve_of = |point: usize| -> String {
        let values = &study.points[point].values;
        let parts: Vec<String> = values
            .iter()
            .filter(|(k, _)| !along.contains(k))
            .map(|(k, v)| format!("{k} = {v}"))
            .collect();
        if parts.is_empty() {
            "mean of the replicas".into()
        } else {
            parts.join(", ")
        }
    };
    let mut last: BTreeMap<usize, usize> = BTreeMap::new();
    for row in rows {
        let s = last.entry(row.point).or_insert(row.sample);
        *s = (*s).max(row.sample);
    }
    let mut quantities: Vec<&str> = Vec::new();
    for row in rows {
        if !quantities.contains(&row.quantity.as_str()) {
            quantities.push(&row.quantity);
        }
    }
    let folder = dir.join("figures");
    if !quantities.is_empty() {
        std::fs::create_dir_all(&folder).map_err(|e| Error::write(&folder, e))?;
    }
    let x_label = axis.clone().unwrap_or_else(|| "point".into());
    for quantity in quantities {
        let mut curves: Vec<(String, Vec<Bar>)> = Vec::new();
        for row in rows
            .iter()
            .filter(|r| r.quantity == quantity && Some(&r.sample) == last.get(&r.point))
        {
            let Some(x) = x_of(row.point) else { continue };
            // One replica has no error bar: drawn as a bar of zero length.
            let error = if row.error.is_finite() {
                row.error
            } else {
                0.0
            };
            let name = curve_of(row.point);
            match curves.iter_mut().find(|(n, _)| *n == name) {
                Some((_, points)) => points.push((x, row.mean, error)),
                None => curves.push((name, vec![(x, row.mean, error)])),
            }
        }
        let mut figure = Figure::new(
            format!("{quantity} at the last sample (mean and standard error over the seeds)"),
            x_label.clone(),
            quantity.to_string(),
        );
        for (name, mut points) in curves {
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            figure = figure.measured(name, points);
        }
        figure.write_png(&folder.join(format!("{}.png", file_name(quantity))))?;
    }
    Ok(())
}

/// A quantity's name as a file name (characters other than letters, digits, `_`, `-` and
/// `.` as `_`).
fn file_name(quantity: &str) -> String {
    quantity
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "_-.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect()
}
