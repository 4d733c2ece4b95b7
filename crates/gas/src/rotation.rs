//! The particles' rotation (rough spheres and disks): each particle's inertia factor q
//! (I = q m a^2, a the radius) and angular velocity, and the rough collision in the
//! engines' layout (the rule of `restitution::rough`, whose reference `collide` the
//! tests compare with).
//!
//! Angular velocities have three components in every dimension: disks in the plane
//! rotate about z only (their x and y components stay 0: the torque of an impulse in the
//! plane points along z). One-dimensional rods have no rotation.

use crate::error::{Error, Result};
use crate::system::{dot, System, Vector};
use restitution::rough::{Body, Tangential};
use serde::{Deserialize, Serialize};

/// The largest inertia factor of a sphere (a hollow shell, 2/3) and of a disk (a ring
/// would be 1; a disk of uniform or inward density at most 1/2).
pub fn largest_inertia(dimension: usize) -> f64 {
    if dimension == 2 {
        0.5
    } else {
        2.0 / 3.0
    }
}

/// The rotational degrees of freedom: 3 for spheres, 1 for disks.
pub fn rotational_dimension(dimension: usize) -> usize {
    if dimension == 2 {
        1
    } else {
        3
    }
}

/// The rotation of N particles.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rotation {
    /// Inertia factor q of each particle: I = q m a^2.
    pub inertia: Vec<f64>,
    /// Angular velocity of each particle.
    pub angular: Vec<[f64; 3]>,
    /// Collisions whose contact slid (Coulomb's limit of Walton's model reached).
    pub sliding: u64,
}

impl Rotation {
    /// N particles of inertia factor q each, not rotating.
    pub fn at_rest(n: usize, inertia: f64) -> Self {
        Rotation {
            inertia: vec![inertia; n],
            angular: vec![[0.0; 3]; n],
            sliding: 0,
        }
    }

    /// Inertia factors `inertia` (one per particle of `system`) and angular velocities
    /// drawn from the Gaussian of rotational temperature `temperature` (I <w_k^2> = T
    /// about each axis: x, y, z for spheres, z for disks), from a stream of its own
    /// (`seed`): the translational draws are those of a smooth gas.
    pub fn thermal<const D: usize>(
        system: &System<D>,
        inertia: Vec<f64>,
        temperature: f64,
        seed: u64,
    ) -> Self {
        let mut stream = crate::rng::Stream::new(seed, crate::rng::Purpose::Spins, 0, 0);
        let angular = (0..system.len())
            .map(|i| {
                let moment = inertia[i] * system.masses[i] * system.radii[i] * system.radii[i];
                let scale = (temperature / moment).sqrt();
                std::array::from_fn(|k| {
                    if D == 2 && k < 2 {
                        0.0
                    } else {
                        scale * stream.normal()
                    }
                })
            })
            .collect();
        Rotation {
            inertia,
            angular,
            sliding: 0,
        }
    }

    /// Checks a rotation given or restored for `n` particles in `dimension`: q in
    /// (0, 2/3] (disks (0, 1/2]), finite angular velocities, disks' about z only.
    pub fn check(&self, n: usize, dimension: usize) -> Result<()> {
        if dimension < 2 {
            return Err(Error::out_of_range(
                "rotation",
                "one dimension",
                "spheres (3D) or disks (2D): rods do not rotate",
            ));
        }
        if self.inertia.len() != n || self.angular.len() != n {
            return Err(Error::LengthMismatch {
                what: "inertia factors, angular velocities and particles".into(),
            });
        }
        let largest = largest_inertia(dimension);
        if let Some(i) = self
            .inertia
            .iter()
            .position(|&q| !(q > 0.0 && q <= largest))
        {
            return Err(Error::out_of_range(
                format!("inertia[{i}]"),
                self.inertia[i],
                format!("0 < inertia <= {largest:.6}"),
            ));
        }
        if let Some(index) = self
            .angular
            .iter()
            .position(|w| w.iter().any(|x| !x.is_finite()))
        {
            return Err(Error::NotFinite {
                what: "angular velocities",
                index,
            });
        }
        if dimension == 2 {
            if let Some(i) = self.angular.iter().position(|w| w[0] != 0.0 || w[1] != 0.0) {
                return Err(Error::out_of_range(
                    format!("angular velocities[{i}]"),
                    format!("{:?}", self.angular[i]),
                    "disks rotating about z (x and y components 0)",
                ));
            }
        }
        Ok(())
    }

