//! The pair correlation g(r): pairs counted in bins of distance (minimum image), normalized
//! by the ideal-gas count N n V_D (r₂^D − r₁^D).
//!
//! Each pair is looked at once, and few pairs out of range are (issue 16 asks g(r) at every
//! sample for at most 10 % of a collision per particle; `haff bench observers`):
//!
//! - the particles are sorted (counting sort) into rows along x, cells on the axes 1.. at
//!   least r_max wide, and within a row into columns [`COLUMNS_PER_RANGE`] times narrower;
//!   coordinates are stored axis by axis;
//! - the particles of a column meet the rows next to theirs of a half stencil (offsets
//!   lexicographically positive) and, in each, only the columns within r_max in x, one
//!   contiguous run (two across the periodic boundary): a slab of about
//!   (2 + 1/c) × 3^(D−1) r_max^D searched instead of the 3^D r_max^D of cubic cells, one
//!   run for all the column's particles;
//! - in their own row they meet each other once and the columns ahead within r_max (across
//!   x = L too), so each pair once, counted twice;
//! - the squared distances of a run are computed four at a time with AVX2
//!   (`pair_avx2`; else axis by axis in loops that vectorize), and only those that
//!   may be in range (a margin of 1e-12 over r_max²) are kept, without branches, for the
//!   square root and the bin.
//!
//! The separation is the minimum image bit for bit (the periodic shift of a row or of a
//! run of columns is subtracted from the difference of the coordinates, as `minimum_image`
//! does), so the counts are those of the plain sum over ordered pairs; they are integers,
//! summed in any order, so the result does not depend on the threads.

use crate::system::{ball_volume, minimum_image, wrap, System};
use rayon::prelude::*;
use std::ops::Range;

/// One point of S(k) or g(r): the argument, the value and the number of wave vectors (pairs
/// of the ideal gas for g) behind it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StructurePoint {
    pub x: f64,
    pub value: f64,
    pub count: f64,
}

/// Columns per r_max along x, c: the run of a column covers its own width and r_max on
/// either side rounded out to whole columns, about (2 + 1/c) r_max; finer columns give
/// shorter runs but more of them (4 and 8 were no faster).
pub const COLUMNS_PER_RANGE: usize = 2;

/// g(r) of `system` in `bins` bins on [0, r_max) (r_max ≤ L/2).
pub fn pair_correlation<const D: usize>(
    system: &System<D>,
    r_max: f64,
    bins: usize,
) -> Vec<StructurePoint> {
    let r_max = r_max.min(0.5 * super::cube_side(system, "g(r)"));
    let dr = r_max / bins as f64;
    let counts = PairCounter::new(system, r_max, bins).ordered_pair_counts();
    let n = system.len() as f64;
    let density = n / system.volume();
    counts
        .iter()
        .enumerate()
        .map(|(b, &c)| {
            let (r1, r2) = (b as f64 * dr, (b + 1) as f64 * dr);
            let ideal = n * density * (ball_volume::<D>(r2) - ball_volume::<D>(r1));
            StructurePoint {
                x: 0.5 * (r1 + r2),
                value: c as f64 / ideal,
                count: ideal,
            }
        })
        .collect()
}

/// The particles sorted into rows and columns, and what binning a pair needs.
struct PairCounter<const D: usize> {
    length: f64,
    r_max: f64,
    dr: f64,
    bins: usize,
    /// r_max with a relative margin of 1e-9, far above the round-off of the coordinates:
    /// how far in x a run of columns reaches, and the least width of the rows.
    reach: f64,
    /// Rows per side on the axes 1..; None when fewer than 3 (all pairs are compared).
    rows: Option<usize>,
    /// Columns per row, and their width.
    columns: usize,
    column_width: f64,
    /// Coordinates per axis, wrapped into [0, L), sorted by row and column.
    coordinates: [Vec<f64>; D],
    /// Start of each column's particles, row by row (rows^(D−1) columns + 1 entries).
    starts: Vec<usize>,
    /// Whether the processor has AVX2 ([`super::pair_avx2`]).
    avx2: bool,
}

