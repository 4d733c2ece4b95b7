//! Verlet neighbour lists with a skin (Verlet 1967; Allen & Tildesley, Sec. 5.3): the
//! pairs closer than the contact distance plus a skin, found through cell lists
//! ([`crate::cells::Grid`]) and kept until some particle may have moved half a skin, so
//! that no contact can begin between two rebuilds unseen.

use crate::cells::{max_cells, Grid};

/// The cells adjacent to the cell of coordinates `c` (itself included, each once) in a grid
/// of `per_side` cells along each axis, as ranges [first, end) of linear cell indices: the cells
/// along dimension 0 have consecutive indices, so the neighbours form rows of three cells
/// (two ranges where a row wraps around the box, one of all cells with fewer than three
/// per side), whose particles are consecutive in the counting sort: 9 ranges in 3D in
/// place of 27 cells.
fn neighbor_rows<const D: usize>(
    per_side: [usize; D],
    c: &[u32; D],
) -> ([(usize, usize); 18], usize) {
    let near = |x: usize, n: usize| -> ([usize; 3], usize) {
        if n < 3 {
            ([0, 1, 2], n)
        } else {
            ([(x + n - 1) % n, x, (x + 1) % n], 3)
        }
    };
    // Linear index of the start of each row (coordinate 0 along dimension 0).
    let (mut bases, mut count) = ([0usize; 9], 1);
    let mut stride = per_side[0];
    // Three rows along every axis (the usual case): the spawning loop unrolled.
    let three = per_side.iter().all(|&n| n >= 3);
    for (d, &x) in c.iter().enumerate().skip(1) {
        let (values, m) = near(x as usize, per_side[d]);
        // Each row start spawns m (in place, from the last).
        for e in (0..count).rev() {
            let base = bases[e];
            if three {
                for (v, &value) in values.iter().enumerate() {
                    bases[e * 3 + v] = base + value * stride;
                }
            } else {
                for (v, &value) in values[..m].iter().enumerate() {
                    bases[e * m + v] = base + value * stride;
                }
            }
        }
        count *= m;
        stride *= per_side[d];
    }
    let (x, per_side) = (c[0] as usize, per_side[0]);
    let mut rows = [(0, 0); 18];
    let mut n = 0;
    for &base in &bases[..count] {
        let mut push = |first: usize, end: usize| {
            rows[n] = (base + first, base + end);
            n += 1;
        };
        if per_side < 3 {
            push(0, per_side);
        } else if x == 0 {
            push(0, 2);
            push(per_side - 1, per_side);
        } else if x == per_side - 1 {
            push(0, 1);
            push(x - 1, per_side);
        } else {
            push(x - 1, x + 2);
        }
    }
    (rows, n)
}
use super::lees_edwards::Images;
use crate::system::{minimum_image, System, Vector};

/// The pairs (i < j) within contact distance + skin, sorted, and a bound on how far the
/// particles have moved since the build.
#[derive(Debug, Clone, Default)]
pub struct NeighborList {
    pub pairs: Vec<(u32, u32)>,
    /// An upper bound on the distance any particle has moved since the build: the sum over
    /// the steps of the step times `speed_bound` (None: never built). Checking it costs
    /// nothing per particle, where the distance of each particle from its position at the
    /// build would cost a pass over the positions every step; it is that distance as long
    /// as the fastest particle keeps its speed.
    moved: Option<f64>,
    /// The square of an upper bound on the speeds since the build: the largest at the
    /// build, raised by every kick that makes a particle faster ([`NeighborList::kicked`]).
    /// Only the particles in contact are kicked, so that the drift need not look at the
    /// speeds.
    speed_bound2: f64,
    pub skin: f64,
    /// The largest radius at the last build.
    pub largest_radius: f64,
    /// Rebuilds so far.
    pub builds: u64,
    /// Axes closed by walls (bit k): no pair across them.
    pub closed: u8,
    /// Under shear, |a| L_y / 2: the images across the sliding faces move relative to the
    /// box at |a| L_y, which the skin criterion counts as half for each of a pair's two
    /// spheres (0 without shear).
    slide: f64,
}

impl NeighborList {
    pub fn new(skin: f64) -> Self {
        NeighborList {
            skin,
            ..Default::default()
        }
    }

    /// Whether a particle may have moved more than half the skin since the build (or the
    /// list was never built).
    pub fn stale(&self) -> bool {
        self.moved.is_none_or(|moved| moved > 0.5 * self.skin)
    }

    /// Records a kick that gave a particle the velocity `v`.
    #[inline]
    pub fn kicked<const D: usize>(&mut self, v: &Vector<D>) {
        let speed2 = v.iter().map(|c| c * c).sum::<f64>();
        if speed2 > self.speed_bound2 {
            self.speed_bound2 = speed2;
        }
    }

