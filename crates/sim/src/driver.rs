//! The one loop of every run (lumol's `Simulation::run` over a `Propagator`): advance the
//! engine towards each target of a [`Schedule`] in pieces of [`PIECE_COLLISIONS`]
//! collisions, asking [`Progress::keep_going`] between pieces, then let every
//! [`Observer`] of the list look at the engine, then write a check-point when one is due.
//! [`crate::Simulation`] (`haff run`, Python), the rod chain (`haff rods chain`), the
//! reproduced papers and the benches all run through it; it knows no engine and no
//! observer by name, so an engine or observer defined outside this crate runs through it
//! with check-points and resumes bit for bit (`tests/extension.rs`).

use crate::checkpoint::{self, Format, Records, RecordsOut};
use crate::error::{Error, Result};
use crate::observer::Observer;
use crate::schedule::{Measure, Schedule, Target};
use gas::{Checkpoint, Engine};
use serde::{Deserialize, Serialize};
use std::path::Path;
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

impl Progress for () {}

/// Collisions per piece of a run, between which the driver asks [`Progress::keep_going`]:
/// about 0.1 s of event-driven MD. Pieces are counted from the start of the run, so a run
/// cut into them is the same whoever drives it (the `haff` command, Python, a resumed run;
/// see `gas::Engine::run_paused`).
pub const PIECE_COLLISIONS: u64 = 1 << 16;

/// A point of a run short of its end, where a run may stop ([`Until::point`]).
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

    /// Its value, in its unit.
    pub fn value(self) -> f64 {
        match self {
            Point::Time(t) => t,
            Point::CollisionsPerParticle(c) => c,
        }
    }
}

/// The collision tally at `c` collisions per particle among `particles`.
pub fn collisions_at(c: f64, particles: f64) -> u64 {
    (c * particles / 2.0).round() as u64
}

/// An engine the driver runs: the engine interface and its state for check-points. Every
/// engine with a [`Checkpoint`] is one. Engines are `Send`, so that a run can go on in
/// another thread (Python releases the GIL).
pub trait Driven<const D: usize>: Engine<D> + Send {
    /// The engine's complete state, encoded for a check-point (collective on several ranks:
    /// every rank calls it).
    fn state_bytes(&mut self) -> Result<Vec<u8>>;
}

impl<const D: usize, E: Checkpoint<D> + Send> Driven<D> for E {
    fn state_bytes(&mut self) -> Result<Vec<u8>> {
        checkpoint::encode_state(&self.save())
    }
}

/// Where a call of [`Driver::go`] ends short of the schedule's end.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Until {
    /// Once this many samples of the schedule have been taken (counted from the start of
    /// the run).
    pub samples: Option<usize>,
    /// Once the engine reaches this point (taking the samples on the way).
    pub point: Option<Point>,
}

/// Check-points during a run: after every `every`-th sample, the file `file` of `format`
/// with the `preamble` records (what the caller keeps besides the driver and its
/// observers: the run description, ...), written by the process where `write` is true.
/// With `after_seconds` > 0 such a sample saves only when that much wall-clock time has
/// passed since the last check-point (or the start of this call): a study's default, which
/// bounds the work a kill loses without writing a large state at every sample of a short
/// run. (Single process only: ranks would disagree on the clock.)
pub struct Saving<'a> {
    pub file: &'a Path,
    pub format: Format,
    pub every: usize,
    pub after_seconds: f64,
    pub write: bool,
    pub preamble: &'a dyn Fn() -> Result<RecordsOut>,
}

/// The driver's own record in a check-point: where it stands in the schedule.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Position {
    /// The targets done (observed).
    next: usize,
}

/// The name of the driver's record in a check-point.
const DRIVER_RECORD: &str = "driver";

/// An engine, its observers and its schedule, and how far the run has gone.
pub struct Driver<const D: usize> {
    engine: Box<dyn Driven<D>>,
    observers: Vec<Box<dyn Observer<D>>>,
    schedule: Schedule,
    /// The next target of the schedule.
    next: usize,
    /// Samples among the targets done.
    taken: usize,
    /// Particles of the engine (collisions per particle count for two of them).
    particles: f64,
}

