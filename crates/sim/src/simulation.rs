//! A run of `haff run` and of Python's `haff.Simulation`: a [`Simulation`] built from a run
//! description (or a check-point) builds its engine ([`crate::engines`]) and its observers
//! ([`crate::observer::for_plan`]) and runs them through the one driver
//! ([`crate::driver::Driver`]), writes check-points and, on request, the output files.

use crate::checkpoint::{self, RecordsOut, Sections};
use crate::description::RunDescription;
use crate::driver::{Driver, Saving, Until};
use crate::engines;
use crate::error::{Error, Result};
use crate::law;
use crate::observer::{self, Histogram, Sample, TimeSeries, VelocityHistograms};
use crate::output::write_json_file;
use crate::parallel::{self, Communicator};
use crate::schedule::{sample_targets, schedule, Measure, Schedule};
use crate::space::{SpaceObserver, SpaceRecords};
use crate::species::{SpeciesSample, SpeciesSeries};
use crate::validate::{validate, Plan, Stop};
use gas::Counters;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

pub use crate::driver::{Point, Progress, PIECE_COLLISIONS};

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

/// How a grown dense start was made (`summary.json`: `initial_state`; kept in check-points).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialState {
    /// `growth`: spheres grown by event-driven MD (Lubachevsky–Stillinger).
    pub method: InitialMethod,
    /// The packing fraction the spheres grew from.
    pub start_fraction: f64,
    pub collisions: u64,
    pub events: u64,
    pub seconds: f64,
}

/// How initial positions were made (only dense starts are recorded).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum InitialMethod {
    Growth,
}

impl InitialState {
    fn of(report: &gas::init::GrowthReport) -> Self {
        InitialState {
            method: InitialMethod::Growth,
            start_fraction: report.start_fraction,
            collisions: report.collisions,
            events: report.events,
            seconds: report.seconds,
        }
    }
}

/// A run: its plan, and its engine and observers in the driver.
pub struct Simulation {
    plan: Plan,
    run: Dimensioned,
    /// How its dense start was grown, if it was.
    grown: Option<InitialState>,
    /// Where its particles came from (`system.initial`), if from a file, a run or code.
    initial_particles: Option<crate::validate::InitialReport>,
    /// Check-points every this many samples into `checkpoint_dir`.
    checkpoint_every: Option<usize>,
    /// Wall-clock seconds between check-points at the least (0: none).
    checkpoint_after_seconds: f64,
    checkpoint_dir: Option<PathBuf>,
    /// The directory files are written to during the run ([`Simulation::set_output_dir`]).
    output_dir: Option<PathBuf>,
    /// Wall-clock seconds spent by this process building the run and in [`Simulation::run`].
    wall_seconds: f64,
    /// Of which in [`Simulation::run`] and [`Simulation::advance`] (the run, without
    /// building it).
    run_seconds: f64,
    /// The ranks the run is spread over ([`parallel::world`]: this process alone unless
    /// launched by mpirun); only rank 0 writes files.
    comm: Arc<dyn Communicator>,
}

/// The driver in the run's dimension (engines are generic over it).
enum Dimensioned {
    One(Box<Driver<1>>),
    Two(Box<Driver<2>>),
    Three(Box<Driver<3>>),
}

/// Calls `$body` with `$run` bound to the driver of whichever dimension.
macro_rules! each {
    ($value:expr, $run:ident => $body:expr) => {
        match $value {
            Dimensioned::One($run) => $body,
            Dimensioned::Two($run) => $body,
            Dimensioned::Three($run) => $body,
        }
    };
}

/// The driver of `$dimension` (1, 2, else 3) dimensions: `$make` evaluated with the
/// constant `$D` set to it, its error returned.
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

/// The stops of a run: its samples (log- or equally spaced) and velocity histograms.
fn schedule_of(plan: &Plan) -> Schedule {
    let run = &plan.description.run;
    let targets = schedule(
        &sample_targets(plan.stop.end(), run.samples, plan.log_spacing()),
        run.histogram_at.as_deref().unwrap_or(&[]),
    );
    let measure = match plan.stop {
        Stop::Time(_) => Measure::Time,
        Stop::CollisionsPerParticle(_) => Measure::CollisionsPerParticle,
    };
    Schedule { targets, measure }
}

