//! The time step of [`SoftSphere`]: velocity Verlet with the forces of the contacts.
//!
//! In a gas most particles touch no other at a given step, so the work per step is
//! arranged around the contacts: the forces are zero except on the particles in contact
//! (`active`), so the half kicks visit only those, and the predicted velocities are
//! needed only for the pairs in contact and are computed there. What remains per particle
//! is the drift and the pair search of the neighbour list.
//!
//! Shear, the tensor virial and rough particles take their own copy of the step
//! (`EXTENDED`, as the event-driven engine's `step_as`): the periodic gas's loops have none
//! of their branches.

use super::contact::normal_force;
use super::SoftSphere;
use crate::shear::Virial;
use crate::system::{minimum_image, wrap, Vector};

/// d = x_j − x_i for coordinates in [0, L) (|d| < L), as [`minimum_image`] but without
/// its rounding (select instructions instead of branches in the pair loop).
#[inline(always)]
fn image_of_difference(d: f64, length: f64, half: f64) -> f64 {
    if d > half {
        d - length
    } else if d < -half {
        d + length
    } else {
        d
    }
}

/// x = wrap(x + dt v) for coordinates in [0, L): by blocks that move and take the least
/// and largest coordinate lane by lane (vector min and max instructions), wrapping the
/// rare blocks that leave the box.
fn drift(x: &mut [f64], v: &[f64], dt: f64, length: f64) {
    const LANES: usize = 8;
    const BLOCK: usize = 8 * LANES;
    let mut xs = x.chunks_exact_mut(BLOCK);
    let mut vs = v.chunks_exact(BLOCK);
    for (x, v) in (&mut xs).zip(&mut vs) {
        let (mut low, mut high) = ([0.0f64; LANES], [0.0f64; LANES]);
        for (x, v) in x.chunks_exact_mut(LANES).zip(v.chunks_exact(LANES)) {
            for k in 0..LANES {
                x[k] += dt * v[k];
                low[k] = if x[k] < low[k] { x[k] } else { low[k] };
                high[k] = if x[k] > high[k] { x[k] } else { high[k] };
            }
        }
        if low.iter().any(|&c| c < 0.0) || high.iter().any(|&c| c >= length) {
            x.iter_mut().for_each(|c| *c = wrap(*c, length));
        }
    }
    for (x, v) in xs.into_remainder().iter_mut().zip(vs.remainder()) {
        *x = wrap(*x + dt * v, length);
    }
}

impl<const D: usize> SoftSphere<D> {
    /// One velocity-Verlet step of length `dt` (see the [module](super) documentation).
    pub(super) fn step(&mut self, dt: f64) {
        if self.extended() {
            self.step_extended(dt);
        } else {
            self.step_as::<false>(dt);
        }
    }

    /// Whether the step is the extended one: shear, the tensor virial or rough particles.
    #[inline]
    fn extended(&self) -> bool {
        self.shear.is_some() || self.virial.is_some() || self.rough.is_some()
    }

    /// [`Self::step`] with shear, the tensor virial or rough particles, out of line.
    #[inline(never)]
    fn step_extended(&mut self, dt: f64) {
        self.step_as::<true>(dt);
    }

