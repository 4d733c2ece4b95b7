//! Cell lists: the periodic box cut into cells at least one interaction range wide, so
//! that a particle can only collide with particles in its own and the adjacent cells.
//!
//! [`Grid`] is the geometry (which cells neighbour which, when a particle leaves its cell);
//! [`CellGrid`] adds doubly linked lists of particles per cell. The event-driven engine
//! keeps its list links inside its particle records instead (one cache line per
//! neighbour visited) and uses [`Grid`] alone.

use crate::system::{minimum_image_within, wrap, Vector};

/// The end of a cell list.
pub const NONE: u32 = u32::MAX;

/// A periodic grid of `per_side[0]` x ... x `per_side[D-1]` cells (cubes in a cubic box).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid<const D: usize> {
    /// Cells along each axis.
    pub per_side: [usize; D],
    /// Width of a cell along each axis.
    pub width: [f64; D],
    /// The box's sides (width times cells).
    pub sides: [f64; D],
    /// Half the sides (the minimum image's bounds).
    pub halves: [f64; D],
    /// The fewest cells along an axis (one test in the scans instead of one per axis).
    pub fewest: usize,
}

/// The most cells a grid for `n` particles has: 1024 per particle (and 2^20 for few): a
/// very dilute gas gets wider cells instead of memory beyond its particles' (and a
/// packing fraction near 0 no overflowing cell count). Gases denser than about
/// phi = 1e-3 in 3D (2e-3 in 2D) are below it and keep cells one diameter wide.
pub fn max_cells(n: usize) -> usize {
    n.saturating_mul(1024).max(1 << 20)
}

impl<const D: usize> Grid<D> {
    /// The grid of a box with `sides` with cells at least `min_width` wide and at most
    /// `max_cells` cells.
    pub fn new(sides: &Vector<D>, min_width: f64, max_cells: usize) -> Self {
        let per_side: [usize; D] = if crate::system::is_cube(sides) {
            // The cube's rule: at most max_cells^(1/D) per side.
            let most = (max_cells as f64).powf(1.0 / D as f64).floor();
            [(sides[0] / min_width).floor().min(most).max(1.0) as usize; D]
        } else {
            // Cells as narrow as allowed, widened by the same factor along every axis
            // until there are at most max_cells.
            let mut width = min_width;
            loop {
                let per: [usize; D] =
                    std::array::from_fn(|k| (sides[k] / width).floor().max(1.0) as usize);
                let total = per.iter().map(|&c| c as f64).product::<f64>();
                if total <= max_cells as f64 {
                    break per;
                }
                width *= (total / max_cells as f64)
                    .powf(1.0 / D as f64)
                    .max(1.0 + 1e-9);
            }
        };
        let width: [f64; D] = std::array::from_fn(|k| sides[k] / per_side[k] as f64);
        let sides: [f64; D] = std::array::from_fn(|k| width[k] * per_side[k] as f64);
        Grid {
            per_side,
            width,
            sides,
            halves: sides.map(|l| 0.5 * l),
            fewest: per_side.iter().copied().min().unwrap_or(1),
        }
    }

    /// Number of cells.
    pub fn cells(&self) -> usize {
        self.per_side.iter().product()
    }

    /// The fewest cells along any axis.
    pub fn fewest_per_side(&self) -> usize {
        self.fewest
    }

    /// The cell coordinates of a position (wrapped into the box first).
    pub fn coords_of(&self, p: &Vector<D>) -> [u32; D] {
        std::array::from_fn(|k| {
            let c = (wrap(p[k], self.sides[k]) / self.width[k]) as usize;
            c.min(self.per_side[k] - 1) as u32
        })
    }

    /// The linear index of the cell with coordinates c.
    #[inline]
    pub fn index(&self, c: &[u32; D]) -> usize {
        (0..D)
            .rev()
            .fold(0, |acc, k| acc * self.per_side[k] + c[k] as usize)
    }

    /// The coordinates of the cell one step from c along dimension k (periodically).
    #[inline]
    pub fn shifted(&self, c: &[u32; D], k: usize, up: bool) -> [u32; D] {
        let mut c = *c;
        let n = self.per_side[k] as u32;
        c[k] = if up {
            (c[k] + 1) % n
        } else {
            (c[k] + n - 1) % n
        };
        c
    }

