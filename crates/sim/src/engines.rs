//! The one place that maps engine kinds to engines (LAMMPS' styles, DynamO's dynamics): each
//! kind's module owns its keys of the run file, what it can do ([`Abilities`]), how it
//! starts from a plan, how it is restored from a check-point (its state checked against the
//! plan) and how it is built for a system set up in code ([`build`]: the reproduced papers,
//! the benches). Validation, the observers and the driver ask [`Abilities`] and never match
//! an engine kind.
//!
//! A new engine: a type in `crates/gas` implementing `gas::Engine` and `gas::Checkpoint`,
//! a module here (its keys, start, restore, state check), a variant of [`EngineSpec`] and
//! one arm in each `match` of this file.

mod dsmc;
mod event_driven;
mod initial;
mod soft_sphere;

use crate::checkpoint::Sections;
use crate::description::{DsmcScheme, EngineKind, RunDescription};
use crate::driver::Driven;
use crate::error::{Error, Result};
use crate::validate::{Plan, Species, Stop};
use gas::dsmc::{Scheme, SpatialOptions};
use gas::parallel::{Communicator, Local};
use gas::soft::contact::ViscoelasticMaterial;
use gas::{SoftSphereOptions, SorterKind, System};
use restitution::Restitution;
use std::sync::Arc;

/// The engine and its options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EngineSpec {
    EventDriven,
    HomogeneousDsmc(Scheme),
    SpatialDsmc(SpatialOptions),
    SoftSphere(SoftSphereOptions, ViscoelasticMaterial),
}

/// How an engine drives a gas ([`gas::Engine::set_driving`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DrivingTimes {
    /// It cannot.
    Never,
    /// At every step of its own (DSMC blocks).
    AtSteps,
    /// At the times k `driving.interval` (event-driven).
    AtIntervals,
}

/// The keys of `[run]` that set an engine's time step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeStep {
    /// No time step (event-driven: events in continuous time).
    None,
    /// DSMC: `run.collisions_per_step` or `run.time_step`.
    Collisions,
    /// Soft-sphere MD: `run.steps_per_contact` or `run.time_step`.
    Contact,
}

/// What an engine can do: the questions validation, the observers and the factory ask.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Abilities {
    /// Its particles have positions (the observers of space need them).
    pub positions: bool,
    /// Its particles are points placed independently (DSMC): no overlaps to avoid, a box
    /// that may stand for more physical particles, S(k -> 0) = 1.
    pub point_particles: bool,
    /// It spreads over MPI ranks.
    pub ranks: bool,
    pub driving: DrivingTimes,
    /// Contacts of finite duration (soft-sphere MD): one viscoelastic material.
    pub contacts: bool,
    pub time_step: TimeStep,
    /// Instantaneous collisions in continuous time: inelastic collapse can stop it (the TC
    /// model; a restitution of 0 sticks for ever).
    pub collapse: bool,
    /// Per-particle baths of the stochastic law (Giese's ED + MC).
    pub baths: bool,
    /// Species of their own viscoelastic materials.
    pub species_materials: bool,
    /// The walls of a container (`[[wall]]`).
    pub walls: bool,
    /// Uniform shear flow (`[shear]`).
    pub shear: bool,
    /// The tensor virial, for the pressure tensor (`output.pressure`, `[shear]`).
    pub stress: bool,
    /// The particles' displacements, for the mean-square displacement (`output.msd`).
    pub displacements: bool,
    /// Rough particles: rotation and the tangential restitution
    /// (`collision.tangential_restitution`).
    pub rotation: bool,
}

/// The name of an engine kind in the run file.
pub fn kind_name(kind: EngineKind) -> &'static str {
    match kind {
        EngineKind::EventDriven => "event-driven",
        EngineKind::Dsmc => "dsmc",
        EngineKind::SoftSphere => "soft-sphere",
    }
}

