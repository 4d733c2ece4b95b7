//! The homogeneous cooling state (HCS) of rough spheres (3D) and disks (2D) in the **first
//! Sonine approximation, linear in the cumulants**: the step beyond the Maxwellian theory of
//! [`super::rough`], after Santos, Kremer & dos Santos, Phys. Fluids 23, 030604 (2011)
//! (arXiv:1009.6180) and, for disks and spheres together, Megías & Santos, arXiv:2303.00057
//! (2023). Derived here from scratch (the papers' equations were not at hand): the record
//! is `scripts/rough-sonine.py`, the oracles are Monte Carlo averages of the collision
//! rule (`monte_carlo` tests).
//!
//! **Trial distribution.** With c = v / sqrt(2 T_tr / m) and w = omega / sqrt(2 T_rot / I)
//! (I = q m sigma^2 / 4; d_t = d_r = 3 for spheres, d_t = 2 and d_r = 1 for disks),
//!
//! f = phi(c) phi(w) [1 + a20 S2(c^2) + a02 S2(w^2) + a11 S1(c^2) S1(w^2)],
//!
//! phi(x) = pi^{-d/2} e^{-x^2}, S1(x) = d/2 - x, S2(x) = x^2/2 - (d+2) x/2 + d (d+2)/8
//! (Laguerre polynomials L_k^{(d/2-1)}, d = d_t for c, d_r for w). The cumulants are the
//! fourth moments: <c^4> = d_t (d_t + 2)/4 (1 + a20), <w^4> = d_r (d_r + 2)/4 (1 + a02),
//! <c^2 w^2> = d_t d_r / 4 (1 + a11); theta = T_rot / T_tr.
//!
//! **Collisional moments.** For psi one of 1, c^2, w^2, c^4, w^4, c^2 w^2,
//! N[psi] = E[(g.n)^+ Delta(psi_1 + psi_2) W] / E[(g.n)^+]_Maxwell over pairs of
//! particles drawn from f and normal directions n (g = c1 - c2; N[1] with Delta psi
//! replaced by 2), W the pair's weight; linear in the cumulants:
//! N[psi] = N_0[psi] + a20 N_20[psi] + a02 N_02[psi] + a11 N_11[psi], each N_k a
//! polynomial in alpha, eta, q, theta and 1/theta (module `moments`). In units of the
//! Maxwellian collision frequency nu_M of one particle, N[1]/2 = 1 - a20/16 is the
//! collision frequency (van Noije & Ernst's factor, in 2D as in 3D), and the moments change
//! at the rates d<psi>/dt = N[psi] / 2 (each collision changes two particles).
//!
//! **HCS equations.** T_tr and T_rot decay at the rates zeta_tr = -N[c^2] / d_t and
//! zeta_rot = -N[w^2] / d_r; the scaled distribution is stationary when
//!
//! (E1) zeta_tr = zeta_rot,
//! (E2) N[c^4] = (d_t + 2) N[c^2] (1 + a20),
//! (E3) N[w^4] = (d_r + 2) N[w^2] (1 + a02),
//! (E4) N[c^2 w^2] / 2 = -(zeta_tr + zeta_rot) d_t d_r / 4 (1 + a11)
//!
//! (each fourth moment decays at twice the rate of its temperatures). The approximation
//! keeps the equations linear in the cumulants (products such as a20 N_20[c^2] dropped, as
//! van Noije & Ernst do for smooth spheres) and theta exact: at each theta, (E2)–(E4) are a
//! 3 x 3 linear system for (a20, a02, a11), and (E1) is one equation for theta, solved by
//! walking out from the Maxwellian ratio and bisecting ([`hcs`]). The cooling rate per
//! collision, -d ln T / d(collisions per particle), is zeta / (1 - a20/16).
//!
//! **Limits** (tests below). beta = -1 (eta = 0): the translational equations lose every
//! term in theta, a02 and a11, and (E2) alone is van Noije & Ernst's a2
//! ([`super::van_noije_ernst_a2`]) exactly; rotation is not touched (N[w^2] = N[w^4] = 0), so
//! theta has no equation ([`hcs`] gives None, as the Maxwellian theory does).
//! alpha = beta = 1: every Maxwellian moment vanishes at theta = 1, and the HCS is
//! equipartition with all cumulants 0 and no cooling.
//!
//! **Where the linear approximation fails.** The rotational equation (E3) has a restoring
//! coefficient of order (eta/q)^2 for small roughness, the order of its source terms; between
//! beta ≈ -0.95 and -0.55 (alpha from 0.4 to 0.95, q = 2/5) it crosses zero and a02 grows
//! without bound (no root connected with the Maxwellian ratio: [`hcs`] gives None). A
//! cumulant above about 1 marks values not to trust (docs/rough.md has the map and the
//! comparison with DSMC).

use super::rough::RoughMaxwellian;

mod moments;
#[cfg(test)]
mod monte_carlo;

