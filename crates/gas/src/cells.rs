//! Cell lists: the periodic box cut into cells at least one interaction range wide, so
//! that a particle can only collide with particles in its own and the adjacent cells.

use crate::system::{minimum_image, wrap, Vector};

const NONE: u32 = u32::MAX;

/// Doubly linked cell lists over a grid of n^D cells.
#[derive(Debug, Clone)]
pub struct CellGrid<const D: usize> {
    /// Cells per dimension.
    pub per_side: usize,
    /// Width of a cell.
    pub width: f64,
    head: Vec<u32>,
    next: Vec<u32>,
    prev: Vec<u32>,
    /// Cell coordinates of each particle.
    pub coords: Vec<[u32; D]>,
}

impl<const D: usize> CellGrid<D> {
    /// A grid for `n` particles in a box of side `length`, cells at least `min_width` wide.
    pub fn new(length: f64, min_width: f64, n: usize) -> Self {
        let per_side = ((length / min_width).floor() as usize).max(1);
        CellGrid {
            per_side,
            width: length / per_side as f64,
            head: vec![NONE; per_side.pow(D as u32)],
            next: vec![NONE; n],
            prev: vec![NONE; n],
            coords: vec![[0; D]; n],
        }
    }

    /// Bytes held by the lists.
    pub fn memory_bytes(&self) -> usize {
        (self.head.capacity() + self.next.capacity() + self.prev.capacity()) * 4
            + self.coords.capacity() * std::mem::size_of::<[u32; D]>()
    }

    /// The cell coordinates of a position in [0, L).
    pub fn coords_of(&self, p: &Vector<D>) -> [u32; D] {
        let length = self.width * self.per_side as f64;
        std::array::from_fn(|k| {
            let c = (wrap(p[k], length) / self.width) as usize;
            c.min(self.per_side - 1) as u32
        })
    }

    fn index(&self, c: &[u32; D]) -> usize {
        c.iter()
            .rev()
            .fold(0, |acc, &x| acc * self.per_side + x as usize)
    }

    /// Puts particle i into the cell with coordinates c.
    pub fn insert(&mut self, i: usize, c: [u32; D]) {
        let cell = self.index(&c);
        let old = self.head[cell];
        self.next[i] = old;
        self.prev[i] = NONE;
        if old != NONE {
            self.prev[old as usize] = i as u32;
        }
        self.head[cell] = i as u32;
        self.coords[i] = c;
    }

    /// Takes particle i out of its cell.
    pub fn remove(&mut self, i: usize) {
        let (p, n) = (self.prev[i], self.next[i]);
        if p != NONE {
            self.next[p as usize] = n;
        } else {
            let cell = self.index(&self.coords[i]);
            self.head[cell] = n;
        }
        if n != NONE {
            self.prev[n as usize] = p;
        }
    }

    /// Moves particle i one cell along dimension k (periodically).
    pub fn shift(&mut self, i: usize, k: usize, up: bool) {
        let mut c = self.coords[i];
        let n = self.per_side as u32;
        c[k] = if up {
            (c[k] + 1) % n
        } else {
            (c[k] + n - 1) % n
        };
        self.remove(i);
        self.insert(i, c);
    }

    /// Calls f for every particle in the cells adjacent to (and including) cell c.
    pub fn for_each_neighbor(&self, c: &[u32; D], mut f: impl FnMut(usize)) {
        let n = self.per_side as i64;
        let span: i64 = if n >= 3 { 1 } else { 0 };
        let reach: Vec<i64> = if n >= 3 {
            vec![-1, 0, 1]
        } else {
            (0..n).collect()
        };
        let total = reach.len().pow(D as u32);
        for combo in 0..total {
            let mut rest = combo;
            let mut cell = [0u32; D];
            for k in 0..D {
                let offset = reach[rest % reach.len()];
                rest /= reach.len();
                let base = if span == 1 {
                    c[k] as i64 + offset
                } else {
                    offset
                };
                cell[k] = base.rem_euclid(n) as u32;
            }
            let mut j = self.head[self.index(&cell)];
            while j != NONE {
                f(j as usize);
                j = self.next[j as usize];
            }
        }
    }

    /// Calls f for every particle in the layer of neighbor cells beyond cell c along
    /// dimension k (the cells a particle that just entered c from the other side had not
    /// seen); needs at least 3 cells per side.
    pub fn for_each_in_layer(&self, c: &[u32; D], k: usize, up: bool, mut f: impl FnMut(usize)) {
        debug_assert!(self.per_side >= 3);
        let n = self.per_side as i64;
        let layer = if up { 1 } else { -1 };
        for combo in 0..3usize.pow(D as u32 - 1) {
            let mut rest = combo;
            let cell: [u32; D] = std::array::from_fn(|d| {
                let offset = if d == k {
                    layer
                } else {
                    let o = (rest % 3) as i64 - 1;
                    rest /= 3;
                    o
                };
                (c[d] as i64 + offset).rem_euclid(n) as u32
            });
            let mut j = self.head[self.index(&cell)];
            while j != NONE {
                f(j as usize);
                j = self.next[j as usize];
            }
        }
    }

    /// Time until a particle at p (in its cell c) moving with v leaves the cell, the
    /// dimension and the direction; None if it never does (one cell per side, or v = 0).
    pub fn exit(&self, c: &[u32; D], p: &Vector<D>, v: &Vector<D>) -> Option<(f64, usize, bool)> {
        if self.per_side < 2 {
            return None;
        }
        let length = self.width * self.per_side as f64;
        let mut best: Option<(f64, usize, bool)> = None;
        for k in 0..D {
            if v[k] == 0.0 {
                continue;
            }
            // Offset from the cell's lower face, robust to positions just across a wrap.
            let centre = (c[k] as f64 + 0.5) * self.width;
            let x = minimum_image(p[k] - centre, length) + 0.5 * self.width;
            let dt = if v[k] > 0.0 {
                (self.width - x) / v[k]
            } else {
                x / -v[k]
            };
            let dt = dt.max(0.0);
            if best.is_none_or(|b| dt < b.0) {
                best = Some((dt, k, v[k] > 0.0));
            }
        }
        best
    }
}
