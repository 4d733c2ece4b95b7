//! Predictions of the event-driven engine: each particle's earliest collision with a
//! neighbour and its next cell crossing, and the cell lists they scan.

use super::{EventDriven, Particle};
use crate::cells::NONE;
use crate::system::{dot, Vector};

impl<const D: usize> EventDriven<D> {
    /// Time from now until a sphere at `pi` with velocity `vi` touches j (contact
    /// distance `sigma`), if they approach. (Always inlined: the pair loop's body.)
    #[inline(always)]
    pub(super) fn collision_delay<I: super::Images<D>>(
        &self,
        pi: &Vector<D>,
        vi: &Vector<D>,
        j: usize,
        sigma: f64,
        image: &I,
    ) -> Option<f64> {
        let pj = &self.particles[j];
        let r = image.separation(pi, &pj.position_at(self.time));
        let v: Vector<D> = std::array::from_fn(|k| pj.velocity[k] - vi[k]);
        let b = dot(&r, &v);
        if b >= 0.0 {
            return None;
        }
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
    pub(super) fn predict(&mut self, i: usize) {
        self.predict_as::<true>(i);
    }

    /// [`Self::predict`]; `EXTENDED = false` only where the engine is not sheared.
    pub(super) fn predict_as<const EXTENDED: bool>(&mut self, i: usize) {
        self.particles[i].collision = f64::INFINITY;
        self.predict_crossing_as::<EXTENDED>(i);
        let mut best = Best::NONE;
        let (pi, vi) = self.now(i);
        // (The periodic scan written out here, not behind a helper taking `best` by
        // reference: kept in registers, it was 12 % fewer instructions.)
        if EXTENDED && self.shear.is_some() {
            self.scan_sheared(i, &pi, &vi, &mut best);
        } else {
            let image = self.image;
            self.for_each_neighbor(i, |j| self.consider(i, &pi, &vi, j, &mut best, &image));
        }
        self.keep_if_earlier(i, best);
    }

    /// Predicts every particle's events from scratch, as [`Self::predict`] for i = 0, 1, ...
    /// would (the same records and sorter updates in the same order), the neighbour scans
    /// in parallel: they only read the state.
    pub(super) fn predict_all(&mut self) {
        use rayon::prelude::*;
        let this = &*self;
        // (cell exit: delay, dimension, direction; earliest collision) per particle.
        type Prediction = (Option<(f64, usize, bool)>, Best);
        let predictions: Vec<Prediction> = (0..this.particles.len())
            .into_par_iter()
            .map(|i| {
                let (pi, vi) = this.now(i);
                let mut best = Best::NONE;
                let exit = if this.shear.is_some() {
                    this.exit_sheared(i, &pi, &vi)
                } else {
                    this.exit_of(i, &pi, &vi)
                };
                if this.shear.is_some() {
                    this.scan_sheared(i, &pi, &vi, &mut best);
                } else {
                    let image = this.image;
                    this.for_each_neighbor(i, |j| this.consider(i, &pi, &vi, j, &mut best, &image));
                }
                (exit, best)
            })
            .collect();
        for (i, (exit, best)) in predictions.into_iter().enumerate() {
            let next = &mut self.particles[i];
            next.collision = f64::INFINITY;
            match exit {
                Some((dt, dim, up)) => {
                    next.crossing = self.time + dt;
                    next.exit_dim = dim as u8;
                    next.exit_up = up;
                }
                None => next.crossing = f64::INFINITY,
            }
            self.keep_if_earlier(i, best);
        }
    }

    /// After i entered a new cell: only the layer of cells beyond it is new to i
    /// (`EXTENDED` as in [`Self::predict_as`]).
    pub(super) fn predict_after_crossing_as<const EXTENDED: bool>(
        &mut self,
        i: usize,
        dim: usize,
        up: bool,
    ) {
        if EXTENDED && self.shear.is_some() {
            // The rows slide: one column of each, or one layer along z, is new.
            self.predict_crossing_as::<true>(i);
            let mut best = Best::NONE;
            let (pi, vi) = self.now(i);
            self.scan_sheared_layer(i, &pi, &vi, dim, up, &mut best);
            self.keep_if_earlier(i, best);
            return;
        }
        self.predict_crossing_as::<false>(i);
        let mut best = Best::NONE;
        let (pi, vi) = self.now(i);
        let (cell, image) = (self.particles[i].cell, self.image);
        let (mut cells, mut count) = self.grid.layer_cells(&cell, dim, up);
        if let Some(walls) = &self.walls {
            count = self.keep_inside(walls, &cell, &mut cells, count);
        }
        self.prefetch_heads(&cells[..count]);
        for &cell in &cells[..count] {
            self.for_each_in_cell(cell, |j| self.consider(i, &pi, &vi, j, &mut best, &image));
        }
        self.keep_if_earlier(i, best);
    }

    /// Calls f for every particle in the cell with linear index `cell`.
    #[inline]
    pub(super) fn for_each_in_cell(&self, cell: usize, mut f: impl FnMut(usize)) {
        if self.occupied[cell / 64] & (1 << (cell % 64)) == 0 {
            return;
        }
        let mut j = self.heads[cell];
        while j != NONE {
            f(j as usize);
            j = self.particles[j as usize].next_in_cell;
        }
    }

    /// Calls f for every particle in the cell of i and the adjacent cells (i included).
    #[inline]
    pub(super) fn for_each_neighbor(&self, i: usize, mut f: impl FnMut(usize)) {
        let cell = self.particles[i].cell;
        let (mut cells, mut count) = self.grid.neighbor_cells(&cell);
        if let Some(walls) = &self.walls {
            count = self.keep_inside(walls, &cell, &mut cells, count);
        }
        self.prefetch_heads(&cells[..count]);
        for &cell in &cells[..count] {
            self.for_each_in_cell(cell, &mut f);
        }
    }

    /// In a container: drops from the `count` cells around cell `c` those that lie across a
    /// wall (the periodic neighbours of a cell along a closed axis), so that no pair is
    /// predicted through a wall; returns how many are left at the front of `cells`.
    #[inline(never)]
    pub(super) fn keep_inside(
        &self,
        walls: &crate::walls::Walls<D>,
        c: &[u32; D],
        cells: &mut [usize],
        count: usize,
    ) -> usize {
        let per_side = self.grid.per_side;
        if !(0..D).any(|k| walls.closed(k) && (c[k] == 0 || c[k] as usize == per_side[k] - 1)) {
            return count;
        }
        let mut kept = 0;
        for index in 0..count {
            let cell = cells[index];
            let mut stride = 1;
            let mut inside = true;
            for (k, &ck) in c.iter().enumerate() {
                let n = per_side[k];
                let x = (cell / stride % n) as u32;
                inside &= !walls.closed(k) || x.abs_diff(ck) <= 1;
                stride *= n;
            }
            if inside {
                cells[kept] = cell;
                kept += 1;
            }
        }
        kept
    }

    /// Fetches the record of the first particle of each occupied cell of `cells` before a
    /// scan visits them, so that the cache misses overlap instead of following each other
    /// (in a dense gas, waiting for each neighbour's record was a third of the run time;
    /// docs/event-driven.md).
    #[inline]
    pub(super) fn prefetch_heads(&self, cells: &[usize]) {
        if !self.prefetch_scans {
            return;
        }
        for &cell in cells {
            if self.occupied[cell / 64] & (1 << (cell % 64)) != 0 {
                super::prefetch_first_line(&self.particles[self.heads[cell] as usize]);
            }
        }
    }

    /// Puts particle i into the cell with coordinates c.
    pub(super) fn insert(&mut self, i: usize, c: [u32; D]) {
        let cell = self.grid.index(&c);
        let old = self.heads[cell];
        if old != NONE {
            self.particles[old as usize].prev_in_cell = i as u32;
        }
        let p = &mut self.particles[i];
        p.next_in_cell = old;
        p.prev_in_cell = NONE;
        p.cell = c;
        self.heads[cell] = i as u32;
        self.occupied[cell / 64] |= 1 << (cell % 64);
    }

    /// Takes particle i out of its cell.
    pub(super) fn remove(&mut self, i: usize) {
        let Particle {
            prev_in_cell: prev,
            next_in_cell: next,
            cell,
            ..
        } = self.particles[i];
        if prev != NONE {
            self.particles[prev as usize].next_in_cell = next;
        } else {
            let cell = self.grid.index(&cell);
            self.heads[cell] = next;
            if next == NONE {
                self.occupied[cell / 64] &= !(1 << (cell % 64));
            }
        }
        if next != NONE {
            self.particles[next as usize].prev_in_cell = prev;
        }
    }

    /// Position and velocity of i now.
    #[inline]
    pub(super) fn now(&self, i: usize) -> (Vector<D>, Vector<D>) {
        let p = &self.particles[i];
        (p.position_at(self.time), p.velocity)
    }

    /// The first of i's cell crossing and, in a container, its contact with a wall (as
    /// dimension k + D): delay from now, dimension, direction.
    #[inline(always)]
    fn exit_of(&self, i: usize, p: &Vector<D>, v: &Vector<D>) -> Option<(f64, usize, bool)> {
        match &self.walls {
            None => self.grid.exit(&self.particles[i].cell, p, v),
            Some(walls) => self.exit_or_wall(walls, i, p, v),
        }
    }

    /// [`Self::exit_of`] in a container: the cell exit or, if earlier, the contact with a
    /// wall; with gravity, along its axes, the first root of the fall to a face or wall
    /// (`p`, `v`: the falling frame's). (Out of line: the periodic box's path stays as
    /// short as before.)
    #[inline(never)]
    fn exit_or_wall(
        &self,
        walls: &crate::walls::Walls<D>,
        i: usize,
        p: &Vector<D>,
        v: &Vector<D>,
    ) -> Option<(f64, usize, bool)> {
        let cell = &self.particles[i].cell;
        let Some(field) = &self.field else {
            let exit = self.grid.exit(cell, p, v);
            let first = self.first_wall_contact(walls, i, p, v, exit);
            if !walls.vibrates() {
                return first;
            }
            return self.vibrating_contact(walls, i, p, v, &[0.0; D], first);
        };
        let (x, u) = field.to_box(p, v, self.time);
        // Straight flights across the axes without gravity, falls along the others.
        let straight: Vector<D> =
            std::array::from_fn(|k| if field.g[k] == 0.0 { u[k] } else { 0.0 });
        let mut first = self.grid.exit(cell, &x, &straight);
        first = self.first_wall_contact(walls, i, &x, &straight, first);
        let radius = self.particles[i].radius;
        for k in (0..D).filter(|&k| field.g[k] != 0.0) {
            let (width, last) = (self.grid.width[k], self.grid.per_side[k] as u32 - 1);
            // The axis is closed: the end cells' outer faces are the walls' contact planes.
            let low = if cell[k] == 0 {
                radius
            } else {
                cell[k] as f64 * width
            };
            let high = if cell[k] == last {
                self.system.sides[k] - radius
            } else {
                (cell[k] + 1) as f64 * width
            };
            let (dt, up) = super::gravity::fall_exit(x[k], u[k], field.g[k], low, high);
            let at_wall = if up { cell[k] == last } else { cell[k] == 0 };
            if first.is_none_or(|f| dt <= f.0) {
                first = Some((dt, if at_wall { k + D } else { k }, up));
            }
        }
        if walls.vibrates() {
            first = self.vibrating_contact(walls, i, &x, &u, &field.g, first);
        }
        first
    }

    /// The event `first` or, if earlier, the first contact of sphere i (at `x` with
    /// velocity `u` in the box, acceleration `a`) with a vibrating wall, found by
    /// [`crate::walls::first_contact`] up to `first`'s time (the sphere is predicted
    /// again at its next event anyway). The fixed contact planes of the other methods stay
    /// as early checks: a vibrating wall sweeps [0, 2A] from its face, so its contact
    /// comes first, and at a plane the bounce finds no approach and does nothing.
    fn vibrating_contact(
        &self,
        walls: &crate::walls::Walls<D>,
        i: usize,
        x: &Vector<D>,
        u: &Vector<D>,
        a: &Vector<D>,
        mut first: Option<(f64, usize, bool)>,
    ) -> Option<(f64, usize, bool)> {
        use crate::walls::Side;
        let (radius, t0) = (self.particles[i].radius, self.time);
        for (index, wall) in walls.walls().iter().enumerate() {
            let Some(motion) = walls.motion(index) else {
                continue;
            };
            let k = wall.axis;
            let length = self.system.sides[k];
            let horizon = first.map_or(f64::INFINITY, |f| f.0);
            // Distance of the centre from the wall's face, its speed and acceleration away.
            let (y, w, c) = match wall.side {
                Side::Low => (x[k], u[k], a[k]),
                Side::High => (length - x[k], -u[k], -a[k]),
            };
            let at = |s: f64| y + w * s + 0.5 * c * s * s;
            let mut lowest = if horizon.is_finite() {
                y.min(at(horizon))
            } else if w < 0.0 || c < 0.0 {
                f64::NEG_INFINITY
            } else {
                y
            };
            if c > 0.0 && w < 0.0 && -w / c < horizon {
                lowest = lowest.min(at(-w / c));
            }
            if lowest - radius > 2.0 * motion.amplitude {
                continue;
            }
            let gap = |s: f64| {
                let t = t0 + s;
                (
                    at(s) - radius - motion.displacement(t),
                    w + c * s - motion.velocity(t),
                )
            };
            let contact = crate::walls::first_contact(
                gap,
                c.abs() + motion.max_acceleration(),
                |s| motion.next_kink(t0 + s) - t0,
                horizon,
                1e-13 * length,
            );
            if let Some(s) = contact {
                if first.is_none_or(|f| s <= f.0) {
                    first = Some((s, k + D, wall.side == Side::High));
                }
            }
        }
        first
    }

    /// The cell exit `exit` or, if earlier, the contact with a wall of a sphere at `p`
    /// moving with `v` (straight).
    fn first_wall_contact(
        &self,
        walls: &crate::walls::Walls<D>,
        i: usize,
        p: &Vector<D>,
        v: &Vector<D>,
        exit: Option<(f64, usize, bool)>,
    ) -> Option<(f64, usize, bool)> {
        let cell = &self.particles[i].cell;
        // A wall can only be touched from the cell along it (a cell is at least a diameter
        // wide), before the particle would leave that cell through the wall's face.
        let radius = self.particles[i].radius;
        let mut first = exit;
        for k in (0..D).filter(|&k| walls.closed(k)) {
            let (length, last) = (self.system.sides[k], self.grid.per_side[k] as u32 - 1);
            let contact = if cell[k] == 0 && v[k] < 0.0 {
                Some(((p[k] - radius) / -v[k], false))
            } else if cell[k] == last && v[k] > 0.0 {
                Some(((length - radius - p[k]) / v[k], true))
            } else {
                None
            };
            if let Some((dt, up)) = contact {
                let dt = dt.max(0.0);
                if first.is_none_or(|f| dt <= f.0) {
                    first = Some((dt, k + D, up));
                }
            }
        }
        first
    }

    /// Predicts i's next cell crossing (`EXTENDED` as in [`Self::predict_as`]).
    #[inline(always)]
    pub(super) fn predict_crossing_as<const EXTENDED: bool>(&mut self, i: usize) {
        let (p, v) = self.now(i);
        let exit = if EXTENDED && self.shear.is_some() {
            self.exit_sheared(i, &p, &v)
        } else {
            self.exit_of(i, &p, &v)
        };
        let next = &mut self.particles[i];
        match exit {
            Some((dt, dim, up)) => {
                next.crossing = self.time + dt;
                next.exit_dim = dim as u8;
                next.exit_up = up;
            }
            None => next.crossing = f64::INFINITY,
        }
    }

    /// Updates `best` with the collision of i (now at `pi` with velocity `vi`) and j
    /// (inlined into the scans: as a call it cost 8 % at phi = 0.45).
    #[inline(always)]
    pub(super) fn consider<I: super::Images<D>>(
        &self,
        i: usize,
        pi: &Vector<D>,
        vi: &Vector<D>,
        j: usize,
        best: &mut Best,
        image: &I,
    ) {
        if j != i {
            if let Some(dt) = self.collision_delay(pi, vi, j, self.sigma(i, j), image) {
                if self.time + dt < best.time {
                    *best = Best {
                        time: self.time + dt,
                        partner: j as u32,
                        partner_count: self.particles[j].count,
                    };
                }
            }
        }
    }

    /// Stores the collision `best` if it is earlier than the one i has, and reschedules i.
    pub(super) fn keep_if_earlier(&mut self, i: usize, best: Best) {
        let next = &mut self.particles[i];
        if best.time < next.collision {
            next.collision = best.time;
            next.partner = best.partner;
            next.partner_count = best.partner_count;
        }
        let t = next.next_event();
        self.queue.update(i, t);
    }
}

/// The earliest collision found so far while scanning neighbours.
#[derive(Debug, Clone, Copy)]
pub(super) struct Best {
    pub(super) time: f64,
    pub(super) partner: u32,
    pub(super) partner_count: u32,
}

impl Best {
    pub(super) const NONE: Best = Best {
        time: f64::INFINITY,
        partner: u32::MAX,
        partner_count: 0,
    };
}
