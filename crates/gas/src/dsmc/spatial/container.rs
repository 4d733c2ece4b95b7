//! The spatial engine in a container: walls and gravity act during streaming. DSMC
//! particles are points, so a wall is touched when the particle's position reaches the
//! wall's plane (0 or L, a vibrating wall's d(t) or L − d(t)); each contact is found at its
//! exact time within the step (straight flights; with gravity the roots of
//! [`crate::walls::fall_exit`]; against a vibrating wall [`crate::walls::first_contact`]),
//! the wall acts ([`crate::walls::Walls`]' rules), and the flight goes on for the rest of
//! the step. A thermal wall draws from a stream of (seed, step, the particle's state at the
//! start of the step), so a run does not depend on the order of the particles or on the
//! threads; the contacts' tallies are summed exactly.

use super::super::kernel::Simulator;
use super::record::Particle;
use super::SpatialDsmc;
use crate::error::Result;
use crate::rng::{Purpose, Stream};
use crate::system::{wrap, Vector};
use crate::walls::{fall_exit, first_contact, ContactSums, Side, Walls, WallsState};
use rayon::prelude::*;

/// Contacts of one particle within one step beyond which it stays where it is for the rest
/// of the step (a point pressed onto a floor by gravity with `rest_height` = 0 would
/// bounce in place for ever).
const MAX_CONTACTS_PER_STEP: usize = 64;

impl<const D: usize> SpatialDsmc<D> {
    /// Puts the gas into a container with `walls` (None: periodic again). Fails if
    /// vibrating walls sweep the whole box. Takes up the walls' tallies from a restored
    /// check-point. On several ranks each streams its particles; the walls' tallies are
    /// summed over the ranks exactly every step.
    pub fn set_walls(&mut self, walls: Option<Walls<D>>) -> Result<()> {
        let mut walls = walls;
        if let Some(w) = walls.as_mut() {
            w.check_sweeps(&self.sides, 0.0)?;
        }
        crate::walls::take_up(walls.as_mut(), self.saved_walls.take())?;
        self.walls = walls;
        Ok(())
    }

    /// Lets every particle fall with the acceleration `g` (None: no field), floors sending
    /// particles off at least as fast as a bounce `rest_height` high needs (the resting
    /// rule). Gravity needs walls on both sides of every axis it acts along.
    pub fn set_gravity(&mut self, g: Option<Vector<D>>, rest_height: f64) -> Result<()> {
        let Some(g) = g.filter(|g| g.iter().any(|&x| x != 0.0)) else {
            self.gravity = None;
            return Ok(());
        };
        crate::walls::fit_gravity(self.walls.as_mut(), &g, rest_height)?;
        self.gravity = Some(g);
        Ok(())
    }

    /// The walls' state to save (None: periodic).
    pub(super) fn walls_state(&self) -> Option<WallsState> {
        self.walls.as_ref().map(|w| w.state())
    }

    /// Streams every particle of `records` (this rank's) for `dt` in the container,
    /// tallying the walls. Walls are smooth for rough particles: a contact changes the
    /// velocity as the wall's rule says and leaves the spin alone (no torque), as in the
    /// event-driven engine.
    pub(super) fn stream_in_container<R: Particle<D>>(&mut self, records: &mut [R], dt: f64) {
        let Some(walls) = self.walls.as_ref() else {
            return;
        };
        let flight = Flight {
            walls,
            g: self.gravity.unwrap_or([0.0; D]),
            sides: self.sides,
            start: self.time,
            dt,
            seed: self.seed,
            step: self.steps,
        };
        let masses = &self.species.masses;
        let count = walls.walls().len();
        let sums = records
            .par_chunks_mut(4096)
            .map(|chunk| {
                let mut sums = vec![ContactSums::default(); count];
                for p in chunk {
                    let p = p.body_mut();
                    flight.stream(p, masses[p.species as usize], &mut sums);
                }
                sums
            })
            .reduce(
                || vec![ContactSums::default(); count],
                |mut a, b| {
                    a.iter_mut().zip(&b).for_each(|(x, y)| x.merge(y));
                    a
                },
            );
        let sums = if self.comm.size() > 1 {
            super::super::reduce::contact_sums_over_ranks(
                &sums,
                self.comm.as_ref(),
                &mut self.traffic,
            )
        } else {
            sums
        };
        let walls = self.walls.as_mut().expect("walls present");
        for (index, s) in sums.iter().enumerate() {
            walls.add_sums(index, s);
        }
    }
}

/// One step's streaming in a container.
struct Flight<'a, const D: usize> {
    walls: &'a Walls<D>,
    g: Vector<D>,
    sides: Vector<D>,
    start: f64,
    dt: f64,
    seed: u64,
    step: u64,
}

