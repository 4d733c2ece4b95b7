//! Fourier amplitudes of the number and momentum densities at wave vectors k = 2π n / L of
//! the periodic box, summed directly over the particles (exact, no grid): ρ_k = Σ_j e^{−ik·r_j},
//! j_k = Σ_j m_j c_j e^{−ik·r_j} with c_j the peculiar velocity. n and −n carry conjugate
//! amplitudes, so only the half space (first non-zero component of n positive) is kept.

use crate::system::System;
use rayon::prelude::*;
use rustfft::num_complex::Complex64;
use std::f64::consts::PI;

/// The wave vectors of one shell |n|² = `norm2` in the half space.
#[derive(Debug, Clone, PartialEq)]
pub struct Shell<const D: usize> {
    pub norm2: usize,
    pub vectors: Vec<[i32; D]>,
}

/// The non-empty shells 1 ≤ |n|² ≤ `max_norm2`, in increasing |n|² (in 3D |n|² = 7 is empty).
pub fn half_space_shells<const D: usize>(max_norm2: usize) -> Vec<Shell<D>> {
    let m = (max_norm2 as f64).sqrt().floor() as i32;
    let side = (2 * m + 1) as usize;
    let mut shells: Vec<Shell<D>> = Vec::new();
    for flat in 0..side.pow(D as u32) {
        let mut f = flat;
        let n: [i32; D] = std::array::from_fn(|_| {
            let c = (f % side) as i32 - m;
            f /= side;
            c
        });
        let norm2 = n.iter().map(|&c| (c * c) as usize).sum::<usize>();
        let first = n.iter().copied().find(|&c| c != 0);
        if norm2 == 0 || norm2 > max_norm2 || first.is_none_or(|c| c < 0) {
            continue;
        }
        match shells.iter_mut().find(|s| s.norm2 == norm2) {
            Some(s) => s.vectors.push(n),
            None => shells.push(Shell {
                norm2,
                vectors: vec![n],
            }),
        }
    }
    shells.sort_by_key(|s| s.norm2);
    shells
}

/// The amplitudes at each wave vector: ρ_k and the D components of j_k.
#[derive(Debug, Clone, PartialEq)]
pub struct Amplitudes<const D: usize> {
    pub density: Vec<Complex64>,
    pub momentum: Vec<[Complex64; D]>,
}

