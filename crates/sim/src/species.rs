//! Per-species observables of a mixture (`system.species`): at every sample, each species'
//! temperature T_i = m_i <c^2>_i / D, Sonine a2_i and collision frequency, written to
//! `species.csv`. c is the velocity relative to the mixture's mean velocity (zero in a
//! freely cooling gas started at rest, where T_i = m_i <v^2>_i / D).

use crate::error::Result;
use crate::observer::{record_of, records_from, Observer};
use crate::output::{number, write_csv_file};
use crate::schedule::{Schedule, Target};
use crate::validate::{LawSpec, Plan};
use gas::driving::{Driving, WhiteNoise};
use gas::Engine;
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use std::any::Any;
use std::path::Path;

/// One row of `species.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpeciesSample {
    pub time: f64,
    pub collisions_per_particle: f64,
    /// The species' index in `system.species`.
    pub species: usize,
    pub temperature: f64,
    /// a2_i = D/(D + 2) <c^4>_i / <c^2>_i^2 - 1.
    pub a2: f64,
    /// Collisions per particle of the species per unit time over the interval since the
    /// previous sample (a collision counts for both of its particles); None at the first
    /// sample and for engines that do not count collisions by particle or species.
    pub collision_frequency: Option<f64>,
    /// Rough particles: the species' T_rot = <I w^2> / d_rot.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotational_temperature: Option<f64>,
}

/// The header of `species.csv` (`rotational_temperature` is appended for rough particles).
pub const SPECIES_HEADER: [&str; 6] = [
    "time",
    "collisions_per_particle",
    "species",
    "temperature",
    "a2",
    "collision_frequency",
];

/// The per-species time series of a mixture.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpeciesSeries {
    /// (radius, mass) of each listed species: how particles are told apart.
    pub kinds: Vec<(f64, f64)>,
    /// Rows in sample order, each sample's species in order.
    pub samples: Vec<SpeciesSample>,
    /// The time and each species' collisions at the last sample (the collision
    /// frequency's interval starts there).
    pub last: Option<(f64, Vec<u64>)>,
}

impl SpeciesSeries {
    /// The series of the listed species `kinds` ((radius, mass) each).
    pub fn new(kinds: Vec<(f64, f64)>) -> Self {
        SpeciesSeries {
            kinds,
            ..Default::default()
        }
    }

    /// The series of a run with `system.species`; None for one kind of particle not
    /// listed as a species.
    pub fn of(plan: &Plan) -> Option<Self> {
        plan.description.system.species.as_ref()?;
        Some(SpeciesSeries::new(plan.kinds()))
    }

    /// The index of the species of a particle of `radius` and `mass`.
    fn kind_of(&self, radius: f64, mass: f64) -> Option<usize> {
        self.kinds
            .iter()
            .position(|&(r, m)| r == radius && m == mass)
    }

    /// Checks the records of a check-point against `samples` samples of the time series.
    pub fn check_records(&self, samples: usize) -> std::result::Result<(), String> {
        if self.samples.len() != samples * self.kinds.len() {
            return Err(format!(
                "{} per-species rows for {samples} samples of {} species",
                self.samples.len(),
                self.kinds.len()
            ));
        }
        Ok(())
    }

    /// Writes `species.csv`.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let rough = self
            .samples
            .iter()
            .any(|s| s.rotational_temperature.is_some());
        let mut header = SPECIES_HEADER.to_vec();
        if rough {
            header.push("rotational_temperature");
        }
        let rows = self.samples.iter().map(|s| {
            let mut row = vec![
                number(s.time),
                number(s.collisions_per_particle),
                s.species.to_string(),
                number(s.temperature),
                number(s.a2),
                s.collision_frequency.map(number).unwrap_or_default(),
            ];
            row.extend(s.rotational_temperature.map(number));
            row
        });
        write_csv_file(path, &header, rows)
    }

    /// Each listed species' rotational temperature (rough particles).
    fn rotational_temperatures<const D: usize>(
        &self,
        engine: &mut dyn Engine<D>,
    ) -> Option<Vec<f64>> {
        engine.rotation()?;
        let system = engine.system().clone();
        let rotation = engine.rotation()?;
        let mut members = vec![Vec::new(); self.kinds.len()];
        for (i, (&r, &m)) in system.radii.iter().zip(&system.masses).enumerate() {
            if let Some(s) = self.kind_of(r, m) {
                members[s].push(i);
            }
        }
        Some(
            members
                .iter()
                .map(|list| rotation.temperature(&system, Some(list)))
                .collect(),
        )
    }

    /// The collisions of each listed species' particles so far, if the engine counts them.
    fn collisions<const D: usize>(&self, engine: &mut dyn Engine<D>) -> Option<Vec<u64>> {
        let mut totals = vec![0u64; self.kinds.len()];
        if let Some(counted) = engine.species_collisions() {
            for c in counted {
                totals[self.kind_of(c.radius, c.mass)?] += c.collisions;
            }
            return Some(totals);
        }
        // Per particle (event-driven, modulo 2^32 each: exact while no particle collides
        // 2^32 times between samples).
        let counts = engine.collision_counts()?;
        let system = engine.system();
        for (i, c) in counts.iter().enumerate() {
            totals[self.kind_of(system.radii[i], system.masses[i])?] += u64::from(*c);
        }
        Some(totals)
    }
}