    /// Records a kick that may have raised any particle's speed by up to `dv` (gravity).
    pub fn accelerated(&mut self, dv: f64) {
        let bound = self.speed_bound2.sqrt() + dv;
        self.speed_bound2 = bound * bound;
    }

    /// Marks the list stale (the walls changed).
    pub fn invalidate(&mut self) {
        self.moved = None;
    }

    /// Records a drift of all particles for a time `dt`.
    pub fn drifted(&mut self, dt: f64) {
        if let Some(moved) = &mut self.moved {
            *moved += dt * (self.speed_bound2.sqrt() + self.slide);
        }
    }

    /// Lists pairs across sliding faces whose images move at `jump` = a L_y (None: a
    /// periodic box); marks the list stale.
    pub fn sheared(&mut self, jump: Option<f64>) {
        self.slide = jump.map_or(0.0, |j| 0.5 * j.abs());
        self.invalidate();
    }

    /// Rebuilds the list for `system` (positions in the box; distances are minimum
    /// images). A pair listed once per build even in a box of fewer than three cells.
    // Out of line: a rare call (every few dozen steps), and its own entry in profiles.
    #[inline(never)]
    pub fn build<const D: usize>(&mut self, system: &System<D>) {
        let largest = system.radii.iter().copied().fold(0.0, f64::max);
        self.largest_radius = largest;
        let reach = 2.0 * largest + self.skin;
        let (grid, coords, start, members) = sort_by_cell(system, reach);
        self.pairs.clear();
        for (i, x) in system.positions.iter().enumerate() {
            let (rows, count) = neighbor_rows(grid.per_side, &coords[i]);
            for &(first, end) in &rows[..count] {
                for &j in &members[start[first] as usize..start[end] as usize] {
                    let j = j as usize;
                    if j <= i {
                        continue;
                    }
                    let cutoff = system.radii[i] + system.radii[j] + self.skin;
                    let d2: f64 = (0..D)
                        .map(|k| {
                            minimum_image(system.positions[j][k] - x[k], system.sides[k]).powi(2)
                        })
                        .sum();
                    // Across a closed axis the nearest image lies behind a wall.
                    let across = self.closed != 0
                        && (0..D).any(|k| {
                            self.closed & (1 << k) != 0
                                && (system.positions[j][k] - x[k]).abs() > 0.5 * system.sides[k]
                        });
                    if d2 < cutoff * cutoff && !across {
                        self.pairs.push((i as u32, j as u32));
                    }
                }
            }
        }
        self.finish(system);
    }

    /// The list sorted, the displacements since the build zero, the speeds' bound that of
    /// `system`.
    fn finish<const D: usize>(&mut self, system: &System<D>) {
        self.pairs.sort_unstable();
        self.moved = Some(0.0);
        self.speed_bound2 = 0.0;
        for v in &system.velocities {
            self.kicked(v);
        }
        self.builds += 1;
    }

    /// [`Self::build`] under Lees–Edwards boundaries, the images as `images` at the time of
    /// the positions ([`super::lees_edwards`]): a pair's distance is its nearest image's
    /// ([`Images::separation`], as the forces take it); a sphere in a row of cells at a
    /// face is paired with the spheres of the row across in the columns its image overlaps
    /// (with a column's margin each side against rounding), the others with the 3^D cells
    /// around it. Each cell scanned once per sphere (stamps), so a pair is listed once.
    #[inline(never)]
    pub(crate) fn build_sheared<const D: usize>(&mut self, system: &System<D>, images: &Images) {
        let largest = system.radii.iter().copied().fold(0.0, f64::max);
        self.largest_radius = largest;
        let reach = 2.0 * largest + self.skin;
        let (grid, coords, start, members) = sort_by_cell(system, reach);
        let (per_side, width) = (grid.per_side, grid.width[0]);
        let near = |c: u32, n: usize| -> Vec<u32> {
            let c = c as i64;
            (c - 1..=c + 1)
                .map(|x| x.rem_euclid(n as i64) as u32)
                .collect()
        };
        let mut stamps = vec![usize::MAX; grid.cells()];
        self.pairs.clear();
        for (i, x) in system.positions.iter().enumerate() {
            let c = coords[i];
            let depths = if D == 3 {
                near(c[2], per_side[2])
            } else {
                vec![0]
            };
            for dy in [-1i64, 0, 1] {
                let row = c[1] as i64 + dy;
                let rows = per_side[1] as i64;
                // s of the image of the row's spheres seen from i (Images::separation).
                let s = if row < 0 {
                    -1.0
                } else if row >= rows {
                    1.0
                } else {
                    0.0
                };
                let columns: Vec<u32> = if s == 0.0 {
                    near(c[0], per_side[0])
                } else {
                    // The row's spheres whose image lies within reach of x: x_j near x − s δ.
                    let target = x[0] - s * images.delta;
                    let low = ((target - reach) / width).floor() as i64 - 1;
                    let high = ((target + reach) / width).floor() as i64 + 1;
                    let n = per_side[0] as i64;
                    if high - low + 1 >= n {
                        (0..n as u32).collect()
                    } else {
                        (low..=high).map(|x| x.rem_euclid(n) as u32).collect()
                    }
                };
                let mut cell = c;
                cell[1] = row.rem_euclid(rows) as u32;
                for &z in &depths {
                    if D == 3 {
                        cell[D - 1] = z;
                    }
                    for &column in &columns {
                        cell[0] = column;
                        let index = grid.index(&cell);
                        if stamps[index] == i {
                            continue;
                        }
                        stamps[index] = i;
                        let members = &members[start[index] as usize..start[index + 1] as usize];
                        for &j in members {
                            let j = j as usize;
                            if j <= i {
                                continue;
                            }
                            let cutoff = system.radii[i] + system.radii[j] + self.skin;
                            let (r, _) = images.separation(x, &system.positions[j], &system.sides);
                            if r.iter().map(|d| d * d).sum::<f64>() < cutoff * cutoff {
                                self.pairs.push((i as u32, j as u32));
                            }
                        }
                    }
                }
            }
        }
        self.finish(system);
    }