/// The moments psi of [`CollisionalMoments`], in the order of its rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Moment {
    /// psi = 1: twice the collision frequency of one particle (in units of the
    /// Maxwellian's).
    Collisions = 0,
    /// c^2 (translational temperature).
    Translational = 1,
    /// w^2 (rotational temperature).
    Rotational = 2,
    /// c^4 (a20).
    TranslationalFourth = 3,
    /// w^4 (a02).
    RotationalFourth = 4,
    /// c^2 w^2 (a11).
    Mixed = 5,
}

/// The weights of the trial distribution, in the order of the columns of
/// [`CollisionalMoments`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Weight {
    Maxwellian = 0,
    A20 = 1,
    A02 = 2,
    A11 = 3,
}

/// The collisional moments N_k[psi] at one theta (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CollisionalMoments {
    /// `table[psi][k]`: rows in the order of [`Moment`], columns of [`Weight`].
    pub table: [[f64; 4]; 6],
}

impl CollisionalMoments {
    /// N[psi] = N_0 + a20 N_20 + a02 N_02 + a11 N_11 for cumulants (a20, a02, a11).
    pub fn value(&self, psi: Moment, cumulants: [f64; 3]) -> f64 {
        let row = &self.table[psi as usize];
        row[0] + row[1] * cumulants[0] + row[2] * cumulants[1] + row[3] * cumulants[2]
    }

    /// N_k[psi].
    pub fn get(&self, psi: Moment, weight: Weight) -> f64 {
        self.table[psi as usize][weight as usize]
    }
}

/// The homogeneous cooling state in the first Sonine approximation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughSonineHcs {
    /// theta = T_rot / T_tr.
    pub ratio: f64,
    /// The cumulant of the translational velocities (<c^4> = d_t (d_t+2)/4 (1 + a20)).
    pub a20: f64,
    /// The cumulant of the angular velocities.
    pub a02: f64,
    /// The correlation of |v|^2 and |omega|^2.
    pub a11: f64,
    /// zeta / nu_M: the cooling rate of both temperatures in units of the Maxwellian
    /// collision frequency of one particle at T_tr.
    pub cooling_rate: f64,
    /// nu / nu_M = 1 - a20 / 16.
    pub collision_frequency: f64,
    /// -d ln T / d(collisions per particle) = cooling_rate / collision_frequency.
    pub cooling_per_collision: f64,
}

impl RoughSonineHcs {
    /// max(|a20|, |a02|, |a11|): the linear approximation drops terms of this order
    /// relative to the ones kept; values above about 1 are not to be trusted.
    pub fn largest_cumulant(&self) -> f64 {
        self.a20.abs().max(self.a02.abs()).max(self.a11.abs())
    }
}

/// (d_t, d_r).
fn degrees(theory: &RoughMaxwellian) -> (f64, f64) {
    if theory.dimension == 2 {
        (2.0, 1.0)
    } else {
        (3.0, 3.0)
    }
}

/// The collisional moments of `theory`'s particles at theta = T_rot / T_tr > 0 (module
/// `moments`: closed forms in alpha, eta, eta / q and theta).
pub fn moments(theory: &RoughMaxwellian, theta: f64) -> CollisionalMoments {
    let eta = theory.eta();
    CollisionalMoments {
        table: moments::table(
            theory.dimension,
            theory.alpha,
            eta,
            eta / theory.inertia,
            theta,
        ),
    }
}

/// The linear system (E2)–(E4) for (a20, a02, a11) at fixed theta: rows of [A | b] with
/// A a = b, linear in the cumulants (module documentation).
fn cumulant_system(theory: &RoughMaxwellian, n: &CollisionalMoments) -> [[f64; 4]; 3] {
    use Moment::*;
    let (dt, dr) = degrees(theory);
    let columns = [Weight::A20, Weight::A02, Weight::A11];
    let zero = [0.0; 3];
    let mut rows = [[0.0; 4]; 3];
    // (E2): N[c^4] - (d_t + 2) (N[c^2] + a20 N_0[c^2]) = 0.
    // (E3): N[w^4] - (d_r + 2) (N[w^2] + a02 N_0[w^2]) = 0.
    // (E4): N[c^2 w^2] / 2 - (d_t d_r / 4) (Z + a11 Z_0) = 0, Z = N[c^2]/d_t + N[w^2]/d_r
    // = -(zeta_tr + zeta_rot).
    for (i, weight) in columns.iter().enumerate() {
        let own = |k: usize| if i == k { 1.0 } else { 0.0 };
        let z = n.get(Translational, *weight) / dt + n.get(Rotational, *weight) / dr;
        let z0 = n.value(Translational, zero) / dt + n.value(Rotational, zero) / dr;
        rows[0][i] = n.get(TranslationalFourth, *weight)
            - (dt + 2.0) * (n.get(Translational, *weight) + own(0) * n.value(Translational, zero));
        rows[1][i] = n.get(RotationalFourth, *weight)
            - (dr + 2.0) * (n.get(Rotational, *weight) + own(1) * n.value(Rotational, zero));
        rows[2][i] = 0.5 * n.get(Mixed, *weight) - 0.25 * dt * dr * (z + own(2) * z0);
    }
    let z0 = n.value(Translational, zero) / dt + n.value(Rotational, zero) / dr;
    rows[0][3] = -(n.value(TranslationalFourth, zero) - (dt + 2.0) * n.value(Translational, zero));
    rows[1][3] = -(n.value(RotationalFourth, zero) - (dr + 2.0) * n.value(Rotational, zero));
    rows[2][3] = -(0.5 * n.value(Mixed, zero) - 0.25 * dt * dr * z0);
    rows
}

