//! The stochastic collision equation, Eqs. (3)-(7) of Giese: ε for one noise realization
//! ([`eps`]), a parallel, thread-count-independent sampler ([`sample_eps`]), a tabulated
//! distribution of ε² for event-driven MD ([`Table`]) and the Markov chain Eq. (6)
//! ([`markov`]).
//!
//! Parameters: γ = l1/l2 > 0, κ = αlV/c > 0 (scaled impact velocity), and the energy ratio
//! r = E_tr/T_bath > 0 (r = ∞ is the deterministic limit T_bath = 0).
mod histogram;
pub mod markov;
pub mod noise;
pub mod table;

pub use histogram::{eps2_histogram, eps2_quantiles, eps2_summary, Eps2Bin};
pub use noise::{covariance, NoiseProcess};
pub use table::Table;

use crate::deterministic::{integrate, Solution, Z0};
use crate::error::{positive, Error, Result};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rayon::prelude::*;

/// Discretization of Eq. (3) of Giese with noise.
///
/// Step h = `step`/κ_eff with κ_eff = κ·max(1, r^{−1/2}) (the larger of the drift rate κ and
/// the thermal velocity scale κ/√r of the exponent). Each Q_i is sampled on
/// N_i = 2^⌈log2(`oversample`·Γ_i/h)⌉ points per period, i.e. with the Fourier series
/// resolved up to n_max = N_i/2 ≥ `oversample`·Γ_i/(2h) (plus the aliased tail, see
/// [`noise`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Resolution {
    /// h·κ_eff.
    pub step: f64,
    /// Noise grid points per integration step (≥ 1).
    pub oversample: f64,
}

impl Default for Resolution {
    /// `step` = 0.1, `oversample` = 1. Measured with common random numbers (test
    /// `converged_in_step_and_modes`, γ = 0.6173, κ = 100): halving h and doubling the
    /// noise points, or 4× the noise points (n_max) alone, changes the mean of ε² by
    /// −0.0009 ± 0.0015 resp. −0.0001 ± 0.0018 at r = 1 and 0.009 ± 0.009 resp.
    /// −0.0007 ± 0.008 at r = 0.1 (pathwise mean |Δε²| ≈ 0.014 at r = 1, ∝ √h).
    fn default() -> Self {
        Self {
            step: 0.1,
            oversample: 1.0,
        }
    }
}

impl Resolution {
    /// Integration step h for (κ, r).
    pub fn h(&self, kappa: f64, energy_ratio: f64) -> f64 {
        let k_eff = kappa * (1.0f64).max(1.0 / energy_ratio.sqrt());
        self.step / k_eff
    }
    /// Noise grid size for period Γ_i and step h.
    pub fn grid_points(&self, period: f64, h: f64) -> usize {
        ((self.oversample * period / h).ceil() as usize)
            .max(2)
            .next_power_of_two()
    }
}

/// Checks the parameters; errors name the parameter and its range.
pub fn check_params(gamma: f64, kappa: f64, energy_ratio: f64) -> Result<()> {
    positive("gamma", gamma)?;
    positive("kappa", kappa)?;
    if energy_ratio.is_nan() || energy_ratio <= 0.0 {
        return Err(Error::out_of_range(
            "energy_ratio (E_tr/T_bath)",
            energy_ratio,
            "a number > 0 (infinity allowed)",
        ));
    }
    Ok(())
}

