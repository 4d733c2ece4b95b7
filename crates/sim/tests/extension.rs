//! The run driver is open for extension: an engine and an observer defined here, outside
//! the library crates, run through the same driver as `haff run` (`sim::driver::Driver`),
//! next to a built-in observer (the time series), with check-points written during the
//! run, and a run stopped, saved and resumed from its file continues bit for bit — without
//! a line of `crates/sim/src` knowing them.
//!
//! The engine is an ideal gas under a Langevin thermostat (an Ornstein–Uhlenbeck process
//! per velocity component, exact over each step: v <- v e^(-g dt) + sqrt(T/m (1 - e^(-2 g
//! dt))) xi), its random numbers drawn from a stream per step so that its state is plain
//! data. Its physics is checked against the exact relaxation of the temperature,
//! T(t) = T_bath + (T0 - T_bath) e^(-2 g t), within the statistical error of N D
//! independent components.

use gas::{Checkpoint, Counters, Engine, System};
use rand::SeedableRng;
use rand_distr::{Distribution, StandardNormal};
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use sim::checkpoint::{self, Format, Records, RecordsOut};
use sim::driver::{Driver, Saving, Until};
use sim::observer::{record_of, records_from, Observer, TimeSeries};
use sim::schedule::{Measure, Schedule, Target};
use std::any::Any;
use std::path::Path;

/// The Langevin gas: particles streaming freely in a periodic box, their velocities
/// relaxing towards the bath.
struct LangevinGas {
    state: LangevinState,
    system: System<2>,
}

/// Everything the Langevin gas needs to continue.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct LangevinState {
    positions: Vec<[f64; 2]>,
    velocities: Vec<[f64; 2]>,
    length: f64,
    time: f64,
    steps: u64,
    step: f64,
    friction: f64,
    bath: f64,
    seed: u64,
}

impl LangevinGas {
    fn new(particles: usize, length: f64, seed: u64) -> Self {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
        let mut draw = || -> f64 { StandardNormal.sample(&mut rng) };
        let positions = (0..particles)
            .map(|_| [length * draw().abs().fract(), length * draw().abs().fract()])
            .collect();
        // Start cold: T0 = 0.25 (unit masses), the bath at 1.
        let velocities = (0..particles)
            .map(|_| [0.5 * draw(), 0.5 * draw()])
            .collect();
        Self::from(LangevinState {
            positions,
            velocities,
            length,
            time: 0.0,
            steps: 0,
            step: 0.01,
            friction: 2.0,
            bath: 1.0,
            seed,
        })
    }

    fn from(state: LangevinState) -> Self {
        LangevinGas {
            state,
            system: System {
                sides: [0.0; 2],
                positions: vec![],
                velocities: vec![],
                radii: vec![],
                masses: vec![],
            },
        }
    }

    /// One step of `dt`: stream, then the exact Ornstein–Uhlenbeck update of every
    /// velocity with the normal deviates of this step's stream.
    fn step(&mut self, dt: f64) {
        let s = &mut self.state;
        let decay = (-s.friction * dt).exp();
        let spread = (s.bath * (1.0 - decay * decay)).sqrt();
        let mut rng = rand_pcg::Pcg64::seed_from_u64(s.seed ^ (s.steps + 1) << 20);
        for (x, v) in s.positions.iter_mut().zip(&mut s.velocities) {
            for k in 0..2 {
                x[k] = (x[k] + v[k] * dt).rem_euclid(s.length);
                let xi: f64 = StandardNormal.sample(&mut rng);
                v[k] = v[k] * decay + spread * xi;
            }
        }
        s.steps += 1;
    }

    /// Half a collision per particle per step, so that a step is one "collision" per
    /// particle for the driver's count.
    fn collisions(&self) -> u64 {
        self.state.steps * self.state.positions.len() as u64 / 2
    }
}

impl Engine<2> for LangevinGas {
    fn run_until(&mut self, t: f64) {
        self.run_paused(t, u64::MAX, u64::MAX);
    }

    fn run_collisions(&mut self, collisions: u64) {
        let target = self.collisions() + collisions;
        self.run_paused(f64::INFINITY, target, u64::MAX);
    }

