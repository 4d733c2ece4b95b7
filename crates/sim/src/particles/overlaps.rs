//! The first overlapping pair of a configuration, by the cell lists of `gas::cells` (cells
//! at least as wide as the largest diameter, so that overlapping spheres lie in the same
//! or neighbouring cells, periodically; O(N) for any density a run accepts).

use super::Configuration;
use gas::cells::CellGrid;

/// The first pair (lowest i, then lowest j > i) of spheres that overlap in the periodic
/// box, with the overlap (sum of radii minus distance), or None.
pub fn first_overlap(c: &Configuration) -> Option<(usize, usize, f64)> {
    match c.dimension {
        1 => scan::<1>(c),
        2 => scan::<2>(c),
        _ => scan::<3>(c),
    }
}

fn scan<const D: usize>(c: &Configuration) -> Option<(usize, usize, f64)> {
    let sides: [f64; D] = std::array::from_fn(|k| c.sides[k]);
    let widest = (0..c.len()).map(|i| c.diameter(i)).fold(0.0, f64::max);
    let mut cells = CellGrid::<D>::new(&sides, widest, c.len());
    for (i, p) in c.positions.iter().enumerate() {
        let coords = cells.coords_of(&std::array::from_fn(|k| p[k]));
        cells.insert(i, coords);
    }
    for i in 0..c.len() {
        let (neighbours, count) = cells.grid.neighbor_cells(&cells.coords[i]);
        let mut first: Option<(usize, f64)> = None;
        for &cell in &neighbours[..count] {
            cells.for_each_in_cell(cell, |j| {
                if j > i && first.is_none_or(|(f, _)| j < f) {
                    if let Some(o) = overlap(c, i, j) {
                        first = Some((j, o));
                    }
                }
            });
        }
        if let Some((j, o)) = first {
            return Some((i, j, o));
        }
    }
    None
}

/// The relative shortfall of the squared distance below contact that is round-off, not an
/// overlap: spheres that have just collided touch to a few ulp of their positions (the
/// event-driven engine's own check, `gas::emd`, allows the same 1e-12).
const CONTACT_ROUNDING: f64 = 1e-12;

/// The overlap of spheres i and j (minimum image), if they overlap beyond round-off.
fn overlap(c: &Configuration, i: usize, j: usize) -> Option<f64> {
    let mut r2 = 0.0;
    for k in 0..c.dimension {
        let x = gas::system::minimum_image(c.positions[j][k] - c.positions[i][k], c.sides[k]);
        r2 += x * x;
    }
    let contact = 0.5 * (c.diameter(i) + c.diameter(j));
    (r2 < contact * contact * (1.0 - CONTACT_ROUNDING)).then(|| contact - r2.sqrt())
}
