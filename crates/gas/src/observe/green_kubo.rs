//! The shear viscosity of a gas at equilibrium by the Green–Kubo formula in its
//! Einstein–Helfand form (Helfand, Phys. Rev. 119, 1 (1960); for hard spheres, whose
//! collisional stress is a train of impulses, Alder, Gass & Wainwright, J. Chem. Phys. 53,
//! 3813 (1970)):
//!
//!   η = V / (T c_D) ∫_0^∞ Σ_ab ⟨P°_ab(0) P°_ab(t)⟩ dt
//!     = V / (2 T c_D) lim_{τ→∞} d/dτ Σ_ab ⟨[G_ab(t + τ) − G_ab(t)]²⟩,
//!
//! with P° the traceless part of the pressure tensor, G_ab(t) = ∫_0^t P°_ab dt' its Helfand
//! moment, and c_D = (D + 2)(D − 1): in an isotropic fluid V/T ∫ ⟨P_ab(0) P_cd(t)⟩ dt =
//! η (δ_ac δ_bd + δ_ad δ_bc − (2/D) δ_ab δ_cd) + γ δ_ab δ_cd, and the traceless projector
//! contracted with itself counts (D + 2)(D − 1)/2 independent components, each twice (all
//! five of 3D used at once, as Daivis & Evans, J. Chem. Phys. 100, 541 (1994)). The
//! derivative is the slope of the mean square between two lags past the stress's
//! correlation time; the error comes from batches of the series taken as independent.
//!
//! The input is the pressure tensor averaged over consecutive intervals of equal length.
//! A kinetic part sampled at the end of each interval in place of its average changes the
//! moment by a bounded amount (no slope) plus a noise that vanishes with the interval; its
//! bias on the slope is measured in docs/shear.md (below 0.5 % at a tenth of a mean free
//! time).

/// The viscosity's estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HelfandViscosity {
    /// η, the mean of the batches' estimates.
    pub viscosity: f64,
    /// Its standard error (the batches' spread over the square root of their number).
    pub error: f64,
    /// The number of batches.
    pub batches: usize,
}

/// The traceless pressure tensor's components with their weights in Σ_ab (off-diagonal
/// ones twice): xx, yy, zz, xy, xz, yz (D = 2: xx, yy, xy).
fn traceless<const D: usize>(p: &[f64; 6]) -> ([f64; 6], [f64; 6]) {
    let trace = (0..D).map(|k| p[k]).sum::<f64>() / D as f64;
    if D == 2 {
        (
            [p[0] - trace, p[1] - trace, 0.0, p[3], 0.0, 0.0],
            [1.0, 1.0, 0.0, 2.0, 0.0, 0.0],
        )
    } else {
        (
            [p[0] - trace, p[1] - trace, p[2] - trace, p[3], p[4], p[5]],
            [1.0, 1.0, 1.0, 2.0, 2.0, 2.0],
        )
    }
}

/// The Helfand moments G(t_n) (n = 0 .. len) of pressures averaged over intervals of
/// length `interval`.
fn moments<const D: usize>(pressures: &[[f64; 6]], interval: f64) -> (Vec<[f64; 6]>, [f64; 6]) {
    let mut g = vec![[0.0; 6]; pressures.len() + 1];
    let mut weights = [0.0; 6];
    for (n, p) in pressures.iter().enumerate() {
        let (q, w) = traceless::<D>(p);
        weights = w;
        g[n + 1] = std::array::from_fn(|c| g[n][c] + q[c] * interval);
    }
    (g, weights)
}

/// Σ_ab ⟨[G_ab(t + lag) − G_ab(t)]²⟩ over the moments given.
fn mean_square(g: &[[f64; 6]], weights: &[f64; 6], lag: usize) -> f64 {
    let pairs = g.len() - lag;
    let sum: f64 = (0..pairs)
        .map(|t| {
            (0..6)
                .map(|c| weights[c] * (g[t + lag][c] - g[t][c]).powi(2))
                .sum::<f64>()
        })
        .sum();
    sum / pairs as f64
}

/// V / (2 T c_D): the mean square's slope to η.
fn scale<const D: usize>(volume: f64, temperature: f64) -> f64 {
    let d = D as f64;
    volume / (2.0 * temperature * (d + 2.0) * (d - 1.0))
}

/// η from `pressures` (each the pressure tensor xx, yy, zz, xy, xz, yz averaged over an
/// interval of length `interval`, consecutive), the slope of the mean square taken between
/// the lags `fit` (in intervals, fit.0 < fit.1), in `batches` consecutive batches. None
/// unless D is 2 or 3, the arguments are positive and finite, and every batch is at least
/// 2 fit.1 intervals long.
pub fn helfand_viscosity<const D: usize>(
    pressures: &[[f64; 6]],
    interval: f64,
    volume: f64,
    temperature: f64,
    fit: (usize, usize),
    batches: usize,
) -> Option<HelfandViscosity> {
    let positive = |x: f64| x.is_finite() && x > 0.0;
    if !(D == 2 || D == 3)
        || !(positive(interval) && positive(volume) && positive(temperature))
        || fit.0 >= fit.1
        || batches < 2
        || pressures.len() / batches < 2 * fit.1
    {
        return None;
    }
    let size = pressures.len() / batches;
    let estimates: Vec<f64> = (0..batches)
        .map(|b| {
            let (g, w) = moments::<D>(&pressures[b * size..(b + 1) * size], interval);
            let rise = mean_square(&g, &w, fit.1) - mean_square(&g, &w, fit.0);
            scale::<D>(volume, temperature) * rise / ((fit.1 - fit.0) as f64 * interval)
        })
        .collect();
    let n = batches as f64;
    let mean = estimates.iter().sum::<f64>() / n;
    let var = estimates.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / (n - 1.0);
    Some(HelfandViscosity {
        viscosity: mean,
        error: (var / n).sqrt(),
        batches,
    })
}

