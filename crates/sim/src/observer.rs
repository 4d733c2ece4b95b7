//! Observers: what a run records at the stops of its schedule. Each observer looks at the
//! engine through [`gas::Engine`] only, owns its name, its records (saved in check-points
//! under its name), their check on resume and its files. A new observable is one type
//! implementing [`Observer`] and one line where a run's list is built
//! ([`for_plan`]); the driver ([`crate::driver`]) runs every observer of the list alike.

use crate::error::{Error, Result};
use crate::output::{number, write_csv_file};
use crate::schedule::{Measure, Schedule, Target};
use crate::validate::Plan;
use gas::observe::{pressure, sonine_a2, temperature, velocity_histogram};
use gas::Engine;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use std::any::Any;
use std::path::Path;

/// Something recorded at the stops of the schedule.
pub trait Observer<const D: usize>: Send {
    /// The name of its record in check-points, unique in a run (not `driver`, nor a key
    /// of the run's own records such as `description` and `every`).
    fn name(&self) -> &'static str;

    /// Looks at the engine at `target` (every stop; the observer picks its own).
    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<D>) -> Result<()>;

    /// What it has recorded so far, as JSON for a check-point ([`record_of`]).
    fn record(&self) -> Result<Box<RawValue>>;

    /// Takes `record` from a check-point in place of its records, after checking it
    /// against the first `done` targets of `schedule` (those observed) and the engine
    /// where it stands; the error says what does not match.
    fn resume(
        &mut self,
        record: &RawValue,
        schedule: &Schedule,
        done: usize,
        engine: &mut dyn Engine<D>,
    ) -> std::result::Result<(), String>;

    /// Fails (naming the key that asked for it) if it cannot observe the rest of the run:
    /// files to write during the run and no directory for them.
    fn check_ready(&self) -> Result<()> {
        Ok(())
    }

    /// The directory files are written to during the run, and whether this process writes
    /// them (rank 0 of a run on several ranks; the others keep the same records).
    fn set_output(&mut self, _dir: &Path, _writer: bool) {}

    /// A few words for the progress bar after a sample (e.g. the temperature).
    fn note(&self) -> Option<String> {
        None
    }

    /// Writes its files into `dir` at the end of a run (or of a part of it).
    fn write(&self, dir: &Path) -> Result<()>;

    /// The observer itself, for reading its records (`Simulation::samples`).
    fn as_any(&self) -> &dyn Any;
}

/// `records` as the JSON of a check-point.
pub fn record_of<T: Serialize>(records: &T) -> Result<Box<RawValue>> {
    serde_json::value::to_raw_value(records).map_err(|e| Error::Numerical {
        key: "check-point".into(),
        message: e.to_string(),
    })
}

/// Checks that a check-point's `rows` of `what` are one per sample the schedule has taken
/// in its first `done` targets.
pub fn one_row_per_sample(
    rows: usize,
    schedule: &Schedule,
    done: usize,
    what: &str,
) -> std::result::Result<(), String> {
    let due = schedule.samples_before(done);
    if rows != due {
        return Err(format!(
            "{rows} {what} rows where the schedule has taken {due} samples"
        ));
    }
    Ok(())
}

/// The records of a check-point as `T`.
pub fn records_from<T: DeserializeOwned>(record: &RawValue) -> std::result::Result<T, String> {
    serde_json::from_str(record.get()).map_err(|e| e.to_string())
}

/// The observers of a run as its plan asks: the time series always, the velocity
/// histograms with `run.histogram_at`, the observers of space with `[output]`, the
/// per-species series of a mixture. A new observer adds its line here.
pub fn for_plan<const D: usize>(plan: &Plan) -> Vec<Box<dyn Observer<D>>> {
    let run = &plan.description.run;
    let mut list: Vec<Box<dyn Observer<D>>> = vec![Box::new(TimeSeries::default())];
    if run.histogram_at.as_ref().is_some_and(|at| !at.is_empty()) {
        let bins = run.histogram_bins.unwrap_or(HISTOGRAM_BINS);
        list.push(Box::new(VelocityHistograms::new(bins)));
    }
    let space = crate::space::SpaceObserver::new(plan);
    if space.is_on() {
        list.push(Box::new(space));
    }
    if let Some(species) = crate::species::SpeciesSeries::of(plan) {
        list.push(Box::new(species));
    }
    if let Some(walls) = crate::walls::WallSeries::of(plan) {
        list.push(Box::new(walls));
    }
    if let Some(profiles) = crate::profiles::ProfileSeries::of(plan) {
        list.push(Box::new(profiles));
    }
    if let Some(pressure) = crate::rheology::PressureSeries::of(plan) {
        list.push(Box::new(pressure));
    }
    if let Some(msd) = crate::diffusion::MsdSeries::of(plan) {
        list.push(Box::new(msd));
    }
    list
}

