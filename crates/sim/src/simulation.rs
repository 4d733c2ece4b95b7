//! The run driver: a [`Simulation`] built from a run description (or a check-point) runs its
//! engine through the sampling schedule, feeds the observers, writes check-points and,
//! on request, the output files. The `haff run` command drives runs through it (and the
//! Python package will).

use crate::checkpoint;
use crate::description::RunDescription;
use crate::engines::{self, Driven, Records, RecordsRef};
use crate::error::{Error, Result};
use crate::law;
use crate::observer::{
    Histogram, Observer, Sample, TimeSeries, VelocityHistograms, HISTOGRAM_BINS,
};
use crate::output::write_json_file;
use crate::schedule::{sample_targets, schedule, Target};
use crate::validate::{validate, Plan, Stop};
use gas::Counters;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Progress of a run, for a progress bar (the CLI's) or nothing (`()`).
pub trait Progress {
    /// The run is about to take samples `done..total`.
    fn start(&mut self, _total: usize, _done: usize) {}
    /// A sample was taken, `done` so far; `note` says how the run goes (rate, temperature).
    fn sample(&mut self, _done: usize, _note: &str) {}
    /// The run stopped (complete or not).
    fn finish(&mut self) {}
}

impl Progress for () {}

/// How a call of [`Simulation::run`] ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    /// Whether every target of the schedule was reached (false: stopped after a number of
    /// samples).
    pub complete: bool,
    pub counters: Counters,
}

/// A run: its plan, its engine and its observers.
pub struct Simulation {
    plan: Plan,
    run: Dimensioned,
    /// Check-points every this many samples into `checkpoint_dir`.
    checkpoint_every: Option<usize>,
    checkpoint_dir: Option<PathBuf>,
    /// Wall-clock seconds spent by this process building the run and in [`Simulation::run`].
    wall_seconds: f64,
}

/// The run in its dimension (the engines are generic over it).
enum Dimensioned {
    One(Box<Run<1>>),
    Two(Box<Run<2>>),
    Three(Box<Run<3>>),
}

/// Calls `$body` with `$run` bound to the run of whichever dimension.
macro_rules! each {
    ($value:expr, $run:ident => $body:expr) => {
        match $value {
            Dimensioned::One($run) => $body,
            Dimensioned::Two($run) => $body,
            Dimensioned::Three($run) => $body,
        }
    };
}

/// The run of `$dimension` (1, 2, else 3) dimensions: `$make` evaluated with the constant
/// `$D` set to it, its error returned.
macro_rules! in_dimension {
    ($dimension:expr, $D:ident => $make:expr) => {
        match $dimension {
            1 => {
                const $D: usize = 1;
                Dimensioned::One(Box::new($make?))
            }
            2 => {
                const $D: usize = 2;
                Dimensioned::Two(Box::new($make?))
            }
            _ => {
                const $D: usize = 3;
                Dimensioned::Three(Box::new($make?))
            }
        }
    };
}

/// The engine and observers of a run in D dimensions.
struct Run<const D: usize> {
    engine: Box<dyn Driven<D>>,
    schedule: Vec<Target>,
    /// The next target of the schedule.
    next: usize,
    timeseries: TimeSeries,
    histograms: VelocityHistograms,
}

impl Simulation {
    /// A run at time 0 from a description (checked first; errors name the key).
    pub fn new(description: &RunDescription) -> Result<Self> {
        let clock = Instant::now();
        let plan = validate(description)?;
        let law = law::build(&plan.law, plan.max_impact_speed())?;
        let bins = plan
            .description
            .run
            .histogram_bins
            .unwrap_or(HISTOGRAM_BINS);
        let (timeseries, histograms) = (TimeSeries::default(), VelocityHistograms::new(bins));
        let run = in_dimension!(plan.description.system.dimension, D => Ok::<_, Error>(Run::<D>::new(
            &plan,
            engines::start::<D>(&plan, law)?,
            timeseries,
            histograms,
        )));
        Ok(Simulation {
            plan,
            run,
            checkpoint_every: None,
            checkpoint_dir: None,
            wall_seconds: clock.elapsed().as_secs_f64(),
        })
    }

    /// A run from TOML text (`origin` names it in messages).
    pub fn from_toml(text: &str, origin: &Path) -> Result<Self> {
        Self::new(&RunDescription::from_toml(text, origin)?)
    }

