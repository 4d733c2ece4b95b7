//! The homogeneous cooling state of a granular mixture: species of mass m_i, diameter
//! sigma_i and number fraction x_i, restitution alpha_ij per pair, at total packing
//! fraction phi, in D = 1, 2, 3 (Enskog: the pair correlation at contact chi_ij of
//! [`super::mixture_contact_value`], BMCSL in 3D). Each species has its own temperature
//! T_i = m_i <c^2>_i / D; in the HCS all cool at one rate, zeta_i = zeta, which fixes the
//! ratios T_i / T (T = sum x_i T_i): energy equipartition breaks down (Garzó & Dufty,
//! Phys. Rev. E 60, 5706 (1999); the Maxwellian approximation here).
//!
//! Derivation (independent of the paper; checked against a Monte Carlo integral in the
//! tests). Species i and j with Maxwellians of variances a_i = T_i / m_i per component,
//! mu_ji = m_j / (m_i + m_j), relative velocity g = v_1 - v_2 and impact direction e: the
//! collision changes v_1 by -mu_ji (1 + alpha_ij)(g.e) e, so the energy of particle 1 by
//!
//!   dE_1 = (m_i / 2) [mu_ji^2 (1 + alpha)^2 (g.e)^2 - 2 mu_ji (1 + alpha)(g.e)(v_1.e)].
//!
//! Given g, v_1 is Gaussian with mean a_i g / (a_i + a_j), so E[(v_1.e) | g] =
//! a_i (g.e) / (a_i + a_j). With the integrals over e of (g.e)^+ and (g.e)^3 for (g.e) > 0
//! and the moments E|g| and E|g|^3 of g ~ N(0, (a_i + a_j) I), the collision frequency of
//! an i particle with j particles and its cooling rate (dT_i/dt = -zeta_i T_i) are
//!
//!   nu_ij  = chi_ij n_j sigma_ij^(D-1) S_D sqrt((a_i + a_j) / (2 pi)),
//!   zeta_i = (2/D) sum_j nu_ij mu_ji (1 + alpha_ij) [2 - mu_ji (1 + alpha_ij)(1 + a_j/a_i)],
//!
//! with S_D = 2, 2 pi, 4 pi. One species: nu = omega of [`super::collision_frequency`] and
//! zeta = (1 - alpha^2) omega / D, the module's Haff law.

mod laws;
pub(crate) use laws::averages as restitution_averages;
mod sonine;

pub use sonine::DrivenState;

use super::{close_packing, mixture_contact_value, sphere_surface};
use crate::error::{Error, Result};
use crate::system::ball_volume;
use std::f64::consts::PI;

/// A granular mixture for kinetic theory (see the [module](self) documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct MixtureTheory<const D: usize> {
    masses: Vec<f64>,
    diameters: Vec<f64>,
    fractions: Vec<f64>,
    restitution: Vec<Vec<f64>>,
    /// Total number density n.
    density: f64,
    /// chi_ij.
    contact: Vec<Vec<f64>>,
}

/// The HCS of a mixture: the temperature ratios T_i / T (T = sum x_i T_i), each species'
/// Sonine coefficient a2_i (zero in the Maxwellian approximation) and, at T, the common
/// cooling rate and each species' collision frequency.
#[derive(Debug, Clone, PartialEq)]
pub struct MixtureHcs {
    pub temperature_ratios: Vec<f64>,
    pub a2: Vec<f64>,
    pub cooling_rate: f64,
    pub collision_frequencies: Vec<f64>,
}

