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
//! Cells that move with the flow. In the lab frame a sphere near the top of the box flies
//! along x with the flow's speed, up to a L_y, and would cross a cell every w / (a L_y):
//! in a dilute gas those crossings would outnumber the collisions tenfold. So each row of
//! cells (the cells of one index along y) slides along x with the flow at its centre,
//! u_j = a (j + 1/2) w_y: a sphere's column is counted in its row's frame, x − u_j t
//! (modulo L_x), and it crosses columns at its speed relative to that frame, its peculiar
//! velocity within a w_y / 2. Adjacent rows slide past each other by Δ(t) = a w_y t
//! (modulo L_x), and so do the top row and the images of the bottom row above the box
//! (u_0 + a L_y − u_{n−1} = a w_y): every pair of adjacent rows, the one across the
//! sheared faces included, is offset alike.
//!
//! Neighbours across rows. While Δ stays in [m w, (m + 1) w] (w the cells' width along
//! x), a sphere in column c can only touch spheres of the row above in its columns
//! c − m − 2 ..= c − m + 1 (four, not three: the row above straddles two columns), and
//! of the row below in c + m − 1 ..= c + m + 2. When Δ passes a multiple of w (every
//! w / (|a| w_y)) each window gains one column: at these *shifts* every sphere is checked
//! against the spheres of its two new columns (its predictions stay valid: the cells only
//! decide whom a sphere is checked against). m is the index of the shift interval (modulo
//! the columns), not Δ / w, so that rounding at a shift never picks the wrong set. A
//! sphere crossing into the next column sees one new column of each row (as a periodic
//! grid's layer of cells); one crossing into another row is placed in the column of its
//! position in that row's frame and predicted anew.
//!
//! Crossing a face. A sphere that leaves the top row upward re-enters the bottom row as
//! its image: y − L_y, x − δ (wrapped), v_x − a L_y, in the cell of its new place, and is
//! predicted anew. Between crossings y is never wrapped (a wrap without the shift of x
//! would move the sphere); a sphere a rounding beyond a face still belongs to the cell it
//! was put in.

mod sliding;

use super::{EventDriven, Particle};
use crate::error::{Error, Result};
use crate::shear::Shear;
use crate::system::{wrap, wrap_far, Vector};
use sliding::{Block, Columns};

/// The shear flow as the engine applies it.
#[derive(Debug, Clone, Copy)]
pub(super) struct LeesEdwards {
    pub shear: Shear,
    /// a L_y: the velocity of the images above relative to the box.
    pub jump: f64,
    /// The cells' height w_y (the rows' spacing).
    row_height: f64,
    /// Time between shifts, w_x / (|a| w_y).
    period: f64,
    /// Index of the current shift interval: the shifts before now.
    interval: u64,
}

impl LeesEdwards {
    /// The columns the row above is offset by in the current interval (Δ in
    /// [m w, (m + 1) w]), as m modulo the columns.
    fn columns_offset(&self, columns: usize) -> usize {
        let k = self.interval % columns as u64;
        if self.shear.rate > 0.0 {
            k as usize
        } else {
            // Δ decreases: in the interval k it lies in [-(k + 1) w, -k w] modulo L_x.
            (columns - 1 - k as usize) % columns
        }
    }

    /// The time of the next shift.
    fn next_shift(&self) -> f64 {
        (self.interval + 1) as f64 * self.period
    }

    /// The velocity of the cells of row `row` along x: the flow at the row's centre.
    #[inline]
    fn row_velocity(&self, row: u32) -> f64 {
        self.shear.rate * (row as f64 + 0.5) * self.row_height
    }

    /// How far the cells of row `row` have slid along x at time t, in [0, length)
    /// (`wrap_far`: no library call, unlike `rem_euclid`'s fmod).
    #[inline]
    fn row_offset(&self, row: u32, time: f64, length: f64) -> f64 {
        wrap_far(self.row_velocity(row) * time, length)
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
        let row_height = self.grid.width[1];
        let period = self.grid.width[0] / (shear.rate * row_height).abs();
        LeesEdwards {
            shear,
            jump,
            row_height,
            period,
            interval: (self.time / period).floor().max(0.0) as u64,
        }
    }

    /// The time of the next shift of the columns across the rows, if sheared.
    #[inline]
    pub(super) fn next_shift(&self) -> Option<f64> {
        self.shear.as_ref().map(LeesEdwards::next_shift)
    }

    /// The cell of a sphere at `p` (in the box but for y a rounding beyond a face):
    /// under shear its column in the frame of its row's cells.
    pub(super) fn cell_of(&self, p: &Vector<D>) -> [u32; D] {
        let mut c = self.grid.coords_of(p);
        if self.shear.is_some() {
            c[0] = self.column_in_row(c[1], p[0]);
        }
        c
    }

