//! DSMC (`run.engine = "dsmc"`): the homogeneous schemes (`gas::HomogeneousDsmc`, blocks and
//! exact) and the spatial one (`gas::SpatialDsmc`); their keys (`run.dsmc_scheme`,
//! `block_size`, `collisions_per_step` or `time_step`, `collision_cell_width`,
//! `particle_weight`), ranks and driving at every step.

use super::{ranks_or_system, state_error, Abilities, DrivingTimes, EngineSpec, Setup, TimeStep};
use crate::checkpoint::Sections;
use crate::description::{DsmcScheme, RunDescription, RunSection};
use crate::driver::Driven;
use crate::error::{positive, Error, Result};
use crate::validate::{Plan, Stop};
use gas::driving::Drive;
use gas::dsmc::{HomogeneousSnapshot, Scheme, SpatialOptions, SpatialSnapshot, StepSize};
use gas::parallel::Communicator;
use gas::{Checkpoint, Engine, HomogeneousDsmc, SpatialDsmc, System};
use restitution::Restitution;
use std::sync::Arc;

/// What each scheme can do: all have point particles, rough ones too, and no collapse; the
/// spatial one has positions (and tracks them, on one rank); the blocks and the spatial
/// scheme spread over ranks; the blocks drive.
pub(super) fn abilities(scheme: DsmcScheme) -> Abilities {
    Abilities {
        positions: scheme == DsmcScheme::Spatial,
        point_particles: true,
        ranks: scheme != DsmcScheme::Exact,
        driving: match scheme {
            DsmcScheme::Blocks => DrivingTimes::AtSteps,
            _ => DrivingTimes::Never,
        },
        contacts: false,
        time_step: match scheme {
            DsmcScheme::Exact => TimeStep::None,
            _ => TimeStep::Collisions,
        },
        collapse: false,
        baths: false,
        species_materials: true,
        walls: scheme == DsmcScheme::Spatial,
        shear: true,
        stress: true,
        displacements: scheme == DsmcScheme::Spatial,
        rotation: true,
    }
}

/// The engine and options of the `[run]` section.
pub(super) fn spec(description: &RunDescription, stop: Stop) -> Result<EngineSpec> {
    super::refuse_foreign_keys(description)?;
    let r = &description.run;
    let spec = scheme_spec(r, description.system.particles)?;
    check_time_step(r, stop)?;
    Ok(spec)
}

fn scheme_spec(r: &RunSection, particles: usize) -> Result<EngineSpec> {
    let step = match (r.collisions_per_step, r.time_step) {
        (None, None) => StepSize::Auto,
        (Some(c), None) => {
            if !(gas::dsmc::MIN_COLLISIONS_PER_STEP..=100.0).contains(&c) {
                return Err(Error::out_of_range(
                    "run.collisions_per_step",
                    c,
                    "1e-4 <= value <= 100",
                ));
            }
            StepSize::CollisionsPerParticle(c)
        }
        (None, Some(dt)) => StepSize::Fixed(positive("run.time_step", dt)?),
        (Some(_), Some(_)) => {
            return Err(Error::input(
                "run.time_step",
                "give at most one of run.collisions_per_step and run.time_step",
            ))
        }
    };
    let scheme = r.dsmc_scheme.unwrap_or(DsmcScheme::Blocks);
    let exclusive = |key: &str, given: bool| -> Result<()> {
        if given {
            Err(Error::input(
                key,
                format!("not used by run.dsmc_scheme = \"{}\"", scheme.name()),
            ))
        } else {
            Ok(())
        }
    };
    match scheme {
        DsmcScheme::Blocks => {
            exclusive("run.collision_cell_width", r.collision_cell_width.is_some())?;
            exclusive("run.particle_weight", r.particle_weight.is_some())?;
            let block_size = r.block_size.unwrap_or(gas::dsmc::DEFAULT_BLOCK_SIZE);
            if !(2..=u32::MAX as usize).contains(&block_size) {
                return Err(Error::out_of_range(
                    "run.block_size",
                    block_size,
                    "2 <= block_size <= 2^32 - 1",
                ));
            }
            Ok(EngineSpec::HomogeneousDsmc(Scheme::Blocks {
                block_size,
                step,
            }))
        }
        DsmcScheme::Exact => {
            exclusive("run.block_size", r.block_size.is_some())?;
            exclusive("run.collision_cell_width", r.collision_cell_width.is_some())?;
            exclusive("run.particle_weight", r.particle_weight.is_some())?;
            exclusive("run.collisions_per_step", r.collisions_per_step.is_some())?;
            exclusive("run.time_step", r.time_step.is_some())?;
            Ok(EngineSpec::HomogeneousDsmc(Scheme::Exact))
        }
        DsmcScheme::Spatial => {
            exclusive("run.block_size", r.block_size.is_some())?;
            let cell_width = r
                .collision_cell_width
                .map(|w| positive("run.collision_cell_width", w))
                .transpose()?;
            if let Some(weight) = r.particle_weight {
                particle_weight(weight, particles)?;
            }
            Ok(EngineSpec::SpatialDsmc(SpatialOptions { cell_width, step }))
        }
    }
}

