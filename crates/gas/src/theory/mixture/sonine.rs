//! The first Sonine correction to the HCS of a mixture: each species' velocity
//! distribution a Maxwellian at T_i times 1 + a2_i S2(m_i c^2 / (2 T_i)), with
//! S2(y) = y^2/2 - (D + 2) y/2 + D (D + 2)/8, the collision integrals linear in the a2_i
//! (Garzó & Dufty 1999 take the same approximation; this is an independent computation).
//!
//! The equations, per species i: the cooling rates are equal, zeta_i = zeta, and the fourth
//! moment decays as T^2 does, d<c^4>_i/dt = -2 zeta <c^4>_i, with <c^4>_i = D (D + 2)
//! (T_i/m_i)^2 (1 + a2_i); products of a2's are dropped (the linearization of van Noije &
//! Ernst, whose one-species a2 this reproduces). For given temperatures the a2_i solve a
//! linear system; Newton's method on ln T_i equalizes the rates.
//!
//! The collision integrals are Gaussian averages of polynomials, computed exactly by Gauss
//! quadrature ([`super::super::gauss`]): with a_i = T_i/m_i and A = a_i + a_j, the
//! velocities are v_1 = w + (a_i/A) g and v_2 = w - (a_j/A) g, where g ~ N(0, A) and
//! w ~ N(0, a_i a_j / A) are independent; by isotropy the impact direction is fixed
//! (e = the first axis, times the surface S_D), and the average over g.e > 0 with the
//! weight g.e splits into an even part (Gauss–Laguerre in (g.e)^2 / 2A) and an odd part
//! (half of a Gauss–Hermite average).

use super::{MixtureHcs, MixtureTheory};
use crate::error::{Error, Result};
use crate::theory::gauss::{hermite_rule, laguerre_rule, Rule};
use crate::theory::sphere_surface;
use std::f64::consts::PI;

/// Points per dimension: exact for the degree-8 polynomials of the fourth moment with a
/// Sonine weight (Gauss rules of n points are exact to degree 2n - 1).
const POINTS: usize = 6;

/// The collision integrals of an i particle with j particles, per i particle and unit time:
/// the collision rate (psi = 1), the rate of change of m_i v^2 and of v^4, each as
/// [Maxwellian part, coefficient of a2_i, coefficient of a2_j].
#[derive(Debug, Clone, Copy, Default)]
struct PairIntegrals {
    rate: [f64; 3],
    energy: [f64; 3],
    fourth: [f64; 3],
}

/// The Gauss–Hermite and Gauss–Laguerre rules of [`POINTS`] points, found once (their roots
/// are bracketed on a fine grid: not work for every pair of every Newton step).
fn rules() -> &'static (Rule, Rule) {
    static RULES: std::sync::OnceLock<(Rule, Rule)> = std::sync::OnceLock::new();
    RULES.get_or_init(|| (hermite_rule(POINTS), laguerre_rule(POINTS)))
}

/// The Sonine polynomial S2(y) in D dimensions.
fn s2(y: f64, d: f64) -> f64 {
    0.5 * y * y - 0.5 * (d + 2.0) * y + d * (d + 2.0) / 8.0
}