impl<const D: usize> PairCounter<D> {
    fn new(system: &System<D>, r_max: f64, bins: usize) -> Self {
        let l = super::cube_side(system, "g(r)");
        let reach = r_max * (1.0 + 1e-9);
        let side = (l / reach).floor() as usize;
        let rows = (D == 1 || side >= 3).then_some(if D == 1 { 1 } else { side });
        let columns = match rows {
            Some(_) => ((COLUMNS_PER_RANGE as f64 * l / reach).floor() as usize).max(1),
            None => 1,
        };
        let column_width = l / columns as f64;
        let wrapped: Vec<[f64; D]> = system
            .positions
            .iter()
            .map(|r| std::array::from_fn(|a| wrap(r[a], l)))
            .collect();
        let index = |x: f64, width: f64, count: usize| ((x / width) as usize).min(count - 1);
        let cell_of = |r: &[f64; D]| match rows {
            Some(c) => {
                let width = l / c as f64;
                let row = (1..D)
                    .rev()
                    .fold(0, |flat, a| flat * c + index(r[a], width, c));
                row * columns + index(r[0], column_width, columns)
            }
            None => 0,
        };
        let cell: Vec<usize> = wrapped.iter().map(cell_of).collect();
        let count = rows.map_or(1, |c| c.pow(D as u32 - 1)) * columns;
        // counting sort by row and column
        let mut starts = vec![0usize; count + 1];
        for &c in &cell {
            starts[c + 1] += 1;
        }
        for c in 1..starts.len() {
            starts[c] += starts[c - 1];
        }
        let mut next = starts.clone();
        let mut coordinates: [Vec<f64>; D] = std::array::from_fn(|_| vec![0.0; cell.len()]);
        for (r, &c) in wrapped.iter().zip(&cell) {
            for (x, &ra) in coordinates.iter_mut().zip(r) {
                x[next[c]] = ra;
            }
            next[c] += 1;
        }
        PairCounter {
            length: l,
            r_max,
            dr: r_max / bins as f64,
            bins,
            reach,
            rows,
            columns,
            column_width,
            coordinates,
            starts,
            avx2: has_avx2(),
        }
    }

    /// Ordered pairs (i, j ≠ i) per bin: each unordered pair found once, counted twice.
    fn ordered_pair_counts(&self) -> Vec<u64> {
        let work = || PairWork {
            counts: vec![0; self.bins + 1],
            candidates: Candidates::default(),
            squares: Vec::new(),
        };
        let counts = match self.rows {
            None => {
                let mut work = work();
                let n = self.coordinates[0].len();
                for i in 0..n {
                    self.collect_minimum_image(i, i + 1..n, &mut work.candidates);
                    self.bin(&mut work);
                }
                work.counts
            }
            Some(c) => (0..c.pow(D as u32 - 1))
                .into_par_iter()
                .fold(work, |mut work, row| {
                    self.count_row(row, &mut work);
                    work
                })
                .map(|work| work.counts)
                .reduce(
                    || vec![0; self.bins + 1],
                    |mut a, b| {
                        a.iter_mut().zip(&b).for_each(|(x, y)| *x += y);
                        a
                    },
                ),
        };
        // the last entry holds the pairs just beyond r_max
        counts[..self.bins].iter().map(|c| 2 * c).collect()
    }

    /// The pairs of the particles of row `row` with those after them in their row and with
    /// the rows of the half stencil.
    fn count_row(&self, row: usize, work: &mut PairWork) {
        let (c, columns) = (self.rows.unwrap_or(1), self.columns);
        // the rows of the half stencil: offsets −1..=1 on the axes 1.., the last non-zero
        // one +1; with the shift of their periodic images on those axes
        let here: [usize; D] = std::array::from_fn(|a| match a {
            0 => 0,
            _ => (row / c.pow(a as u32 - 1)) % c,
        });
        let mut stencil: Vec<(usize, [f64; D])> = Vec::new();
        for code in 0..3usize.pow(D as u32 - 1) {
            let mut offset = [0isize; D];
            let mut s = code;
            for o in offset.iter_mut().skip(1) {
                *o = (s % 3) as isize - 1;
                s /= 3;
            }
            if offset[1..].iter().rev().find(|&&o| o != 0) != Some(&1) {
                continue;
            }
            let mut shift = [0.0; D];
            let mut other = 0;
            for a in (1..D).rev() {
                let (index, s) = self.neighbour(here[a], offset[a], c);
                shift[a] = s;
                other = other * c + index;
            }
            stencil.push((other, shift));
        }
        // the columns within reach of any point of a column: K on either side
        let spread = (self.reach / self.column_width) as isize + 1;
        for column in 0..columns {
            let cell = row * columns + column;
            let mine = self.starts[cell]..self.starts[cell + 1];
            if mine.is_empty() {
                continue;
            }
            let column = column as isize;
            // own row: the pairs within the column once, then the columns ahead
            for i in mine.clone() {
                self.collect(i..i + 1, i + 1..mine.end, [0.0; D], work);
            }
            let (first, last) = (column - spread, column + spread);
            self.collect_columns(mine.clone(), row, column + 1, last, [0.0; D], work);
            for &(other, shift) in &stencil {
                self.collect_columns(mine.clone(), other, first, last, shift, work);
            }
        }
        self.bin(work);
    }

