//! The tangential contact force of rough soft spheres and disks ([`SoftSphere::set_friction`]):
//! a Cundall–Strack spring with Mindlin's no-slip stiffness, viscoelastic damping and
//! Coulomb's limit, and the torques it exerts.
//!
//! For a pair (i, j) in contact, n the unit vector from i to j, the contact point lies
//! l_i = a_i − ξ/2 from i's centre and l_j = a_j − ξ/2 from j's (a the radii, ξ the
//! overlap: l_i + l_j is the distance, so that the torques keep the angular momentum, as
//! LAMMPS's `granular` pair style's distance to contact), and the velocity of j's contact
//! point relative to i's is g = v_j − v_i − (l_i ω_i + l_j ω_j) × n, its tangential part
//! g_t = g − (g·n) n. Each contact keeps the tangential displacement δ of
//! its contact points since it began (its history, Cundall & Strack 1979): each step
//! turns δ into the new tangent plane (keeping its length, as LAMMPS's `granular` pair
//! style does) and adds g_t dt at the middle of the step. The force on j is
//!
//!   F_t = −k_t δ − A k_t g_t,   k_t = 8 G* √(R_eff ξ),   G* = Y / (4 (1 + ν)(2 − ν)),
//!
//! Mindlin's (1949) tangential stiffness of two spheres of one material at overlap ξ
//! (1/G* = 2 (2 − ν)/G, G = Y / (2 (1 + ν))): k_t / k_n = 2 (1 − ν)/(2 − ν) of the normal
//! incremental stiffness k_n = dF_n/dξ = (3/2) ρ √ξ. The damping takes the dissipative
//! constant A of the normal force, as its dissipative part (3/2) A ρ √ξ ξ̇ = A dF_el/dt
//! (Brilliantov, Spahn, Hertzsch & Pöschel 1996) does: the tangential force relaxes on the
//! same time A (an assumption: the two viscosities of the material could give shear its
//! own). Where |F_t| exceeds μ F_n, the contact slides: F_t is cut to μ F_n along itself
//! and δ is set to the displacement that force holds, δ = −(F_t + A k_t g_t)/k_t (the
//! spring loses what it held beyond the limit). Mindlin & Deresiewicz's partial slip
//! within a contact (the hysteresis of a stick–slip annulus) is not modelled: the contact
//! sticks or slides as a whole, as in Walton's model of instantaneous collisions whose
//! effective tangential restitution [`crate::soft::tangential`] tests measure.
//!
//! The force on i is −F_t; sphere i feels the torque −l_i (n × F_t) and j the torque
//! −l_j (n × F_t) (contact points at +l_i n from i, −l_j n from j). The power the tangential force takes from the kinetic energy is −F_t·g_t; the
//! spring holds (1/2) k_t |δ|², which vanishes with k_t as a contact ends: the energy
//! lost is the work taken less what the springs hold.

use super::contact::ViscoelasticMaterial;
use super::SoftSphere;
use crate::error::{Error, Result};
use crate::rotation::Rotation;
use crate::system::{System, Vector};
use restitution::rough::cross;
use serde::{Deserialize, Serialize};

/// Time steps per tangential oscillation of a sticking contact that a rough soft-sphere
/// run needs at least (see `SoftSphere::set_rotation`).
pub const MIN_TANGENTIAL_STEPS: f64 = 10.0;

/// One contact's history: its tangential displacement δ and whether it has slid while
/// loading (see [`Rough::contact`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spring {
    pub displacement: [f64; 3],
    pub slid: bool,
}

/// The saved tangential state of rough soft spheres (the last part of
/// [`super::SoftSphereState`]'s tail; their angular velocities are the tail's rotation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactHistory {
    /// Coulomb's friction coefficient μ.
    pub friction: f64,
    /// One spring per pair in contact, in the order of the contacts.
    pub springs: Vec<Spring>,
    /// The torque on each particle at the current positions (saved as the forces are: it
    /// depends on the predicted velocities of the step that computed it).
    pub torques: Vec<[f64; 3]>,
    /// The energy the springs hold now, Σ (1/2) k_t |δ|².
    pub stored: f64,
}

