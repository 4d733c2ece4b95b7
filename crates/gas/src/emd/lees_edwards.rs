//! Lees–Edwards boundaries in the event-driven engine (uniform shear flow u = a y e_x; see
//! [`crate::shear`]).
//!
//! Velocities are the lab frame's, so spheres fly straight between events, as in the
//! periodic box. The images above the box sit at x + δ(t), y + L_y and move with
//! v + a L_y e_x; δ(t) = a L_y t grows linearly, so an image's flight is straight too, and
//! a pair across the upper or lower face is predicted as any other: the sphere in the
//! boundary row is moved to its image on the other side (x ∓ δ, y ∓ L_y, v_x ∓ a L_y) and
//! paired with the spheres of the row across, by the minimum image along x (DynamO's
//! sheared boundaries do the same; Bannerman, Sargant & Lue, J. Comput. Chem. 32, 3329
//! (2011)).
//!
//! Cells across a face. A sphere in column c of the top row can only touch, while δ stays
//! in [m w, (m + 1) w] (w the cells' width along x), spheres of the bottom row whose
//! images lie within one cell of its column: the columns c − m − 2 ..= c − m + 1 (four, not
//! three: the images straddle two columns). A sphere of the bottom row sees the top
//! row's columns c + m − 1 ..= c + m + 2. When δ passes a multiple of w (every
//! w / (|a| L_y)) the columns move by one: at these *shifts* the spheres of both boundary
//! rows are predicted anew. m is the index of the shift interval (modulo the columns),
//! not δ / w, so that rounding at a shift never picks the wrong set.
//!
//! Crossing a face. A sphere that leaves the top row upward re-enters the bottom row as
//! its image: y − L_y, x − δ (wrapped), v_x − a L_y, in the cell of its new place, and is
//! predicted anew (its new neighbours are not one layer of cells). Between crossings y is
//! never wrapped (a wrap without the shift of x would move the sphere); a sphere a
//! rounding beyond a face still belongs to the cell it was put in.

use super::predict::Best;
use super::{EventDriven, Particle};
use crate::error::{Error, Result};
use crate::shear::Shear;
use crate::system::{wrap, Vector};

/// The shear flow as the engine applies it.
#[derive(Debug, Clone, Copy)]
pub(super) struct LeesEdwards {
    pub shear: Shear,
    /// a L_y: the velocity of the images above relative to the box.
    pub jump: f64,
    /// Time between shifts, w / (|a| L_y).
    period: f64,
    /// Index of the current shift interval: the shifts before now.
    interval: u64,
}

impl LeesEdwards {
    /// The columns the images of the row across are offset by in the current interval
    /// (δ in [m w, (m + 1) w]), as m modulo the columns.
    fn columns_offset(&self, columns: usize) -> usize {
        let k = self.interval % columns as u64;
        if self.shear.rate > 0.0 {
            k as usize
        } else {
            // δ decreases: in the interval k it lies in [-(k + 1) w, -k w] modulo L_x.
            (columns - 1 - k as usize) % columns
        }
    }

    /// The time of the next shift.
    fn next_shift(&self) -> f64 {
        (self.interval + 1) as f64 * self.period
    }
}

impl<const D: usize> EventDriven<D> {
    /// Shears the gas: Lees–Edwards boundaries with the flow u = rate y e_x (flow along x,
    /// gradient along y), the flow added to every velocity (the gas's velocities become
    /// the peculiar ones), every event predicted anew. None: periodic again (the flow is
    /// taken out). Fails in 1D, in a container, with gravity, and (`rate`) for a rate
    /// that is not finite and nonzero.
    pub fn set_shear(&mut self, shear: Option<Shear>) -> Result<()> {
        if let Some(s) = &shear {
            s.check_for::<D>()?;
            if self.walls.is_some() || self.field.is_some() {
                return Err(Error::out_of_range(
                    "shear",
                    "a container or gravity",
                    "a periodic box (Lees-Edwards boundaries on x and y)",
                ));
            }
        }
        self.synchronize();
        let old = self.shear.map(|le| le.shear);
        for p in &mut self.particles {
            let y = p.position[1];
            if let Some(s) = &old {
                p.velocity[0] -= s.flow(y);
            }
            if let Some(s) = &shear {
                p.velocity[0] += s.flow(y);
            }
        }
        self.shear = shear.map(|s| self.lees_edwards(s));
        self.synchronize();
        Ok(())
    }

    /// The shear flow, if the gas is sheared.
    pub fn shear(&self) -> Option<Shear> {
        self.shear.map(|le| le.shear)
    }