    /// The section `rotation` of an engine's report after `collisions` collisions:
    /// `sliding_contacts` and `sliding_fraction` (Walton's model; 0 without friction).
    pub fn report(&self, collisions: u64) -> crate::engine::ReportSection {
        use crate::engine::ReportValue::{Count, Real};
        crate::engine::ReportSection {
            name: "rotation",
            values: vec![
                ("sliding_contacts", Count(self.sliding)),
                (
                    "sliding_fraction",
                    Real(self.sliding as f64 / collisions.max(1) as f64),
                ),
            ],
        }
    }

    /// Particle i's moment of inertia in `system`.
    fn moment<const D: usize>(&self, system: &System<D>, i: usize) -> f64 {
        self.inertia[i] * system.masses[i] * system.radii[i] * system.radii[i]
    }

    /// Rotational kinetic energy, sum of I |w|^2 / 2.
    pub fn energy<const D: usize>(&self, system: &System<D>) -> f64 {
        (0..self.angular.len())
            .map(|i| 0.5 * self.moment(system, i) * squared(&self.angular[i]))
            .sum()
    }

    /// The rotational temperature T_rot = <I |w|^2> / d_rot over the particles `which`
    /// (all: `None`).
    pub fn temperature<const D: usize>(&self, system: &System<D>, which: Option<&[usize]>) -> f64 {
        let d_rot = rotational_dimension(D) as f64;
        let (sum, count) = match which {
            None => (2.0 * self.energy(system), self.angular.len()),
            Some(list) => (
                list.iter()
                    .map(|&i| self.moment(system, i) * squared(&self.angular[i]))
                    .sum(),
                list.len(),
            ),
        };
        sum / (d_rot * count.max(1) as f64)
    }
}

fn squared(w: &[f64; 3]) -> f64 {
    w[0] * w[0] + w[1] * w[1] + w[2] * w[2]
}

/// A rough contact's constants, computed once per pair of species (DSMC) or per
/// collision (event-driven MD): each particle's 1/m, 1/(q m a) and radius a, and the
/// rule's impulse and energy per unit of the tangential speed, so that a sticking
/// contact needs neither a square root nor a division (module `restitution::rough`:
/// P_t = -(1 + beta) g_t / k_t takes (1 - beta^2) |g_t|^2 / (2 k_t)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Contact {
    inverse_mass: [f64; 2],
    /// 1/(q m a): the change of a w per unit of torque over a.
    arm: [f64; 2],
    radius: [f64; 2],
    /// (1 + beta) / k_t: the sticking impulse per unit of |g_t|.
    stick: f64,
    /// (1 - beta^2) / (2 k_t): the energy a sticking contact takes per unit of |g_t|^2.
    stick_loss: f64,
    k_t: f64,
    friction: Option<f64>,
}

impl Contact {
    /// The contact of `rule` between particles `i` and `j`.
    pub fn new(rule: &Tangential, i: Body, j: Body) -> Self {
        let inverse_mass = [1.0 / i.mass, 1.0 / j.mass];
        let inertia_mass = [1.0 / (i.inertia * i.mass), 1.0 / (j.inertia * j.mass)];
        let k_t = inverse_mass[0] + inverse_mass[1] + inertia_mass[0] + inertia_mass[1];
        let beta = rule.beta();
        Contact {
            inverse_mass,
            arm: [inertia_mass[0] / i.radius, inertia_mass[1] / j.radius],
            radius: [i.radius, j.radius],
            stick: (1.0 + beta) / k_t,
            stick_loss: 0.5 * (1.0 - beta * beta) / k_t,
            k_t,
            friction: rule.friction(),
        }
    }
}

