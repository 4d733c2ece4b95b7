//! The scans of the cells that slide with the flow (see the parent module): the windows
//! of columns across rows, the blocks of cells a prediction, a crossing or a shift checks,
//! and the loops over them.

use crate::emd::predict::Best;
use crate::emd::EventDriven;
use crate::system::Vector;

/// Columns of a row: the first (counted from 0, taken modulo the columns) and how many.
#[derive(Debug, Clone, Copy)]
pub(super) struct Columns {
    pub(super) first: usize,
    pub(super) count: usize,
}

/// Cells of the row `step` rows above a sphere's (−1: below): `columns`, and the cells
/// along z `depths` (first, count; modulo their number).
#[derive(Debug, Clone, Copy)]
pub(super) struct Block {
    step: i32,
    columns: Columns,
    depths: (usize, usize),
}

impl Block {
    pub(super) fn new(step: i32, columns: Columns, depths: (usize, usize)) -> Self {
        Block {
            step,
            columns,
            depths,
        }
    }
}

impl<const D: usize> EventDriven<D> {
    /// The shift at its time (not later than the next event): every sphere checked
    /// against the spheres of the column each window across the rows gained.
    #[cold]
    #[inline(never)]
    pub(in crate::emd) fn shift(&mut self) {
        let Some(le) = self.shear.as_mut() else {
            return;
        };
        self.time = self.time.max(le.next_shift());
        le.interval += 1;
        // Each window (`windows`) gained one column: above, its first when m grew (a > 0)
        // and its last when m fell; below, the other way round.
        let grew = le.shear.rate > 0.0;
        let edge = |w: Columns, first: bool| Columns {
            first: if first {
                w.first
            } else {
                w.first + w.count - 1
            },
            count: 1,
        };
        for i in 0..self.particles.len() {
            let (pi, vi) = self.now(i);
            let [above, _, below] = self.windows(i);
            let all = self.all_depths(i);
            let blocks = [
                Block::new(1, edge(above, grew), all),
                Block::new(-1, edge(below, !grew), all),
            ];
            let best = self.scan_blocks(i, &pi, &vi, &blocks);
            if best.time < self.particles[i].collision {
                self.keep_if_earlier(i, best);
            }
        }
    }

    /// The cells along z around i's (all of its row's neighbours along z): first, count.
    #[inline]
    pub(super) fn all_depths(&self, i: usize) -> (usize, usize) {
        if D == 3 {
            let n = self.grid.per_side[D - 1];
            (self.particles[i].cell[D - 1] as usize + n - 1, 3)
        } else {
            (0, 1)
        }
    }

    /// The row `step` rows above i's (−1: below) and i (at `pi` with `vi`) as seen from
    /// it: as it is or, across a sheared face, as its image on that side.
    #[inline(always)]
    fn row_frame(
        &self,
        i: usize,
        pi: &Vector<D>,
        vi: &Vector<D>,
        step: i32,
    ) -> (u32, Vector<D>, Vector<D>) {
        let row = self.particles[i].cell[1];
        let last = self.grid.per_side[1] as u32 - 1;
        match step {
            1 if row == last => {
                let le = self.shear.expect("sheared");
                let (p, v) = self.image_across(&le, pi, vi, true);
                (0, p, v)
            }
            -1 if row == 0 => {
                let le = self.shear.expect("sheared");
                let (p, v) = self.image_across(&le, pi, vi, false);
                (last, p, v)
            }
            _ => ((row as i32 + step) as u32, *pi, *vi),
        }
    }

    /// The earliest collision of i (now at `pi` with `vi`) with the spheres of `blocks`.
    /// Away from the sheared faces i is the same in every row: one list of cells, one
    /// loop (as the periodic scans: half the instructions of a loop per block).
    #[inline]
    pub(super) fn scan_blocks(
        &self,
        i: usize,
        pi: &Vector<D>,
        vi: &Vector<D>,
        blocks: &[Block],
    ) -> Best {
        let image = crate::emd::AnyImage(self.image);
        let mut best = Best::NONE;
        let row = self.particles[i].cell[1];
        if row != 0 && row as usize + 1 != self.grid.per_side[1] {
            let mut cells = [0; 33];
            let mut count = 0;
            for block in blocks {
                let row = (row as i32 + block.step) as u32;
                self.for_each_cell_of_block(row, block, |cell| {
                    cells[count] = cell;
                    count += 1;
                });
            }
            self.prefetch_heads(&cells[..count]);
            for &cell in &cells[..count] {
                self.for_each_in_cell(cell, |j| self.consider(i, pi, vi, j, &mut best, &image));
            }
            return best;
        }
        for block in blocks {
            let (row, p, v) = self.row_frame(i, pi, vi, block.step);
            self.for_each_in_block(row, block, |j| {
                self.consider(i, &p, &v, j, &mut best, &image)
            });
        }
        best
    }