/// The records of an empty space observer (a run without `[output]`).
static NO_SPACE_RECORDS: std::sync::OnceLock<SpaceRecords> = std::sync::OnceLock::new();

impl Simulation {
    /// A run at time 0 from a description (checked first; errors name the key).
    pub fn new(description: &RunDescription) -> Result<Self> {
        Self::new_on(description, parallel::world())
    }

    /// A run at time 0 spread over the ranks of `comm` (every rank calls this with the
    /// same description; see [`parallel`]).
    pub fn new_on(description: &RunDescription, comm: Arc<dyn Communicator>) -> Result<Self> {
        let clock = Instant::now();
        Self::start(validate(description)?, comm, clock)
    }

    /// A run at time 0 from particles given in code (Python's arrays): `system.initial`
    /// is set to `{}` if absent (a file or run there is refused), and the particles are
    /// checked and resolved as a file's ([`crate::validate::validate_with`]). A
    /// configuration without a box takes `system.box`.
    pub fn with_initial(
        description: &RunDescription,
        particles: crate::particles::Configuration,
    ) -> Result<Self> {
        let clock = Instant::now();
        let mut description = description.clone();
        description
            .system
            .initial
            .get_or_insert_with(Default::default);
        let plan = crate::validate::validate_with(&description, particles)?;
        Self::start(plan, parallel::world(), clock)
    }