/// The tangential side of a rough soft-sphere engine: the contacts' history, the
/// particles' rotation and the scratch of a step.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Rough {
    pub history: ContactHistory,
    pub rotation: Rotation,
    /// Scratch: the springs lined up with the contacts of the current step.
    pub aligned: Vec<Spring>,
    /// Scratch: whether each contact of the current step began in it.
    pub fresh: Vec<bool>,
    /// Scratch: n × F_t of each contact of the current step and the arms (l_i, l_j).
    pub twists: Vec<([f64; 3], [f64; 2])>,
}

impl Rough {
    /// Checks a friction coefficient (μ >= 0, finite).
    pub fn check_friction(friction: f64) -> Result<f64> {
        if friction.is_finite() && friction >= 0.0 {
            Ok(friction)
        } else {
            Err(Error::out_of_range(
                "friction",
                friction,
                "a finite friction coefficient mu >= 0",
            ))
        }
    }

    /// Lines the springs up with the new contact list `current` (both lists sorted): a
    /// contact that goes on keeps its spring, a new one starts relaxed.
    pub fn align(&mut self, old: &[(u32, u32)], current: &[(u32, u32)]) {
        self.aligned.clear();
        self.fresh.clear();
        let mut previous = old.iter().zip(&self.history.springs).peekable();
        for pair in current {
            while previous.peek().is_some_and(|(p, _)| *p < pair) {
                previous.next();
            }
            match previous.peek() {
                Some((p, spring)) if *p == pair => {
                    self.aligned.push(**spring);
                    self.fresh.push(false);
                }
                _ => {
                    self.aligned.push(Spring::default());
                    self.fresh.push(true);
                }
            }
        }
        std::mem::swap(&mut self.aligned, &mut self.history.springs);
    }

    /// The angular velocity of particle i half a step `dt` ahead by its torque so far (the
    /// current one for None), as velocities are predicted for the forces.
    #[inline]
    pub fn angular(&self, i: usize, moment: f64, predicting: Option<f64>) -> [f64; 3] {
        let w = self.rotation.angular[i];
        match predicting {
            Some(dt) => {
                let t = &self.history.torques[i];
                std::array::from_fn(|k| w[k] + 0.5 * dt / moment * t[k])
            }
            None => w,
        }
    }
}

/// The arms l_i = a_i − ξ/2 and l_j = a_j − ξ/2 of the pair (i, j) at overlap ξ: the
/// distances from the centres to the contact point.
#[inline]
fn arms<const D: usize>(system: &System<D>, (i, j): (usize, usize), xi: f64) -> (f64, f64) {
    (system.radii[i] - 0.5 * xi, system.radii[j] - 0.5 * xi)
}

/// Mindlin's tangential stiffness k_t = 8 G* √(R_eff ξ) of two spheres of radii r1 and r2
/// of `material` at overlap ξ, G* = Y / (4 (1 + ν)(2 − ν)) (module documentation).
#[inline]
pub fn mindlin_stiffness(material: &ViscoelasticMaterial, r1: f64, r2: f64, xi: f64) -> f64 {
    let effective_radius = r1 * r2 / (r1 + r2);
    let nu = material.poisson;
    2.0 * material.young * (effective_radius * xi).sqrt() / ((1.0 + nu) * (2.0 - nu))
}

/// The tangential part of `g` (3 components) normal to the unit vector `n`.
#[inline]
pub fn tangential_part(g: &[f64; 3], n: &[f64; 3]) -> [f64; 3] {
    let along = g[0] * n[0] + g[1] * n[1] + g[2] * n[2];
    std::array::from_fn(|k| g[k] - along * n[k])
}

