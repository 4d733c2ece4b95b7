//! Padé approximants [m/n] of the coefficient of restitution in v* (Eq. 11 of MP2011).
//!
//! [`Pade::computed`] builds any [m/n] from the h_k of the computer-algebra chain
//! (`haff-series`, solved in high precision); the constants of Table I of MP2011 are
//! available as [`Pade::table_i`] (the tests check them against the exact law and against
//! the Padé approximants of Table V of SP2008, [`Pade::from_series`]).

use crate::error::{Error, Result};
use std::sync::Arc;

/// Largest numerator or denominator degree of [`Pade::computed`].
pub const MAX_COMPUTED_DEGREE: usize = 60;

/// Table I of MP2011: (m, n, a_0..a_m, b_0..b_n). The table omits b_3 of [0/3]; it is
/// b_3 = -(h_3 + b_1 h_2 + b_2 h_1) = 0 because h_1 = h_3 = 0 and b_1 = 0.
const TABLE_I: [(usize, usize, &[f64], &[f64]); 4] = [
    (0, 3, &[1.0], &[1.0, 0.0, 1.153_45, 0.0]),
    (
        1,
        4,
        &[1.0, 0.501_086],
        &[1.0, 0.501_086, 1.153_45, 0.577_977, 0.532_178],
    ),
    (
        2,
        5,
        &[1.0, 0.553_528, -0.128_445],
        &[1.0, 0.553_528, 1.025, 0.638_466, 0.384_023, 0.027_908],
    ),
    (
        3,
        6,
        &[1.0, 1.072_32, 0.574_198, 0.141_552],
        &[
            1.0, 1.072_32, 1.727_65, 1.378_42, 1.194_49, 0.467_273, 0.235_585,
        ],
    ),
];

/// A rational function sum a_i v*^i / sum b_i v*^i.
#[derive(Debug, Clone, PartialEq)]
pub struct Pade {
    numerator: Arc<[f64]>,
    denominator: Arc<[f64]>,
    /// Whether the coefficients are those printed in Table I of MP2011.
    from_paper: bool,
}

impl Pade {
    /// A rational function from its coefficients (lowest power first); b_0 must not be 0.
    pub fn new(numerator: &[f64], denominator: &[f64]) -> Result<Self> {
        let finite = |c: &[f64]| !c.is_empty() && c.iter().all(|x| x.is_finite());
        if !finite(numerator) || !finite(denominator) || denominator[0] == 0.0 {
            return Err(Error::parse(
                "Padé approximant",
                "coefficients must be finite, non-empty, with b_0 != 0",
            ));
        }
        Ok(Pade {
            numerator: numerator.into(),
            denominator: denominator.into(),
            from_paper: false,
        })
    }

    /// The approximant [m/m+3] of Table I of MP2011, m = 0..3.
    pub fn table_i(m: usize, n: usize) -> Result<Self> {
        TABLE_I
            .iter()
            .find(|row| row.0 == m && row.1 == n)
            .map(|row| {
                let mut pade = Pade::new(row.2, row.3)?;
                pade.from_paper = true;
                Ok(pade)
            })
            .unwrap_or_else(|| {
                Err(Error::out_of_range(
                    "pade order M/N",
                    format!("{m}/{n}"),
                    "one of 0/3, 1/4, 2/5, 3/6 (Table I of MP2011)",
                ))
            })
    }

    /// [m/n] from the h_k computed by `haff-series`, the linear system solved in high
    /// precision (the chain of order m + n is computed once per process and order).
    pub fn computed(m: usize, n: usize) -> Result<Self> {
        if m > MAX_COMPUTED_DEGREE || n > MAX_COMPUTED_DEGREE {
            return Err(Error::out_of_range(
                "pade order M/N",
                format!("{m}/{n}"),
                "M, N <= 60",
            ));
        }
        let longest = crate::series::max_chain_order();
        if m + n > longest {
            return Err(Error::out_of_range(
                "pade order M/N",
                format!("{m}/{n}"),
                &format!(
                    "M + N <= {longest} (h_0..h_(M+N) by computer algebra within about {} s)",
                    series::coefficients::MAX_SECONDS
                ),
            ));
        }
        let h = crate::series::computed_chain(m + n);
        let approximant = series::pade::pade(&h, m, n).map_err(|e| match e {
            series::pade::PadeError::Singular { .. } => Error::Undefined(e.to_string()),
            _ => Error::Numerical(format!("Padé [{m}/{n}]: {e}")),
        })?;
        let (a, b) = approximant.to_f64();
        Pade::new(&a, &b)
    }

