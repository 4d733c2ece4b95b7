//! Stochastic coefficients of restitution: Giese's rods (G. Giese, "Stochastic coefficient
//! of restitution — a new approach to the dynamics of granular media").
//!
//! A particle carries a bath of `modes` internal vibration modes at temperature T_i (bath
//! energy `modes * T_i`, one T per mode: kinetic plus potential). At a collision with
//! normal translational energy E_tr = mu v_n^2 / 2 the law draws eps^2 from a transition
//! density p(eps^2 | E_tr / T_bath) and the energy (1 - eps^2) E_tr goes into the pair's
//! baths. This is steps (2)-(4) of Giese's event-driven + Monte Carlo algorithm; step (1),
//! finding the collision, is the engine's.

use crate::error::{Error, Result};
use crate::law::Restitution;
use serde::{Deserialize, Serialize};
use std::fmt;

/// A law whose eps is random and exchanges energy with the colliding particles' baths.
pub trait StochasticRestitution: Send + Sync + fmt::Debug {
    /// The post-collision translational energy E'_tr = eps^2 E_tr for `e_tr` >= 0 and bath
    /// temperature `t_bath` >= 0, from one uniform number `u` in [0, 1) (inverse transform
    /// sampling). Energies, not eps: a pair touching with E_tr = 0 can still be kicked
    /// apart by its bath.
    fn draw_energy(&self, e_tr: f64, t_bath: f64, u: f64) -> f64;
    /// Internal modes per particle (N_modes of Giese).
    fn modes(&self) -> u32;
}

/// One collision of the event-driven + Monte Carlo algorithm of Giese, steps (2)-(4):
/// the pair's bath temperature is the mean of the two (equal numbers of modes, so this is
/// the energy-weighted mean), eps^2 is drawn, and both baths leave the collision at
/// T' = T + (1 - eps^2) E_tr / (2 N_modes) (Giese, text after Eq. (4)), so that
/// E_tr + 2 N_modes T is conserved exactly. (Giese leaves the update of step (4) open;
/// one temperature for both is our choice: it is the state Eq. (3) assumes.) E'_tr is capped at E_tr + 2 N_modes T: a bath
/// cannot give more energy than it holds. Returns E'_tr.
pub fn collide_with_baths(
    law: &dyn StochasticRestitution,
    e_tr: f64,
    baths: (&mut f64, &mut f64),
    u: f64,
) -> f64 {
    let modes = 2.0 * f64::from(law.modes());
    let t_bath = 0.5 * (*baths.0 + *baths.1);
    let bath_energy = modes * t_bath;
    let e_after = law
        .draw_energy(e_tr, t_bath, u)
        .clamp(0.0, e_tr + bath_energy);
    let t_after = ((bath_energy + e_tr - e_after) / modes).max(0.0);
    *baths.0 = t_after;
    *baths.1 = t_after;
    e_after
}

/// The Glauber-like transition density, Eq. (7) of Giese:
/// p(eps^2) = (E_tr / T) exp(-eps^2 E_tr / T), i.e. E'_tr = eps^2 E_tr is exponential with
/// mean T whatever E_tr was. It obeys detailed balance with respect to
/// p_stat(E_tr) ~ exp(-E_tr / T) exactly (the collision-sampled Boltzmann density).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Glauber {
    modes: u32,
}

impl Glauber {
    /// Fails unless `modes` >= 1.
    pub fn new(modes: u32) -> Result<Self> {
        require_modes(modes)?;
        Ok(Glauber { modes })
    }
}

impl StochasticRestitution for Glauber {
    /// Inverse transform of Eq. (7): E' = -T ln(1 - u) (ln_1p keeps precision for small
    /// u); at T = 0 all translational energy goes to the bath.
    fn draw_energy(&self, _e_tr: f64, t_bath: f64, u: f64) -> f64 {
        -t_bath.max(0.0) * (-u).ln_1p()
    }

    fn modes(&self) -> u32 {
        self.modes
    }
}

/// p(eps^2 | E_tr / T_bath) tabulated from realizations of Giese's stochastic collision
/// equation, Eq. (3) (built by `rods::stochastic::Table`): quantiles of eps^2 at L
/// equally spaced probabilities 0, 1/(L-1), ..., 1 for each energy ratio r = E_tr/T_bath
/// of an increasing grid.
///
/// Sampling (inverse distribution function): linear in u between the quantiles; between
/// two grid ratios ln eps^2 is interpolated linearly in ln r at fixed u (a proper
/// distribution, exact for power laws such as eps^2 ~ 1/r at small r). For r above the
/// grid the last row is used (the distribution tends to the deterministic, cold-bath eps);
/// below it the outgoing energy is distributed as at the first ratio,
/// E'/T = eps^2(r_min, u) r_min (for r -> 0 the bath alone sets E').
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Tabulated {
    /// Length ratio gamma = l1 / l2 of the rods the table was built for.
    pub gamma: f64,
    /// Hard-core parameter kappa of Eq. (3).
    pub kappa: f64,
    /// E_tr / T_bath, increasing.
    pub energy_ratios: Vec<f64>,
    /// `quantiles[r][k]`: the k-th quantile of eps^2 at `energy_ratios[r]`, non-decreasing in k.
    pub quantiles: Vec<Vec<f64>>,
    /// Internal modes per particle.
    pub modes: u32,
}

