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
use crate::parallel::{self, Communicator};
use crate::schedule::{sample_targets, schedule, Target};
use crate::space::{SpaceObserver, SpaceRecords};
use crate::species::{SpeciesSample, SpeciesSeries};
use crate::validate::{validate, Plan, Stop};
use gas::Counters;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// Progress of a run, for a progress bar (the CLI's) or nothing (`()`).
pub trait Progress {
    /// The run is about to take samples `done..total`.
    fn start(&mut self, _total: usize, _done: usize) {}
    /// A sample was taken, `done` so far; `note` says how the run goes (rate, temperature).
    fn sample(&mut self, _done: usize, _note: &str) {}
    /// The run stopped (complete or not).
    fn finish(&mut self) {}
    /// Asked between pieces of a run (every [`PIECE_COLLISIONS`] collisions or one step of a
    /// stepped engine, whichever is longer): false interrupts the run ([`Error::Interrupted`]),
    /// which stands where it stopped and can go on (Ctrl-C in Python).
    fn keep_going(&mut self) -> bool {
        true
    }
}

/// Collisions per piece of a run, between which the driver asks [`Progress::keep_going`]:
/// about 0.1 s of event-driven MD. Pieces are counted from the start of the run, so a run
/// cut into them is the same whoever drives it (the `haff` command, Python, a resumed run;
/// see `gas::Engine::run_paused`).
pub const PIECE_COLLISIONS: u64 = 1 << 16;

/// A point of a run short of its end, where [`Simulation::advance`] stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Point {
    Time(f64),
    CollisionsPerParticle(f64),
}

impl Point {
    /// The argument that gave it.
    pub fn key(self) -> &'static str {
        match self {
            Point::Time(_) => "time",
            Point::CollisionsPerParticle(_) => "collisions_per_particle",
        }
    }

    fn value(self) -> f64 {
        match self {
            Point::Time(t) => t,
            Point::CollisionsPerParticle(c) => c,
        }
    }
}