    /// Whether the coefficients are those printed in Table I of MP2011.
    pub fn is_from_paper(&self) -> bool {
        self.from_paper
    }

    /// The [m/n] Padé approximant of the power series sum h_k x^k (needs m + n + 1
    /// coefficients), normalized to b_0 = 1. Solved in f64 with partial pivoting: adequate
    /// for low orders only (the system becomes ill-conditioned as m, n grow).
    pub fn from_series(h: &[f64], m: usize, n: usize) -> Result<Self> {
        if h.len() < m + n + 1 {
            return Err(Error::out_of_range(
                "series length",
                h.len(),
                &format!(">= m + n + 1 = {}", m + n + 1),
            ));
        }
        let coeff = |k: isize| if k < 0 { 0.0 } else { h[k as usize] };
        // sum_{j=1}^{n} b_j h_{k-j} = -h_k for k = m+1 .. m+n.
        let mut matrix: Vec<Vec<f64>> = (0..n)
            .map(|row| {
                let k = (m + 1 + row) as isize;
                (1..=n).map(|j| coeff(k - j as isize)).collect()
            })
            .collect();
        let mut rhs: Vec<f64> = (0..n).map(|row| -coeff((m + 1 + row) as isize)).collect();
        let b_tail = solve_dense(&mut matrix, &mut rhs)
            .ok_or_else(|| Error::Undefined(format!("Padé [{m}/{n}] system is singular")))?;
        let mut b = vec![1.0];
        b.extend(b_tail);
        let a: Vec<f64> = (0..=m)
            .map(|k| (0..=n.min(k)).map(|j| b[j] * h[k - j]).sum())
            .collect();
        Pade::new(&a, &b)
    }

    pub fn numerator(&self) -> &[f64] {
        &self.numerator
    }

    pub fn denominator(&self) -> &[f64] {
        &self.denominator
    }

    /// (m, n): the degrees of numerator and denominator.
    pub fn orders(&self) -> (usize, usize) {
        (self.numerator.len() - 1, self.denominator.len() - 1)
    }

    #[inline]
    pub fn eval(&self, vstar: f64) -> f64 {
        horner(&self.numerator, vstar) / horner(&self.denominator, vstar)
    }

    /// Positive real zeros of the denominator up to `limit`, located by sign changes on a
    /// fine logarithmic grid and refined by bisection.
    pub fn positive_poles(&self, limit: f64) -> Vec<f64> {
        let den = |x: f64| horner(&self.denominator, x);
        let grid: Vec<f64> = (0..=20_000)
            .map(|i| 1e-3 * (limit / 1e-3).powf(i as f64 / 20_000.0))
            .collect();
        grid.windows(2)
            .filter(|w| den(w[0]).signum() != den(w[1]).signum())
            .map(|w| bisect(den, w[0], w[1]))
            .collect()
    }
}

#[inline]
fn horner(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ci| acc * x + ci)
}

fn bisect(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let fa = f(a);
    for _ in 0..200 {
        let mid = 0.5 * (a + b);
        if mid == a || mid == b {
            break;
        }
        if (f(mid) > 0.0) == (fa > 0.0) {
            a = mid;
        } else {
            b = mid;
        }
    }
    0.5 * (a + b)
}

/// Gaussian elimination with partial pivoting; `None` if singular.
fn solve_dense(m: &mut [Vec<f64>], r: &mut [f64]) -> Option<Vec<f64>> {
    let n = r.len();
    for col in 0..n {
        let piv = (col..n).max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))?;
        if m[piv][col] == 0.0 {
            return None;
        }
        m.swap(col, piv);
        r.swap(col, piv);
        let (upper, lower) = m.split_at_mut(col + 1);
        let pivot_row = &upper[col];
        for (offset, row) in lower.iter_mut().enumerate() {
            let f = row[col] / pivot_row[col];
            for (x, p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                *x -= f * p;
            }
            r[col + 1 + offset] -= f * r[col];
        }
    }
    let mut x = vec![0.0; n];
    for row in (0..n).rev() {
        let tail: f64 = (row + 1..n).map(|k| m[row][k] * x[k]).sum();
        x[row] = (r[row] - tail) / m[row][row];
    }
    Some(x)
}
