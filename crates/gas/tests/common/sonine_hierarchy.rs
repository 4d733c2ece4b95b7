//! The Sonine hierarchy of the homogeneous cooling state, computed here independently of
//! the engines and of `theory`. The scaled distribution F(c) = φ(c) [1 + Σ_{k=2..K} a_k
//! S_k(c²)] (φ = π^{-d/2} e^{-c²}, S_k the Sonine (Laguerre L_k^{(d/2-1)}) polynomials) is
//! stationary in the HCS exactly when μ_p = (p/d) μ_2 <c^p> for all p, where
//! μ_p = −∫ c^p I(F, F) dc is the collisional moment (Brilliantov & Pöschel, Kinetic
//! Theory of Granular Gases, Ch. 7; the overall collision constant cancels). The
//! truncation at order K keeps the equations p = 4, 6, …, 2K with all their terms
//! (quadratic in the a_k) and solves them by Newton's method. The collisional moments
//! A[p][j][l] = ∫∫∫ φ(c1) φ(c2) S_j(c1²) S_l(c2²) Θ(g·e) (g·e) Δ(c1^p + c2^p) are computed by
//! quadrature that is exact for their polynomial integrands: c1 = C + g/2, c2 = C − g/2,
//! e fixed along the last axis (isotropy), Gauss–Hermite in C (and in g_x in 2D), and
//! Gauss–Legendre on [0, 14] in g·e (and in |g_⊥| in 3D, by rotation about e) for the
//! weights g e^{-g²/2}, whose tail beyond 14 is e^{-98}.

use rayon::prelude::*;
use std::f64::consts::PI;

/// Gauss–Hermite nodes and weights for the weight e^{-x²} (Newton on the orthonormal
/// recurrence, as in Numerical Recipes' `gauher`).
fn gauss_hermite(n: usize) -> (Vec<f64>, Vec<f64>) {
    let (mut x, mut w) = (vec![0.0; n], vec![0.0; n]);
    let nf = n as f64;
    let mut z: f64 = 0.0;
    for i in 0..n.div_ceil(2) {
        z = match i {
            0 => (2.0 * nf + 1.0).sqrt() - 1.85575 * (2.0 * nf + 1.0).powf(-0.16667),
            1 => z - 1.14 * nf.powf(0.426) / z,
            2 => 1.86 * z - 0.86 * x[0],
            3 => 1.91 * z - 0.91 * x[1],
            _ => 2.0 * z - x[i - 2],
        };
        let mut pp = 0.0;
        for _ in 0..200 {
            let (mut p1, mut p2) = (PI.powf(-0.25), 0.0);
            for j in 0..n {
                let (p3, jf) = (p2, j as f64);
                p2 = p1;
                p1 = z * (2.0 / (jf + 1.0)).sqrt() * p2 - (jf / (jf + 1.0)).sqrt() * p3;
            }
            pp = (2.0 * nf).sqrt() * p2;
            let z1 = z;
            z = z1 - p1 / pp;
            if (z - z1).abs() <= 1e-15 * z1.abs().max(1.0) {
                break;
            }
        }
        (x[i], x[n - 1 - i]) = (z, -z);
        w[i] = 2.0 / (pp * pp);
        w[n - 1 - i] = w[i];
    }
    (x, w)
}