impl<const D: usize> Observer<D> for SpeciesSeries {
    fn name(&self) -> &'static str {
        "species"
    }

    fn record(&self) -> Result<Box<RawValue>> {
        record_of(self)
    }

    /// The species of `system.species`, one row each per sample done.
    fn resume(
        &mut self,
        record: &RawValue,
        schedule: &Schedule,
        done: usize,
        _engine: &mut dyn Engine<D>,
    ) -> std::result::Result<(), String> {
        let records: SpeciesSeries = records_from(record)?;
        if records.kinds != self.kinds {
            return Err("the per-species records do not match system.species".into());
        }
        records.check_records(schedule.samples_before(done))?;
        *self = records;
        Ok(())
    }

    fn write(&self, dir: &Path) -> Result<()> {
        self.write_csv(&dir.join("species.csv"))
    }

    fn as_any(&self) -> &dyn Any {
        self
    }

    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<D>) -> Result<()> {
        if target.sample.is_none() {
            return Ok(());
        }
        let (time, collisions_per_particle) = (engine.time(), engine.collisions_per_particle());
        let collisions = self.collisions(engine);
        let rotational = self.rotational_temperatures(engine);
        let system = engine.system();
        let kinds = self.kinds.len();
        let total_mass: f64 = system.masses.iter().sum();
        let mean: [f64; D] = std::array::from_fn(|k| {
            system
                .velocities
                .iter()
                .zip(&system.masses)
                .map(|(v, m)| m * v[k])
                .sum::<f64>()
                / total_mass
        });
        // Per species: particles, sum m c^2, sum c^2, sum c^4.
        let mut sums = vec![(0usize, 0.0, 0.0, 0.0); kinds];
        for ((v, &r), &m) in system
            .velocities
            .iter()
            .zip(&system.radii)
            .zip(&system.masses)
        {
            let Some(s) = self.kind_of(r, m) else {
                continue;
            };
            let c2: f64 = (0..D).map(|k| (v[k] - mean[k]).powi(2)).sum();
            let e = &mut sums[s];
            *e = (e.0 + 1, e.1 + m * c2, e.2 + c2, e.3 + c2 * c2);
        }
        let frequencies: Vec<Option<f64>> = match (&collisions, &self.last) {
            (Some(now), Some((then, before))) if time > *then => (0..kinds)
                .map(|s| {
                    let n = sums[s].0 as f64;
                    Some(now[s].saturating_sub(before[s]) as f64 / (n * (time - then)))
                })
                .collect(),
            _ => vec![None; kinds],
        };
        for (s, &(n, mc2, c2, c4)) in sums.iter().enumerate() {
            self.samples.push(SpeciesSample {
                time,
                collisions_per_particle,
                species: s,
                temperature: mc2 / (n * D) as f64,
                a2: gas::observe::sonine_a2_of_sums::<D>(c2, c4, n as f64),
                collision_frequency: frequencies[s],
                rotational_temperature: rotational.as_ref().map(|t| t[s]),
            });
        }
        self.last = collisions.map(|c| (time, c));
        Ok(())
    }
}