impl<const D: usize> Driver<D> {
    /// A run of `engine` at the start of `schedule`, observed by `observers` (their names
    /// distinct, and none of "driver" or a caller's preamble key).
    pub fn new(
        engine: Box<dyn Driven<D>>,
        observers: Vec<Box<dyn Observer<D>>>,
        schedule: Schedule,
    ) -> Self {
        let particles = engine.particles() as f64;
        Driver {
            engine,
            observers,
            schedule,
            next: 0,
            taken: 0,
            particles,
        }
    }

    /// A run continuing from the `records` of a check-point: the driver's position and each
    /// observer's records, checked against the schedule and the engine (which must stand at
    /// the last target done or between it and the next). The records used are taken out of
    /// `records`.
    pub fn resume(
        engine: Box<dyn Driven<D>>,
        observers: Vec<Box<dyn Observer<D>>>,
        schedule: Schedule,
        records: &mut Records,
    ) -> std::result::Result<Self, String> {
        let mut driver = Driver::new(engine, observers, schedule);
        let position: Position = records.take(DRIVER_RECORD)?;
        if position.next > driver.schedule.targets.len() {
            return Err(format!(
                "{} targets (samples and histograms) done where the schedule has {}",
                position.next,
                driver.schedule.targets.len()
            ));
        }
        driver.next = position.next;
        driver.taken = driver.schedule.samples_before(position.next);
        let (time, collisions) = (driver.engine.time(), driver.engine.counters().collisions);
        let within = match driver.schedule.targets.get(driver.next) {
            None => true,
            Some(next) => match driver.schedule.measure {
                Measure::Time => time <= next.value,
                Measure::CollisionsPerParticle => {
                    collisions <= collisions_at(next.value, driver.particles)
                }
            },
        };
        if !(time.is_finite() && within) {
            return Err(
                "the engine does not stand at the last sample or before the next one".into(),
            );
        }
        let Driver {
            engine,
            observers,
            schedule,
            next,
            ..
        } = &mut driver;
        for observer in observers.iter_mut() {
            let record = records.take_raw(observer.name())?;
            observer
                .resume(&record, schedule, *next, engine.as_mut())
                .map_err(|e| format!("{}: {e}", observer.name()))?;
        }
        Ok(driver)
    }

    /// The engine.
    pub fn engine(&self) -> &dyn Driven<D> {
        self.engine.as_ref()
    }

    /// The engine, mutable (its state for observables: `system()` synchronizes).
    pub fn engine_mut(&mut self) -> &mut dyn Driven<D> {
        self.engine.as_mut()
    }

    pub fn schedule(&self) -> &Schedule {
        &self.schedule
    }

    /// The targets done so far.
    pub fn done(&self) -> usize {
        self.next
    }

    /// Samples taken so far.
    pub fn samples_taken(&self) -> usize {
        self.taken
    }

    /// Whether every target of the schedule has been observed.
    pub fn is_complete(&self) -> bool {
        self.next >= self.schedule.targets.len()
    }

    pub fn observers(&self) -> &[Box<dyn Observer<D>>] {
        &self.observers
    }

    pub fn observers_mut(&mut self) -> &mut [Box<dyn Observer<D>>] {
        &mut self.observers
    }

