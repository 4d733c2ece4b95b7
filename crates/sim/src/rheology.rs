//! The pressure tensor at every sample (`pressure.csv`: `output.pressure`, always under
//! `[shear]`) and the rheology of a sheared gas (`summary.json`'s `rheology`).
//!
//! Each row is the kinetic part of the peculiar velocities now plus the collisional part
//! averaged over the interval since the previous sample ([`gas::observe::pressure_tensor`];
//! the first row has the kinetic part only). `rheology` averages over the second half of
//! the run (the samples from the first at or after half the last sample's time) the
//! temperature, P_ab / (n T), the shear viscosity eta = -P_xy / a, and the normal stress
//! differences N1 = (P_xx - P_yy) / (n T), N2 = (P_yy - P_zz) / (n T), each with its
//! standard error from batch means (the samples cut into up to 10 consecutive batches,
//! whose means are taken as independent: batches longer than the correlation time), and
//! the reduced shear rate a* = a / nu0 (nu0 = n T / eta0(T), eta0 the elastic Boltzmann
//! viscosity; `gas::theory::usf`), with Grad's steady state of the dilute gas for a constant
//! restitution (`gas::theory::usf::steady_grad`) to compare.

use crate::error::Result;
use crate::observer::{one_row_per_sample, record_of, records_from, Observer};
use crate::output::{number, write_csv_file};
use crate::schedule::{Schedule, Target};
use crate::validate::{LawSpec, Plan};
use gas::observe::{pressure_tensor, temperature};
use gas::shear::Virial;
use gas::Engine;
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use std::any::Any;
use std::path::Path;

/// The header of `pressure.csv`.
pub const PRESSURE_HEADER: [&str; 9] = [
    "time",
    "collisions_per_particle",
    "pxx",
    "pyy",
    "pzz",
    "pxy",
    "pxz",
    "pyz",
    "kinetic_xy",
];

/// One row of `pressure.csv`, with the temperature and density it is reduced by.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PressureSample {
    pub time: f64,
    pub collisions_per_particle: f64,
    /// xx, yy, zz, xy, xz, yz (2D: zz, xz, yz are 0).
    pub pressure: [f64; 6],
    pub kinetic_xy: f64,
    /// Temperature of the peculiar velocities.
    pub temperature: f64,
    /// Number density of the physical particles.
    pub density: f64,
}

/// The pressure tensor's series.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PressureSeries {
    pub samples: Vec<PressureSample>,
    /// The time and the engine's tensor virial at the last sample.
    pub last: (f64, Virial),
}

impl PressureSeries {
    /// The series of a run that measures the pressure tensor; None otherwise.
    pub fn of(plan: &Plan) -> Option<Self> {
        plan.pressure_tensor.then(Self::default)
    }

    /// Writes `pressure.csv`.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let rows = self.samples.iter().map(|s| {
            let mut row = vec![number(s.time), number(s.collisions_per_particle)];
            row.extend(s.pressure.iter().map(|&p| number(p)));
            row.push(number(s.kinetic_xy));
            row
        });
        write_csv_file(path, &PRESSURE_HEADER, rows)
    }
}

