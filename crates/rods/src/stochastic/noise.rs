//! The Gaussian noise processes Q_i of Eq. (3) of Giese, with covariance Eq. (5).
//!
//! Q_i(τ) = Σ_{n≥1} (a_n/n) sin(2πnτ/Γ_i) + (b_n/n) cos(2πnτ/Γ_i), a_n, b_n iid
//! N(0, s_i²), s_i² = κ²(T_bath/E_tr)Γ_i/(4π²), so that
//! ⟨Q_i(τ)Q_i(τ')⟩ = κ²(T/E)(Γ_i/4)[((τ−τ')/Γ_i − 1/2)² − 1/12] for 0 ≤ τ−τ' ≤ Γ_i
//! (Eq. (5) of Giese; variance κ²(T/E)Γ_i/24).
//!
//! Discretization: one period is sampled on N = 2^k points (spacing Γ_i/N) by one FFT.
//! The modes n = 1..N/2 (n_max = N/2) are drawn explicitly, in order of n, so that two
//! resolutions share their low modes (common random numbers for convergence checks). The
//! tail n > N/2 is folded onto the grid modes (from an independent stream) with its exact
//! aliased variance: Σ_{n≡±m (mod N)} s²/n², using Σ_{j∈Z} 1/(m + jN)² = π²/(N² sin²(πm/N)).
//! Hence the grid values have *exactly* the covariance of Eq. (5) at the grid lags. Between grid
//! points the process is linearly interpolated (the unresolved sub-grid part of the
//! Brownian-like process is dropped; its effect is measured by the convergence checks).
use rand::{Rng, SeedableRng};
use rand_distr::StandardNormal;
use std::f64::consts::PI;

/// Covariance Eq. (5) of Giese at lag `lag`, periodically continued:
/// κ²/r · (Γ/4)[(x − 1/2)² − 1/12], x = (lag mod Γ)/Γ, r = E_tr/T_bath.
pub fn covariance(period: f64, kappa: f64, energy_ratio: f64, lag: f64) -> f64 {
    let x = (lag / period).rem_euclid(1.0);
    kappa * kappa / energy_ratio * period / 4.0 * ((x - 0.5).powi(2) - 1.0 / 12.0)
}

/// One realization of Q_i over one period Γ_i on a uniform grid of N = 2^k points.
#[derive(Clone, Debug)]
pub struct NoiseProcess {
    period: f64,
    inv_dt: f64,
    values: Vec<f64>,
}

impl NoiseProcess {
    /// Samples Q with period `period` (Γ_i) on `n` grid points (`n` a power of two ≥ 2),
    /// for scaled velocity κ and r = E_tr/T_bath.
    pub fn sample<R: Rng + ?Sized>(
        period: f64,
        kappa: f64,
        energy_ratio: f64,
        n: usize,
        rng: &mut R,
    ) -> Self {
        assert!(
            n.is_power_of_two() && n >= 2,
            "grid size must be a power of two"
        );
        let s2 = kappa * kappa * period / (4.0 * PI * PI * energy_ratio);
        let nf = n as f64;
        let half = n / 2;
        // aliased grid variance Λ_m = Σ_{n'≡m mod N} s²/n'² (see module doc)
        let lam = |m: usize| -> f64 {
            if m == 0 {
                s2 * PI * PI / (3.0 * nf * nf)
            } else {
                let s = (PI * m as f64 / nf).sin();
                s2 * PI * PI / (nf * nf * s * s)
            }
        };
        let mut tail_rng = rand_pcg::Pcg64::seed_from_u64(rng.random());
        let mut re = vec![0.0; n];
        let mut im = vec![0.0; n];
        // resolved modes n = 1..N/2, drawn in order of n (common random numbers across
        // resolutions): c_n = (b_n − i a_n)/n gives Re Σ c_n e^{2πink/N} = Σ (a_n sin + b_n cos)/n
        let s = s2.sqrt();
        for m in 1..=half {
            let a: f64 = rng.sample::<f64, _>(StandardNormal) * s;
            let b: f64 = rng.sample::<f64, _>(StandardNormal) * s;
            re[m] = b / m as f64;
            im[m] = -a / m as f64;
        }
        // aliased tail n > N/2, folded onto grid modes 0..=N/2 (independent stream)
        let mm = half as f64;
        for m in 0..=half {
            let extra = if m == 0 {
                lam(0) / 2.0
            } else if m == half {
                lam(m) / 2.0 - s2 / (mm * mm)
            } else {
                lam(m) - s2 / (m * m) as f64
            };
            let sd = extra.max(0.0).sqrt();
            let a: f64 = tail_rng.sample::<f64, _>(StandardNormal) * sd;
            let b: f64 = tail_rng.sample::<f64, _>(StandardNormal) * sd;
            re[m] += b;
            im[m] -= a;
        }
        // Q_k = Re Σ_m c_m e^{2πimk/N}
        fft_inverse(&mut re, &mut im);
        Self {
            period,
            inv_dt: nf / period,
            values: re,
        }
    }

