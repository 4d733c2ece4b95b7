//! The event-driven engine (`run.engine = "event-driven"`, `gas::EventDriven`): no keys of
//! its own in `[run]`; the stochastic law's baths, the TC model and driving at discrete
//! times from the plan.

use super::{state_error, Abilities, DrivingTimes, EngineSpec, TimeStep, Tuning};
use crate::checkpoint::Sections;
use crate::description::RunDescription;
use crate::driver::Driven;
use crate::error::{Error, Result};
use crate::validate::{LawSpec, Plan};
use gas::driving::Drive;
use gas::{BathState, Checkpoint, Engine, EventDriven, EventDrivenState, System};
use restitution::Restitution;

pub(super) const ABILITIES: Abilities = Abilities {
    positions: true,
    point_particles: false,
    ranks: false,
    driving: DrivingTimes::AtIntervals,
    contacts: false,
    time_step: TimeStep::None,
    collapse: true,
    baths: true,
    species_materials: true,
};

/// The engine's keys: none beyond the common ones.
pub(super) fn spec(description: &RunDescription) -> Result<EngineSpec> {
    super::refuse_foreign_keys(description)?;
    Ok(EngineSpec::EventDriven)
}

/// The engine of `system` with `law` and `tuning`.
pub(super) fn engine<const D: usize>(
    system: System<D>,
    law: Box<dyn Restitution>,
    tuning: Tuning,
) -> gas::Result<EventDriven<D>> {
    let mut engine = if tuning.cell_width == 0.0 {
        EventDriven::new(system, law)?
    } else {
        EventDriven::with_cell_width(system, law, tuning.cell_width)?
    };
    if tuning.sorter != gas::SorterKind::default() {
        engine.set_sorter(tuning.sorter);
    }
    Ok(engine)
}

/// A fresh engine of the plan: baths of the stochastic law, the TC model, driving.
pub(super) fn start<const D: usize>(
    plan: &Plan,
    system: System<D>,
    law: Box<dyn Restitution>,
) -> Result<Box<dyn Driven<D>>> {
    let s = &plan.description.system;
    let mut engine =
        engine(system, law, Tuning::default()).map_err(|e| Error::input("system", e))?;
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
    drive(&mut engine, plan)?;
    Ok(Box::new(engine))
}

/// The engine of a check-point, its state checked against the plan, driven as the plan
/// says.
pub(super) fn restore<const D: usize>(
    plan: &Plan,
    law: Box<dyn Restitution>,
    sections: &Sections,
) -> Result<Box<dyn Driven<D>>> {
    let state: EventDrivenState<D> = sections.engine()?;
    check_state(plan, &state).map_err(state_error(sections))?;
    let mut engine =
        EventDriven::restore(state, law).map_err(|e| state_error(sections)(e.to_string()))?;
    drive(&mut engine, plan)?;
    Ok(Box::new(engine))
}

/// Drives the engine as the plan says, at its interval (resolved by validation), with
/// kicks drawn from the run's seed.
fn drive<const D: usize>(engine: &mut EventDriven<D>, plan: &Plan) -> Result<()> {
    let drive = plan.driving.map(|driving| Drive {
        driving,
        interval: plan.driving_interval,
        seed: plan.description.system.seed,
    });
    engine
        .set_driving(drive)
        .map_err(|e| Error::input("driving.interval", e))
}

/// Why `state` cannot be a state of the run of `plan`, if it cannot.
fn check_state<const D: usize>(
    plan: &Plan,
    state: &EventDrivenState<D>,
) -> std::result::Result<(), String> {
    super::initial::particles(plan, &state.system)?;
    super::initial::box_side(plan, &state.system)?;
    if state.tc.as_ref().map(|tc| tc.duration) != plan.tc {
        return Err("the TC model differs from collision.tc".into());
    }
    let stochastic = matches!(plan.law, LawSpec::Stochastic { .. });
    match &state.baths {
        Some(b) if stochastic && b.seed == plan.description.system.seed => {}
        None if !stochastic => {}
        _ => return Err("the baths do not belong to collision.law".into()),
    }
    if state.min_cell_width != 0.0 || state.sorter != gas::SorterKind::default() {
        return Err("cells or sorter differ from a run's".into());
    }
    super::initial::no_energy_gained(
        plan,
        &state.system,
        state.baths.as_ref().map(|b| b.temperatures.as_slice()),
    )
}
