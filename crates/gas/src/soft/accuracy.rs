//! How well a time step resolves a contact: the eps of isolated head-on contacts,
//! integrated by the engine itself, against the exact law of the same material
//! (`restitution::exact`), reported with every soft-sphere run (`eps_error`).

use super::contact::ViscoelasticMaterial;
use super::{SoftSphere, SoftSphereOptions};
use crate::error::Result;
use crate::system::System;
use restitution::exact::{solve, Criterion};

/// The largest eps error of isolated contacts a run may have ([`super::SoftSphere::new`]
/// refuses coarser steps): ten times the default step's worst (8.4e-4, at v* ~ 1).
pub const MAX_EPS_ERROR: f64 = 1e-2;

/// Impact speeds probed, in units of the reference speed sqrt(T/m) of the lightest species.
pub const PROBED_SPEEDS: [f64; 3] = [0.1, 1.0, 10.0];

/// Where in a time step the contacts begin (fractions of a step): the error of a contact
/// depends on it, since the force ξ^{3/2} switches on within a step.
const PHASES: [f64; 4] = [0.125, 0.375, 0.625, 0.875];

/// eps of one head-on contact of spheres (r1, m1) and (r2, m2) meeting at relative speed
/// `v`, integrated with the step `dt`, the contact beginning 1 − `phase` of a step after
/// the start (a step boundary).
pub fn isolated_contact_eps(
    material: ViscoelasticMaterial,
    (r1, m1): (f64, f64),
    (r2, m2): (f64, f64),
    v: f64,
    dt: f64,
    phase: f64,
) -> Result<f64> {
    let contact = r1 + r2;
    let length = 8.0 * contact;
    // Start one step (minus the phase) before touching: gap closes at speed v.
    let gap = (1.0 - phase) * dt * v;
    let system = System {
        sides: [length],
        positions: vec![
            [0.5 * length - r1 - 0.5 * gap],
            [0.5 * length + r2 + 0.5 * gap],
        ],
        velocities: vec![[v * m2 / (m1 + m2)], [-v * m1 / (m1 + m2)]],
        radii: vec![r1, r2],
        masses: vec![m1, m2],
    };
    let options = SoftSphereOptions {
        time_step: Some(dt),
        ..Default::default()
    };
    let mut engine = SoftSphere::<1>::build(system, material, options)?;
    // The contact is over once the spheres no longer overlap, or once the force of the
    // current state vanishes while they separate: then xi + (3/2) A xi' <= 0 keeps holding
    // as xi shrinks at constant xi' < 0, the force stays zero however slowly a strongly
    // damped pair creeps apart, and the velocities are final. (The force the step computed
    // from its predicted velocity is not enough: it can vanish for a step while the pair
    // still approaches.) A contact lasts a few hundred steps at the steps the engine
    // chooses; the bound only stops a pathological step.
    let rho = material.elastic_constant(r1, r2);
    let mut touched = false;
    for _ in 0..10_000_000 {
        engine.run_steps(1);
        let overlapping = !engine.contacts().is_empty();
        touched |= overlapping;
        let (x, u) = (&engine.system.positions, &engine.system.velocities);
        let xi = contact - (x[1][0] - x[0][0]);
        let xi_dot = u[0][0] - u[1][0];
        let released = xi_dot < 0.0
            && super::contact::normal_force(rho, material.dissipative_constant, xi, xi_dot).0
                == 0.0;
        if touched && (!overlapping || released) {
            return Ok((u[1][0] - u[0][0]) / v);
        }
    }
    Ok(f64::NAN)
}

/// The largest |eps(MD) − eps(exact)| over the pairs of species of `system`, the impact
/// speeds [`PROBED_SPEEDS`] × sqrt(T/m_lightest) and four phases of the contact's start
/// within a step, for the time step `dt`.
pub fn eps_error<const D: usize>(
    system: &System<D>,
    material: ViscoelasticMaterial,
    dt: f64,
) -> Result<f64> {
    let kinds = super::species(system);
    let temperature = crate::observe::temperature(system).max(f64::MIN_POSITIVE);
    let reference = super::thermal_speed(&kinds, temperature);
    let mut worst: f64 = 0.0;
    for (a, &(r1, m1)) in kinds.iter().enumerate() {
        for &(r2, m2) in &kinds[a..] {
            let beta = material.beta(r1, r2, m1, m2);
            for c in PROBED_SPEEDS {
                let v = c * reference;
                let vstar = beta.sqrt() * v.powf(0.1);
                let exact = solve(vstar, Criterion::Improved)?.eps;
                for phase in PHASES {
                    let md = isolated_contact_eps(material, (r1, m1), (r2, m2), v, dt, phase)?;
                    worst = worst.max((md - exact).abs());
                }
            }
        }
    }
    Ok(worst)
}
