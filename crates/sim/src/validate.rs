//! Checks a run description before anything runs, and turns it into a [`Plan`]: typed
//! choices, every key of `[system]` and `[run]` in range, the keys each law needs present
//! and the stochastic keys only with the stochastic law. The law's own parameter ranges
//! (restitution, damping ratio, beta, modes, the form's order, the table) are checked by the
//! law itself when [`crate::law::build`] builds it, which [`crate::Simulation::new`] does
//! before anything runs. Errors name the key and the allowed range.

mod driving;
mod material;

use crate::description::{
    species, Distribution, DsmcScheme, EngineKind, LawKind, RestitutionValue, RunDescription,
    RunSection, Spacing,
};
use crate::error::{positive, Error, Result};
use gas::dsmc::{Scheme, SpatialOptions, StepSize};
use gas::soft::contact::ViscoelasticMaterial;
use gas::SoftSphereOptions;
use material::{material, species_betas, viscoelastic_beta};
use restitution::{Criterion, FormName};
use std::path::PathBuf;

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

/// The collision law, checked (built by [`crate::law::build`]).
#[derive(Debug, Clone, PartialEq)]
pub enum LawSpec {
    Constant(f64),
    /// A constant restitution per pair of species: kinds (radius, mass) in the order of
    /// `system.species` and the symmetric matrix.
    ConstantPairs {
        kinds: Vec<(f64, f64)>,
        matrix: Vec<Vec<f64>>,
    },
    Dashpot {
        damping_ratio: f64,
        criterion: Criterion,
    },
    Viscoelastic {
        beta: f64,
        form: FormName,
    },
    /// A viscoelastic mixture: kinds (radius, mass) in the order of `system.species` and
    /// beta per pair from the species' materials.
    ViscoelasticPairs {
        kinds: Vec<(f64, f64)>,
        betas: Vec<Vec<f64>>,
        form: FormName,
    },
    Stochastic {
        modes: u32,
        distribution: StochasticTable,
        bath_temperature: f64,
    },
}

/// Where a stochastic law draws eps^2 from.
#[derive(Debug, Clone, PartialEq)]
pub enum StochasticTable {
    Glauber,
    Tabulated(PathBuf),
}

/// The engine and its options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EngineSpec {
    EventDriven,
    HomogeneousDsmc(Scheme),
    SpatialDsmc(SpatialOptions),
    SoftSphere(SoftSphereOptions, ViscoelasticMaterial),
}

/// Whether the engine spreads over ranks: the spatial DSMC, and the homogeneous one's
/// block scheme (the exact scheme is one serial process).
pub fn spreads_over_ranks(engine: &EngineSpec) -> bool {
    matches!(
        engine,
        EngineSpec::SpatialDsmc(_) | EngineSpec::HomogeneousDsmc(Scheme::Blocks { .. })
    )
}

/// A checked run: the description (normalized) and its typed reading.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    pub description: RunDescription,
    pub stop: Stop,
    pub law: LawSpec,
    pub engine: EngineSpec,
    /// Contact duration of the TC model, if on.
    pub tc: Option<f64>,
    /// Driving (`[driving]`), if on.
    pub driving: Option<gas::driving::Driving>,
    /// The event-driven engine's time between applications of the driving.
    pub driving_interval: Option<f64>,
}