/// The largest `run.particle_weight`: coarser DSMC than 1e6 physical particles per
/// simulated one resolves nothing of a granular gas.
const MAX_PARTICLE_WEIGHT: f64 = 1e6;

/// `run.particle_weight` F: 0 < F <= 1e6, and the box holds at least two physical
/// particles (N F >= 2).
fn particle_weight(weight: f64, particles: usize) -> Result<f64> {
    let smallest = 2.0 / particles as f64;
    if weight.is_finite() && (smallest..=MAX_PARTICLE_WEIGHT).contains(&weight) {
        Ok(weight)
    } else {
        Err(Error::out_of_range(
            "run.particle_weight",
            weight,
            &format!("2 / system.particles = {smallest:e} <= weight <= 1e6"),
        ))
    }
}

/// The most DSMC steps a run with a fixed `run.time_step` may take.
const MAX_STEPS: f64 = 1e8;

/// A fixed DSMC time step: a bounded number of steps to `run.end_time`. With a stop by
/// collisions the number of steps is unbounded (a cooling gas collides ever more slowly:
/// reaching C collisions per particle at a constant restitution takes a time exponential
/// in C), so that combination is refused.
fn check_time_step(r: &RunSection, stop: Stop) -> Result<()> {
    let Some(dt) = r.time_step else {
        return Ok(());
    };
    match stop {
        Stop::Time(end) if end / dt <= MAX_STEPS => Ok(()),
        Stop::Time(end) => Err(Error::out_of_range(
            "run.time_step",
            dt,
            &format!(
                "run.end_time / time_step <= 1e8 steps, i.e. time_step >= {:e}",
                end / MAX_STEPS
            ),
        )),
        Stop::CollisionsPerParticle(_) => Err(Error::input(
            "run.time_step",
            "a fixed time step with run.collisions_per_particle: a cooling gas collides ever \
             more slowly, so the steps to reach the collisions are unbounded; give run.end_time, \
             or run.collisions_per_step (a step that follows the collision rate)",
        )),
    }
}

/// The homogeneous engine of `system` over the ranks of `comm`.
pub(super) fn homogeneous<const D: usize>(
    system: System<D>,
    setup: Setup,
    scheme: Scheme,
    comm: &Arc<dyn Communicator>,
) -> gas::Result<HomogeneousDsmc<D>> {
    HomogeneousDsmc::distributed(
        system,
        setup.packing_fraction,
        setup.law,
        setup.seed,
        scheme,
        comm.clone(),
    )
}

/// The spatial engine of `system` over the ranks of `comm`.
pub(super) fn spatial<const D: usize>(
    system: System<D>,
    setup: Setup,
    options: SpatialOptions,
    comm: &Arc<dyn Communicator>,
) -> gas::Result<SpatialDsmc<D>> {
    SpatialDsmc::distributed(
        system,
        setup.packing_fraction,
        setup.law,
        setup.seed,
        options,
        comm.clone(),
    )
}

/// The engine's setup from the plan.
fn setup(plan: &Plan, law: Box<dyn Restitution>) -> Setup {
    let s = &plan.description.system;
    Setup {
        law,
        packing_fraction: plan.description.packing_fraction(),
        seed: s.seed,
        baths: None,
    }
}

/// The driving of the plan, at every step.
fn drive(plan: &Plan) -> Option<Drive> {
    plan.driving.map(|driving| Drive {
        driving,
        interval: None,
        seed: plan.description.system.seed,
    })
}

pub(super) fn start_homogeneous<const D: usize>(
    plan: &Plan,
    system: System<D>,
    law: Box<dyn Restitution>,
    scheme: Scheme,
    comm: &Arc<dyn Communicator>,
) -> Result<Box<dyn Driven<D>>> {
    let mut engine =
        homogeneous(system, setup(plan, law), scheme, comm).map_err(ranks_or_system)?;
    engine
        .set_driving(drive(plan))
        .map_err(|e| Error::input("driving", e))?;
    Ok(Box::new(engine))
}