/// The `species` entry of `summary.json`: the last sample's rows, each species' T_i / T
/// there (T = sum x_i T_i), and for a constant restitution (one, or one per pair) the HCS
/// of kinetic theory ([`gas::theory::MixtureTheory`]): T_i / T in the Maxwellian
/// approximation, and T_i / T and a2_i in the first Sonine approximation (up to
/// [`SONINE_SPECIES`] species: its quadrature grows as the square of the species).
pub fn summary(plan: &Plan, rows: &[SpeciesSample]) -> serde_json::Value {
    let Some(list) = plan.description.system.species.as_ref() else {
        return serde_json::Value::Null;
    };
    let table = Kinds::of(plan);
    let fractions = &table.fractions;
    let last = &rows[rows.len().saturating_sub(list.len())..];
    let mixture_temperature: f64 = last
        .iter()
        .map(|r| fractions[r.species] * r.temperature)
        .sum();
    let ratios: Vec<f64> = last
        .iter()
        .map(|r| r.temperature / mixture_temperature)
        .collect();
    let mut out = serde_json::json!({
        "final": last,
        "temperature_ratios": ratios,
    });
    let alpha = restitution_matrix(plan, list.len());
    // The thermostat's steady state is the HCS scaled: its theory is the HCS's.
    let hcs = !matches!(plan.driving, Some(Driving::WhiteNoise(_)));
    if let (Some(alpha), true) = (alpha, hcs) {
        let phi = plan.description.packing_fraction();
        let theory = match plan.description.system.dimension {
            1 => hcs_theory::<1>(&table, &alpha, phi),
            2 => hcs_theory::<2>(&table, &alpha, phi),
            _ => hcs_theory::<3>(&table, &alpha, phi),
        };
        if let Some(theory) = theory {
            out["hcs_theory"] = theory;
        }
    }
    out
}

/// The most species for which `summary.json` carries the Sonine theory.
pub const SONINE_SPECIES: usize = 4;

/// The HCS of kinetic theory: Maxwellian T_i / T, and Sonine T_i / T and a2_i.
fn hcs_theory<const D: usize>(
    table: &Kinds,
    alpha: &[Vec<f64>],
    phi: f64,
) -> Option<serde_json::Value> {
    let theory = table.theory::<D>(alpha, phi)?;
    let maxwellian = theory.hcs(1.0).ok()?;
    let mut out = serde_json::json!({
        "maxwellian": { "temperature_ratios": maxwellian.temperature_ratios },
    });
    if table.masses.len() <= SONINE_SPECIES {
        if let Ok(sonine) = theory.hcs_sonine(1.0) {
            out["sonine"] = serde_json::json!({
                "temperature_ratios": sonine.temperature_ratios,
                "a2": sonine.a2,
            });
        }
    }
    Some(out)
}

/// The restitution of every pair of `kinds` species for a constant law (one, or one per
/// pair).
fn restitution_matrix(plan: &Plan, kinds: usize) -> Option<Vec<Vec<f64>>> {
    match &plan.law {
        LawSpec::Constant(eps) => Some(vec![vec![*eps; kinds]; kinds]),
        LawSpec::ConstantPairs { matrix, .. } => Some(matrix.clone()),
        _ => None,
    }
}

/// The `driven_theory` entry of `summary.json` for a run driven by white noise with a
/// constant restitution: each species' steady temperature (and a2) in the Maxwellian and
/// the first Sonine approximation (`gas::theory::MixtureTheory::white_noise`; up to
/// [`SONINE_SPECIES`] species for Sonine).
pub fn driven_theory(plan: &Plan) -> Option<serde_json::Value> {
    let Some(Driving::WhiteNoise(noise)) = plan.driving else {
        return None;
    };
    let s = &plan.description.system;
    let table = Kinds::of(plan);
    let alpha = restitution_matrix(plan, table.masses.len())?;
    let strength = vec![noise.strength; table.masses.len()];
    let phi = plan.description.packing_fraction();
    match s.dimension {
        1 => steady::<1>(&table, &alpha, phi, &strength),
        2 => steady::<2>(&table, &alpha, phi, &strength),
        _ => steady::<3>(&table, &alpha, phi, &strength),
    }
}

fn steady<const D: usize>(
    table: &Kinds,
    alpha: &[Vec<f64>],
    phi: f64,
    strength: &[f64],
) -> Option<serde_json::Value> {
    let theory = table.theory::<D>(alpha, phi)?;
    let maxwellian = theory.white_noise(strength, false).ok()?;
    let mut out = serde_json::json!({
        "maxwellian": { "temperatures": maxwellian.temperatures },
    });
    if table.masses.len() <= SONINE_SPECIES {
        if let Ok(sonine) = theory.white_noise(strength, true) {
            out["sonine"] = serde_json::json!({
                "temperatures": sonine.temperatures,
                "a2": sonine.a2,
            });
        }
    }
    Some(out)
}