/// Checks every key of `description` and returns the plan of the run.
pub fn validate(description: &RunDescription) -> Result<Plan> {
    let resolved = material::resolve_named_material(description)?;
    let description = &resolved;
    check_system(description)?;
    let law = law_spec(description)?;
    let c = &description.collision;
    if let Some(tc) = c.tc {
        if !(tc.is_finite() && tc >= 0.0) {
            return Err(Error::out_of_range(
                "collision.tc",
                tc,
                "a finite number >= 0 (0: off)",
            ));
        }
    }
    let r = &description.run;
    if r.steps_per_contact.is_some() && r.engine != EngineKind::SoftSphere {
        return Err(Error::input(
            "run.steps_per_contact",
            "only for run.engine = \"soft-sphere\"",
        ));
    }
    let engine = match r.engine {
        EngineKind::SoftSphere => soft_sphere_spec(description)?,
        EngineKind::EventDriven => {
            refuse_dsmc_keys(r, true)?;
            EngineSpec::EventDriven
        }
        EngineKind::Dsmc => {
            if c.tc.is_some_and(|tc| tc > 0.0) {
                return Err(Error::input(
                    "collision.tc",
                    "the TC model is for run.engine = \"event-driven\" (DSMC has no collapse)",
                ));
            }
            dsmc_spec(r, description.system.particles)?
        }
    };
    if !(2..=1_000_000).contains(&r.samples) {
        return Err(Error::out_of_range(
            "run.samples",
            r.samples,
            "2 <= samples <= 1e6",
        ));
    }
    let stop = match (r.collisions_per_particle, r.end_time) {
        (Some(c), None) => Stop::CollisionsPerParticle(positive("run.collisions_per_particle", c)?),
        (None, Some(t)) => Stop::Time(positive("run.end_time", t)?),
        _ => {
            return Err(Error::input(
                "run.collisions_per_particle",
                "give exactly one of run.collisions_per_particle and run.end_time",
            ))
        }
    };
    check_histograms(r, stop)?;
    if let EngineSpec::SoftSphere(options, material) = &engine {
        check_soft_sphere_steps(description, options, material, stop)?;
    }
    crate::space::check_output(description, &engine)?;
    if r.engine == EngineKind::Dsmc {
        check_time_step(r, stop)?;
    }
    if let Some(ranks) = r.ranks {
        if !(1..=1_000_000).contains(&ranks) {
            return Err(Error::out_of_range("run.ranks", ranks, "1 <= ranks <= 1e6"));
        }
        if ranks > 1 && !spreads_over_ranks(&engine) {
            return Err(Error::input(
                "run.ranks",
                format!("several ranks: {}", crate::parallel::SPREADING),
            ));
        }
    }
    let (driving, driving_interval) = driving::driving_spec(description, &engine, &law)?;
    let mut description = description.clone();
    description.normalize();
    let mut plan = Plan {
        description,
        stop,
        law,
        engine,
        tc: c.tc.filter(|&tc| tc > 0.0),
        driving,
        driving_interval,
    };
    if plan.driving.is_some()
        && plan.driving_interval.is_none()
        && plan.engine == EngineSpec::EventDriven
    {
        plan.driving_interval = Some(crate::species::default_driving_interval(&plan));
    }
    Ok(plan)
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

/// `[system]`.
fn check_system(description: &RunDescription) -> Result<()> {
    let s = &description.system;
    if !(1..=3).contains(&s.dimension) {
        return Err(Error::out_of_range(
            "system.dimension",
            s.dimension,
            "1, 2 or 3",
        ));
    }
    if s.particles < 2 || s.particles > 100_000_000 {
        return Err(Error::out_of_range(
            "system.particles",
            s.particles,
            "2 <= N <= 1e8",
        ));
    }
    let max_phi = gas::init::packing_limit(s.dimension as usize);
    if !(s.packing_fraction >= MIN_PACKING && s.packing_fraction <= max_phi) {
        let allowed = format!(
            "{MIN_PACKING:e} <= phi <= {max_phi} in {} dimensions",
            s.dimension
        );
        return Err(Error::out_of_range(
            "system.packing_fraction",
            s.packing_fraction,
            &allowed,
        ));
    }
    match &s.species {
        None => {
            in_scale("system.diameter", s.diameter.unwrap_or(1.0))?;
            in_scale("system.mass", s.mass.unwrap_or(1.0))?;
        }
        Some(_) if s.diameter.is_some() || s.mass.is_some() => {
            return Err(Error::input(
                "system.species",
                "give either system.species or system.diameter/system.mass, not both",
            ));
        }
        Some(entries) => {
            if entries.is_empty() {
                return Err(Error::input("system.species", "give at least one species"));
            }
            for (k, x) in entries.iter().enumerate() {
                in_scale(&format!("system.species[{k}].diameter"), x.diameter)?;
                in_scale(&format!("system.species[{k}].mass"), x.mass)?;
                positive(&format!("system.species[{k}].fraction"), x.fraction)?;
                // Particles are told apart by diameter and mass (species.csv, the DSMC
                // tables): two entries alike would be one species counted twice.
                if let Some(j) = entries[..k]
                    .iter()
                    .position(|y| y.diameter == x.diameter && y.mass == x.mass)
                {
                    return Err(Error::input(
                        format!("system.species[{k}]"),
                        format!(
                            "the diameter and mass of system.species[{j}]: species must differ \
                             in diameter or mass (merge the two entries)"
                        ),
                    ));
                }
            }
            gas::init::species_counts(s.particles, &species(entries))
                .map_err(|e| Error::input("system.species", e))?;
        }
    }
    in_scale("system.temperature", s.temperature)?;
    Ok(())
}

/// `[collision]` without the TC model: the law and its keys.
fn law_spec(description: &RunDescription) -> Result<LawSpec> {
    let c = &description.collision;
    let need =
        |key: &str, x: Option<f64>| x.ok_or_else(|| Error::input(key, "missing for this law"));
    // Every key belongs to one law: a key of another law would be recorded and ignored.
    let keys = [
        (
            "collision.restitution",
            c.restitution.is_some(),
            LawKind::Constant,
        ),
        (
            "collision.damping_ratio",
            c.damping_ratio.is_some(),
            LawKind::Dashpot,
        ),
        (
            "collision.criterion",
            c.criterion.is_some(),
            LawKind::Dashpot,
        ),
        ("collision.beta", c.beta.is_some(), LawKind::Viscoelastic),
        ("collision.form", c.form.is_some(), LawKind::Viscoelastic),
        ("collision.young", c.young.is_some(), LawKind::Viscoelastic),
        (
            "collision.poisson",
            c.poisson.is_some(),
            LawKind::Viscoelastic,
        ),
        (
            "collision.dissipative_constant",
            c.dissipative_constant.is_some(),
            LawKind::Viscoelastic,
        ),
        (
            "collision.distribution",
            c.distribution.is_some(),
            LawKind::Stochastic,
        ),
        ("collision.modes", c.modes.is_some(), LawKind::Stochastic),
        (
            "collision.bath_temperature",
            c.bath_temperature.is_some(),
            LawKind::Stochastic,
        ),
        ("collision.table", c.table.is_some(), LawKind::Stochastic),
    ];
    if let Some((key, _, owner)) = keys
        .iter()
        .find(|(_, given, owner)| *given && *owner != c.law)
    {
        return Err(Error::input(
            *key,
            format!(
                "only for law = \"{}\" (this run has law = \"{}\")",
                owner.name(),
                c.law.name()
            ),
        ));
    }
    if c.law != LawKind::Viscoelastic {
        for (i, x) in description.system.species.iter().flatten().enumerate() {
            if x.has_material() {
                return Err(Error::input(
                    format!("system.species[{i}].young"),
                    format!(
                        "a species' material (young, poisson, dissipative_constant) is for \
                         law = \"viscoelastic\" (this run has law = \"{}\")",
                        c.law.name()
                    ),
                ));
            }
        }
    }
    Ok(match c.law {
        LawKind::Constant => {
            let tc = c.tc.is_some_and(|t| t > 0.0);
            let sticking = |key: &str, eps: f64| {
                if eps == 0.0 && description.run.engine == EngineKind::EventDriven && !tc {
                    return Err(Error::out_of_range(
                        key,
                        eps,
                        "0 < restitution <= 1 in an event-driven run (at 0 the spheres stick: \
                         they collide again at once, forever, and time stops); or set \
                         collision.tc, the TC model, or use engine = \"dsmc\"",
                    ));
                }
                Ok(())
            };
            match &c.restitution {
                None => {
                    return Err(Error::input(
                        "collision.restitution",
                        "missing for this law",
                    ))
                }
                Some(RestitutionValue::One(eps)) => {
                    sticking("collision.restitution", *eps)?;
                    LawSpec::Constant(*eps)
                }
                Some(RestitutionValue::PerPair(matrix)) => {
                    let kinds = restitution_matrix(description, matrix)?;
                    for (i, row) in matrix.iter().enumerate() {
                        for (j, &eps) in row.iter().enumerate() {
                            sticking(&format!("collision.restitution[{i}][{j}]"), eps)?;
                        }
                    }
                    LawSpec::ConstantPairs {
                        kinds,
                        matrix: matrix.clone(),
                    }
                }
            }
        }
        LawKind::Dashpot => LawSpec::Dashpot {
            damping_ratio: need("collision.damping_ratio", c.damping_ratio)?,
            criterion: c.criterion.unwrap_or(Criterion::Improved),
        },
        LawKind::Viscoelastic => {
            let form = c.form.unwrap_or(FormName::Fast(Criterion::Improved));
            match species_betas(description)? {
                Some((kinds, betas)) => LawSpec::ViscoelasticPairs { kinds, betas, form },
                None => LawSpec::Viscoelastic {
                    beta: viscoelastic_beta(description)?,
                    form,
                },
            }
        }
        LawKind::Stochastic => stochastic_spec(description)?,
    })
}

/// The keys of `[run]` that only DSMC reads, `time_step` among them if `time_step_too`
/// (soft-sphere MD takes a time step too).
fn refuse_dsmc_keys(r: &RunSection, time_step_too: bool) -> Result<()> {
    for (key, given) in [
        ("run.dsmc_scheme", r.dsmc_scheme.is_some()),
        ("run.block_size", r.block_size.is_some()),
        ("run.collisions_per_step", r.collisions_per_step.is_some()),
        ("run.time_step", time_step_too && r.time_step.is_some()),
        ("run.collision_cell_width", r.collision_cell_width.is_some()),
        ("run.particle_weight", r.particle_weight.is_some()),
    ] {
        if given {
            return Err(Error::input(key, "only for run.engine = \"dsmc\""));
        }
    }
    Ok(())
}

/// Soft-sphere MD: the viscoelastic material, no DSMC keys, no TC model.
fn soft_sphere_spec(description: &RunDescription) -> Result<EngineSpec> {
    let (c, r) = (&description.collision, &description.run);
    refuse_dsmc_keys(r, false)?;
    if c.tc.is_some_and(|tc| tc > 0.0) {
        return Err(Error::input(
            "collision.tc",
            "the TC model is for run.engine = \"event-driven\" (soft spheres have no collapse)",
        ));
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
            "run.engine = \"soft-sphere\" takes one material (collision.young, poisson, \
             dissipative_constant); species of their own materials run with \"event-driven\" \
             or \"dsmc\"",
        ));
    }
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
        let contact = contact_duration(description, &material)
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
    Ok(EngineSpec::SoftSphere(options, material))
}

