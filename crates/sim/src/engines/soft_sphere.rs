//! Soft-sphere MD (`run.engine = "soft-sphere"`, `gas::SoftSphere`): the viscoelastic
//! material of `[collision]` integrated as a force, its time step from `run.steps_per_contact`
//! or `run.time_step`, checked to resolve the contacts and to keep the run bounded.

use super::{state_error, Abilities, DrivingTimes, EngineSpec, TimeStep};
use crate::checkpoint::Sections;
use crate::description::{LawKind, RunDescription};
use crate::driver::Driven;
use crate::error::{Error, Result};
use crate::validate::{material, Plan, Species, Stop};
use gas::soft::contact::ViscoelasticMaterial;
use gas::{Checkpoint, SoftSphere, SoftSphereOptions, SoftSphereState, System};

pub(super) const ABILITIES: Abilities = Abilities {
    positions: true,
    point_particles: false,
    ranks: false,
    driving: DrivingTimes::Never,
    contacts: true,
    time_step: TimeStep::Contact,
    collapse: false,
    baths: false,
    species_materials: false,
    walls: true,
    shear: true,
    stress: true,
    displacements: true,
    rotation: true,
};

/// The material and the time step (`run.steps_per_contact` or `run.time_step`).
pub(super) fn spec(
    description: &RunDescription,
    species: &[Species],
    stop: Stop,
) -> Result<EngineSpec> {
    super::refuse_foreign_keys(description)?;
    let (c, r) = (&description.collision, &description.run);
    let material = match (c.law, material(description)?) {
        (LawKind::Viscoelastic, Some(m)) => m,
        _ => {
            return Err(Error::input(
                "collision.law",
                "run.engine = \"soft-sphere\" integrates the viscoelastic force: law = \
                 \"viscoelastic\" with young, poisson and dissipative_constant",
            ))
        }
    };
    let mut options = SoftSphereOptions::default();
    if let Some(s) = r.steps_per_contact {
        if !(s.is_finite() && (4.0..=1e6).contains(&s)) {
            return Err(Error::out_of_range(
                "run.steps_per_contact",
                s,
                "4 <= steps_per_contact <= 1e6",
            ));
        }
        if r.time_step.is_some() {
            return Err(Error::input(
                "run.time_step",
                "give at most one of run.steps_per_contact and run.time_step",
            ));
        }
        options.steps_per_contact = s;
    }
    if let Some(dt) = r.time_step {
        // The range steps_per_contact allows, 4 ..= 1e6 steps per contact: coarser steps
        // miss contacts, finer ones would run for ever.
        let contact = contact_duration(description, species, &material)
            .map_err(|e| Error::input("run.time_step", e))?;
        let (finest, coarsest) = time_step_range(contact);
        if !(dt.is_finite() && (finest..=coarsest).contains(&dt)) {
            return Err(Error::out_of_range(
                "run.time_step",
                dt,
                &format!(
                    "{finest:e} ..= {coarsest:e} (4 to 1e6 steps per contact duration {contact:e} \
                     at ten thermal speeds)"
                ),
            ));
        }
        options.time_step = Some(dt);
    }
    check_steps(description, species, &options, &material, stop)?;
    Ok(EngineSpec::SoftSphere(options, material))
}

/// The contact duration the soft-sphere time step resolves, for the spheres and the
/// temperature of `[system]` ([`gas::soft::shortest_contact_duration`]).
pub(crate) fn contact_duration(
    description: &RunDescription,
    species: &[Species],
    material: &ViscoelasticMaterial,
) -> gas::Result<f64> {
    let kinds: Vec<(f64, f64)> = species.iter().map(|x| (x.radius(), x.mass)).collect();
    gas::soft::shortest_contact_duration(&kinds, description.system.temperature, material)
}

/// The soft-sphere time steps allowed for a contact duration: 4 to 1e6 steps per contact
/// (as steps_per_contact), finest first.
pub(crate) fn time_step_range(contact: f64) -> (f64, f64) {
    (contact / 1e6, contact / 4.0)
}

/// The most time steps a soft-sphere run may take.
const MAX_STEPS: f64 = 1e8;

/// A soft-sphere run takes at most 1e8 time steps: end_time / dt, or, to reach
/// collisions_per_particle, at least that many over the initial Enskog collision frequency
/// (a cooling gas collides ever more slowly). A very stiff material in the run's units
/// (young = 1e19 with sigma = m = T = 1) would otherwise run for days.
fn check_steps(
    description: &RunDescription,
    species: &[Species],
    options: &SoftSphereOptions,
    material: &ViscoelasticMaterial,
    stop: Stop,
) -> Result<()> {
    let key = stop.key();
    let contact =
        contact_duration(description, species, material).map_err(|e| Error::input(key, e))?;
    let dt = options
        .time_step
        .unwrap_or(contact / options.steps_per_contact);
    let s = &description.system;
    let (diameter, mass) = (species[0].diameter, species[0].mass);
    let time = match stop {
        Stop::Time(end) => end,
        Stop::CollisionsPerParticle(c) => {
            let phi = description.packing_fraction();
            let omega = match s.dimension {
                1 => enskog_frequency::<1>(phi, diameter, mass, s.temperature),
                2 => enskog_frequency::<2>(phi, diameter, mass, s.temperature),
                _ => enskog_frequency::<3>(phi, diameter, mass, s.temperature),
            };
            c / omega
        }
    };
    let steps = time / dt;
    if steps <= MAX_STEPS {
        return Ok(());
    }
    Err(Error::input(
        key,
        format!(
            "{steps:.3e} time steps of {dt:e} (contacts of this material last {contact:e} at \
             ten thermal speeds); a run takes at most 1e8: shorten the run, or check \
             collision.young in the units of the system"
        ),
    ))
}