/// The running Green–Kubo integral η(τ) = V/(T c_D) ∫_0^τ Σ_ab ⟨P°_ab(0) P°_ab(t)⟩ dt at the
/// midpoints of consecutive `lags` (in intervals, increasing), as (τ, η(τ)): the mean
/// square's slope between the lags, from the whole series. Empty if the series is shorter
/// than twice the last lag.
pub fn running_viscosity<const D: usize>(
    pressures: &[[f64; 6]],
    interval: f64,
    volume: f64,
    temperature: f64,
    lags: &[usize],
) -> Vec<(f64, f64)> {
    if lags.last().is_none_or(|&l| pressures.len() < 2 * l) {
        return Vec::new();
    }
    let (g, w) = moments::<D>(pressures, interval);
    let squares: Vec<f64> = lags.iter().map(|&l| mean_square(&g, &w, l)).collect();
    lags.windows(2)
        .zip(squares.windows(2))
        .map(|(l, s)| {
            let tau = 0.5 * (l[0] + l[1]) as f64 * interval;
            let slope = (s[1] - s[0]) / ((l[1] - l[0]) as f64 * interval);
            (tau, scale::<D>(volume, temperature) * slope)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Oracle: an Ornstein–Uhlenbeck stress with the exact integral of its correlation.
    /// Each of the five independent traceless components is an AR(1) series p_{n+1} =
    /// r p_n + s ξ_n (ξ unit Gaussian), whose correlation sums (the rectangle rule of the
    /// integral with intervals Δt) to Δt var (1 + r)/(2(1 − r)) per component; η follows
    /// from the formula in the module documentation with the off-diagonal weights. The
    /// tolerance is 4 standard errors of the estimate it reports.
    #[test]
    fn recovers_the_integral_of_a_known_correlation() {
        use rand::{Rng, SeedableRng};
        use rand_distr::StandardNormal;
        let mut rng = rand::rngs::StdRng::seed_from_u64(5);
        let (r, s, dt, n) = (0.8f64, 0.3f64, 0.5, 400_000);
        let var = s * s / (1.0 - r * r);
        let per_component = dt * var * (1.0 + r) / (2.0 * (1.0 - r));
        // Off-diagonal xy, xz, yz independent with this integral; the diagonal built from
        // two independent series u, w as xx = u, yy = -u/2 + w sqrt(3)/2, zz = -u/2 -
        // w sqrt(3)/2: traceless, and Σ xx² + yy² + zz² = (3/2)(u² + w²).
        let mut state = [0.0f64; 5];
        let pressures: Vec<[f64; 6]> = (0..n)
            .map(|_| {
                for x in &mut state {
                    *x = r * *x + s * rng.sample::<f64, _>(StandardNormal);
                }
                let (u, w) = (state[0], state[1]);
                let h = 0.75f64.sqrt();
                [
                    u,
                    -0.5 * u + h * w,
                    -0.5 * u - h * w,
                    state[2],
                    state[3],
                    state[4],
                ]
            })
            .collect();
        let (volume, temperature) = (2.0, 0.7);
        // Σ_ab ∫⟨P°P°⟩ = (3/2)·2 + 2·3 = 9 component integrals; η = V/(T·10) times that.
        let expected = volume / (temperature * 10.0) * 9.0 * per_component;
        let fit = (40, 120); // r^40 ~ 1e-4: past the correlation
        let got = helfand_viscosity::<3>(&pressures, dt, volume, temperature, fit, 10).unwrap();
        assert!(
            (got.viscosity - expected).abs() < 4.0 * got.error,
            "{got:?} vs {expected}"
        );
        assert!(got.error < 0.05 * expected, "{got:?}");
        let curve = running_viscosity::<3>(&pressures, dt, volume, temperature, &[1, 40, 120]);
        assert_eq!(curve.len(), 2);
        assert!((curve[1].1 - expected).abs() < 0.1 * expected, "{curve:?}");
    }

    #[test]
    fn refuses_what_it_cannot_estimate() {
        let p = vec![[0.0; 6]; 100];
        assert!(helfand_viscosity::<3>(&p, 1.0, 1.0, 1.0, (5, 10), 10).is_none());
        assert!(helfand_viscosity::<3>(&p, 1.0, 1.0, 1.0, (10, 5), 2).is_none());
        assert!(helfand_viscosity::<3>(&p, f64::NAN, 1.0, 1.0, (1, 5), 2).is_none());
        assert!(helfand_viscosity::<1>(&p, 1.0, 1.0, 1.0, (1, 5), 2).is_none());
        assert!(helfand_viscosity::<3>(&p, 1.0, 1.0, 1.0, (1, 5), 2).is_some());
        assert!(running_viscosity::<3>(&p, 1.0, 1.0, 1.0, &[1, 60]).is_empty());
    }
}