/// The event-driven engine's default time between applications of the driving: a tenth
/// of the shortest mean free time (the largest species' collision frequency, Enskog,
/// Maxwellian) at the larger of the initial temperature and the steady one the driving
/// aims at: the thermostat's, or white noise's Maxwellian energy balance for a constant
/// restitution (else the initial temperature alone). Kicks that far apart change a
/// particle's velocity between two of its collisions by a tenth of the kick of one mean
/// free time; `tests/driving.rs` shows the steady state converged there.
pub(crate) fn default_driving_interval(plan: &Plan) -> f64 {
    match fastest_collision_frequency(plan) {
        Some(nu) if nu > 0.0 && nu.is_finite() => 0.1 / nu,
        _ => 1.0,
    }
}

/// The largest species' collision frequency (Enskog, Maxwellian) at the larger of the
/// initial temperature and the steady one the driving aims at (see
/// [`default_driving_interval`]): an upper bound of the collision rate of a run.
pub(crate) fn fastest_collision_frequency(plan: &Plan) -> Option<f64> {
    let s = &plan.description.system;
    let phi = plan.description.packing_fraction();
    let table = Kinds::of(plan);
    let kinds = table.masses.len();
    let mut reference = vec![s.temperature; kinds];
    match plan.driving {
        Some(Driving::Thermostat(t)) => {
            reference.iter_mut().for_each(|r| *r = r.max(t.temperature))
        }
        Some(Driving::WhiteNoise(noise)) => {
            if let Some(alpha) = restitution_matrix(plan, kinds) {
                let steady = match s.dimension {
                    1 => white_noise_maxwellian::<1>(&table, &alpha, phi, noise),
                    2 => white_noise_maxwellian::<2>(&table, &alpha, phi, noise),
                    _ => white_noise_maxwellian::<3>(&table, &alpha, phi, noise),
                };
                for (r, t) in reference.iter_mut().zip(steady.unwrap_or_default()) {
                    *r = r.max(t);
                }
            }
        }
        None => {}
    }
    let elastic = vec![vec![1.0; kinds]; kinds];
    match s.dimension {
        1 => fastest_frequency::<1>(&table, &elastic, phi, &reference),
        2 => fastest_frequency::<2>(&table, &elastic, phi, &reference),
        _ => fastest_frequency::<3>(&table, &elastic, phi, &reference),
    }
}

fn white_noise_maxwellian<const D: usize>(
    table: &Kinds,
    alpha: &[Vec<f64>],
    phi: f64,
    noise: WhiteNoise,
) -> Option<Vec<f64>> {
    let strength = vec![noise.strength; table.masses.len()];
    let theory = table.theory::<D>(alpha, phi)?;
    Some(theory.white_noise(&strength, false).ok()?.temperatures)
}

fn fastest_frequency<const D: usize>(
    table: &Kinds,
    alpha: &[Vec<f64>],
    phi: f64,
    temperatures: &[f64],
) -> Option<f64> {
    let theory = table.theory::<D>(alpha, phi)?;
    Some(
        theory
            .collision_frequencies(temperatures)
            .into_iter()
            .fold(0.0, f64::max),
    )
}

/// The species of a run for kinetic theory: `system.species` (fractions normalized), or the
/// one species of `system.diameter` and `system.mass`.
struct Kinds {
    masses: Vec<f64>,
    diameters: Vec<f64>,
    fractions: Vec<f64>,
}

impl Kinds {
    fn of(plan: &Plan) -> Self {
        Kinds {
            masses: plan.species.iter().map(|x| x.mass).collect(),
            diameters: plan.species.iter().map(|x| x.diameter).collect(),
            fractions: plan.species.iter().map(|x| x.fraction).collect(),
        }
    }

    /// Their kinetic theory with restitutions `alpha` at packing fraction `phi`.
    fn theory<const D: usize>(
        &self,
        alpha: &[Vec<f64>],
        phi: f64,
    ) -> Option<gas::theory::MixtureTheory<D>> {
        gas::theory::MixtureTheory::<D>::new(
            &self.masses,
            &self.diameters,
            &self.fractions,
            alpha,
            phi,
        )
        .ok()
    }
}
