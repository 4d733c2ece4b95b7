//! Tabulated distribution of ε² (Eq. (3)-(4) of Giese) on a grid of energy ratios
//! r = E_tr/T_bath, for a Monte-Carlo collision law in event-driven MD (the algorithm
//! proposed at the end of Giese's letter, with the exact p(ε²) instead of Eq. (7)).
use super::{check_params, realization_rng, sample_eps};
use crate::error::{Error, Result};
use rand::RngCore;
use restitution::stochastic::{tabulated_eps2, Tabulated};
use serde::{Deserialize, Serialize};

/// Quantiles of ε² at the probability levels p_k = k/`levels`, k = 0..=`levels`, for each
/// energy ratio of an increasing grid.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Table {
    /// Length ratio γ = l1/l2.
    pub gamma: f64,
    /// Scaled impact velocity κ.
    pub kappa: f64,
    /// Increasing grid of r = E_tr/T_bath (log-spaced by [`Table::log_grid`]).
    pub energy_ratios: Vec<f64>,
    /// Number of probability intervals; `quantiles[i]` has `levels + 1` entries.
    pub levels: usize,
    /// `quantiles[i][k]`: the p_k = k/levels quantile of ε² at `energy_ratios[i]`
    /// (empirical, linear interpolation of the order statistics), except k = 0 and
    /// k = levels, which are set such that the first and last probability bins, with ε²
    /// linear in u, have the sample mean of the samples they hold.
    pub quantiles: Vec<Vec<f64>>,
    /// Realizations of Eq. (3) per energy ratio.
    pub realizations: usize,
    /// Seed of the sample.
    pub seed: u64,
}

impl Table {
    /// Default number of probability intervals.
    pub const LEVELS: usize = 200;

    /// `n` ratios log-spaced from `min` to `max` (inclusive).
    pub fn log_grid(min: f64, max: f64, n: usize) -> Vec<f64> {
        if n == 1 {
            return vec![min];
        }
        let (a, b) = (min.ln(), max.ln());
        (0..n)
            .map(|i| (a + (b - a) * i as f64 / (n - 1) as f64).exp())
            .collect()
    }

    /// Samples `realizations` values of ε² per ratio with [`sample_eps`] (ratio i uses a
    /// seed derived from (`seed`, i)) and stores [`Table::LEVELS`] + 1 quantiles.
    pub fn build(
        gamma: f64,
        kappa: f64,
        ratios: &[f64],
        realizations: usize,
        seed: u64,
    ) -> Result<Self> {
        Self::build_reporting(gamma, kappa, ratios, realizations, seed, |_| {})
    }

