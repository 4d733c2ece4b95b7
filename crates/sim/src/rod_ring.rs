//! `haff rods chain`: the rod-chain MD of Giese's Eq. (2) on a ring ([`rods::engine`]),
//! and, on request, Giese's event-driven + Monte Carlo gas of the same rods from the same
//! start (the 1D event-driven engine with a stochastic law and per-particle baths), so that
//! the cooling of the translational energy can be compared. Runs of several seeds are
//! averaged; the chain MD check-points after any sample and continues bit for bit.
//!
//! ```toml
//! [chain]
//! rods = 100                    # N rods on a ring
//! lengths = [0.80865, 1.31001]  # repeated along the ring
//! modes = 10                    # modes per rod
//! alpha = 5000.0                # 1/alpha: range of the contact potential B exp(-alpha r)
//! temperature = 1e-4            # initial translational T (Maxwellian, zero momentum)
//! # perimeter, strength, sound_speed = 1, density = 1, bath_temperature = 0, seed = 1,
//! # step = 0.05
//! [run]
//! end_time = 20000.0
//! samples = 41
//! repeats = 4
//! compare = ["glauber", "tabulated"]
//! table = "docs/data/giese-table-gamma0.6173.json"
//! ```

mod description;
mod rows;

use description::chain_error;
pub use description::{ChainSection, CompareLaw, RingDescription, RingRunSection};
pub use rows::{EnergyRow, ENERGY_HEADER};

use crate::checkpoint::{self, Format, RecordsOut};
use crate::driver::{Driver, Progress, Saving, Until};
use crate::engines::{self, EngineSpec, Setup};
use crate::error::{Error, Result};
use crate::output::{number, write_csv_file, write_json_file};
use crate::plot::{self, Axes};
use crate::schedule::{Measure, Schedule};
use gas::{BathState, Checkpoint};
use restitution::{Glauber, Restitution};
use rods::engine::{ChainEngine, ChainEngineState};
use rods::ring::{equipartition_share, RingSetup, RingState};
use rows::EnergyRows;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// A named curve of rows (the chain MD, or ED + MC with one law), summed over repeats.
type Curve = (String, Vec<EnergyRow>);

/// The format of a rods chain check-point (5: the common layout of [`crate::driver`]: the
/// run's records, the driver's position, the rows as the observer's record).
const FORMAT: Format = Format {
    name: "haff-rods-chain-checkpoint",
    version: 5,
};

/// Where a run stands besides the chain MD of the repeat in progress (the check-point's
/// own records).
#[derive(Debug, Clone)]
struct Progressed {
    /// The repeat in progress (0-based).
    repeat: usize,
    /// Sums of the completed repeats (curve 0: chain MD; then one per compared law).
    curves: Vec<Curve>,
    chain_seconds: f64,
}

/// A chain run: the chain MD of every repeat, then ED + MC from the same start, each
/// through the run driver ([`Driver`]: pieces, interruptions, check-points).
pub struct RingRun {
    description: RingDescription,
    ring: RingSetup,
    /// Sampling times.
    targets: Vec<f64>,
    repeat: usize,
    /// The chain MD of the repeat in progress.
    current: Option<Driver<1>>,
    curves: Vec<Curve>,
    chain_seconds: f64,
    checkpoint_dir: Option<PathBuf>,
    every: Option<usize>,
    wall_seconds: f64,
}

impl RingRun {
    /// A run from its description (checked first).
    pub fn new(description: &RingDescription) -> Result<Self> {
        let ring = description.validate()?;
        let run = &description.run;
        let targets = (0..run.samples)
            .map(|k| run.end_time * k as f64 / (run.samples - 1) as f64)
            .collect();
        Ok(RingRun {
            description: description.clone(),
            ring,
            targets,
            repeat: 0,
            current: None,
            curves: Vec::new(),
            chain_seconds: 0.0,
            checkpoint_dir: None,
            every: None,
            wall_seconds: 0.0,
        })
    }