    /// [`Self::step`], compiled twice: with `EXTENDED = false` (neither shear nor the
    /// tensor virial) the loops are the periodic gas's alone.
    #[inline(always)]
    fn step_as<const EXTENDED: bool>(&mut self, dt: f64) {
        let (power_before, virial_before, stress_before) = self.contact_rates::<EXTENDED>();
        let stored_before = self.rough.as_ref().map_or(0.0, |r| r.history.stored);
        self.half_kick(dt);
        if EXTENDED {
            self.half_kick_spins(dt);
        }
        if EXTENDED && self.shear.is_some() {
            self.drift_sheared(dt);
        } else if self.system.is_cubic() {
            drift(
                self.system.positions.as_flattened_mut(),
                self.system.velocities.as_flattened(),
                dt,
                self.system.sides[0],
            );
        } else {
            let s = &mut self.system;
            for (x, v) in s.positions.iter_mut().zip(&s.velocities) {
                for k in 0..D {
                    x[k] = wrap(x[k] + dt * v[k], s.sides[k]);
                }
            }
        }
        self.neighbors.drifted(dt);
        let (power, virial, begun) = self.compute_forces_as::<EXTENDED>(Some(dt));
        self.tally_walls(dt);
        self.half_kick(dt);
        if EXTENDED {
            self.half_kick_spins(dt);
        }
        self.steps += 1;
        self.tally.collisions += begun;
        self.tally.events += 1;
        self.tally.energy_lost += 0.5 * dt * (power_before + power);
        self.tally.virial += 0.5 * dt * (virial_before + virial);
        if EXTENDED {
            // What the tangential springs took and still hold is not lost.
            if let Some(rough) = &self.rough {
                self.tally.energy_lost -= rough.history.stored - stored_before;
            }
            // The trapezoid of the tensor, as of the virial.
            if let Some(total) = &mut self.virial {
                for (c, t) in total.0.iter_mut().enumerate() {
                    *t += 0.5 * dt * (stress_before.0[c] + self.stress_rate.0[c]);
                }
            }
        }
    }

    /// ω += (dt/2) τ / I of rough particles with a torque.
    fn half_kick_spins(&mut self, dt: f64) {
        if let Some(rough) = &mut self.rough {
            rough.half_kick(&self.active, &self.system, dt);
        }
    }

    /// v += (dt/2) F / m on the particles with a force (the others have F = 0).
    fn half_kick(&mut self, dt: f64) {
        let s = &mut self.system;
        for &i in &self.active {
            let i = i as usize;
            let kick = 0.5 * dt / s.masses[i];
            for k in 0..D {
                s.velocities[i][k] += kick * self.forces[i][k];
            }
            self.neighbors.kicked(&s.velocities[i]);
        }
    }

    /// Forces at the current positions, with the velocities predicted half a step ahead by
    /// the forces so far, v + (dt/2) F / m, for `Some(dt)`, the current velocities for
    /// None; replaces the contact list. Returns the dissipated power Σ F_dis ξ̇, the virial
    /// rate Σ F_n d and the number of contacts begun (with the tensor virial, its rate
    /// Σ F_n d n n into `stress_rate`).
    pub(super) fn compute_forces(&mut self, predicting: Option<f64>) -> (f64, f64, u64) {
        if self.extended() {
            self.compute_forces_as::<true>(predicting)
        } else {
            self.compute_forces_as::<false>(predicting)
        }
    }

