//! Padé approximants of the coefficient of restitution (MP2011, Eqs. 11–12, Table I).
//!
//! Müller & Pöschel (2011, "MP2011") replace the divergent series eps(v*) = sum_k h_k v*^k
//! by the rational function
//!
//! ```text
//!   [m/n](x) = (a_0 + a_1 x + ... + a_m x^m) / (b_0 + b_1 x + ... + b_n x^n),   b_0 = 1,
//! ```
//!
//! whose Maclaurin series agrees with sum h_k x^k through x^(m+n). With h_i = 0 for i < 0 the
//! denominator solves the n linear equations
//!
//! ```text
//!   sum_{j=0}^{n} b_j h_{k-j} = 0,   k = m+1, ..., m+n,
//! ```
//!
//! and then a_k = sum_{j=0}^{min(k,n)} b_j h_{k-j}, k = 0..m. The system (a Toeplitz matrix of
//! the h_k) is very ill-conditioned for large orders, so it is solved by Gaussian elimination
//! with partial pivoting in [`Real`] at the precision of the inputs, never in f64.
//!
//! - [`pade`]: the ordinary one-point approximant.
//! - [`pade_with_asymptote`]: a two-point variant that fixes the large-x law
//!   [m/n] ~ leading x^(m-n) at the price of one matching condition at x = 0.
//! - [`Approximant::positive_real_poles`], [`Approximant::positive_real_zeros`]: the real
//!   zeros of the denominator and the numerator on (0, limit], isolated exactly by
//!   [`crate::sturm`].
//!
//! Findings on the eps series (see the tests): h_1 = h_3 = 0 exactly, so some entries of
//! the Padé table do not exist ([1/1], [1/3], [3/1]: the system is singular; these are the
//! only ones with m + n <= 24); [0/3] has
//! b_3 = 0, which is why MP2011 print only b_0..b_2; and the "pole" of [2/5] at
//! v* = 5.6801 that MP2011 report is a zero of the numerator (a_2 < 0), not of the
//! denominator: [2/5] has no pole on the positive axis, it changes sign there instead.

use crate::power::{Real, Scalar, Series};

// The poles and zeros of an approximant are found by it; re-exported for callers of `pade`.
pub use crate::sturm::positive_real_roots;

/// Largest numerator or denominator degree the haff command and Python build.
pub const MAX_DEGREE: usize = 60;

/// Why an approximant could not be built.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum PadeError {
    /// Fewer series coefficients than the approximant needs.
    #[error(
        "the [{m}/{n}] Padé approximant needs {needed} series coefficients \
         (h_0..h_{last}), but only {available} were given",
        last = needed.saturating_sub(1)
    )]
    TooFewCoefficients {
        m: usize,
        n: usize,
        /// h_0..h_(needed - 1) are required.
        needed: usize,
        available: usize,
    },
    /// The linear system for b_1..b_n is singular to the working precision: the [m/n]
    /// approximant does not exist (or is degenerate, i.e. reducible to a lower order).
    #[error(
        "the [{m}/{n}] Padé approximant does not exist or is degenerate: the linear \
         system for the denominator is singular to the working precision \
         (no pivot in column {column})"
    )]
    Singular {
        m: usize,
        n: usize,
        /// The column (0-based, i.e. the unknown b_(column+1) after pivoting) at which
        /// elimination found no usable pivot.
        column: usize,
    },
}

/// The rational function numerator(x) / denominator(x), coefficients in ascending powers;
/// denominator[0] = 1.
#[derive(Debug, Clone, PartialEq)]
pub struct Approximant {
    /// a_0..a_m.
    pub numerator: Vec<Real>,
    /// b_0 = 1, b_1..b_n.
    pub denominator: Vec<Real>,
}

impl Approximant {
    /// The coefficients rounded to f64: (a_0..a_m, b_0..b_n).
    pub fn to_f64(&self) -> (Vec<f64>, Vec<f64>) {
        let f = |c: &[Real]| c.iter().map(|x| x.to_f64().value()).collect();
        (f(&self.numerator), f(&self.denominator))
    }

