//! The Sonine hierarchy of the homogeneous cooling state (HCS) of smooth inelastic hard
//! spheres (D = 3) and disks (D = 2) with a constant coefficient of restitution eps.
//!
//! The scaled velocity distribution F(c) = φ(c) [1 + Σ_{k=2..K} a_k S_k(c²)]
//! (φ = π^{-D/2} e^{-c²}; S_k the Sonine polynomials, i.e. the Laguerre polynomials
//! L_k^{(D/2-1)}, S_2(x) = x²/2 − (D+2)x/2 + D(D+2)/8) is stationary in the HCS exactly when
//!
//!   μ_p = (p / D) μ_2 <c^p>   for all p,   μ_p = −∫ c^p I(F, F) dc
//!
//! (Brilliantov & Pöschel, *Kinetic Theory of Granular Gases*, Oxford 2004, Ch. 7; the overall
//! collision constant cancels). The truncation at order K keeps the equations p = 4, 6, …, 2K.
//! With K = 2, linearized in a2, it is the first Sonine approximation of van Noije & Ernst
//! (1998, [`super::van_noije_ernst_a2`]); with K = 3, linearized in a2 and a3, the second
//! Sonine approximation (Brilliantov & Pöschel, EPL 74, 424 (2006); Santos & Montanero,
//! Granular Matter 11, 157 (2009)); with all quadratic terms kept and K growing, the
//! truncations converge at moderate dissipation to the exact a2 of the Enskog–Boltzmann HCS
//! (which homogeneous DSMC samples) and oscillate below eps ≈ 0.6 (the breakdown of the
//! Sonine expansion, Brilliantov & Pöschel 2006).
//!
//! The collisional moments A[p][j][l] = ∫∫∫ φ(c1) φ(c2) S_j(c1²) S_l(c2²) Θ(g·e) (g·e)
//! Δ(c1^p + c2^p) are computed here by a quadrature that is exact for their polynomial
//! integrands, not from closed forms: c1 = C + g/2, c2 = C − g/2 (so φ1 φ2 ∝ e^{-2C²−g²/2}), e
//! fixed along the last axis (isotropy), Gauss–Hermite in C (and in g_x in 2D), and
//! Gauss–Legendre on [0, 14] in g·e (and in |g_⊥| in 3D, by rotation about e) for the weights
//! g e^{-g²/2}, whose tail beyond 14 is e^{-98}.

use gauss_quad::{hermite::GaussHermite, legendre::GaussLegendre};
use rayon::prelude::*;
use std::f64::consts::PI;
use std::num::NonZeroUsize;

/// Gauss–Legendre nodes in g·e (and |g_⊥|): 48 on [0, 14]; 64 move a2 by < 1e-12.
const LEGENDRE_NODES: usize = 48;
const G_MAX: f64 = 14.0;

/// S_0(x) … S_k(x) in D dimensions, by the three-term recurrence of L_j^{(D/2-1)}.
fn sonine_polynomials(dimension: usize, x: f64, out: &mut [f64]) {
    let a = dimension as f64 / 2.0 - 1.0;
    out[0] = 1.0;
    if out.len() > 1 {
        out[1] = 1.0 + a - x;
    }
    for j in 1..out.len() - 1 {
        let jf = j as f64;
        out[j + 1] = ((2.0 * jf + 1.0 + a - x) * out[j] - (jf + a) * out[j - 1]) / (jf + 1.0);
    }
}

/// The truncation of the HCS hierarchy at order K for one restitution.
#[derive(Debug, Clone)]
pub struct SonineHierarchy {
    dimension: usize,
    order: usize,
    /// `collisional[i][j][l]` = A[p][j][l] for p = 2(i + 1).
    collisional: Vec<Vec<Vec<f64>>>,
    /// `maxwellian[i][j]` = <c^p S_j(c²)>_φ for p = 2(i + 1).
    maxwellian: Vec<Vec<f64>>,
}

