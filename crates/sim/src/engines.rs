//! Engines built from a plan: fresh from the `[system]` section, or restored from a
//! check-point after checking that the saved state belongs to the plan's run. The one place
//! that maps `run.engine` to an engine type.

use crate::checkpoint::{self, Sections};
use crate::description::species;
use crate::error::{Error, Result};
use crate::observer::{TimeSeries, VelocityHistograms};
use crate::validate::{EngineSpec, LawSpec, Plan};
use gas::parallel::Communicator;
use gas::{
    BathState, Checkpoint, Engine, EventDriven, EventDrivenState, HomogeneousDsmc, SoftSphere,
    SoftSphereState, SpatialDsmc, System,
};
use restitution::Restitution;
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;

/// The `format` of a run check-point.
pub const FORMAT: &str = "haff-run-checkpoint";

/// What a run check-point holds besides the engine (JSON, readable).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Records {
    /// The run file (normalized).
    pub description: crate::RunDescription,
    /// Check-point interval in samples (reused on resume).
    pub every: Option<usize>,
    pub timeseries: TimeSeries,
    pub histograms: VelocityHistograms,
    /// The observers of `[output]` (absent in check-points of runs without them).
    #[serde(default)]
    pub space: crate::space::SpaceRecords,
    /// The per-species series of a mixture (`system.species`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub species: Option<crate::species::SpeciesSeries>,
}

/// [`Records`], borrowed for writing.
#[derive(Serialize)]
pub(crate) struct RecordsRef<'a> {
    pub description: &'a crate::RunDescription,
    pub every: Option<usize>,
    pub timeseries: &'a TimeSeries,
    pub histograms: &'a VelocityHistograms,
    pub space: &'a crate::space::SpaceRecords,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub species: Option<&'a crate::species::SpeciesSeries>,
}