    /// The run saved in the check-point of `dir` (`checkpoint.bin`), to continue bit for
    /// bit. The file is verified (format, version, checksum) and its content checked for
    /// meaning: the run description like a fresh run's, the engine state and the records
    /// against it. Its check-point interval is kept, and further check-points go to `dir`.
    pub fn resume(dir: &Path) -> Result<Self> {
        let clock = Instant::now();
        let sections = checkpoint::read(dir, engines::FORMAT)?;
        let records: Records = sections.records()?;
        let plan = validate(&records.description).map_err(|e| sections.error(e))?;
        if records.description != plan.description {
            return Err(sections.error("the run description is not in its normal form"));
        }
        if !records.every.is_none_or(|k| (1..=1_000_000).contains(&k)) {
            return Err(sections.error("every: allowed 1 ..= 1e6 samples"));
        }
        let law = law::build(&plan.law, plan.max_impact_speed()).map_err(|e| sections.error(e))?;
        let run = in_dimension!(plan.description.system.dimension, D => Run::<D>::resumed(
            &plan,
            engines::restore::<D>(&plan, law, &sections)?,
            records.timeseries,
            records.histograms,
        )
        .map_err(|e| sections.error(e)));
        Ok(Simulation {
            plan,
            run,
            checkpoint_every: records.every,
            checkpoint_dir: Some(dir.to_path_buf()),
            wall_seconds: clock.elapsed().as_secs_f64(),
        })
    }

    /// Saves the state to the check-point of `dir` every `every` samples (None: never).
    pub fn set_checkpoints(&mut self, dir: &Path, every: Option<usize>) {
        self.checkpoint_dir = Some(dir.to_path_buf());
        self.checkpoint_every = every;
    }

    /// The check-point interval in samples (kept from a resumed check-point).
    pub fn checkpoint_interval(&self) -> Option<usize> {
        self.checkpoint_every
    }

    /// The checked plan of the run.
    pub fn plan(&self) -> &Plan {
        &self.plan
    }

    /// The run description (normalized).
    pub fn description(&self) -> &RunDescription {
        &self.plan.description
    }

    /// The samples taken so far.
    pub fn samples(&self) -> &[Sample] {
        each!(&self.run, r => &r.timeseries.samples)
    }

    /// The velocity histograms taken so far.
    pub fn histograms(&self) -> &[Histogram] {
        each!(&self.run, r => &r.histograms.histograms)
    }

    pub fn time(&self) -> f64 {
        each!(&self.run, r => r.engine.time())
    }

    pub fn counters(&self) -> Counters {
        each!(&self.run, r => r.engine.counters())
    }

    /// Whether every target of the schedule has been reached.
    pub fn is_complete(&self) -> bool {
        each!(&self.run, r => r.next == r.schedule.len())
    }

    /// Runs to the end of the schedule, or until `stop_after` samples exist (a run in
    /// chunks), writing check-points as set by [`Simulation::set_checkpoints`].
    pub fn run(
        &mut self,
        progress: &mut dyn Progress,
        stop_after: Option<usize>,
    ) -> Result<Outcome> {
        let clock = Instant::now();
        let saving = self.checkpoint_dir.as_deref().zip(self.checkpoint_every);
        let plan = &self.plan;
        let result = each!(&mut self.run, r => r.run(plan, saving, progress, stop_after));
        self.wall_seconds += clock.elapsed().as_secs_f64();
        let complete = result?;
        Ok(Outcome {
            complete,
            counters: self.counters(),
        })
    }

    /// Writes the output files into `dir`: `timeseries.csv`, `velocity_histograms.csv`
    /// (with `run.histogram_at`), `temperature.png` and `summary.json`.
    pub fn write(&self, dir: &Path) -> Result<()> {
        let run = &self.plan.description.run;
        each!(&self.run, r => {
            r.timeseries.write(&dir.join("timeseries.csv"))?;
            if run.histogram_at.as_ref().is_some_and(|at| !at.is_empty()) {
                r.histograms.write(&dir.join("velocity_histograms.csv"))?;
            }
        });
        crate::figures::temperature(&dir.join("temperature.png"), &self.plan, self.samples())?;
        let counters = self.counters();
        let wall = self.wall_seconds;
        let summary = serde_json::json!({
            "parameters": self.plan.description,
            "collisions": counters.collisions,
            "events": counters.events,
            "tc_elastic_collisions": counters.tc_elastic,
            "wall_seconds": wall,
            "events_per_second": counters.events as f64 / wall,
            "collisions_per_second": counters.collisions as f64 / wall,
            "final": self.samples().last(),
            "complete": self.is_complete(),
        });
        write_json_file(&dir.join("summary.json"), &summary)
    }

    /// Wall-clock seconds spent building and running in this process.
    pub fn wall_seconds(&self) -> f64 {
        self.wall_seconds
    }
}