impl SonineHierarchy {
    /// The moments of the truncation at `order` K ≥ 2 in `dimension` 2 or 3 for the
    /// restitution `eps` in [0, 1]. The integrands are polynomials of degree ≤ 6K in C and
    /// g_⊥ (S_j, S_l of degree 2K each, Δc^p of degree 2K), so 3K + 1 Gauss–Hermite nodes per
    /// axis integrate them exactly.
    pub fn new(dimension: usize, order: usize, eps: f64) -> crate::Result<Self> {
        if !(2..=3).contains(&dimension) {
            return Err(crate::Error::out_of_range("dimension", dimension, "2, 3"));
        }
        if !(2..=12).contains(&order) {
            return Err(crate::Error::out_of_range(
                "Sonine order",
                order,
                "2 ..= 12",
            ));
        }
        if !(0.0..=1.0).contains(&eps) {
            return Err(crate::Error::out_of_range("eps", eps, "[0, 1]"));
        }
        let (d, k) = (dimension, order);
        let hermite_nodes = NonZeroUsize::new(3 * k + 1).expect("3K + 1 > 0");
        let hermite = GaussHermite::new(hermite_nodes);
        let hermite = hermite.as_node_weight_pairs();
        let legendre = GaussLegendre::new(NonZeroUsize::new(LEGENDRE_NODES).expect("> 0"));
        let half = 0.5 * G_MAX;
        // g samples along a half-line with the weight g e^{-g²/2}
        let half_line: Vec<(f64, f64)> = legendre
            .as_node_weight_pairs()
            .iter()
            .map(|&(x, w)| {
                let g = half * (x + 1.0);
                (g, half * w * g * (-0.5 * g * g).exp())
            })
            .collect();
        let s2 = 2f64.sqrt();
        // g_⊥: a whole line with weight e^{-g²/2} in 2D, a radius in 3D
        let perpendicular: Vec<(f64, f64)> = if d == 2 {
            hermite.iter().map(|&(x, w)| (s2 * x, w)).collect()
        } else {
            half_line.clone()
        };
        let relative: Vec<(f64, f64, f64)> = perpendicular
            .iter()
            .flat_map(|&(gp, wp)| half_line.iter().map(move |&(gz, wz)| (gp, gz, wp * wz)))
            .collect();
        // centre-of-mass samples C with the weight e^{-2C²}
        let n = hermite.len();
        let centres: Vec<([f64; 3], f64)> = (0..n.pow(d as u32))
            .map(|flat| {
                let (mut c, mut w, mut f) = ([0.0; 3], 1.0, flat);
                for ci in c.iter_mut().take(d) {
                    let (x, wx) = hermite[f % n];
                    *ci = x / s2;
                    w *= wx;
                    f /= n;
                }
                (c, w)
            })
            .collect();
        let zero = || vec![vec![vec![0.0; k + 1]; k + 1]; k];
        // Fixed chunks summed in order: the result does not depend on how rayon splits
        // the work (a fold/reduce would group the sums differently from run to run).
        let partial: Vec<_> = centres
            .par_chunks(16)
            .map(|chunk| {
                chunk.iter().fold(zero(), |mut acc, &(c, wc)| {
                    let (mut sj, mut sl) = (vec![0.0; k + 1], vec![0.0; k + 1]);
                    for &(gp, gz, wg) in &relative {
                        let w = wc * wg;
                        // g = (g_⊥, 0, g_z) in 3D, (g_⊥, g_z) in 2D; e along the last axis
                        let mut g = [0.0; 3];
                        g[0] = gp;
                        g[d - 1] = gz;
                        let (mut c1, mut c2) = ([0.0; 3], [0.0; 3]);
                        for i in 0..d {
                            c1[i] = c[i] + 0.5 * g[i];
                            c2[i] = c[i] - 0.5 * g[i];
                        }
                        let square = |v: &[f64; 3]| v.iter().map(|x| x * x).sum::<f64>();
                        let (q1, q2) = (square(&c1), square(&c2));
                        let kick = 0.5 * (1.0 + eps) * gz;
                        c1[d - 1] -= kick;
                        c2[d - 1] += kick;
                        let (r1, r2) = (square(&c1), square(&c2));
                        sonine_polynomials(d, q1, &mut sj);
                        sonine_polynomials(d, q2, &mut sl);
                        let (mut pr1, mut pr2, mut pq1, mut pq2) = (1.0, 1.0, 1.0, 1.0);
                        for acc_p in acc.iter_mut() {
                            pr1 *= r1;
                            pr2 *= r2;
                            pq1 *= q1;
                            pq2 *= q2;
                            let delta = w * (pr1 + pr2 - pq1 - pq2);
                            for (j, row) in acc_p.iter_mut().enumerate() {
                                let dj = delta * sj[j];
                                for (l, x) in row.iter_mut().enumerate() {
                                    *x += dj * sl[l];
                                }
                            }
                        }
                    }
                    acc
                })
            })
            .collect();
        let collisional = partial.into_iter().fold(zero(), |mut a, b| {
            for (pa, pb) in a.iter_mut().zip(&b) {
                for (ra, rb) in pa.iter_mut().zip(pb) {
                    for (x, y) in ra.iter_mut().zip(rb) {
                        *x += y;
                    }
                }
            }
            a
        });
        // <c^p S_j>_φ with the weight π^{-D/2} e^{-c²}
        let mut maxwellian = vec![vec![0.0; k + 1]; k];
        let mut sj = vec![0.0; k + 1];
        for flat in 0..n.pow(d as u32) {
            let (mut w, mut q, mut f) = (1.0, 0.0, flat);
            for _ in 0..d {
                let (x, wx) = hermite[f % n];
                w *= wx / PI.sqrt();
                q += x * x;
                f /= n;
            }
            sonine_polynomials(d, q, &mut sj);
            let mut power = 1.0;
            for row in maxwellian.iter_mut() {
                power *= q;
                for (x, s) in row.iter_mut().zip(&sj) {
                    *x += w * power * s;
                }
            }
        }
        Ok(SonineHierarchy {
            dimension,
            order,
            collisional,
            maxwellian,
        })
    }