impl<const D: usize> MixtureTheory<D> {
    /// Species with `masses`, `diameters` and number `fractions` (positive, summing to 1
    /// within 1e-9; normalized), `restitution[i][j]` = alpha_ij (symmetric, in [0, 1]), at
    /// total packing fraction `phi` (0 < phi < close packing). Errors name the parameter.
    pub fn new(
        masses: &[f64],
        diameters: &[f64],
        fractions: &[f64],
        restitution: &[Vec<f64>],
        phi: f64,
    ) -> Result<Self> {
        super::check_dimension::<D>()?;
        let s = masses.len();
        if s == 0 {
            return Err(Error::out_of_range("masses", 0, "at least one species"));
        }
        for (name, values) in [("diameters", diameters), ("fractions", fractions)] {
            if values.len() != s {
                return Err(Error::out_of_range(
                    name,
                    values.len(),
                    format!("one per species ({s})"),
                ));
            }
        }
        for (name, values) in [
            ("masses", masses),
            ("diameters", diameters),
            ("fractions", fractions),
        ] {
            if let Some(&v) = values.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
                return Err(Error::out_of_range(name, v, "finite and > 0"));
            }
        }
        let total: f64 = fractions.iter().sum();
        if (total - 1.0).abs() > 1e-9 {
            return Err(Error::out_of_range("fractions", total, "summing to 1"));
        }
        if restitution.len() != s || restitution.iter().any(|row| row.len() != s) {
            return Err(Error::out_of_range(
                "restitution",
                restitution.len(),
                format!("a {s} x {s} matrix"),
            ));
        }
        for (i, row) in restitution.iter().enumerate() {
            for (j, &a) in row.iter().enumerate() {
                if !(0.0..=1.0).contains(&a) || a != restitution[j][i] {
                    return Err(Error::out_of_range(
                        "restitution",
                        a,
                        format!("0 <= alpha <= 1, symmetric (alpha[{i}][{j}] = alpha[{j}][{i}])"),
                    ));
                }
            }
        }
        if !(phi > 0.0 && phi < close_packing::<D>()) {
            return Err(Error::out_of_range(
                "packing_fraction",
                phi,
                format!("0 < phi < {}", close_packing::<D>()),
            ));
        }
        let fractions: Vec<f64> = fractions.iter().map(|x| x / total).collect();
        let mean_volume: f64 = fractions
            .iter()
            .zip(diameters)
            .map(|(x, d)| x * ball_volume::<D>(d / 2.0))
            .sum();
        // M = sum x sigma^(D-1) / sum x sigma^D (see mixture_contact_value).
        let moment = |k: i32| -> f64 {
            fractions
                .iter()
                .zip(diameters)
                .map(|(x, d)| x * d.powi(k))
                .sum()
        };
        let ratio = moment(D as i32 - 1) / moment(D as i32);
        let contact = (0..s)
            .map(|i| {
                (0..s)
                    .map(|j| {
                        let (a, b) = (diameters[i], diameters[j]);
                        mixture_contact_value::<D>(phi, a * b / (a + b) * ratio)
                    })
                    .collect()
            })
            .collect();
        Ok(MixtureTheory {
            masses: masses.to_vec(),
            diameters: diameters.to_vec(),
            fractions,
            restitution: restitution.to_vec(),
            density: phi / mean_volume,
            contact,
        })
    }

    /// The number of species.
    pub fn species(&self) -> usize {
        self.masses.len()
    }

    /// The total number density n = phi / sum x_i V(sigma_i / 2).
    pub fn density(&self) -> f64 {
        self.density
    }

    /// chi_ij.
    pub fn contact_value(&self, i: usize, j: usize) -> f64 {
        self.contact[i][j]
    }

    /// nu_ij: collisions per unit time of one i particle with j particles, for Maxwellians
    /// at the species temperatures `temperatures`.
    pub fn pair_frequency(&self, i: usize, j: usize, temperatures: &[f64]) -> f64 {
        let a = |k: usize| temperatures[k] / self.masses[k];
        let sigma = 0.5 * (self.diameters[i] + self.diameters[j]);
        self.contact[i][j]
            * self.fractions[j]
            * self.density
            * sigma.powi(D as i32 - 1)
            * sphere_surface::<D>()
            * ((a(i) + a(j)) / (2.0 * PI)).sqrt()
    }

    /// Each species' collision frequency nu_i = sum_j nu_ij.
    pub fn collision_frequencies(&self, temperatures: &[f64]) -> Vec<f64> {
        let s = self.species();
        (0..s)
            .map(|i| {
                (0..s)
                    .map(|j| self.pair_frequency(i, j, temperatures))
                    .sum()
            })
            .collect()
    }

    /// Each species' cooling rate zeta_i (dT_i/dt = -zeta_i T_i by collisions), for
    /// Maxwellians at `temperatures`.
    pub fn cooling_rates(&self, temperatures: &[f64]) -> Vec<f64> {
        self.cooling_rates_with(temperatures, |i, j| {
            let one_plus = 1.0 + self.restitution[i][j];
            (one_plus, one_plus * one_plus)
        })
    }

    /// zeta_i = (2/D) sum_j nu_ij mu_ji [2 K1 - mu_ji K2 (1 + a_j / a_i)] with
    /// (K1, K2) = `factors(i, j)`, the pair's (1 + alpha) and (1 + alpha)^2 (averaged over
    /// the impact speeds for a speed-dependent restitution, [`Self::cooling_rates_for`]).
    fn cooling_rates_with(
        &self,
        temperatures: &[f64],
        factors: impl Fn(usize, usize) -> (f64, f64),
    ) -> Vec<f64> {
        let s = self.species();
        (0..s)
            .map(|i| {
                let a_i = temperatures[i] / self.masses[i];
                let sum: f64 = (0..s)
                    .map(|j| {
                        let a_j = temperatures[j] / self.masses[j];
                        let mu = self.masses[j] / (self.masses[i] + self.masses[j]);
                        let (k1, k2) = factors(i, j);
                        self.pair_frequency(i, j, temperatures)
                            * mu
                            * (2.0 * k1 - mu * k2 * (1.0 + a_j / a_i))
                    })
                    .sum();
                2.0 * sum / D as f64
            })
            .collect()
    }

    /// The homogeneous cooling state at mixture temperature `temperature` in the
    /// Maxwellian approximation: the ratios T_i / T at which all species cool at one rate
    /// (Newton's method on ln T_i, to 1e-13 in the rates over a collision frequency), that
    /// rate, and the collision frequencies.
    pub fn hcs(&self, temperature: f64) -> Result<MixtureHcs> {
        // Unknowns: ln T_i for i >= 1 with T_0 = 1; residuals (zeta_i - zeta_0) / nu_0
        // (zero rates in the elastic limit: not a ratio of rates).
        let residual = |y: &[f64]| -> Result<Vec<f64>> {
            let t = with_first(y);
            let z = self.cooling_rates(&t);
            let nu = self.collision_frequencies(&t)[0];
            Ok(z[1..].iter().map(|zi| (zi - z[0]) / nu).collect())
        };
        let y = newton(&mut vec![0.0; self.species() - 1], residual, 1e-13)?;
        let ratios = self.ratios(&with_first(&y));
        let at: Vec<f64> = ratios.iter().map(|r| r * temperature).collect();
        Ok(MixtureHcs {
            cooling_rate: self.cooling_rates(&at)[0],
            collision_frequencies: self.collision_frequencies(&at),
            a2: vec![0.0; self.species()],
            temperature_ratios: ratios,
        })
    }

    /// T_i / T for species temperatures `t` (T = sum x_i T_i).
    fn ratios(&self, t: &[f64]) -> Vec<f64> {
        let mean: f64 = t.iter().zip(&self.fractions).map(|(t, x)| t * x).sum();
        t.iter().map(|t| t / mean).collect()
    }
}