impl<const D: usize> Run<D> {
    /// A run of `engine` at the start of its schedule.
    fn new(
        plan: &Plan,
        engine: Box<dyn Driven<D>>,
        timeseries: TimeSeries,
        histograms: VelocityHistograms,
    ) -> Self {
        let run = &plan.description.run;
        let schedule = schedule(
            &sample_targets(plan.stop.end(), run.samples, plan.log_spacing()),
            run.histogram_at.as_deref().unwrap_or(&[]),
        );
        Run {
            engine,
            schedule,
            next: 0,
            timeseries,
            histograms,
        }
    }

    /// A run continuing from a check-point, which is written right after a sample: the
    /// records must be those of the run up to that sample, and the engine must stand there.
    fn resumed(
        plan: &Plan,
        engine: Box<dyn Driven<D>>,
        timeseries: TimeSeries,
        histograms: VelocityHistograms,
    ) -> std::result::Result<Self, String> {
        let mut run = Run::new(plan, engine, timeseries, histograms);
        let samples = &run.timeseries.samples;
        let Some(last) = samples.last() else {
            return Err("no sample: a check-point follows a sample".into());
        };
        run.next = run
            .schedule
            .iter()
            .position(|target| target.sample == Some(samples.len() - 1))
            .ok_or(format!(
                "{} samples where run.samples = {}",
                samples.len(),
                plan.description.run.samples
            ))?
            + 1;
        let counters = run.engine.counters();
        if last.time != run.engine.time() || last.events != counters.events {
            return Err("the engine does not stand at the last sample".into());
        }
        let bins = plan
            .description
            .run
            .histogram_bins
            .unwrap_or(HISTOGRAM_BINS);
        let due: Vec<f64> = run.schedule[..run.next]
            .iter()
            .filter(|t| t.histogram)
            .map(|t| t.value)
            .collect();
        let taken: Vec<f64> = run.histograms.histograms.iter().map(|h| h.target).collect();
        let wrong_bins = run
            .histograms
            .histograms
            .iter()
            .any(|h| h.bins.len() != bins);
        if due != taken || run.histograms.bins != bins || wrong_bins {
            return Err("the velocity histograms do not match run.histogram_at and bins".into());
        }
        Ok(run)
    }

    /// Runs through the remaining targets; false if it stopped after `stop_after` samples.
    fn run(
        &mut self,
        plan: &Plan,
        saving: Option<(&Path, usize)>,
        progress: &mut dyn Progress,
        stop_after: Option<usize>,
    ) -> Result<bool> {
        let particles = plan.description.system.particles as f64;
        progress.start(plan.description.run.samples, self.timeseries.samples.len());
        let started = Instant::now();
        let result = (|| {
            while self.next < self.schedule.len() {
                let target = self.schedule[self.next];
                self.advance(plan.stop, target.value, particles)?;
                self.timeseries.observe(&target, self.engine.as_mut());
                self.histograms.observe(&target, self.engine.as_mut());
                self.next += 1;
                if target.sample.is_none() {
                    continue;
                }
                let taken = self.timeseries.samples.len();
                if let Some((dir, every)) = saving {
                    if taken.is_multiple_of(every) {
                        self.write_checkpoint(plan, dir, every)?;
                    }
                }
                let events = self.engine.counters().events as f64;
                let rate = events / started.elapsed().as_secs_f64().max(1e-9);
                let temperature = self.timeseries.samples[taken - 1].temperature;
                progress.sample(
                    taken,
                    &format!("{rate:.3e} events/s, T = {temperature:.4e}"),
                );
                if stop_after.is_some_and(|k| taken >= k) {
                    return Ok(self.next == self.schedule.len());
                }
            }
            Ok(true)
        })();
        progress.finish();
        result
    }

    /// Brings the engine to `value` of the stop criterion.
    fn advance(&mut self, stop: Stop, value: f64, particles: f64) -> Result<()> {
        match stop {
            Stop::Time(_) => self.engine.run_until(value),
            Stop::CollisionsPerParticle(_) => {
                let want = (value * particles / 2.0).round() as u64;
                let have = self.engine.counters().collisions;
                self.engine.run_collisions(want.saturating_sub(have));
            }
        }
        match self.engine.collapsed() {
            Some(time) => Err(Error::Collapse { time }),
            None => Ok(()),
        }
    }

    fn write_checkpoint(&mut self, plan: &Plan, dir: &Path, every: usize) -> Result<()> {
        let records = RecordsRef {
            description: &plan.description,
            every: Some(every),
            timeseries: &self.timeseries,
            histograms: &self.histograms,
        };
        self.engine.write_checkpoint(dir, records)
    }
}