impl<const D: usize> MixtureTheory<D> {
    fn pair_integrals(&self, i: usize, j: usize, temperatures: &[f64]) -> PairIntegrals {
        let d = D as f64;
        let (a_i, a_j) = (
            temperatures[i] / self.masses[i],
            temperatures[j] / self.masses[j],
        );
        let big = a_i + a_j;
        let (p, q) = (a_i / big, a_j / big);
        let mu = self.masses[j] / (self.masses[i] + self.masses[j]);
        let k = mu * (1.0 + self.restitution[i][j]);
        let (hermite, laguerre) = rules();
        // Points and weights of N(0, var) averages.
        let gaussian = |var: f64| -> Vec<(f64, f64)> {
            hermite
                .nodes
                .iter()
                .zip(&hermite.weights)
                .map(|(x, w)| ((2.0 * var).sqrt() * x, w / PI.sqrt()))
                .collect()
        };
        let w_points = gaussian(a_i * a_j / big);
        let g_points = gaussian(big);
        // E[Theta(x) x h(x)] for x ~ N(0, A) as sum c h(x) over these (x, c).
        let norm = big / (2.0 * PI * big).sqrt();
        let mut half_line = Vec::with_capacity(4 * POINTS);
        for (u, w) in laguerre.nodes.iter().zip(&laguerre.weights) {
            let r = (2.0 * big * u).sqrt();
            half_line.push((r, 0.5 * norm * w));
            half_line.push((-r, 0.5 * norm * w));
        }
        for (x, w) in hermite.nodes.iter().zip(&hermite.weights) {
            let t = (2.0 * big).sqrt() * x;
            half_line.push((t, 0.5 * norm * w * x));
            half_line.push((-t, -0.5 * norm * w * x));
        }
        // The 2D - 1 Gaussian coordinates: w (D components), then g's transverse ones.
        let dims = 2 * D - 1;
        let combos = POINTS.pow(dims as u32);
        let mut out = PairIntegrals::default();
        let m_i = self.masses[i];
        for combo in 0..combos {
            let mut index = combo;
            let mut weight = 1.0;
            let mut w = [0.0; D];
            let mut g = [0.0; D];
            for c in 0..dims {
                let (point, wt) = if c < D {
                    w_points[index % POINTS]
                } else {
                    g_points[index % POINTS]
                };
                index /= POINTS;
                weight *= wt;
                if c < D {
                    w[c] = point;
                } else {
                    g[c - D + 1] = point;
                }
            }
            for &(x, c) in &half_line {
                g[0] = x;
                let v1: [f64; D] = std::array::from_fn(|n| w[n] + p * g[n]);
                let v2: [f64; D] = std::array::from_fn(|n| w[n] - q * g[n]);
                let v1sq: f64 = v1.iter().map(|v| v * v).sum();
                let v2sq: f64 = v2.iter().map(|v| v * v).sum();
                let change = -2.0 * k * x * v1[0] + k * k * x * x;
                let fourth = 2.0 * v1sq * change + change * change;
                let weights = [1.0, s2(v1sq / (2.0 * a_i), d), s2(v2sq / (2.0 * a_j), d)];
                let f = weight * c;
                for (n, sw) in weights.iter().enumerate() {
                    out.rate[n] += f * sw;
                    out.energy[n] += f * sw * m_i * change;
                    out.fourth[n] += f * sw * fourth;
                }
            }
        }
        let sigma = 0.5 * (self.diameters[i] + self.diameters[j]);
        let prefactor = self.contact[i][j]
            * self.fractions[j]
            * self.density
            * sigma.powi(D as i32 - 1)
            * sphere_surface::<D>();
        for part in [&mut out.rate, &mut out.energy, &mut out.fourth] {
            part.iter_mut().for_each(|v| *v *= prefactor);
        }
        out
    }

    /// For the species temperatures `temperatures`: the Sonine coefficients a2_i of the
    /// linearized fourth-moment equations, and with them each species' cooling rate and
    /// collision frequency. Cooling (`noise` None): d<c^4>_i/dt = -2 zeta_i <c^4>_i.
    /// White noise of strength xi_i^2 (`noise`: velocity variance per component and unit
    /// time): the steady d<v^4>_i/dt = L_i + 2 D (D + 2) xi_i^2 a_i = 0, the kicks adding
    /// 2 (D + 2) xi^2 <v^2> to the fourth moment (Itô).
    fn sonine_state(
        &self,
        temperatures: &[f64],
        noise: Option<&[f64]>,
    ) -> Result<(Vec<f64>, Vec<f64>, Vec<f64>)> {
        let s = self.species();
        let d = D as f64;
        // zeta_i = zeta0_i + sum_k Z_ik a2_k; L_i = l0_i + sum_k Lambda_ik a2_k (d<v^4>/dt);
        // nu_i = nu0_i + sum_k N_ik a2_k.
        let mut zeta0 = vec![0.0; s];
        let mut big_z = vec![vec![0.0; s]; s];
        let mut l0 = vec![0.0; s];
        let mut big_l = vec![vec![0.0; s]; s];
        let mut nu0 = vec![0.0; s];
        let mut big_n = vec![vec![0.0; s]; s];
        for i in 0..s {
            let scale = -1.0 / (d * temperatures[i]);
            for j in 0..s {
                let p = self.pair_integrals(i, j, temperatures);
                zeta0[i] += scale * p.energy[0];
                big_z[i][i] += scale * p.energy[1];
                big_z[i][j] += scale * p.energy[2];
                l0[i] += p.fourth[0];
                big_l[i][i] += p.fourth[1];
                big_l[i][j] += p.fourth[2];
                nu0[i] += p.rate[0];
                big_n[i][i] += p.rate[1];
                big_n[i][j] += p.rate[2];
            }
        }
        // l0_i + Lambda_i.a2 + M_i (zeta0_i + Z_i.a2 + zeta0_i a2_i) = 0, with
        // M_i = 2 D (D + 2) a_i^2.
        let mut matrix = vec![vec![0.0; s]; s];
        let mut rhs = vec![0.0; s];
        for i in 0..s {
            let a = temperatures[i] / self.masses[i];
            match noise {
                None => {
                    let m = 2.0 * d * (d + 2.0) * a * a;
                    for k in 0..s {
                        matrix[i][k] = big_l[i][k] + m * big_z[i][k];
                    }
                    matrix[i][i] += m * zeta0[i];
                    rhs[i] = -(l0[i] + m * zeta0[i]);
                }
                Some(xi2) => {
                    matrix[i].clone_from(&big_l[i]);
                    rhs[i] = -(l0[i] + 2.0 * d * (d + 2.0) * xi2[i] * a);
                }
            }
        }
        let a2 = super::solve(matrix, rhs)
            .ok_or_else(|| Error::out_of_range("restitution", 0, "a mixture whose HCS exists"))?;
        let linear = |base: &[f64], slope: &[Vec<f64>]| -> Vec<f64> {
            (0..s)
                .map(|i| base[i] + (0..s).map(|k| slope[i][k] * a2[k]).sum::<f64>())
                .collect()
        };
        let zeta = linear(&zeta0, &big_z);
        let nu = linear(&nu0, &big_n);
        Ok((a2, zeta, nu))
    }