    /// The run saved in the check-point of `dir`, verified (format, version, checksum) and
    /// checked against its run file; further check-points go to `dir`.
    pub fn resume(dir: &Path) -> Result<Self> {
        let sections = checkpoint::read(dir, FORMAT)?;
        let fail = |e: String| sections.error(e);
        let mut records: checkpoint::Records = sections.records()?;
        let description: RingDescription = records.take("description").map_err(fail)?;
        let every: Option<usize> = records.take("every").map_err(fail)?;
        let saved = Progressed {
            repeat: records.take("repeat").map_err(fail)?,
            curves: records.take("curves").map_err(fail)?,
            chain_seconds: records.take("chain_seconds").map_err(fail)?,
        };
        let state: ChainEngineState = sections.engine()?;
        let mut run = RingRun::new(&description).map_err(|e| sections.error(e))?;
        run.check_saved(&saved, every, &state).map_err(fail)?;
        let engine = ChainEngine::restore(state, ()).map_err(|e| sections.error(e))?;
        let driver = Driver::resume(
            Box::new(engine),
            vec![Box::new(EnergyRows::chain())],
            run.schedule(),
            &mut records,
        )
        .map_err(fail)?;
        records.finish().map_err(fail)?;
        run.repeat = saved.repeat;
        run.current = Some(driver);
        run.curves = saved.curves;
        run.chain_seconds = saved.chain_seconds;
        run.every = every;
        run.checkpoint_dir = Some(dir.to_path_buf());
        Ok(run)
    }

    /// The samples of one repeat.
    fn schedule(&self) -> Schedule {
        Schedule::samples_at(&self.targets, Measure::Time)
    }

    /// Why the saved records and chain cannot be this run's, if they cannot (the rows and
    /// the driver's position are checked by the driver).
    fn check_saved(
        &self,
        saved: &Progressed,
        every: Option<usize>,
        state: &ChainEngineState,
    ) -> std::result::Result<(), String> {
        let run = &self.description.run;
        let chain = &state.chain;
        if chain.n_rods() != self.ring.rods || chain.modes() != self.ring.modes {
            return Err(format!(
                "a chain of {} rods with {} modes where the run file has {} and {}",
                chain.n_rods(),
                chain.modes(),
                self.ring.rods,
                self.ring.modes
            ));
        }
        if saved.repeat >= run.repeats {
            return Err("the repeat does not match run.repeats".into());
        }
        let curves = if saved.repeat == 0 {
            0
        } else {
            1 + run.compare.len()
        };
        let complete = saved
            .curves
            .iter()
            .all(|(_, rows)| rows.len() == run.samples);
        if saved.curves.len() != curves || !complete {
            return Err("the averaged curves do not match the repeats done".into());
        }
        let every = every.is_none_or(|k| (1..=1_000_000).contains(&k));
        if !(every && saved.chain_seconds.is_finite() && saved.chain_seconds >= 0.0) {
            return Err("every or chain_seconds out of range".into());
        }
        Ok(())
    }

    /// Saves the run to the check-point of `dir` every `every` samples of the chain MD.
    pub fn set_checkpoints(&mut self, dir: &Path, every: Option<usize>) {
        self.checkpoint_dir = Some(dir.to_path_buf());
        self.every = every;
    }

    /// The check-point interval (kept from a resumed check-point).
    pub fn checkpoint_interval(&self) -> Option<usize> {
        self.every
    }

    /// The run file (as read).
    pub fn description(&self) -> &RingDescription {
        &self.description
    }

    pub fn ring(&self) -> &RingSetup {
        &self.ring
    }

    /// Runs every remaining repeat; false if it stopped (after a check-point) once
    /// `stop_after` samples of the chain MD were taken by this call. Between pieces of the
    /// chain MD it asks [`Progress::keep_going`] (an interruption stands where it stopped).
    pub fn run(&mut self, progress: &mut dyn Progress, stop_after: Option<usize>) -> Result<bool> {
        let clock = Instant::now();
        let result = self.run_repeats(progress, stop_after);
        self.wall_seconds += clock.elapsed().as_secs_f64();
        result
    }

    fn run_repeats(
        &mut self,
        progress: &mut dyn Progress,
        stop_after: Option<usize>,
    ) -> Result<bool> {
        let mut taken = 0;
        let repeats = self.description.run.repeats;
        while self.repeat < repeats {
            let mut chain = self.description.chain.clone();
            chain.seed = chain.seed.wrapping_add(self.repeat as u64);
            let ring = chain.ring();
            let start = ring.initial_state();
            let mut driver = match self.current.take() {
                Some(driver) => driver,
                None => {
                    let engine = engines::rod_chain(ring.chain(&start).map_err(chain_error)?);
                    let rows: Vec<Box<dyn crate::observer::Observer<1>>> =
                        vec![Box::new(EnergyRows::chain())];
                    Driver::new(Box::new(engine), rows, self.schedule())
                }
            };
            let before = driver.samples_taken();
            let until = Until {
                samples: stop_after.map(|k| before + k.saturating_sub(taken)),
                point: None,
            };
            let clock = Instant::now();
            let result = self.run_chain(&mut driver, progress, until, &clock);
            self.chain_seconds += clock.elapsed().as_secs_f64();
            taken += driver.samples_taken() - before;
            if let Err(e) = result {
                self.current = Some(driver);
                return Err(e);
            }
            if stop_after.is_some_and(|k| taken >= k) || !driver.is_complete() {
                let seconds = self.chain_seconds;
                self.write_checkpoint(&mut driver, seconds)?;
                self.current = Some(driver);
                return Ok(false);
            }
            let mut runs = vec![("rod-chain MD".to_string(), rows_of(&driver))];
            for &law in &self.description.run.compare {
                let rows = ed_mc(self.compare_law(law)?, &ring, &start, self.schedule())?;
                runs.push((format!("ED + MC, {}", law.name()), rows));
            }
            accumulate(&mut self.curves, runs, repeats);
            self.repeat += 1;
        }
        Ok(true)
    }