    /// The relative change of μ_2 (the cooling rate) per unit a_k, to first order:
    /// ∂ ln μ_2 / ∂a_k at a = 0 (3/16 for k = 2, 1/64 for k = 3, in 2D and 3D).
    pub fn cooling_rate_coefficient(&self, k: usize) -> f64 {
        let mu2 = &self.collisional[0];
        (mu2[k][0] + mu2[0][k]) / mu2[0][0]
    }

    /// μ_p − (p/D) μ_2 <c^p> for p = 4 … 2K at a = (a_2 … a_K), all terms kept.
    fn residual(&self, a: &[f64]) -> Vec<f64> {
        let mut full = vec![0.0; self.order + 1];
        full[0] = 1.0;
        full[2..].copy_from_slice(a);
        let mu = |i: usize| {
            let mut s = 0.0;
            for (j, row) in self.collisional[i].iter().enumerate() {
                for (l, x) in row.iter().enumerate() {
                    s += full[j] * full[l] * x;
                }
            }
            s
        };
        let moment = |i: usize| -> f64 {
            full.iter()
                .zip(&self.maxwellian[i])
                .map(|(a, m)| a * m)
                .sum()
        };
        (1..self.order)
            .map(|i| mu(i) - 2.0 * (i + 1) as f64 / self.dimension as f64 * mu(0) * moment(i))
            .collect()
    }

    /// The Jacobian of [`Self::residual`] at a = 0, exactly (the residual is quadratic).
    fn jacobian_at_zero(&self) -> Vec<Vec<f64>> {
        let d = self.dimension as f64;
        let mu0 = &self.collisional[0];
        (1..self.order)
            .map(|i| {
                let c = 2.0 * (i + 1) as f64 / d;
                let mu = &self.collisional[i];
                (2..=self.order)
                    .map(|k| {
                        mu[k][0] + mu[0][k]
                            - c * ((mu0[k][0] + mu0[0][k]) * self.maxwellian[i][0]
                                + mu0[0][0] * self.maxwellian[i][k])
                    })
                    .collect()
            })
            .collect()
    }

    /// a_2 … a_K of the truncation linearized in the a_k: at K = 2 van Noije & Ernst's
    /// first Sonine approximation, at K = 3 the second Sonine approximation.
    pub fn linearized(&self) -> Vec<f64> {
        let zero = vec![0.0; self.order - 1];
        let rhs: Vec<f64> = self.residual(&zero).iter().map(|r| -r).collect();
        solve(self.jacobian_at_zero(), rhs)
    }

    /// a_2 … a_K of the truncation with all its (quadratic) terms, by Newton's method from the
    /// linearized solution; `None` if Newton does not converge in 50 steps (possible where
    /// the Sonine expansion breaks down, eps ≲ 0.3).
    pub fn coefficients(&self) -> Option<Vec<f64>> {
        let n = self.order - 1;
        let mut a = self.linearized();
        for _ in 0..50 {
            let r = self.residual(&a);
            // the residual is quadratic: central differences give its Jacobian to round-off
            let h = 1e-4;
            let mut jacobian = vec![vec![0.0; n]; n];
            for col in 0..n {
                let (mut up, mut down) = (a.clone(), a.clone());
                up[col] += h;
                down[col] -= h;
                let (ru, rd) = (self.residual(&up), self.residual(&down));
                for row in 0..n {
                    jacobian[row][col] = (ru[row] - rd[row]) / (2.0 * h);
                }
            }
            let step = solve(jacobian, r.iter().map(|x| -x).collect());
            a.iter_mut().zip(&step).for_each(|(x, dx)| *x += dx);
            if step.iter().all(|dx| dx.is_finite() && dx.abs() < 1e-14) {
                return Some(a);
            }
            if step.iter().any(|dx| !dx.is_finite()) {
                return None;
            }
        }
        None
    }
}