    /// The pairs of the particles `mine` with the columns first..=last (indices beyond the
    /// box meaning the periodic images: shift −L past its end, +L before its start) of row
    /// `row`, whose images are shifted by `shift` on the axes 1...
    fn collect_columns(
        &self,
        mine: Range<usize>,
        row: usize,
        first: isize,
        last: isize,
        mut shift: [f64; D],
        work: &mut PairWork,
    ) {
        let columns = self.columns as isize;
        let base = row * self.columns;
        let run = |from: isize, to: isize| {
            self.starts[base + from as usize]..self.starts[base + to as usize + 1]
        };
        // the pieces do not overlap while 2 K + 1 ≤ columns (K columns on either side);
        // where they would (r_max close to L/2), a particle met twice is met as two
        // different images, of which at most one is within r_max ≤ L/2
        let (below, above) = (first.max(-columns), last.min(2 * columns - 1));
        if below < 0 {
            shift[0] = self.length;
            self.collect(mine.clone(), run(below + columns, columns - 1), shift, work);
        }
        let (from, to) = (below.max(0), above.min(columns - 1));
        if from <= to {
            shift[0] = 0.0;
            self.collect(mine.clone(), run(from, to), shift, work);
        }
        if above >= columns {
            shift[0] = -self.length;
            self.collect(mine, run(0, above - columns), shift, work);
        }
    }

    /// The row `home + offset` on one axis of `c` rows (periodic) and the shift that brings
    /// its particles next to `home`: −L past the box's end (images x + L), +L before its
    /// start (images x − L).
    fn neighbour(&self, home: usize, offset: isize, c: usize) -> (usize, f64) {
        let index = home as isize + offset;
        if index >= c as isize {
            (index as usize - c, -self.length)
        } else if index < 0 {
            ((index + c as isize) as usize, self.length)
        } else {
            (index as usize, 0.0)
        }
    }