impl<const D: usize> Observer<D> for PressureSeries {
    fn name(&self) -> &'static str {
        "pressure"
    }

    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<D>) -> Result<()> {
        if target.sample.is_none() {
            return Ok(());
        }
        let (time, per_particle, weight) = (
            engine.time(),
            engine.collisions_per_particle(),
            engine.weight(),
        );
        let virial = engine.virial_tensor().unwrap_or_default();
        let (last_time, last_virial) = self.last;
        let system = engine.system();
        let p = pressure_tensor(
            system,
            weight,
            &virial.since(&last_virial),
            time - last_time,
        );
        self.samples.push(PressureSample {
            time,
            collisions_per_particle: per_particle,
            pressure: p.total,
            kinetic_xy: p.kinetic[3],
            temperature: temperature(system),
            density: weight * system.len() as f64 / system.volume(),
        });
        self.last = (time, virial);
        Ok(())
    }

    fn record(&self) -> Result<Box<RawValue>> {
        record_of(self)
    }

    /// One row per sample done; the interval starts at the last one, with a finite virial.
    fn resume(
        &mut self,
        record: &RawValue,
        schedule: &Schedule,
        done: usize,
        engine: &mut dyn Engine<D>,
    ) -> std::result::Result<(), String> {
        let records: PressureSeries = records_from(record)?;
        one_row_per_sample(records.samples.len(), schedule, done, "pressure")?;
        let (time, virial) = records.last;
        let start = records.samples.last().map_or(0.0, |s| s.time);
        if time != start || virial.check().is_err() || time > engine.time() {
            return Err(format!(
                "the pressure's interval starts at time {time} (the last row's is {start}) \
                 with the virial {:?}",
                virial.0
            ));
        }
        *self = records;
        Ok(())
    }

    fn write(&self, dir: &Path) -> Result<()> {
        self.write_csv(&dir.join("pressure.csv"))
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// A mean and its standard error from batch means (None: fewer than 2 values).
fn batch_mean(values: &[f64]) -> serde_json::Value {
    let n = values.len();
    if n == 0 {
        return serde_json::Value::Null;
    }
    let mean = values.iter().sum::<f64>() / n as f64;
    let batches = n.min(10);
    let error = (batches >= 2).then(|| {
        let size = n / batches;
        let means: Vec<f64> = (0..batches)
            .map(|b| {
                let chunk = &values[b * size..if b + 1 == batches { n } else { (b + 1) * size }];
                chunk.iter().sum::<f64>() / chunk.len() as f64
            })
            .collect();
        let m = means.iter().sum::<f64>() / batches as f64;
        let var = means.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (batches - 1) as f64;
        (var / batches as f64).sqrt()
    });
    serde_json::json!({ "mean": mean, "error": error })
}

/// `summary.json`'s `rheology` of a sheared run (see the module documentation).
pub fn summary<const D: usize>(plan: &Plan, series: &PressureSeries) -> serde_json::Value {
    let Some(shear) = plan.shear else {
        return serde_json::Value::Null;
    };
    let rows = &series.samples;
    let Some(last) = rows.last() else {
        return serde_json::Value::Null;
    };
    // The first row has no collisional part: the half starts after it.
    let half: Vec<&PressureSample> = rows
        .iter()
        .skip(1)
        .filter(|s| s.time >= 0.5 * last.time)
        .collect();
    let of = |f: &dyn Fn(&PressureSample) -> f64| -> serde_json::Value {
        batch_mean(&half.iter().map(|s| f(s)).collect::<Vec<f64>>())
    };
    let reduced = |c: usize| move |s: &PressureSample| s.pressure[c] / (s.density * s.temperature);
    let a = shear.rate;
    let (diameter, mass) = (plan.species[0].diameter, plan.species[0].mass);
    let eta0 = |t: f64| gas::theory::dilute_elastic_viscosity::<D>(diameter, mass, t);
    let mut out = serde_json::json!({
        "shear_rate": a,
        "from_time": half.first().map(|s| s.time),
        "to_time": last.time,
        "samples": half.len(),
        "temperature": of(&|s| s.temperature),
        "pxx": of(&reduced(0)),
        "pyy": of(&reduced(1)),
        "pxy": of(&reduced(3)),
        "viscosity": of(&|s| -s.pressure[3] / a),
        "reduced_viscosity": of(&|s| -s.pressure[3] / (a * eta0(s.temperature))),
        "reduced_shear_rate": of(&|s| a * eta0(s.temperature) / (s.density * s.temperature)),
        "first_normal_difference": of(&|s| (s.pressure[0] - s.pressure[1]) / (s.density * s.temperature)),
    });
    if D == 3 {
        out["pzz"] = of(&reduced(2));
        out["second_normal_difference"] =
            of(&|s| (s.pressure[1] - s.pressure[2]) / (s.density * s.temperature));
    }
    if let (LawSpec::Constant(alpha), None) = (&plan.law, plan.driving) {
        if plan.species.len() == 1 && *alpha < 1.0 {
            let grad = match D {
                2 => gas::theory::usf::steady_grad::<2>(*alpha),
                _ => gas::theory::usf::steady_grad::<3>(*alpha),
            };
            out["theory"] = serde_json::json!({
                "method": "Grad's 13 moments, dilute gas, steady USF (gas::theory::usf)",
                "reduced_shear_rate": grad.reduced_shear_rate,
                "pxx": grad.pxx,
                "pyy": grad.pyy,
                "pzz": grad.pzz,
                "pxy": grad.pxy,
                "reduced_viscosity": grad.viscosity,
            });
        }
    }
    out
}
