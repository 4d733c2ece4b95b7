//! The slow manifold of the overdamped collision, which ends a naive (overlap-vanishes)
//! collision at large v* in closed form.
//!
//! For A = v*^2 >~ 10 a collision of viscoelastic spheres, after maximal compression,
//! creeps apart on the slow manifold of Eq. (9) of MP2011, x'' + x^{3/2} + A x' sqrt(x) = 0:
//! the force nearly vanishes, x' ~ -x/A, and any other motion decays at the rate
//! A sqrt(x) >> 1/A. Integrating the creep down to x = 0 is stiff (the fast rate exceeds
//! the slow one by A^2 sqrt(x) = 1/y, y defined below) and long (tau ~ A ln(x A^4)). It is
//! not needed, for two exact reasons:
//!
//! 1. **Scale invariance.** With x = s X, tau = s^{-1/4} T the equation becomes the same
//!    equation with A' = A s^{1/4}. Taking s = A^{-4} maps every A onto A' = 1: the slow
//!    manifold for A is the image of the one for A = 1, its exit speed is P* A^{-5} and the
//!    time left from a point x on it is A F(x A^4), with one universal constant P* and one
//!    universal function F (the time left on the A = 1 manifold).
//! 2. **The manifold as a series.** Writing the manifold as x' = -(x/A) (1 + u(y)),
//!    y = 1/(A^2 sqrt(x)), the equation x' dx'/dx = -sqrt(x) (x + A x') gives
//!    `u = y (1 + u) (1 + u - (y/2) u')`, whose power series in y is found term by term
//!    below ([`Series`]). The time left follows as
//!    `F(X) = ln X + K + R(y)`, `R(y) = 2 int_0^y u / ((1 + u) y') dy'` (X = x A^4,
//!    dtau = dx/x' and dX/X = -2 dy/y), with a second universal constant K.
//!
//! The series are asymptotic (|u_k| grows like k! 0.4^k: u_40 = 1.2e26), so they are used
//! only for y <= [`Y_MAX`] = 0.05, where the first neglected term, |u_25| y^25 = 9e-24, and
//! the exponentially small ambiguity of a slow manifold, ~exp(-2.5/y) = 2e-22, are far
//! below round-off. The constants P* and K are measured once, at first use, by an
//! integration at v* = [`CALIBRATION_VSTAR`] without this shortcut
//! ([`crate::taylor::calibrate`]).

use std::sync::OnceLock;

/// Number of terms of the series kept.
pub(crate) const TERMS: usize = 24;

/// Largest y = 1/(A^2 sqrt(x)) at which the truncated series are used.
pub(crate) const Y_MAX: f64 = 0.05;

/// v* of the integration that measures P* and K: large enough that the trajectory joins the
/// manifold at y ~ 0.01, small enough that the creep to x = 0 is integrated explicitly in
/// a few tens of steps.
pub(crate) const CALIBRATION_VSTAR: f64 = 4.0;

/// Coefficients of u(y) = sum_k u_k y^k and R(y) = sum_k r_k y^k (index k).
#[derive(Debug)]
pub(crate) struct Series {
    pub u: [f64; TERMS + 1],
    pub r: [f64; TERMS + 1],
}

impl Series {
    /// From `u = y W Z` with W = 1 + u and Z = W - (y/2) u', i.e. Z_0 = 1,
    /// Z_k = (1 - k/2) u_k: `u_{k+1} = sum_{j=0}^{k} W_j Z_{k-j}` (u_0 = 0, u_1 = 1). Then
    /// V = 1/W (V_0 = 1, V_k = -sum_{j=1}^k u_j V_{k-j}), u/(1+u) = 1 - V and
    /// `r_k = -2 V_k / k` (k >= 1).
    fn new() -> Self {
        let mut u = [0.0; TERMS + 1];
        for k in 0..TERMS {
            let w = |j: usize| if j == 0 { 1.0 } else { u[j] };
            let z = |j: usize| {
                if j == 0 {
                    1.0
                } else {
                    (1.0 - 0.5 * j as f64) * u[j]
                }
            };
            u[k + 1] = (0..=k).map(|j| w(j) * z(k - j)).sum();
        }
        let mut v = [0.0; TERMS + 1];
        v[0] = 1.0;
        for k in 1..=TERMS {
            v[k] = -(1..=k).map(|j| u[j] * v[k - j]).sum::<f64>();
        }
        let mut r = [0.0; TERMS + 1];
        for k in 1..=TERMS {
            r[k] = -2.0 * v[k] / k as f64;
        }
        Series { u, r }
    }

    pub(crate) fn get() -> &'static Series {
        static SERIES: OnceLock<Series> = OnceLock::new();
        SERIES.get_or_init(Series::new)
    }
}

fn horner(c: &[f64], y: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &a| acc * y + a)
}

/// u(y): the manifold is x' = -(x/A) (1 + u(y)). For y <= [`Y_MAX`].
pub(crate) fn u(y: f64) -> f64 {
    horner(&Series::get().u, y)
}

/// R(y) = F(X) - ln X - K, the part of the time left that vanishes as y -> 0.
pub(crate) fn rest(y: f64) -> f64 {
    horner(&Series::get().r, y)
}

/// The universal constants of the A = 1 slow manifold.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Constants {
    /// P*: the naive eps is P* A^{-5} = P* v*^{-10} once the creep has begun.
    pub exit_speed: f64,
    /// K: the time left from x on the manifold is A (ln(x A^4) + K + R(y)).
    pub offset: f64,
}

/// P* and K, measured at first use (see the module documentation).
pub(crate) fn constants() -> Constants {
    static CONSTANTS: OnceLock<Constants> = OnceLock::new();
    *CONSTANTS.get_or_init(|| {
        crate::taylor::calibrate().expect("calibration of the slow manifold at v* = 4")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The recurrence reproduces the exact (dyadic) coefficients found with rational
    /// arithmetic from the same equation (u_1 .. u_16).
    #[test]
    fn manifold_series_coefficients() {
        let exact = [
            1.0,
            1.5,
            2.0,
            1.75,
            0.0,
            -2.375,
            -2.25,
            1.6875,
            5.1875,
            3.125,
            -6.5625,
            -13.234375,
            -4.15625,
            29.53125,
            18.046875,
            69.99609375,
        ];
        let s = Series::get();
        for (k, e) in exact.iter().enumerate() {
            assert_eq!(s.u[k + 1], *e, "u_{}", k + 1);
        }
    }

    /// u solves u = y (1 + u) (1 + u - (y/2) u') to round-off at y = Y_MAX, and R' = 2 u /
    /// ((1 + u) y).
    #[test]
    fn manifold_series_solve_their_equations() {
        let s = Series::get();
        let y = Y_MAX;
        let du: f64 = (1..=TERMS)
            .map(|k| k as f64 * s.u[k] * y.powi(k as i32 - 1))
            .sum();
        let uy = u(y);
        let residual = uy - y * (1.0 + uy) * (1.0 + uy - 0.5 * y * du);
        assert!(residual.abs() < 1e-16, "{residual:e}");
        let dr: f64 = (1..=TERMS)
            .map(|k| k as f64 * s.r[k] * y.powi(k as i32 - 1))
            .sum();
        let expected = 2.0 * uy / ((1.0 + uy) * y);
        assert!((dr - expected).abs() < 1e-15 * expected, "{dr} {expected}");
    }
}