    /// The chain MD of the repeat in progress through the driver, with check-points every
    /// `every` samples of the repeat.
    fn run_chain(
        &self,
        driver: &mut Driver<1>,
        progress: &mut dyn Progress,
        until: Until,
        clock: &Instant,
    ) -> Result<()> {
        let preamble = || self.records(self.chain_seconds + clock.elapsed().as_secs_f64());
        let file = self
            .checkpoint_dir
            .as_ref()
            .map(|d| d.join(checkpoint::FILE_NAME));
        let saving = file.as_deref().zip(self.every).map(|(file, every)| Saving {
            file,
            format: FORMAT,
            every,
            after_seconds: 0.0,
            write: true,
            preamble: &preamble,
        });
        driver.go(progress, until, saving.as_ref())
    }

    /// The run's own records of a check-point.
    fn records(&self, chain_seconds: f64) -> Result<RecordsOut> {
        let mut records = RecordsOut::new();
        records.push("description", &self.description)?;
        records.push("every", &self.every)?;
        records.push("repeat", &self.repeat)?;
        records.push("curves", &self.curves)?;
        records.push("chain_seconds", &chain_seconds)?;
        Ok(records)
    }

    fn write_checkpoint(&self, driver: &mut Driver<1>, chain_seconds: f64) -> Result<()> {
        let Some(dir) = &self.checkpoint_dir else {
            return Ok(());
        };
        let records = self.records(chain_seconds)?;
        driver.write_checkpoint(&dir.join(checkpoint::FILE_NAME), FORMAT, records, true)
    }

    /// The stochastic law of an ED + MC comparison.
    fn compare_law(&self, law: CompareLaw) -> Result<Box<dyn Restitution>> {
        let modes = u32::try_from(self.ring.modes)
            .map_err(|_| Error::out_of_range("chain.modes", self.ring.modes, "at most 2^32 - 1"))?;
        match law {
            CompareLaw::Glauber => Ok(Box::new(
                Glauber::new(modes).map_err(|e| Error::law("chain.modes", e))?,
            )),
            CompareLaw::Tabulated => {
                let path = self.description.run.table.as_ref().ok_or_else(|| {
                    Error::input("run.table", "missing for compare = \"tabulated\"")
                })?;
                crate::law::tabulated(path, modes, "run.table")
            }
        }
    }

    /// Writes `timeseries.csv` (the chain MD), `ed_mc_<law>.csv`, `cooling.png` and
    /// `summary.json` into `dir`.
    pub fn write(&self, dir: &Path) -> Result<()> {
        let Some((_, chain_rows)) = self.curves.first() else {
            return Err(Error::input("run.repeats", "no repeat has finished"));
        };
        write_rows(&dir.join("timeseries.csv"), chain_rows)?;
        for (law, (_, rows)) in self.description.run.compare.iter().zip(&self.curves[1..]) {
            write_rows(&dir.join(format!("ed_mc_{}.csv", law.name())), rows)?;
        }
        let share = equipartition_share(self.ring.rods, self.ring.modes);
        let equilibrium: Vec<(f64, f64)> = chain_rows
            .iter()
            .map(|r| (r.time, share * r.total_energy))
            .collect();
        plot_cooling(&dir.join("cooling.png"), &self.curves, equilibrium)?;
        let (Some(&first), last) = (chain_rows.first(), chain_rows.last().copied()) else {
            return Err(Error::input("run.samples", "no sample was taken"));
        };
        let summary = serde_json::json!({
            "parameters": self.description,
            "perimeter": self.ring.perimeter(),
            "wall_seconds_chain": self.chain_seconds,
            "wall_seconds": self.wall_seconds,
            "equipartition_translational_energy": share * first.total_energy,
            "final": last,
            "energy_drift": last.map(|r| (r.total_energy - first.total_energy) / first.total_energy),
            "compare_final": self.curves[1..].iter().map(|(n, r)| (n.clone(), r.last().copied())).collect::<Vec<_>>(),
        });
        write_json_file(&dir.join("summary.json"), &summary)
    }

