//! Profiles along an axis (`[output] profiles = { axis, bins }`): at every sample the gas
//! cut into `bins` slabs normal to the axis ([`gas::profile`]), one row of
//! `profiles.csv` per slab: density, packing fraction, temperature and its components,
//! mean velocity. Cells without a value are empty: the components a dimension lacks, the
//! velocity of an empty slab, the temperatures of a slab with fewer than two particles.
//! Rough particles append [`ROTATION_COLUMNS`]: each slab's rotational temperature about its
//! mean angular velocity, and that mean ([`gas::profile::rotation_profile`]).

use crate::description::ProfilesOutput;
use crate::error::Result;
use crate::observer::{record_of, records_from, Observer};
use crate::output::{number, write_csv_file};
use crate::schedule::{Schedule, Target};
use crate::validate::Plan;
use gas::Engine;
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use std::any::Any;
use std::path::Path;

/// The header of `profiles.csv` (a contract).
pub const PROFILES_HEADER: [&str; 12] = [
    "time",
    "collisions_per_particle",
    "position",
    "density",
    "packing_fraction",
    "temperature",
    "temperature_x",
    "temperature_y",
    "temperature_z",
    "velocity_x",
    "velocity_y",
    "velocity_z",
];

/// The columns rough particles append to `profiles.csv` (a contract).
pub const ROTATION_COLUMNS: [&str; 4] = [
    "rotational_temperature",
    "angular_velocity_x",
    "angular_velocity_y",
    "angular_velocity_z",
];

/// One row of `profiles.csv`: one slab at one sample.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProfileRow {
    pub time: f64,
    pub collisions_per_particle: f64,
    /// The slab's centre along the axis.
    pub position: f64,
    /// Particles per unit volume (times `particle_weight`).
    pub density: f64,
    pub packing_fraction: f64,
    /// Granular temperature (None below two particles).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature: Option<f64>,
    /// The temperature of each of the D components.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperatures: Option<Vec<f64>>,
    /// The slab's centre-of-mass velocity, D components (None when empty).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub velocity: Option<Vec<f64>>,
    /// Rough particles: the rotational temperature about the slab's mean spin (None below
    /// two particles).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotational_temperature: Option<f64>,
    /// Rough particles: the slab's mean angular velocity, 3 components (None when empty).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angular_velocity: Option<Vec<f64>>,
}

impl ProfileRow {
    /// Component `k` of the temperature (None beyond the dimension or without a value).
    pub fn temperature_component(&self, k: usize) -> Option<f64> {
        self.temperatures.as_ref().and_then(|t| t.get(k).copied())
    }

    /// Component `k` of the velocity (None beyond the dimension or without a value).
    pub fn velocity_component(&self, k: usize) -> Option<f64> {
        self.velocity.as_ref().and_then(|v| v.get(k).copied())
    }
}

/// The profiles of a run with `output.profiles`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProfileSeries {
    pub axis: usize,
    pub bins: usize,
    /// Physical particles per simulated one.
    pub weight: f64,
    /// `bins` rows per sample, in sample order.
    pub rows: Vec<ProfileRow>,
    /// Whether the particles rotate ([`ROTATION_COLUMNS`]).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub rough: bool,
}

impl ProfileSeries {
    /// The series `output.profiles` asks for; None without it.
    pub fn of(plan: &Plan) -> Option<Self> {
        let output = plan.description.output.as_ref()?;
        output
            .profiles
            .map(|ProfilesOutput { axis, bins }| ProfileSeries {
                axis: axis.index(),
                bins,
                weight: plan.particle_weight,
                rows: Vec::new(),
                rough: plan.rough.is_some(),
            })
    }

    /// Writes `profiles.csv`.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let cell = |x: Option<f64>| x.map(number).unwrap_or_default();
        let rows = self.rows.iter().map(|r| {
            let mut row = vec![
                number(r.time),
                number(r.collisions_per_particle),
                number(r.position),
                number(r.density),
                number(r.packing_fraction),
                cell(r.temperature),
            ];
            row.extend((0..3).map(|k| cell(r.temperature_component(k))));
            row.extend((0..3).map(|k| cell(r.velocity_component(k))));
            if self.rough {
                row.push(cell(r.rotational_temperature));
                let spin = |k: usize| r.angular_velocity.as_ref().map(|w| w[k]);
                row.extend((0..3).map(|k| cell(spin(k))));
            }
            row
        });
        let mut header = PROFILES_HEADER.to_vec();
        if self.rough {
            header.extend(ROTATION_COLUMNS);
        }
        write_csv_file(path, &header, rows)
    }
}

impl<const D: usize> Observer<D> for ProfileSeries {
    fn name(&self) -> &'static str {
        "profiles"
    }

    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<D>) -> Result<()> {
        if target.sample.is_none() {
            return Ok(());
        }
        let (time, cpp) = (engine.time(), engine.collisions_per_particle());
        let slabs = gas::profile::profile(engine.system(), self.axis, self.bins, self.weight);
        let spins = match self.rough {
            true => {
                let system = engine.system().clone();
                engine.rotation().map_or_else(Vec::new, |rotation| {
                    gas::profile::rotation_profile(&system, rotation, self.axis, self.bins)
                })
            }
            false => Vec::new(),
        };
        let spin = |b: usize| spins.get(b).copied();
        self.rows
            .extend(slabs.iter().enumerate().map(|(b, s)| ProfileRow {
                time,
                collisions_per_particle: cpp,
                position: s.position,
                density: s.density,
                packing_fraction: s.packing_fraction,
                temperature: s.temperature(),
                temperatures: s.temperature.map(|t| t.to_vec()),
                velocity: s.velocity.map(|v| v.to_vec()),
                rotational_temperature: spin(b).and_then(|x| x.rotational_temperature),
                angular_velocity: spin(b).and_then(|x| x.angular_velocity.map(|w| w.to_vec())),
            }));
        Ok(())
    }

    fn record(&self) -> Result<Box<RawValue>> {
        record_of(self)
    }

    fn resume(
        &mut self,
        record: &RawValue,
        schedule: &Schedule,
        done: usize,
        _engine: &mut dyn Engine<D>,
    ) -> std::result::Result<(), String> {
        let records: ProfileSeries = records_from(record)?;
        if (records.axis, records.bins, records.weight, records.rough)
            != (self.axis, self.bins, self.weight, self.rough)
        {
            return Err("the profile records do not match output.profiles".into());
        }
        let samples = schedule.samples_before(done);
        if records.rows.len() != samples * self.bins {
            return Err(format!(
                "{} profile rows for {samples} samples of {} slabs",
                records.rows.len(),
                self.bins
            ));
        }
        let sized = |v: &Option<Vec<f64>>| v.as_ref().is_none_or(|v| v.len() == D);
        let spun = |v: &Option<Vec<f64>>| v.as_ref().is_none_or(|v| v.len() == 3);
        if !records
            .rows
            .iter()
            .all(|r| sized(&r.temperatures) && sized(&r.velocity) && spun(&r.angular_velocity))
        {
            return Err(format!("profile rows with components other than {D}"));
        }
        *self = records;
        Ok(())
    }

    fn write(&self, dir: &Path) -> Result<()> {
        self.write_csv(&dir.join("profiles.csv"))
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}