/// The engine a run file names, for messages: `run.engine = "event-driven"`, for DSMC with its
/// scheme (`run.engine = "dsmc" with run.dsmc_scheme = "blocks"`), whose abilities differ.
pub(crate) fn engine_named(description: &RunDescription) -> String {
    let kind = description.run.engine;
    match (kind, description.run.dsmc_scheme) {
        (EngineKind::Dsmc, scheme) => format!(
            "run.engine = \"dsmc\" with run.dsmc_scheme = \"{}\"",
            scheme.unwrap_or(DsmcScheme::Blocks).name()
        ),
        _ => format!("run.engine = \"{}\"", kind_name(kind)),
    }
}

/// What the engine a run file names can do (`run.engine`, for DSMC `run.dsmc_scheme`), known
/// before its keys are read.
pub fn abilities_of(description: &RunDescription) -> Abilities {
    kind_abilities(description.run.engine, description.run.dsmc_scheme)
}

/// What an engine kind can do (DSMC: with `scheme`, by default the blocks).
fn kind_abilities(kind: EngineKind, scheme: Option<DsmcScheme>) -> Abilities {
    match kind {
        EngineKind::EventDriven => event_driven::ABILITIES,
        EngineKind::SoftSphere => soft_sphere::ABILITIES,
        EngineKind::Dsmc => dsmc::abilities(scheme.unwrap_or(DsmcScheme::Blocks)),
    }
}

impl EngineSpec {
    /// What this engine can do.
    pub fn abilities(&self) -> Abilities {
        match self {
            EngineSpec::EventDriven => event_driven::ABILITIES,
            EngineSpec::SoftSphere(..) => soft_sphere::ABILITIES,
            EngineSpec::HomogeneousDsmc(Scheme::Blocks { .. }) => {
                dsmc::abilities(DsmcScheme::Blocks)
            }
            EngineSpec::HomogeneousDsmc(Scheme::Exact) => dsmc::abilities(DsmcScheme::Exact),
            EngineSpec::SpatialDsmc(_) => dsmc::abilities(DsmcScheme::Spatial),
        }
    }
}

/// The engine of the run file and its options from its keys of `[run]` (and, for
/// soft-sphere MD, the material of `[collision]`), for the particles `species` and a run
/// to `stop`; keys of another engine are refused.
pub(crate) fn spec(
    description: &RunDescription,
    species: &[Species],
    stop: Stop,
) -> Result<EngineSpec> {
    match description.run.engine {
        EngineKind::EventDriven => event_driven::spec(description),
        EngineKind::Dsmc => dsmc::spec(description, stop),
        EngineKind::SoftSphere => soft_sphere::spec(description, species, stop),
    }
}

/// Every engine kind, in the order the run file's documentation lists them.
const KINDS: [EngineKind; 3] = [
    EngineKind::EventDriven,
    EngineKind::Dsmc,
    EngineKind::SoftSphere,
];

/// The keys of `[run]` each engine kind reads beyond the common ones.
fn own_keys(kind: EngineKind) -> &'static [&'static str] {
    match kind {
        EngineKind::EventDriven => &[],
        EngineKind::Dsmc => &[
            "run.dsmc_scheme",
            "run.block_size",
            "run.collisions_per_step",
            "run.time_step",
            "run.collision_cell_width",
            "run.particle_weight",
        ],
        EngineKind::SoftSphere => &["run.steps_per_contact", "run.time_step"],
    }
}

/// Refuses a key of `[run]` that the run's engine does not read (it would be recorded and
/// ignored), naming the engines that read it.
fn refuse_foreign_keys(description: &RunDescription) -> Result<()> {
    let r = &description.run;
    let given = [
        ("run.steps_per_contact", r.steps_per_contact.is_some()),
        ("run.dsmc_scheme", r.dsmc_scheme.is_some()),
        ("run.block_size", r.block_size.is_some()),
        ("run.collisions_per_step", r.collisions_per_step.is_some()),
        ("run.time_step", r.time_step.is_some()),
        ("run.collision_cell_width", r.collision_cell_width.is_some()),
        ("run.particle_weight", r.particle_weight.is_some()),
    ];
    for (key, _) in given.iter().filter(|(_, on)| *on) {
        if !own_keys(r.engine).contains(key) {
            let owners: Vec<String> = KINDS
                .iter()
                .filter(|&&k| own_keys(k).contains(key))
                .map(|&k| format!("\"{}\"", kind_name(k)))
                .collect();
            return Err(Error::input(
                *key,
                format!("only for run.engine = {}", owners.join(" or ")),
            ));
        }
    }
    Ok(())
}