    /// The homogeneous cooling state in the first Sonine approximation at mixture
    /// temperature `temperature`: the ratios T_i / T at which all species cool at one rate,
    /// each species' a2, that rate and the collision frequencies (Newton's method on
    /// ln T_i, to 1e-12 in the rates over a collision frequency).
    pub fn hcs_sonine(&self, temperature: f64) -> Result<MixtureHcs> {
        let s = self.species();
        let residual = |y: &[f64]| -> Result<Vec<f64>> {
            let (_, zeta, nu) = self.sonine_state(&super::with_first(y), None)?;
            Ok(zeta[1..].iter().map(|z| (z - zeta[0]) / nu[0]).collect())
        };
        // Start from the Maxwellian ratios.
        let start = self.hcs(1.0)?.temperature_ratios;
        let mut y: Vec<f64> = start[1..].iter().map(|r| (r / start[0]).ln()).collect();
        let y = super::newton(&mut y, residual, 1e-12)?;
        let ratios = self.ratios(&super::with_first(&y));
        let at: Vec<f64> = ratios.iter().map(|r| r * temperature).collect();
        let (a2, zeta, nu) = self.sonine_state(&at, None)?;
        debug_assert_eq!(a2.len(), s);
        Ok(MixtureHcs {
            temperature_ratios: ratios,
            cooling_rate: zeta[0],
            collision_frequencies: nu,
            a2,
        })
    }

    /// The steady state of the mixture driven by white noise of strength `noise[i]` for
    /// species i (velocity variance per component and unit time; the same for all species
    /// for a random acceleration), in the first Sonine approximation (`sonine`) or the
    /// Maxwellian one: each species' heating m_i xi_i^2 balances its collisional cooling,
    /// zeta_i T_i = m_i xi_i^2 (Newton's method on ln T_i, to 1e-12 relative). Returns
    /// the temperatures, a2's, rates and frequencies ([`DrivenState`]).
    pub fn white_noise(&self, noise: &[f64], sonine: bool) -> Result<DrivenState> {
        let s = self.species();
        if noise.len() != s || noise.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
            return Err(Error::out_of_range(
                "strength",
                format!("{noise:?}"),
                "one finite strength > 0 per species",
            ));
        }
        let state = |t: &[f64]| -> Result<(Vec<f64>, Vec<f64>, Vec<f64>)> {
            if sonine {
                self.sonine_state(t, Some(noise))
            } else {
                Ok((
                    vec![0.0; s],
                    self.cooling_rates(t),
                    self.collision_frequencies(t),
                ))
            }
        };
        let residual = |y: &[f64]| -> Result<Vec<f64>> {
            let t: Vec<f64> = y.iter().map(|v| v.exp()).collect();
            let (_, zeta, _) = state(&t)?;
            Ok((0..s)
                .map(|i| zeta[i] * t[i] / (self.masses[i] * noise[i]) - 1.0)
                .collect())
        };
        // Start from the Maxwellian balance of one species at its own noise: zeta ~ T^(1/2).
        let unit = self.cooling_rates(&vec![1.0; s]);
        let mut y: Vec<f64> = (0..s)
            .map(|i| (2.0 / 3.0) * (self.masses[i] * noise[i] / unit[i].max(1e-300)).ln())
            .collect();
        let y = super::newton(&mut y, residual, 1e-12)?;
        let t: Vec<f64> = y.iter().map(|v| v.exp()).collect();
        let (a2, zeta, nu) = state(&t)?;
        Ok(DrivenState {
            temperatures: t,
            a2,
            cooling_rates: zeta,
            collision_frequencies: nu,
        })
    }
}

/// The steady state of a driven mixture: each species' temperature, a2, collisional
/// cooling rate and collision frequency.
#[derive(Debug, Clone, PartialEq)]
pub struct DrivenState {
    pub temperatures: Vec<f64>,
    pub a2: Vec<f64>,
    pub cooling_rates: Vec<f64>,
    pub collision_frequencies: Vec<f64>,
}
