//! Checks a run description before anything runs, and turns it into a [`Plan`]: typed
//! choices, every default resolved once (a one-species gas is a one-entry species list),
//! every key in range, the keys each law and engine needs present and the keys of other
//! laws and engines refused. One module per concern: `[system]` ([`system`]), `[collision]`
//! ([`law`], the materials in [`material`]), `[run]` ([`run`]; the engine's own keys in
//! [`crate::engines`]), `[driving]` ([`driving`]), `[[wall]]` ([`walls`]); `[output]` in
//! [`crate::space`]. What an engine can do comes from [`crate::engines::Abilities`]. The
//! law's own parameter ranges (restitution, damping ratio, beta, modes, the form's order,
//! the table) are checked by the law itself when [`crate::law::build`] builds it, which
//! [`crate::Simulation::new`] does before anything runs. Errors name the key and the
//! allowed range.

mod driving;
mod field;
mod initial;
mod law;
pub(crate) mod material;
mod rough;
mod run;
mod shear;
mod system;
mod walls;

pub use crate::engines::EngineSpec;
pub use field::GravitySpec;
pub(crate) use initial::Source;
pub use initial::{Initial, InitialReport};
pub use law::{LawSpec, StochasticTable};
pub(crate) use material::material;
pub use rough::RoughSpec;
pub use walls::{wall_impact_speed, WallLaw, WallSpec, WallSpecKind};

use crate::description::{RunDescription, Spacing};
use crate::engines::{self, DrivingTimes};
use crate::error::{Error, Result};

/// How far a run goes: collisions per particle or time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stop {
    CollisionsPerParticle(f64),
    Time(f64),
}

impl Stop {
    /// The end value, in the unit of the criterion.
    pub fn end(self) -> f64 {
        match self {
            Stop::CollisionsPerParticle(c) => c,
            Stop::Time(t) => t,
        }
    }

    /// The key that set it.
    pub fn key(self) -> &'static str {
        match self {
            Stop::CollisionsPerParticle(_) => "run.collisions_per_particle",
            Stop::Time(_) => "run.end_time",
        }
    }
}

/// One kind of particle of a run, every default resolved: an entry of `system.species`, or
/// the one kind of `system.diameter` and `system.mass` (1 unless given).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Species {
    pub diameter: f64,
    pub mass: f64,
    /// Number fraction, normalized over the species.
    pub fraction: f64,
    /// Particles of this kind (`system.particles` split by the fractions).
    pub count: usize,
}

impl Species {
    pub fn radius(&self) -> f64 {
        0.5 * self.diameter
    }
}

/// A checked run: the description (normalized) and its typed reading.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    pub description: RunDescription,
    /// The particles, one entry per species (never empty).
    pub species: Vec<Species>,
    /// Physical particles per simulated one (`run.particle_weight`; 1 unless given).
    pub particle_weight: f64,
    pub stop: Stop,
    pub law: LawSpec,
    pub engine: EngineSpec,
    /// Contact duration of the TC model, if on.
    pub tc: Option<f64>,
    /// Driving (`[driving]`), if on.
    pub driving: Option<gas::driving::Driving>,
    /// The time between applications of the driving of an engine that drives at discrete
    /// times (given, or the default of [`crate::species::default_driving_interval`]).
    pub driving_interval: Option<f64>,
    /// The walls of a container (`[[wall]]`; empty: the periodic box).
    pub walls: Vec<WallSpec>,
    /// Gravity (`[field]`), if on.
    pub gravity: Option<GravitySpec>,
    /// `[shear]`: the uniform shear flow.
    pub shear: Option<gas::shear::Shear>,
    /// The pressure tensor is measured (`output.pressure` or `[shear]`): the engine sums
    /// the tensor virial.
    pub pressure_tensor: bool,
    /// `output.msd`: the engine tracks the particles' displacements.
    pub msd: bool,
    /// Rough particles (`collision.tangential_restitution` > -1).
    pub rough: Option<RoughSpec>,
    /// The particles of `system.initial` (a file's, another run's, given in code), checked;
    /// None for a placement, and for a check-point's plan (its state holds them).
    pub initial: Option<std::sync::Arc<Initial>>,
    /// What a user should know before the run starts (its estimated work, when large).
    pub notes: Vec<String>,
}

/// Checks every key of `description` and returns the plan of the run (reading the
/// particles of `system.initial`, if any).
pub fn validate(description: &RunDescription) -> Result<Plan> {
    validate_from(description, Source::Description)
}

/// [`validate`] for a description with `system.initial = {}` and its particles given in
/// code (Python's arrays), checked as a file's.
pub fn validate_with(
    description: &RunDescription,
    particles: crate::particles::Configuration,
) -> Result<Plan> {
    validate_from(description, Source::Given(particles))
}