    pub fn memory_bytes(&self) -> usize {
        self.pairs.capacity() * 8
    }
}

/// The grid of cells at least `reach` wide over the box of `system`, each particle's cell
/// coordinates, and a counting sort of the particles by cell: cell c holds
/// `members[start[c]..start[c + 1]]`.
#[allow(clippy::type_complexity)]
fn sort_by_cell<const D: usize>(
    system: &System<D>,
    reach: f64,
) -> (Grid<D>, Vec<[u32; D]>, Vec<u32>, Vec<u32>) {
    let n = system.len();
    let grid = Grid::<D>::new(&system.sides, reach, max_cells(n));
    let coords: Vec<[u32; D]> = system.positions.iter().map(|x| grid.coords_of(x)).collect();
    let cells: Vec<usize> = coords.iter().map(|c| grid.index(c)).collect();
    let mut start = vec![0u32; grid.cells() + 1];
    for &c in &cells {
        start[c + 1] += 1;
    }
    for c in 0..grid.cells() {
        start[c + 1] += start[c];
    }
    let mut fill = start.clone();
    let mut members = vec![0u32; n];
    for (i, &c) in cells.iter().enumerate() {
        members[fill[c] as usize] = i as u32;
        fill[c] += 1;
    }
    (grid, coords, start, members)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Positions in the box and radii from 0.5 to 1 from a linear congruential generator.
    fn gas<const D: usize>(n: usize, length: f64, seed: u64) -> System<D> {
        let mut state = seed;
        let mut uniform = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        System {
            sides: [length; D],
            positions: (0..n)
                .map(|_| std::array::from_fn(|_| uniform() * length))
                .collect(),
            velocities: vec![[0.0; D]; n],
            radii: (0..n).map(|_| 0.5 + 0.5 * uniform()).collect(),
            masses: vec![1.0; n],
        }
    }

    /// The list is every pair within reach, each once, sorted: from boxes of fewer than
    /// three cells per side (where a row of cells wraps onto itself) to many cells.
    fn matches_all_pairs<const D: usize>() {
        for (n, length) in [(5, 4.5), (20, 6.5), (40, 9.0), (300, 30.0)] {
            let system = gas::<D>(n, length, 7 + n as u64);
            let skin = 0.3;
            let mut list = NeighborList::new(skin);
            list.build(&system);
            let mut expected = Vec::new();
            for i in 0..n {
                for j in i + 1..n {
                    let cutoff = system.radii[i] + system.radii[j] + skin;
                    let d2: f64 = (0..D)
                        .map(|k| {
                            let d = system.positions[j][k] - system.positions[i][k];
                            minimum_image(d, length).powi(2)
                        })
                        .sum();
                    if d2 < cutoff * cutoff {
                        expected.push((i as u32, j as u32));
                    }
                }
            }
            assert_eq!(list.pairs, expected, "D = {D}, n = {n}, L = {length}");
        }
    }

    #[test]
    fn lists_every_pair_within_reach_once() {
        matches_all_pairs::<1>();
        matches_all_pairs::<2>();
        matches_all_pairs::<3>();
    }
}