    /// Appends to `work.candidates` the squared distances of the particles `mine` to the
    /// particles `others`, whose images next to them are shifted by `shift`, that may be
    /// below r_max: four at a time with AVX2 ([`super::pair_avx2`]), else axis by axis in
    /// loops that vectorize and a pass that keeps the near ones.
    fn collect(
        &self,
        mine: Range<usize>,
        others: Range<usize>,
        shift: [f64; D],
        work: &mut PairWork,
    ) {
        if others.is_empty() || mine.is_empty() {
            return;
        }
        let near = self.r_max * self.r_max * (1.0 + 1e-12);
        let len = others.len();
        let xs: [&[f64]; D] = std::array::from_fn(|a| &self.coordinates[a][others.clone()]);
        let homes: [&[f64]; D] = std::array::from_fn(|a| &self.coordinates[a][mine.clone()]);
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            let out = work.candidates.reserve(mine.len() * len);
            // SAFETY: the processor supports AVX2 (`avx2` is set only then).
            let kept = unsafe { super::pair_avx2::keep_near(xs, homes, shift, near, out) };
            work.candidates.len += kept;
            return;
        }
        if work.squares.len() < len {
            work.squares.resize(len, 0.0);
        }
        let squares = &mut work.squares[..len];
        for i in 0..mine.len() {
            for (a, (x, home)) in xs.iter().zip(&homes).enumerate() {
                let (xi, shift) = (home[i], shift[a]);
                for (r2, &xj) in squares.iter_mut().zip(x.iter()) {
                    // the minimum image: the shift (the same arithmetic as `minimum_image`
                    // for pairs in range); 0 + d² = d² exactly
                    let d = (xj - xi) - shift;
                    *r2 = if a == 0 { d * d } else { *r2 + d * d };
                }
            }
            work.candidates.keep_below(squares, near);
        }
    }

    /// Appends to `candidates` the squared distances of particle `i` to the particles
    /// `others` (minimum image) that may be below r_max.
    fn collect_minimum_image(&self, i: usize, others: Range<usize>, candidates: &mut Candidates) {
        let near = self.r_max * self.r_max * (1.0 + 1e-12);
        let xi: [f64; D] = std::array::from_fn(|a| self.coordinates[a][i]);
        for j in others {
            let mut r2 = 0.0;
            for (a, &xi) in xi.iter().enumerate() {
                let d = minimum_image(self.coordinates[a][j] - xi, self.length);
                r2 += d * d;
            }
            if r2 < near {
                candidates.push(r2);
            }
        }
    }

    /// Adds the `candidates` (squared distances) to the counts, the pairs at r ≥ r_max to
    /// the extra last bin, and empties them.
    fn bin(&self, work: &mut PairWork) {
        let candidates = work.candidates.as_slice();
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: the processor supports AVX2 (`avx2` is set only then).
            unsafe {
                super::pair_avx2::add_to_bins(
                    candidates,
                    self.r_max,
                    self.dr,
                    self.bins,
                    &mut work.counts,
                )
            };
            work.candidates.clear();
            return;
        }
        for &r2 in candidates {
            let r = r2.sqrt();
            let bin = if r < self.r_max {
                ((r / self.dr) as usize).min(self.bins)
            } else {
                self.bins
            };
            work.counts[bin] += 1;
        }
        work.candidates.clear();
    }
}

/// Whether the processor has AVX2.
fn has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    return std::arch::is_x86_feature_detected!("avx2");
    #[cfg(not(target_arch = "x86_64"))]
    false
}

/// Counts per bin (and one for beyond r_max), squared distances to bin, and the squared
/// distances of one particle to a run, per thread.
struct PairWork {
    counts: Vec<u64>,
    candidates: Candidates,
    squares: Vec<f64>,
}

/// Squared distances that may be in range: a buffer that only grows, and how much of it
/// is used (so that appending needs no bookkeeping per element).
#[derive(Default)]
struct Candidates {
    buffer: Vec<f64>,
    len: usize,
}

impl Candidates {
    fn as_slice(&self) -> &[f64] {
        &self.buffer[..self.len]
    }

    fn clear(&mut self) {
        self.len = 0;
    }

    fn push(&mut self, r2: f64) {
        if self.len == self.buffer.len() {
            self.buffer.resize(2 * self.len + 64, 0.0);
        }
        self.buffer[self.len] = r2;
        self.len += 1;
    }

    /// Room for `more` candidates after the current ones.
    fn reserve(&mut self, more: usize) -> &mut [f64] {
        if self.buffer.len() < self.len + more {
            self.buffer.resize(2 * (self.len + more), 0.0);
        }
        &mut self.buffer[self.len..self.len + more]
    }