/// The contact duration the soft-sphere time step resolves, for the spheres and the
/// temperature of `[system]` ([`gas::soft::shortest_contact_duration`]).
pub(crate) fn contact_duration(
    description: &RunDescription,
    material: &ViscoelasticMaterial,
) -> gas::Result<f64> {
    let s = &description.system;
    let kinds: Vec<(f64, f64)> = match &s.species {
        Some(species) => species.iter().map(|x| (0.5 * x.diameter, x.mass)).collect(),
        None => vec![(0.5 * s.diameter.unwrap_or(1.0), s.mass.unwrap_or(1.0))],
    };
    gas::soft::shortest_contact_duration(&kinds, s.temperature, material)
}

/// The soft-sphere time steps allowed for a contact duration: 4 to 1e6 steps per contact
/// (as steps_per_contact), finest first.
pub(crate) fn time_step_range(contact: f64) -> (f64, f64) {
    (contact / 1e6, contact / 4.0)
}

/// A soft-sphere run takes at most 1e8 time steps: end_time / dt, or, to reach
/// collisions_per_particle, at least that many over the initial Enskog collision frequency
/// (a cooling gas collides ever more slowly). A very stiff material in the run's units
/// (young = 1e19 with sigma = m = T = 1) would otherwise run for days.
fn check_soft_sphere_steps(
    description: &RunDescription,
    options: &SoftSphereOptions,
    material: &ViscoelasticMaterial,
    stop: Stop,
) -> Result<()> {
    let key = match stop {
        Stop::Time(_) => "run.end_time",
        Stop::CollisionsPerParticle(_) => "run.collisions_per_particle",
    };
    let contact = contact_duration(description, material).map_err(|e| Error::input(key, e))?;
    let dt = options
        .time_step
        .unwrap_or(contact / options.steps_per_contact);
    let s = &description.system;
    let (diameter, mass) = match &s.species {
        Some(species) => (species[0].diameter, species[0].mass),
        None => (s.diameter.unwrap_or(1.0), s.mass.unwrap_or(1.0)),
    };
    let time = match stop {
        Stop::Time(end) => end,
        Stop::CollisionsPerParticle(c) => {
            let phi = s.packing_fraction;
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

/// Giese's stochastic law: event-driven only, `modes`, `distribution` and, tabulated,
/// `table`.
fn stochastic_spec(description: &RunDescription) -> Result<LawSpec> {
    let c = &description.collision;
    if description.run.engine != EngineKind::EventDriven {
        return Err(Error::input(
            "run.engine",
            "law = \"stochastic\" runs with engine = \"event-driven\" (Giese's ED + Monte Carlo)",
        ));
    }
    let bath_temperature = c.bath_temperature.unwrap_or(0.0);
    // 0 (cold baths) or within the scale of a temperature (the baths feed their energy to
    // the translation: 1e300 would overflow v^2).
    if bath_temperature != 0.0 && !(SCALE.0..=SCALE.1).contains(&bath_temperature) {
        return Err(Error::out_of_range(
            "collision.bath_temperature",
            crate::output::number(bath_temperature),
            "0, or 1e-30 <= value <= 1e30",
        ));
    }
    let modes = c
        .modes
        .ok_or_else(|| Error::input("collision.modes", "missing for law = \"stochastic\""))?;
    let distribution = match c.distribution.unwrap_or(Distribution::Glauber) {
        Distribution::Glauber => {
            if c.table.is_some() {
                return Err(Error::input(
                    "collision.table",
                    "only for distribution = \"tabulated\"",
                ));
            }
            StochasticTable::Glauber
        }
        Distribution::Tabulated => {
            let path = c.table.as_deref().ok_or_else(|| {
                Error::input("collision.table", "missing: a table from `haff rods table`")
            })?;
            StochasticTable::Tabulated(PathBuf::from(path))
        }
    };
    Ok(LawSpec::Stochastic {
        modes,
        distribution,
        bath_temperature,
    })
}

/// The DSMC engine and options of the `[run]` section.
fn dsmc_spec(r: &RunSection, particles: usize) -> Result<EngineSpec> {
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

/// `run.histogram_at` and `run.histogram_bins`.
fn check_histograms(r: &RunSection, stop: Stop) -> Result<()> {
    if let Some(bins) = r.histogram_bins {
        if !(4..=10_000).contains(&bins) {
            return Err(Error::out_of_range(
                "run.histogram_bins",
                bins,
                "4 <= bins <= 10000",
            ));
        }
    }
    let Some(at) = &r.histogram_at else {
        return Ok(());
    };
    let end = stop.end();
    if at.len() > 10_000 {
        return Err(Error::out_of_range(
            "run.histogram_at",
            format!("a list of {}", at.len()),
            "at most 10000 values",
        ));
    }
    for &x in at {
        if !(0.0..=end).contains(&x) {
            let allowed = format!("0 <= value <= {end} (the end of the run, {})", stop.key());
            return Err(Error::out_of_range("run.histogram_at", x, &allowed));
        }
    }
    let mut sorted = at.clone();
    sorted.sort_by(f64::total_cmp);
    if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
        return Err(Error::input(
            "run.histogram_at",
            format!("{} appears twice", w[0]),
        ));
    }
    Ok(())
}

impl Plan {
    /// Whether the samples are log-spaced.
    pub fn log_spacing(&self) -> bool {
        self.description.run.spacing == Spacing::Log
    }

    /// An upper bound of every normal impact speed of the run: a cooling gas never gains
    /// energy, so no pair can approach faster than with all the initial kinetic energy,
    /// N (D/2) T0, in its relative motion at the smallest reduced mass (half the smallest
    /// mass): g <= (2 E / mu)^(1/2) = (2 N D T0 / m_min)^(1/2).
    pub fn max_impact_speed(&self) -> f64 {
        let s = &self.description.system;
        let lightest = match &s.species {
            None => s.mass.unwrap_or(1.0),
            Some(entries) => entries.iter().map(|x| x.mass).fold(f64::INFINITY, f64::min),
        };
        (2.0 * s.particles as f64 * f64::from(s.dimension) * s.temperature / lightest).sqrt()
    }
}

/// Checks a matrix `collision.restitution` against `system.species`: one row and column
/// per species, values in [0, 1], symmetric; returns the kinds (radius, mass).
fn restitution_matrix(
    description: &RunDescription,
    matrix: &[Vec<f64>],
) -> Result<Vec<(f64, f64)>> {
    let Some(species) = &description.system.species else {
        return Err(Error::input(
            "collision.restitution",
            "a matrix needs system.species (one row per species); give one number otherwise",
        ));
    };
    let s = species.len();
    if matrix.len() != s || matrix.iter().any(|row| row.len() != s) {
        return Err(Error::input(
            "collision.restitution",
            format!("a {s} x {s} matrix: one row and column per species of system.species"),
        ));
    }
    for (i, row) in matrix.iter().enumerate() {
        for (j, &eps) in row.iter().enumerate() {
            let key = format!("collision.restitution[{i}][{j}]");
            if !(eps.is_finite() && (0.0..=1.0).contains(&eps)) {
                return Err(Error::out_of_range(&key, eps, "0 <= eps <= 1"));
            }
            if eps != matrix[j][i] {
                return Err(Error::out_of_range(
                    &key,
                    eps,
                    &format!(
                        "collision.restitution[{j}][{i}] = {} (symmetric)",
                        matrix[j][i]
                    ),
                ));
            }
        }
    }
    Ok(species.iter().map(|x| (0.5 * x.diameter, x.mass)).collect())
}
