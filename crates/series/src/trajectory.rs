//! The trajectory of the viscoelastic collision as an exact power series (Appendix A of
//! SP2008), with the damping parameter kept as a symbol.
//!
//! In the natural units of Eq. (9) of MP2011 (v = 1, A = beta v^(1/5) = v*^2)
//!
//! ```text
//! x'' + x^{3/2} + A x' sqrt(x) = 0,   x(0) = 0,  x'(0) = 1,
//! ```
//!
//! and x = sum_j X_j(A) s^j with s = sqrt(tau), X_2 = 1, and X_j a polynomial in A with
//! rational coefficients. With Y = x/s^2 (Y_m = X_{m+2}), P = x' (P_m = (m+2)/2 Y_m) and
//! Q = sqrt(Y), matching powers of s in the equation gives, for j >= 1,
//!
//! ```text
//! P_j = -(2/j) ( (Y Q)_{j-5} + A (Q P)_{j-3} ),   Q_j = ( Y_j - sum_{i=1}^{j-1} Q_i Q_{j-i} ) / 2,
//! ```
//!
//! the recurrence that the Maple program of Table I of SP2008 carries out by substitution.
//! The terms are sparse: X_j contains A^i only for 3i = j - 2 (mod 5) (the "universal
//! functions" x_i of Eq. (26) advance in steps of tau^{5/2}), which the representation uses.

use dashu_ratio::RBig;

/// A polynomial in A with exponents i0, i0 + 5, i0 + 10, ... <= degree.
#[derive(Debug, Clone, PartialEq)]
pub struct SparsePoly {
    first: usize,
    coefficients: Vec<RBig>,
}

impl SparsePoly {
    /// The zero polynomial with the exponents allowed at series index m (of Y).
    fn zero(m: usize, degree: usize) -> Self {
        let first = (2 * m) % 5;
        let len = if first > degree {
            0
        } else {
            (degree - first) / 5 + 1
        };
        SparsePoly {
            first,
            coefficients: vec![RBig::ZERO; len],
        }
    }

    /// The coefficient of A^i.
    pub fn coefficient(&self, i: usize) -> RBig {
        if i < self.first || !(i - self.first).is_multiple_of(5) {
            return RBig::ZERO;
        }
        self.coefficients
            .get((i - self.first) / 5)
            .cloned()
            .unwrap_or(RBig::ZERO)
    }

    /// (exponent, coefficient) of the non-zero terms.
    pub fn terms(&self) -> impl Iterator<Item = (usize, &RBig)> {
        self.coefficients
            .iter()
            .enumerate()
            .filter(|(_, c)| **c != RBig::ZERO)
            .map(|(k, c)| (self.first + 5 * k, c))
    }

    /// self += A^shift a b, truncated at `degree`.
    fn add_product(&mut self, a: &SparsePoly, b: &SparsePoly, shift: usize, degree: usize) {
        for (ea, ca) in a.terms() {
            for (eb, cb) in b.terms() {
                let e = ea + eb + shift;
                if e > degree {
                    break;
                }
                debug_assert_eq!((e - self.first) % 5, 0);
                self.coefficients[(e - self.first) / 5] += ca * cb;
            }
        }
    }

    fn scale(&mut self, factor: &RBig) {
        for c in &mut self.coefficients {
            *c *= factor;
        }
    }
}

/// The exact trajectory x(tau; A) = sum_j X_j(A) tau^{j/2}, j <= order, truncated at A^degree.
#[derive(Debug, Clone)]
pub struct Trajectory {
    order: usize,
    degree: usize,
    /// Y_m = X_{m+2}, m = 0 ..= order - 2.
    y: Vec<SparsePoly>,
}

