//! The first overlapping pair of a configuration, by a cell list: cells at least as wide as
//! the largest diameter, so that overlapping spheres lie in the same or neighbouring cells
//! (periodic); O(N) for any density a run accepts.

use super::Configuration;

/// The first pair (i < j, lowest i, then lowest j among i's neighbours found) of spheres
/// that overlap in the periodic box, with the overlap (sum of radii minus distance), or
/// None.
pub fn first_overlap(c: &Configuration) -> Option<(usize, usize, f64)> {
    let d = c.dimension;
    let widest = (0..c.len()).map(|i| c.diameter(i)).fold(0.0, f64::max);
    // Cells per axis: each at least `widest` wide (at least one), at most 2 N^(1/d), to
    // bound the memory. With fewer than 3 along an axis the neighbours repeat: deduplicated.
    let limit = ((c.len() as f64).powf(1.0 / d as f64) * 2.0).ceil() as usize;
    let counts: Vec<usize> = c.sides[..d]
        .iter()
        .map(|&l| ((l / widest).floor() as usize).clamp(1, limit.max(1)))
        .collect();
    let cell_of = |p: &[f64; 3]| -> usize {
        let mut index = 0;
        for k in (0..d).rev() {
            let x = ((p[k] / c.sides[k]) * counts[k] as f64) as usize;
            index = index * counts[k] + x.min(counts[k] - 1);
        }
        index
    };
    let total: usize = counts.iter().product();
    let mut heads = vec![usize::MAX; total];
    let mut next = vec![usize::MAX; c.len()];
    for i in (0..c.len()).rev() {
        let cell = cell_of(&c.positions[i]);
        next[i] = heads[cell];
        heads[cell] = i;
    }
    let mut best: Option<(usize, usize, f64)> = None;
    let offsets: Vec<[i64; 3]> = (0..3usize.pow(d as u32))
        .map(|m| {
            let mut o = [0i64; 3];
            let mut m = m;
            for slot in o.iter_mut().take(d) {
                *slot = (m % 3) as i64 - 1;
                m /= 3;
            }
            o
        })
        .collect();
    let mut cells: Vec<usize> = Vec::with_capacity(offsets.len());
    for i in 0..c.len() {
        let p = &c.positions[i];
        let home: Vec<i64> = (0..d)
            .map(|k| (((p[k] / c.sides[k]) * counts[k] as f64) as i64).min(counts[k] as i64 - 1))
            .collect();
        cells.clear();
        cells.extend(offsets.iter().map(|o| {
            let mut cell = 0usize;
            for k in (0..d).rev() {
                let x = (home[k] + o[k]).rem_euclid(counts[k] as i64) as usize;
                cell = cell * counts[k] + x;
            }
            cell
        }));
        cells.sort_unstable();
        cells.dedup();
        for &cell in &cells {
            let mut j = heads[cell];
            while j != usize::MAX {
                if j > i {
                    if let Some(overlap) = overlap(c, i, j) {
                        let better = best.is_none_or(|(bi, bj, _)| (i, j) < (bi, bj));
                        if better {
                            best = Some((i, j, overlap));
                        }
                    }
                }
                j = next[j];
            }
        }
        if best.is_some_and(|(bi, _, _)| bi == i) {
            return best;
        }
    }
    best
}

/// The overlap of spheres i and j (minimum image), if they overlap.
fn overlap(c: &Configuration, i: usize, j: usize) -> Option<f64> {
    let mut r2 = 0.0;
    for k in 0..c.dimension {
        let l = c.sides[k];
        let mut x = c.positions[j][k] - c.positions[i][k];
        x -= l * (x / l).round();
        r2 += x * x;
    }
    let contact = 0.5 * (c.diameter(i) + c.diameter(j));
    (r2 < contact * contact).then(|| contact - r2.sqrt())
}
