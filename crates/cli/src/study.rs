//! `haff study STUDY.toml [--out DIR] [--jobs N]`: the runs of a study (schema:
//! `sim::study`) on local threads, one bar over the runs, then the aggregates.

use crate::error::{CliError, CliResult, EXIT_FAILURE};
use crate::output::parse_count;
use crate::StudyArgs;
use indicatif::{ProgressBar, ProgressStyle};
use sim::study::{self, RunOutcome, Study, StudyProgress};
use std::path::PathBuf;
use std::sync::Mutex;

/// One bar over the runs, the runs in flight as its message.
struct Runs {
    bar: ProgressBar,
    flying: Mutex<Vec<String>>,
}

impl Runs {
    fn new(total: usize) -> Self {
        let bar = ProgressBar::new(total as u64);
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} runs {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Runs {
            bar,
            flying: Mutex::new(Vec::new()),
        }
    }

    fn show(&self, flying: &[String]) {
        self.bar
            .set_message(format!("running {}", flying.join(" ")));
    }
}

impl StudyProgress for Runs {
    fn started(&self, point: usize, seed: u64) {
        let mut flying = self.flying.lock().unwrap_or_else(|e| e.into_inner());
        flying.push(format!("{point:03}/{seed}"));
        self.show(&flying);
    }

    fn finished(&self, outcome: &RunOutcome) {
        let mut flying = self.flying.lock().unwrap_or_else(|e| e.into_inner());
        let name = format!("{:03}/{}", outcome.point, outcome.seed);
        flying.retain(|f| *f != name);
        self.show(&flying);
        if let Some(error) = &outcome.error {
            self.bar.suspend(|| {
                eprintln!(
                    "haff study: point {} seed {} failed: {error}",
                    outcome.point, outcome.seed
                )
            });
        }
        self.bar.inc(1);
    }
}

/// `haff study`.
pub fn study(args: &StudyArgs) -> CliResult {
    let in_file = CliError::in_file(&args.file);
    let study = Study::from_path(&args.file).map_err(&in_file)?;
    let jobs = match &args.jobs {
        Some(text) => parse_count("--jobs", text, 1, 4096)?,
        None => 1,
    };
    let threads = match &args.threads {
        Some(text) => parse_count("--threads", text, 1, 4096)?,
        None => 1,
    };
    let every = args
        .checkpoint_every
        .as_ref()
        .map(|text| parse_count("--checkpoint-every", text, 1, 1_000_000))
        .transpose()?;
    // Every run is checked before the first starts; with --keep-going the invalid points
    // are reported and left out.
    let invalid = if args.keep_going {
        study.invalid_points()
    } else {
        study.check_runs().map_err(&in_file)?;
        Vec::new()
    };
    for (point, error) in &invalid {
        eprintln!("haff study: point {point} left out: {error}");
    }
    let out = args.out.clone().unwrap_or_else(|| default_out(&args.file));
    study::open_study_dir(&out, &study, args.force)?;
    let skip: Vec<usize> = invalid.iter().map(|(p, _)| *p).collect();
    let total = study.runs() - skip.len() * study.seeds() as usize;
    let progress = Runs::new(total);
    let clock = std::time::Instant::now();
    let outcomes = study::execute(&study, &out, jobs, threads, every, &skip, &progress);
    progress.bar.finish_and_clear();
    let aggregates = study::aggregate(&study, &out, &outcomes, &invalid)?;
    let failed = outcomes.iter().filter(|o| o.error.is_some()).count();
    let kept = outcomes.iter().filter(|o| o.kept).count();
    let resumed = outcomes.iter().filter(|o| o.resumed).count();
    eprintln!(
        "haff study: {} runs ({} points x {} seeds): {} complete ({kept} kept, {resumed} \
         resumed), {failed} failed, {} left out, in {:.2} s on {jobs} jobs; {} rows in {}",
        study.runs(),
        study.points.len(),
        study.seeds(),
        outcomes.len() - failed,
        skip.len() * study.seeds() as usize,
        clock.elapsed().as_secs_f64(),
        aggregates.rows.len(),
        out.join("ensemble.csv").display()
    );
    if failed > 0 || !invalid.is_empty() {
        return Err(CliError::failure(format!(
            "{failed} runs failed and {} points were left out (study.json: runs, \
             invalid_points); the others are aggregated",
            invalid.len()
        ))
        .with_code(if invalid.is_empty() { EXIT_FAILURE } else { 2 }));
    }
    Ok(())
}

/// STUDY.toml -> ./STUDY.
fn default_out(file: &std::path::Path) -> PathBuf {
    PathBuf::from(
        file.file_stem()
            .map_or("haff-study".into(), |s| s.to_os_string()),
    )
}