/// An engine the driver runs: the engine interface and a check-point writer. Engines are
/// `Send`, so that a run can go on in another thread (Python releases the GIL).
pub(crate) trait Driven<const D: usize>: Engine<D> + Send {
    /// Saves the engine's state with `records` as the check-point file `path` if `write`
    /// (the state is taken in any case: on several ranks that is collective).
    fn write_checkpoint(&mut self, path: &Path, records: RecordsRef<'_>, write: bool)
        -> Result<()>;
}

impl<const D: usize, E: Checkpoint<D> + Send> Driven<D> for E {
    fn write_checkpoint(
        &mut self,
        path: &Path,
        records: RecordsRef<'_>,
        write: bool,
    ) -> Result<()> {
        let state = self.save();
        if !write {
            return Ok(());
        }
        checkpoint::write_to(path, FORMAT, &records, &state)
    }
}

/// Physical particles per simulated one (`run.particle_weight`, spatial DSMC; else 1).
fn particle_weight(plan: &Plan) -> f64 {
    plan.description.run.particle_weight.unwrap_or(1.0)
}

/// The initial particles of the `[system]` section.
fn initial_system<const D: usize>(plan: &Plan) -> Result<System<D>> {
    let s = &plan.description.system;
    let diameter = s.diameter.unwrap_or(1.0);
    let mass = s.mass.unwrap_or(1.0);
    let phi = s.packing_fraction;
    let weight = particle_weight(plan);
    match (&s.species, plan.engine) {
        // DSMC particles are points: no need to place them without overlaps.
        (None, EngineSpec::HomogeneousDsmc(_) | EngineSpec::SpatialDsmc(_)) => {
            gas::dsmc::point_gas::<D>(
                s.particles,
                monodisperse_side::<D>(s.particles, diameter, phi, weight),
                diameter,
                mass,
                s.temperature,
                s.seed,
            )
        }
        (None, EngineSpec::EventDriven | EngineSpec::SoftSphere(..)) => {
            gas::init::monodisperse::<D>(s.particles, phi, diameter, mass, s.temperature, s.seed)
        }
        (Some(entries), _) => {
            gas::init::polydisperse::<D>(s.particles, phi, &species(entries), s.temperature, s.seed)
                .map(|system| widened(system, phi, weight))
        }
    }
    .map_err(|e| Error::input("system", e))
}

/// The box side of `n` simulated spheres of one kind standing for `n` x `weight` physical
/// ones at packing fraction `phi` (exactly the initializer's side for weight 1).
fn monodisperse_side<const D: usize>(n: usize, diameter: f64, phi: f64, weight: f64) -> f64 {
    if weight == 1.0 {
        gas::system::monodisperse_box_side::<D>(n, diameter, phi)
    } else {
        let volume = n as f64 * weight * gas::system::ball_volume::<D>(0.5 * diameter);
        gas::system::box_side::<D>(volume, phi)
    }
}

/// `system` (a mixture placed at `phi`) in the box of its spheres times `weight` at `phi`,
/// positions scaled with the box: DSMC particles are points, so the placement only has to
/// be uniform.
fn widened<const D: usize>(mut system: System<D>, phi: f64, weight: f64) -> System<D> {
    if weight == 1.0 {
        return system;
    }
    let length = mixture_side::<D>(&system, phi, weight);
    let scale = length / system.length;
    for x in &mut system.positions {
        for c in x.iter_mut() {
            *c = gas::system::wrap(*c * scale, length);
        }
    }
    system.length = length;
    system
}

/// The box side of the mixture `system` standing for `weight` times its spheres at `phi`.
fn mixture_side<const D: usize>(system: &System<D>, phi: f64, weight: f64) -> f64 {
    let volume: f64 = system
        .radii
        .iter()
        .map(|&r| gas::system::ball_volume::<D>(r))
        .sum();
    gas::system::box_side::<D>(volume * weight, phi)
}

/// A fresh engine at time 0.
pub(crate) fn start<const D: usize>(
    plan: &Plan,
    law: Box<dyn Restitution>,
    comm: &Arc<dyn Communicator>,
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
            drive(&mut engine, plan)?;
            Box::new(engine)
        }
        EngineSpec::HomogeneousDsmc(scheme) => {
            let mut engine = HomogeneousDsmc::distributed(
                system,
                s.packing_fraction,
                law,
                s.seed,
                scheme,
                comm.clone(),
            )
            .map_err(ranks_or_system)?;
            engine
                .set_driving(plan.driving)
                .map_err(|e| Error::input("driving", e))?;
            Box::new(engine)
        }
        EngineSpec::SpatialDsmc(options) => Box::new(
            SpatialDsmc::distributed(
                system,
                s.packing_fraction,
                law,
                s.seed,
                options,
                comm.clone(),
            )
            .map_err(ranks_or_system)?,
        ),
        EngineSpec::SoftSphere(options, material) => {
            Box::new(
                SoftSphere::new(system, material, options).map_err(|e| match &e {
                    // The step comes from run.steps_per_contact or run.time_step.
                    gas::Error::OutOfRange { name, .. }
                        if name == "steps_per_contact" || name == "time_step" =>
                    {
                        Error::input(format!("run.{name}"), e)
                    }
                    _ => fail(e),
                })?,
            )
        }
    })
}

/// The engine of the check-point `sections`, after checking that its state belongs to
/// the run of `plan`.
pub(crate) fn restore<const D: usize>(
    plan: &Plan,
    law: Box<dyn Restitution>,
    sections: &Sections,
    comm: &Arc<dyn Communicator>,
) -> Result<Box<dyn Driven<D>>> {
    if let (EngineSpec::SpatialDsmc(_), true) = (plan.engine, comm.size() > 1) {
        let state: gas::dsmc::SpatialSnapshot<D> = sections.engine()?;
        SpatialDsmc::check_state(plan, &state)
            .map_err(|e| sections.error(format!("engine state: {e}")))?;
        state
            .check(true)
            .map_err(|e| sections.error(format!("engine state: {e}")))?;
        let engine =
            SpatialDsmc::restore_distributed(state, law, comm.clone()).map_err(ranks_or_system)?;
        return Ok(Box::new(engine));
    }
    match plan.engine {
        EngineSpec::EventDriven => {
            let mut engine = restored::<D, EventDriven<D>>(plan, law, sections)?;
            drive(&mut engine, plan)?;
            Ok(Box::new(engine))
        }
        EngineSpec::HomogeneousDsmc(_) => restore_homogeneous::<D>(plan, law, sections, comm),
        EngineSpec::SpatialDsmc(_) => restore_as::<D, SpatialDsmc<D>>(plan, law, sections),
        EngineSpec::SoftSphere(..) => restore_as::<D, SoftSphere<D>>(plan, law, sections),
    }
}

/// Drives an event-driven engine as the plan says, at its interval, with kicks drawn from
/// the run's seed.
fn drive<const D: usize>(engine: &mut EventDriven<D>, plan: &Plan) -> Result<()> {
    let interval = plan.driving_interval.unwrap_or(1.0);
    engine
        .set_driving(plan.driving, interval, plan.description.system.seed)
        .map_err(|e| Error::input("driving.interval", e))
}