    /// The value at x in f64 (Horner on the rounded coefficients).
    pub fn eval_f64(&self, x: f64) -> f64 {
        let (a, b) = self.to_f64();
        let horner = |c: &[f64]| c.iter().rev().fold(0.0, |acc, ci| acc * x + ci);
        horner(&a) / horner(&b)
    }

    /// The value at x in full precision.
    pub fn eval(&self, x: &Real) -> Real {
        let horner = |c: &[Real]| {
            c.iter()
                .rev()
                .fold(c[0].zero_like(), |acc, ci| acc.mul(x).add(ci))
        };
        horner(&self.numerator).div(&horner(&self.denominator))
    }

    /// The first `len` Maclaurin coefficients of numerator / denominator.
    pub fn maclaurin(&self, len: usize) -> Vec<Real> {
        let padded = |c: &[Real]| {
            let mut v: Vec<Real> = c.iter().take(len).cloned().collect();
            v.resize(len, c[0].zero_like());
            Series::new(v)
        };
        padded(&self.numerator)
            .mul(&padded(&self.denominator).inverse())
            .c
    }

    /// The distinct real zeros of the denominator on (0, limit], ascending (`limit` may be
    /// `f64::INFINITY`). See [`positive_real_roots`] for what is guaranteed.
    pub fn positive_real_poles(&self, limit: f64) -> Vec<f64> {
        positive_real_roots(&self.denominator, limit)
    }

    /// The distinct real zeros of the numerator on (0, limit], ascending.
    pub fn positive_real_zeros(&self, limit: f64) -> Vec<f64> {
        positive_real_roots(&self.numerator, limit)
    }
}

/// The [m/n] Padé approximant of sum_k h_k x^k (MP2011, Eqs. 11–12): b_0 = 1 and the
/// Maclaurin series of the approximant matches h_0..h_(m+n). Needs `h.len() >= m + n + 1`.
///
/// Computed in [`Real`] at the largest precision among h_0..h_(m+n) (at least 64 bits).
/// Returns [`PadeError::Singular`] when a pivot is exactly zero or smaller than
/// 2^-(precision - 20) times the largest entry of the matrix: then the approximant does
/// not exist or is degenerate. Note that this only recognises singularity to the working
/// precision; if the h_k themselves carry a larger error, a (mathematically) singular
/// system shows up as a well-pivoted one with huge, meaningless b_j.
pub fn pade(h: &[Real], m: usize, n: usize) -> Result<Approximant, PadeError> {
    let needed = m + n + 1;
    if h.len() < needed {
        return Err(PadeError::TooFewCoefficients {
            m,
            n,
            needed,
            available: h.len(),
        });
    }
    let bits = working_precision(h[..needed].iter());
    let h = Coefficients::new(&h[..needed], bits);
    let mut matrix = Vec::with_capacity(n);
    let mut rhs = Vec::with_capacity(n);
    for k in m + 1..=m + n {
        matrix.push((1..=n).map(|j| h.at(k as isize - j as isize)).collect());
        rhs.push(h.zero.sub(&h.at(k as isize)));
    }
    let b = solve(matrix, rhs, bits).map_err(|column| PadeError::Singular { m, n, column })?;
    Ok(h.assemble(m, b))
}

