//! Mixtures whose restitution depends on the impact speed (viscoelastic spheres): each
//! species' cooling rate in the Maxwellian approximation, and the free cooling of the
//! species' temperatures in time.
//!
//! Derivation. In the cooling rate of the [module](super) documentation the energy a
//! collision takes from particle 1 at normal relative speed g_n = g.e > 0 is
//! (m_i / 2) g_n^2 [mu^2 (1 + alpha)^2 - 2 mu (1 + alpha) a_i / (a_i + a_j)], and the
//! collisions of a Maxwellian pair come at the rate weight g_n^3 exp(-g_n^2 / (2 s^2)),
//! s^2 = a_i + a_j (for a fixed e, g.e of an isotropic Gaussian g is a Gaussian of
//! variance s^2). With alpha(g_n) the constant-alpha rate holds with (1 + alpha) and
//! (1 + alpha)^2 replaced by their averages over that weight,
//!
//!   K1 = <1 + alpha(g_n)>_3,  K2 = <(1 + alpha(g_n))^2>_3,
//!   zeta_i = (2/D) sum_j nu_ij mu_ji [2 K1 - mu_ji K2 (1 + a_j / a_i)].
//!
//! A viscoelastic alpha = 1 - O(g^(1/5)) makes the rates scale as T^(1/10) nu: the
//! species' temperatures fall as t^(-5/3) at late times and their ratios tend to 1 as the
//! collisions turn elastic (Brilliantov & Pöschel, Kinetic Theory of Granular Gases, for
//! one species).

use super::MixtureTheory;
use crate::error::{Error, Result};

/// Simpson intervals of the weighted averages over u = g_n / s in [0, U_MAX]: the weight
/// u^3 exp(-u^2/2) is below 1e-19 of its peak beyond, and the integrand is smooth but for
/// u^(3 + 1/5) at 0 (error ~ h^4.2 ~ 1e-10).
const INTERVALS: usize = 1000;
const U_MAX: f64 = 10.0;

impl<const D: usize> MixtureTheory<D> {
    /// Each species' cooling rate for Maxwellians at `temperatures` when a pair (i, j)
    /// meeting at normal relative speed g restitutes with `eps(i, j, g)` (the
    /// [`Self::restitution`] matrix is not used). A constant eps gives
    /// [`Self::cooling_rates`].
    pub fn cooling_rates_for(
        &self,
        temperatures: &[f64],
        eps: &impl Fn(usize, usize, f64) -> f64,
    ) -> Vec<f64> {
        self.cooling_rates_with(temperatures, |i, j| {
            let s = (temperatures[i] / self.masses[i] + temperatures[j] / self.masses[j]).sqrt();
            averages(|g| eps(i, j, g), s)
        })
    }

    /// The species' temperatures of a freely cooling mixture, dT_i/dt = -zeta_i T_i with
    /// the rates of [`Self::cooling_rates_for`], from `initial` at t = 0 at each of `times`
    /// (ascending, >= 0). Classical Runge–Kutta in ln(1 + nu_0 t) (nu_0: the initial mean
    /// collision frequency) with at least `steps_per_unit` steps per unit of it (the late
    /// power law is a straight line there), and steps below the inverse relaxation rate of
    /// the ratios.
    pub fn free_cooling(
        &self,
        initial: &[f64],
        eps: &impl Fn(usize, usize, f64) -> f64,
        times: &[f64],
        steps_per_unit: usize,
    ) -> Result<Vec<Vec<f64>>> {
        if initial.len() != self.species() || initial.iter().any(|t| !(t.is_finite() && *t > 0.0)) {
            return Err(Error::out_of_range(
                "initial",
                initial.len(),
                format!("{} temperatures, finite and > 0", self.species()),
            ));
        }
        if times.windows(2).any(|w| w[1] < w[0]) || times.iter().any(|t| t.is_nan() || *t < 0.0) {
            return Err(Error::out_of_range("times", times.len(), "ascending, >= 0"));
        }
        let nu0: f64 = self
            .collision_frequencies(initial)
            .iter()
            .zip(&self.fractions)
            .map(|(nu, x)| nu * x)
            .sum();
        // y = ln T_i against sigma = ln(1 + nu0 t): dy/dsigma = -zeta_i (1 + nu0 t) / nu0.
        let rate = |sigma: f64, y: &[f64]| -> Vec<f64> {
            let t: Vec<f64> = y.iter().map(|v| v.exp()).collect();
            let stretch = sigma.exp() / nu0;
            self.cooling_rates_for(&t, eps)
                .iter()
                .map(|z| -z * stretch)
                .collect()
        };
        let mut y: Vec<f64> = initial.iter().map(|t| t.ln()).collect();
        let mut sigma = 0.0;
        let mut out = Vec::with_capacity(times.len());
        for &time in times {
            let target = (nu0 * time).ln_1p();
            while sigma < target {
                // The ratios relax at the collision frequency nu, a rate nu (1 + nu0 t) / nu0
                // in sigma that grows as t^(1/6) on the late power law: steps below its
                // inverse keep the classical Runge–Kutta stable.
                let t: Vec<f64> = y.iter().map(|v| v.exp()).collect();
                let stiffness = self
                    .collision_frequencies(&t)
                    .iter()
                    .fold(0.0, |a: f64, b| a.max(*b))
                    * sigma.exp()
                    / nu0;
                let h = (1.0 / steps_per_unit as f64)
                    .min(1.0 / stiffness)
                    .min(target - sigma);
                let add = |y: &[f64], k: &[f64], f: f64| -> Vec<f64> {
                    y.iter().zip(k).map(|(a, b)| a + f * b).collect()
                };
                let k1 = rate(sigma, &y);
                let k2 = rate(sigma + h / 2.0, &add(&y, &k1, h / 2.0));
                let k3 = rate(sigma + h / 2.0, &add(&y, &k2, h / 2.0));
                let k4 = rate(sigma + h, &add(&y, &k3, h));
                for (n, v) in y.iter_mut().enumerate() {
                    *v += h / 6.0 * (k1[n] + 2.0 * k2[n] + 2.0 * k3[n] + k4[n]);
                }
                sigma = if target - sigma <= h {
                    target
                } else {
                    sigma + h
                };
            }
            out.push(y.iter().map(|v| v.exp()).collect());
        }
        Ok(out)
    }
}

/// K1 = <1 + eps>_3 and K2 = <(1 + eps)^2>_3 over the weight g^3 exp(-g^2 / (2 s^2)) of
/// normal relative speeds g (Simpson in u = g / s; normalized by the weight's integral by
/// the same rule, whose error then cancels).
pub(crate) fn averages(eps: impl Fn(f64) -> f64, s: f64) -> (f64, f64) {
    let h = U_MAX / INTERVALS as f64;
    let (mut norm, mut k1, mut k2) = (0.0, 0.0, 0.0);
    for n in 1..=INTERVALS {
        let u = n as f64 * h;
        let simpson = match n {
            _ if n == INTERVALS => 1.0,
            _ if n % 2 == 1 => 4.0,
            _ => 2.0,
        };
        let w = simpson * u * u * u * (-0.5 * u * u).exp();
        let one_plus = 1.0 + eps(u * s);
        norm += w;
        k1 += w * one_plus;
        k2 += w * one_plus * one_plus;
    }
    (k1 / norm, k2 / norm)
}