/// Every DSMC scheme, in the order the run file's documentation lists them.
const DSMC_SCHEMES: [DsmcScheme; 3] = [DsmcScheme::Blocks, DsmcScheme::Exact, DsmcScheme::Spatial];

/// The engines that can do what `can` asks, for messages: a DSMC that can with some schemes
/// only is named with them, last (`"event-driven", "soft-sphere" or "dsmc" with
/// run.dsmc_scheme = "spatial"`), so a message follows the engines' abilities.
pub(crate) fn kinds_that(can: impl Fn(&Abilities) -> bool) -> String {
    let mut names: Vec<String> = Vec::new();
    let mut qualified: Vec<String> = Vec::new();
    for &kind in &KINDS {
        let name = format!("\"{}\"", kind_name(kind));
        if kind != EngineKind::Dsmc {
            if can(&kind_abilities(kind, None)) {
                names.push(name);
            }
            continue;
        }
        let schemes: Vec<String> = DSMC_SCHEMES
            .iter()
            .filter(|&&s| can(&dsmc::abilities(s)))
            .map(|s| format!("\"{}\"", s.name()))
            .collect();
        if schemes.len() == DSMC_SCHEMES.len() {
            names.push(name);
        } else if !schemes.is_empty() {
            qualified.push(format!(
                "{name} with run.dsmc_scheme = {}",
                schemes.join(" or ")
            ));
        }
    }
    names.extend(qualified);
    match names.split_last() {
        None => "none".to_string(),
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
    }
}

/// A fresh engine at time 0, from the `[system]` section, and the report of a grown dense
/// start (`gas::init::GrowthReport`).
pub(crate) fn start<const D: usize>(
    plan: &Plan,
    law: Box<dyn Restitution>,
    comm: &Arc<dyn Communicator>,
) -> Result<(Box<dyn Driven<D>>, Option<gas::init::GrowthReport>)> {
    let (system, grown) = initial::system::<D>(plan)?;
    let engine = match plan.engine {
        EngineSpec::EventDriven => event_driven::start(plan, system, law),
        EngineSpec::HomogeneousDsmc(scheme) => {
            dsmc::start_homogeneous(plan, system, law, scheme, comm)
        }
        EngineSpec::SpatialDsmc(options) => dsmc::start_spatial(plan, system, law, options, comm),
        EngineSpec::SoftSphere(options, material) => {
            soft_sphere::start(plan, system, options, material)
        }
    }?;
    let mut engine = engine;
    flow(engine.as_mut(), plan)?;
    Ok((engine, grown))
}

/// Shears a fresh engine as `[shear]` says (its velocities become the peculiar ones) and
/// has it sum the tensor virial for the pressure tensor (`output.pressure`, `[shear]`).
fn flow<const D: usize>(engine: &mut dyn Driven<D>, plan: &Plan) -> Result<()> {
    if let Some(shear) = plan.shear {
        engine
            .set_shear(Some(shear))
            .map_err(|e| Error::input("shear", e))?;
    }
    if plan.msd {
        engine
            .set_tracking(true)
            .map_err(|e| Error::input("output.msd", e))?;
    }
    if let Some(rough) = &plan.rough {
        let rotation = thermal_rotation(engine, plan, rough)?;
        engine.set_rotation(Some(rotation)).map_err(|e| {
            // Soft-sphere MD's spheres are rough by their friction alone.
            let key = match rough.betas.is_empty() {
                true => "collision.friction",
                false => "collision.tangential_restitution",
            };
            Error::input(key, e)
        })?;
    }
    if plan.pressure_tensor {
        let key = if plan.shear.is_some() {
            "shear"
        } else {
            "output.pressure"
        };
        engine
            .set_virial_tensor(true)
            .map_err(|e| Error::input(key, e))?;
    }
    Ok(())
}