/// The homogeneous engine of a check-point, on the ranks of `comm`, driven as the plan says.
fn restore_homogeneous<const D: usize>(
    plan: &Plan,
    law: Box<dyn Restitution>,
    sections: &Sections,
    comm: &Arc<dyn Communicator>,
) -> Result<Box<dyn Driven<D>>> {
    let state: gas::dsmc::HomogeneousSnapshot<D> = sections.engine()?;
    HomogeneousDsmc::check_state(plan, &state)
        .map_err(|e| sections.error(format!("engine state: {e}")))?;
    state
        .check(true)
        .map_err(|e| sections.error(format!("engine state: {e}")))?;
    let mut engine = HomogeneousDsmc::restore_distributed(state, law, comm.clone())
        .map_err(|e| sections.error(format!("engine state: {e}")))?;
    engine
        .set_driving(plan.driving)
        .map_err(|e| Error::input("driving", e))?;
    Ok(Box::new(engine))
}

fn restore_as<const D: usize, E: Planned<D> + Send + 'static>(
    plan: &Plan,
    law: Box<dyn Restitution>,
    sections: &Sections,
) -> Result<Box<dyn Driven<D>>> {
    Ok(Box::new(restored::<D, E>(plan, law, sections)?))
}

/// The engine of the check-point `sections`, its state checked against the run of `plan`.
fn restored<const D: usize, E: Planned<D>>(
    plan: &Plan,
    law: Box<dyn Restitution>,
    sections: &Sections,
) -> Result<E> {
    let state: E::State = sections.engine()?;
    E::check_state(plan, &state).map_err(|e| sections.error(format!("engine state: {e}")))?;
    E::restore(state, law).map_err(|e| sections.error(format!("engine state: {e}")))
}

/// An error of an engine spread over ranks: too many ranks for its planes of cells or
/// blocks (naming `run.ranks`, the launch's count), else an error of `[system]`.
fn ranks_or_system(e: gas::Error) -> Error {
    match &e {
        gas::Error::OutOfRange { name, .. } if name == "ranks" => Error::input("run.ranks", e),
        _ => Error::input("system", e),
    }
}

/// An engine state that can be checked against the run it claims to belong to.
trait Planned<const D: usize>: Checkpoint<D> {
    /// Why `state` cannot be a state of the run of `plan`, if it cannot.
    fn check_state(plan: &Plan, state: &Self::State) -> std::result::Result<(), String>;
}

impl<const D: usize> Planned<D> for EventDriven<D> {
    fn check_state(plan: &Plan, state: &EventDrivenState<D>) -> std::result::Result<(), String> {
        particles(plan, &state.system)?;
        box_side(plan, &state.system)?;
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
        no_energy_gained(
            plan,
            &state.system,
            state.baths.as_ref().map(|b| b.temperatures.as_slice()),
        )
    }
}

