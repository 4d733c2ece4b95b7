//! Observers: what a run records at the stops of its schedule. Each observer looks at the
//! engine through [`gas::Engine`] only, keeps its records (saved in check-points) and
//! writes its own file. A new observable is a new observer.

use crate::error::Result;
use crate::output::{number, write_csv_file};
use crate::schedule::Target;
use gas::observe::{pressure, sonine_a2, temperature, velocity_histogram};
use gas::Engine;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Something recorded at the stops of the schedule.
pub trait Observer<const D: usize> {
    /// Looks at the engine at `target` (every stop; the observer picks its own).
    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<D>);
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
}

/// The header of `timeseries.csv` (`bath_temperature` is appended for a stochastic law).
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
    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<D>) {
        if target.sample.is_none() {
            return;
        }
        let counters = engine.counters();
        let (time, collisions_per_particle) = (engine.time(), engine.collisions_per_particle());
        let (weight, particles) = (engine.weight(), engine.particles());
        let bath_temperature = engine.bath_temperatures().map(mean);
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
        });
        self.last_virial = (time, counters.virial);
    }
}

impl TimeSeries {
    /// Writes `timeseries.csv`.
    pub fn write(&self, path: &Path) -> Result<()> {
        let baths = self.samples.iter().any(|s| s.bath_temperature.is_some());
        let mut header = TIMESERIES_HEADER.to_vec();
        if baths {
            header.push("bath_temperature");
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
            row
        });
        write_csv_file(path, &header, rows)
    }
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
    pub fn write(&self, path: &Path) -> Result<()> {
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
    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<D>) {
        if !target.histogram {
            return;
        }
        let (time, collisions_per_particle) = (engine.time(), engine.collisions_per_particle());
        self.histograms.push(Histogram {
            target: target.value,
            time,
            collisions_per_particle,
            bins: velocity_histogram(engine.system(), self.bins, C_MAX),
        });
    }
}