/// The velocity of j's contact point relative to i's, v_j − v_i − (l_i ω_i + l_j ω_j) × n,
/// from the relative velocity `dv` of the centres (l the arms to the contact point).
#[inline]
pub fn contact_velocity(
    dv: &[f64; 3],
    n: &[f64; 3],
    (ai, wi): (f64, &[f64; 3]),
    (aj, wj): (f64, &[f64; 3]),
) -> [f64; 3] {
    let w: [f64; 3] = std::array::from_fn(|k| ai * wi[k] + aj * wj[k]);
    let spin = cross(&w, n);
    std::array::from_fn(|k| dv[k] - spin[k])
}

/// What one contact's tangential force did in a force computation.
#[derive(Debug, Clone, Copy)]
pub struct TangentialForce {
    /// The force on j (on i: its opposite).
    pub force: [f64; 3],
    /// Whether Coulomb's limit cut it.
    pub sliding: bool,
}

/// The tangential force on j of a contact whose spring is `spring` (module documentation):
/// with `advance = Some((g_mid, dt))` the spring is first turned into the tangent plane of
/// `n` and advanced by g_mid dt (g_mid the contact velocity at the middle of the step),
/// then the force is −k_t δ − A k_t g_t of the contact velocity `g` (predicted to the
/// force's time), cut to μ F_n; the spring then holds the force it exerts.
#[allow(clippy::too_many_arguments)]
pub fn tangential_force(
    spring: &mut Spring,
    n: &[f64; 3],
    g: &[f64; 3],
    advance: Option<(&[f64; 3], f64)>,
    stiffness: f64,
    damping: f64,
    normal_force: f64,
    friction: f64,
) -> TangentialForce {
    let delta = &mut spring.displacement;
    if let Some((g_mid, dt)) = advance {
        let length2: f64 = delta.iter().map(|x| x * x).sum();
        if length2 > 0.0 {
            let turned = tangential_part(delta, n);
            let turned2: f64 = turned.iter().map(|x| x * x).sum();
            let scale = if turned2 > 0.0 {
                (length2 / turned2).sqrt()
            } else {
                0.0
            };
            *delta = turned.map(|x| scale * x);
        }
        let slip = tangential_part(g_mid, n);
        for k in 0..3 {
            delta[k] += slip[k] * dt;
        }
    }
    let g_t = tangential_part(g, n);
    let viscous = damping * stiffness;
    let mut force: [f64; 3] = std::array::from_fn(|k| -stiffness * delta[k] - viscous * g_t[k]);
    let size = force.iter().map(|x| x * x).sum::<f64>().sqrt();
    let limit = friction * normal_force;
    let sliding = size > limit;
    if sliding {
        let cut = if size > 0.0 { limit / size } else { 0.0 };
        force = force.map(|f| f * cut);
        if stiffness > 0.0 {
            *delta = std::array::from_fn(|k| -(force[k] + viscous * g_t[k]) / stiffness);
        }
    }
    TangentialForce { force, sliding }
}

/// (1/2) k_t |δ|²: the energy a spring of stiffness k_t holds.
#[inline]
pub fn spring_energy(spring: &Spring, stiffness: f64) -> f64 {
    0.5 * stiffness * spring.displacement.iter().map(|x| x * x).sum::<f64>()
}

/// A D-vector as three components (zero beyond D).
#[inline]
pub fn embed<const D: usize>(v: &[f64; D]) -> [f64; 3] {
    std::array::from_fn(|k| if k < D { v[k] } else { 0.0 })
}

impl Rough {
    /// Starts a force computation over the contacts `current` that were `old`: lines the
    /// springs up and empties the sums of the step.
    pub fn begin(&mut self, old: &[(u32, u32)], current: &[(u32, u32)]) {
        self.align(old, current);
        self.twists.clear();
        self.history.stored = 0.0;
    }

    /// The moment of inertia q m a² of particle i of `system`.
    #[inline]
    pub fn moment<const D: usize>(&self, system: &System<D>, i: usize) -> f64 {
        self.rotation.inertia[i] * system.masses[i] * system.radii[i] * system.radii[i]
    }

