//! One oblique contact of two rough soft spheres, integrated by the engine itself: the
//! normal and effective tangential restitution it yields (ε = −g_n'/g_n, β = −g_t'/g_t of
//! the contact points' relative velocity), for comparison with Walton's model of
//! instantaneous collisions (`restitution::rough::Tangential`: sticking restitution β₀
//! below the Coulomb limit, β = −1 + μ (1 + ε)(1 + 1/q) g_n/g_t for two equal spheres
//! above it) and the fraction of such contacts that slid.

use super::contact::ViscoelasticMaterial;
use super::{SoftSphere, SoftSphereOptions};
use crate::error::Result;
use crate::rotation::Rotation;
use crate::system::System;

/// What an oblique contact did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObliqueOutcome {
    /// −g_n'/g_n.
    pub eps: f64,
    /// −g_t'/g_t (−1: the tangential velocity unchanged, as for smooth spheres).
    pub beta: f64,
    /// Whether Coulomb's limit was reached during the contact.
    pub slid: bool,
    /// The angle the line of centres turned through during the contact.
    pub turn: f64,
    /// Time steps in contact.
    pub steps: u64,
}

/// Two equal spheres (radius a, mass m, inertia factor q) of `material`, not spinning, meet
/// with contact-point velocity g = (−g_n, g_t) (normal along the line of centres at first
/// touch, tangential normal to it) and friction μ, integrated with the step `dt` in 3D.
/// The contact ends as the isolated contacts of [`super::accuracy`] do: once the spheres
/// separate, or once the force of the current state vanishes while they recede.
pub fn oblique_contact(
    material: ViscoelasticMaterial,
    friction: f64,
    (radius, mass, inertia): (f64, f64, f64),
    (g_n, g_t): (f64, f64),
    dt: f64,
) -> Result<ObliqueOutcome> {
    let contact = 2.0 * radius;
    let length = 16.0 * contact;
    // Start one step before touching: j at (2a, 0, 0) from i at the touch.
    let u = [-g_n, g_t, 0.0];
    let centre = 0.5 * length;
    let r = [contact - dt * u[0], -dt * u[1], 0.0];
    let system = System {
        sides: [length; 3],
        positions: vec![
            std::array::from_fn(|k| centre - 0.5 * r[k]),
            std::array::from_fn(|k| centre + 0.5 * r[k]),
        ],
        velocities: vec![u.map(|x| -0.5 * x), u.map(|x| 0.5 * x)],
        radii: vec![radius; 2],
        masses: vec![mass; 2],
    };
    let options = SoftSphereOptions {
        time_step: Some(dt),
        ..Default::default()
    };
    let mut engine = SoftSphere::<3>::build(system, material, options)?;
    engine.set_friction(Some(friction))?;
    engine.set_rotation(Some(Rotation::at_rest(2, inertia)))?;
    let rho = material.elastic_constant(radius, radius);
    let (mut touched, mut steps) = (false, 0);
    for _ in 0..10_000_000 {
        engine.run_steps(1);
        let overlapping = !engine.contacts().is_empty();
        touched |= overlapping;
        steps += overlapping as u64;
        let s = &engine.system;
        let d: [f64; 3] = std::array::from_fn(|k| s.positions[1][k] - s.positions[0][k]);
        let distance = d.iter().map(|x| x * x).sum::<f64>().sqrt();
        let n = d.map(|x| x / distance);
        let dv: [f64; 3] = std::array::from_fn(|k| s.velocities[1][k] - s.velocities[0][k]);
        let xi = contact - distance;
        let xi_dot = -(0..3).map(|k| dv[k] * n[k]).sum::<f64>();
        let released = xi_dot < 0.0
            && super::contact::normal_force(rho, material.dissipative_constant, xi, xi_dot).0
                == 0.0;
        if touched && (!overlapping || released) {
            let rough = engine.rough.as_ref().expect("rough engine");
            let w = &rough.rotation.angular;
            let g = super::tangential::contact_velocity(&dv, &n, (radius, &w[0]), (radius, &w[1]));
            // The tangent in the plane of motion (z = 0), turned with the line of centres.
            let t = [-n[1], n[0], 0.0];
            let normal = (0..3).map(|k| g[k] * n[k]).sum::<f64>();
            let tangential = (0..3).map(|k| g[k] * t[k]).sum::<f64>();
            return Ok(ObliqueOutcome {
                eps: normal / g_n,
                beta: -tangential / g_t,
                slid: rough.rotation.sliding > 0,
                turn: n[1].atan2(n[0]),
                steps,
            });
        }
    }
    Ok(ObliqueOutcome {
        eps: f64::NAN,
        beta: f64::NAN,
        slid: false,
        turn: f64::NAN,
        steps,
    })
}