/// The rotation of a fresh rough gas: each particle's inertia factor by its species
/// (told apart by radius and mass), angular velocities at `system.rotational_temperature`
/// from their own random stream of `system.seed`.
fn thermal_rotation<const D: usize>(
    engine: &mut dyn Driven<D>,
    plan: &Plan,
    rough: &crate::validate::RoughSpec,
) -> Result<gas::rotation::Rotation> {
    let system = engine.system().clone();
    let inertia = particle_inertia(plan, rough, &system)?;
    if let Some(spins) = plan
        .initial
        .as_ref()
        .and_then(|i| i.configuration.spins.as_ref())
    {
        // The file's spins (disks: about z only).
        let angular = spins
            .iter()
            .map(|w| if D == 2 { [0.0, 0.0, w[2]] } else { *w })
            .collect();
        return Ok(gas::rotation::Rotation {
            inertia,
            angular,
            sliding: 0,
        });
    }
    Ok(gas::rotation::Rotation::thermal(
        &system,
        inertia,
        rough.temperature,
        plan.description.system.seed,
    ))
}

/// Each particle's inertia factor in `system` by its species.
fn particle_inertia<const D: usize>(
    plan: &Plan,
    rough: &crate::validate::RoughSpec,
    system: &System<D>,
) -> Result<Vec<f64>> {
    let kinds = plan.kinds();
    system
        .radii
        .iter()
        .zip(&system.masses)
        .map(|(&r, &m)| {
            let s = kinds.iter().position(|&k| k == (r, m)).ok_or_else(|| {
                Error::input(
                    "system.species",
                    format!("a particle of radius {r} and mass {m} belongs to no species"),
                )
            })?;
            Ok(rough.inertia[s])
        })
        .collect()
}

/// Why a restored engine's flow is not the plan's, if it is not: its shear, whether it
/// sums the tensor virial, whether its particles rotate with the plan's inertia.
fn check_flow<const D: usize>(
    engine: &mut dyn Driven<D>,
    plan: &Plan,
) -> std::result::Result<(), String> {
    if engine.shear() != plan.shear {
        return Err(format!(
            "its shear ({:?}) differs from [shear] ({:?})",
            engine.shear().map(|s| s.rate),
            plan.shear.map(|s| s.rate)
        ));
    }
    if engine.displacements().is_some() != plan.msd {
        return Err(
            "it tracks displacements where the run does not, or the other way \
                    (output.msd)"
                .into(),
        );
    }
    if engine.virial_tensor().is_some() != plan.pressure_tensor {
        return Err(
            "it measures the pressure tensor where the run does not, or the other way \
             (output.pressure, [shear])"
                .into(),
        );
    }
    match &plan.rough {
        None if engine.rotation().is_some() => {
            return Err("its particles rotate where the run's are smooth".into())
        }
        None => {}
        Some(rough) => {
            let system = engine.system().clone();
            let inertia = particle_inertia(plan, rough, &system).map_err(|e| e.to_string())?;
            if engine.rotation().is_none_or(|r| r.inertia != inertia) {
                return Err(
                    "its particles' rotation is not the run's (collision.tangential_restitution, \
                     system.inertia)"
                        .into(),
                );
            }
        }
    }
    Ok(())
}

/// The engine of the check-point `sections`, after checking that its state belongs to the
/// run of `plan`.
pub(crate) fn restore<const D: usize>(
    plan: &Plan,
    law: Box<dyn Restitution>,
    sections: &Sections,
    comm: &Arc<dyn Communicator>,
) -> Result<Box<dyn Driven<D>>> {
    let engine = match plan.engine {
        EngineSpec::EventDriven => event_driven::restore(plan, law, sections),
        EngineSpec::HomogeneousDsmc(_) => dsmc::restore_homogeneous(plan, law, sections, comm),
        EngineSpec::SpatialDsmc(_) => dsmc::restore_spatial(plan, law, sections, comm),
        EngineSpec::SoftSphere(..) => soft_sphere::restore(plan, sections),
    }?;
    let mut engine = engine;
    check_flow(engine.as_mut(), plan).map_err(state_error(sections))?;
    Ok(engine)
}