    /// The tangential force on j of contact `c`, the pair (i, j) of `system` along `n` at
    /// overlap `xi` with normal force `normal_force`: `predicted` the relative velocity of
    /// the centres at the force's time, `mid` at the middle of the step (`predicting` its
    /// length; None: no step, the spring stays). Records the twist n × F_t and the
    /// spring's energy; returns the force and the power −F_t·g_t it takes from the
    /// kinetic energy.
    #[allow(clippy::too_many_arguments)]
    pub fn contact<const D: usize>(
        &mut self,
        c: usize,
        (i, j): (usize, usize),
        system: &System<D>,
        material: &ViscoelasticMaterial,
        n: &Vector<D>,
        (predicted, mid): (&Vector<D>, &Vector<D>),
        predicting: Option<f64>,
        (xi, normal_force): (f64, f64),
    ) -> ([f64; 3], f64) {
        let (ai, aj) = arms(system, (i, j), xi);
        let n = embed(n);
        let (wi, wj) = (
            self.angular(i, self.moment(system, i), predicting),
            self.angular(j, self.moment(system, j), predicting),
        );
        let g = contact_velocity(&embed(predicted), &n, (ai, &wi), (aj, &wj));
        let g_mid = predicting.map(|dt| {
            let (wi, wj) = (&self.rotation.angular[i], &self.rotation.angular[j]);
            let g = contact_velocity(&embed(mid), &n, (ai, wi), (aj, wj));
            // A contact begun within this step has slipped only since it touched, ξ / ξ'
            // ago: so its spring's start, like the force's, is of second order in dt.
            let approach = -(0..3).map(|k| g[k] * n[k]).sum::<f64>();
            let since = if self.fresh[c] && approach > 0.0 {
                (xi / approach).min(dt)
            } else {
                dt
            };
            (g, since)
        });
        let (ri, rj) = (system.radii[i], system.radii[j]);
        let stiffness = mindlin_stiffness(material, ri, rj, xi);
        let spring = &mut self.history.springs[c];
        let t = tangential_force(
            spring,
            &n,
            &g,
            g_mid.as_ref().map(|(g, dt)| (g, *dt)),
            stiffness,
            material.dissipative_constant,
            normal_force,
            self.history.friction,
        );
        // A contact counts as sliding (Walton's sense: the Coulomb limit holds the
        // tangential impulse) if it slides while the overlap grows; every contact slides
        // as it unloads, the normal force vanishing under the spring's.
        let loading = (0..D).map(|k| predicted[k] * n[k]).sum::<f64>() < 0.0;
        if t.sliding && loading && !spring.slid {
            spring.slid = true;
            self.rotation.sliding += 1;
        }
        self.history.stored += spring_energy(spring, stiffness);
        self.twists.push((cross(&n, &t.force), [ai, aj]));
        let power = -(0..3).map(|k| t.force[k] * g[k]).sum::<f64>();
        (t.force, power)
    }

    /// The tangential force on j of contact `c` at the current velocities and the power
    /// −F_t·g_t it takes, without moving its spring (the left end of a step's trapezoid).
    #[allow(clippy::too_many_arguments)]
    pub fn now<const D: usize>(
        &self,
        c: usize,
        (i, j): (usize, usize),
        system: &System<D>,
        material: &ViscoelasticMaterial,
        n: &Vector<D>,
        dv: &Vector<D>,
        (xi, normal_force): (f64, f64),
    ) -> ([f64; 3], f64) {
        let (ai, aj) = arms(system, (i, j), xi);
        let n = embed(n);
        let (wi, wj) = (&self.rotation.angular[i], &self.rotation.angular[j]);
        let g = contact_velocity(&embed(dv), &n, (ai, wi), (aj, wj));
        let mut spring = self.history.springs[c];
        let t = tangential_force(
            &mut spring,
            &n,
            &g,
            None,
            mindlin_stiffness(material, system.radii[i], system.radii[j], xi),
            material.dissipative_constant,
            normal_force,
            self.history.friction,
        );
        (t.force, -(0..3).map(|k| t.force[k] * g[k]).sum::<f64>())
    }