/// The Enskog collision frequency of one sphere of the gas at its initial temperature.
fn enskog_frequency<const D: usize>(phi: f64, diameter: f64, mass: f64, temperature: f64) -> f64 {
    let density = phi / gas::system::ball_volume::<D>(0.5 * diameter);
    gas::theory::collision_frequency::<D>(density, diameter, mass, temperature, phi)
}

/// The engine of `system`.
pub(super) fn engine<const D: usize>(
    system: System<D>,
    options: SoftSphereOptions,
    material: ViscoelasticMaterial,
) -> gas::Result<SoftSphere<D>> {
    SoftSphere::new(system, material, options)
}

/// A fresh engine of the plan: a step that does not resolve the contacts blames the key
/// that set it.
pub(super) fn start<const D: usize>(
    plan: &Plan,
    system: System<D>,
    options: SoftSphereOptions,
    material: ViscoelasticMaterial,
) -> Result<Box<dyn Driven<D>>> {
    let step_key = match options.time_step {
        Some(_) => "run.time_step",
        None => "run.steps_per_contact",
    };
    let mut engine = engine(system, options, material).map_err(|e| match e {
        gas::Error::UnresolvedStep { .. } => Error::input(step_key, e),
        _ => Error::input("system", e),
    })?;
    if let Some(friction) = plan.rough.as_ref().and_then(|r| r.friction) {
        engine
            .set_friction(Some(friction))
            .map_err(|e| Error::input("collision.friction", e))?;
    }
    enclose(&mut engine, plan)?;
    Ok(Box::new(engine))
}

/// Puts the engine's gas into the plan's walls and gravity, if any.
fn enclose<const D: usize>(engine: &mut SoftSphere<D>, plan: &Plan) -> Result<()> {
    let Some(walls) = super::walls_of::<D>(plan)? else {
        return Ok(());
    };
    engine
        .set_walls(Some(walls))
        .map_err(|e| Error::input("wall", e))?;
    let Some((g, _)) = super::gravity_of::<D>(plan) else {
        return Ok(());
    };
    engine
        .set_gravity(Some(g))
        .map_err(|e| Error::input("field.gravity", e))
}

/// The engine of a check-point, its state checked against the plan.
pub(super) fn restore<const D: usize>(
    plan: &Plan,
    sections: &Sections,
) -> Result<Box<dyn Driven<D>>> {
    let state: SoftSphereState<D> = sections.engine()?;
    check_state(plan, &state).map_err(state_error(sections))?;
    if state.tail.walls.as_ref().map(|c| c.walls.tallies.len())
        != (!plan.walls.is_empty()).then_some(plan.walls.len())
    {
        return Err(state_error(sections)(
            "the walls differ from [[wall]]".into(),
        ));
    }
    let mut engine =
        SoftSphere::restore(state, ()).map_err(|e| state_error(sections)(e.to_string()))?;
    enclose(&mut engine, plan)?;
    Ok(Box::new(engine))
}

/// Why `state` cannot be a state of the run of `plan`, if it cannot.
fn check_state<const D: usize>(
    plan: &Plan,
    state: &SoftSphereState<D>,
) -> std::result::Result<(), String> {
    super::initial::particles(plan, &state.system)?;
    super::initial::box_side(plan, &state.system)?;
    let friction = state.tail.history.as_ref().map(|h| h.friction);
    if friction != plan.rough.as_ref().and_then(|r| r.friction) {
        return Err("the contacts' friction differs from collision.friction".into());
    }
    match plan.engine {
        EngineSpec::SoftSphere(options, material)
            if state.options == options && state.material == material => {}
        _ => {
            return Err("the material or the soft-sphere options differ from the run file's".into())
        }
    }
    // Rough spheres: spins exchange energy with translation (hot spins heat it).
    super::initial::no_energy_gained(plan, &state.system, None, state.tail.rotation.as_ref())?;
    let contact = contact_duration(&plan.description, &plan.species, &state.material)
        .map_err(|e| e.to_string())?;
    let (finest, coarsest) = time_step_range(contact);
    let dt = state.time_step;
    if !(finest..=coarsest).contains(&dt) {
        return Err(format!(
            "time_step {dt:e} outside {finest:e} ..= {coarsest:e} (4 to 1e6 steps per contact)"
        ));
    }
    // A half kick changes no velocity by more than a few times the largest speed the
    // initial energy allows (the forces are repulsive contact forces): a bound that
    // every state of the run meets, and forged forces do not.
    let s = &plan.description.system;
    let mut energy = 0.5 * (D * s.particles) as f64 * s.temperature;
    if let Some(shear) = &plan.shear {
        // The flow's work heats a sheared gas: its own peculiar energy bounds it as well.
        let peculiar: f64 = (state.system.positions.iter())
            .zip(&state.system.velocities)
            .zip(&state.system.masses)
            .map(|((x, v), m)| 0.5 * m * shear.peculiar(x[1], v).iter().map(|u| u * u).sum::<f64>())
            .sum();
        energy = energy.max(peculiar);
    }
    let lightest = state
        .system
        .masses
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    let speed = (2.0 * energy / lightest).sqrt();
    for (force, mass) in state.forces.iter().zip(&state.system.masses) {
        let kick = force.iter().map(|f| f * f).sum::<f64>().sqrt() * 0.5 * dt / mass;
        if kick.is_nan() || kick > 10.0 * speed {
            return Err(format!(
                "a force kicks a particle by {kick:e} in half a step, more than 10 times \
                 the largest speed {speed:e} the initial energy allows"
            ));
        }
    }
    Ok(())
}