/// One row of `timeseries.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sample {
    pub time: f64,
    pub collisions_per_particle: f64,
    /// Granular temperature T = <m c^2> / D.
    pub temperature: f64,
    /// Sonine coefficient a2 ([`gas::observe::sonine_a2`]).
    pub a2: f64,
    /// Energy dissipated since the start.
    pub energy_lost: f64,
    /// Kinetic plus collisional pressure over the interval since the previous sample
    /// ([`gas::observe::pressure`]).
    pub pressure: f64,
    pub events: u64,
    /// Stochastic law: mean bath temperature of the particles.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bath_temperature: Option<f64>,
    /// Rough particles: T_rot = <I w^2> / d_rot ([`gas::rotation::Rotation::temperature`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotational_temperature: Option<f64>,
}

/// The header of `timeseries.csv` (`bath_temperature` is appended for a stochastic law,
/// `rotational_temperature` for rough particles).
pub const TIMESERIES_HEADER: [&str; 7] = [
    "time",
    "collisions_per_particle",
    "temperature",
    "a2",
    "energy_lost",
    "pressure",
    "events",
];

/// The time series: one [`Sample`] at every sample target.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeSeries {
    pub samples: Vec<Sample>,
    /// (time, virial counter) at the last sample: the pressure's interval starts there.
    pub last_virial: (f64, f64),
}

impl<const D: usize> Observer<D> for TimeSeries {
    fn name(&self) -> &'static str {
        "timeseries"
    }

    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<D>) -> Result<()> {
        if target.sample.is_none() {
            return Ok(());
        }
        let counters = engine.counters();
        let (time, collisions_per_particle) = (engine.time(), engine.collisions_per_particle());
        let (weight, particles) = (engine.weight(), engine.particles());
        let bath_temperature = engine.bath_temperatures().map(mean);
        let rotational_temperature = rotational_temperature(engine);
        let statistics = engine.velocity_statistics().unwrap_or_else(|| {
            let system = engine.system();
            gas::engine::VelocityStatistics {
                temperature: temperature(system),
                a2: sonine_a2(system),
                volume: system.volume(),
            }
        });
        let t = statistics.temperature;
        let (last_time, last_virial) = self.last_virial;
        self.samples.push(Sample {
            time,
            collisions_per_particle,
            temperature: t,
            a2: statistics.a2,
            energy_lost: counters.energy_lost,
            pressure: pressure::<D>(
                particles,
                statistics.volume,
                t,
                weight,
                counters.virial - last_virial,
                time - last_time,
            ),
            events: counters.events,
            bath_temperature,
            rotational_temperature,
        });
        self.last_virial = (time, counters.virial);
        Ok(())
    }

    fn record(&self) -> Result<Box<RawValue>> {
        record_of(self)
    }

    /// One sample per sample target done, in order, each where its target put it, and the
    /// engine at or after the last one (exactly there if the run is complete).
    fn resume(
        &mut self,
        record: &RawValue,
        schedule: &Schedule,
        done: usize,
        engine: &mut dyn Engine<D>,
    ) -> std::result::Result<(), String> {
        let records: TimeSeries = records_from(record)?;
        let due = schedule.samples_before(done);
        if records.samples.len() != due {
            return Err(format!(
                "{} samples where the schedule has taken {due}",
                records.samples.len()
            ));
        }
        records.check_samples(schedule)?;
        let (time, events) = (engine.time(), engine.counters().events);
        records.check_last_virial(engine.counters().virial)?;
        if let Some(last) = records.samples.last() {
            let complete = done == schedule.targets.len();
            let behind = time < last.time || events < last.events;
            let beyond = complete && (time != last.time || events != last.events);
            if behind || beyond {
                return Err(
                    "the engine does not stand at the last sample or before the next one".into(),
                );
            }
        }
        *self = records;
        Ok(())
    }

    fn note(&self) -> Option<String> {
        let temperature = self.samples.last()?.temperature;
        Some(format!("T = {temperature:.4e}"))
    }

    fn write(&self, dir: &Path) -> Result<()> {
        self.write_csv(&dir.join("timeseries.csv"))
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

impl TimeSeries {
    /// Checks the samples against the schedule: from the start onwards in time, collisions
    /// and events, and (a schedule in time) each at the time of its target.
    fn check_samples(&self, schedule: &Schedule) -> std::result::Result<(), String> {
        let mut previous = (0.0, 0.0, 0);
        let mut targets = schedule.targets.iter().filter(|t| t.sample.is_some());
        for (i, sample) in self.samples.iter().enumerate() {
            let now = (sample.time, sample.collisions_per_particle, sample.events);
            let ordered = now.0 >= previous.0 && now.1 >= previous.1 && now.2 >= previous.2;
            let on_time = match (schedule.measure, targets.next()) {
                (Measure::Time, Some(target)) => sample.time == target.value,
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

    /// The pressure's interval starts at the last sample (time 0 before the first), with a
    /// finite virial counter of at most twice the engine's now in size (it grows, but for
    /// the soft contacts' short attractive ends): a forged one would give an infinite
    /// pressure.
    fn check_last_virial(&self, virial_now: f64) -> std::result::Result<(), String> {
        let (time, virial) = self.last_virial;
        let start = self.samples.last().map_or(0.0, |s| s.time);
        if time == start && virial.is_finite() && virial.abs() <= 2.0 * virial_now.abs() {
            Ok(())
        } else {
            Err(format!(
                "the pressure's interval starts at time {time} with the virial {virial}, \
                 where the last sample (time {start}) and the engine's virial {virial_now} \
                 allow neither"
            ))
        }
    }

    /// Writes `timeseries.csv`.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let baths = self.samples.iter().any(|s| s.bath_temperature.is_some());
        let mut header = TIMESERIES_HEADER.to_vec();
        if baths {
            header.push("bath_temperature");
        }
        let rough = self
            .samples
            .iter()
            .any(|s| s.rotational_temperature.is_some());
        if rough {
            header.push("rotational_temperature");
        }
        let rows = self.samples.iter().map(|s| {
            let mut row: Vec<String> = [
                s.time,
                s.collisions_per_particle,
                s.temperature,
                s.a2,
                s.energy_lost,
                s.pressure,
            ]
            .map(number)
            .to_vec();
            row.push(s.events.to_string());
            row.extend(s.bath_temperature.map(number));
            row.extend(s.rotational_temperature.map(number));
            row
        });
        write_csv_file(path, &header, rows)
    }
}

/// The rotational temperature of an engine's rough particles; None for smooth ones.
pub fn rotational_temperature<const D: usize>(engine: &mut dyn Engine<D>) -> Option<f64> {
    engine.rotation()?;
    let system = engine.system().clone();
    Some(engine.rotation()?.temperature(&system, None))
}

fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len().max(1) as f64
}

/// Default number of bins of a velocity histogram.
pub const HISTOGRAM_BINS: usize = 60;
/// Velocity histograms cover the scaled components -C_MAX <= c < C_MAX.
pub const C_MAX: f64 = 5.0;

/// A velocity histogram taken at one of `run.histogram_at`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Histogram {
    pub target: f64,
    pub time: f64,
    pub collisions_per_particle: f64,
    /// (bin centre, density) of [`gas::observe::velocity_histogram`].
    pub bins: Vec<(f64, f64)>,
}

/// The velocity histograms at the histogram targets.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VelocityHistograms {
    pub bins: usize,
    pub histograms: Vec<Histogram>,
}