    /// [`Self::compute_forces`]; `EXTENDED`: with shear or the tensor virial. Under shear a
    /// pair across a sliding face is its nearest image's, the image's velocity jump a L_y
    /// in the overlap's rate (module [`super::lees_edwards`]), at the images' offset at the
    /// positions' time.
    #[inline(always)]
    fn compute_forces_as<const EXTENDED: bool>(
        &mut self,
        predicting: Option<f64>,
    ) -> (f64, f64, u64) {
        let images = if EXTENDED {
            self.images_at(self.time + predicting.unwrap_or(0.0))
        } else {
            None
        };
        if self.neighbors.stale() {
            match &images {
                Some(images) => self.neighbors.build_sheared(&self.system, images),
                None => self.neighbors.build(&self.system),
            }
        }
        // The pairs in contact, in the order of the list (i < j, sorted).
        self.current.clear();
        let s = &self.system;
        // The largest contact distance first, which saves loading the radii of the pairs
        // far from contact (most of them); r_i + r_j <= 2 r_max also in floating point.
        let widest = 2.0 * self.neighbors.largest_radius;
        let widest2 = widest * widest;
        // The sides and half sides out of the pair loop.
        let (sides, halves) = (s.sides, s.sides.map(|l| 0.5 * l));
        match &images {
            Some(images) => {
                for &(i, j) in &self.neighbors.pairs {
                    let (xi, xj) = (&s.positions[i as usize], &s.positions[j as usize]);
                    let (r, _) = images.separation(xi, xj, &sides);
                    let d2: f64 = r.iter().map(|x| x * x).sum();
                    let contact = s.radii[i as usize] + s.radii[j as usize];
                    if d2 < contact * contact {
                        self.current.push((i, j));
                    }
                }
            }
            None => {
                for &(i, j) in &self.neighbors.pairs {
                    let (xi, xj) = (&s.positions[i as usize], &s.positions[j as usize]);
                    let d2: f64 = (0..D)
                        .map(|k| image_of_difference(xj[k] - xi[k], sides[k], halves[k]).powi(2))
                        .sum();
                    if d2 < widest2 {
                        let contact = s.radii[i as usize] + s.radii[j as usize];
                        if d2 < contact * contact {
                            self.current.push((i, j));
                        }
                    }
                }
            }
        }
        // Their forces, before the forces of the last step, which predict the velocities,
        // are cleared.
        let a = self.material.dissipative_constant;
        let (mut power, mut virial) = (0.0, 0.0);
        let mut stress = Virial::default();
        self.impulses.clear();
        if EXTENDED {
            if let Some(rough) = &mut self.rough {
                rough.begin(&self.contacts, &self.current);
            }
        }
        for (c, &(i, j)) in self.current.iter().enumerate() {
            let (i, j) = (i as usize, j as usize);
            let (r, across): (Vector<D>, f64) = match &images {
                Some(images) => images.separation(&s.positions[i], &s.positions[j], &s.sides),
                None => (
                    std::array::from_fn(|k| {
                        minimum_image(s.positions[j][k] - s.positions[i][k], s.sides[k])
                    }),
                    0.0,
                ),
            };
            let d = r.iter().map(|x| x * x).sum::<f64>().sqrt();
            let contact = s.radii[i] + s.radii[j];
            let xi = contact - d;
            let normal: Vector<D> = std::array::from_fn(|k| r[k] / d);
            let velocity = |p: usize, k: usize| match predicting {
                Some(dt) => s.velocities[p][k] + 0.5 * dt / s.masses[p] * self.forces[p][k],
                None => s.velocities[p][k],
            };
            let mut dv: Vector<D> = std::array::from_fn(|k| velocity(j, k) - velocity(i, k));
            if EXTENDED && across != 0.0 {
                // j's image across the face moves with v_j + s a L_y e_x.
                dv[0] += across * images.as_ref().map_or(0.0, |im| im.jump);
            }
            let xi_dot = -(0..D).map(|k| dv[k] * normal[k]).sum::<f64>();
            let rho = self.material.elastic_constant(s.radii[i], s.radii[j]);
            let (force, dissipative) = normal_force(rho, a, xi, xi_dot);
            let mut impulse: Vector<D> = std::array::from_fn(|k| force * normal[k]);
            power += dissipative * xi_dot;
            virial += force * d;
            if EXTENDED {
                stress.add(force, d, &normal);
                if let Some(rough) = &mut self.rough {
                    let mut mid: Vector<D> =
                        std::array::from_fn(|k| s.velocities[j][k] - s.velocities[i][k]);
                    if across != 0.0 {
                        mid[0] += across * images.as_ref().map_or(0.0, |im| im.jump);
                    }
                    let (tangential, taken) = rough.contact(
                        c,
                        (i, j),
                        s,
                        &self.material,
                        &normal,
                        (&dv, &mid),
                        predicting,
                        (xi, force),
                    );
                    for k in 0..D {
                        impulse[k] += tangential[k];
                    }
                    power += taken;
                    stress.add_tangential(d, &normal, &tangential);
                }
            }
            self.impulses.push(impulse);
            let relative = xi / contact;
            if relative > self.statistics.max_relative_overlap {
                self.statistics.max_relative_overlap = relative;
            }
        }
        self.find_wall_contacts(predicting);
        for &i in &self.active {
            self.forces[i as usize] = [0.0; D];
            self.touching[i as usize] = 0;
        }
        if EXTENDED {
            if let Some(rough) = &mut self.rough {
                for &i in &self.active {
                    rough.history.torques[i as usize] = [0.0; 3];
                }
            }
        }
        self.active.clear();
        for (&(i, j), f) in self.current.iter().zip(&self.impulses) {
            for p in [i, j] {
                let t = &mut self.touching[p as usize];
                *t = t.saturating_add(1);
                match *t {
                    1 => {
                        self.statistics.contact_steps += 1;
                        self.active.push(p);
                    }
                    2 => self.statistics.multi_contact_steps += 1,
                    _ => {}
                }
            }
            let (i, j) = (i as usize, j as usize);
            for (k, f) in f.iter().enumerate() {
                self.forces[i][k] -= f;
                self.forces[j][k] += f;
            }
        }
        if EXTENDED {
            if let Some(rough) = &mut self.rough {
                rough.add_torques(&self.current);
            }
        }
        self.add_container_forces();
        // Contacts begun: in `current` but not in the previous list (both sorted).
        let mut begun = 0;
        let mut old = self.contacts.iter().peekable();
        for &pair in &self.current {
            while old.peek().is_some_and(|&&p| p < pair) {
                old.next();
            }
            if old.peek() != Some(&&pair) {
                begun += 1;
                let (i, j) = (pair.0 as usize, pair.1 as usize);
                self.collision_counts[i] = self.collision_counts[i].wrapping_add(1);
                self.collision_counts[j] = self.collision_counts[j].wrapping_add(1);
            }
        }
        std::mem::swap(&mut self.contacts, &mut self.current);
        if EXTENDED {
            self.stress_rate = stress;
        }
        (power, virial, begun)
    }

