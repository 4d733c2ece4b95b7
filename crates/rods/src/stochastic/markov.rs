//! The Markov chain Eq. (6) of Giese: E_{n+1} = ε² E_n with ε² drawn from p(ε² | E_n/T_bath)
//! at fixed T_bath, and the Glauber form Eq. (7).

use crate::error::{positive, Error, Result};

/// Runs Eq. (6) of Giese for `steps` collisions in units of T_bath (T_bath = 1), starting at
/// E_0/T = `e0`; `eps2(r)` draws ε² for the energy ratio r = E_n/T. Returns E_1..E_steps.
pub fn run_chain(e0: f64, steps: usize, mut eps2: impl FnMut(f64) -> f64) -> Vec<f64> {
    let mut e = e0;
    (0..steps)
        .map(|_| {
            e *= eps2(e);
            e
        })
        .collect()
}

/// Inverse distribution function of the Glauber form Eq. (7) of Giese,
/// p_G(ε²) = r e^{−ε² r} (r = E_tr/T_bath): ε² = −ln(1 − u)/r for u ∈ [0, 1).
pub fn glauber_eps2(energy_ratio: f64, u: f64) -> f64 {
    -(-u).ln_1p() / energy_ratio
}

/// Density of the Glauber form Eq. (7) of Giese, p_G(ε²) = r e^{−ε² r}.
pub fn glauber_density(energy_ratio: f64, eps2: f64) -> f64 {
    energy_ratio * (-eps2 * energy_ratio).exp()
}

/// Transition density Eq. (6) of Giese, p(E → E') = p(ε² = E'/E)/E, for a density
/// `p_eps2(r, ε²)` of ε² at r = E/T (energies in units of T_bath).
pub fn transition_density(p_eps2: impl Fn(f64, f64) -> f64, e: f64, e_next: f64) -> f64 {
    p_eps2(e, e_next / e) / e
}

/// Mean and second moment of a sample.
pub fn moments(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    (
        x.iter().sum::<f64>() / n,
        x.iter().map(|v| v * v).sum::<f64>() / n,
    )
}

/// Kolmogorov-Smirnov distance of a sample from the exponential law 1 − e^{−x}
/// (the stationary density exp(−E/T_bath) in units of T_bath).
pub fn ks_exponential(x: &[f64]) -> f64 {
    let mut s = x.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len() as f64;
    s.iter()
        .enumerate()
        .map(|(i, &v)| {
            let f = 1.0 - (-v).exp();
            (f - i as f64 / n).abs().max(((i + 1) as f64 / n - f).abs())
        })
        .fold(0.0, f64::max)
}

/// One step of Eq. (6) of Giese from the canonical density: E_k/T ~ Exp(1) conditioned on
/// E_k/T ≥ `e_min` (drawn by inversion from [`super::realization_rng`]`(seed, k)`), then
/// E'_k = ε² E_k with ε from [`super::solve`] (default resolution) at r = E_k/T.
/// Returns the pairs (E_k, E'_k) in units of T_bath. If exp(−E/T) is the stationary density
/// of Eq. (6), the E'_k are Exp(1) distributed up to the conditioning, whose total-variation
/// effect is at most P(E < e_min) = 1 − e^{−e_min}. The conditioning avoids the cost of
/// r → 0, which grows like 1/r (step ∝ √r, approach time ∝ 1/√r).
pub fn canonical_step(
    gamma: f64,
    kappa: f64,
    n: usize,
    seed: u64,
    e_min: f64,
) -> Result<Vec<(f64, f64)>> {
    use rand::Rng;
    use rayon::prelude::*;
    super::check_params(gamma, kappa, 1.0)?;
    if n == 0 {
        return Err(Error::out_of_range("n", 0, ">= 1"));
    }
    positive("e_min", e_min)?;
    let res = super::Resolution::default();
    (0..n as u64)
        .into_par_iter()
        .map(|k| {
            let mut rng = super::realization_rng(seed, k);
            let u: f64 = rng.random();
            let e = e_min - (-u).ln_1p();
            let s = super::solve(gamma, kappa, e, &res, &mut rng)?;
            Ok((e, s.eps * s.eps * e))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glauber_detailed_balance_exact() {
        // p(E→E') e^{−E} = e^{−E'} e^{−E} is symmetric in (E, E')
        for &(a, b) in &[(0.1, 2.0), (1.0, 3.5), (0.01, 0.7)] {
            let f = transition_density(glauber_density, a, b) * (-a).exp();
            let g = transition_density(glauber_density, b, a) * (-b).exp();
            assert!((f - g).abs() < 1e-15 * f.max(g), "{f} {g}");
        }
        // the inverse distribution function inverts p_G's CDF 1 − e^{−ε² r}
        let r = 3.0;
        let e2 = glauber_eps2(r, 0.3);
        assert!((1.0 - (-e2 * r).exp() - 0.3).abs() < 1e-15);
    }
}