/// A two-point Padé approximant: [m/n] with b_0 = 1 whose Maclaurin series matches
/// h_0..h_(m+n-1) (one condition fewer than [`pade`]) and whose leading coefficients obey
/// a_m / b_n = `leading`, so that for large x it behaves as `leading` * x^(m-n). The number
/// of unknowns (a_0..a_m, b_1..b_n) is the same as for [`pade`]; the condition at x = 0 of
/// order m+n is traded for the behaviour at x = infinity. Needs `h.len() >= m + n`.
///
/// The n equations for b_1..b_n are sum_{j=0}^{n} b_j h_{k-j} = 0 for k = m+1..m+n-1 and
/// sum_{j=0}^{min(m,n)} b_j h_{m-j} - `leading` b_n = 0 (a_m expressed by the series);
/// for n = 0 simply a_k = h_k (k < m) and a_m = `leading`.
///
/// For the coefficient of restitution (MP2011, Eq. 10: eps -> v*^-3.2) an integer power
/// x^(m-n) can only mimic the true law; `leading` then fixes the amplitude of the chosen
/// power, e.g. m - n = -3 with a fitted constant.
pub fn pade_with_asymptote(
    h: &[Real],
    m: usize,
    n: usize,
    leading: &Real,
) -> Result<Approximant, PadeError> {
    let needed = m + n;
    if h.len() < needed {
        return Err(PadeError::TooFewCoefficients {
            m,
            n,
            needed,
            available: h.len(),
        });
    }
    let bits = working_precision(h[..needed].iter().chain(std::iter::once(leading)));
    let h = Coefficients::new(&h[..needed], bits);
    let leading = to_precision(leading, bits);
    if n == 0 {
        let mut numerator: Vec<Real> = (0..m).map(|k| h.at(k as isize)).collect();
        numerator.push(leading);
        return Ok(Approximant {
            numerator,
            denominator: vec![h.zero.one_like()],
        });
    }
    let mut matrix: Vec<Vec<Real>> = Vec::with_capacity(n);
    let mut rhs = Vec::with_capacity(n);
    for k in m + 1..m + n {
        matrix.push((1..=n).map(|j| h.at(k as isize - j as isize)).collect());
        rhs.push(h.zero.sub(&h.at(k as isize)));
    }
    let mut row: Vec<Real> = (1..=n).map(|j| h.at(m as isize - j as isize)).collect();
    row[n - 1] = row[n - 1].sub(&leading);
    matrix.push(row);
    rhs.push(h.zero.sub(&h.at(m as isize)));
    let b = solve(matrix, rhs, bits).map_err(|column| PadeError::Singular { m, n, column })?;
    Ok(h.assemble(m, b))
}

/// h_k at a common precision, with h_k = 0 outside the given range.
struct Coefficients {
    h: Vec<Real>,
    zero: Real,
}

impl Coefficients {
    fn new(h: &[Real], bits: usize) -> Self {
        Coefficients {
            h: h.iter().map(|x| to_precision(x, bits)).collect(),
            zero: Real::ZERO.with_precision(bits).value(),
        }
    }

    fn at(&self, i: isize) -> Real {
        usize::try_from(i)
            .ok()
            .and_then(|i| self.h.get(i))
            .unwrap_or(&self.zero)
            .clone()
    }

    /// b = (b_1..b_n) -> the approximant with a_k = sum_{j<=min(k,n)} b_j h_{k-j}.
    fn assemble(&self, m: usize, b: Vec<Real>) -> Approximant {
        let mut denominator = vec![self.zero.one_like()];
        denominator.extend(b);
        let numerator = (0..=m)
            .map(|k| {
                denominator
                    .iter()
                    .enumerate()
                    .take(k + 1)
                    .fold(self.zero.clone(), |acc, (j, bj)| {
                        acc.add(&bj.mul(&self.at((k - j) as isize)))
                    })
            })
            .collect();
        Approximant {
            numerator,
            denominator,
        }
    }
}

fn working_precision<'a>(xs: impl Iterator<Item = &'a Real>) -> usize {
    xs.map(|x| x.precision()).max().unwrap_or(0).max(64)
}

fn to_precision(x: &Real, bits: usize) -> Real {
    x.clone().with_precision(bits).value()
}

fn abs(x: &Real) -> Real {
    if x.sign() == dashu_base::Sign::Negative {
        -x.clone()
    } else {
        x.clone()
    }
}