    /// The distinct coordinates c-1, c, c+1 along axis k (periodically; fewer with fewer
    /// than 3 cells along it) times the axis' stride, and how many there are.
    #[inline]
    fn adjacent_parts(&self, x: usize, k: usize, stride: usize) -> ([usize; 3], usize) {
        let n = self.per_side[k];
        if n < 3 {
            // Every cell along the axis is adjacent: each once.
            return ([0, stride, 0], n);
        }
        let below = if x == 0 { n - 1 } else { x - 1 };
        let above = if x + 1 == n { 0 } else { x + 1 };
        ([below * stride, x * stride, above * stride], 3)
    }

    /// Linear indices of cell c and its adjacent cells, each once (also with fewer than 3
    /// cells along an axis); the first `count` entries are valid.
    #[inline]
    pub fn neighbor_cells(&self, c: &[u32; D]) -> ([usize; 27], usize) {
        let mut cells = [0; 27];
        if self.fewest >= 3 {
            // Three cells along every axis (the engines' case), the loop unrolled.
            // Linear-index contributions of coordinates c-1, c, c+1 along each axis.
            let mut stride = 1;
            let parts: [[usize; 3]; D] = std::array::from_fn(|k| {
                let (x, n) = (c[k] as usize, self.per_side[k]);
                let below = if x == 0 { n - 1 } else { x - 1 };
                let above = if x + 1 == n { 0 } else { x + 1 };
                let part = [below * stride, x * stride, above * stride];
                stride *= n;
                part
            });
            let mut count = 1;
            for part in &parts {
                // Each existing entry spawns three: (entry + part[0], + part[1], + part[2]).
                for e in (0..count).rev() {
                    let base = cells[e];
                    cells[3 * e] = base + part[0];
                    cells[3 * e + 1] = base + part[1];
                    cells[3 * e + 2] = base + part[2];
                }
                count *= 3;
            }
            return (cells, count);
        }
        if self.per_side.iter().all(|&n| n < 3) {
            // Every cell is adjacent: each once, in linear order.
            let count = self.cells();
            for (i, cell) in cells.iter_mut().enumerate().take(count) {
                *cell = i;
            }
            return (cells, count);
        }
        let mut stride = 1;
        let mut count = 1;
        for (k, &ck) in c.iter().enumerate() {
            let (part, width) = self.adjacent_parts(ck as usize, k, stride);
            stride *= self.per_side[k];
            // Each existing entry spawns `width`: (entry + part[0], + part[1], ...).
            for e in (0..count).rev() {
                let base = cells[e];
                for (o, &p) in part.iter().enumerate().take(width) {
                    cells[width * e + o] = base + p;
                }
            }
            count *= width;
        }
        (cells, count)
    }

    /// Linear indices of the layer of neighbour cells beyond cell c along dimension k (the
    /// cells a particle that just entered c from the other side had not seen); needs at
    /// least 3 cells along every axis. The first `count` entries are valid.
    #[inline]
    pub fn layer_cells(&self, c: &[u32; D], k: usize, up: bool) -> ([usize; 9], usize) {
        debug_assert!(self.fewest_per_side() >= 3);
        let mut stride = 1;
        let parts: [[usize; 3]; D] = std::array::from_fn(|d| {
            let n = self.per_side[d];
            let base = c[d] as usize;
            let part = if d == k {
                let layer = if up { 1 } else { n - 1 };
                [(base + layer) % n * stride; 3]
            } else {
                [n - 1, 0, 1].map(|o| (base + o) % n * stride)
            };
            stride *= n;
            part
        });
        let mut cells = [0; 9];
        let count = 3usize.pow(D as u32 - 1);
        for (combo, cell) in cells.iter_mut().enumerate().take(count) {
            let mut rest = combo;
            for (d, part) in parts.iter().enumerate() {
                if d == k {
                    *cell += part[0];
                } else {
                    *cell += part[rest % 3];
                    rest /= 3;
                }
            }
        }
        (cells, count)
    }