    /// The engine's form of `shear` at the current time.
    pub(super) fn lees_edwards(&self, shear: Shear) -> LeesEdwards {
        let sides = &self.system.sides;
        let jump = shear.jump(sides);
        let period = self.grid.width[0] / jump.abs();
        LeesEdwards {
            shear,
            jump,
            period,
            interval: (self.time / period).floor().max(0.0) as u64,
        }
    }

    /// The time of the next shift of the columns across the faces, if sheared.
    #[inline]
    pub(super) fn next_shift(&self) -> Option<f64> {
        self.shear.as_ref().map(LeesEdwards::next_shift)
    }

    /// The shift at its time (not later than the next event): the spheres of the top and
    /// bottom rows predicted anew.
    #[cold]
    #[inline(never)]
    pub(super) fn shift(&mut self) {
        let Some(le) = self.shear.as_mut() else {
            return;
        };
        self.time = self.time.max(le.next_shift());
        le.interval += 1;
        let last = self.grid.per_side[1] as u32 - 1;
        let rows: Vec<usize> = (0..self.particles.len())
            .filter(|&i| {
                let row = self.particles[i].cell[1];
                row == 0 || row == last
            })
            .collect();
        for i in rows {
            self.predict(i);
        }
    }

    /// The offset δ(t) of the images above the box, now.
    #[inline]
    pub(super) fn offset(&self, le: &LeesEdwards) -> f64 {
        le.shear.offset(self.time, &self.system.sides)
    }

    /// Whether i's cell is in the top or bottom row.
    #[inline]
    pub(super) fn on_a_face(&self, i: usize) -> bool {
        let row = self.particles[i].cell[1];
        row == 0 || row as usize == self.grid.per_side[1] - 1
    }

    /// The collisions of i (in a boundary row, now at `pi` with velocity `vi`) with the
    /// spheres of its own image and of the row across the face, into `best`.
    #[cold]
    #[inline(never)]
    pub(super) fn scan_sheared(&self, i: usize, pi: &Vector<D>, vi: &Vector<D>, best: &mut Best) {
        let image = self.image;
        self.for_each_sheared_neighbor(i, pi, vi, |p, v, j| {
            self.consider(i, p, v, j, best, &image)
        });
    }

    /// Calls f(p, v, j) for every sphere j that i (in a boundary row, at `pi` with `vi`)
    /// can meet before the next shift: those of the neighbour cells in the box with i as it
    /// is, those of the row across the face with i's image on that side.
    pub(super) fn for_each_sheared_neighbor(
        &self,
        i: usize,
        pi: &Vector<D>,
        vi: &Vector<D>,
        mut f: impl FnMut(&Vector<D>, &Vector<D>, usize),
    ) {
        let le = self.shear.expect("sheared");
        let cell = self.particles[i].cell;
        let (per_side, last) = (self.grid.per_side, self.grid.per_side[1] as u32 - 1);
        let top = cell[1] == last;
        let across = if top { 0 } else { last };
        // This image: the neighbour cells but the row across.
        let (cells, count) = self.grid.neighbor_cells(&cell);
        for &c in &cells[..count] {
            if (c / per_side[0] % per_side[1]) as u32 != across {
                self.for_each_in_cell(c, |j| f(pi, vi, j));
            }
        }
        // The row across: i as its image on that side; four columns.
        let (shifted, moved) = self.image_across(&le, pi, vi, top);
        let columns = per_side[0];
        let m = le.columns_offset(columns);
        let first = if top {
            cell[0] as usize + 2 * columns - m - 2
        } else {
            cell[0] as usize + columns + m - 1
        };
        let depth = if D == 3 { 3 } else { 1 };
        let mut c = cell;
        c[1] = across;
        for dz in 0..depth {
            if D == 3 {
                let n = per_side[D - 1];
                c[D - 1] = ((cell[D - 1] as usize + n + dz - 1) % n) as u32;
            }
            for dx in 0..4 {
                c[0] = ((first + dx) % columns) as u32;
                let index = self.grid.index(&c);
                self.for_each_in_cell(index, |j| f(&shifted, &moved, j));
            }
        }
    }

    /// A sphere at `p` with velocity `v` as its image across the top face (`top`) or the
    /// bottom one: the frame of the row across.
    #[inline]
    fn image_across(
        &self,
        le: &LeesEdwards,
        p: &Vector<D>,
        v: &Vector<D>,
        top: bool,
    ) -> (Vector<D>, Vector<D>) {
        let (sides, delta) = (&self.system.sides, self.offset(le));
        let sign = if top { -1.0 } else { 1.0 };
        let mut q = *p;
        q[0] = wrap(p[0] + sign * delta, sides[0]);
        q[1] = p[1] + sign * sides[1];
        let mut u = *v;
        u[0] += sign * le.jump;
        (q, u)
    }