    /// [`Table::build`], calling `row_done(i)` after ratio i (for progress bars).
    pub fn build_reporting(
        gamma: f64,
        kappa: f64,
        ratios: &[f64],
        realizations: usize,
        seed: u64,
        mut row_done: impl FnMut(usize),
    ) -> Result<Self> {
        const GRID: &str = "a non-empty increasing grid of finite values > 0";
        if ratios.is_empty() {
            return Err(Error::out_of_range("ratios", "[]", GRID));
        }
        for w in ratios.windows(2) {
            if w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater) {
                let value = format!("{} then {}", w[0], w[1]);
                return Err(Error::out_of_range("ratios", value, GRID));
            }
        }
        for &r in ratios {
            check_params(gamma, kappa, r)?;
            if !r.is_finite() {
                return Err(Error::out_of_range("ratios", r, GRID));
            }
        }
        if realizations < 2 {
            return Err(Error::out_of_range("realizations", realizations, ">= 2"));
        }
        let levels = Self::LEVELS;
        let mut quantiles = Vec::with_capacity(ratios.len());
        for (i, &r) in ratios.iter().enumerate() {
            let s = realization_rng(seed, i as u64).next_u64();
            let mut e2: Vec<f64> = sample_eps(gamma, kappa, r, realizations, s)?
                .into_iter()
                .map(|e| e * e)
                .collect();
            e2.sort_by(f64::total_cmp);
            let n = e2.len();
            let mut q: Vec<f64> = (0..=levels)
                .map(|k| {
                    let x = (n - 1) as f64 * k as f64 / levels as f64;
                    let j = (x as usize).min(n - 2);
                    let f = x - j as f64;
                    e2[j] + f * (e2[j + 1] - e2[j])
                })
                .collect();
            // end points: the extreme bins, linear in u, reproduce the sample mean of the
            // samples they hold (the raw min/max would overweight the tails by a factor
            // ~ realizations/levels)
            let top = &e2[(n * (levels - 1) / levels).min(n - 1)..];
            let m_top = top.iter().sum::<f64>() / top.len() as f64;
            q[levels] = (2.0 * m_top - q[levels - 1]).max(q[levels - 1]);
            let bot = &e2[..n.div_ceil(levels).max(1)];
            let m_bot = bot.iter().sum::<f64>() / bot.len() as f64;
            q[0] = (2.0 * m_bot - q[1]).clamp(0.0, q[1]);
            quantiles.push(q);
            row_done(i);
        }
        Ok(Self {
            gamma,
            kappa,
            energy_ratios: ratios.to_vec(),
            levels,
            quantiles,
            realizations,
            seed,
        })
    }

    /// ε² for energy ratio r = E_tr/T_bath and a uniform variate u ∈ [0, 1) (inverse
    /// distribution function), interpolated as `restitution::Tabulated` says (linear in u;
    /// ln ε² linear in ln r; last row above the grid; E'_tr/T_bath as at r_min below it).
    pub fn sample(&self, energy_ratio: f64, u: f64) -> f64 {
        tabulated_eps2(&self.energy_ratios, &self.quantiles, energy_ratio, u)
    }

    /// The collision law of this table for particles with `modes` internal modes each.
    pub fn law(&self, modes: u32) -> Result<Tabulated> {
        let (ratios, quantiles) = (self.energy_ratios.clone(), self.quantiles.clone());
        Ok(Tabulated::new(
            self.gamma, self.kappa, ratios, quantiles, modes,
        )?)
    }

    /// Mean of ε² at grid row `i` under [`Table::sample`] (trapezoidal in u).
    pub fn mean_eps2(&self, i: usize) -> f64 {
        let q = &self.quantiles[i];
        let l = self.levels;
        (q[0] / 2.0 + q[1..l].iter().sum::<f64>() + q[l] / 2.0) / l as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toy() -> Table {
        Table {
            gamma: 0.5,
            kappa: 100.0,
            energy_ratios: vec![1.0, 10.0],
            levels: 2,
            quantiles: vec![vec![0.0, 1.0, 4.0], vec![0.2, 0.4, 0.6]],
            realizations: 3,
            seed: 0,
        }
    }

    #[test]
    fn interpolation_and_clamping() {
        let t = toy();
        assert_eq!(t.sample(1.0, 0.25), 0.5);
        assert_eq!(t.sample(1.0, 0.75), 2.5);
        assert_eq!(t.sample(10.0, 0.5), 0.4);
        assert_eq!(t.sample(100.0, 0.5), 0.4); // ε² clamped above the grid
        assert_eq!(t.sample(0.1, 0.5), 10.0); // E'/T clamped below the grid
        let m = t.sample(10f64.sqrt(), 0.5); // halfway in ln r: geometric mean
        assert!((m - 0.4f64.sqrt()).abs() < 1e-12, "{m}");
        assert!((t.mean_eps2(1) - 0.4).abs() < 1e-15);
        assert_eq!(t.sample(1.0, 1.0), 4.0);
    }

    #[test]
    fn serde_round_trip() {
        let t = toy();
        let s = serde_json::to_string(&t).unwrap();
        assert_eq!(serde_json::from_str::<Table>(&s).unwrap(), t);
    }

    #[test]
    fn build_guards() {
        assert!(Table::build(0.5, 100.0, &[], 10, 0)
            .unwrap_err()
            .to_string()
            .contains("ratios"));
        assert!(Table::build(0.5, 100.0, &[2.0, 1.0], 10, 0)
            .unwrap_err()
            .to_string()
            .contains("increasing"));
        assert!(Table::build(0.5, 100.0, &[1.0], 1, 0)
            .unwrap_err()
            .to_string()
            .contains("realizations"));
        assert!(Table::build(-0.5, 100.0, &[1.0], 10, 0)
            .unwrap_err()
            .to_string()
            .contains("gamma"));
    }
}
