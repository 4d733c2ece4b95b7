//! Engines built from a plan: fresh from the `[system]` section, or restored from a
//! check-point. The one place that maps `run.engine` to an engine type.

use crate::checkpoint::{self, CheckpointRef, FORMAT, VERSION};
use crate::description::species;
use crate::error::{Error, Result};
use crate::observer::{TimeSeries, VelocityHistograms};
use crate::validate::{EngineSpec, LawSpec, Plan};
use gas::{BathState, Checkpoint, Engine, EventDriven, HomogeneousDsmc, SpatialDsmc, System};
use restitution::Restitution;
use std::path::Path;

/// What a check-point holds besides the engine.
pub(crate) struct Records<'a> {
    pub plan: &'a Plan,
    pub every: Option<usize>,
    pub timeseries: &'a TimeSeries,
    pub histograms: &'a VelocityHistograms,
}

/// An engine the driver runs: the engine interface and a check-point writer.
pub(crate) trait Driven<const D: usize>: Engine<D> {
    /// Saves the engine's state with `records` as `dir/checkpoint.json`.
    fn write_checkpoint(&mut self, dir: &Path, records: Records<'_>) -> Result<()>;
}

impl<const D: usize, E: Checkpoint<D>> Driven<D> for E {
    fn write_checkpoint(&mut self, dir: &Path, records: Records<'_>) -> Result<()> {
        let state = self.save();
        checkpoint::write(
            dir,
            &CheckpointRef {
                format: FORMAT,
                version: VERSION,
                description: &records.plan.description,
                every: records.every,
                timeseries: records.timeseries,
                histograms: records.histograms,
                engine: &state,
            },
        )
    }
}

/// The initial particles of the `[system]` section.
fn initial_system<const D: usize>(plan: &Plan) -> Result<System<D>> {
    let s = &plan.description.system;
    let diameter = s.diameter.unwrap_or(1.0);
    let mass = s.mass.unwrap_or(1.0);
    let phi = s.packing_fraction;
    match (&s.species, plan.engine) {
        // DSMC particles are points: no need to place them without overlaps.
        (None, EngineSpec::HomogeneousDsmc(_) | EngineSpec::SpatialDsmc(_)) => {
            gas::dsmc::point_gas::<D>(
                s.particles,
                gas::system::monodisperse_box_side::<D>(s.particles, diameter, phi),
                diameter,
                mass,
                s.temperature,
                s.seed,
            )
        }
        (None, EngineSpec::EventDriven) => {
            gas::init::monodisperse::<D>(s.particles, phi, diameter, mass, s.temperature, s.seed)
        }
        (Some(entries), _) => {
            gas::init::polydisperse::<D>(s.particles, phi, &species(entries), s.temperature, s.seed)
        }
    }
    .map_err(|e| Error::input("system", e))
}

/// A fresh engine at time 0.
pub(crate) fn start<const D: usize>(
    plan: &Plan,
    law: Box<dyn Restitution>,
) -> Result<Box<dyn Driven<D>>> {
    let system = initial_system::<D>(plan)?;
    let s = &plan.description.system;
    let fail = |e: gas::Error| Error::input("system", e);
    Ok(match plan.engine {
        EngineSpec::EventDriven => {
            let mut engine = EventDriven::new(system, law).map_err(fail)?;
            if let LawSpec::Stochastic {
                bath_temperature, ..
            } = plan.law
            {
                let baths = BathState {
                    temperatures: vec![bath_temperature; s.particles],
                    seed: s.seed,
                    draws: 0,
                };
                engine
                    .set_bath_state(baths)
                    .map_err(|e| Error::input("collision.bath_temperature", e))?;
            }
            if let Some(tc) = plan.tc {
                engine
                    .set_tc_model(tc, None)
                    .map_err(|e| Error::input("collision.tc", e))?;
            }
            Box::new(engine)
        }
        EngineSpec::HomogeneousDsmc(scheme) => Box::new(
            HomogeneousDsmc::new(system, s.packing_fraction, law, s.seed, scheme).map_err(fail)?,
        ),
        EngineSpec::SpatialDsmc(options) => Box::new(
            SpatialDsmc::new(system, s.packing_fraction, law, s.seed, options).map_err(fail)?,
        ),
    })
}

/// The engine of the check-point `text` (read from `dir`).
pub(crate) fn restore<const D: usize>(
    plan: &Plan,
    law: Box<dyn Restitution>,
    text: &str,
    dir: &Path,
) -> Result<Box<dyn Driven<D>>> {
    match plan.engine {
        EngineSpec::EventDriven => restore_as::<D, EventDriven<D>>(law, text, dir),
        EngineSpec::HomogeneousDsmc(_) => restore_as::<D, HomogeneousDsmc<D>>(law, text, dir),
        EngineSpec::SpatialDsmc(_) => restore_as::<D, SpatialDsmc<D>>(law, text, dir),
    }
}

fn restore_as<const D: usize, E: Checkpoint<D> + 'static>(
    law: Box<dyn Restitution>,
    text: &str,
    dir: &Path,
) -> Result<Box<dyn Driven<D>>> {
    let file = checkpoint::parse::<E::State>(text, dir)?;
    let engine = E::restore(file.engine, law).map_err(|e| Error::Checkpoint {
        path: dir.join(checkpoint::FILE_NAME),
        message: e.to_string(),
    })?;
    Ok(Box::new(engine))
}