/// det A and the solution of A a = b by Cramer's rule (3 x 3).
fn solve(rows: &[[f64; 4]; 3]) -> (f64, [f64; 3]) {
    let det3 = |c: [usize; 3]| {
        let m = |r: usize, k: usize| rows[r][c[k]];
        m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1))
            - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
            + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0))
    };
    let det = det3([0, 1, 2]);
    (
        det,
        [
            det3([3, 1, 2]) / det,
            det3([0, 3, 2]) / det,
            det3([0, 1, 3]) / det,
        ],
    )
}

/// The cumulants (a20, a02, a11) that make the fourth moments stationary at this theta
/// ((E2)–(E4)), and the determinant of their system.
pub fn cumulants_at(theory: &RoughMaxwellian, theta: f64) -> (f64, [f64; 3]) {
    solve(&cumulant_system(theory, &moments(theory, theta)))
}

/// (E1)'s mismatch zeta_rot - zeta_tr at theta with the cumulants of [`cumulants_at`], and
/// the determinant.
fn mismatch(theory: &RoughMaxwellian, theta: f64) -> (f64, f64, [f64; 3]) {
    let (dt, dr) = degrees(theory);
    let n = moments(theory, theta);
    let (det, a) = solve(&cumulant_system(theory, &n));
    let gap = n.value(Moment::Translational, a) / dt - n.value(Moment::Rotational, a) / dr;
    (gap, det, a)
}

/// The state at the root theta of (E1).
fn state(theory: &RoughMaxwellian, theta: f64) -> RoughSonineHcs {
    let (dt, _) = degrees(theory);
    let n = moments(theory, theta);
    let (_, a) = cumulants_at(theory, theta);
    let cooling_rate = -n.value(Moment::Translational, a) / dt;
    let collision_frequency = 0.5 * n.value(Moment::Collisions, a);
    RoughSonineHcs {
        ratio: theta,
        a20: a[0],
        a02: a[1],
        a11: a[2],
        cooling_rate,
        collision_frequency,
        cooling_per_collision: cooling_rate / collision_frequency,
    }
}

/// Steps of the walk in ln theta, and how far it goes (a factor 1e4 either way).
const STEP: f64 = 0.01;
const STEPS: usize = 921;

/// The HCS in the first Sonine approximation: the root of (E1) nearest (in ln theta) to
/// the Maxwellian ratio among those reached without crossing a zero of the cumulants'
/// determinant (where a20, a02, a11 diverge). None for smooth particles (beta = -1: theta
/// has no equation) and where no such root exists (the linear approximation's breakdown;
/// module documentation).
pub fn hcs(theory: &RoughMaxwellian) -> Option<RoughSonineHcs> {
    let start = theory.hcs()?.ratio;
    let (gap0, det0, _) = mismatch(theory, start);
    if gap0 == 0.0 {
        return Some(state(theory, start));
    }
    if det0 == 0.0 || !gap0.is_finite() {
        return None;
    }
    // Both directions in turn, so that the nearer root is found first.
    let mut open = [true, true];
    let mut last = [(start.ln(), gap0); 2];
    for k in 1..=STEPS {
        for (side, sign) in [(0, 1.0), (1, -1.0)] {
            if !open[side] {
                continue;
            }
            let x = start.ln() + sign * STEP * k as f64;
            let (gap, det, _) = mismatch(theory, x.exp());
            if det.signum() != det0.signum() || !gap.is_finite() {
                open[side] = false;
                continue;
            }
            let (x0, g0) = last[side];
            if gap == 0.0 || gap.signum() != g0.signum() {
                return Some(state(theory, bisect(theory, x0, g0, x).exp()));
            }
            last[side] = (x, gap);
        }
        if open == [false, false] {
            return None;
        }
    }
    None
}

/// The root in ln theta of (E1)'s mismatch between x0 (mismatch g0) and x1, by bisection
/// to round-off.
fn bisect(theory: &RoughMaxwellian, mut x0: f64, g0: f64, mut x1: f64) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (x0 + x1);
        if mid == x0 || mid == x1 {
            break;
        }
        let (gap, _, _) = mismatch(theory, mid.exp());
        if gap == 0.0 {
            return mid;
        }
        if gap.signum() == g0.signum() {
            x0 = mid;
        } else {
            x1 = mid;
        }
    }
    0.5 * (x0 + x1)
}

#[cfg(test)]
mod tests;