    /// Time until a particle at p (in its cell c) moving with v leaves the cell, the
    /// dimension and the direction; None if it never does (one cell per side, or v = 0).
    pub fn exit(&self, c: &[u32; D], p: &Vector<D>, v: &Vector<D>) -> Option<(f64, usize, bool)> {
        let mut best: Option<(f64, usize, bool)> = None;
        for k in 0..D {
            if v[k] == 0.0 || (self.fewest < 2 && self.per_side[k] < 2) {
                continue;
            }
            let width = self.width[k];
            // Offset from the cell's lower face, robust to positions just across a wrap.
            let centre = (c[k] as f64 + 0.5) * width;
            let x =
                minimum_image_within(p[k] - centre, self.sides[k], self.halves[k]) + 0.5 * width;
            let dt = if v[k] > 0.0 {
                (width - x) / v[k]
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

/// Doubly linked cell lists over a [`Grid`].
#[derive(Debug, Clone)]
pub struct CellGrid<const D: usize> {
    pub grid: Grid<D>,
    head: Vec<u32>,
    next: Vec<u32>,
    prev: Vec<u32>,
    /// Cell coordinates of each particle.
    pub coords: Vec<[u32; D]>,
}

impl<const D: usize> CellGrid<D> {
    /// A grid for `n` particles in a box with `sides`, cells at least `min_width` wide.
    pub fn new(sides: &Vector<D>, min_width: f64, n: usize) -> Self {
        let grid = Grid::new(sides, min_width, max_cells(n));
        CellGrid {
            grid,
            head: vec![NONE; grid.cells()],
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

    /// The cell coordinates of a position.
    pub fn coords_of(&self, p: &Vector<D>) -> [u32; D] {
        self.grid.coords_of(p)
    }

    /// Puts particle i into the cell with coordinates c.
    pub fn insert(&mut self, i: usize, c: [u32; D]) {
        let cell = self.grid.index(&c);
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
            let cell = self.grid.index(&self.coords[i]);
            self.head[cell] = n;
        }
        if n != NONE {
            self.prev[n as usize] = p;
        }
    }

    /// Moves particle i one cell along dimension k (periodically).
    pub fn shift(&mut self, i: usize, k: usize, up: bool) {
        let c = self.grid.shifted(&self.coords[i], k, up);
        self.remove(i);
        self.insert(i, c);
    }

    /// Calls f for every particle in the cell with linear index `cell`.
    pub fn for_each_in_cell(&self, cell: usize, mut f: impl FnMut(usize)) {
        let mut j = self.head[cell];
        while j != NONE {
            f(j as usize);
            j = self.next[j as usize];
        }
    }

    /// Calls f for every particle in the cells adjacent to (and including) cell c.
    pub fn for_each_neighbor(&self, c: &[u32; D], mut f: impl FnMut(usize)) {
        let (cells, count) = self.grid.neighbor_cells(c);
        for &cell in &cells[..count] {
            let mut j = self.head[cell];
            while j != NONE {
                f(j as usize);
                j = self.next[j as usize];
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Neighbour and layer cells agree with a brute-force periodic distance test.
    #[test]
    fn neighbour_cells_are_the_adjacent_ones() {
        let shapes = [1usize, 2, 3, 4, 7].map(|n| [n; 3]).into_iter().chain([
            [1, 3, 5],
            [4, 2, 3],
            [3, 3, 6],
            [5, 4, 3],
        ]);
        for per_side in shapes {
            let grid = Grid::<3> {
                per_side,
                width: [1.0; 3],
                sides: per_side.map(|n| n as f64),
                halves: per_side.map(|n| 0.5 * n as f64),
                fewest: per_side.into_iter().min().unwrap(),
            };
            let adjacent = |a: &[u32; 3], b: &[u32; 3]| {
                (0..3).all(|k| {
                    let n = per_side[k] as i64;
                    let d = (a[k] as i64 - b[k] as i64).rem_euclid(n);
                    d <= 1 || d == n - 1
                })
            };
            let [px, py, _] = per_side.map(|p| p as u32);
            let all: Vec<[u32; 3]> = (0..grid.cells())
                .map(|i| {
                    let i = i as u32;
                    [i % px, i / px % py, i / (px * py)]
                })
                .collect();
            for c in &all {
                let (cells, count) = grid.neighbor_cells(c);
                let mut got: Vec<usize> = cells[..count].to_vec();
                got.sort();
                let mut want: Vec<usize> = all
                    .iter()
                    .filter(|b| adjacent(c, b))
                    .map(|b| grid.index(b))
                    .collect();
                want.sort();
                assert_eq!(got, want, "per_side {per_side:?}, cell {c:?}");
                if grid.fewest_per_side() >= 3 {
                    for k in 0..3 {
                        for up in [false, true] {
                            let (layer, count) = grid.layer_cells(c, k, up);
                            let beyond = grid.shifted(c, k, up);
                            let mut got: Vec<usize> = layer[..count].to_vec();
                            got.sort();
                            let mut want: Vec<usize> = all
                                .iter()
                                .filter(|b| b[k] == beyond[k] && adjacent(c, b))
                                .map(|b| grid.index(b))
                                .collect();
                            want.sort();
                            assert_eq!(got, want);
                        }
                    }
                }
            }
        }
    }
}