/// ρ_k and j_k at the wave vectors `vectors` (integer n, k = 2π n / L). The per-axis phases
/// e^{−2πi x/L} are raised to the powers of n by multiplication (one sin_cos per particle
/// and axis), in parallel over fixed chunks of particles summed in order (deterministic).
pub fn fourier_amplitudes<const D: usize>(
    system: &System<D>,
    vectors: &[[i32; D]],
) -> Amplitudes<D> {
    let m_max = vectors
        .iter()
        .flat_map(|n| n.iter().map(|c| c.unsigned_abs() as usize))
        .max()
        .unwrap_or(0);
    let total_mass: f64 = system.masses.iter().sum();
    let mean: [f64; D] = std::array::from_fn(|a| {
        system
            .velocities
            .iter()
            .zip(&system.masses)
            .map(|(v, m)| m * v[a])
            .sum::<f64>()
            / total_mass
    });
    let zero = || Amplitudes::<D> {
        density: vec![Complex64::new(0.0, 0.0); vectors.len()],
        momentum: vec![[Complex64::new(0.0, 0.0); D]; vectors.len()],
    };
    let angle: [f64; D] = std::array::from_fn(|a| -2.0 * PI / system.sides[a]);
    // Fixed chunks summed in order: the result does not depend on the thread count or
    // scheduling (a resumed run writes the same bits).
    const CHUNK: usize = 2048;
    let partial: Vec<Amplitudes<D>> = (0..system.len().div_ceil(CHUNK))
        .into_par_iter()
        .map(|chunk| {
            let mut acc = zero();
            let mut powers = vec![[Complex64::new(1.0, 0.0); D]; m_max + 1];
            for j in chunk * CHUNK..((chunk + 1) * CHUNK).min(system.len()) {
                let r = &system.positions[j];
                for a in 0..D {
                    let (s, c) = (angle[a] * r[a]).sin_cos();
                    let base = Complex64::new(c, s);
                    for p in 1..=m_max {
                        powers[p][a] = powers[p - 1][a] * base;
                    }
                }
                let m = system.masses[j];
                let c: [f64; D] = std::array::from_fn(|a| m * (system.velocities[j][a] - mean[a]));
                for (i, n) in vectors.iter().enumerate() {
                    let mut phase = Complex64::new(1.0, 0.0);
                    for a in 0..D {
                        let p = powers[n[a].unsigned_abs() as usize][a];
                        phase *= if n[a] < 0 { p.conj() } else { p };
                    }
                    acc.density[i] += phase;
                    for (j, ca) in acc.momentum[i].iter_mut().zip(&c) {
                        *j += phase * ca;
                    }
                }
            }
            acc
        })
        .collect();
    partial.into_iter().fold(zero(), |mut x, y| {
        for (a, b) in x.density.iter_mut().zip(&y.density) {
            *a += b;
        }
        for (a, b) in x.momentum.iter_mut().zip(&y.momentum) {
            for (p, q) in a.iter_mut().zip(b) {
                *p += q;
            }
        }
        x
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shells_count_the_lattice_points_of_the_half_space() {
        // |n|² = 1, 2, 3 in 3D: 6, 12, 8 lattice points, half of them kept
        let s = half_space_shells::<3>(3);
        let counts: Vec<usize> = s.iter().map(|s| s.vectors.len()).collect();
        assert_eq!(counts, vec![3, 6, 4]);
        let s = half_space_shells::<2>(5);
        let counts: Vec<(usize, usize)> = s.iter().map(|s| (s.norm2, s.vectors.len())).collect();
        assert_eq!(counts, vec![(1, 2), (2, 2), (4, 2), (5, 4)]);
        assert!(half_space_shells::<3>(8).iter().all(|s| s.norm2 != 7));
    }

    /// Against the direct definition with exp() for a few particles.
    #[test]
    fn amplitudes_match_the_definition() {
        let system = System::<2> {
            sides: [3.0; 2],
            positions: vec![[0.1, 0.2], [1.5, 2.9], [2.2, 0.7]],
            velocities: vec![[1.0, -0.5], [0.3, 0.2], [-0.4, 0.9]],
            radii: vec![0.1; 3],
            masses: vec![1.0, 2.0, 1.5],
        };
        let vectors = [[1, 0], [2, -1], [0, 3]];
        let amp = fourier_amplitudes(&system, &vectors);
        let total: f64 = system.masses.iter().sum();
        let mean: Vec<f64> = (0..2)
            .map(|a| {
                (0..3)
                    .map(|j| system.masses[j] * system.velocities[j][a])
                    .sum::<f64>()
                    / total
            })
            .collect();
        for (i, n) in vectors.iter().enumerate() {
            let mut rho = Complex64::new(0.0, 0.0);
            let mut jx = Complex64::new(0.0, 0.0);
            for j in 0..3 {
                let kr = 2.0 * PI / 3.0
                    * (n[0] as f64 * system.positions[j][0] + n[1] as f64 * system.positions[j][1]);
                let e = Complex64::new(0.0, -kr).exp();
                rho += e;
                jx += e * system.masses[j] * (system.velocities[j][0] - mean[0]);
            }
            assert!((amp.density[i] - rho).norm() < 1e-12);
            assert!((amp.momentum[i][0] - jx).norm() < 1e-12);
        }
    }

    /// Many particles (two parallel chunks of 2048 and part of a third) and wave vectors
    /// with components up to 3 of either sign: the sums built from powers of the per-axis
    /// phases agree with the direct definition to 1e-12 of their scale sqrt(Σ |term|²).
    #[test]
    fn many_particles_match_the_definition() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(21);
        let n = 2 * 2048 + 263;
        let length = 7.0;
        let system = System::<3> {
            sides: [length; 3],
            positions: (0..n)
                .map(|_| std::array::from_fn(|_| rng.random::<f64>() * length))
                .collect(),
            velocities: (0..n)
                .map(|_| std::array::from_fn(|_| rng.random::<f64>() - 0.5))
                .collect(),
            radii: vec![0.1; n],
            masses: (0..n).map(|_| 1.0 + rng.random::<f64>()).collect(),
        };
        let vectors = [[1, 0, 0], [0, -2, 1], [3, 1, -1], [1, -3, 2]];
        let amp = fourier_amplitudes(&system, &vectors);
        let total: f64 = system.masses.iter().sum();
        let mean: [f64; 3] = std::array::from_fn(|a| {
            (0..n)
                .map(|j| system.masses[j] * system.velocities[j][a])
                .sum::<f64>()
                / total
        });
        for (i, v) in vectors.iter().enumerate() {
            let (mut rho, mut jk) = (Complex64::new(0.0, 0.0), [Complex64::new(0.0, 0.0); 3]);
            let (mut scale_rho, mut scale_j) = (0.0, [0.0; 3]);
            for j in 0..n {
                let kr: f64 = (0..3)
                    .map(|a| 2.0 * PI / length * v[a] as f64 * system.positions[j][a])
                    .sum();
                let e = Complex64::new(0.0, -kr).exp();
                rho += e;
                scale_rho += 1.0;
                for a in 0..3 {
                    let c = system.masses[j] * (system.velocities[j][a] - mean[a]);
                    jk[a] += e * c;
                    scale_j[a] += c * c;
                }
            }
            assert!((amp.density[i] - rho).norm() < 1e-12 * f64::sqrt(scale_rho));
            for a in 0..3 {
                assert!((amp.momentum[i][a] - jk[a]).norm() < 1e-12 * f64::sqrt(scale_j[a]));
            }
        }
    }
}