/// Full solution of Eq. (3) of Giese for one noise realization drawn from `rng`.
/// z0 = 30 + max Q1 + max Q2: the initial force is ≤ e^{−30}; since the bound is a
/// shift-invariant functional of the stationary noise, the start time is independent of
/// the noise phase and the ε distribution is that of z0 → ∞.
pub fn solve<R: Rng + ?Sized>(
    gamma: f64,
    kappa: f64,
    energy_ratio: f64,
    res: &Resolution,
    rng: &mut R,
) -> Result<Solution> {
    check_params(gamma, kappa, energy_ratio)?;
    positive("resolution.step", res.step)?;
    if !(res.oversample >= 1.0 && res.oversample.is_finite()) {
        return Err(Error::out_of_range(
            "resolution.oversample",
            res.oversample,
            "a finite number >= 1",
        ));
    }
    let h = res.h(kappa, energy_ratio);
    if energy_ratio.is_infinite() {
        return Ok(integrate(gamma, kappa, h, Z0, |_| 0.0));
    }
    let (g1, g2) = (1.0 + gamma, 1.0 + 1.0 / gamma);
    // one stream per process: the low modes do not depend on the resolution
    let (mut r1, mut r2) = (
        Pcg64::seed_from_u64(rng.random()),
        Pcg64::seed_from_u64(rng.random()),
    );
    let q1 = NoiseProcess::sample(g1, kappa, energy_ratio, res.grid_points(g1, h), &mut r1);
    let q2 = NoiseProcess::sample(g2, kappa, energy_ratio, res.grid_points(g2, h), &mut r2);
    let z0 = Z0 + q1.max() + q2.max();
    Ok(integrate(gamma, kappa, h, z0, |j| {
        let t = j as f64 * h;
        q1.at(t) + q2.at(t)
    }))
}

/// ε (Eq. (4) of Giese) of Eq. (3) for one noise realization, default [`Resolution`].
/// r = E_tr/T_bath = ∞ gives exactly
/// `deterministic::eps_numeric(gamma, kappa, Resolution::default().h(kappa, r))`.
pub fn eps<R: Rng + ?Sized>(gamma: f64, kappa: f64, energy_ratio: f64, rng: &mut R) -> Result<f64> {
    Ok(solve(gamma, kappa, energy_ratio, &Resolution::default(), rng)?.eps)
}

/// The generator of realization `index` of a sample with seed `seed` (SplitMix64 mix of
/// both, so samples do not depend on the thread count or scheduling).
pub fn realization_rng(seed: u64, index: u64) -> Pcg64 {
    fn mix(mut z: u64) -> u64 {
        z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    Pcg64::seed_from_u64(mix(seed ^ mix(index)))
}

/// `realizations` values of ε (Eq. (4) of Giese) in parallel (rayon), realization k drawn
/// with [`realization_rng`]`(seed, k)`; default [`Resolution`].
pub fn sample_eps(
    gamma: f64,
    kappa: f64,
    energy_ratio: f64,
    realizations: usize,
    seed: u64,
) -> Result<Vec<f64>> {
    sample_eps_with(
        gamma,
        kappa,
        energy_ratio,
        realizations,
        seed,
        &Resolution::default(),
    )
}

/// [`sample_eps`] with an explicit [`Resolution`].
pub fn sample_eps_with(
    gamma: f64,
    kappa: f64,
    energy_ratio: f64,
    realizations: usize,
    seed: u64,
    res: &Resolution,
) -> Result<Vec<f64>> {
    check_params(gamma, kappa, energy_ratio)?;
    if realizations == 0 {
        return Err(Error::out_of_range("realizations", 0, ">= 1"));
    }
    (0..realizations as u64)
        .into_par_iter()
        .map(|k| {
            let mut rng = realization_rng(seed, k);
            solve(gamma, kappa, energy_ratio, res, &mut rng).map(|s| s.eps)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn guards_name_parameters() {
        let e = sample_eps(0.0, 100.0, 1.0, 1, 0).unwrap_err().to_string();
        assert!(e.contains("gamma"), "{e}");
        let e = sample_eps(0.5, -1.0, 1.0, 1, 0).unwrap_err().to_string();
        assert!(e.contains("kappa"), "{e}");
        let e = sample_eps(0.5, 100.0, f64::NAN, 1, 0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("energy_ratio"), "{e}");
        let e = sample_eps(0.5, 100.0, 1.0, 0, 0).unwrap_err().to_string();
        assert!(e.contains("realizations"), "{e}");
    }
}