    /// Grid values over one period (spacing Γ_i/N).
    pub fn grid(&self) -> &[f64] {
        &self.values
    }

    /// Period Γ_i.
    pub fn period(&self) -> f64 {
        self.period
    }

    /// Maximum over the grid (the supremum of the interpolant).
    pub fn max(&self) -> f64 {
        self.values
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Q(τ) by linear interpolation, periodic.
    #[inline]
    pub fn at(&self, tau: f64) -> f64 {
        let n = self.values.len();
        let x = (tau * self.inv_dt).rem_euclid(n as f64);
        let i = (x as usize).min(n - 1);
        let f = x - i as f64;
        let a = self.values[i];
        let b = self.values[(i + 1) & (n - 1)];
        a + f * (b - a)
    }
}

/// In-place unnormalized inverse DFT, x_k = Σ_m X_m e^{+2πimk/N}, N a power of two
/// (iterative radix-2).
pub(crate) fn fft_inverse(re: &mut [f64], im: &mut [f64]) {
    let n = re.len();
    let mut j = 0usize;
    for i in 1..n {
        let mut bit = n >> 1;
        while j & bit != 0 {
            j ^= bit;
            bit >>= 1;
        }
        j |= bit;
        if i < j {
            re.swap(i, j);
            im.swap(i, j);
        }
    }
    let mut len = 2;
    while len <= n {
        let ang = 2.0 * PI / len as f64;
        let half = len / 2;
        let (wr, wi) = (ang.cos(), ang.sin());
        for start in (0..n).step_by(len) {
            let (mut cr, mut ci) = (1.0f64, 0.0f64);
            for k in 0..half {
                let (a, b) = (start + k, start + k + half);
                let tr = re[b] * cr - im[b] * ci;
                let ti = re[b] * ci + im[b] * cr;
                re[b] = re[a] - tr;
                im[b] = im[a] - ti;
                re[a] += tr;
                im[a] += ti;
                let ncr = cr * wr - ci * wi;
                ci = cr * wi + ci * wr;
                cr = ncr;
            }
        }
        len <<= 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fft_matches_direct_sum() {
        let n = 16;
        let re0: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let im0: Vec<f64> = (0..n).map(|i| (i as f64 * 1.1).cos()).collect();
        let (mut re, mut im) = (re0.clone(), im0.clone());
        fft_inverse(&mut re, &mut im);
        for k in 0..n {
            let (mut sr, mut si) = (0.0, 0.0);
            for m in 0..n {
                let t = 2.0 * PI * (m * k) as f64 / n as f64;
                sr += re0[m] * t.cos() - im0[m] * t.sin();
                si += re0[m] * t.sin() + im0[m] * t.cos();
            }
            assert!((sr - re[k]).abs() < 1e-12 && (si - im[k]).abs() < 1e-12);
        }
    }

    #[test]
    fn aliased_spectrum_sums_to_eq5_variance() {
        // (1/2) Σ_m Λ_m must equal the variance κ²Γ/(24 r) of Eq. (5) for every N
        for &n in &[2usize, 8, 1024] {
            let nf = n as f64;
            let mut s = 1.0 / (3.0 * nf * nf);
            for m in 1..n {
                let x = (PI * m as f64 / nf).sin();
                s += 1.0 / (nf * nf * x * x);
            }
            // Σ_{n≠0} 1/n² = π²/3 → Λ-sum/(s²π²) = 1/3
            assert!((s - 1.0 / 3.0).abs() < 1e-12, "{n}: {s}");
        }
    }
}