/// Temperatures 1, e^y_1, e^y_2, ...
fn with_first(y: &[f64]) -> Vec<f64> {
    std::iter::once(1.0)
        .chain(y.iter().map(|v| v.exp()))
        .collect()
}

/// Newton's method with a finite-difference Jacobian and backtracking from `y` to
/// |residual| < `tolerance`.
fn newton(
    y: &mut Vec<f64>,
    residual: impl Fn(&[f64]) -> Result<Vec<f64>>,
    tolerance: f64,
) -> Result<Vec<f64>> {
    let norm = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>().sqrt();
    let n = y.len();
    let mut r = residual(y)?;
    for _ in 0..100 {
        if norm(&r) < tolerance {
            break;
        }
        let h = 1e-7;
        let mut jacobian = vec![vec![0.0; n]; n];
        for k in 0..n {
            let mut shifted = y.clone();
            shifted[k] += h;
            let rk = residual(&shifted)?;
            for row in 0..n {
                jacobian[row][k] = (rk[row] - r[row]) / h;
            }
        }
        let step = solve(jacobian, r.iter().map(|v| -v).collect())
            .ok_or_else(|| Error::out_of_range("restitution", 0, "a mixture whose HCS exists"))?;
        // Backtracking: halve the step until the residual decreases.
        let mut scale = 1.0;
        loop {
            let trial: Vec<f64> = y.iter().zip(&step).map(|(a, b)| a + scale * b).collect();
            let rt = residual(&trial)?;
            if norm(&rt) < norm(&r) || scale < 1e-6 {
                *y = trial;
                r = rt;
                break;
            }
            scale *= 0.5;
        }
    }
    if norm(&r).is_nan() || norm(&r) >= 1e3 * tolerance {
        return Err(Error::out_of_range(
            "restitution",
            norm(&r),
            "a mixture whose HCS the solver finds",
        ));
    }
    Ok(y.clone())
}

/// x with A x = b; None if A is singular.
fn solve(a: Vec<Vec<f64>>, b: Vec<f64>) -> Option<Vec<f64>> {
    let x = super::sonine::solve(a, b);
    x.iter().all(|v| v.is_finite()).then_some(x)
}
