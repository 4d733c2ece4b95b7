//! Running a study's runs: its directory (owned by one study, as a run's is by one run),
//! one run at a time ([`run_one`]: new, resumed from its check-point, or kept when
//! complete) and all of them on local threads ([`execute`]), each run single-threaded by
//! default (independent runs scale better than threads within one run).

use super::{run_dir, Study};
use crate::error::{Error, Result};
use crate::outdir::{run_hash, Manifest, OutputDir, RunState, MANIFEST};
use crate::Simulation;
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// By default a run of a study check-points at the first sample after each minute of
/// wall-clock time: a kill loses at most that much of each run in flight, and a short run
/// writes no state at all (a check-point of 1e5 particles at every sample would cost as
/// much as the run).
pub const CHECKPOINT_SECONDS: f64 = 60.0;

/// The study's manifest in its directory.
pub const STUDY_MANIFEST: &str = "haff-study.json";

/// The files of a study besides its runs (removed by `--force`).
const STUDY_OUTPUTS: [&str; 3] = [STUDY_MANIFEST, "ensemble.csv", "study.json"];

#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct StudyManifest {
    command: String,
    study_hash: String,
    haff_version: String,
}

/// What became of one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunOutcome {
    pub point: usize,
    pub replica: u64,
    pub seed: u64,
    /// `runs/<point>/<seed>`, relative to the study directory.
    pub dir: String,
    /// `complete` or `failed`.
    pub state: String,
    /// Wall-clock seconds of this run in the process that finished it (None: failed).
    pub wall_seconds: Option<f64>,
    /// Whether the run continued from a check-point, or was complete already.
    pub resumed: bool,
    pub kept: bool,
    pub error: Option<String>,
}

/// What a study reports as its runs go (called from the worker threads).
pub trait StudyProgress: Sync {
    fn started(&self, _point: usize, _seed: u64) {}
    fn finished(&self, _outcome: &RunOutcome) {}
}

impl StudyProgress for () {}

/// Claims `dir` for `study`: a new or empty directory, or one holding this study already
/// (to continue it); another study's only with `force` (its runs and aggregates removed
/// first); anything else is refused.
pub fn open_study_dir(dir: &Path, study: &Study, force: bool) -> Result<()> {
    let fail = |message: String| Error::input("--out", format!("{}: {message}", dir.display()));
    let manifest = StudyManifest {
        command: "study".into(),
        study_hash: study.hash(),
        haff_version: env!("CARGO_PKG_VERSION").into(),
    };
    let path = dir.join(STUDY_MANIFEST);
    if path.exists() {
        let text = std::fs::read_to_string(&path).map_err(|e| fail(e.to_string()))?;
        let old: StudyManifest = serde_json::from_str(&text)
            .map_err(|e| fail(format!("{STUDY_MANIFEST} is not a haff study's: {e}")))?;
        if old.study_hash == manifest.study_hash {
            return Ok(());
        }
        if !force {
            return Err(fail(
                "holds another study (its runs differ); give --force to replace it, or \
                 choose a new directory"
                    .into(),
            ));
        }
        remove_study(dir).map_err(|e| fail(e.to_string()))?;
    } else if dir.exists() {
        let mut entries = std::fs::read_dir(dir).map_err(|e| fail(e.to_string()))?;
        if let Some(entry) = entries.next() {
            let name = entry.map_err(|e| fail(e.to_string()))?.file_name();
            return Err(fail(format!(
                "holds files that are not a haff study's (e.g. {}); choose a new or empty \
                 directory",
                name.to_string_lossy()
            )));
        }
    }
    std::fs::create_dir_all(dir.join("runs")).map_err(|e| fail(e.to_string()))?;
    crate::output::write_json_file(&path, &manifest)
}

fn remove_study(dir: &Path) -> std::io::Result<()> {
    let runs = dir.join("runs");
    if runs.exists() {
        std::fs::remove_dir_all(runs)?;
    }
    for name in STUDY_OUTPUTS {
        let path = dir.join(name);
        if path.exists() {
            std::fs::remove_file(path)?;
        }
    }
    let figures = dir.join("figures");
    if figures.exists() {
        std::fs::remove_dir_all(figures)?;
    }
    Ok(())
}