    /// Calls f for every sphere in the cells of `block` in row `row`.
    #[inline(always)]
    fn for_each_in_block(&self, row: u32, block: &Block, mut f: impl FnMut(usize)) {
        self.for_each_cell_of_block(row, block, |cell| self.for_each_in_cell(cell, &mut f));
    }

    /// Calls f with the linear index of every cell of `block` in row `row` (columns
    /// counted from 0 in that row's frame; the cells along z modulo their number).
    #[inline(always)]
    fn for_each_cell_of_block(&self, row: u32, block: &Block, mut f: impl FnMut(usize)) {
        let per_side = self.grid.per_side;
        // Linear indices x + n_x (y + n_y z), counted up with wraps (no divisions: the
        // first column is below 3 n_x, the first cell along z below 2 n_z).
        let (columns, plane) = (per_side[0], per_side[0] * per_side[1]);
        let row = row as usize * columns;
        let mut first = block.columns.first;
        while first >= columns {
            first -= columns;
        }
        let (depth_cells, mut z) = if D == 3 {
            let n = per_side[D - 1];
            let z = block.depths.0;
            (n, if z >= n { z - n } else { z })
        } else {
            (1, 0)
        };
        for _ in 0..block.depths.1 {
            let base = z * plane + row;
            let mut x = first;
            for _ in 0..block.columns.count {
                f(base + x);
                x += 1;
                if x == columns {
                    x = 0;
                }
            }
            z += 1;
            if z == depth_cells {
                z = 0;
            }
        }
    }

    /// The windows of columns of the rows above and below i's (each from 0, modulo the
    /// columns) and its own row's three.
    #[inline]
    pub(super) fn windows(&self, i: usize) -> [Columns; 3] {
        let le = self.shear.expect("sheared");
        let columns = self.grid.per_side[0];
        let m = le.columns_offset(columns);
        let c = self.particles[i].cell[0] as usize;
        [
            Columns {
                first: c + 2 * columns - m - 2,
                count: 4,
            },
            Columns {
                first: c + columns - 1,
                count: 3,
            },
            Columns {
                first: c + columns + m - 1,
                count: 4,
            },
        ]
    }

    /// All of i's neighbour cells: its row's and the adjacent rows' windows.
    #[inline]
    fn neighbor_blocks(&self, i: usize) -> [Block; 3] {
        let [above, own, below] = self.windows(i);
        let all = self.all_depths(i);
        [
            Block::new(0, own, all),
            Block::new(1, above, all),
            Block::new(-1, below, all),
        ]
    }

    /// The collisions of i (now at `pi` with velocity `vi`) with the spheres of its
    /// row's and the adjacent rows' neighbour cells, into `best`.
    #[inline(never)]
    pub(in crate::emd) fn scan_sheared(
        &self,
        i: usize,
        pi: &Vector<D>,
        vi: &Vector<D>,
        best: &mut Best,
    ) {
        let found = self.scan_blocks(i, pi, vi, &self.neighbor_blocks(i));
        if found.time < best.time {
            *best = found;
        }
    }

    /// After i entered the next cell along x or z (`dim`, `up`): the collisions with the
    /// spheres of the cells new to it (one column of each row, or one layer along z),
    /// into `best`.
    #[inline(never)]
    pub(in crate::emd) fn scan_sheared_layer(
        &self,
        i: usize,
        pi: &Vector<D>,
        vi: &Vector<D>,
        dim: usize,
        up: bool,
        best: &mut Best,
    ) {
        let [above, own, below] = self.windows(i);
        let all = self.all_depths(i);
        let blocks = if dim == 0 {
            let edge = |w: Columns| Columns {
                first: if up { w.first + w.count - 1 } else { w.first },
                count: 1,
            };
            [
                Block::new(0, edge(own), all),
                Block::new(1, edge(above), all),
                Block::new(-1, edge(below), all),
            ]
        } else {
            let n = self.grid.per_side[D - 1];
            let z = self.particles[i].cell[D - 1] as usize;
            let layer = (if up { z + 1 } else { z + n - 1 }, 1);
            [
                Block::new(0, own, layer),
                Block::new(1, above, layer),
                Block::new(-1, below, layer),
            ]
        };
        let found = self.scan_blocks(i, pi, vi, &blocks);
        if found.time < best.time {
            *best = found;
        }
    }

    /// Calls f(p, v, j) for every sphere j that i (at `pi` with `vi`) can meet before the
    /// next shift: those of its row's neighbour cells and of the adjacent rows' windows,
    /// with i as its image across a sheared face.
    pub(in crate::emd) fn for_each_sheared_neighbor(
        &self,
        i: usize,
        pi: &Vector<D>,
        vi: &Vector<D>,
        mut f: impl FnMut(&Vector<D>, &Vector<D>, usize),
    ) {
        for block in &self.neighbor_blocks(i) {
            let (row, p, v) = self.row_frame(i, pi, vi, block.step);
            self.for_each_in_block(row, block, |j| f(&p, &v, j));
        }
    }
}