/// The tangential half of a collision whose normal impulse `normal_impulse` (its size)
/// along the unit normal `n` from i to j an engine has applied: the tangential impulse
/// of the contact's rule (`restitution::rough::Tangential::impulse`) on i (velocity and
/// angular velocity `i`) and j, with `relative` the velocity of i less that of j's image
/// (the normal impulse leaves its tangential part alone). Disks (D = 2) spin about z.
#[inline(always)]
pub(crate) fn tangential_kick<const D: usize>(
    contact: &Contact,
    n: &Vector<D>,
    relative: &Vector<D>,
    normal_impulse: f64,
    i: (&mut Vector<D>, &mut [f64; 3]),
    j: (&mut Vector<D>, &mut [f64; 3]),
) -> Kick {
    let [ra, rb] = contact.radius;
    // g_t = (v_i - v_j) - ((v_i - v_j) . n) n + (a_i w_i + a_j w_j) x n.
    let g_n = dot(relative, n);
    let mut g_t: Vector<D> = std::array::from_fn(|k| relative[k] - g_n * n[k]);
    if D == 2 {
        let s = ra * i.1[2] + rb * j.1[2];
        g_t[0] -= s * n[1];
        g_t[1] += s * n[0];
    } else {
        let s: [f64; 3] = std::array::from_fn(|k| ra * i.1[k] + rb * j.1[k]);
        g_t[0] += s[1] * n[2] - s[2] * n[1];
        g_t[1] += s[2] * n[0] - s[0] * n[2];
        g_t[2] += s[0] * n[1] - s[1] * n[0];
    }
    let g2 = dot(&g_t, &g_t);
    // Sticking unless Coulomb's limit mu |P_n| is below the sticking impulse
    // stick |g_t| (compared squared: both >= 0).
    let sticking = contact.stick;
    let (scale, energy_lost, sliding) = match contact.friction {
        Some(mu) if (mu * normal_impulse).powi(2) < sticking * sticking * g2 => {
            let (limit, speed) = (mu * normal_impulse, g2.sqrt());
            let energy = limit * speed - 0.5 * limit * limit * contact.k_t;
            (limit / speed, energy, true)
        }
        _ => (sticking, contact.stick_loss * g2, false),
    };
    // The impulse on i, -scale g_t, and its torque about i's centre over a_i.
    let p: Vector<D> = g_t.map(|x| -scale * x);
    let [ma, mb] = contact.inverse_mass;
    for (k, pk) in p.iter().enumerate() {
        i.0[k] += pk * ma;
        j.0[k] -= pk * mb;
    }
    let [aa, ab] = contact.arm;
    if D == 2 {
        let torque = n[0] * p[1] - n[1] * p[0];
        i.1[2] += torque * aa;
        j.1[2] += torque * ab;
    } else {
        let torque = [
            n[1] * p[2] - n[2] * p[1],
            n[2] * p[0] - n[0] * p[2],
            n[0] * p[1] - n[1] * p[0],
        ];
        for (k, tk) in torque.iter().enumerate() {
            i.1[k] += tk * aa;
            j.1[k] += tk * ab;
        }
    }
    Kick {
        energy_lost,
        sliding,
        to_j: std::array::from_fn(|k| if k < D { -p[k] } else { 0.0 }),
    }
}

/// What the tangential half of a collision did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Kick {
    pub energy_lost: f64,
    pub sliding: bool,
    /// The tangential momentum given to j (i got its negative).
    pub to_j: [f64; 3],
}

#[cfg(test)]
mod tests {
    use super::*;
    use restitution::rough::{collide, Body};