/// Solves A y = r by Gaussian elimination with partial pivoting. Err(column) when the
/// pivot is zero or below 2^-(bits - 20) times the largest |A_ij|.
fn solve(mut a: Vec<Vec<Real>>, mut r: Vec<Real>, bits: usize) -> Result<Vec<Real>, usize> {
    let size = r.len();
    let largest = a
        .iter()
        .flatten()
        .map(abs)
        .max()
        .unwrap_or_else(|| Real::ZERO.with_precision(bits).value());
    let threshold = largest << -(bits.saturating_sub(20) as isize);
    for col in 0..size {
        let (pivot_row, pivot) = (col..size)
            .map(|i| (i, abs(&a[i][col])))
            .max_by(|x, y| x.1.cmp(&y.1))
            .expect("non-empty column");
        if pivot.is_zero() || pivot < threshold {
            return Err(col);
        }
        a.swap(col, pivot_row);
        r.swap(col, pivot_row);
        let (head, tail) = a.split_at_mut(col + 1);
        let pivot_row = &head[col];
        for (offset, row) in tail.iter_mut().enumerate() {
            if row[col].is_zero() {
                continue;
            }
            let factor = row[col].div(&pivot_row[col]);
            for (x, p) in row.iter_mut().zip(pivot_row).skip(col + 1) {
                *x = x.sub(&factor.mul(p));
            }
            let i = col + 1 + offset;
            r[i] = r[i].sub(&factor.mul(&r[col]));
        }
    }
    let mut y: Vec<Real> = r.clone();
    for i in (0..size).rev() {
        let s = (i + 1..size).fold(r[i].clone(), |acc, j| acc.sub(&a[i][j].mul(&y[j])));
        y[i] = s.div(&a[i][i]);
    }
    Ok(y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coefficients::{compute, Settings};
    use crate::power::real;
    use dashu_ratio::RBig;
    use std::sync::OnceLock;

    const BITS: usize = 256;

    fn r(n: i64, d: u64) -> RBig {
        RBig::from_parts(n.into(), d.into())
    }

    fn f64_of(x: &Real) -> f64 {
        x.to_f64().value()
    }

    /// Exact Maclaurin coefficients of num / den (den_0 = 1), as Reals.
    fn rational_series(num: &[i64], den: &[i64], len: usize) -> Vec<Real> {
        let pad = |c: &[i64]| {
            let mut v: Vec<RBig> = c.iter().map(|&x| r(x, 1)).collect();
            v.resize(len, RBig::ZERO);
            Series::new(v)
        };
        let s = pad(num).mul(&pad(den).inverse());
        s.c.iter().map(|x| real(x, BITS)).collect()
    }

    /// h_k for k <= 20 (Settings::for_order(20)), computed once.
    fn h20() -> &'static [Real] {
        static H: OnceLock<Vec<Real>> = OnceLock::new();
        H.get_or_init(|| compute(Settings::for_order(20)).h)
    }

    fn assert_close(computed: &[Real], printed: &[f64], what: &str) {
        assert_eq!(computed.len(), printed.len(), "{what}: length");
        for (i, (c, p)) in computed.iter().zip(printed).enumerate() {
            let c = f64_of(c);
            // Printed to 6 decimals below 1 and to 6 significant digits above.
            let tol = if p.abs() < 1.0 { 5e-7 } else { 5e-6 };
            assert!(
                (c - p).abs() <= tol,
                "{what}_{i}: computed {c}, printed {p}"
            );
        }
    }

    #[test]
    fn pade_recovers_a_rational_function() {
        // (1 + 2x) / (1 - x + 3x^2).
        let h = rational_series(&[1, 2], &[1, -1, 3], 12);
        let approx = pade(&h, 1, 2).unwrap();
        let exact = [[1.0, 2.0].as_slice(), [1.0, -1.0, 3.0].as_slice()];
        for (got, want) in [&approx.numerator, &approx.denominator].iter().zip(exact) {
            for (g, w) in got.iter().zip(want) {
                assert!((f64_of(g) - w).abs() < 1e-60, "{g} vs {w}");
                let diff = g.sub(&real(&r(*w as i64, 1), BITS));
                assert!(diff.is_zero() || diff.repr().exponent() < -(BITS as isize) + 16);
            }
        }
        // Higher orders that still determine it uniquely: [2/2] (a_2 = 0) and [1/3] (b_3 = 0).
        let a22 = pade(&h, 2, 2).unwrap();
        assert!(f64_of(&a22.numerator[2]).abs() < 1e-60);
        let a13 = pade(&h, 1, 3).unwrap();
        assert!(f64_of(&a13.denominator[3]).abs() < 1e-60);
        assert!((a13.eval_f64(0.3) - 1.6 / (1.0 - 0.3 + 0.27)).abs() < 1e-15);
        // [2/3] is not unique (a common factor can be added): singular.
        let err = pade(&h, 2, 3).unwrap_err();
        assert!(
            matches!(err, PadeError::Singular { m: 2, n: 3, .. }),
            "{err}"
        );
        assert!(err.to_string().contains("does not exist"));
        // Too few coefficients.
        let err = pade(&h[..4], 2, 2).unwrap_err();
        assert!(
            matches!(
                err,
                PadeError::TooFewCoefficients {
                    needed: 5,
                    available: 4,
                    ..
                }
            ),
            "{err}"
        );
        assert!(err.to_string().contains("h_0..h_4"), "{err}");
        // Poles: 1 - x + 3x^2 has no real zero; the numerator's zero -1/2 is negative.
        assert!(approx.positive_real_poles(f64::INFINITY).is_empty());
        assert!(approx.positive_real_zeros(f64::INFINITY).is_empty());
    }

    #[test]
    fn two_point_pade_recovers_a_rational_function() {
        // (1 + 2x) / (1 - x + 3x^2) ~ (2/3) / x: from only h_0..h_2 and the asymptote.
        let h = rational_series(&[1, 2], &[1, -1, 3], 3);
        let leading = real(&r(2, 3), BITS);
        let approx = pade_with_asymptote(&h, 1, 2, &leading).unwrap();
        let (a, b) = approx.to_f64();
        for (g, w) in a.iter().chain(&b).zip([1.0, 2.0, 1.0, -1.0, 3.0]) {
            assert!((g - w).abs() < 1e-60, "{a:?} {b:?}");
        }
        assert!(matches!(
            pade_with_asymptote(&h[..2], 1, 2, &leading),
            Err(PadeError::TooFewCoefficients { needed: 3, .. })
        ));
    }

    #[test]
    fn two_point_pade_of_the_restitution_series() {
        // [1/4] with a_1 / b_4 = 1: matches h_0..h_4 and behaves as 1/v*^3.
        let h = h20();
        let one = h[0].one_like();
        let approx = pade_with_asymptote(h, 1, 4, &one).unwrap();
        let ratio = approx.numerator[1].div(&approx.denominator[4]);
        assert!((f64_of(&ratio) - 1.0).abs() < 1e-40);
        for (k, c) in approx.maclaurin(6).iter().enumerate() {
            let d = f64_of(&c.sub(&h[k])).abs();
            if k < 5 {
                assert!(d < 1e-40, "h_{k}: {d}");
            } else {
                assert!(d > 1e-6, "h_5 should not be matched: {d}");
            }
        }
        let x: f64 = 1e4;
        assert!((approx.eval_f64(x) * x.powi(3) - 1.0).abs() < 1e-3);
    }

    /// Table I of MP2011 from the h_k of the chain.
    #[test]
    fn table_one_of_mp2011() {
        let h = h20();
        let p03 = pade(h, 0, 3).unwrap();
        assert_close(&p03.numerator, &[1.0], "[0/3] a");
        assert_close(&p03.denominator[..3], &[1.0, 0.0, 1.15345], "[0/3] b");
        // b_3 = -h_3 = 0: omitted in the paper.
        assert!(
            f64_of(&p03.denominator[3]).abs() < 1e-40,
            "{}",
            p03.denominator[3]
        );

        let p14 = pade(h, 1, 4).unwrap();
        assert_close(&p14.numerator, &[1.0, 0.501086], "[1/4] a");
        let b14 = [1.0, 0.501086, 1.15345, 0.577977, 0.532178];
        assert_close(&p14.denominator, &b14, "[1/4] b");

        let p25 = pade(h, 2, 5).unwrap();
        assert_close(&p25.numerator, &[1.0, 0.553528, -0.128445], "[2/5] a");
        let b25 = [1.0, 0.553528, 1.025, 0.638466, 0.384023, 0.027908];
        assert_close(&p25.denominator, &b25, "[2/5] b");

        let p36 = pade(h, 3, 6).unwrap();
        let a36 = [1.0, 1.07232, 0.574198, 0.141552];
        assert_close(&p36.numerator, &a36, "[3/6] a");
        let b36 = [1.0, 1.07232, 1.72765, 1.37842, 1.19449, 0.467273, 0.235585];
        assert_close(&p36.denominator, &b36, "[3/6] b");

        // Each matches the series through v*^(m+n).
        for (p, order) in [(&p03, 3), (&p14, 5), (&p25, 7), (&p36, 9)] {
            for (k, c) in p.maclaurin(order + 1).iter().enumerate() {
                assert!(f64_of(&c.sub(&h[k])).abs() < 1e-40, "order {order}, h_{k}");
            }
        }
    }

    /// MP2011 say [2/5] "reveals a pole at v* = 5.6801": it is a zero of the numerator.
    #[test]
    fn two_five_has_a_zero_not_a_pole() {
        let p25 = pade(h20(), 2, 5).unwrap();
        assert!(p25.positive_real_poles(f64::INFINITY).is_empty());
        let zeros = p25.positive_real_zeros(100.0);
        assert_eq!(zeros.len(), 1, "{zeros:?}");
        assert!((zeros[0] - 5.6801).abs() < 5e-5, "{}", zeros[0]);
        assert!(p25.eval_f64(5.0) > 0.0 && p25.eval_f64(6.5) < 0.0);
        // [1/4] and [3/6] are free of positive poles and zeros.
        for (m, n) in [(1, 4), (3, 6)] {
            let p = pade(h20(), m, n).unwrap();
            assert!(p.positive_real_poles(f64::INFINITY).is_empty(), "[{m}/{n}]");
            assert!(p.positive_real_zeros(f64::INFINITY).is_empty(), "[{m}/{n}]");
        }
        // The next one, [4/7], does have a pole on the positive axis (v* = 3.6874, next to a
        // numerator zero at 3.3681 that does not cancel it), unlike [5/8].
        let p47 = pade(h20(), 4, 7).unwrap();
        let poles = p47.positive_real_poles(f64::INFINITY);
        assert_eq!(poles.len(), 1, "{poles:?}");
        assert!((poles[0] - 3.68743).abs() < 1e-4, "{poles:?}");
        let zeros = p47.positive_real_zeros(f64::INFINITY);
        assert!(
            zeros.len() == 1 && (zeros[0] - 3.36813).abs() < 1e-4,
            "{zeros:?}"
        );
        assert!(pade(h20(), 5, 8)
            .unwrap()
            .positive_real_poles(1e3)
            .is_empty());
    }

    /// h_1 = h_3 = 0 exactly, so [1/1], [1/3] and [3/1] do not exist (the only singular
    /// entries with m + n <= 20).
    #[test]
    fn missing_entries_of_the_pade_table() {
        let h = h20();
        for s in 0..=20 {
            for m in 0..=s {
                let singular = matches!(pade(h, m, s - m), Err(PadeError::Singular { .. }));
                let expected = matches!((m, s - m), (1, 1) | (1, 3) | (3, 1));
                assert_eq!(singular, expected, "[{m}/{}]", s - m);
            }
        }
        assert!(
            h[1].is_zero() && h[3].is_zero(),
            "h_1 = {}, h_3 = {}",
            h[1],
            h[3]
        );
        for (m, n) in [(1, 1), (1, 3), (3, 1)] {
            assert!(
                matches!(pade(h, m, n), Err(PadeError::Singular { .. })),
                "[{m}/{n}]"
            );
        }
    }

    /// A high order: [20/23] from K = 43 coefficients agrees with the (convergent) partial
    /// sum at v* = 0.5.
    #[test]
    fn high_order_approximant() {
        let (m, n) = (20, 23);
        let h = compute(Settings::for_order(m + n)).h;
        let approx = pade(&h, m, n).unwrap();
        let x = 0.5;
        let partial: f64 = h.iter().rev().fold(0.0, |acc, c| acc * x + f64_of(c));
        let value = f64_of(&approx.eval(&real(&r(1, 2), h[0].precision())));
        assert!((value - partial).abs() < 1e-10, "{value} vs {partial}");
        assert!((approx.eval_f64(x) - partial).abs() < 1e-10);
    }
}
