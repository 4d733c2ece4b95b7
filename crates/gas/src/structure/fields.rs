//! Coarse-grained fields on a grid of G^D cells: number density n, flow velocity u (mass
//! weighted), granular temperature T = Σ m |v − u|² / (D N_cell), and vorticity ∇ × u
//! (central differences across the periodic grid; the z component in 2D, the vector in 3D,
//! none in 1D). Particles are assigned to the cell that holds their centre. A cell without
//! particles has n = 0 and u = T = 0; the vorticity uses its u = 0 (so choose cells that
//! hold several particles: G = (N / 10)^(1/D) or fewer).

use crate::system::{wrap, System};

/// The fields, flattened with x fastest (VTK ImageData order).
#[derive(Debug, Clone, PartialEq)]
pub struct Fields<const D: usize> {
    pub grid: usize,
    /// Sides of one cell, per axis (L_a / G).
    pub spacing: [f64; D],
    pub density: Vec<f64>,
    pub velocity: Vec<[f64; D]>,
    pub temperature: Vec<f64>,
    /// (ω_x, ω_y, ω_z); in 2D only ω_z is non-zero, in 1D all are zero.
    pub vorticity: Vec<[f64; 3]>,
}

/// The fields of `system` on a `grid`^D grid (grid ≥ 3 for the differences).
pub fn coarse_grained_fields<const D: usize>(system: &System<D>, grid: usize) -> Fields<D> {
    let g = grid;
    let l = system.sides;
    let h: [f64; D] = std::array::from_fn(|a| l[a] / g as f64);
    let cells = g.pow(D as u32);
    let (mut count, mut mass) = (vec![0.0; cells], vec![0.0; cells]);
    let mut momentum = vec![[0.0; D]; cells];
    let mut energy = vec![0.0; cells];
    let cell_of = |r: &[f64; D]| {
        let mut index = 0;
        for a in (0..D).rev() {
            index = index * g + ((wrap(r[a], l[a]) / h[a]) as usize).min(g - 1);
        }
        index
    };
    for ((r, v), &m) in system
        .positions
        .iter()
        .zip(&system.velocities)
        .zip(&system.masses)
    {
        let c = cell_of(r);
        count[c] += 1.0;
        mass[c] += m;
        for a in 0..D {
            momentum[c][a] += m * v[a];
        }
        energy[c] += m * v.iter().map(|x| x * x).sum::<f64>();
    }
    let volume = if system.is_cubic() {
        h[0].powi(D as i32)
    } else {
        h.iter().product()
    };
    let velocity: Vec<[f64; D]> = (0..cells)
        .map(|c| {
            if mass[c] > 0.0 {
                std::array::from_fn(|a| momentum[c][a] / mass[c])
            } else {
                [0.0; D]
            }
        })
        .collect();
    let temperature: Vec<f64> = (0..cells)
        .map(|c| {
            if count[c] > 0.0 {
                let u2: f64 = velocity[c].iter().map(|x| x * x).sum();
                ((energy[c] - mass[c] * u2) / (D as f64 * count[c])).max(0.0)
            } else {
                0.0
            }
        })
        .collect();
    // ∂_b u_a by central differences; a cell's grid indices are taken apart once, its
    // neighbours found by adding strides (a division per neighbour made the vorticity the
    // dearest part on large grids)
    let strides: [usize; D] = std::array::from_fn(|a| g.pow(a as u32));
    let vorticity: Vec<[f64; 3]> = (0..cells)
        .map(|c| {
            let index: [usize; D] = std::array::from_fn(|a| (c / strides[a]) % g);
            let neighbour = |axis: usize, up: bool| {
                let (i, stride) = (index[axis], strides[axis]);
                match (up, i) {
                    (true, i) if i + 1 == g => c - i * stride,
                    (true, _) => c + stride,
                    (false, 0) => c + (g - 1) * stride,
                    (false, _) => c - stride,
                }
            };
            let derivative = |a: usize, b: usize| {
                (velocity[neighbour(b, true)][a] - velocity[neighbour(b, false)][a]) / (2.0 * h[b])
            };
            match D {
                2 => [0.0, 0.0, derivative(1, 0) - derivative(0, 1)],
                3 => [
                    derivative(2, 1) - derivative(1, 2),
                    derivative(0, 2) - derivative(2, 0),
                    derivative(1, 0) - derivative(0, 1),
                ],
                _ => [0.0; 3],
            }
        })
        .collect();
    Fields {
        grid,
        spacing: h,
        density: count.iter().map(|c| c / volume).collect(),
        velocity,
        temperature,
        vorticity,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A shear flow u_x = sin(2π y / L) on a fine lattice (4 rows per cell): ω_z = −∂_y u_x
    /// is the central difference of the cell means of u_x, computed here from the rows; it
    /// is 0.968 of −(2π/L) cos(2π y / L) (the difference quotient's sin(2πh/L)/(2πh/L) =
    /// 0.975 times the cell average's 0.994).
    #[test]
    fn shear_flow_vorticity() {
        let (side, g, l) = (64, 16, 64.0);
        let mut positions = vec![];
        let mut velocities = vec![];
        for i in 0..side * side {
            let r = [(i % side) as f64 + 0.5, (i / side) as f64 + 0.5];
            positions.push(r);
            velocities.push([(2.0 * PI * r[1] / l).sin(), 0.0]);
        }
        let n = positions.len();
        let s = System::<2> {
            sides: [l; 2],
            positions,
            velocities,
            radii: vec![0.0; n],
            masses: vec![1.0; n],
        };
        let f = coarse_grained_fields(&s, g);
        assert!(f.density.iter().all(|&d| (d - 1.0).abs() < 1e-12));
        let h = l / g as f64;
        let cell_mean = |j: isize| {
            let j = j.rem_euclid(g as isize) as f64;
            (0..4)
                .map(|r| (2.0 * PI * (j * h + r as f64 + 0.5) / l).sin())
                .sum::<f64>()
                / 4.0
        };
        for (c, w) in f.vorticity.iter().enumerate() {
            let j = (c / g) as isize;
            let expected = -(cell_mean(j + 1) - cell_mean(j - 1)) / (2.0 * h);
            assert!(
                (w[2] - expected).abs() < 1e-12,
                "{c}: {} vs {expected}",
                w[2]
            );
            let smooth = -(2.0 * PI / l) * (2.0 * PI * (j as f64 + 0.5) * h / l).cos();
            assert!((w[2] - 0.968 * smooth).abs() < 1e-3 * 2.0 * PI / l);
        }
        // within a cell the velocity varies: T is the spread of u_x over its rows
        assert!(f.temperature.iter().all(|&t| t < 0.01));
    }
}