    /// The first observer of type `T`, if the run has one.
    pub fn observer<T: 'static>(&self) -> Option<&T> {
        self.observers
            .iter()
            .find_map(|o| o.as_any().downcast_ref::<T>())
    }

    /// Runs through the remaining targets until the schedule ends or `until` is reached,
    /// writing check-points as `saving` says.
    pub fn go(
        &mut self,
        progress: &mut dyn Progress,
        until: Until,
        saving: Option<&Saving<'_>>,
    ) -> Result<()> {
        if self.next < self.schedule.targets.len() {
            for observer in &self.observers {
                observer.check_ready()?;
            }
        }
        progress.start(self.schedule.samples(), self.samples_taken());
        let started = Instant::now();
        let result = self.run_targets(progress, until, saving, started);
        progress.finish();
        result
    }

    fn run_targets(
        &mut self,
        progress: &mut dyn Progress,
        until: Until,
        saving: Option<&Saving<'_>>,
        started: Instant,
    ) -> Result<()> {
        let mut last_saved = started;
        while self.next < self.schedule.targets.len() {
            let target = self.schedule.targets[self.next];
            if self.advance(target.value, until.point, progress)? {
                return Ok(());
            }
            for observer in &mut self.observers {
                observer.observe(&target, self.engine.as_mut())?;
            }
            self.next += 1;
            if target.sample.is_some() {
                self.taken += 1;
                let taken = self.taken;
                if let Some(saving) = saving {
                    if taken.is_multiple_of(saving.every)
                        && last_saved.elapsed().as_secs_f64() >= saving.after_seconds
                    {
                        last_saved = Instant::now();
                        let preamble = (saving.preamble)()?;
                        self.write_checkpoint(saving.file, saving.format, preamble, saving.write)?;
                    }
                }
                let events = self.engine.counters().events as f64;
                let rate = events / started.elapsed().as_secs_f64().max(1e-9);
                let mut note = format!("{rate:.3e} events/s");
                for observer in &self.observers {
                    if let Some(more) = observer.note() {
                        note += &format!(", {more}");
                    }
                }
                progress.sample(taken, &note);
                if until.samples.is_some_and(|k| taken >= k) {
                    return Ok(());
                }
            }
            if until.point.is_some_and(|p| self.reached(p)) {
                return Ok(());
            }
        }
        Ok(())
    }

    /// Whether the engine has reached `point`.
    pub fn reached(&self, point: Point) -> bool {
        match point {
            Point::Time(t) => self.engine.time() >= t,
            Point::CollisionsPerParticle(c) => {
                self.engine.counters().collisions >= collisions_at(c, self.particles)
            }
        }
    }

    /// Brings the engine to `value` of the schedule's measure, or to `point` if that comes
    /// first, in pieces of [`PIECE_COLLISIONS`] collisions with [`Progress::keep_going`]
    /// asked between them. Returns true if it stopped at the point short of `value`.
    fn advance(
        &mut self,
        value: f64,
        point: Option<Point>,
        progress: &mut dyn Progress,
    ) -> Result<bool> {
        let (mut end, mut total) = match self.schedule.measure {
            Measure::Time => (value, u64::MAX),
            Measure::CollisionsPerParticle => (f64::INFINITY, collisions_at(value, self.particles)),
        };
        match point {
            Some(Point::Time(t)) => end = end.min(t),
            Some(Point::CollisionsPerParticle(c)) => {
                total = total.min(collisions_at(c, self.particles))
            }
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
        let at_target = match self.schedule.measure {
            Measure::Time => self.engine.time() >= value,
            Measure::CollisionsPerParticle => {
                self.engine.counters().collisions >= collisions_at(value, self.particles)
            }
        };
        Ok(!at_target && point.is_some_and(|p| self.reached(p)))
    }

    /// Saves the state as a check-point: the `preamble` records, the driver's position,
    /// every observer's records (by name) and the engine's state. The state is taken in
    /// any case (on several ranks that is collective); the file `file` of `format` is
    /// written only if `write`.
    pub fn write_checkpoint(
        &mut self,
        file: &Path,
        format: Format,
        mut records: RecordsOut,
        write: bool,
    ) -> Result<()> {
        let state = self.engine.state_bytes()?;
        if !write {
            return Ok(());
        }
        records.push(DRIVER_RECORD, &Position { next: self.next })?;
        for observer in &self.observers {
            records.push_raw(observer.name(), observer.record()?);
        }
        checkpoint::write_to(file, format, &records, &state)
    }

    /// The observed target at which each sample was taken, in the schedule's order.
    pub fn sample_targets(&self) -> impl Iterator<Item = &Target> {
        self.schedule.targets[..self.next]
            .iter()
            .filter(|t| t.sample.is_some())
    }
}