impl Tabulated {
    /// Checks the table's shape: >= 1 increasing positive ratios, >= 2 levels per row,
    /// finite non-decreasing non-negative quantiles.
    pub fn new(
        gamma: f64,
        kappa: f64,
        energy_ratios: Vec<f64>,
        quantiles: Vec<Vec<f64>>,
        modes: u32,
    ) -> Result<Self> {
        require_modes(modes)?;
        let bad = |what: String| Err(Error::parse("stochastic restitution table", what));
        if energy_ratios.is_empty() || energy_ratios.len() != quantiles.len() {
            return bad("one row of quantiles per energy ratio, at least one".into());
        }
        let increasing = energy_ratios.windows(2).all(|w| w[0] < w[1]);
        if !increasing || energy_ratios[0] <= 0.0 || !energy_ratios.iter().all(|r| r.is_finite()) {
            return bad("energy ratios must be finite, positive and increasing".into());
        }
        let levels = quantiles[0].len();
        for (r, row) in quantiles.iter().enumerate() {
            let sorted = row.windows(2).all(|w| w[0] <= w[1]);
            let finite = row.iter().all(|q| q.is_finite() && *q >= 0.0);
            if row.len() != levels || levels < 2 || !sorted || !finite {
                return bad(format!(
                    "row {r} must hold {levels} >= 2 finite, non-negative, non-decreasing quantiles"
                ));
            }
        }
        Ok(Tabulated {
            gamma,
            kappa,
            energy_ratios,
            quantiles,
            modes,
        })
    }

    /// eps^2 at r = E_tr / T_bath > 0 (infinite for a cold bath) and probability `u`.
    pub fn draw_eps2(&self, energy_ratio: f64, u: f64) -> f64 {
        tabulated_eps2(&self.energy_ratios, &self.quantiles, energy_ratio, u)
    }
}

/// The quantile function of one row of a table at probability `u`.
fn quantile(row: &[f64], u: f64) -> f64 {
    let x = u.clamp(0.0, 1.0) * (row.len() - 1) as f64;
    let k = (x as usize).min(row.len() - 2);
    let f = x - k as f64;
    row[k] + f * (row[k + 1] - row[k])
}

/// eps^2 from the quantile table (`energy_ratios`, `quantiles`) at r = `energy_ratio` and
/// probability `u`, interpolated as [`Tabulated`] says; shared with `rods::stochastic::Table`.
pub fn tabulated_eps2(
    energy_ratios: &[f64],
    quantiles: &[Vec<f64>],
    energy_ratio: f64,
    u: f64,
) -> f64 {
    let last = energy_ratios.len() - 1;
    if energy_ratio <= energy_ratios[0] {
        return quantile(&quantiles[0], u) * energy_ratios[0] / energy_ratio;
    }
    if energy_ratio >= energy_ratios[last] {
        return quantile(&quantiles[last], u);
    }
    let r = energy_ratios.partition_point(|&q| q <= energy_ratio) - 1;
    let f = (energy_ratio / energy_ratios[r]).ln() / (energy_ratios[r + 1] / energy_ratios[r]).ln();
    let (a, b) = (quantile(&quantiles[r], u), quantile(&quantiles[r + 1], u));
    if a > 0.0 && b > 0.0 {
        ((1.0 - f) * a.ln() + f * b.ln()).exp()
    } else {
        (1.0 - f) * a + f * b
    }
}

impl StochasticRestitution for Tabulated {
    fn draw_energy(&self, e_tr: f64, t_bath: f64, u: f64) -> f64 {
        let r_min = self.energy_ratios[0];
        if t_bath > 0.0 && e_tr <= r_min * t_bath {
            // Below the grid: E' / T as at r_min (also for a pair touching at rest).
            return quantile(&self.quantiles[0], u) * r_min * t_bath;
        }
        let ratio = if t_bath > 0.0 {
            e_tr / t_bath
        } else {
            f64::INFINITY
        };
        e_tr * self.draw_eps2(ratio, u)
    }

    fn modes(&self) -> u32 {
        self.modes
    }
}