    /// The dissipated power, virial rate and (`EXTENDED`) tensor virial rate of the current
    /// contacts with the current velocities (the trapezoid's left end).
    fn contact_rates<const EXTENDED: bool>(&self) -> (f64, f64, Virial) {
        let (s, a) = (&self.system, self.material.dissipative_constant);
        let images = if EXTENDED {
            self.images_at(self.time)
        } else {
            None
        };
        let (mut power, mut virial) = (0.0, 0.0);
        let mut stress = Virial::default();
        for (c, &(i, j)) in self.contacts.iter().enumerate() {
            let (i, j) = (i as usize, j as usize);
            let (r, across): (Vector<D>, f64) = match &images {
                Some(images) => images.separation(&s.positions[i], &s.positions[j], &s.sides),
                None => (
                    std::array::from_fn(|k| {
                        minimum_image(s.positions[j][k] - s.positions[i][k], s.sides[k])
                    }),
                    0.0,
                ),
            };
            let d = r.iter().map(|x| x * x).sum::<f64>().sqrt();
            let xi = s.radii[i] + s.radii[j] - d;
            let mut dv: Vector<D> =
                std::array::from_fn(|k| s.velocities[j][k] - s.velocities[i][k]);
            if EXTENDED && across != 0.0 {
                dv[0] += across * images.as_ref().map_or(0.0, |im| im.jump);
            }
            let xi_dot = -(0..D).map(|k| dv[k] * r[k] / d).sum::<f64>();
            let rho = self.material.elastic_constant(s.radii[i], s.radii[j]);
            let (force, dissipative) = normal_force(rho, a, xi, xi_dot);
            power += dissipative * xi_dot;
            virial += force * d;
            if EXTENDED {
                let normal: Vector<D> = std::array::from_fn(|k| r[k] / d);
                stress.add(force, d, &normal);
                if let Some(rough) = &self.rough {
                    let (t, taken) =
                        rough.now(c, (i, j), s, &self.material, &normal, &dv, (xi, force));
                    power += taken;
                    stress.add_tangential(d, &normal, &t);
                }
            }
        }
        (power, virial, stress)
    }
}
