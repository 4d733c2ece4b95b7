//! The event-driven engine (`run.engine = "event-driven"`, `gas::EventDriven`): no keys of
//! its own in `[run]`; the stochastic law's baths, the TC model and driving at discrete
//! times from the plan.

use super::{state_error, Abilities, DrivingTimes, EngineSpec, TimeStep, Tuning};
use crate::checkpoint::Sections;
use crate::description::RunDescription;
use crate::driver::Driven;
use crate::error::{Error, Result};
use crate::validate::{LawSpec, Plan, Stop};
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
    walls: true,
    shear: true,
    stress: true,
    displacements: true,
    rotation: true,
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
    enclose(&mut engine, plan)?;
    Ok(Box::new(engine))
}

/// Puts the engine's gas into the plan's walls, if any (their thermal velocities drawn
/// from the run's seed), and in its gravity.
fn enclose<const D: usize>(engine: &mut EventDriven<D>, plan: &Plan) -> Result<()> {
    let Some(walls) = super::walls_of::<D>(plan)? else {
        return Ok(());
    };
    engine
        .set_walls(Some(walls))
        .map_err(|e| Error::input("wall", e))?;
    let Some((g, rest_height)) = super::gravity_of::<D>(plan) else {
        return Ok(());
    };
    engine
        .set_gravity(Some(g), rest_height)
        .map_err(|e| Error::input("field.gravity", e))
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
    enclose(&mut engine, plan)?;
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
    match &state.tail.walls {
        Some(w) if w.tallies.len() == plan.walls.len() => {}
        None if plan.walls.is_empty() => {}
        _ => return Err("the walls differ from [[wall]]".into()),
    }
    if state.min_cell_width != 0.0 || state.sorter != gas::SorterKind::default() {
        return Err("cells or sorter differ from a run's".into());
    }
    super::initial::no_energy_gained(
        plan,
        &state.system,
        state.baths.as_ref().map(|b| b.temperatures.as_slice()),
        state.tail.rotation.as_ref(),
    )
}

/// The work of an event-driven run, told before it starts: its collisions, the events per
/// collision of its cells, and the events its driving adds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Work {
    pub collisions: f64,
    /// Whether `collisions` is an estimate (a run to a number of collisions, a driven or an
    /// elastic gas, Haff's law of a constant restitution) rather than only an upper bound
    /// (the initial rate for the whole time of a gas that cools by a law of its own).
    pub estimated: bool,
    pub events_per_collision: f64,
    /// Every application of the driving brings every particle to the present and predicts
    /// its events afresh: about one event's work per particle.
    pub driving_events: f64,
}

impl Work {
    pub fn events(&self) -> f64 {
        self.collisions * self.events_per_collision + self.driving_events
    }
}

/// The estimate of [`Work`] for the run of `plan`. Events per collision: a collision and
/// the cell crossings of its two free paths, 1 + 2 c_D lambda / w, with c_D the mean number
/// of cell faces a unit of path crosses per cell width (the sum over the axes of the mean
/// |cos| of the direction: 1, 4/pi, 3/2 in 1, 2, 3 dimensions), lambda the Enskog mean
/// free path of the largest spheres and w the cell width the engine will choose
/// (`gas::cells::Grid`; 7.6 at phi = 0.05 in 3D where 7.3 are measured, docs/event-driven.md).
/// Collisions: the run's; for a run in time the fastest species' Enskog frequency
/// ([`crate::species::fastest_collision_frequency`], at the larger of the initial and the
/// driven temperature) over the time, for a freely cooling gas of one constant restitution
/// eps < 1 integrated over Haff's law, nu0 tau ln(1 + t/tau) per particle (tau of
/// `gas::theory::haff_time`), for other cooling laws only an upper bound. Driving: the
/// time over the interval (for a run to a number of collisions, at least that number over
/// the fastest frequency).
pub(crate) fn work<const D: usize>(plan: &Plan) -> Work {
    let s = &plan.description.system;
    let n = s.particles as f64;
    let phi = plan.description.packing_fraction();
    let volume: f64 = plan
        .species
        .iter()
        .map(|x| x.count as f64 * gas::system::ball_volume::<D>(x.radius()))
        .sum::<f64>()
        / phi;
    let diameter = plan.species.iter().map(|x| x.diameter).fold(0.0, f64::max);
    let sides: [f64; D] = match &s.sides {
        Some(sides) => std::array::from_fn(|k| sides[k]),
        None => [volume.powf(1.0 / D as f64); D],
    };
    let grid = gas::cells::Grid::<D>::new(&sides, diameter, gas::cells::max_cells(s.particles));
    let free_path = gas::theory::mean_free_path::<D>(n / volume, diameter, phi);
    let faces = match D {
        1 => 1.0,
        2 => 4.0 / std::f64::consts::PI,
        _ => 1.5,
    };
    let width = grid.width.iter().sum::<f64>() / D as f64;
    let events_per_collision = 1.0 + 2.0 * faces * free_path / width;
    let frequency =
        crate::species::fastest_collision_frequency(plan).filter(|nu| *nu > 0.0 && nu.is_finite());
    let nu = frequency.unwrap_or(0.0);
    let (per_particle, duration, estimated) = match plan.stop {
        Stop::CollisionsPerParticle(c) => (c, if nu > 0.0 { c / nu } else { 0.0 }, true),
        Stop::Time(t) => match (&plan.law, plan.driving) {
            (LawSpec::Constant(eps), None) if *eps < 1.0 && nu > 0.0 => {
                let tau = gas::theory::haff_time::<D>(*eps, nu);
                (nu * tau * (t / tau).ln_1p(), t, true)
            }
            (LawSpec::Constant(_), _) | (_, Some(_)) => (nu * t, t, true),
            _ => (nu * t, t, false),
        },
    };
    let collisions = 0.5 * per_particle * n;
    let driving_events = match (plan.driving, plan.driving_interval) {
        (Some(_), Some(interval)) => duration / interval * n,
        _ => 0.0,
    };
    Work {
        collisions,
        estimated,
        events_per_collision,
        driving_events,
    }
}