    /// Adds the torques of the contacts `current` (twists of [`Rough::contact`]): each
    /// sphere of a pair feels −l (n × F_t), l its arm.
    pub fn add_torques(&mut self, current: &[(u32, u32)]) {
        for (&(i, j), (twist, arms)) in current.iter().zip(&self.twists) {
            for (p, l) in [(i as usize, arms[0]), (j as usize, arms[1])] {
                for (t, w) in self.history.torques[p].iter_mut().zip(twist) {
                    *t -= l * w;
                }
            }
        }
    }

    /// ω += (dt/2) τ / I on the particles `active` (the others feel no torque).
    pub fn half_kick<const D: usize>(&mut self, active: &[u32], system: &System<D>, dt: f64) {
        for &i in active {
            let i = i as usize;
            let kick = 0.5 * dt / self.moment(system, i);
            let t = self.history.torques[i];
            for (w, t) in self.rotation.angular[i].iter_mut().zip(t) {
                *w += kick * t;
            }
        }
    }
}

impl<const D: usize> SoftSphere<D> {
    /// Makes the contacts rough with Coulomb's friction coefficient μ >= 0 (with a rotation,
    /// [`crate::Engine::set_rotation`]: the tangential force of [the module](self)), or smooth again
    /// (None; refused while the particles rotate).
    pub fn set_friction(&mut self, friction: Option<f64>) -> Result<()> {
        match friction {
            Some(mu) => {
                let mu = Rough::check_friction(mu)?;
                if let Some(rough) = &mut self.rough {
                    rough.history.friction = mu;
                }
                self.friction = Some(mu);
            }
            None if self.rough.is_some() => {
                return Err(Error::out_of_range(
                    "friction",
                    "none",
                    "a friction coefficient: the particles rotate",
                ))
            }
            None => self.friction = None,
        }
        Ok(())
    }

    /// Refuses a step that does not resolve the tangential oscillation of a sticking
    /// contact: its frequency is that of the normal one times
    /// r = √((k_t/k_n) m_eff / m_t) <= √((k_t/k_n)(1 + 1/q)) (1/m_t = Σ (1 + 1/q)/m: the
    /// contact point's inertia; k_t/k_n = 2(1 − ν)/(2 − ν)), for the smallest q. The step
    /// must take at least [`MIN_TANGENTIAL_STEPS`] steps per contact duration over r (the
    /// engine's β then converges at first order, ~0.13 r / steps: 1e-2 at the bound).
    fn check_tangential_step(&self, rotation: &Rotation) -> Result<()> {
        let nu = self.material.poisson;
        let smallest = rotation
            .inertia
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        if self.system.is_empty() {
            return Ok(());
        }
        let ratio = (2.0 * (1.0 - nu) / (2.0 - nu) * (1.0 + 1.0 / smallest)).sqrt();
        let contact = super::shortest_contact(&self.system, &self.material)?;
        let steps = contact / self.time_step / ratio;
        if steps < MIN_TANGENTIAL_STEPS {
            return Err(Error::UnresolvedStep {
                name: "steps_per_contact",
                value: contact / self.time_step,
                allowed: format!(
                    "at least {} steps per contact for spheres of inertia factor {smallest} \
                     (their tangential oscillation is {ratio:.2} times faster than the \
                     normal one): more steps per contact or a larger inertia",
                    (MIN_TANGENTIAL_STEPS * ratio).ceil()
                ),
            });
        }
        Ok(())
    }

