//! Studies from Python (`haff.study`): the library's `sim::study` behind functions of
//! plain arguments (the study as TOML text, the directory as a path, outcomes as JSON), so
//! that a worker of any executor — a thread, a process, a dask worker on another node —
//! runs one run with nothing but picklable values. Runs go on with the GIL released.

use crate::sim_error;
use pyo3::prelude::*;
use sim::study::{self, RunOutcome, Study};
use std::path::{Path, PathBuf};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(study_plan, m)?)?;
    m.add_function(wrap_pyfunction!(study_open, m)?)?;
    m.add_function(wrap_pyfunction!(study_run, m)?)?;
    m.add_function(wrap_pyfunction!(study_aggregate, m)?)?;
    Ok(())
}

/// The study of `text` (relative base paths from `origin`'s folder).
fn parse(text: &str, origin: &Path) -> PyResult<Study> {
    Study::from_toml(text, origin).map_err(sim_error)
}

/// The runs of a study: `(keys, points, runs, invalid)` with `points` the JSON of each
/// point's values, `runs` `(point, replica, seed)` of every run to do and `invalid`
/// `(point, error)` of the points whose run files are invalid. Without `keep_going` an
/// invalid point raises `ConfigError` naming it and the key.
#[pyfunction]
#[pyo3(signature = (text, origin, keep_going = false))]
#[allow(clippy::type_complexity)]
fn study_plan(
    text: &str,
    origin: PathBuf,
    keep_going: bool,
) -> PyResult<(
    Vec<String>,
    Vec<String>,
    Vec<(usize, u64, u64)>,
    Vec<(usize, String)>,
)> {
    let study = parse(text, &origin)?;
    let invalid = if keep_going {
        study.invalid_points()
    } else {
        study.check_runs().map_err(sim_error)?;
        Vec::new()
    };
    let points = study
        .points
        .iter()
        .map(|p| serde_json::to_string(&p.values).unwrap_or_default())
        .collect();
    let runs = study
        .points
        .iter()
        .filter(|p| !invalid.iter().any(|(i, _)| *i == p.index))
        .flat_map(|p| (0..study.seeds()).map(move |r| (p.index, r)))
        .map(|(point, replica)| (point, replica, study.seed(replica)))
        .collect();
    Ok((study.keys(), points, runs, invalid))
}

/// Claims `dir` for the study (`haff study`'s rules: new, empty, or this study's; another
/// study's only with `force`).
#[pyfunction]
#[pyo3(signature = (text, origin, dir, force = false))]
fn study_open(text: &str, origin: PathBuf, dir: PathBuf, force: bool) -> PyResult<()> {
    let study = parse(text, &origin)?;
    study::open_study_dir(&dir, &study, force).map_err(sim_error)
}

/// Runs one run of the study in `dir/runs/<point>/<seed>` (kept if complete, resumed from
/// its check-point if interrupted) with the GIL released; returns its outcome as JSON (a
/// failed run's error is in it, not raised).
#[pyfunction]
#[pyo3(signature = (text, origin, dir, point, replica, threads = 1, checkpoint_every = None))]
#[allow(clippy::too_many_arguments)] // a worker's call: plain picklable values only
fn study_run(
    py: Python<'_>,
    text: &str,
    origin: PathBuf,
    dir: PathBuf,
    point: usize,
    replica: u64,
    threads: usize,
    checkpoint_every: Option<usize>,
) -> PyResult<String> {
    let study = parse(text, &origin)?;
    if point >= study.points.len() || replica >= study.seeds() {
        return Err(crate::config_error(
            "point",
            format!(
                "point {point}, replica {replica} is not a run of this study ({} points x {} \
                 seeds)",
                study.points.len(),
                study.seeds()
            ),
        ));
    }
    if threads == 0 {
        return Err(crate::out_of_range("threads", 0, "threads >= 1"));
    }
    let outcome =
        py.detach(|| study::run_one(&study, &dir, point, replica, threads, checkpoint_every));
    serde_json::to_string(&outcome).map_err(|e| crate::config_error("outcome", e))
}

/// Writes `ensemble.csv`, `study.json` and the figures from the runs' files, given the
/// runs' outcomes (JSON) and the points left out; returns `study.json`'s text.
#[pyfunction]
#[pyo3(signature = (text, origin, dir, outcomes, invalid))]
fn study_aggregate(
    py: Python<'_>,
    text: &str,
    origin: PathBuf,
    dir: PathBuf,
    outcomes: Vec<String>,
    invalid: Vec<(usize, String)>,
) -> PyResult<String> {
    let study = parse(text, &origin)?;
    let outcomes = outcomes
        .iter()
        .map(|o| serde_json::from_str::<RunOutcome>(o))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| crate::config_error("outcomes", e))?;
    let aggregates = py
        .detach(|| study::aggregate(&study, &dir, &outcomes, &invalid))
        .map_err(sim_error)?;
    Ok(aggregates.study.to_string())
}