impl Trajectory {
    /// Computes X_j for j <= `order` (the power of s = sqrt(tau)) and powers of A up to
    /// `degree`.
    pub fn new(order: usize, degree: usize) -> Self {
        assert!(order >= 2, "trajectory order must be >= 2");
        let top = order - 2;
        let mut one = SparsePoly::zero(0, degree);
        one.coefficients[0] = RBig::ONE;
        let (mut y, mut q, mut p) = (vec![one.clone()], vec![one.clone()], vec![one]);
        for j in 1..=top {
            let mut pj = SparsePoly::zero(j, degree);
            if j >= 5 {
                let m = j - 5;
                for i in 0..=m {
                    pj.add_product(&y[i], &q[m - i], 0, degree);
                }
            }
            if j >= 3 {
                let m = j - 3;
                for i in 0..=m {
                    pj.add_product(&q[i], &p[m - i], 1, degree);
                }
            }
            pj.scale(&RBig::from_parts((-2).into(), (j as u64).into()));
            let mut yj = pj.clone();
            yj.scale(&RBig::from_parts(2.into(), (j as u64 + 2).into()));
            let mut square = SparsePoly::zero(j, degree);
            for i in 1..j {
                square.add_product(&q[i], &q[j - i], 0, degree);
            }
            let mut qj = yj.clone();
            let half = RBig::from_parts(1.into(), 2u64.into());
            for (c, s) in qj.coefficients.iter_mut().zip(&square.coefficients) {
                *c = (&*c - s) * &half;
            }
            y.push(yj);
            q.push(qj);
            p.push(pj);
        }
        Trajectory { order, degree, y }
    }

    pub fn order(&self) -> usize {
        self.order
    }

    pub fn degree(&self) -> usize {
        self.degree
    }

    /// X_j(A): the coefficient of tau^{j/2} (zero for j < 2 or j > order).
    pub fn power(&self, j: usize) -> Option<&SparsePoly> {
        j.checked_sub(2).and_then(|m| self.y.get(m))
    }

    /// The rational coefficient of A^i tau^{j/2}.
    pub fn coefficient(&self, j: usize, i: usize) -> RBig {
        self.power(j).map_or(RBig::ZERO, |p| p.coefficient(i))
    }

    /// (j, i, c) for every non-zero term c A^i tau^{j/2}.
    pub fn terms(&self) -> impl Iterator<Item = (usize, usize, &RBig)> {
        self.y
            .iter()
            .enumerate()
            .flat_map(|(m, p)| p.terms().map(move |(i, c)| (m + 2, i, c)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(n: i64, d: u64) -> RBig {
        RBig::from_parts(n.into(), d.into())
    }

    /// Every term of Eq. (25) of SP2008 (v = 1, beta = A), and nothing else up to tau^{19/2}.
    #[test]
    fn reproduces_eq_25() {
        let t = Trajectory::new(19, 10);
        let expected = [
            (2, 0, r(1, 1)),
            (5, 1, r(-4, 15)),
            (7, 0, r(-4, 35)),
            (8, 2, r(1, 15)),
            (10, 1, r(3, 70)),
            (11, 3, r(-38, 2475)),
            (12, 0, r(1, 175)),
            (13, 2, r(-937, 75075)),
            (14, 4, r(2612, 779625)),
            (15, 1, r(-713, 238875)),
            (16, 3, r(43943, 13513500)),
            (17, 0, r(-22, 104125)),
            (17, 5, r(-31159, 44178750)),
            (18, 2, r(871, 808500)),
            (19, 4, r(-192113, 242492250)),
        ];
        for (j, i, c) in &expected {
            assert_eq!(&t.coefficient(*j, *i), c, "tau^({j}/2) A^{i}");
        }
        assert_eq!(t.terms().count(), expected.len());
    }

    /// The elastic trajectory conserves energy: x'^2/2 + (2/5) x^{5/2} = 1/2 (checked on
    /// the exact coefficients of the series through a numeric evaluation at small tau).
    #[test]
    fn elastic_energy_is_conserved() {
        let t = Trajectory::new(60, 0);
        let f = |c: &RBig| c.to_f64().value();
        let tau: f64 = 0.5;
        let s = tau.sqrt();
        let x: f64 = t.terms().map(|(j, _, c)| f(c) * s.powi(j as i32)).sum();
        let v: f64 = t
            .terms()
            .map(|(j, _, c)| f(c) * j as f64 / 2.0 * s.powi(j as i32 - 2))
            .sum();
        let energy = 0.5 * v * v + 0.4 * x.powf(2.5);
        assert!((energy - 0.5).abs() < 1e-15, "{energy}");
    }
}
