//! The mean-square displacement (`output.msd`: `msd.csv`) and the self-diffusion
//! coefficient it gives (`summary.json`'s `self_diffusion`).
//!
//! msd(t) = < |r_i(t) - r_i(0)|^2 > over the particles, their positions unwrapped across the
//! periodic box (`gas::tail::Tracks`). In a steady state msd grows as 2 D D_s t at long
//! times (Einstein): `self_diffusion` is the least-squares slope of msd over the second half
//! of the run (from the first sample at or after half the last sample's time) over 2 D,
//! with Enskog's value for elastic spheres beside it (`gas::theory::NavierStokes`: the first
//! Sonine approximation D0 / chi; the converged Chapman–Enskog series is 1.019 times it in
//! 3D). In a cooling gas D_s falls with the temperature and the slope is an average.

use crate::error::Result;
use crate::observer::{one_row_per_sample, record_of, records_from, Observer};
use crate::output::{number, write_csv_file};
use crate::schedule::{Schedule, Target};
use crate::validate::Plan;
use gas::Engine;
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use std::any::Any;
use std::path::Path;

/// The header of `msd.csv`.
pub const MSD_HEADER: [&str; 3] = ["time", "collisions_per_particle", "msd"];

/// One row of `msd.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MsdSample {
    pub time: f64,
    pub collisions_per_particle: f64,
    pub msd: f64,
}

/// The mean-square displacement's series.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MsdSeries {
    pub samples: Vec<MsdSample>,
}

impl MsdSeries {
    /// The series of a run with `output.msd`; None otherwise.
    pub fn of(plan: &Plan) -> Option<Self> {
        plan.msd.then(Self::default)
    }

    /// Writes `msd.csv`.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let rows = self.samples.iter().map(|s| {
            vec![
                number(s.time),
                number(s.collisions_per_particle),
                number(s.msd),
            ]
        });
        write_csv_file(path, &MSD_HEADER, rows)
    }
}

impl<const D: usize> Observer<D> for MsdSeries {
    fn name(&self) -> &'static str {
        "msd"
    }

    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<D>) -> Result<()> {
        if target.sample.is_none() {
            return Ok(());
        }
        let (time, per_particle) = (engine.time(), engine.collisions_per_particle());
        let Some(displacements) = engine.displacements() else {
            return Ok(());
        };
        let n = displacements.len().max(1) as f64;
        let msd = displacements
            .iter()
            .map(|d| d.iter().map(|x| x * x).sum::<f64>())
            .sum::<f64>()
            / n;
        self.samples.push(MsdSample {
            time,
            collisions_per_particle: per_particle,
            msd,
        });
        Ok(())
    }

    fn record(&self) -> Result<Box<RawValue>> {
        record_of(self)
    }

    /// One row per sample done, finite and not negative.
    fn resume(
        &mut self,
        record: &RawValue,
        schedule: &Schedule,
        done: usize,
        _engine: &mut dyn Engine<D>,
    ) -> std::result::Result<(), String> {
        let records: MsdSeries = records_from(record)?;
        one_row_per_sample(records.samples.len(), schedule, done, "msd")?;
        if records
            .samples
            .iter()
            .any(|s| !(s.msd.is_finite() && s.msd >= 0.0))
        {
            return Err("an msd row that is not a finite number >= 0".into());
        }
        *self = records;
        Ok(())
    }

    fn write(&self, dir: &Path) -> Result<()> {
        self.write_csv(&dir.join("msd.csv"))
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// `summary.json`'s `self_diffusion` (see the module documentation); null with fewer than
/// three samples in the second half.
pub fn summary<const D: usize>(plan: &Plan, series: &MsdSeries) -> serde_json::Value {
    let rows = &series.samples;
    let Some(last) = rows.last() else {
        return serde_json::Value::Null;
    };
    let half: Vec<&MsdSample> = rows.iter().filter(|s| s.time >= 0.5 * last.time).collect();
    if half.len() < 3 {
        return serde_json::Value::Null;
    }
    let m = half.len() as f64;
    let (tm, ym) = (
        half.iter().map(|s| s.time).sum::<f64>() / m,
        half.iter().map(|s| s.msd).sum::<f64>() / m,
    );
    let stt: f64 = half.iter().map(|s| (s.time - tm).powi(2)).sum();
    let sty: f64 = half.iter().map(|s| (s.time - tm) * (s.msd - ym)).sum();
    let slope = sty / stt;
    let mut out = serde_json::json!({
        "from_time": half[0].time,
        "to_time": last.time,
        "coefficient": slope / (2.0 * D as f64),
    });
    let s = &plan.description.system;
    if plan.species.len() == 1 && D >= 2 {
        let species = plan.species[0];
        let sides = plan.description.box_sides();
        let density = plan.particle_weight * s.particles as f64 / sides.iter().product::<f64>();
        let phi = plan.description.packing_fraction();
        let enskog = match D {
            2 => gas::theory::NavierStokes::enskog::<2>(
                density,
                species.diameter,
                species.mass,
                s.temperature,
                phi,
                1.0,
            ),
            _ => gas::theory::NavierStokes::enskog::<3>(
                density,
                species.diameter,
                species.mass,
                s.temperature,
                phi,
                1.0,
            ),
        };
        out["enskog_elastic_at_initial_temperature"] = serde_json::json!(enskog.self_diffusion);
    }
    out
}