    /// The column of the cells of row `row` that holds x now.
    fn column_in_row(&self, row: u32, x: f64) -> u32 {
        let le = self.shear.expect("sheared");
        let length = self.grid.sides[0];
        let relative = wrap(x - le.row_offset(row, self.time, length), length);
        ((relative / self.grid.width[0]) as usize).min(self.grid.per_side[0] - 1) as u32
    }

    /// The first exit of sphere i (at `p` with `v` now) from its cell, whose row slides
    /// along x with the flow at its centre.
    pub(super) fn exit_sheared(
        &self,
        i: usize,
        p: &Vector<D>,
        v: &Vector<D>,
    ) -> Option<(f64, usize, bool)> {
        let le = self.shear.expect("sheared");
        let cell = &self.particles[i].cell;
        let length = self.grid.sides[0];
        let (mut q, mut u) = (*p, *v);
        q[0] = wrap(p[0] - le.row_offset(cell[1], self.time, length), length);
        u[0] = v[0] - le.row_velocity(cell[1]);
        self.grid.exit(cell, &q, &u)
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

    /// The offset δ(t) of the images above the box, now.
    #[inline]
    pub(super) fn offset(&self, le: &LeesEdwards) -> f64 {
        le.shear.offset(self.time, &self.system.sides)
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

    /// The crossing of i into the next row up (`up`) or down: in the column of its
    /// position in that row's frame; through a sheared face it re-enters on the other
    /// side as its image.
    #[cold]
    #[inline(never)]
    pub(super) fn cross_row(&mut self, i: usize, up: bool) {
        let le = self.shear.expect("sheared");
        self.bring_to_now(i);
        let mut c = self.particles[i].cell;
        let last = self.grid.per_side[1] as u32 - 1;
        if self.through_a_face(&c, 1, up) {
            let (q, u) = {
                let p = &self.particles[i];
                self.image_across(&le, &p.position, &p.velocity, up)
            };
            let p = &mut self.particles[i];
            p.position = q;
            p.velocity = u;
        }
        c[1] = match (up, c[1] == last) {
            (true, true) => 0,
            (true, false) => c[1] + 1,
            (false, _) if c[1] == 0 => last,
            (false, _) => c[1] - 1,
        };
        let before = c[0] as usize;
        c[0] = self.column_in_row(c[1], self.particles[i].position[0]);
        self.remove(i);
        self.insert(i, c);
        // From column c of its old row, i lands in column c − m − 1 or c − m of the row
        // above (c + m or c + m + 1 of the row below). Its new row's three columns were in
        // its old window of that row, and its old row's new window is its old three columns
        // and one more; only the row beyond is new. (Any other column, a rounding at a
        // corner: predicted anew.)
        let columns = self.grid.per_side[0];
        let m = le.columns_offset(columns);
        let expected = if up {
            before + 2 * columns - m - 1
        } else {
            before + columns + m
        };
        let landed = (c[0] as usize + columns - expected % columns) % columns;
        if landed > 1 {
            self.predict(i);
            return;
        }
        let [above, _, below] = self.windows(i);
        let all = self.all_depths(i);
        // The old row's extra column: the new window's first (landed 0) or last.
        let extra = |w: Columns| Columns {
            first: if landed == 0 { w.first } else { w.first + 3 },
            count: 1,
        };
        let blocks = if up {
            [Block::new(1, above, all), Block::new(-1, extra(below), all)]
        } else {
            [Block::new(-1, below, all), Block::new(1, extra(above), all)]
        };
        self.predict_crossing_as::<true>(i);
        let (pi, vi) = self.now(i);
        let best = self.scan_blocks(i, &pi, &vi, &blocks);
        self.keep_if_earlier(i, best);
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
            if let Some(dt) = self.collision_delay(&p, &v, j, sigma, &super::AnyImage(self.image)) {
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

impl<const D: usize> EventDriven<D> {
    /// A sphere of a sheared gas that lies outside its cell now (beyond a rounding), in
    /// its row's sliding frame along x; O(N): for tests.
    #[doc(hidden)]
    pub fn misplaced_sphere(&self) -> Option<usize> {
        let le = self.shear?;
        let (length, width) = (self.grid.sides[0], self.grid.width[0]);
        (0..self.particles.len()).find(|&i| {
            let (x, _) = self.now(i);
            let p = &self.particles[i];
            let relative = wrap(x[0] - le.row_offset(p.cell[1], self.time, length), length);
            let centre = (p.cell[0] as f64 + 0.5) * width;
            let d = crate::system::minimum_image_within(relative - centre, length, 0.5 * length);
            let height = self.grid.width[1];
            let dy = x[1] - (p.cell[1] as f64 + 0.5) * height;
            d.abs() > 0.5 * width * (1.0 + 1e-9) || dy.abs() > 0.5 * height * (1.0 + 1e-9)
        })
    }
}