/// Runs replica `replica` of point `point` of `study` in its directory under `dir` on
/// `threads` threads: kept if complete, resumed from its check-point if interrupted,
/// started otherwise. Check-points every `checkpoint_every` samples (None: at the first
/// sample after each [`CHECKPOINT_SECONDS`]).
pub fn run_one(
    study: &Study,
    dir: &Path,
    point: usize,
    replica: u64,
    threads: usize,
    checkpoint_every: Option<usize>,
) -> RunOutcome {
    let seed = study.seed(replica);
    let path = run_dir(dir, point, seed);
    let mut outcome = RunOutcome {
        point,
        replica,
        seed,
        dir: format!("runs/{point:03}/{seed}"),
        state: "failed".into(),
        wall_seconds: None,
        resumed: false,
        kept: false,
        error: None,
    };
    // Everything of the run, its set-up too, on a pool of its own: nothing touches
    // rayon's global pool, which a process forked by a Python process pool inherits
    // without its threads.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| Error::input("threads", e));
    let result = pool.and_then(|pool| {
        pool.install(|| -> Result<(f64, bool, bool)> {
            let description = study.run_description(&study.points[point], replica)?;
            let hash = run_hash(&description);
            let manifest = read_run_manifest(&path);
            let same = manifest.as_ref().is_some_and(|m| m.run_hash == hash);
            if same
                && manifest
                    .as_ref()
                    .is_some_and(|m| m.state == RunState::Complete)
            {
                return Ok((recorded_wall_seconds(&path), false, true));
            }
            let checkpoint = path.join(crate::checkpoint::FILE_NAME);
            let (mut simulation, mut out, resumed) = if same && checkpoint.exists() {
                let simulation = Simulation::resume(&path)?;
                (
                    simulation,
                    OutputDir::for_resume(&path, "run", &hash)?,
                    true,
                )
            } else {
                std::fs::create_dir_all(&path).map_err(|e| Error::write(&path, e))?;
                let out = OutputDir::claim(&path, "run", &hash, true)?;
                (Simulation::new(&description)?, out, false)
            };
            let every = checkpoint_every
                .or(simulation.checkpoint_interval())
                .unwrap_or(1);
            simulation.set_checkpoints(&path, Some(every));
            if checkpoint_every.is_none() {
                simulation.set_checkpoint_spacing(CHECKPOINT_SECONDS);
            }
            simulation.set_output_dir(&path);
            simulation.run(&mut (), None)?;
            simulation.write(&path)?;
            out.set_state(RunState::Complete)?;
            Ok((simulation.wall_seconds(), resumed, false))
        })
    });
    match result {
        Ok((wall, resumed, kept)) => {
            outcome.state = "complete".into();
            outcome.wall_seconds = Some(wall);
            outcome.resumed = resumed;
            outcome.kept = kept;
        }
        Err(e) => outcome.error = Some(e.to_string()),
    }
    outcome
}

/// The manifest of a run directory, if it holds one.
fn read_run_manifest(path: &Path) -> Option<Manifest> {
    let text = std::fs::read_to_string(path.join(MANIFEST)).ok()?;
    serde_json::from_str(&text).ok()
}

/// The wall-clock seconds a complete run's summary records.
fn recorded_wall_seconds(path: &Path) -> f64 {
    std::fs::read_to_string(path.join("summary.json"))
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
        .and_then(|v| v["wall_seconds"].as_f64())
        .unwrap_or(f64::NAN)
}

/// Runs every run of `study` whose point is not in `skip` (points left out: invalid ones
/// of a study that goes on without them) on `jobs` local threads, `threads` each, in the
/// order of points and replicas; a failed run is reported and the others go on. Returns
/// the outcomes in that order.
pub fn execute(
    study: &Study,
    dir: &Path,
    jobs: usize,
    threads: usize,
    checkpoint_every: Option<usize>,
    skip: &[usize],
    progress: &dyn StudyProgress,
) -> Vec<RunOutcome> {
    let work: Vec<(usize, u64)> = study
        .points
        .iter()
        .filter(|p| !skip.contains(&p.index))
        .flat_map(|p| (0..study.seeds()).map(move |r| (p.index, r)))
        .collect();
    let next = AtomicUsize::new(0);
    let outcomes: Mutex<Vec<Option<RunOutcome>>> = Mutex::new(vec![None; work.len()]);
    std::thread::scope(|scope| {
        for _ in 0..jobs.clamp(1, work.len().max(1)) {
            scope.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some(&(point, replica)) = work.get(k) else {
                    break;
                };
                progress.started(point, study.seed(replica));
                let outcome = run_one(study, dir, point, replica, threads, checkpoint_every);
                progress.finished(&outcome);
                outcomes.lock().unwrap_or_else(|e| e.into_inner())[k] = Some(outcome);
            });
        }
    });
    outcomes
        .into_inner()
        .unwrap_or_else(|e| e.into_inner())
        .into_iter()
        .flatten()
        .collect()
}