    /// Steps until the time reaches `end` (the last one shortened to end there, as DSMC
    /// does) or the count reaches `collisions`, pausing at the step where it reaches
    /// `pause`: the steps do not depend on the pauses.
    fn run_paused(&mut self, end: f64, collisions: u64, pause: u64) {
        while self.state.time < end && self.collisions() < collisions.min(pause) {
            let dt = self.state.step;
            if self.state.time + dt >= end {
                self.step(end - self.state.time);
                self.state.time = end;
            } else {
                self.step(dt);
                self.state.time += dt;
            }
        }
    }

    fn time(&self) -> f64 {
        self.state.time
    }

    fn counters(&self) -> Counters {
        Counters {
            collisions: self.collisions(),
            events: self.state.steps,
            ..Counters::default()
        }
    }

    fn particles(&self) -> usize {
        self.state.positions.len()
    }

    fn system(&mut self) -> &System<2> {
        let n = self.state.positions.len();
        self.system = System {
            sides: [self.state.length; 2],
            positions: self.state.positions.clone(),
            velocities: self.state.velocities.clone(),
            radii: vec![0.0; n],
            masses: vec![1.0; n],
        };
        &self.system
    }

    fn memory_bytes(&self) -> usize {
        self.state.positions.len() * 32
    }
}

impl Checkpoint<2> for LangevinGas {
    type State = LangevinState;
    type Needs = ();

    fn save(&mut self) -> LangevinState {
        self.state.clone()
    }

    fn restore(state: LangevinState, _needs: ()) -> gas::Result<Self> {
        let finite = state.velocities.iter().flatten().all(|v| v.is_finite());
        if !finite || state.positions.len() != state.velocities.len() {
            return Err(gas::Error::LengthMismatch {
                what: "positions and velocities".into(),
            });
        }
        Ok(LangevinGas::from(state))
    }
}

/// An observer of this test: the largest speed at every sample, written to `speeds.csv`.
#[derive(Debug, Default, Serialize, Deserialize)]
struct FastestSpeed {
    rows: Vec<(f64, f64)>,
}

