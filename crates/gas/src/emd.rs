//! Event-driven molecular dynamics of smooth inelastic hard spheres.
//!
//! Particles stream freely between events; each particle stores only its earliest
//! predicted event (a collision or leaving its cell) in an indexed heap, and positions are
//! updated lazily (each particle knows the time at which its stored position is valid).
//! A predicted collision carries the partner's collision count at prediction time; it is
//! stale if the partner has collided since and is then re-predicted (Marín, Risso & Cordero
//! 1993). At each collision eps comes from the `Restitution` law with the normal impact
//! speed.

use crate::cells::CellGrid;
use crate::queue::EventQueue;
use crate::system::{dot, wrap, System, Vector};
use restitution::Restitution;

/// The predictions of a particle: its earliest collision (with the partner's collision
/// count at prediction time) and the moment it leaves its cell. Keeping both lets a cell
/// crossing look only at the newly adjacent layer of cells.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Next {
    collision: f64,
    partner: u32,
    partner_count: u64,
    crossing: f64,
    dim: u8,
    up: bool,
}

impl Next {
    const NONE: Next = Next {
        collision: f64::INFINITY,
        partner: u32::MAX,
        partner_count: 0,
        crossing: f64::INFINITY,
        dim: 0,
        up: false,
    };

    fn time(&self) -> f64 {
        self.collision.min(self.crossing)
    }
}

/// Counters and accumulators of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Tally {
    /// Collisions processed.
    pub collisions: u64,
    /// All events processed (collisions, cell crossings, stale predictions).
    pub events: u64,
    /// Kinetic energy dissipated.
    pub energy_lost: f64,
    /// Sum over collisions of the momentum transfer times the contact distance (virial).
    pub virial: f64,
}

/// The event-driven engine.
pub struct EventDriven<const D: usize> {
    system: System<D>,
    law: Box<dyn Restitution>,
    time: f64,
    valid_at: Vec<f64>,
    counts: Vec<u64>,
    next: Vec<Next>,
    queue: EventQueue,
    cells: CellGrid<D>,
    tally: Tally,
}

impl<const D: usize> EventDriven<D> {
    /// An engine at time 0 with cells one diameter wide; fails if spheres overlap.
    pub fn new(system: System<D>, law: Box<dyn Restitution>) -> Result<Self, String> {
        Self::with_cell_width(system, law, 0.0)
    }

    /// As [`EventDriven::new`] with cells at least `min_width` wide (and at least one
    /// diameter). At least 4 cells per side are required: then two particles in adjacent
    /// cells are closer than L/2 in every direction, so the minimum image used to predict
    /// their collision is the image that collides. (With fewer cells, or all pairs, a
    /// prediction far ahead can pick the wrong periodic image and miss a collision.)
    pub fn with_cell_width(
        mut system: System<D>,
        law: Box<dyn Restitution>,
        min_width: f64,
    ) -> Result<Self, String> {
        let n = system.len();
        let max_diameter = 2.0 * system.radii.iter().cloned().fold(0.0, f64::max);
        if max_diameter <= 0.0 {
            return Err("particles need a positive radius".into());
        }
        let mut cells = CellGrid::new(system.length, max_diameter.max(min_width), n);
        if cells.per_side < 4 {
            return Err(format!(
                "the box (side {}) must hold at least 4 cells of width {} per side",
                system.length,
                max_diameter.max(min_width)
            ));
        }
        for (i, p) in system.positions.iter_mut().enumerate() {
            for x in p.iter_mut() {
                *x = wrap(*x, system.length);
            }
            cells.insert(i, cells.coords_of(p));
        }
        let mut engine = EventDriven {
            system,
            law,
            time: 0.0,
            valid_at: vec![0.0; n],
            counts: vec![0; n],
            next: vec![Next::NONE; n],
            queue: EventQueue::new(n),
            cells,
            tally: Tally::default(),
        };
        engine.check_overlaps()?;
        for i in 0..n {
            engine.predict(i);
        }
        Ok(engine)
    }

    fn check_overlaps(&self) -> Result<(), String> {
        for i in 0..self.system.len() {
            let mut overlap = None;
            self.cells.for_each_neighbor(&self.cells.coords[i], |j| {
                if j > i {
                    let d = self
                        .system
                        .separation(&self.system.positions[i], &self.system.positions[j]);
                    let sigma = self.system.radii[i] + self.system.radii[j];
                    if dot(&d, &d) < sigma * sigma * (1.0 - 1e-12) {
                        overlap = Some(j);
                    }
                }
            });
            if let Some(j) = overlap {
                return Err(format!("particles {i} and {j} overlap"));
            }
        }
        Ok(())
    }

