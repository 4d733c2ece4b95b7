//! Truncated power series over exact rationals or arbitrary-precision floats.

use dashu_float::{round::mode::HalfEven, FBig};
use dashu_ratio::RBig;

/// A binary floating-point number of arbitrary precision, rounded half to even.
pub type Real = FBig<HalfEven, 2>;

/// The field operations the series algorithms need. Constructors take `self` as a model so
/// that floats inherit its precision.
pub trait Scalar: Clone + PartialEq + std::fmt::Debug {
    fn zero_like(&self) -> Self;
    fn ratio_like(&self, numerator: i64, denominator: u64) -> Self;
    fn add(&self, other: &Self) -> Self;
    fn sub(&self, other: &Self) -> Self;
    fn mul(&self, other: &Self) -> Self;
    fn div(&self, other: &Self) -> Self;
    fn is_zero(&self) -> bool {
        *self == self.zero_like()
    }
    fn one_like(&self) -> Self {
        self.ratio_like(1, 1)
    }
}

/// The four operations of `Scalar` through the operators of a type with `&a op &b`.
macro_rules! operator_arithmetic {
    () => {
        fn add(&self, o: &Self) -> Self {
            self + o
        }
        fn sub(&self, o: &Self) -> Self {
            self - o
        }
        fn mul(&self, o: &Self) -> Self {
            self * o
        }
        fn div(&self, o: &Self) -> Self {
            self / o
        }
    };
}

impl Scalar for RBig {
    fn zero_like(&self) -> Self {
        RBig::ZERO
    }
    fn ratio_like(&self, n: i64, d: u64) -> Self {
        RBig::from_parts(n.into(), d.into())
    }
    operator_arithmetic!();
}

impl Scalar for Real {
    fn zero_like(&self) -> Self {
        Real::ZERO.with_precision(self.precision()).value()
    }
    fn ratio_like(&self, n: i64, d: u64) -> Self {
        let p = self.precision();
        Real::from(n).with_precision(p).value() / Real::from(d).with_precision(p).value()
    }
    operator_arithmetic!();
}

/// A rational as a float of precision `bits`.
pub fn real(r: &RBig, bits: usize) -> Real {
    r.to_float(bits).value()
}

/// An integer ratio as a float of precision `bits`.
pub fn ratio(n: i64, d: u64, bits: usize) -> Real {
    Real::ONE.with_precision(bits).value().ratio_like(n, d)
}

/// sum_k c_k x^k truncated after x^(len - 1), len = `c.len()`.
#[derive(Debug, Clone, PartialEq)]
pub struct Series<T: Scalar> {
    pub c: Vec<T>,
}

impl<T: Scalar> Series<T> {
    /// The series with the given coefficients.
    pub fn new(c: Vec<T>) -> Self {
        assert!(!c.is_empty(), "a series needs at least one coefficient");
        Series { c }
    }

    /// `len` coefficients equal to zero, modelled on `model`.
    pub fn zeros(model: &T, len: usize) -> Self {
        Series::new(vec![model.zero_like(); len])
    }

    /// The constant `value` with `len` coefficients.
    pub fn constant(value: T, len: usize) -> Self {
        let mut s = Series::zeros(&value, len);
        s.c[0] = value;
        s
    }

    pub fn len(&self) -> usize {
        self.c.len()
    }

    pub fn is_empty(&self) -> bool {
        false
    }

    fn model(&self) -> &T {
        &self.c[0]
    }

    pub fn add(&self, o: &Self) -> Self {
        Series::new(self.c.iter().zip(&o.c).map(|(a, b)| a.add(b)).collect())
    }

    pub fn sub(&self, o: &Self) -> Self {
        Series::new(self.c.iter().zip(&o.c).map(|(a, b)| a.sub(b)).collect())
    }

    pub fn scale(&self, factor: &T) -> Self {
        Series::new(self.c.iter().map(|a| a.mul(factor)).collect())
    }

    /// The product, truncated to the shorter length.
    pub fn mul(&self, o: &Self) -> Self {
        let n = self.len().min(o.len());
        let c = (0..n)
            .map(|k| {
                (0..=k)
                    .filter(|&i| !self.c[i].is_zero() && !o.c[k - i].is_zero())
                    .fold(self.model().zero_like(), |acc, i| {
                        acc.add(&self.c[i].mul(&o.c[k - i]))
                    })
            })
            .collect();
        Series::new(c)
    }

    /// x^shift times the series (same length).
    pub fn shift(&self, by: usize) -> Self {
        let mut c = vec![self.model().zero_like(); self.len()];
        if by < self.len() {
            c[by..].clone_from_slice(&self.c[..self.len() - by]);
        }
        Series::new(c)
    }