impl Observer<2> for FastestSpeed {
    fn name(&self) -> &'static str {
        "fastest"
    }

    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<2>) -> sim::Result<()> {
        if target.sample.is_some() {
            let time = engine.time();
            let fastest = engine
                .system()
                .velocities
                .iter()
                .map(|v| v[0].hypot(v[1]))
                .fold(0.0, f64::max);
            self.rows.push((time, fastest));
        }
        Ok(())
    }

    fn record(&self) -> sim::Result<Box<RawValue>> {
        record_of(&self.rows)
    }

    fn resume(
        &mut self,
        record: &RawValue,
        schedule: &Schedule,
        done: usize,
        _engine: &mut dyn Engine<2>,
    ) -> Result<(), String> {
        let rows: Vec<(f64, f64)> = records_from(record)?;
        if rows.len() != schedule.samples_before(done) {
            return Err("one row per sample".into());
        }
        self.rows = rows;
        Ok(())
    }

    fn write(&self, dir: &Path) -> sim::Result<()> {
        let rows = self
            .rows
            .iter()
            .map(|&(t, v)| vec![sim::output::number(t), sim::output::number(v)]);
        sim::output::write_csv_file(&dir.join("speeds.csv"), &["time", "fastest"], rows)
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

const FORMAT: Format = Format {
    name: "langevin-test-checkpoint",
    version: 1,
};

fn schedule() -> Schedule {
    let times: Vec<f64> = (0..=20).map(|k| 0.05 * k as f64).collect();
    Schedule::samples_at(&times, Measure::Time)
}

fn driver(engine: LangevinGas) -> Driver<2> {
    let observers: Vec<Box<dyn Observer<2>>> = vec![
        Box::new(TimeSeries::default()),
        Box::new(FastestSpeed::default()),
    ];
    Driver::new(Box::new(engine), observers, schedule())
}

/// The test's own records of a check-point (what `haff run` keeps as its description).
fn preamble() -> sim::Result<RecordsOut> {
    let mut records = RecordsOut::new();
    records.push("note", "a Langevin gas")?;
    Ok(records)
}

#[test]
fn an_engine_and_an_observer_from_outside_run_check_point_and_resume_bit_for_bit() {
    let dir = std::env::temp_dir().join(format!("haff-extension-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(checkpoint::FILE_NAME);
    let (particles, length, seed) = (4000, 50.0, 11);

    // The whole run at once.
    let mut whole = driver(LangevinGas::new(particles, length, seed));
    whole.go(&mut (), Until::default(), None).unwrap();
    assert!(whole.is_complete());

    // The same run with a check-point every 3 samples, stopped after 8 of 21.
    let mut first = driver(LangevinGas::new(particles, length, seed));
    let saving = Saving {
        file: &file,
        format: FORMAT,
        every: 3,
        after_seconds: 0.0,
        write: true,
        preamble: &preamble,
    };
    let until = Until {
        samples: Some(8),
        point: None,
    };
    first.go(&mut (), until, Some(&saving)).unwrap();
    assert_eq!(first.samples_taken(), 8);
    // The last check-point is the one after sample 6: resume from it.
    let sections = checkpoint::read_from(&file, FORMAT).unwrap();
    let mut records: Records = sections.records().unwrap();
    assert_eq!(records.take::<String>("note").unwrap(), "a Langevin gas");
    let engine = LangevinGas::restore(sections.engine().unwrap(), ()).unwrap();
    let observers: Vec<Box<dyn Observer<2>>> = vec![
        Box::new(TimeSeries::default()),
        Box::new(FastestSpeed::default()),
    ];
    let mut resumed =
        Driver::resume(Box::new(engine), observers, schedule(), &mut records).unwrap();
    records.finish().unwrap();
    assert_eq!(resumed.samples_taken(), 6);
    resumed.go(&mut (), Until::default(), None).unwrap();

    // Bit for bit: the time series, the test's observer and the engine's state.
    let series = |d: &Driver<2>| d.observer::<TimeSeries>().unwrap().samples.clone();
    let fastest = |d: &Driver<2>| d.observer::<FastestSpeed>().unwrap().rows.clone();
    assert_eq!(series(&resumed), series(&whole));
    assert_eq!(fastest(&resumed), fastest(&whole));
    assert_eq!(resumed.engine().time(), whole.engine().time());
    assert_eq!(resumed.engine_mut().system(), whole.engine_mut().system());
    for observer in resumed.observers() {
        observer.write(&dir).unwrap();
    }
    let csv = std::fs::read_to_string(dir.join("speeds.csv")).unwrap();
    assert_eq!(csv.lines().count(), 22, "a header and 21 rows");

    // A check-point of this run is refused by the driver of another schedule (fewer
    // targets than it has done) and by `haff run`'s format.
    let sections = checkpoint::read_from(&file, FORMAT).unwrap();
    let mut records: Records = sections.records().unwrap();
    let engine = LangevinGas::restore(sections.engine().unwrap(), ()).unwrap();
    let short = Schedule::samples_at(&[0.0, 0.05, 0.1], Measure::Time);
    let observers: Vec<Box<dyn Observer<2>>> = vec![Box::new(FastestSpeed::default())];
    assert!(Driver::resume(Box::new(engine), observers, short, &mut records).is_err());
    assert!(checkpoint::read_from(&file, checkpoint::RUN).is_err());

    // The physics: T(t) = T_b + (T0 - T_b) e^(-2 g t) (unit masses), T0 = 0.25, T_b = 1,
    // g = 2. The sampled T of N D = 8000 Gaussian components has a relative standard
    // error sqrt(2 / 8000) = 1.6 %; 5 of them bound every sample.
    for sample in series(&whole).iter().skip(1) {
        let exact = 1.0 + (0.25 - 1.0) * (-4.0 * sample.time).exp();
        let tolerance = 5.0 * (2.0 / (2.0 * particles as f64)).sqrt() * exact;
        assert!(
            (sample.temperature - exact).abs() < tolerance,
            "T({}) = {} vs {exact}",
            sample.time,
            sample.temperature
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