impl<const D: usize> Flight<'_, D> {
    /// Streams particle `p` (mass `mass`) for the step, wall contacts included.
    fn stream(&self, p: &mut Simulator<D>, mass: f64, sums: &mut [ContactSums]) {
        let (walls, g, sides) = (self.walls, &self.g, &self.sides);
        let mut stream: Option<Stream> = None;
        let key = state_key(p);
        let (mut x, mut v) = (p.position, p.velocity);
        let mut elapsed = 0.0;
        let mut last = None;
        for n in 0..=MAX_CONTACTS_PER_STEP {
            let left = self.dt - elapsed;
            let Some((s, index)) = self.first_contact(&x, &v, left) else {
                last = None;
                break;
            };
            if n == MAX_CONTACTS_PER_STEP {
                break;
            }
            last = Some(index);
            advance(&mut x, &mut v, g, s);
            let wall = &walls.walls()[index];
            let t = self.start + elapsed + s;
            let plane = walls.motion(index).map_or(0.0, |m| m.displacement(t));
            x[wall.axis] = match wall.side {
                Side::Low => plane,
                Side::High => sides[wall.axis] - plane,
            };
            let stream = stream
                .get_or_insert_with(|| Stream::new(self.seed, Purpose::Walls, self.step, key));
            if let Some(contact) = walls.contact(index, mass, &mut v, t, stream) {
                sums[index].add(&contact);
            }
            elapsed += s;
        }
        match last {
            // Contacts without end: the point rests on that wall for the rest of the step.
            Some(index) => self.rest(index, &mut x, &mut v, mass, elapsed, &mut sums[index]),
            None => advance(&mut x, &mut v, g, self.dt - elapsed),
        }
        // Positions stay in [0, L) on every axis (check-points and cells expect it): a
        // point on the high wall is kept a rounding below it.
        for (k, c) in x.iter_mut().enumerate() {
            let length = sides[k];
            *c = if walls.closed(k) {
                c.clamp(0.0, f64::from_bits(length.to_bits() - 1))
            } else {
                wrap(*c, length)
            };
        }
        p.position = x;
        p.velocity = v;
    }

    /// The rest of the step from `elapsed` on, for a point that touched wall `index` more
    /// than [`MAX_CONTACTS_PER_STEP`] times: it moves with the wall along its axis (the
    /// normal velocity the wall's, the position its plane) and flies freely across it. The
    /// wall's work and impulse on it are tallied as one contact, so energy balances stay
    /// exact.
    fn rest(
        &self,
        index: usize,
        x: &mut Vector<D>,
        v: &mut Vector<D>,
        mass: f64,
        elapsed: f64,
        sums: &mut ContactSums,
    ) {
        let wall = &self.walls.walls()[index];
        let k = wall.axis;
        let energy = |x: &Vector<D>, v: &Vector<D>| {
            (0..D)
                .map(|j| 0.5 * mass * v[j] * v[j] - mass * self.g[j] * x[j])
                .sum::<f64>()
        };
        let (before, vk) = (energy(x, v), v[k]);
        let span = self.dt - elapsed;
        advance(x, v, &self.g, span);
        let t = self.start + self.dt;
        let motion = self.walls.motion(index);
        let (plane, speed) = motion.map_or((0.0, 0.0), |m| (m.displacement(t), m.velocity(t)));
        let inward = match wall.side {
            Side::Low => 1.0,
            Side::High => -1.0,
        };
        x[k] = if inward > 0.0 {
            plane
        } else {
            self.sides[k] - plane
        };
        v[k] = inward * speed;
        // The wall's impulse on the point along k, m dv − m g dt, given back to the wall.
        let impulse = mass * (v[k] - vk) - mass * self.g[k] * span;
        sums.add(&crate::walls::Contact {
            momentum: inward * impulse,
            energy: energy(x, v) - before,
            lift: None,
        });
    }

    /// The first wall contact within `left` of a point at x with velocity v: (delay, wall).
    fn first_contact(&self, x: &Vector<D>, v: &Vector<D>, left: f64) -> Option<(f64, usize)> {
        let (walls, g) = (self.walls, &self.g);
        let mut first: Option<(f64, usize)> = None;
        for k in (0..D).filter(|&k| walls.closed(k)) {
            let length = self.sides[k];
            let reach = if g[k] != 0.0 {
                Some(fall_exit(x[k], v[k], g[k], 0.0, length))
            } else if v[k] < 0.0 {
                Some((x[k].max(0.0) / -v[k], false))
            } else if v[k] > 0.0 {
                Some(((length - x[k]).max(0.0) / v[k], true))
            } else {
                None
            };
            if let Some((s, high)) = reach {
                let side = if high { Side::High } else { Side::Low };
                let index = walls.at(k, side).expect("a closed axis has both walls");
                if s <= left && first.is_none_or(|f| s < f.0) {
                    first = Some((s, index));
                }
            }
        }
        if !walls.vibrates() {
            return first;
        }
        let t0 = self.start + (self.dt - left);
        for (index, wall) in walls.walls().iter().enumerate() {
            let Some(motion) = walls.motion(index) else {
                continue;
            };
            let k = wall.axis;
            let length = self.sides[k];
            let (y, w, c) = match wall.side {
                Side::Low => (x[k], v[k], g[k]),
                Side::High => (length - x[k], -v[k], -g[k]),
            };
            let horizon = first.map_or(left, |f| f.0);
            let gap = |s: f64| {
                let t = t0 + s;
                (
                    y + w * s + 0.5 * c * s * s - motion.displacement(t),
                    w + c * s - motion.velocity(t),
                )
            };
            let contact = first_contact(
                gap,
                c.abs() + motion.max_acceleration(),
                |s| motion.next_kink(t0 + s) - t0,
                horizon,
                1e-13 * length,
            );
            if let Some(s) = contact {
                if first.is_none_or(|f| s <= f.0) {
                    first = Some((s, index));
                }
            }
        }
        first
    }
}

/// x and v after a flight of s under acceleration g.
#[inline]
fn advance<const D: usize>(x: &mut Vector<D>, v: &mut Vector<D>, g: &Vector<D>, s: f64) {
    for k in 0..D {
        x[k] += v[k] * s + 0.5 * g[k] * s * s;
        v[k] += g[k] * s;
    }
}

/// A key of a particle's state (its position and velocity bits), for its wall stream.
fn state_key<const D: usize>(p: &Simulator<D>) -> u64 {
    let mut h = 0x9E37_79B9_7F4A_7C15u64 ^ p.species as u64;
    for x in p.position.iter().chain(&p.velocity) {
        h = (h ^ x.to_bits())
            .wrapping_mul(0xBF58_476D_1CE4_E5B9)
            .rotate_left(29);
    }
    h
}
