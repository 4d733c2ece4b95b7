//! What the walls of a container do (`[[wall]]`): at every sample, each wall's collisions,
//! the normal momentum the gas gave it and the energy it gave the gas, cumulative from the
//! start, written to `walls.csv`; `summary.json` gets `walls`: each wall's pressure and
//! energy flux per unit area over the second half of the run.

use crate::description::AXIS_NAMES;
use crate::error::Result;
use crate::observer::{record_of, records_from, Observer};
use crate::output::{number, write_csv_file};
use crate::schedule::{Schedule, Target};
use crate::validate::Plan;
use gas::walls::Side;
use gas::Engine;
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use std::any::Any;
use std::path::Path;

/// One row of `walls.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WallSample {
    pub time: f64,
    pub collisions_per_particle: f64,
    /// x, y or z.
    pub axis: String,
    pub side: Side,
    pub collisions: u64,
    /// Normal momentum given to the wall since the start (times `particle_weight`).
    pub momentum: f64,
    /// Energy the wall gave the gas since the start (negative where it took energy; times
    /// `particle_weight`).
    pub energy: f64,
}

/// The header of `walls.csv`.
pub const WALLS_HEADER: [&str; 7] = [
    "time",
    "collisions_per_particle",
    "axis",
    "side",
    "collisions",
    "momentum",
    "energy",
];

/// The walls' series of a run in a container.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WallSeries {
    /// Walls per sample.
    pub walls: usize,
    /// Physical particles per simulated one.
    pub weight: f64,
    /// The area of each wall, L^(D-1) (known from the first sample on).
    pub area: f64,
    /// In a box that is not a cube, the area of the walls of each axis, V / L_axis (empty
    /// in a cube: `area`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub areas: Vec<f64>,
    /// Rows in sample order, each sample's walls in the order of `[[wall]]`.
    pub samples: Vec<WallSample>,
}

impl WallSeries {
    /// The series of a run with `[[wall]]`; None for the periodic box.
    pub fn of(plan: &Plan) -> Option<Self> {
        (!plan.walls.is_empty()).then(|| WallSeries {
            walls: plan.walls.len(),
            weight: plan.particle_weight,
            area: 0.0,
            areas: Vec::new(),
            samples: Vec::new(),
        })
    }

    /// Writes `walls.csv`.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let rows = self.samples.iter().map(|s| {
            vec![
                number(s.time),
                number(s.collisions_per_particle),
                s.axis.clone(),
                s.side.name().to_string(),
                s.collisions.to_string(),
                number(s.momentum),
                number(s.energy),
            ]
        });
        write_csv_file(path, &WALLS_HEADER, rows)
    }
}

impl<const D: usize> Observer<D> for WallSeries {
    fn name(&self) -> &'static str {
        "walls"
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
        let records: WallSeries = records_from(record)?;
        if records.walls != self.walls || records.weight != self.weight {
            return Err("the wall records do not match [[wall]]".into());
        }
        let samples = schedule.samples_before(done);
        if records.samples.len() != samples * self.walls {
            return Err(format!(
                "{} wall rows for {samples} samples of {} walls",
                records.samples.len(),
                self.walls
            ));
        }
        *self = records;
        Ok(())
    }

    fn write(&self, dir: &Path) -> Result<()> {
        self.write_csv(&dir.join("walls.csv"))
    }

    fn as_any(&self) -> &dyn Any {
        self
    }

    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<D>) -> Result<()> {
        if target.sample.is_none() {
            return Ok(());
        }
        let Some(walls) = engine.walls() else {
            return Ok(());
        };
        let (time, per_particle) = (engine.time(), engine.collisions_per_particle());
        if self.area == 0.0 {
            // Once: taking the engine's system copies every particle.
            let system = engine.system();
            self.area = system.sides[0].powi(D as i32 - 1);
            if !system.is_cubic() {
                let volume = system.volume();
                self.areas = system.sides.iter().map(|l| volume / l).collect();
            }
        }
        for w in walls {
            self.samples.push(WallSample {
                time,
                collisions_per_particle: per_particle,
                axis: AXIS_NAMES[w.axis].to_string(),
                side: w.side,
                collisions: w.tally.collisions,
                momentum: self.weight * w.tally.momentum,
                energy: self.weight * w.tally.energy,
            });
        }
        Ok(())
    }
}

/// `summary.json`'s `walls`: per wall, the pressure (normal momentum per unit time and
/// area) and the energy flux into the gas (per unit time and area) over the second half
/// of the run (from the first sample at or after half the last sample's time), with the
/// collisions per unit time. The area of a wall is L^(D-1) in a cube, V / L_axis otherwise.
pub fn summary(series: &WallSeries) -> serde_json::Value {
    let (rows, walls) = (&series.samples, series.walls);
    let area_of = |axis: &str| {
        AXIS_NAMES
            .iter()
            .position(|a| *a == axis)
            .and_then(|k| series.areas.get(k))
            .copied()
            .unwrap_or(series.area)
    };
    let Some(last) = rows.len().checked_sub(walls).map(|i| &rows[i..]) else {
        return serde_json::Value::Null;
    };
    let end = last[0].time;
    let first = rows
        .chunks(walls)
        .find(|sample| sample[0].time >= 0.5 * end)
        .unwrap_or(last);
    let span = end - first[0].time;
    let per_wall: Vec<serde_json::Value> = first
        .iter()
        .zip(last)
        .map(|(a, b)| {
            let rate = |x: f64| if span > 0.0 { Some(x / span) } else { None };
            let area = area_of(&b.axis);
            serde_json::json!({
                "axis": b.axis,
                "side": b.side,
                "from_time": a.time,
                "to_time": b.time,
                "pressure": rate((b.momentum - a.momentum) / area),
                "energy_flux": rate((b.energy - a.energy) / area),
                "collision_rate": rate((b.collisions - a.collisions) as f64),
            })
        })
        .collect();
    serde_json::json!(per_wall)
}
