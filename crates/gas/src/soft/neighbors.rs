//! Verlet neighbour lists with a skin (Verlet 1967; Allen & Tildesley, Sec. 5.3): the
//! pairs closer than the contact distance plus a skin, found through cell lists
//! ([`crate::cells::Grid`]) and kept until some particle has moved half a skin, so that no
//! contact can begin between two rebuilds unseen.

use crate::cells::{max_cells, Grid};
use crate::system::{minimum_image, System, Vector};

/// The pairs (i < j) within contact distance + skin, sorted, and the positions at the
/// build.
#[derive(Debug, Clone, Default)]
pub struct NeighborList<const D: usize> {
    pub pairs: Vec<(u32, u32)>,
    /// Positions when the list was built.
    anchors: Vec<Vector<D>>,
    pub skin: f64,
    /// Rebuilds so far.
    pub builds: u64,
}

impl<const D: usize> NeighborList<D> {
    pub fn new(skin: f64) -> Self {
        NeighborList {
            skin,
            ..Default::default()
        }
    }

    /// Whether a particle has moved more than half the skin since the build (or the list
    /// was never built).
    pub fn stale(&self, system: &System<D>) -> bool {
        if self.anchors.len() != system.len() {
            return true;
        }
        let limit = 0.25 * self.skin * self.skin;
        system.positions.iter().zip(&self.anchors).any(|(x, a)| {
            (0..D)
                .map(|k| minimum_image(x[k] - a[k], system.length).powi(2))
                .sum::<f64>()
                > limit
        })
    }

    /// Rebuilds the list for `system` (positions in the box; distances are minimum
    /// images). A pair listed once per build even in a box of fewer than three cells.
    pub fn build(&mut self, system: &System<D>) {
        let largest = system.radii.iter().copied().fold(0.0, f64::max);
        let reach = 2.0 * largest + self.skin;
        let n = system.len();
        let grid = Grid::<D>::new(system.length, reach, max_cells(n));
        // Counting sort of the particles by cell.
        let cells: Vec<usize> = system
            .positions
            .iter()
            .map(|x| grid.index(&grid.coords_of(x)))
            .collect();
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
        self.pairs.clear();
        for (i, x) in system.positions.iter().enumerate() {
            let (neighbors, count) = grid.neighbor_cells(&grid.coords_of(x));
            for &cell in &neighbors[..count] {
                for &j in &members[start[cell] as usize..start[cell + 1] as usize] {
                    let j = j as usize;
                    if j <= i {
                        continue;
                    }
                    let cutoff = system.radii[i] + system.radii[j] + self.skin;
                    let d2: f64 = (0..D)
                        .map(|k| {
                            minimum_image(system.positions[j][k] - x[k], system.length).powi(2)
                        })
                        .sum();
                    if d2 < cutoff * cutoff {
                        self.pairs.push((i as u32, j as u32));
                    }
                }
            }
        }
        self.pairs.sort_unstable();
        self.anchors.clone_from(&system.positions);
        self.builds += 1;
    }

    pub fn memory_bytes(&self) -> usize {
        self.pairs.capacity() * 8 + self.anchors.capacity() * 8 * D
    }
}
