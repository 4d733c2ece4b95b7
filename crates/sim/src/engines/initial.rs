//! The initial particles of `[system]` and the checks every engine state of a run must pass:
//! its particles are those of `[system]`, in its box, and a cooling gas has not gained
//! energy.

use crate::description::species;
use crate::error::{Error, Result};
use crate::validate::{LawSpec, Plan, Species};
use gas::init::GrowthReport;
use gas::System;

/// The initial particles of the `[system]` section: a mixture placed at the packing
/// fraction (in the wider box of weighted particles), spheres of one kind (randomly added,
/// a melted lattice, or grown: `gas::init`), or (point particles) points placed
/// independently; and the report of a growth.
pub(super) fn system<const D: usize>(plan: &Plan) -> Result<(System<D>, Option<GrowthReport>)> {
    if let Some(initial) = &plan.initial {
        let system = of_configuration::<D>(&initial.configuration);
        if plan.description.system.sides.is_some() {
            return Ok((system, None));
        }
        // An engine without space: the cube of the file's packing fraction.
        let side = match plan.species.len() {
            1 => monodisperse_side::<D>(
                system.len(),
                plan.species[0].diameter,
                plan.description.packing_fraction(),
                1.0,
            ),
            _ => mixture_side::<D>(&system, plan.description.packing_fraction(), 1.0),
        };
        return Ok((stretched(system, [side; D]), None));
    }
    let s = &plan.description.system;
    let weight = plan.particle_weight;
    let Species { diameter, mass, .. } = plan.species[0];
    let closed: [bool; D] = std::array::from_fn(|k| plan.walls.iter().any(|w| w.axis == k));
    let given: Option<[f64; D]> = s.sides.as_ref().map(|l| std::array::from_fn(|k| l[k]));
    let phi = plan.description.packing_fraction();
    match &s.species {
        // Weighted particles (DSMC: points) are placed at the physical packing fraction,
        // then spread uniformly over the wider box.
        Some(entries) => gas::init::polydisperse_reporting::<D>(
            s.particles,
            match given {
                Some(sides) if weight == 1.0 => gas::init::BoxSize::Sides(sides),
                _ => gas::init::BoxSize::PackingFraction(phi),
            },
            &species(entries),
            s.temperature,
            s.seed,
            closed,
        )
        .map(|(system, report)| match given {
            Some(sides) if weight != 1.0 => (stretched(system, sides), report),
            Some(_) => (system, report),
            None => (widened(system, phi, weight), report),
        }),
        // Points need not be placed without overlaps.
        None if plan.engine.abilities().point_particles => gas::dsmc::point_gas::<D>(
            s.particles,
            given.unwrap_or([monodisperse_side::<D>(s.particles, diameter, phi, weight); D]),
            diameter,
            mass,
            s.temperature,
            s.seed,
        )
        .map(|system| (system, None)),
        None => gas::init::monodisperse_reporting::<D>(
            s.particles,
            match given {
                Some(sides) => gas::init::BoxSize::Sides(sides),
                None => gas::init::BoxSize::PackingFraction(phi),
            },
            diameter,
            mass,
            s.temperature,
            s.seed,
            closed,
        ),
    }
    .map_err(|e| {
        Error::input(
            if given.is_some() {
                "system.box"
            } else {
                "system"
            },
            e,
        )
    })
}

/// The system of a checked configuration of `D` dimensions with every column filled in
/// (`crate::validate::Initial`): the file's order of particles, radii half the diameters.
fn of_configuration<const D: usize>(c: &crate::particles::Configuration) -> System<D> {
    let cut = |v: &[f64; 3]| -> [f64; D] { std::array::from_fn(|k| v[k]) };
    System {
        sides: std::array::from_fn(|k| c.sides[k]),
        positions: c.positions.iter().map(cut).collect(),
        velocities: c
            .velocities
            .as_ref()
            .expect("filled in by validation")
            .iter()
            .map(cut)
            .collect(),
        radii: c
            .diameters
            .as_ref()
            .expect("filled in by validation")
            .iter()
            .map(|d| 0.5 * d)
            .collect(),
        masses: c.masses.clone().expect("filled in by validation"),
    }
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
    let scale = length / system.sides[0];
    for x in &mut system.positions {
        for c in x.iter_mut() {
            *c = gas::system::wrap(*c * scale, length);
        }
    }
    system.sides = [length; D];
    system
}