    /// The curves summed over the finished repeats: the chain MD first, then ED + MC with
    /// each compared law (named).
    pub fn curves(&self) -> &[(String, Vec<EnergyRow>)] {
        &self.curves
    }

    /// E_tr of equipartition with the modes, per unit of total energy.
    pub fn equipartition_share(&self) -> f64 {
        equipartition_share(self.ring.rods, self.ring.modes)
    }

    /// Seconds of the chain MD over all repeats (resumed runs included).
    pub fn chain_seconds(&self) -> f64 {
        self.chain_seconds
    }
}

/// The rows the chain MD of `driver` took.
fn rows_of(driver: &Driver<1>) -> Vec<EnergyRow> {
    driver
        .observer::<EnergyRows>()
        .map_or_else(Vec::new, |r| r.rows.clone())
}

/// Giese's ED + MC: the same rods as hard rods on the ring, each with a bath of `modes`
/// modes at the chain's initial mode temperature, through the driver at the samples of
/// `schedule`.
fn ed_mc(
    law: Box<dyn Restitution>,
    ring: &RingSetup,
    start: &RingState,
    schedule: Schedule,
) -> Result<Vec<EnergyRow>> {
    let masses = ring.masses();
    let lengths = ring.rod_lengths();
    let system = gas::System::<1> {
        sides: [ring.perimeter()],
        positions: start.positions.iter().map(|x| [*x]).collect(),
        velocities: start.velocities.iter().map(|v| [*v]).collect(),
        radii: lengths.iter().map(|l| 0.5 * l).collect(),
        masses: masses.clone(),
    };
    let setup = Setup {
        law,
        packing_fraction: 0.0,
        seed: ring.seed,
        baths: Some(BathState {
            temperatures: vec![ring.bath_temperature; lengths.len()],
            seed: ring.seed,
            draws: 0,
        }),
    };
    let engine = engines::build(&EngineSpec::EventDriven, system, setup)
        .map_err(|e| Error::input("chain", e))?;
    let rows = EnergyRows::baths(ring.modes, masses);
    let mut driver = Driver::new(engine, vec![Box::new(rows)], schedule);
    driver.go(&mut (), Until::default(), None)?;
    Ok(driver
        .observer::<EnergyRows>()
        .map_or_else(Vec::new, |r| r.rows.clone()))
}

/// Adds `runs` (one row list per curve) into `sums` with weight 1/`repeats`.
fn accumulate(sums: &mut Vec<Curve>, runs: Vec<Curve>, repeats: usize) {
    let w = 1.0 / repeats as f64;
    if sums.is_empty() {
        for (name, rows) in &runs {
            let zero = rows
                .iter()
                .map(|r| EnergyRow {
                    time: r.time,
                    ..EnergyRow::default()
                })
                .collect();
            sums.push((name.clone(), zero));
        }
    }
    for ((_, sum), (_, rows)) in sums.iter_mut().zip(runs) {
        for (s, r) in sum.iter_mut().zip(rows) {
            s.collisions_per_particle += w * r.collisions_per_particle;
            s.translational_energy += w * r.translational_energy;
            s.bath_energy += w * r.bath_energy;
            s.total_energy += w * r.total_energy;
        }
    }
}

fn write_rows(path: &Path, rows: &[EnergyRow]) -> Result<()> {
    let cells = rows.iter().map(|r| {
        [
            r.time,
            r.collisions_per_particle,
            r.translational_energy,
            r.bath_energy,
            r.total_energy,
        ]
        .map(number)
        .to_vec()
    });
    write_csv_file(path, &ENERGY_HEADER, cells)
}

fn plot_cooling(path: &Path, curves: &[Curve], equilibrium: Vec<(f64, f64)>) -> Result<()> {
    let mut series: Vec<(String, Vec<(f64, f64)>)> = curves
        .iter()
        .map(|(name, rows)| {
            let points = rows.iter().map(|r| (r.time, r.translational_energy));
            (name.clone(), points.collect())
        })
        .collect();
    series.push((
        "equilibrium (equipartition with the modes)".into(),
        equilibrium,
    ));
    let axes = Axes {
        title: "translational energy of the rods",
        x: "time",
        y: "E_tr (centre-of-mass frame)",
        log_x: false,
        log_y: true,
    };
    plot::lines(path, axes, &series)
}