/// Gauss–Legendre nodes and weights on [a, b].
fn gauss_legendre(n: usize, a: f64, b: f64) -> (Vec<f64>, Vec<f64>) {
    let (mut x, mut w) = (vec![0.0; n], vec![0.0; n]);
    let (xm, xl, nf) = (0.5 * (b + a), 0.5 * (b - a), n as f64);
    for i in 0..n.div_ceil(2) {
        let mut z = (PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        let mut pp = 0.0;
        for _ in 0..200 {
            let (mut p1, mut p2) = (1.0, 0.0);
            for j in 0..n {
                let (p3, jf) = (p2, j as f64);
                p2 = p1;
                p1 = ((2.0 * jf + 1.0) * z * p2 - jf * p3) / (jf + 1.0);
            }
            pp = nf * (z * p1 - p2) / (z * z - 1.0);
            let z1 = z;
            z = z1 - p1 / pp;
            if (z - z1).abs() <= 1e-15 {
                break;
            }
        }
        (x[i], x[n - 1 - i]) = (xm - xl * z, xm + xl * z);
        w[i] = 2.0 * xl / ((1.0 - z * z) * pp * pp);
        w[n - 1 - i] = w[i];
    }
    (x, w)
}

/// S_0(x) … S_k(x) in d dimensions (three-term recurrence of L_j^{(d/2-1)}):
/// S_2(x) = x²/2 − (d+2)x/2 + d(d+2)/8.
fn sonine(d: usize, x: f64, out: &mut [f64]) {
    let a = d as f64 / 2.0 - 1.0;
    out[0] = 1.0;
    if out.len() > 1 {
        out[1] = 1.0 + a - x;
    }
    for j in 1..out.len() - 1 {
        let jf = j as f64;
        out[j + 1] = ((2.0 * jf + 1.0 + a - x) * out[j] - (jf + a) * out[j - 1]) / (jf + 1.0);
    }
}

/// The truncation at order K: collisional moments `mu[i][j][l]` for p = 2(i + 1) and
/// Maxwellian moments `moment[i][j]` = <c^p S_j(c²)>_φ.
pub struct Hierarchy {
    d: usize,
    k: usize,
    mu: Vec<Vec<Vec<f64>>>,
    moment: Vec<Vec<f64>>,
}

impl Hierarchy {
    /// Exact quadrature: the integrands are polynomials of degree ≤ 6K in C and g_⊥
    /// (S_j, S_l of degree 2K each, Δc^p of degree 2K), so 3K + 1 Gauss–Hermite
    /// nodes per axis; 48 Gauss–Legendre nodes on [0, 14] (a change to 64 nodes moves
    /// a2 by < 1e-12).
    pub fn new(d: usize, k: usize, alpha: f64) -> Self {
        assert!(d == 2 || d == 3);
        let (xh, wh) = gauss_hermite(3 * k + 1);
        let (xl, wl) = gauss_legendre(48, 0.0, 14.0);
        let s2 = 2f64.sqrt();
        // g samples (g_⊥, g_z) with weight g_z e^{-g²/2} (3D: |g_⊥| e^{-g_⊥²/2} too)
        let half_line: Vec<(f64, f64)> = xl
            .iter()
            .zip(&wl)
            .map(|(&x, &w)| (x, w * x * (-0.5 * x * x).exp()))
            .collect();
        let perp: Vec<(f64, f64)> = if d == 2 {
            xh.iter().zip(&wh).map(|(&x, &w)| (s2 * x, w)).collect()
        } else {
            half_line.clone()
        };
        let mut gs = vec![];
        for &(gp, wp) in &perp {
            for &(gz, wz) in &half_line {
                gs.push((gp, gz, wp * wz));
            }
        }
        // C samples with weight e^{-2C²}
        let n = xh.len();
        let cs: Vec<([f64; 3], f64)> = (0..n.pow(d as u32))
            .map(|flat| {
                let (mut c, mut w, mut f) = ([0.0; 3], 1.0, flat);
                for ci in c.iter_mut().take(d) {
                    *ci = xh[f % n] / s2;
                    w *= wh[f % n];
                    f /= n;
                }
                (c, w)
            })
            .collect();
        let zero = || vec![vec![vec![0.0; k + 1]; k + 1]; k];
        let mu = cs
            .par_iter()
            .fold(zero, |mut acc, &(c, wc)| {
                let (mut sj, mut sl) = (vec![0.0; k + 1], vec![0.0; k + 1]);
                for &(gp, gz, wg) in &gs {
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
                    let sq = |v: &[f64; 3]| v.iter().map(|x| x * x).sum::<f64>();
                    let (q1, q2) = (sq(&c1), sq(&c2));
                    let kick = 0.5 * (1.0 + alpha) * gz;
                    c1[d - 1] -= kick;
                    c2[d - 1] += kick;
                    let (r1, r2) = (sq(&c1), sq(&c2));
                    sonine(d, q1, &mut sj);
                    sonine(d, q2, &mut sl);
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
            .reduce(zero, |mut a, b| {
                for (pa, pb) in a.iter_mut().zip(&b) {
                    for (ra, rb) in pa.iter_mut().zip(pb) {
                        for (x, y) in ra.iter_mut().zip(rb) {
                            *x += y;
                        }
                    }
                }
                a
            });
        // <c^p S_j>_φ with the weight π^{-d/2} e^{-c²}
        let mut moment = vec![vec![0.0; k + 1]; k];
        let mut sj = vec![0.0; k + 1];
        for flat in 0..n.pow(d as u32) {
            let (mut w, mut q, mut f) = (1.0, 0.0, flat);
            for _ in 0..d {
                w *= wh[f % n] / PI.sqrt();
                q += xh[f % n] * xh[f % n];
                f /= n;
            }
            sonine(d, q, &mut sj);
            let mut power = 1.0;
            for row in moment.iter_mut() {
                power *= q;
                for (x, s) in row.iter_mut().zip(&sj) {
                    *x += w * power * s;
                }
            }
        }
        Hierarchy { d, k, mu, moment }
    }

    /// μ_p(a)/const − (p/d) μ_2(a)/const <c^p>(a) for p = 4 … 2K, a = (a_2 … a_K).
    fn residual(&self, a: &[f64]) -> Vec<f64> {
        let mut full = vec![0.0; self.k + 1];
        full[0] = 1.0;
        full[2..].copy_from_slice(a);
        let mu = |i: usize| {
            let mut s = 0.0;
            for j in 0..=self.k {
                for l in 0..=self.k {
                    s += full[j] * full[l] * self.mu[i][j][l];
                }
            }
            s
        };
        let moment = |i: usize| {
            (0..=self.k)
                .map(|j| full[j] * self.moment[i][j])
                .sum::<f64>()
        };
        (1..self.k)
            .map(|i| mu(i) - 2.0 * (i + 1) as f64 / self.d as f64 * mu(0) * moment(i))
            .collect()
    }

    /// The a2 of the truncation at order K (all terms kept), by Newton from a = 0.
    pub fn a2(&self) -> f64 {
        let n = self.k - 1;
        let mut a = vec![0.0; n];
        for _ in 0..100 {
            let r = self.residual(&a);
            let mut m: Vec<Vec<f64>> = vec![vec![0.0; n + 1]; n];
            for c in 0..n {
                let mut b = a.clone();
                b[c] += 1e-7;
                for (i, rb) in self.residual(&b).iter().enumerate() {
                    m[i][c] = (rb - r[i]) / 1e-7;
                }
            }
            for i in 0..n {
                m[i][n] = -r[i];
            }
            for col in 0..n {
                let pivot = (col..n)
                    .max_by(|&x, &y| m[x][col].abs().total_cmp(&m[y][col].abs()))
                    .unwrap();
                m.swap(col, pivot);
                let (top, below) = m.split_at_mut(col + 1);
                let pivot_row = &top[col];
                for row in below.iter_mut() {
                    let f = row[col] / pivot_row[col];
                    for (x, p) in row[col..=n].iter_mut().zip(&pivot_row[col..=n]) {
                        *x -= f * p;
                    }
                }
            }
            let mut step = vec![0.0; n];
            for row in (0..n).rev() {
                let s: f64 = (row + 1..n).map(|cc| m[row][cc] * step[cc]).sum();
                step[row] = (m[row][n] - s) / m[row][row];
            }
            a.iter_mut().zip(&step).for_each(|(x, dx)| *x += dx);
            if step.iter().all(|dx| dx.abs() < 1e-14) {
                break;
            }
        }
        a[0]
    }

    /// a2 of the K = 2 equation linearized in a2 (the approximation of van Noije &
    /// Ernst 1998).
    pub fn linear_a2(&self) -> f64 {
        let (mu2, mu4) = (&self.mu[0], &self.mu[1]);
        let (m40, m42) = (self.moment[1][0], self.moment[1][2]);
        let c = 4.0 / self.d as f64;
        let f0 = mu4[0][0] - c * mu2[0][0] * m40;
        let f1 = mu4[0][2] + mu4[2][0] - c * ((mu2[0][2] + mu2[2][0]) * m40 + mu2[0][0] * m42);
        -f0 / f1
    }
}