pub use event_driven::Work;

/// The estimated work of an event-driven run ([`event_driven::work`]); None for the other
/// engines.
pub fn work(plan: &Plan) -> Option<Work> {
    if plan.engine != EngineSpec::EventDriven {
        return None;
    }
    Some(match plan.description.system.dimension {
        1 => event_driven::work::<1>(plan),
        2 => event_driven::work::<2>(plan),
        _ => event_driven::work::<3>(plan),
    })
}

/// Events beyond which an event-driven run is refused: about a day at 1e6 events per
/// second.
const MAX_EVENTS: f64 = 1e11;
/// Events beyond which a run is announced with its estimate before it starts (a quarter of
/// an hour).
const ANNOUNCED_EVENTS: f64 = 1e9;

/// The work of the run of `plan` told in advance: refused (naming the key that makes it
/// absurd) beyond [`MAX_EVENTS`], noted in `plan.notes` beyond [`ANNOUNCED_EVENTS`]. The
/// event-driven engine's estimate is [`event_driven::work`]; soft-sphere MD and DSMC bound
/// their steps when their keys are read.
pub(crate) fn check_work(plan: &mut Plan) -> Result<()> {
    let Some(work) = work(plan) else {
        return Ok(());
    };
    let events = work.events();
    let hours = events / 1e6 / 3600.0;
    let told = format!(
        "{} {events:.1e} events: {:.1e} collisions x {:.3} events per collision{} (~{} h at \
         1e6 events/s)",
        if work.estimated { "about" } else { "at most" },
        work.collisions,
        work.events_per_collision,
        if work.driving_events > 0.0 {
            format!(
                " + {:.1e} for the applications of the driving",
                work.driving_events
            )
        } else {
            String::new()
        },
        if hours < 100.0 {
            format!("{hours:.1}")
        } else {
            format!("{hours:.1e}")
        }
    );
    let collision_events = work.collisions * work.events_per_collision;
    if work.driving_events > MAX_EVENTS.max(collision_events) {
        // The applications alone are too many: the interval that keeps to the bound.
        let interval = plan.driving_interval.unwrap_or(f64::NAN);
        let shortest =
            interval * work.driving_events / (MAX_EVENTS - collision_events.min(0.5 * MAX_EVENTS));
        return Err(Error::out_of_range(
            "driving.interval",
            interval,
            &format!(
                "{told}; at most {MAX_EVENTS:e} events: interval >= {shortest:.3e} (each \
                 application re-predicts every particle's events)"
            ),
        ));
    }
    if events > MAX_EVENTS && work.estimated {
        let (key, advice) = if work.events_per_collision > 100.0 {
            (
                "system.packing_fraction",
                "a denser gas (its cell crossings dominate), fewer particles per box, or \
                 run.engine = \"dsmc\"",
            )
        } else {
            (plan.stop.key(), "a shorter run")
        };
        return Err(Error::input(
            key,
            format!("{told}; allowed: at most {MAX_EVENTS:e} events: {advice}"),
        ));
    }
    if events > ANNOUNCED_EVENTS {
        plan.notes.push(told);
    }
    Ok(())
}

/// What an engine built for a system set up in code needs besides the particles.
pub struct Setup {
    pub law: Box<dyn Restitution>,
    /// The packing fraction the collision rates refer to (DSMC: the spheres' volume is
    /// that fraction of the volume they move in).
    pub packing_fraction: f64,
    /// The seed of the engine's random streams (DSMC).
    pub seed: u64,
    /// The baths of a stochastic law (Giese's ED + MC; an engine with baths only).
    pub baths: Option<gas::BathState>,
}