    /// The engines' kick after the normal impulse gives the reference rule's velocities
    /// (`restitution::rough::collide`, one formula for the whole impulse), in 3D and for
    /// disks in 2D, sticking and sliding.
    #[test]
    fn the_kick_after_the_normal_impulse_is_the_reference_collision() {
        let bodies = [
            Body {
                mass: 1.3,
                radius: 0.7,
                inertia: 0.4,
            },
            Body {
                mass: 0.6,
                radius: 0.45,
                inertia: 2.0 / 3.0,
            },
        ];
        for (planar, friction) in [
            (false, None),
            (false, Some(0.05)),
            (true, None),
            (true, Some(0.02)),
        ] {
            let rule = Tangential::new(0.35, friction).unwrap();
            let eps = 0.8;
            let r: [f64; 3] = if planar {
                [0.6, -0.8, 0.0]
            } else {
                [0.3, -0.5, 0.8]
            };
            let l = squared(&r).sqrt();
            let n = r.map(|x| x / l);
            let mut v = [[0.9, -0.4, 1.1], [-0.2, 0.3, -0.7]];
            let mut w = [[1.5, -0.8, 0.2], [0.1, 2.2, -1.3]];
            if planar {
                v.iter_mut().for_each(|v| v[2] = 0.0);
                w.iter_mut().for_each(|w| (w[0], w[1]) = (0.0, 0.0));
                w[1][2] = 1.3; // not the spin that nearly rolls: g_t = 0.015 would stick
            }
            let reference = collide(&rule, eps, bodies, n, v, w);
            // The engine's way: the normal impulse first, then the kick.
            let k_n = 1.0 / bodies[0].mass + 1.0 / bodies[1].mass;
            let g_n: f64 = (0..3).map(|k| (v[0][k] - v[1][k]) * n[k]).sum();
            let p_n = (1.0 + eps) * g_n / k_n;
            let mut after = v;
            for k in 0..3 {
                after[0][k] -= p_n / bodies[0].mass * n[k];
                after[1][k] += p_n / bodies[1].mass * n[k];
            }
            let relative: [f64; 3] = std::array::from_fn(|k| after[0][k] - after[1][k]);
            let [mut vi, mut vj] = after;
            let [mut wi, mut wj] = w;
            let contact = Contact::new(&rule, bodies[0], bodies[1]);
            let kick = tangential_kick::<3>(
                &contact,
                &n,
                &relative,
                p_n,
                (&mut vi, &mut wi),
                (&mut vj, &mut wj),
            );
            for k in 0..3 {
                assert!((vi[k] - reference.velocities[0][k]).abs() < 1e-14);
                assert!((vj[k] - reference.velocities[1][k]).abs() < 1e-14);
                assert!((wi[k] - reference.angular[0][k]).abs() < 1e-14);
                assert!((wj[k] - reference.angular[1][k]).abs() < 1e-14);
            }
            if planar {
                assert!(wi[0] == 0.0 && wi[1] == 0.0 && vi[2] == 0.0);
                // The disks' own path (D = 2: spins about z only).
                let plane = |x: [f64; 3]| [x[0], x[1]];
                let [mut vi2, mut vj2] = after.map(plane);
                let [mut wi2, mut wj2] = w;
                let kick2 = tangential_kick::<2>(
                    &contact,
                    &plane(n),
                    &plane(relative),
                    p_n,
                    (&mut vi2, &mut wi2),
                    (&mut vj2, &mut wj2),
                );
                for k in 0..2 {
                    assert!((vi2[k] - reference.velocities[0][k]).abs() < 1e-14);
                    assert!((vj2[k] - reference.velocities[1][k]).abs() < 1e-14);
                }
                assert!((wi2[2] - reference.angular[0][2]).abs() < 1e-14);
                assert!((wj2[2] - reference.angular[1][2]).abs() < 1e-14);
                assert_eq!((wi2[0], wi2[1], wj2[0], wj2[1]), (0.0, 0.0, 0.0, 0.0));
                assert!((kick2.energy_lost - kick.energy_lost).abs() < 1e-14);
                assert_eq!(kick2.sliding, kick.sliding);
            }
            let normal_loss = 0.5 * (1.0 - eps * eps) * g_n * g_n / k_n;
            assert!((normal_loss + kick.energy_lost - reference.energy_lost).abs() < 1e-13);
            assert_eq!(kick.sliding, reference.sliding);
            assert_eq!(
                kick.sliding,
                friction.is_some(),
                "the small friction makes it slide"
            );
            for (k, to_j) in kick.to_j.iter().enumerate() {
                let gained = bodies[1].mass * (reference.velocities[1][k] - after[1][k]);
                assert!((to_j - gained).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn checks_name_the_field() {
        let mut r = Rotation::at_rest(3, 0.4);
        assert!(r.check(3, 3).is_ok());
        assert!(r.check(3, 1).unwrap_err().to_string().contains("rotation"));
        r.inertia[1] = 0.6;
        assert!(r
            .check(3, 2)
            .unwrap_err()
            .to_string()
            .contains("inertia[1]"));
        r.inertia[1] = 0.4;
        r.angular[2] = [0.0, 1.0, 0.0];
        assert!(r.check(3, 2).is_err());
        r.angular[2] = [0.0, f64::NAN, 0.0];
        assert!(r.check(3, 3).is_err());
    }
}