impl VelocityHistograms {
    pub fn new(bins: usize) -> Self {
        VelocityHistograms {
            bins,
            histograms: Vec::new(),
        }
    }

    /// Writes `velocity_histograms.csv`: one row per bin of every histogram, with the
    /// Maxwellian exp(-c^2) / sqrt(pi) at the bin centre.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let header = [
            "target",
            "time",
            "collisions_per_particle",
            "c",
            "density",
            "maxwellian",
        ];
        let rows = self.histograms.iter().flat_map(|h| {
            h.bins.iter().map(move |&(c, density)| {
                let maxwellian = (-c * c).exp() / std::f64::consts::PI.sqrt();
                [
                    h.target,
                    h.time,
                    h.collisions_per_particle,
                    c,
                    density,
                    maxwellian,
                ]
                .map(number)
                .to_vec()
            })
        });
        write_csv_file(path, &header, rows)
    }
}

impl<const D: usize> Observer<D> for VelocityHistograms {
    fn name(&self) -> &'static str {
        "histograms"
    }

    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<D>) -> Result<()> {
        if !target.histogram {
            return Ok(());
        }
        let (time, collisions_per_particle) = (engine.time(), engine.collisions_per_particle());
        self.histograms.push(Histogram {
            target: target.value,
            time,
            collisions_per_particle,
            bins: velocity_histogram(engine.system(), self.bins, C_MAX),
        });
        Ok(())
    }

    fn record(&self) -> Result<Box<RawValue>> {
        record_of(self)
    }

    /// One histogram of the run's bins at each histogram target done.
    fn resume(
        &mut self,
        record: &RawValue,
        schedule: &Schedule,
        done: usize,
        _engine: &mut dyn Engine<D>,
    ) -> std::result::Result<(), String> {
        let records: VelocityHistograms = records_from(record)?;
        let due: Vec<f64> = schedule.targets[..done]
            .iter()
            .filter(|t| t.histogram)
            .map(|t| t.value)
            .collect();
        let taken: Vec<f64> = records.histograms.iter().map(|h| h.target).collect();
        let wrong_bins = records.histograms.iter().any(|h| h.bins.len() != self.bins);
        if due != taken || records.bins != self.bins || wrong_bins {
            return Err("the velocity histograms do not match run.histogram_at and bins".into());
        }
        *self = records;
        Ok(())
    }

    fn write(&self, dir: &Path) -> Result<()> {
        self.write_csv(&dir.join("velocity_histograms.csv"))
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}