/// `system` (points placed uniformly) with its positions scaled, axis by axis, into the box
/// with `sides`.
fn stretched<const D: usize>(mut system: System<D>, sides: [f64; D]) -> System<D> {
    let scale: [f64; D] = std::array::from_fn(|k| sides[k] / system.sides[k]);
    for x in &mut system.positions {
        for k in 0..D {
            x[k] = gas::system::wrap(x[k] * scale[k], sides[k]);
        }
    }
    system.sides = sides;
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

/// The particles of `system` are those of `[system]`: their number, and the radii and
/// masses of each species in its count.
pub(super) fn particles<const D: usize>(
    plan: &Plan,
    system: &System<D>,
) -> std::result::Result<(), String> {
    let s = &plan.description.system;
    if system.len() != s.particles {
        return Err(format!(
            "{} particles where system.particles = {}",
            system.len(),
            s.particles
        ));
    }
    for kind in &plan.species {
        let (radius, mass) = (kind.radius(), kind.mass);
        let found = system
            .radii
            .iter()
            .zip(&system.masses)
            .filter(|&(&r, &m)| r == radius && m == mass)
            .count();
        if found != kind.count {
            return Err(format!(
                "{found} particles of radius {radius} and mass {mass} where [system] has {}",
                kind.count
            ));
        }
    }
    Ok(())
}

/// The box is the one of `[system]`: `system.box` exactly, or the cube of the spheres'
/// volume at the packing fraction, exactly for one kind of sphere (the initializer
/// computes it the same way), to the round-off of the initializer's sum over the particles
/// for a mixture (n ulp).
pub(super) fn box_side<const D: usize>(
    plan: &Plan,
    system: &System<D>,
) -> std::result::Result<(), String> {
    let s = &plan.description.system;
    if let Some(sides) = &s.sides {
        if system.sides.as_slice() == sides.as_slice() {
            return Ok(());
        }
        return Err(format!(
            "box sides {:?} where system.box gives {sides:?}",
            system.sides
        ));
    }
    let weight = plan.particle_weight;
    let phi = plan.description.packing_fraction();
    let (expected, tolerance) = match &s.species {
        None => {
            let diameter = plan.species[0].diameter;
            let side = monodisperse_side::<D>(s.particles, diameter, phi, weight);
            (side, 0.0)
        }
        Some(_) => {
            let side = mixture_side::<D>(system, phi, weight);
            (side, 2.0 * f64::EPSILON * system.len() as f64 * side)
        }
    };
    if system.is_cubic() && (system.sides[0] - expected).abs() <= tolerance {
        Ok(())
    } else {
        Err(format!(
            "box sides {:?} where system.packing_fraction gives {expected}",
            system.sides
        ))
    }
}

/// A cooling gas never gains energy: the kinetic energy of the particles (plus, for a
/// stochastic law, the energy `modes * T_i` held by each particle's bath, which the
/// collisions exchange with the translation, `restitution::collide_with_baths`) is at most
/// the initial one, `N (D/2) T0 (+ N modes T_bath)`: the initializer sets the temperature
/// exactly (to round-off). The tolerance 1e-6 is far above the round-off of the collision
/// updates (~1e-16 relative per collision, a random walk) and far below what an edit that
/// would blow up the run (a velocity or bath temperature of 1e100) adds. Rough particles
/// add their rotational energy (`rotation`, the state's, one entry per particle) on one
/// side, the collisions exchanging it with the translation, and on the other the most
/// the start's spins hold: they are drawn at T_rot0 without rescaling, so their energy is
/// (T_rot0 / 2) times a chi-square of M = N d_rot degrees of freedom, bounded here by its
/// mean M plus 10 standard deviations (2 M)^(1/2) (a legitimate state exceeds it with
/// probability below 1e-20). A spin of 1e300 in a state is refused as a velocity is.
pub(super) fn no_energy_gained<const D: usize>(
    plan: &Plan,
    system: &System<D>,
    bath_temperatures: Option<&[f64]>,
    rotation: Option<&gas::rotation::Rotation>,
) -> std::result::Result<(), String> {
    if plan.driving.is_some()
        || plan.walls.iter().any(|w| w.kind.can_heat())
        || plan.shear.is_some()
    {
        // A driven gas, one touching a thermal wall, or a sheared one (the flow's work, and
        // the flow's own energy in the lab velocities a state keeps) gains energy.
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
    if let Some(rotation) = rotation {
        if rotation.angular.len() != system.len() || rotation.inertia.len() != system.len() {
            return Err("a rotation of another number of particles".into());
        }
        let start = plan.rough.as_ref().map_or(0.0, |r| r.temperature);
        let freedoms = n * gas::rotation::rotational_dimension(D) as f64;
        initial += 0.5 * start * (freedoms + 10.0 * (2.0 * freedoms).sqrt());
        now += rotation.energy(system);
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