/// An engine of `spec` for the particles of `system` set up in code (the reproduced papers,
/// the benches), in this process.
pub fn build<const D: usize>(
    spec: &EngineSpec,
    system: System<D>,
    setup: Setup,
) -> Result<Box<dyn Driven<D>>> {
    let local: Arc<dyn Communicator> = Arc::new(Local);
    let fail = |e: gas::Error| Error::input("system", e);
    if setup.baths.is_some() && !spec.abilities().baths {
        return Err(Error::input("baths", "this engine has no baths"));
    }
    Ok(match *spec {
        EngineSpec::EventDriven => {
            let mut engine =
                event_driven::engine(system, setup.law, Tuning::default()).map_err(fail)?;
            if let Some(baths) = setup.baths {
                engine.set_bath_state(baths).map_err(fail)?;
            }
            Box::new(engine)
        }
        EngineSpec::HomogeneousDsmc(scheme) => {
            Box::new(dsmc::homogeneous(system, setup, scheme, &local).map_err(fail)?)
        }
        EngineSpec::SpatialDsmc(options) => {
            Box::new(dsmc::spatial(system, setup, options, &local).map_err(fail)?)
        }
        EngineSpec::SoftSphere(options, material) => {
            Box::new(soft_sphere::engine(system, options, material).map_err(fail)?)
        }
    })
}

/// Options of the event-driven engine that no run file sets (the benches compare them):
/// the smallest cell width and the sorter of its event calendar.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Tuning {
    /// The smallest cell width (0: the largest diameter).
    pub cell_width: f64,
    pub sorter: SorterKind,
}

/// The event-driven engine of `system` with `law` and `tuning`, as the type itself (the
/// benches step it event by event).
pub fn event_driven<const D: usize>(
    system: System<D>,
    law: Box<dyn Restitution>,
    tuning: Tuning,
) -> Result<gas::EventDriven<D>> {
    event_driven::engine(system, law, tuning).map_err(|e| Error::input("system", e))
}

/// The soft-sphere engine of `system`, as the type itself (the bench steps it).
pub fn soft_sphere<const D: usize>(
    system: System<D>,
    options: SoftSphereOptions,
    material: ViscoelasticMaterial,
) -> Result<gas::SoftSphere<D>> {
    soft_sphere::engine(system, options, material).map_err(|e| Error::input("system", e))
}

/// The rod-chain MD of Giese's Eq. (2) for `chain` (`haff rods chain`).
pub fn rod_chain(chain: rods::chain::Chain) -> rods::engine::ChainEngine {
    rods::engine::ChainEngine::new(chain)
}

/// An error of building an engine spread over ranks: too many ranks for its planes of
/// cells or blocks blames `run.ranks` (the launch's count), anything else `[system]`.
fn ranks_or_system(e: gas::Error) -> Error {
    match e {
        gas::Error::TooManyRanks { .. } => Error::input("run.ranks", e),
        _ => Error::input("system", e),
    }
}

/// The error of a check-point's engine state.
fn state_error(sections: &Sections) -> impl Fn(String) -> Error + '_ {
    move |e| sections.error(format!("engine state: {e}"))
}

/// The plan's walls as the engines take them (their thermal velocities drawn from the
/// run's seed); None for the periodic box.
fn walls_of<const D: usize>(plan: &Plan) -> Result<Option<gas::walls::Walls<D>>> {
    if plan.walls.is_empty() {
        return Ok(None);
    }
    let speed = crate::validate::wall_impact_speed(plan);
    let walls = plan
        .walls
        .iter()
        .enumerate()
        .map(|(i, w)| w.build(i, speed))
        .collect::<Result<Vec<_>>>()?;
    gas::walls::Walls::new(walls, plan.description.system.seed)
        .map(Some)
        .map_err(|e| Error::input("wall", e))
}

/// The plan's gravity and rest height, if any.
fn gravity_of<const D: usize>(plan: &Plan) -> Option<([f64; D], f64)> {
    plan.gravity
        .as_ref()
        .map(|g| (std::array::from_fn(|k| g.acceleration[k]), g.rest_height))
}