    /// The series in x^step: sum c_k x^(step k), truncated at `len`.
    pub fn spread(&self, step: usize, len: usize) -> Self {
        let mut out = Series::zeros(self.model(), len);
        for (k, c) in self.c.iter().enumerate() {
            if k * step < len {
                out.c[k * step] = c.clone();
            }
        }
        out
    }

    /// 1 / self (needs c_0 != 0).
    pub fn inverse(&self) -> Self {
        let c0 = &self.c[0];
        let mut r = vec![c0.one_like().div(c0)];
        for k in 1..self.len() {
            let s = (1..=k).fold(c0.zero_like(), |acc, i| acc.add(&self.c[i].mul(&r[k - i])));
            r.push(s.div(c0).mul(&c0.ratio_like(-1, 1)));
        }
        Series::new(r)
    }

    /// self^q for rational q = num/den, needs c_0 = 1: from f g' = q f' g,
    /// g_k = sum_{i=1}^k (q i - (k - i)) f_i g_{k-i} / k.
    pub fn power(&self, num: i64, den: u64) -> Self {
        assert!(self.c[0] == self.model().one_like(), "power needs c_0 = 1");
        let one = self.model().one_like();
        let q = one.ratio_like(num, den);
        let mut g = vec![one.clone()];
        for k in 1..self.len() {
            let s = (1..=k).fold(one.zero_like(), |acc, i| {
                let weight = q
                    .mul(&one.ratio_like(i as i64, 1))
                    .sub(&one.ratio_like((k - i) as i64, 1));
                acc.add(&weight.mul(&self.c[i]).mul(&g[k - i]))
            });
            g.push(s.div(&one.ratio_like(k as i64, 1)));
        }
        Series::new(g)
    }

    /// sum_k coefficients[k] * x^k where x is this series (x(0) must be 0 for the result
    /// to be exact to the series' length); Horner.
    pub fn compose_scalar(&self, coefficients: &[T]) -> Self {
        let len = self.len();
        let mut acc = Series::zeros(self.model(), len);
        for ck in coefficients.iter().rev() {
            acc = acc.mul(self);
            acc.c[0] = acc.c[0].add(ck);
        }
        acc
    }

    /// sum_k coefficients[k] * x^k with series coefficients; Horner.
    pub fn compose(&self, coefficients: &[Series<T>]) -> Self {
        let len = self.len();
        let mut acc = Series::zeros(self.model(), len);
        for ck in coefficients.iter().rev() {
            acc = acc.mul(self).add(ck);
        }
        acc
    }
}

impl Series<Real> {
    /// sqrt(self), needs c_0 > 0.
    pub fn sqrt(&self) -> Self {
        let s0 = self.c[0].sqrt();
        let two_s0 = s0.mul(&s0.ratio_like(2, 1));
        let mut s = vec![s0];
        for k in 1..self.len() {
            let cross = (1..k).fold(self.c[0].zero_like(), |acc, i| {
                acc.add(&s[i].mul(&s[k - i]))
            });
            s.push(self.c[k].sub(&cross).div(&two_s0));
        }
        Series::new(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(n: i64, d: u64) -> RBig {
        RBig::from_parts(n.into(), d.into())
    }

    #[test]
    fn rational_identities() {
        // (1 + x)^(1/2) squared is 1 + x; (1 - x)^-1 = sum x^k.
        let f = Series::new(vec![r(1, 1), r(1, 1), r(0, 1), r(0, 1), r(0, 1)]);
        let h = f.power(1, 2);
        assert_eq!(h.c[2], r(-1, 8));
        assert_eq!(h.mul(&h), f);
        let g = Series::new(vec![r(1, 1), r(-1, 1), r(0, 1), r(0, 1)]).inverse();
        assert!(g.c.iter().all(|c| *c == r(1, 1)));
        // exp-free check of compose: (x/(1-x)) composed into 1 + y: 1 + x + x^2 + ...
        let x = Series::new(vec![r(0, 1), r(1, 1), r(1, 1), r(1, 1)]);
        assert_eq!(x.compose_scalar(&[r(1, 1), r(1, 1)]).c, vec![r(1, 1); 4]);
    }

    #[test]
    fn real_sqrt_and_power_agree() {
        let bits = 200;
        let f = Series::new((0..8).map(|k| ratio(1, (k + 1) as u64, bits)).collect());
        let a = f.sqrt();
        let b = f.power(1, 2);
        for (x, y) in a.c.iter().zip(&b.c) {
            let d = x.sub(y).to_f64().value().abs();
            assert!(d < 1e-55, "{d}");
        }
    }
}