/// Gaussian elimination with partial pivoting (small systems: at most 11 unknowns here, a
/// few per species in `mixture`); a singular system gives non-finite values.
pub(super) fn solve(mut m: Vec<Vec<f64>>, mut rhs: Vec<f64>) -> Vec<f64> {
    let n = rhs.len();
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&x, &y| m[x][col].abs().total_cmp(&m[y][col].abs()))
            .expect("non-empty");
        m.swap(col, pivot);
        rhs.swap(col, pivot);
        let (top, below) = m.split_at_mut(col + 1);
        let pivot_row = &top[col];
        for (row, r) in below.iter_mut().zip(col + 1..) {
            let f = row[col] / pivot_row[col];
            for (x, p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * p;
            }
            rhs[r] -= f * rhs[col];
        }
    }
    let mut x = vec![0.0; n];
    for row in (0..n).rev() {
        let s: f64 = (row + 1..n).map(|c| m[row][c] * x[c]).sum();
        x[row] = (rhs[row] - s) / m[row][row];
    }
    x
}

/// (a2, a3) of the HCS in the second Sonine approximation, linear in a2 and a3
/// (Brilliantov & Pöschel, EPL 74, 424 (2006); Santos & Montanero, Granular Matter 11, 157
/// (2009)), for D = 2, 3 and eps in [0, 1].
pub fn second_sonine<const D: usize>(eps: f64) -> crate::Result<(f64, f64)> {
    let a = SonineHierarchy::new(D, 3, eps)?.linearized();
    Ok((a[0], a[1]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::theory::van_noije_ernst_a2;

    /// Linearized at K = 2 the hierarchy is van Noije & Ernst's closed form: the quadrature
    /// and the algebra agree to round-off (the tolerance, 1e-11, is ~100x the measured
    /// difference).
    /// The quadrature sums in a fixed order: the same bits on 1, 2 or 3 threads (the second
    /// Sonine a2 at eps = 0.5 once changed in its last digits from run to run).
    #[test]
    fn the_same_bits_on_any_number_of_threads() {
        let on = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| second_sonine::<3>(0.5).unwrap())
        };
        let one = on(1);
        assert_eq!(one, on(2));
        assert_eq!(one, on(3));
    }

    #[test]
    fn first_order_is_van_noije_ernst() {
        for eps in [0.1, 0.3, 0.5, 0.7, 0.9, 0.99] {
            let two = SonineHierarchy::new(2, 2, eps).unwrap().linearized()[0];
            let three = SonineHierarchy::new(3, 2, eps).unwrap().linearized()[0];
            assert!((two - van_noije_ernst_a2::<2>(eps)).abs() < 1e-11, "{eps}");
            assert!(
                (three - van_noije_ernst_a2::<3>(eps)).abs() < 1e-11,
                "{eps}"
            );
        }
    }

    /// μ_2 ∝ (1 − eps²) <g³>_F: its a2 coefficient 3/16 (van Noije & Ernst 1998) and its a3
    /// coefficient, +1/64 for the Laguerre convention S_3 = −x³/6 + …, computed independently
    /// as 2 <S_k(c1²) |c1 − c2|³>_φφ / <|c1 − c2|³>_φφ by nested one-dimensional quadratures
    /// in mpmath (30 digits; the inner average over c2 in closed form by angle: sinh in 3D,
    /// I_0 in 2D): 0.1875 and 0.015625 in 2D and 3D.
    #[test]
    fn cooling_rate_coefficients() {
        for d in [2, 3] {
            for eps in [0.2, 0.8] {
                let h = SonineHierarchy::new(d, 3, eps).unwrap();
                assert!((h.cooling_rate_coefficient(2) - 3.0 / 16.0).abs() < 1e-12);
                assert!((h.cooling_rate_coefficient(3) - 1.0 / 64.0).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn elastic_gas_is_maxwellian() {
        for d in [2, 3] {
            for a in SonineHierarchy::new(d, 4, 1.0)
                .unwrap()
                .coefficients()
                .unwrap()
            {
                assert!(a.abs() < 1e-12, "{a}");
            }
        }
    }

    #[test]
    fn bad_arguments_are_errors() {
        assert!(SonineHierarchy::new(1, 3, 0.5).is_err());
        assert!(SonineHierarchy::new(3, 1, 0.5).is_err());
        assert!(SonineHierarchy::new(3, 3, 1.5).is_err());
        assert!(second_sonine::<3>(f64::NAN).is_err());
    }
}