/// The collision tally at `c` collisions per particle among `particles`.
fn collisions_at(c: f64, particles: f64) -> u64 {
    (c * particles / 2.0).round() as u64
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

/// The particles of a run at one moment, in the engine's current order: positions (in the
/// box) and velocities row by row (particle i at `i * dimension ..`), radii and masses.
#[derive(Debug, Clone, PartialEq)]
pub struct Particles {
    pub dimension: usize,
    pub positions: Vec<f64>,
    pub velocities: Vec<f64>,
    pub radii: Vec<f64>,
    pub masses: Vec<f64>,
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
    /// Of which in [`Simulation::run`] and [`Simulation::advance`] (the run, without
    /// building it).
    run_seconds: f64,
    /// The ranks the run is spread over ([`parallel::world`]: this process alone unless
    /// launched by mpirun); only rank 0 writes files.
    comm: Arc<dyn Communicator>,
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
    /// The observers of `[output]`.
    space: SpaceObserver,
    /// Per-species observables of a mixture (`system.species`).
    species: Option<SpeciesSeries>,
}

impl Simulation {
    /// A run at time 0 from a description (checked first; errors name the key).
    pub fn new(description: &RunDescription) -> Result<Self> {
        Self::new_on(description, parallel::world())
    }

    /// A run at time 0 spread over the ranks of `comm` (every rank calls this with the
    /// same description; see [`parallel`]).
    pub fn new_on(description: &RunDescription, comm: Arc<dyn Communicator>) -> Result<Self> {
        let clock = Instant::now();
        let plan = validate(description)?;
        parallel::check_ranks(&plan, comm.size())?;
        let law = law::build(&plan.law, plan.max_impact_speed())?;
        let bins = plan
            .description
            .run
            .histogram_bins
            .unwrap_or(HISTOGRAM_BINS);
        let (timeseries, histograms) = (TimeSeries::default(), VelocityHistograms::new(bins));
        let run = in_dimension!(plan.description.system.dimension, D => Ok::<_, Error>(Run::<D>::new(
            &plan,
            engines::start::<D>(&plan, law, &comm)?,
            timeseries,
            histograms,
            SpaceObserver::new(&plan, SpaceRecords::default()),
            species_series(&plan),
        )));
        Ok(Simulation {
            plan,
            run,
            checkpoint_every: None,
            checkpoint_dir: None,
            wall_seconds: clock.elapsed().as_secs_f64(),
            run_seconds: 0.0,
            comm,
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
        Self::resume_on(dir, parallel::world())
    }

    /// [`Simulation::resume`] spread over the ranks of `comm` (any number: a check-point
    /// holds the whole gas).
    pub fn resume_on(dir: &Path, comm: Arc<dyn Communicator>) -> Result<Self> {
        let clock = Instant::now();
        let sections = checkpoint::read(dir, engines::FORMAT)?;
        let mut run = Self::from_sections(&sections, clock, comm)?;
        run.checkpoint_dir = Some(dir.to_path_buf());
        Ok(run)
    }

    /// The run saved by [`Simulation::save`] as the file `path` (or in the directory
    /// `path`, as `checkpoint.bin`), checked as [`Simulation::resume`] checks it. Further
    /// check-points are written only when set ([`Simulation::set_checkpoints`]).
    pub fn load(path: &Path) -> Result<Self> {
        if path.is_dir() {
            let mut run = Self::resume(path)?;
            run.checkpoint_dir = None;
            return Ok(run);
        }
        let clock = Instant::now();
        let sections = checkpoint::read_from(path, engines::FORMAT)?;
        Self::from_sections(&sections, clock, parallel::world())
    }

    /// The run of a verified check-point, checked for meaning.
    fn from_sections(
        sections: &checkpoint::Sections,
        clock: Instant,
        comm: Arc<dyn Communicator>,
    ) -> Result<Self> {
        let records: Records = sections.records()?;
        let plan = validate(&records.description).map_err(|e| sections.error(e))?;
        parallel::check_ranks(&plan, comm.size())?;
        if records.description != plan.description {
            return Err(sections.error("the run description is not in its normal form"));
        }
        if !records.every.is_none_or(|k| (1..=1_000_000).contains(&k)) {
            return Err(sections.error("every: allowed 1 ..= 1e6 samples"));
        }
        let law = law::build(&plan.law, plan.max_impact_speed()).map_err(|e| sections.error(e))?;
        let run = in_dimension!(plan.description.system.dimension, D => Run::<D>::resumed(
            &plan,
            engines::restore::<D>(&plan, law, sections, &comm)?,
            records.timeseries,
            records.histograms,
            SpaceObserver::new(&plan, records.space.clone()),
            records.species,
        )
        .map_err(|e| sections.error(e)));
        Ok(Simulation {
            plan,
            run,
            checkpoint_every: records.every,
            checkpoint_dir: None,
            wall_seconds: clock.elapsed().as_secs_f64(),
            run_seconds: 0.0,
            comm,
        })
    }

    /// Writes the state now as a check-point: the file `path`, or `checkpoint.bin` in the
    /// directory `path`. A run may be saved anywhere (between samples too) and loaded
    /// with [`Simulation::load`]; saving brings the event-driven engine's particles to the
    /// present, so the run goes on as one resumed from there (bit for bit the same).
    pub fn save(&mut self, path: &Path) -> Result<()> {
        let file = if path.is_dir() {
            path.join(checkpoint::FILE_NAME)
        } else {
            path.to_path_buf()
        };
        let (plan, every, root) = (&self.plan, self.checkpoint_every, self.is_root());
        each!(&mut self.run, r => r.write_checkpoint(plan, &file, every, root))
    }

    /// Whether this process is rank 0 of the run, the one that writes files (true for a
    /// run in one process).
    pub fn is_root(&self) -> bool {
        self.comm.rank() == 0
    }

    /// The ranks the run is spread over.
    pub fn ranks(&self) -> usize {
        self.comm.size()
    }

    /// Every rank's particles and communication so far (collective: every rank calls
    /// it); None for a run in one process.
    pub fn rank_reports(&self) -> Option<Vec<gas::parallel::RankReport>> {
        each!(&self.run, r => r.engine.rank_reports())
    }

    /// The directory that field and snapshot files (`[output]`) are written to during the
    /// run; without one a run that asks for them is refused before it goes on (an input
    /// error naming `output.fields` or `output.snapshots`).
    pub fn set_output_dir(&mut self, dir: &Path) {
        let root = self.is_root();
        each!(&mut self.run, r => {
            r.space.set_directory(dir);
            r.space.set_writer(root);
        })
    }

    /// The directory set by [`Simulation::set_output_dir`], if any.
    pub fn output_dir(&self) -> Option<&Path> {
        each!(&self.run, r => r.space.directory())
    }

    /// What the observers of `[output]` have recorded so far (the rows of `modes.csv` and
    /// `structure.csv`, the field and snapshot files written).
    pub fn space_records(&self) -> &SpaceRecords {
        each!(&self.run, r => &r.space.records)
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

    /// The per-species rows taken so far (`species.csv`); None for a run without
    /// `system.species`.
    pub fn species_samples(&self) -> Option<&[SpeciesSample]> {
        each!(&self.run, r => r.species.as_ref().map(|s| s.samples.as_slice()))
    }

    /// The velocity histograms taken so far.
    pub fn histograms(&self) -> &[Histogram] {
        each!(&self.run, r => &r.histograms.histograms)
    }

    pub fn time(&self) -> f64 {
        each!(&self.run, r => r.engine.time())
    }

    /// The particles now (copies; see [`Particles`]).
    pub fn particles(&mut self) -> Particles {
        each!(&mut self.run, r => {
            let system = r.engine.system();
            Particles {
                dimension: system.positions.first().map_or(0, |x| x.len()),
                positions: system.positions.iter().flatten().copied().collect(),
                velocities: system.velocities.iter().flatten().copied().collect(),
                radii: system.radii.clone(),
                masses: system.masses.clone(),
            }
        })
    }

    /// The granular temperature now, T = <m c^2> / D ([`gas::observe::temperature`]).
    pub fn temperature(&mut self) -> f64 {
        each!(&mut self.run, r => gas::observe::temperature(r.engine.system()))
    }

    pub fn counters(&self) -> Counters {
        each!(&self.run, r => r.engine.counters())
    }

    /// The contacts of a soft-sphere run so far (time step, multi-particle contacts,
    /// largest overlap, elastic energy now); None for the other engines.
    pub fn contact_report(&self) -> Option<gas::soft::ContactReport> {
        each!(&self.run, r => r.engine.contact_report())
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
        self.go(progress, stop_after, None)?;
        Ok(Outcome {
            complete: self.is_complete(),
            counters: self.counters(),
        })
    }

    /// Runs to `point` (a time, or collisions per particle), taking the samples of the
    /// schedule on the way, or to the end of the run if that comes first. Returns whether
    /// the run stands at the point. A point in the unit of the stop criterion must lie
    /// between the run's position and its end; a point behind the run is refused.
    pub fn advance(&mut self, point: Point, progress: &mut dyn Progress) -> Result<bool> {
        let value = point.value();
        let particles = self.plan.description.system.particles as f64;
        let now = match point {
            Point::Time(_) => self.time(),
            Point::CollisionsPerParticle(_) => 2.0 * self.counters().collisions as f64 / particles,
        };
        let end = match (point, self.plan.stop) {
            (Point::Time(_), Stop::Time(end))
            | (Point::CollisionsPerParticle(_), Stop::CollisionsPerParticle(end)) => end,
            _ => f64::INFINITY,
        };
        if !(value.is_finite() && value >= now && value <= end) {
            let allowed = if end.is_finite() {
                format!("{now} ..= {end} (from where the run stands to its end)")
            } else {
                format!("a finite number >= {now} (where the run stands)")
            };
            return Err(Error::out_of_range(point.key(), value, &allowed));
        }
        self.go(progress, None, Some(point))?;
        Ok(each!(&self.run, r => r.reached(point, particles)))
    }

    /// Runs through the schedule (see [`Run::go`]), keeping the wall-clock time.
    fn go(
        &mut self,
        progress: &mut dyn Progress,
        stop_after: Option<usize>,
        point: Option<Point>,
    ) -> Result<()> {
        let clock = Instant::now();
        let saving = self.checkpoint_dir.as_deref().zip(self.checkpoint_every);
        let (plan, root) = (&self.plan, self.is_root());
        let result =
            each!(&mut self.run, r => r.go(plan, saving, root, progress, stop_after, point));
        self.wall_seconds += clock.elapsed().as_secs_f64();
        self.run_seconds += clock.elapsed().as_secs_f64();
        result
    }

    /// Writes the output files into `dir`: `timeseries.csv`, `velocity_histograms.csv`
    /// (with `run.histogram_at`), `temperature.png` and `summary.json`.
    /// On several ranks every rank calls it (it gathers the ranks' reports) and rank 0
    /// writes, adding `parallel` to `summary.json`.
    pub fn write(&self, dir: &Path) -> Result<()> {
        let reports = self.rank_reports();
        if !self.is_root() {
            return Ok(());
        }
        let run = &self.plan.description.run;
        each!(&self.run, r => {
            r.timeseries.write(&dir.join("timeseries.csv"))?;
            if run.histogram_at.as_ref().is_some_and(|at| !at.is_empty()) {
                r.histograms.write(&dir.join("velocity_histograms.csv"))?;
            }
            r.space.write(dir)?;
            if let Some(species) = &r.species {
                species.write(&dir.join("species.csv"))?;
            }
        });
        crate::figures::temperature(
            &dir.join("temperature.png"),
            &self.plan,
            self.samples(),
            self.species_samples(),
        )?;
        let counters = self.counters();
        let wall = self.wall_seconds;
        let mut summary = serde_json::json!({
            "parameters": self.plan.description,
            "collisions": counters.collisions,
            "events": counters.events,
            "tc_elastic_collisions": counters.tc_elastic,
            "wall_seconds": wall,
            "run_seconds": self.run_seconds,
            "events_per_second": counters.events as f64 / wall,
            "collisions_per_second": counters.collisions as f64 / wall,
            "final": self.samples().last(),
            "complete": self.is_complete(),
        });
        if let Some(theory) = crate::species::driven_theory(&self.plan) {
            summary["driven_theory"] = theory;
        }
        if let Some(rows) = self.species_samples() {
            summary["species"] = crate::species::summary(&self.plan, rows);
        }
        if let Some(contacts) = self.contact_report() {
            summary["contacts"] = serde_json::json!(contacts);
        }
        if let Some(ranks) = reports {
            summary["parallel"] =
                parallel::summary(&ranks, self.plan.description.system.dimension as usize);
        }
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
        space: SpaceObserver,
        species: Option<SpeciesSeries>,
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
            space,
            species,
        }
    }

    /// A run continuing from a check-point: the records must be those of the run up to
    /// its last sample, and the engine must stand there or between it and the next target
    /// (a run saved between samples).
    fn resumed(
        plan: &Plan,
        engine: Box<dyn Driven<D>>,
        timeseries: TimeSeries,
        histograms: VelocityHistograms,
        space: SpaceObserver,
        species: Option<SpeciesSeries>,
    ) -> std::result::Result<Self, String> {
        let wanted = species_series(plan);
        let species = match (species, wanted) {
            (Some(records), Some(fresh)) if records.kinds == fresh.kinds => Some(records),
            (None, None) => None,
            _ => {
                return Err(
                    "the per-species records do not match system.species (or the check-point \
                     was written before species.csv existed)"
                        .into(),
                )
            }
        };
        let mut run = Run::new(plan, engine, timeseries, histograms, space, species);
        let samples = &run.timeseries.samples;
        run.next = match samples.len() {
            0 => 0,
            taken => {
                run.schedule
                    .iter()
                    .position(|target| target.sample == Some(taken - 1))
                    .ok_or(format!(
                        "{taken} samples where run.samples = {}",
                        plan.description.run.samples
                    ))?
                    + 1
            }
        };
        run.check_samples(plan.stop)?;
        run.space.check_records(run.timeseries.samples.len())?;
        if let Some(species) = &run.species {
            species.check_records(run.timeseries.samples.len())?;
        }
        let (time, counters) = (run.engine.time(), run.engine.counters());
        let (last_time, last_events) = samples.last().map_or((0.0, 0), |s| (s.time, s.events));
        let particles = plan.description.system.particles as f64;
        let within = match (run.schedule.get(run.next), plan.stop) {
            (None, _) => time == last_time && counters.events == last_events,
            (Some(next), Stop::Time(_)) => time <= next.value,
            (Some(next), Stop::CollisionsPerParticle(_)) => {
                counters.collisions <= collisions_at(next.value, particles)
            }
        };
        if time < last_time || counters.events < last_events || !within {
            return Err(
                "the engine does not stand at the last sample or before the next one".into(),
            );
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

    /// Checks the samples against the schedule: from the start onwards in time, collisions
    /// and events, and (a run stopped by time) each at the time of its target.
    fn check_samples(&self, stop: Stop) -> std::result::Result<(), String> {
        let mut previous = (0.0, 0.0, 0);
        for (i, sample) in self.timeseries.samples.iter().enumerate() {
            let now = (sample.time, sample.collisions_per_particle, sample.events);
            let ordered = now.0 >= previous.0 && now.1 >= previous.1 && now.2 >= previous.2;
            let target = self.schedule.iter().find(|t| t.sample == Some(i));
            let on_time = match (stop, target) {
                (Stop::Time(_), Some(target)) => sample.time == target.value,
                _ => true,
            };
            if !(sample.time.is_finite() && ordered && on_time) {
                return Err(format!(
                    "sample {i} (time {}, {} collisions per particle, {} events) is not where \
                     the schedule and the samples before it put it",
                    sample.time, sample.collisions_per_particle, sample.events
                ));
            }
            previous = now;
        }
        Ok(())
    }

    /// Runs through the remaining targets, until `stop_after` samples exist or the run
    /// reaches `point`, whichever first.
    fn go(
        &mut self,
        plan: &Plan,
        saving: Option<(&Path, usize)>,
        root: bool,
        progress: &mut dyn Progress,
        stop_after: Option<usize>,
        point: Option<Point>,
    ) -> Result<()> {
        let particles = plan.description.system.particles as f64;
        if self.next < self.schedule.len() {
            self.space.check_directory()?;
        }
        progress.start(plan.description.run.samples, self.timeseries.samples.len());
        let started = Instant::now();
        let result = (|| {
            while self.next < self.schedule.len() {
                let target = self.schedule[self.next];
                if self.advance(plan.stop, target.value, point, particles, progress)? {
                    return Ok(());
                }
                self.timeseries.observe(&target, self.engine.as_mut());
                self.histograms.observe(&target, self.engine.as_mut());
                if let Some(species) = &mut self.species {
                    species.observe(&target, self.engine.as_mut());
                }
                if let Some(sample) = target.sample {
                    self.space.observe(sample, self.engine.as_mut())?;
                }
                self.next += 1;
                if target.sample.is_some() {
                    let taken = self.timeseries.samples.len();
                    if let Some((dir, every)) = saving {
                        if taken.is_multiple_of(every) {
                            let file = dir.join(checkpoint::FILE_NAME);
                            self.write_checkpoint(plan, &file, Some(every), root)?;
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
                        return Ok(());
                    }
                }
                if point.is_some_and(|p| self.reached(p, particles)) {
                    return Ok(());
                }
            }
            Ok(())
        })();
        progress.finish();
        result
    }

    /// Whether the engine has reached `point`.
    fn reached(&self, point: Point, particles: f64) -> bool {
        match point {
            Point::Time(t) => self.engine.time() >= t,
            Point::CollisionsPerParticle(c) => {
                self.engine.counters().collisions >= collisions_at(c, particles)
            }
        }
    }

    /// Brings the engine to `value` of the stop criterion, or to `point` if that comes
    /// first, in pieces of [`PIECE_COLLISIONS`] collisions with [`Progress::keep_going`]
    /// asked between them. Returns true if it stopped at the point short of `value`.
    fn advance(
        &mut self,
        stop: Stop,
        value: f64,
        point: Option<Point>,
        particles: f64,
        progress: &mut dyn Progress,
    ) -> Result<bool> {
        let (mut end, mut total) = match stop {
            Stop::Time(_) => (value, u64::MAX),
            Stop::CollisionsPerParticle(_) => (f64::INFINITY, collisions_at(value, particles)),
        };
        match point {
            Some(Point::Time(t)) => end = end.min(t),
            Some(Point::CollisionsPerParticle(c)) => total = total.min(collisions_at(c, particles)),
            None => {}
        }
        loop {
            let (time, counters) = (self.engine.time(), self.engine.counters());
            if time >= end || counters.collisions >= total {
                break;
            }
            // Asked only short of the target: an interrupted run never stands at a target
            // it has not observed.
            if !progress.keep_going() {
                return Err(Error::Interrupted { time });
            }
            let pause = (counters.collisions / PIECE_COLLISIONS + 1) * PIECE_COLLISIONS;
            self.engine.run_paused(end, total, pause);
            if let Some(time) = self.engine.collapsed() {
                return Err(Error::Collapse { time });
            }
            if self.engine.time() == time && self.engine.counters() == counters {
                break; // nothing more happens (no collision left to count)
            }
        }
        let at_target = match stop {
            Stop::Time(_) => self.engine.time() >= value,
            Stop::CollisionsPerParticle(_) => {
                self.engine.counters().collisions >= collisions_at(value, particles)
            }
        };
        Ok(!at_target && point.is_some_and(|p| self.reached(p, particles)))
    }

    /// Saves the state (collective on several ranks: the engine gathers it) and, on the
    /// `root` rank, writes it to `file`.
    fn write_checkpoint(
        &mut self,
        plan: &Plan,
        file: &Path,
        every: Option<usize>,
        root: bool,
    ) -> Result<()> {
        let records = RecordsRef {
            description: &plan.description,
            every,
            timeseries: &self.timeseries,
            histograms: &self.histograms,
            space: &self.space.records,
            species: self.species.as_ref(),
        };
        self.engine.write_checkpoint(file, records, root)
    }
}

/// The per-species series of a run with `system.species`.
fn species_series(plan: &Plan) -> Option<SpeciesSeries> {
    let list = plan.description.system.species.as_ref()?;
    Some(SpeciesSeries::new(
        list.iter().map(|x| (0.5 * x.diameter, x.mass)).collect(),
    ))
}