    /// Gives the spheres `rotation` (checked: one entry per sphere, inertia factors in
    /// range, disks about z; the contacts' springs start relaxed), or takes it away.
    /// Refused without a friction ([`SoftSphere::set_friction`]): smooth contacts exert no
    /// torque.
    pub fn set_rotation(&mut self, rotation: Option<crate::rotation::Rotation>) -> Result<()> {
        let Some(rotation) = rotation else {
            self.rough = None;
            return Ok(());
        };
        rotation.check(self.system.len(), D)?;
        let Some(friction) = self.friction else {
            return Err(Error::out_of_range(
                "rotation",
                "a rotation of smooth spheres",
                "a friction coefficient first: smooth contacts exert no torque",
            ));
        };
        self.check_tangential_step(&rotation)?;
        let n = self.system.len();
        self.rough = Some(Rough {
            history: ContactHistory {
                friction,
                springs: vec![Spring::default(); self.contacts.len()],
                torques: vec![[0.0; 3]; n],
                stored: 0.0,
            },
            rotation,
            aligned: Vec::new(),
            fresh: Vec::new(),
            twists: Vec::new(),
        });
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mindlin's ratio k_t / k_n = 2 (1 − ν)/(2 − ν), k_n = (3/2) ρ √ξ the normal
    /// incremental stiffness (the derivative of ρ ξ^{3/2}).
    #[test]
    fn mindlin_ratio() {
        let m = ViscoelasticMaterial::new(1e5, 0.3, 1e-3).unwrap();
        let (r1, r2, xi) = (0.5, 0.7, 1e-3f64);
        let k_n = 1.5 * m.elastic_constant(r1, r2) * xi.sqrt();
        let ratio = mindlin_stiffness(&m, r1, r2, xi) / k_n;
        assert!((ratio - 2.0 * 0.7 / 1.7).abs() < 1e-14, "{ratio}");
    }

    /// A force beyond Coulomb's limit is cut to μ F_n along itself and the spring then
    /// holds exactly that force; within the limit nothing is cut.
    #[test]
    fn coulomb_limit_resets_the_spring() {
        let n = [0.0, 0.0, 1.0];
        let mut spring = Spring {
            displacement: [0.1, 0.0, 0.0],
            slid: false,
        };
        let g = [0.5, 0.2, 0.3];
        let f = tangential_force(&mut spring, &n, &g, None, 10.0, 0.01, 2.0, 0.3);
        assert!(f.sliding);
        let size = f.force.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!((size - 0.6).abs() < 1e-14);
        assert!(f.force[2].abs() < 1e-15);
        let mut again = spring;
        let g_t = tangential_part(&g, &n);
        let held: [f64; 3] = std::array::from_fn(|k| -10.0 * again.displacement[k] - 0.1 * g_t[k]);
        for (h, f) in held.iter().zip(f.force) {
            assert!((h - f).abs() < 1e-14);
        }
        let within = tangential_force(&mut again, &n, &g, None, 10.0, 0.01, 2.0, 1.0);
        assert!(!within.sliding);
    }

    /// Turning the spring into a new tangent plane keeps its length and makes it normal to
    /// the new n; advancing adds g_t dt.
    #[test]
    fn spring_turns_with_the_contact() {
        let mut spring = Spring {
            displacement: [0.0, 0.2, 0.0],
            slid: false,
        };
        let t = 0.1f64;
        let n = [0.0, t.sin(), t.cos()];
        tangential_force(
            &mut spring,
            &n,
            &[0.0; 3],
            Some((&[0.0; 3], 1e-3)),
            1.0,
            0.0,
            1.0,
            1e9,
        );
        let d = spring.displacement;
        let along = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        assert!(along.abs() < 1e-15);
        assert!(((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() - 0.2).abs() < 1e-15);
        let before = spring.displacement;
        let g = [0.3, 0.0, 0.0];
        tangential_force(&mut spring, &n, &g, Some((&g, 0.01)), 1.0, 0.0, 1.0, 1e9);
        assert!((spring.displacement[0] - before[0] - 0.003).abs() < 1e-15);
    }
}