pub(super) fn start_spatial<const D: usize>(
    plan: &Plan,
    system: System<D>,
    law: Box<dyn Restitution>,
    options: SpatialOptions,
    comm: &Arc<dyn Communicator>,
) -> Result<Box<dyn Driven<D>>> {
    let mut engine = spatial(system, setup(plan, law), options, comm).map_err(ranks_or_system)?;
    enclose(&mut engine, plan)?;
    Ok(Box::new(engine))
}

/// Puts the spatial engine's gas into the plan's walls and gravity, if any.
fn enclose<const D: usize>(engine: &mut SpatialDsmc<D>, plan: &Plan) -> Result<()> {
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

/// The homogeneous engine of a check-point, on the ranks of `comm`, driven as the plan says.
pub(super) fn restore_homogeneous<const D: usize>(
    plan: &Plan,
    law: Box<dyn Restitution>,
    sections: &Sections,
    comm: &Arc<dyn Communicator>,
) -> Result<Box<dyn Driven<D>>> {
    let state: HomogeneousSnapshot<D> = sections.engine()?;
    let EngineSpec::HomogeneousDsmc(scheme) = plan.engine else {
        return Err(state_error(sections)("another engine".into()));
    };
    check_state(plan, &state.system, &state, state.options == scheme, false)
        .map_err(state_error(sections))?;
    let mut engine = HomogeneousDsmc::restore_distributed(state, law, comm.clone())
        .map_err(|e| state_error(sections)(e.to_string()))?;
    engine
        .set_driving(drive(plan))
        .map_err(|e| Error::input("driving", e))?;
    Ok(Box::new(engine))
}

/// The spatial engine of a check-point, on the ranks of `comm`.
pub(super) fn restore_spatial<const D: usize>(
    plan: &Plan,
    law: Box<dyn Restitution>,
    sections: &Sections,
    comm: &Arc<dyn Communicator>,
) -> Result<Box<dyn Driven<D>>> {
    let state: SpatialSnapshot<D> = sections.engine()?;
    let EngineSpec::SpatialDsmc(options) = plan.engine else {
        return Err(state_error(sections)("another engine".into()));
    };
    check_state(plan, &state.system, &state, state.options == options, true)
        .map_err(state_error(sections))?;
    if state.tail.walls.as_ref().map(|w| w.tallies.len())
        != (!plan.walls.is_empty()).then_some(plan.walls.len())
    {
        return Err(state_error(sections)(
            "the walls differ from [[wall]]".into(),
        ));
    }
    let mut engine = if comm.size() > 1 {
        SpatialDsmc::restore_distributed(state, law, comm.clone()).map_err(ranks_or_system)?
    } else {
        SpatialDsmc::restore(state, law).map_err(|e| state_error(sections)(e.to_string()))?
    };
    enclose(&mut engine, plan)?;
    Ok(Box::new(engine))
}

/// What both DSMC snapshots share for the check against the plan.
trait Snapshot {
    fn packing_fraction(&self) -> f64;
    fn seed(&self) -> u64;
    fn rotation(&self) -> Option<&gas::rotation::Rotation>;
}

impl<const D: usize> Snapshot for HomogeneousSnapshot<D> {
    fn packing_fraction(&self) -> f64 {
        self.packing_fraction
    }
    fn seed(&self) -> u64 {
        self.seed
    }
    fn rotation(&self) -> Option<&gas::rotation::Rotation> {
        self.tail.rotation.as_ref()
    }
}

impl<const D: usize> Snapshot for SpatialSnapshot<D> {
    fn packing_fraction(&self) -> f64 {
        self.packing_fraction
    }
    fn seed(&self) -> u64 {
        self.seed
    }
    fn rotation(&self) -> Option<&gas::rotation::Rotation> {
        self.tail.rotation.as_ref()
    }
}

/// Why a DSMC state (its particles `system`, its options those of the plan or not) cannot
/// be a state of the run of `plan`, if it cannot. The homogeneous engine's box is its
/// volume's cube root, not an initial box: `in_box` only for the spatial engine.
fn check_state<const D: usize>(
    plan: &Plan,
    system: &System<D>,
    state: &impl Snapshot,
    same_options: bool,
    in_box: bool,
) -> std::result::Result<(), String> {
    super::initial::particles(plan, system)?;
    let s = &plan.description.system;
    let phi = plan.description.packing_fraction();
    if !same_options || state.packing_fraction() != phi || state.seed() != s.seed {
        return Err("the DSMC options, packing fraction or seed differ from the run file's".into());
    }
    if in_box {
        super::initial::box_side(plan, system)?;
    }
    super::initial::no_energy_gained(plan, system, None, state.rotation())
}