    /// The separation b − a of the nearest images of a and b (both at the current time)
    /// and the velocity of b's image along x less b's: across a face b's image is moved.
    #[inline]
    pub(super) fn sheared_separation(&self, a: &Particle<D>, b: &Particle<D>) -> (Vector<D>, f64) {
        let le = self.shear.expect("sheared");
        let height = self.system.sides[1];
        let dy = b.position[1] - a.position[1];
        if dy.abs() <= 0.5 * height {
            return (self.separation(&a.position, &b.position), 0.0);
        }
        // b above a's image... b's image on a's side.
        let top = dy > 0.0;
        let (q, _) = self.image_across(&le, &b.position, &b.velocity, top);
        let sign = if top { -1.0 } else { 1.0 };
        (self.separation(&a.position, &q), sign * le.jump)
    }

    /// The crossing of i through the top (`up`) or bottom face: it re-enters on the other
    /// side as its image, in the cell of its new place.
    #[cold]
    #[inline(never)]
    pub(super) fn cross_face(&mut self, i: usize, up: bool) {
        let le = self.shear.expect("sheared");
        self.bring_to_now(i);
        let (q, u) = {
            let p = &self.particles[i];
            self.image_across(&le, &p.position, &p.velocity, up)
        };
        self.remove(i);
        let p = &mut self.particles[i];
        p.position = q;
        p.velocity = u;
        let mut c = self.grid.coords_of(&q);
        let last = self.grid.per_side[1] as u32 - 1;
        c[1] = if up { 0 } else { last };
        self.insert(i, c);
        self.predict(i);
    }

    /// Whether i's crossing in dimension `dim` (`up`) goes through a sheared face.
    #[inline]
    pub(super) fn through_a_face(&self, cell: &[u32; D], dim: usize, up: bool) -> bool {
        self.shear.is_some()
            && dim == 1
            && if up {
                cell[1] as usize == self.grid.per_side[1] - 1
            } else {
                cell[1] == 0
            }
    }

    /// A sphere's position brought into the box across the sheared faces (a rounding
    /// beyond a face), with its velocity.
    pub(super) fn brought_into_box(&self, p: &Vector<D>, v: &Vector<D>) -> (Vector<D>, Vector<D>) {
        let Some(le) = &self.shear else {
            return (*p, *v);
        };
        let height = self.system.sides[1];
        if p[1] >= height {
            self.image_across(le, p, v, true)
        } else if p[1] < 0.0 {
            let (mut q, u) = self.image_across(le, p, v, false);
            // -tiny + L may round to L, which a wrap would take to 0 without the shift.
            if q[1] >= height {
                q[1] = height * (1.0 - f64::EPSILON);
            }
            (q, u)
        } else {
            (*p, *v)
        }
    }

    /// The peculiar velocity (less the flow at its height) of a sphere at `p` with `v`.
    #[inline]
    pub(super) fn peculiar(&self, p: &Vector<D>, v: &Vector<D>) -> Vector<D> {
        match &self.shear {
            None => *v,
            Some(le) => le.shear.peculiar(p[1], v),
        }
    }

    /// [`EventDriven::missed_collision`] for one pair of a sheared gas: the pair's
    /// collision time with b's nearest image (the direct one or one across a face), if
    /// it is earlier than both particles' scheduled events. O(1); for tests.
    pub(super) fn missed_across(&self, i: usize, j: usize) -> Option<f64> {
        let le = self.shear.expect("sheared");
        let (pi, vi) = self.now(i);
        let pj = self.particles[j].position_at(self.time);
        let height = self.system.sides[1];
        let sigma = self.sigma(i, j);
        let mut images = vec![(pi, vi)];
        images.push(self.image_across(&le, &pi, &vi, true));
        images.push(self.image_across(&le, &pi, &vi, false));
        let scheduled = self.queue.time_of(i).min(self.queue.time_of(j));
        for (p, v) in images {
            if (pj[1] - p[1]).abs() > 0.5 * height {
                continue;
            }
            if let Some(dt) = self.collision_delay(&p, &v, j, sigma, &self.image) {
                let t = self.time + dt;
                // Collisions after the next shift are predicted at the shift.
                let horizon = scheduled.min(self.next_shift().unwrap_or(f64::INFINITY));
                if t < horizon * (1.0 - 1e-12) - 1e-12 {
                    return Some(t);
                }
            }
        }
        None
    }
}