    pub fn time(&self) -> f64 {
        self.time
    }

    /// Bytes held by the engine's per-particle and per-cell arrays (state, predictions,
    /// calendar, cell lists).
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        let s = &self.system;
        let state = s.positions.capacity() * size_of::<Vector<D>>()
            + s.velocities.capacity() * size_of::<Vector<D>>()
            + (s.radii.capacity() + s.masses.capacity() + self.valid_at.capacity())
                * size_of::<f64>()
            + self.counts.capacity() * size_of::<u64>()
            + self.next.capacity() * size_of::<Next>();
        state + self.queue.memory_bytes() + self.cells.memory_bytes()
    }

    pub fn tally(&self) -> Tally {
        self.tally
    }

    /// Collisions per particle so far (each collision counts for two particles).
    pub fn collisions_per_particle(&self) -> f64 {
        2.0 * self.tally.collisions as f64 / self.system.len() as f64
    }

    /// The state with every position brought to the current time.
    pub fn system(&mut self) -> &System<D> {
        for i in 0..self.system.len() {
            self.bring_to_now(i);
        }
        &self.system
    }

    fn position_at(&self, i: usize, t: f64) -> Vector<D> {
        let dt = t - self.valid_at[i];
        let (p, v) = (&self.system.positions[i], &self.system.velocities[i]);
        std::array::from_fn(|k| p[k] + v[k] * dt)
    }

    fn bring_to_now(&mut self, i: usize) {
        let p = self.position_at(i, self.time);
        let length = self.system.length;
        self.system.positions[i] = std::array::from_fn(|k| wrap(p[k], length));
        self.valid_at[i] = self.time;
    }

    /// Time from now until i and j touch, if they approach.
    fn collision_delay(&self, i: usize, j: usize) -> Option<f64> {
        let (pi, pj) = (
            self.position_at(i, self.time),
            self.position_at(j, self.time),
        );
        let r = self.system.separation(&pi, &pj);
        let (vi, vj) = (&self.system.velocities[i], &self.system.velocities[j]);
        let v: Vector<D> = std::array::from_fn(|k| vj[k] - vi[k]);
        let b = dot(&r, &v);
        if b >= 0.0 {
            return None;
        }
        let sigma = self.system.radii[i] + self.system.radii[j];
        let gap = dot(&r, &r) - sigma * sigma;
        if gap <= 0.0 {
            return Some(0.0);
        }
        let v2 = dot(&v, &v);
        let disc = b * b - v2 * gap;
        // gap / (-b + sqrt(disc)) is the smaller root without cancellation.
        (disc >= 0.0).then(|| gap / (-b + disc.sqrt()))
    }

    /// Predicts and schedules the events of particle i from scratch.
    fn predict(&mut self, i: usize) {
        self.next[i].collision = f64::INFINITY;
        self.predict_crossing(i);
        let c = self.cells.coords[i];
        let mut best = (f64::INFINITY, 0, 0);
        self.cells
            .for_each_neighbor(&c, |j| self.consider(i, j, &mut best));
        self.keep_if_earlier(i, best);
    }

    /// After i entered a new cell: only the layer of cells beyond it is new to i.
    fn predict_after_crossing(&mut self, i: usize, dim: usize, up: bool) {
        if self.cells.per_side < 3 {
            return self.predict(i);
        }
        self.predict_crossing(i);
        let c = self.cells.coords[i];
        let mut best = (f64::INFINITY, 0, 0);
        self.cells
            .for_each_in_layer(&c, dim, up, |j| self.consider(i, j, &mut best));
        self.keep_if_earlier(i, best);
    }

    fn predict_crossing(&mut self, i: usize) {
        let p = self.position_at(i, self.time);
        let exit = self
            .cells
            .exit(&self.cells.coords[i], &p, &self.system.velocities[i]);
        let next = &mut self.next[i];
        match exit {
            Some((dt, dim, up)) => {
                next.crossing = self.time + dt;
                next.dim = dim as u8;
                next.up = up;
            }
            None => next.crossing = f64::INFINITY,
        }
    }

    /// Updates `best` = (time, partner, partner count) with the collision of i and j.
    fn consider(&self, i: usize, j: usize, best: &mut (f64, usize, u64)) {
        if j != i {
            if let Some(dt) = self.collision_delay(i, j) {
                if self.time + dt < best.0 {
                    *best = (self.time + dt, j, self.counts[j]);
                }
            }
        }
    }

    /// Stores the collision `best` if it is earlier than the one i has, and reschedules i.
    fn keep_if_earlier(&mut self, i: usize, best: (f64, usize, u64)) {
        let next = &mut self.next[i];
        if best.0 < next.collision {
            next.collision = best.0;
            next.partner = best.1 as u32;
            next.partner_count = best.2;
        }
        let t = next.time();
        self.queue.update(i, t);
    }

    /// Brings every particle to the current time, rebuilds the cell lists and predicts
    /// every event afresh: the state is then a function of (positions, velocities, time)
    /// alone, so a run restored from a snapshot taken here continues bit for bit.
    pub fn synchronize(&mut self) {
        let n = self.system.len();
        for i in 0..n {
            self.bring_to_now(i);
            self.cells.remove(i);
        }
        for i in 0..n {
            let c = self.cells.coords_of(&self.system.positions[i]);
            self.cells.insert(i, c);
            self.next[i] = Next::NONE;
        }
        for i in 0..n {
            self.predict(i);
        }
    }

    /// A synchronized engine from a snapshot: state at `time`, collision counts, tally.
    pub fn restore(
        system: System<D>,
        law: Box<dyn Restitution>,
        time: f64,
        counts: Vec<u64>,
        tally: Tally,
    ) -> Result<Self, String> {
        if counts.len() != system.len() {
            return Err("snapshot: counts and particles differ in number".into());
        }
        let mut engine = Self::new(system, law)?;
        engine.time = time;
        engine.valid_at.iter_mut().for_each(|t| *t = time);
        engine.counts = counts;
        engine.tally = tally;
        engine.synchronize();
        Ok(engine)
    }

    /// Collision counts per particle (for snapshots).
    pub fn counts(&self) -> &[u64] {
        &self.counts
    }

    /// A pair whose next collision is earlier than both particles' scheduled events
    /// (which the calendar must never allow), with that collision time. O(N^2): for tests.
    pub fn missed_collision(&self) -> Option<(usize, usize, f64)> {
        let n = self.system.len();
        for i in 0..n {
            for j in i + 1..n {
                if let Some(dt) = self.collision_delay(i, j) {
                    let t = self.time + dt;
                    let scheduled = self.queue.time_of(i).min(self.queue.time_of(j));
                    if t < scheduled * (1.0 - 1e-12) - 1e-12 {
                        return Some((i, j, t));
                    }
                }
            }
        }
        None
    }

    /// Processes the next event; false if there is none (all particles at rest).
    pub fn step(&mut self) -> bool {
        let Some((i, t)) = self.queue.peek() else {
            return false;
        };
        if !t.is_finite() {
            return false;
        }
        self.time = t;
        self.tally.events += 1;
        let next = self.next[i];
        if next.crossing <= next.collision {
            self.bring_to_now(i);
            self.cells.shift(i, next.dim as usize, next.up);
            self.predict_after_crossing(i, next.dim as usize, next.up);
        } else {
            let j = next.partner as usize;
            if self.counts[j] == next.partner_count {
                self.collide(i, j);
                self.predict(i);
                self.predict(j);
            } else {
                self.predict(i);
            }
        }
        true
    }

    /// The collision of i and j at the current time.
    fn collide(&mut self, i: usize, j: usize) {
        self.bring_to_now(i);
        self.bring_to_now(j);
        let s = &mut self.system;
        let r = s.separation(&s.positions[i], &s.positions[j]);
        let distance = dot(&r, &r).sqrt();
        let n: Vector<D> = std::array::from_fn(|k| r[k] / distance);
        let (vi, vj) = (s.velocities[i], s.velocities[j]);
        let approach = -(0..D).map(|k| (vj[k] - vi[k]) * n[k]).sum::<f64>();
        let eps = self.law.eps(approach.max(0.0));
        let (mi, mj) = (s.masses[i], s.masses[j]);
        let reduced = mi * mj / (mi + mj);
        let impulse = (1.0 + eps) * reduced * approach;
        for (k, nk) in n.iter().enumerate() {
            s.velocities[i][k] -= impulse / mi * nk;
            s.velocities[j][k] += impulse / mj * nk;
        }
        self.counts[i] += 1;
        self.counts[j] += 1;
        self.tally.collisions += 1;
        self.tally.energy_lost += 0.5 * reduced * (1.0 - eps * eps) * approach * approach;
        self.tally.virial += impulse * distance;
    }

    /// Runs until `collisions` more collisions have happened (or nothing moves).
    pub fn run_collisions(&mut self, collisions: u64) {
        let target = self.tally.collisions + collisions;
        while self.tally.collisions < target && self.step() {}
    }

    /// Runs until the time reaches `t` (events at later times stay pending).
    pub fn run_until(&mut self, t: f64) {
        while let Some((_, next)) = self.queue.peek() {
            if next > t || !self.step() {
                break;
            }
        }
        self.time = self.time.max(t);
    }
}
