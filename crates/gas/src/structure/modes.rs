//! The hydrodynamic modes at the smallest wave vectors: the momentum density split into its
//! transverse and longitudinal parts, and the number density, each averaged over a shell of
//! wave vectors and normalized by its value in a homogeneous gas at the current temperature.
//!
//! In a homogeneous gas the velocities are independent of the positions, so
//! <|j_k|²> = Σ_j m_j² <c_a²> per component = T Σ_j m_j (T_j = T for every species), of which
//! (D − 1) components are transverse to k and one longitudinal; and <|ρ_k|²> = N S(k), with
//! S(k → 0) the compressibility of the hard-sphere fluid
//! ([`crate::theory::long_wavelength_structure_factor`]). So a homogeneous gas gives 1 for every
//! mode up to noise (each normalized power is an average of |·|² over 2 × vectors real
//! Gaussian components: relative noise sqrt(1 / (vectors × (D − 1))) for the transverse part).
//! Shear modes growing in the HCS show up as transverse energies ≫ 1 (Goldhirsch & Zanetti
//! 1993), clusters as density powers ≫ 1.

use super::fourier::{fourier_amplitudes, half_space_shells};
use crate::observe::temperature;
use crate::system::System;
use std::f64::consts::PI;

/// The normalized powers of one shell |n|² of wave vectors k = 2π |n| / L.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModeShell {
    /// |n|².
    pub norm2: usize,
    pub k: f64,
    /// <|j_⊥|²> / ((D − 1) T Σ m); 0 in 1D (no transverse direction).
    pub transverse_energy: f64,
    /// <|k̂·j|²> / (T Σ m).
    pub longitudinal_energy: f64,
    /// <|ρ_k|²> / (N S0).
    pub density_power: f64,
    /// Wave vectors averaged over (half space).
    pub vectors: usize,
}

/// The modes of the shells 1 ≤ |n|² ≤ `max_norm2` of `system`, the density normalized by
/// `structure_factor0` = S(k → 0) of the homogeneous fluid at its packing fraction.
pub fn hydrodynamic_modes<const D: usize>(
    system: &System<D>,
    max_norm2: usize,
    structure_factor0: f64,
) -> Vec<ModeShell> {
    let shells = half_space_shells::<D>(max_norm2);
    let vectors: Vec<[i32; D]> = shells.iter().flat_map(|s| s.vectors.clone()).collect();
    let amplitudes = fourier_amplitudes(system, &vectors);
    let t = temperature(system);
    let total_mass: f64 = system.masses.iter().sum();
    let n = system.len() as f64;
    let mut out = Vec::with_capacity(shells.len());
    let mut i = 0;
    for shell in &shells {
        let (mut transverse, mut longitudinal, mut density) = (0.0, 0.0, 0.0);
        for nvec in &shell.vectors {
            let norm = (shell.norm2 as f64).sqrt();
            let unit: [f64; D] = std::array::from_fn(|a| nvec[a] as f64 / norm);
            let j = &amplitudes.momentum[i];
            let total: f64 = j.iter().map(|c| c.norm_sqr()).sum();
            let along = j
                .iter()
                .zip(&unit)
                .fold(
                    rustfft::num_complex::Complex64::new(0.0, 0.0),
                    |s, (c, u)| s + c * u,
                )
                .norm_sqr();
            longitudinal += along;
            transverse += total - along;
            density += amplitudes.density[i].norm_sqr();
            i += 1;
        }
        let count = shell.vectors.len() as f64;
        let scale = t * total_mass * count;
        out.push(ModeShell {
            norm2: shell.norm2,
            k: 2.0 * PI * (shell.norm2 as f64).sqrt() / super::cube_side(system, "the modes"),
            transverse_energy: if D > 1 {
                transverse / ((D - 1) as f64 * scale)
            } else {
                0.0
            },
            longitudinal_energy: longitudinal / scale,
            density_power: density / (count * n * structure_factor0),
            vectors: shell.vectors.len(),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_distr::StandardNormal;

    /// An ideal gas (uniform positions, Maxwellian velocities) gives 1 for every mode: the mean
    /// over 200 configurations of each normalized power is 1 within 5 standard errors (each
    /// configuration's power is a mean of exponential variables: relative s.d. 1/sqrt(2 ×
    /// components), so over 200 the error is below 0.071 / sqrt(vectors)).
    #[test]
    fn ideal_gas_gives_one() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(5);
        let (n, configs) = (2000, 200);
        let mut sums = [[0.0; 3]; 3];
        let mut counts = [0; 3];
        for _ in 0..configs {
            let system = System::<3> {
                sides: [10.0; 3],
                positions: (0..n)
                    .map(|_| std::array::from_fn(|_| rng.random::<f64>() * 10.0))
                    .collect(),
                velocities: (0..n)
                    .map(|_| std::array::from_fn(|_| rng.sample(StandardNormal)))
                    .collect(),
                radii: vec![0.0; n],
                masses: vec![1.0; n],
            };
            for (i, m) in hydrodynamic_modes(&system, 3, 1.0).iter().enumerate() {
                sums[i][0] += m.transverse_energy / configs as f64;
                sums[i][1] += m.longitudinal_energy / configs as f64;
                sums[i][2] += m.density_power / configs as f64;
                counts[i] = m.vectors;
            }
        }
        for (s, &v) in sums.iter().zip(&counts) {
            let error = 1.0 / ((configs * v) as f64).sqrt();
            for x in s {
                assert!((x - 1.0).abs() < 5.0 * error, "{x} (error {error})");
            }
        }
    }

    /// A pure shear flow u_x = U sin(2π y / L) puts the energy of the lowest shell in its
    /// transverse part: |j_k|² = (N m U / 2)² at n = (0, 1, 0), none longitudinal.
    #[test]
    fn shear_flow_is_transverse() {
        let side = 16;
        let l = 16.0;
        let mut positions = vec![];
        let mut velocities = vec![];
        for i in 0..side * side * side {
            let r = [
                (i % side) as f64 + 0.5,
                ((i / side) % side) as f64 + 0.5,
                (i / (side * side)) as f64 + 0.5,
            ];
            velocities.push([(2.0 * PI * r[1] / l).sin(), 0.0, 0.0]);
            positions.push(r);
        }
        let n = positions.len();
        let system = System::<3> {
            sides: [l; 3],
            positions,
            velocities,
            radii: vec![0.0; n],
            masses: vec![1.0; n],
        };
        let modes = hydrodynamic_modes(&system, 1, 1.0);
        let t = temperature(&system);
        let expected = (n as f64 / 2.0).powi(2) / 3.0 / (2.0 * t * n as f64);
        assert!(
            (modes[0].transverse_energy / expected - 1.0).abs() < 1e-9,
            "{modes:?}"
        );
        assert!(modes[0].longitudinal_energy < 1e-20);
    }
}