/// As a [`Restitution`], a stochastic law answers `eps(speed)` with its cold-bath median
/// (T_bath = 0); engines that support baths call [`Restitution::stochastic`] instead.
macro_rules! restitution_via_baths {
    ($law:ty, $what:expr) => {
        impl Restitution for $law {
            fn eps(&self, _speed: f64) -> f64 {
                self.draw_energy(1.0, 0.0, 0.5).sqrt()
            }
            fn describe(&self) -> String {
                $what(self)
            }
            fn box_clone(&self) -> Box<dyn Restitution> {
                Box::new(self.clone())
            }
            fn stochastic(&self) -> Option<&dyn StochasticRestitution> {
                Some(self)
            }
        }
    };
}

restitution_via_baths!(Glauber, |g: &Glauber| format!(
    "stochastic Glauber (Eq. 7 of Giese, {} modes per particle)",
    g.modes
));
restitution_via_baths!(Tabulated, |t: &Tabulated| format!(
    "stochastic tabulated from Eq. (3) of Giese (gamma = {}, kappa = {}, {} modes per particle)",
    t.gamma, t.kappa, t.modes
));

fn require_modes(modes: u32) -> Result<()> {
    if modes == 0 {
        return Err(Error::out_of_range(
            "modes",
            modes,
            "an integer >= 1 (internal vibration modes per particle)",
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fixed-T bath (infinitely many modes) and a Markov chain of E_tr (Eq. (6) of Giese).
    fn chain(law: &dyn StochasticRestitution, steps: usize) -> Vec<f64> {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut uniform = move || {
            // xorshift64*: enough for a unit test's statistics.
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut e = 5.0;
        (0..steps)
            .map(|_| {
                e = law.draw_energy(e, 1.0, uniform());
                e
            })
            .collect()
    }

    #[test]
    fn glauber_chain_is_boltzmann_and_detailed_balanced() {
        let law = Glauber::new(10).unwrap();
        let n = 400_000;
        let e = chain(&law, n);
        let mean = e.iter().sum::<f64>() / n as f64;
        let second = e.iter().map(|x| x * x).sum::<f64>() / n as f64;
        // Exponential(1): mean 1 (sd of the mean 1/sqrt(n) = 1.6e-3), <E^2> = 2 (sd 7e-3).
        assert!((mean - 1.0).abs() < 8e-3, "mean {mean}");
        assert!((second - 2.0).abs() < 4e-2, "second moment {second}");
        // Detailed balance: transitions below->above a threshold as often as back.
        let (up, down) = e.windows(2).fold((0u32, 0u32), |(u, d), w| {
            (
                u + (w[0] < 1.0 && w[1] >= 1.0) as u32,
                d + (w[0] >= 1.0 && w[1] < 1.0) as u32,
            )
        });
        let expected = n as f64 * (1.0 - (-1.0f64).exp()) * (-1.0f64).exp();
        assert!((f64::from(up) - expected).abs() < 5.0 * expected.sqrt());
        assert!((f64::from(up) - f64::from(down)).abs() <= 1.0);
    }

    #[test]
    fn bath_bookkeeping_conserves_energy() {
        let law = Glauber::new(7).unwrap();
        for (e_tr, ta, tb, u) in [
            (1.0, 0.0, 0.0, 0.3),
            (2.0, 0.5, 1.5, 0.999_999),
            (0.1, 3.0, 1.0, 0.5),
        ] {
            let (mut a, mut b) = (ta, tb);
            let e_after = collide_with_baths(&law, e_tr, (&mut a, &mut b), u);
            let before = e_tr + 7.0 * (ta + tb);
            let after = e_after + 7.0 * (a + b);
            assert!((after - before).abs() < 1e-12 * before, "{before} {after}");
            assert!(a >= 0.0 && a == b);
        }
    }

    #[test]
    fn tabulated_interpolates_and_validates() {
        let rows = vec![vec![0.0, 2.0], vec![0.2, 0.4]];
        let t = Tabulated::new(0.5, 100.0, vec![1.0, 100.0], rows, 3).unwrap();
        assert_eq!(t.draw_eps2(1.0, 0.5), 1.0);
        assert!((t.draw_eps2(1e4, 0.5) - 0.3).abs() < 1e-15);
        assert!((t.draw_energy(1.0, 0.0, 0.0) - 0.2).abs() < 1e-15);
        // Halfway in ln(ratio): the geometric mean of the two rows' quantiles.
        assert!((t.draw_eps2(10.0, 0.5) - 0.3f64.sqrt()).abs() < 1e-15);
        // Below the grid E'/T is that of the first ratio, for E_tr = 0 too.
        assert!((t.draw_energy(0.0, 2.0, 0.5) - 2.0).abs() < 1e-15);
        assert!((t.draw_energy(0.1, 2.0, 0.5) - 2.0).abs() < 1e-15);
        assert!(Tabulated::new(0.5, 100.0, vec![2.0, 1.0], vec![vec![0.0, 1.0]; 2], 3).is_err());
        assert!(Tabulated::new(0.5, 100.0, vec![1.0], vec![vec![1.0, 0.0]], 3).is_err());
        assert!(Glauber::new(0).is_err());
    }
}