/// The plan of `description`, its `system.initial` read from `source`.
pub(crate) fn validate_from(description: &RunDescription, source: Source) -> Result<Plan> {
    let resolved = material::resolve_named_material(description)?;
    let space = engines::abilities_of(&resolved);
    let (resolved, initial) = initial::resolve(&resolved, source, &space)?;
    let description = &resolved;
    let species = system::check_system(description)?;
    let abilities = engines::abilities_of(description);
    let law = law::law_spec(description, &species, &abilities)?;
    check_engine_can(description, &abilities)?;
    let r = &description.run;
    let stop = run::stop(r)?;
    let engine = engines::spec(description, &species, stop)?;
    let abilities = engine.abilities();
    system::check_box_engine(description, &abilities, &species)?;
    run::check_histograms(r, stop)?;
    crate::space::check_output(description, &abilities)?;
    run::check_ranks(r, &abilities)?;
    let (driving, driving_interval) = driving::driving_spec(description, &abilities, &law)?;
    let walls = walls::walls_spec(description, &abilities, &species)?;
    let gravity = field::gravity_spec(description, &abilities, &walls, &species)?;
    let shear = shear::shear_spec(description, &abilities, &walls, &species)?;
    let pressure_tensor =
        shear.is_some() || description.output.as_ref().is_some_and(|o| o.pressure);
    let msd = shear::msd_spec(description, &abilities)?;
    let rough = rough::rough_spec(description, &abilities, &species)?;
    let c = &description.collision;
    let mut description = description.clone();
    description.normalize();
    let mut plan = Plan {
        particle_weight: description.run.particle_weight.unwrap_or(1.0),
        description,
        species,
        stop,
        law,
        engine,
        tc: c.tc.filter(|&tc| tc > 0.0),
        driving,
        driving_interval,
        walls,
        gravity,
        shear,
        pressure_tensor,
        msd,
        rough,
        initial,
        notes: Vec::new(),
    };
    if plan.driving.is_some()
        && plan.driving_interval.is_none()
        && abilities.driving == DrivingTimes::AtIntervals
    {
        plan.driving_interval = Some(crate::species::default_driving_interval(&plan));
    }
    engines::check_work(&mut plan)?;
    initial::finish(&mut plan)?;
    Ok(plan)
}

/// The keys of `[collision]` and `[system]` that need an ability of the engine: the TC
/// model (inelastic collapse) and species of their own materials.
fn check_engine_can(description: &RunDescription, abilities: &engines::Abilities) -> Result<()> {
    let c = &description.collision;
    let engine = engines::kind_name(description.run.engine);
    if let Some(tc) = c.tc {
        if !(tc.is_finite() && tc >= 0.0) {
            return Err(Error::out_of_range(
                "collision.tc",
                tc,
                "a finite number >= 0 (0: off)",
            ));
        }
        if tc > 0.0 && !abilities.collapse {
            return Err(Error::input(
                "collision.tc",
                format!(
                    "the TC model is for run.engine = {} (\"{engine}\" has no inelastic \
                     collapse)",
                    engines::kinds_that(|a| a.collapse)
                ),
            ));
        }
    }
    if abilities.species_materials {
        return Ok(());
    }
    if let Some(i) = description
        .system
        .species
        .iter()
        .flatten()
        .position(|x| x.has_material())
    {
        return Err(Error::input(
            format!("system.species[{i}].young"),
            format!(
                "run.engine = \"{engine}\" takes one material (collision.young, poisson, \
                 dissipative_constant); species of their own materials run with {}",
                engines::kinds_that(|a| a.species_materials)
            ),
        ));
    }
    Ok(())
}

/// The range of a diameter, mass or temperature (any unit system): wide enough for SI and
/// scaled units alike, narrow enough that v^4 ~ (T/m)^2 (the Sonine coefficient a2) and
/// the box volume of 1e8 spheres stay finite in f64.
const SCALE: (f64, f64) = (1e-30, 1e30);

/// The most dilute gas: its box (N d^D / phi) stays finite for every allowed N and d.
const MIN_PACKING: f64 = 1e-12;

/// `x` within [`SCALE`].
fn in_scale(key: &str, x: f64) -> Result<f64> {
    if (SCALE.0..=SCALE.1).contains(&x) {
        Ok(x)
    } else {
        Err(Error::out_of_range(
            key,
            crate::output::number(x),
            "1e-30 <= value <= 1e30",
        ))
    }
}

impl Plan {
    /// Whether the samples are log-spaced.
    pub fn log_spacing(&self) -> bool {
        self.description.run.spacing == Spacing::Log
    }

    /// The (radius, mass) of each species.
    pub fn kinds(&self) -> Vec<(f64, f64)> {
        self.species.iter().map(|x| (x.radius(), x.mass)).collect()
    }

    /// An upper bound of every normal impact speed of the run: a cooling gas never gains
    /// energy, so no pair can approach faster than with all the initial kinetic energy,
    /// N (D/2) T0, in its relative motion at the smallest reduced mass (half the smallest
    /// mass): g <= (2 E / mu)^(1/2) = (2 N D T0 / m_min)^(1/2). Rough particles add
    /// the rotational energy N d_rot T_rot0 / 2, which collisions turn into translation.
    pub fn max_impact_speed(&self) -> f64 {
        let s = &self.description.system;
        let lightest = self
            .species
            .iter()
            .map(|x| x.mass)
            .fold(f64::INFINITY, f64::min);
        let rotational = self.rough.as_ref().map_or(0.0, |r| {
            gas::rotation::rotational_dimension(s.dimension as usize) as f64 * r.temperature
        });
        let energy_per_particle = f64::from(s.dimension) * s.temperature + rotational;
        (2.0 * s.particles as f64 * energy_per_particle / lightest).sqrt()
    }
}