    /// The run of a checked plan at time 0.
    fn start(plan: Plan, comm: Arc<dyn Communicator>, clock: Instant) -> Result<Self> {
        parallel::check_ranks(&plan, comm.size())?;
        let law = law::of_plan(&plan)?;
        let grown;
        let initial_particles = plan.initial.as_ref().map(|i| i.report.clone());
        let run = in_dimension!(plan.description.system.dimension, D => {
            let (engine, report) = engines::start::<D>(&plan, law, &comm)?;
            grown = report;
            Ok::<_, Error>(Driver::<D>::new(engine, observer::for_plan::<D>(&plan), schedule_of(&plan)))
        });
        Ok(Simulation {
            plan,
            run,
            grown: grown.map(|r| InitialState::of(&r)),
            initial_particles,
            checkpoint_every: None,
            checkpoint_after_seconds: 0.0,
            checkpoint_dir: None,
            output_dir: None,
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
        let sections = checkpoint::read(dir, checkpoint::RUN)?;
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
        let sections = checkpoint::read_from(path, checkpoint::RUN)?;
        Self::from_sections(&sections, clock, parallel::world())
    }

    /// The run of a verified check-point, checked for meaning: the run description like a
    /// fresh run's, then the engine state, the driver's position and every observer's
    /// records against it.
    fn from_sections(
        sections: &Sections,
        clock: Instant,
        comm: Arc<dyn Communicator>,
    ) -> Result<Self> {
        let fail = |e: String| sections.error(e);
        let mut records: checkpoint::Records = sections.records()?;
        let description: RunDescription = records.take("description").map_err(fail)?;
        let every: Option<usize> = records.take("every").map_err(fail)?;
        let grown: Option<InitialState> = records.take_optional("initial_state").map_err(fail)?;
        let initial_particles: Option<crate::validate::InitialReport> =
            records.take_optional("initial_particles").map_err(fail)?;
        let plan = crate::validate::validate_from(&description, crate::validate::Source::Saved)
            .map_err(|e| sections.error(e))?;
        parallel::check_ranks(&plan, comm.size())?;
        if description != plan.description {
            return Err(sections.error("the run description is not in its normal form"));
        }
        if !every.is_none_or(|k| (1..=1_000_000).contains(&k)) {
            return Err(sections.error("every: allowed 1 ..= 1e6 samples"));
        }
        let law = law::of_plan(&plan).map_err(|e| sections.error(e))?;
        let run = in_dimension!(plan.description.system.dimension, D => Driver::<D>::resume(
            engines::restore::<D>(&plan, law, sections, &comm)?,
            observer::for_plan::<D>(&plan),
            schedule_of(&plan),
            &mut records,
        )
        .map_err(fail));
        records.finish().map_err(fail)?;
        Ok(Simulation {
            plan,
            run,
            grown,
            initial_particles,
            checkpoint_every: every,
            checkpoint_after_seconds: 0.0,
            checkpoint_dir: None,
            output_dir: None,
            wall_seconds: clock.elapsed().as_secs_f64(),
            run_seconds: 0.0,
            comm,
        })
    }

    /// The records of a check-point besides the driver's: the run description and the
    /// check-point interval.
    fn preamble(
        plan: &Plan,
        every: Option<usize>,
        grown: Option<&InitialState>,
        initial_particles: Option<&crate::validate::InitialReport>,
    ) -> Result<RecordsOut> {
        let mut records = RecordsOut::new();
        records.push("description", &plan.description)?;
        records.push("every", &every)?;
        if let Some(grown) = grown {
            records.push("initial_state", grown)?;
        }
        if let Some(report) = initial_particles {
            records.push("initial_particles", report)?;
        }
        Ok(records)
    }

    /// How the dense start of the run was grown, if it was.
    pub fn initial_state(&self) -> Option<&InitialState> {
        self.grown.as_ref()
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
        let preamble = Self::preamble(
            &self.plan,
            self.checkpoint_every,
            self.grown.as_ref(),
            self.initial_particles.as_ref(),
        )?;
        let root = self.is_root();
        each!(&mut self.run, r => r.write_checkpoint(&file, checkpoint::RUN, preamble, root))
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
        each!(&self.run, r => r.engine().rank_reports())
    }

    /// The directory that field and snapshot files (`[output]`) are written to during the
    /// run; without one a run that asks for them is refused before it goes on (an input
    /// error naming `output.fields` or `output.snapshots`).
    pub fn set_output_dir(&mut self, dir: &Path) {
        let root = self.is_root();
        self.output_dir = Some(dir.to_path_buf());
        each!(&mut self.run, r => {
            for observer in r.observers_mut() {
                observer.set_output(dir, root);
            }
        })
    }

    /// The directory set by [`Simulation::set_output_dir`], if any.
    pub fn output_dir(&self) -> Option<&Path> {
        self.output_dir.as_deref()
    }

    /// What the observers of `[output]` have recorded so far (the rows of `modes.csv` and
    /// `structure.csv`, the field and snapshot files written).
    pub fn space_records(&self) -> &SpaceRecords {
        each!(&self.run, r => r.observer::<SpaceObserver>().map(|s| &s.records))
            .unwrap_or_else(|| NO_SPACE_RECORDS.get_or_init(SpaceRecords::default))
    }

    /// Saves the state to the check-point of `dir` every `every` samples (None: never).
    pub fn set_checkpoints(&mut self, dir: &Path, every: Option<usize>) {
        self.checkpoint_dir = Some(dir.to_path_buf());
        self.checkpoint_every = every;
    }

    /// Check-points at those samples only when `seconds` of wall-clock time have passed
    /// since the last one (0, or not a finite number > 0: at every one; a study's default
    /// is 60). Ignored on several ranks, whose clocks would disagree on when to save.
    pub fn set_checkpoint_spacing(&mut self, seconds: f64) {
        self.checkpoint_after_seconds = if seconds.is_finite() && seconds > 0.0 {
            seconds
        } else {
            0.0
        };
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
        each!(&self.run, r => r.observer::<TimeSeries>().map_or(&[][..], |t| &t.samples))
    }

    /// The per-species rows taken so far (`species.csv`); None for a run without
    /// `system.species`.
    pub fn species_samples(&self) -> Option<&[SpeciesSample]> {
        each!(&self.run, r => r.observer::<SpeciesSeries>().map(|s| s.samples.as_slice()))
    }

    /// The rows of `pressure.csv` (`output.pressure`, `[shear]`), None without them.
    pub fn pressure(&self) -> Option<&crate::rheology::PressureSeries> {
        each!(&self.run, r => r.observer::<crate::rheology::PressureSeries>())
    }

    /// The rows of `msd.csv` (`output.msd`), None without it.
    pub fn msd(&self) -> Option<&crate::diffusion::MsdSeries> {
        each!(&self.run, r => r.observer::<crate::diffusion::MsdSeries>())
    }

    /// `summary.json`'s `rheology` of the rows so far (`[shear]`; null otherwise).
    pub fn rheology(&self, series: &crate::rheology::PressureSeries) -> serde_json::Value {
        match self.plan.description.system.dimension {
            2 => crate::rheology::summary::<2>(&self.plan, series),
            _ => crate::rheology::summary::<3>(&self.plan, series),
        }
    }

    /// `summary.json`'s `green_kubo` of the rows so far (`output.pressure` without
    /// `[shear]`: the equilibrium viscosity, or why it was skipped).
    pub fn green_kubo(&self, series: &crate::rheology::PressureSeries) -> serde_json::Value {
        match self.plan.description.system.dimension {
            2 => crate::green_kubo::summary::<2>(&self.plan, series),
            _ => crate::green_kubo::summary::<3>(&self.plan, series),
        }
    }

    /// The rows of `profiles.csv` (`output.profiles`), None without it.
    pub fn profile_rows(&self) -> Option<&[crate::profiles::ProfileRow]> {
        each!(&self.run, r => r.observer::<crate::profiles::ProfileSeries>().map(|s| s.rows.as_slice()))
    }

    /// The walls' rows taken so far (`walls.csv`); None for a run in the periodic box.
    pub fn wall_samples(&self) -> Option<&[crate::walls::WallSample]> {
        each!(&self.run, r => r.observer::<crate::walls::WallSeries>().map(|s| s.samples.as_slice()))
    }

    /// The velocity histograms taken so far.
    pub fn histograms(&self) -> &[Histogram] {
        each!(&self.run, r => r.observer::<VelocityHistograms>().map_or(&[][..], |h| &h.histograms))
    }

    pub fn time(&self) -> f64 {
        each!(&self.run, r => r.engine().time())
    }

    /// The particles now (copies; see [`Particles`]).
    pub fn particles(&mut self) -> Particles {
        each!(&mut self.run, r => {
            let system = r.engine_mut().system();
            Particles {
                dimension: system.positions.first().map_or(0, |x| x.len()),
                positions: system.positions.iter().flatten().copied().collect(),
                velocities: system.velocities.iter().flatten().copied().collect(),
                radii: system.radii.clone(),
                masses: system.masses.clone(),
            }
        })
    }

    /// The particles now as a particle file holds them ([`crate::particles`]): the box,
    /// positions, velocities (under `[shear]` relative to the flow), diameters, masses,
    /// species (the index of the plan's species), the spins of rough particles, the time.
    pub fn configuration(&mut self) -> crate::particles::Configuration {
        let kinds = self.plan.kinds();
        let time = self.time();
        each!(&mut self.run, r => {
            let engine = r.engine_mut();
            let spins = engine.rotation().map(|w| w.angular.clone());
            let system = engine.system();
            let lift = |v: &[f64]| -> [f64; 3] { std::array::from_fn(|k| v.get(k).copied().unwrap_or(0.0)) };
            crate::particles::Configuration {
                dimension: system.sides.len(),
                sides: system.sides.to_vec(),
                positions: system.positions.iter().map(|x| lift(x)).collect(),
                velocities: Some(system.velocities.iter().map(|x| lift(x)).collect()),
                diameters: Some(system.radii.iter().map(|r| 2.0 * r).collect()),
                masses: Some(system.masses.clone()),
                species: Some(
                    system
                        .radii
                        .iter()
                        .zip(&system.masses)
                        .map(|(&r, &m)| kinds.iter().position(|&k| k == (r, m)).unwrap_or(0))
                        .collect(),
                ),
                spins,
                time: Some(time),
            }
        })
    }

    /// The granular temperature now, T = <m c^2> / D ([`gas::observe::temperature`]).
    pub fn temperature(&mut self) -> f64 {
        each!(&mut self.run, r => gas::observe::temperature(r.engine_mut().system()))
    }

    pub fn counters(&self) -> Counters {
        each!(&self.run, r => r.engine().counters())
    }

    /// What the engine reports of itself (soft-sphere MD: the section `contacts`: time
    /// step, multi-particle contacts, largest overlap, elastic energy now); each section
    /// goes into `summary.json` under its name.
    pub fn report(&self) -> gas::engine::Report {
        each!(&self.run, r => r.engine().report())
    }

    /// Whether every target of the schedule has been reached.
    pub fn is_complete(&self) -> bool {
        each!(&self.run, r => r.is_complete())
    }

    /// Runs to the end of the schedule, or until `stop_after` samples exist (a run in
    /// chunks), writing check-points as set by [`Simulation::set_checkpoints`].
    pub fn run(
        &mut self,
        progress: &mut dyn Progress,
        stop_after: Option<usize>,
    ) -> Result<Outcome> {
        let until = Until {
            samples: stop_after,
            point: None,
        };
        self.go(progress, until)?;
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
        let until = Until {
            samples: None,
            point: Some(point),
        };
        self.go(progress, until)?;
        Ok(each!(&self.run, r => r.reached(point)))
    }

    /// Runs through the schedule ([`Driver::go`]), keeping the wall-clock time.
    fn go(&mut self, progress: &mut dyn Progress, until: Until) -> Result<()> {
        let clock = Instant::now();
        let root = self.is_root();
        let (plan, every, grown) = (&self.plan, self.checkpoint_every, self.grown);
        let initial_particles = self.initial_particles.as_ref();
        let after_seconds = if self.ranks() > 1 {
            0.0
        } else {
            self.checkpoint_after_seconds
        };
        let preamble = || Self::preamble(plan, every, grown.as_ref(), initial_particles);
        let file = self
            .checkpoint_dir
            .as_ref()
            .map(|d| d.join(checkpoint::FILE_NAME));
        let saving = file.as_deref().zip(every).map(|(file, every)| Saving {
            file,
            format: checkpoint::RUN,
            every,
            after_seconds,
            write: root,
            preamble: &preamble,
        });
        let result = each!(&mut self.run, r => r.go(progress, until, saving.as_ref()));
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
        each!(&self.run, r => {
            for observer in r.observers() {
                observer.write(dir)?;
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
        if let Some(theory) = crate::rough::theory(&self.plan, self.samples()) {
            summary["rough_theory"] = theory;
        }
        if let Some(rows) = self.species_samples() {
            summary["species"] = crate::species::summary(&self.plan, rows);
        }
        if let Some(grown) = &self.grown {
            summary["initial_state"] = serde_json::json!(grown);
        }
        if let Some(report) = &self.initial_particles {
            summary["initial_particles"] = serde_json::json!(report);
        }
        if let Some(walls) = each!(&self.run, r => r.observer::<crate::walls::WallSeries>()) {
            summary["walls"] = crate::walls::summary(walls);
        }
        if let Some(series) = self.msd() {
            summary["self_diffusion"] = match self.plan.description.system.dimension {
                1 => crate::diffusion::summary::<1>(&self.plan, series),
                2 => crate::diffusion::summary::<2>(&self.plan, series),
                _ => crate::diffusion::summary::<3>(&self.plan, series),
            };
        }
        if let Some(series) = self.pressure() {
            if self.plan.shear.is_some() {
                summary["rheology"] = self.rheology(series);
            } else {
                summary["green_kubo"] = self.green_kubo(series);
            }
        }
        for section in self.report().sections {
            summary[section.name] = serde_json::json!(section);
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