    /// Appends the `squares` below `near`, without branches: every square is written, and
    /// the next one overwrites it if it is not near.
    fn keep_below(&mut self, squares: &[f64], near: f64) {
        let out = self.reserve(squares.len());
        let mut kept = 0;
        for &r2 in squares {
            out[kept] = r2;
            kept += usize::from(r2 < near);
        }
        self.len += kept;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    use crate::structure::test_points::random_system;

    /// Uniform random points: g(r) = 1. Each bin is a Poisson count of pairs with s.d.
    /// 1/sqrt(ideal/2) (pairs counted twice). Five standard deviations.
    #[test]
    fn ideal_gas_is_structureless() {
        let s2 = random_system::<2>(20_000, 100.0, 1);
        for p in pair_correlation(&s2, 5.0, 20) {
            assert!(
                (p.value - 1.0).abs() < 5.0 / (0.5 * p.count).sqrt(),
                "g({}) = {}",
                p.x,
                p.value
            );
        }
        let s3 = random_system::<3>(20_000, 30.0, 2);
        for p in pair_correlation(&s3, 3.0, 10) {
            assert!(
                (p.value - 1.0).abs() < 5.0 / (0.5 * p.count).sqrt(),
                "g({}) = {}",
                p.x,
                p.value
            );
        }
    }

    /// A square lattice: g(r) has its first peak at the lattice constant.
    #[test]
    fn lattice_peak() {
        let side = 30;
        let positions: Vec<[f64; 2]> = (0..side * side)
            .map(|i| [(i % side) as f64 + 0.5, (i / side) as f64 + 0.5])
            .collect();
        let n = positions.len();
        let s = System::<2> {
            sides: [side as f64; 2],
            positions,
            velocities: vec![[0.0; 2]; n],
            radii: vec![0.0; n],
            masses: vec![1.0; n],
        };
        let g = pair_correlation(&s, 3.0, 30);
        let peak = g.iter().max_by(|a, b| a.value.total_cmp(&b.value)).unwrap();
        assert!((peak.x - 1.05).abs() < 0.051, "{peak:?}");
        // 4 neighbours at r = 1 in the bin [1.0, 1.1): count 4 per particle
        let expected = 4.0 / ((n as f64 / (side * side) as f64) * PI * (1.1f64.powi(2) - 1.0));
        assert!((peak.value - expected).abs() < 1e-9 * expected);
    }

    /// The ordered pairs per bin by the plain definition: every pair (i, j ≠ i), minimum
    /// image.
    fn all_pairs_counts<const D: usize>(s: &System<D>, r_max: f64, bins: usize) -> Vec<u64> {
        let r_max = r_max.min(0.5 * s.sides[0]);
        let dr = r_max / bins as f64;
        let mut counts = vec![0; bins];
        for (i, a) in s.positions.iter().enumerate() {
            for (j, b) in s.positions.iter().enumerate() {
                let d = s.separation(a, b);
                let r = d.iter().map(|x| x * x).sum::<f64>().sqrt();
                if i != j && r < r_max {
                    counts[(r / dr) as usize] += 1;
                }
            }
        }
        counts
    }

    fn assert_counts_match<const D: usize>(s: &System<D>, r_max: f64, bins: usize) {
        let mut counter = PairCounter::new(s, r_max.min(0.5 * s.sides[0]), bins);
        let expected = all_pairs_counts(s, r_max, bins);
        let what = format!(
            "{D}D, L = {}, r_max = {r_max}, {:?} rows",
            s.sides[0], counter.rows
        );
        assert_eq!(counter.ordered_pair_counts(), expected, "{what}");
        // the loops without AVX2 too
        counter.avx2 = false;
        assert_eq!(counter.ordered_pair_counts(), expected, "{what}, no AVX2");
    }

    /// The rows and runs find every pair in range once, with the distance of the minimum
    /// image to the bit: the counts equal the sum over all ordered pairs, in 1, 2 and 3
    /// dimensions, for boxes with many rows, with just 3 (the least for the stencil), with
    /// fewer (all pairs compared) and with r_max = L/2. Positions include points on the
    /// box's faces and outside it (wrapped).
    #[test]
    fn cell_counts_equal_all_pairs() {
        for (l, r_max) in [
            (40.0, 3.0),
            (10.0, 2.0),
            (10.0, 3.9),
            (10.0, 5.0),
            (7.0, 4.0),
        ] {
            let mut s1 = random_system::<1>(300, l, 11);
            s1.positions[0] = [0.0];
            s1.positions[1] = [l - 1e-14];
            s1.positions[2] = [l + 0.3];
            assert_counts_match(&s1, r_max, 17);
            let mut s2 = random_system::<2>(600, l, 12);
            s2.positions[0] = [0.0, l - 1e-14];
            s2.positions[1] = [-0.2, 0.5 * l];
            assert_counts_match(&s2, r_max, 23);
            let mut s3 = random_system::<3>(800, l, 13);
            s3.positions[0] = [0.0, l - 1e-14, 0.0];
            s3.positions[1] = [l, 0.1, -1e-9];
            assert_counts_match(&s3, r_max, 31);
        }
    }
}
