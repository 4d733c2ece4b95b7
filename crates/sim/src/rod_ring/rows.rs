//! The energies of the rods at the samples of a chain run: one observer for the rod-chain
//! MD (its modes' energy from the engine's report) and for ED + MC (its baths' energy).

use crate::error::{Error, Result};
use crate::observer::{record_of, records_from, Observer};
use crate::schedule::{Schedule, Target};
use gas::Engine;
use rods::ring::translational_energy;
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use std::any::Any;
use std::path::Path;

/// One row of a time series: energies summed over the rods.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnergyRow {
    pub time: f64,
    pub collisions_per_particle: f64,
    /// Translational energy in the centre-of-mass frame.
    pub translational_energy: f64,
    /// Energy of the internal modes (the baths of ED + MC).
    pub bath_energy: f64,
    pub total_energy: f64,
}

/// The header of `timeseries.csv` and `ed_mc_<law>.csv`.
pub const ENERGY_HEADER: [&str; 5] = [
    "time",
    "collisions_per_particle",
    "translational_energy",
    "bath_energy",
    "total_energy",
];

/// Where the internal energy of the rods comes from.
#[derive(Debug, Clone, PartialEq)]
enum Internal {
    /// The rod-chain MD: the modes' energy and the chain's energy, from the section `chain`
    /// of the engine's report (`rods::engine::ChainEngine`).
    Modes,
    /// ED + MC: baths of `modes` modes each (a bath at temperature T holds `modes` T), the
    /// rods' masses in the engine's order.
    Baths { modes: usize, masses: Vec<f64> },
}

/// The energy rows of a chain run at its samples.
#[derive(Debug, Clone)]
pub(super) struct EnergyRows {
    internal: Internal,
    pub rows: Vec<EnergyRow>,
}

impl EnergyRows {
    /// The rows of the rod-chain MD.
    pub fn chain() -> Self {
        EnergyRows {
            internal: Internal::Modes,
            rows: Vec::new(),
        }
    }

    /// The rows of ED + MC with baths of `modes` modes, rods of `masses`.
    pub fn baths(modes: usize, masses: Vec<f64>) -> Self {
        EnergyRows {
            internal: Internal::Baths { modes, masses },
            rows: Vec::new(),
        }
    }
}

impl Observer<1> for EnergyRows {
    fn name(&self) -> &'static str {
        "rows"
    }

    fn observe(&mut self, target: &Target, engine: &mut dyn Engine<1>) -> Result<()> {
        if target.sample.is_none() {
            return Ok(());
        }
        let (time, collisions_per_particle) = (engine.time(), engine.collisions_per_particle());
        let row = match &self.internal {
            Internal::Modes => {
                let report = engine.report();
                let chain = report.section("chain").ok_or_else(|| Error::Numerical {
                    key: "chain".into(),
                    message: "the engine reports no modes".into(),
                })?;
                let system = engine.system();
                let v: Vec<f64> = system.velocities.iter().map(|v| v[0]).collect();
                EnergyRow {
                    time,
                    collisions_per_particle,
                    translational_energy: translational_energy(&v, &system.masses),
                    bath_energy: chain.number("mode_energy"),
                    total_energy: chain.number("total_energy"),
                }
            }
            Internal::Baths { modes, masses } => {
                let baths = engine
                    .bath_temperatures()
                    .unwrap_or(&[])
                    .iter()
                    .sum::<f64>()
                    * *modes as f64;
                let v: Vec<f64> = engine.system().velocities.iter().map(|v| v[0]).collect();
                let kinetic = translational_energy(&v, masses);
                EnergyRow {
                    time: target.value.max(time),
                    collisions_per_particle,
                    translational_energy: kinetic,
                    bath_energy: baths,
                    total_energy: kinetic + baths,
                }
            }
        };
        self.rows.push(row);
        Ok(())
    }

    fn record(&self) -> Result<Box<RawValue>> {
        record_of(&self.rows)
    }

    /// A row per sample done, the last at the engine's time.
    fn resume(
        &mut self,
        record: &RawValue,
        schedule: &Schedule,
        done: usize,
        engine: &mut dyn Engine<1>,
    ) -> std::result::Result<(), String> {
        let rows: Vec<EnergyRow> = records_from(record)?;
        if rows.len() != schedule.samples_before(done) {
            return Err(format!(
                "{} rows where the schedule has taken {} samples",
                rows.len(),
                schedule.samples_before(done)
            ));
        }
        if rows.last().is_some_and(|last| last.time != engine.time()) {
            return Err("the chain's time does not match the rows".into());
        }
        self.rows = rows;
        Ok(())
    }

    /// The rows are written by the run (averaged over repeats).
    fn write(&self, _dir: &Path) -> Result<()> {
        Ok(())
    }

    fn as_any(&self) -> &dyn Any {
        self
    }
}