impl<const D: usize> Planned<D> for SoftSphere<D> {
    fn check_state(plan: &Plan, state: &SoftSphereState<D>) -> std::result::Result<(), String> {
        particles(plan, &state.system)?;
        box_side(plan, &state.system)?;
        match plan.engine {
            EngineSpec::SoftSphere(options, material)
                if state.options == options && state.material == material => {}
            _ => {
                return Err(
                    "the material or the soft-sphere options differ from the run file's".into(),
                )
            }
        }
        no_energy_gained(plan, &state.system, None)?;
        let contact = crate::validate::contact_duration(&plan.description, &state.material)
            .map_err(|e| e.to_string())?;
        let (finest, coarsest) = crate::validate::time_step_range(contact);
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
        let energy = 0.5 * (D * s.particles) as f64 * s.temperature;
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
}

macro_rules! planned_dsmc {
    ($engine:ident, $spec:ident, $box:expr) => {
        impl<const D: usize> Planned<D> for $engine<D> {
            fn check_state(
                plan: &Plan,
                state: &<Self as Checkpoint<D>>::State,
            ) -> std::result::Result<(), String> {
                particles(plan, &state.system)?;
                let s = &plan.description.system;
                let options = match plan.engine {
                    EngineSpec::$spec(options) => options,
                    _ => return Err("another engine".into()),
                };
                if state.options != options
                    || state.packing_fraction != s.packing_fraction
                    || state.seed != s.seed
                {
                    return Err(
                        "the DSMC options, packing fraction or seed differ from the run file's"
                            .into(),
                    );
                }
                if $box {
                    box_side(plan, &state.system)?;
                }
                no_energy_gained(plan, &state.system, None)
            }
        }
    };
}

// The homogeneous engine's box is its volume's cube root, not an initial box.
planned_dsmc!(HomogeneousDsmc, HomogeneousDsmc, false);
planned_dsmc!(SpatialDsmc, SpatialDsmc, true);

/// The particles of `system` are those of `[system]`: their number, and their radii and
/// masses (one kind, or the species in their counts).
fn particles<const D: usize>(plan: &Plan, system: &System<D>) -> std::result::Result<(), String> {
    let s = &plan.description.system;
    if system.len() != s.particles {
        return Err(format!(
            "{} particles where system.particles = {}",
            system.len(),
            s.particles
        ));
    }
    let kinds: Vec<(f64, f64, usize)> = match &s.species {
        None => vec![(
            0.5 * s.diameter.unwrap_or(1.0),
            s.mass.unwrap_or(1.0),
            s.particles,
        )],
        Some(entries) => {
            let counts = gas::init::species_counts(s.particles, &species(entries))
                .map_err(|e| e.to_string())?;
            entries
                .iter()
                .zip(counts)
                .map(|(x, count)| (0.5 * x.diameter, x.mass, count))
                .collect()
        }
    };
    for (radius, mass, count) in kinds {
        let found = system
            .radii
            .iter()
            .zip(&system.masses)
            .filter(|&(&r, &m)| r == radius && m == mass)
            .count();
        if found != count {
            return Err(format!(
                "{found} particles of radius {radius} and mass {mass} where [system] has {count}"
            ));
        }
    }
    Ok(())
}

/// A cooling gas never gains energy: the kinetic energy of the particles (plus, for a
/// stochastic law, the energy `modes * T_i` held by each particle's bath, which the
/// collisions exchange with the translation, `restitution::collide_with_baths`) is at most
/// the initial one, `N (D/2) T0 (+ N modes T_bath)`: the initializer sets the temperature
/// exactly (to round-off). The tolerance 1e-6 is far above the round-off of the collision
/// updates (~1e-16 relative per collision, a random walk) and far below what an edit that
/// would blow up the run (a velocity or bath temperature of 1e100) adds.
fn no_energy_gained<const D: usize>(
    plan: &Plan,
    system: &System<D>,
    bath_temperatures: Option<&[f64]>,
) -> std::result::Result<(), String> {
    if plan.driving.is_some() {
        // A driven gas gains energy.
        return Ok(());
    }
    let s = &plan.description.system;
    let n = system.len() as f64;
    let kinetic = gas::observe::kinetic_energy(system);
    let mut initial = n * 0.5 * D as f64 * s.temperature;
    let mut now = kinetic;
    if let LawSpec::Stochastic {
        modes,
        bath_temperature,
        ..
    } = plan.law
    {
        let modes = f64::from(modes);
        initial += n * modes * bath_temperature;
        now += modes * bath_temperatures.unwrap_or(&[]).iter().sum::<f64>();
    }
    if now.is_finite() && now <= initial * (1.0 + 1e-6) {
        Ok(())
    } else {
        Err(format!(
            "energy {now:e} above the initial energy {initial:e} of [system] and [collision]; \
             a cooling gas does not gain energy"
        ))
    }
}

/// The box side is the one of `[system]` (the spheres' volume at the packing fraction),
/// exactly for one kind of sphere (the initializer computes it the same way), to the
/// round-off of the initializer's sum over the particles for a mixture (n ulp).
fn box_side<const D: usize>(plan: &Plan, system: &System<D>) -> std::result::Result<(), String> {
    let s = &plan.description.system;
    let weight = particle_weight(plan);
    let (expected, tolerance) = match &s.species {
        None => {
            let side = monodisperse_side::<D>(
                s.particles,
                s.diameter.unwrap_or(1.0),
                s.packing_fraction,
                weight,
            );
            (side, 0.0)
        }
        Some(_) => {
            let side = mixture_side::<D>(system, s.packing_fraction, weight);
            (side, 2.0 * f64::EPSILON * system.len() as f64 * side)
        }
    };
    if (system.length - expected).abs() <= tolerance {
        Ok(())
    } else {
        Err(format!(
            "box side {} where system.packing_fraction gives {expected}",
            system.length
        ))
    }
}
