//! Exact isolation of the real zeros of a polynomial with binary-float coefficients.
//!
//! The coefficients are turned *exactly* into an integer polynomial p; Sturm's theorem then
//! counts the distinct real zeros of p in (lo, hi] as V(lo) - V(hi), V(x) being the number
//! of sign changes of the Sturm sequence p_0 = p, p_1 = p', p_(i+1) = -rem(p_(i-1), p_i)
//! at x. The sequence is built over the integers with primitive pseudo-remainders, so no
//! count is ever wrong by rounding; zeros are then separated by bisection on dyadic
//! rationals. [`positive_real_roots`] is the entry point (used for the poles and zeros of
//! Padé approximants, [`crate::pade::Approximant`]).

use crate::power::Real;
use dashu_base::{BitTest, Gcd, UnsignedAbs};
use dashu_int::IBig;
use std::cmp::Ordering;

/// A polynomial with integer coefficients, ascending, without leading zeros.
type IntPoly = Vec<IBig>;

/// A dyadic rational num / 2^shift.
#[derive(Debug, Clone)]
struct Dyadic {
    num: IBig,
    shift: usize,
}

impl Dyadic {
    fn aligned(&self, other: &Dyadic) -> (IBig, IBig, usize) {
        let s = self.shift.max(other.shift);
        (
            &self.num << (s - self.shift),
            &other.num << (s - other.shift),
            s,
        )
    }

    fn midpoint(&self, other: &Dyadic) -> Dyadic {
        let (a, b, s) = self.aligned(other);
        Dyadic {
            num: a + b,
            shift: s + 1,
        }
    }

    fn to_f64(&self) -> f64 {
        Real::from_parts(self.num.clone(), -(self.shift as isize))
            .to_f64()
            .value()
    }
}

/// [`positive_real_roots`] of a polynomial with f64 coefficients (converted exactly); a
/// non-finite coefficient yields `None`.
pub fn positive_real_roots_of_floats(coefficients: &[f64], limit: f64) -> Option<Vec<f64>> {
    let exact: Option<Vec<Real>> = coefficients
        .iter()
        .map(|&c| Real::try_from(c).ok())
        .collect();
    Some(positive_real_roots(&exact?, limit))
}

/// The distinct real zeros on (0, limit] of the polynomial sum_i c_i x^i, ascending.
///
/// Method and guarantee: the coefficients, which are binary floats, are converted *exactly*
/// to an integer polynomial p; its square-free part q = p / gcd(p, p') and the Sturm
/// sequence of q are computed exactly over the integers (primitive pseudo-remainders), so
/// the Sturm counts are exact and *every* distinct zero of p in (0, limit] is found exactly
/// once, whatever its multiplicity (double zeros included) and however close zeros are.
/// Each is isolated by exact bisection on dyadic rationals and refined (a simple zero of q
/// changes sign) to a relative width below 2^-60, then rounded to f64.
///
/// The statement is about the polynomial with the *stored* (rounded) coefficients. A
/// multiple zero of the exact polynomial generically splits under rounding into nearby
/// simple real zeros or into a complex pair close to the axis (which is then not reported);
/// a coefficient that should vanish but is a rounding residue (e.g. b_3 of [0/3]) creates
/// a spurious zero of enormous size, far beyond any sensible `limit`. An identically zero
/// polynomial yields no zeros.
pub fn positive_real_roots(coefficients: &[Real], limit: f64) -> Vec<f64> {
    if limit.is_nan() || limit <= 0.0 {
        return Vec::new();
    }
    let mut p = to_int_poly(coefficients);
    // Zeros at x = 0 are not in (0, limit].
    let low = p.iter().take_while(|c| c.is_zero()).count();
    p.drain(..low);
    if p.len() < 2 {
        return Vec::new();
    }
    let q = square_free(&p);
    let sturm = sturm_sequence(&q);
    let hi = upper_end(&q, limit);
    let lo = Dyadic {
        num: IBig::ZERO,
        shift: 0,
    };
    let changes = |x: &Dyadic| sign_changes(&sturm, x);
    let mut roots = Vec::new();
    // Intervals (lo, hi] with their Sturm counts, processed left to right.
    let (v_lo, v_hi) = (changes(&lo), changes(&hi));
    let mut stack = vec![(lo, v_lo, hi, v_hi)];
    while let Some((lo, v_lo, hi, v_hi)) = stack.pop() {
        match v_lo.saturating_sub(v_hi) {
            0 => {}
            1 => roots.push(refine(&q, lo, hi)),
            _ => {
                let mid = lo.midpoint(&hi);
                let v_mid = changes(&mid);
                stack.push((mid.clone(), v_mid, hi, v_hi));
                stack.push((lo, v_lo, mid, v_mid));
            }
        }
    }
    roots
}

/// Exact integer polynomial with the same zeros (a positive power of two times the input),
/// leading zeros removed.
fn to_int_poly(c: &[Real]) -> IntPoly {
    let min_exp = c
        .iter()
        .filter(|x| !x.repr().significand().is_zero())
        .map(|x| x.repr().exponent())
        .min()
        .unwrap_or(0);
    let mut p: IntPoly = c
        .iter()
        .map(|x| {
            let s = x.repr().significand();
            if s.is_zero() {
                IBig::ZERO
            } else {
                s << (x.repr().exponent() - min_exp) as usize
            }
        })
        .collect();
    trim(&mut p);
    p
}

fn trim(p: &mut IntPoly) {
    while p.last().is_some_and(|c| c.is_zero()) {
        p.pop();
    }
}

fn derivative(p: &IntPoly) -> IntPoly {
    let mut d: IntPoly = p
        .iter()
        .enumerate()
        .skip(1)
        .map(|(i, c)| c * IBig::from(i))
        .collect();
    trim(&mut d);
    d
}

/// p divided by the (positive) gcd of its coefficients.
fn primitive(mut p: IntPoly) -> IntPoly {
    let content = p
        .iter()
        .filter(|c| !c.is_zero())
        .map(|c| c.unsigned_abs())
        .reduce(|g, c| (&g).gcd(&c));
    if let Some(g) = content {
        let g = IBig::from(g);
        if g != IBig::ONE {
            for c in &mut p {
                *c = &*c / &g;
            }
        }
    }
    p
}

/// (Q, R) with s f = Q g + R, deg R < deg g, for some constant s > 0 (a power of |lc(g)|).
fn pseudo_divide(f: &IntPoly, g: &IntPoly) -> (IntPoly, IntPoly) {
    let dg = g.len() - 1;
    let lead = &g[dg];
    let (abs_lead, negative) = (IBig::from(lead.unsigned_abs()), *lead < IBig::ZERO);
    let mut r = f.clone();
    let mut q = vec![IBig::ZERO; f.len().saturating_sub(dg)];
    while !r.is_empty() && r.len() > dg {
        let shift = r.len() - 1 - dg;
        let c = if negative {
            -r[r.len() - 1].clone()
        } else {
            r[r.len() - 1].clone()
        };
        for x in r.iter_mut().chain(q.iter_mut()) {
            *x = &*x * &abs_lead;
        }
        for (i, gi) in g.iter().enumerate() {
            r[shift + i] -= &c * gi;
        }
        q[shift] += &c;
        r.pop();
        trim(&mut r);
    }
    trim(&mut q);
    (q, r)
}

/// p, p', -rem, ... (each made primitive; positive factors do not change the sign counts).
fn sturm_sequence(p: &IntPoly) -> Vec<IntPoly> {
    let mut seq = vec![primitive(p.clone()), primitive(derivative(p))];
    loop {
        let (_, r) = pseudo_divide(&seq[seq.len() - 2], &seq[seq.len() - 1]);
        if r.is_empty() {
            return seq;
        }
        seq.push(primitive(r.into_iter().map(|c| -c).collect()));
    }
}

/// p / gcd(p, p') up to a positive constant: the same zeros, all simple.
fn square_free(p: &IntPoly) -> IntPoly {
    let seq = sturm_sequence(p);
    let g = seq.last().expect("non-empty");
    if g.len() <= 1 {
        primitive(p.clone())
    } else {
        primitive(pseudo_divide(p, g).0)
    }
}

/// sign of p(x) for dyadic x (homogenised Horner, exact).
fn sign_at(p: &IntPoly, x: &Dyadic) -> Ordering {
    let d = p.len() - 1;
    let mut acc = p[d].clone();
    for i in (0..d).rev() {
        acc = acc * &x.num + (&p[i] << (x.shift * (d - i)));
    }
    acc.cmp(&IBig::ZERO)
}

fn sign_changes(seq: &[IntPoly], x: &Dyadic) -> usize {
    let signs: Vec<Ordering> = seq
        .iter()
        .map(|p| sign_at(p, x))
        .filter(|s| *s != Ordering::Equal)
        .collect();
    signs.windows(2).filter(|w| w[0] != w[1]).count()
}

/// min(limit, 2^t) with 2^t above the Cauchy bound 1 + max |q_i / q_d|, as a dyadic.
fn upper_end(q: &IntPoly, limit: f64) -> Dyadic {
    let d = q.len() - 1;
    let bits = |c: &IBig| c.unsigned_abs().bit_len() as isize;
    let largest = q[..d].iter().map(bits).max().unwrap_or(0);
    let t = (largest - bits(&q[d]) + 2).max(1) as usize;
    let bound = Dyadic {
        num: IBig::ONE << t,
        shift: 0,
    };
    if limit.is_infinite() {
        return bound;
    }
    let l = Real::try_from(limit).expect("finite limit");
    let (num, exp) = (l.repr().significand().clone(), l.repr().exponent());
    let limit = if exp >= 0 {
        Dyadic {
            num: num << exp as usize,
            shift: 0,
        }
    } else {
        Dyadic {
            num,
            shift: (-exp) as usize,
        }
    };
    let (a, b, _) = limit.aligned(&bound);
    if a < b {
        limit
    } else {
        bound
    }
}

/// The single (simple) zero of q in (lo, hi], by bisection on the sign of q.
fn refine(q: &IntPoly, mut lo: Dyadic, mut hi: Dyadic) -> f64 {
    let s_hi = sign_at(q, &hi);
    if s_hi == Ordering::Equal {
        return hi.to_f64();
    }
    loop {
        let (a, b, s) = lo.aligned(&hi);
        // Relative width below 2^-60, or absolute width below the f64 range.
        if (a > IBig::ZERO && ((&b - &a) << 60) < a) || s > 1200 {
            return lo.midpoint(&hi).to_f64();
        }
        let mid = lo.midpoint(&hi);
        match sign_at(q, &mid) {
            Ordering::Equal => return mid.to_f64(),
            s if s == s_hi => hi = mid,
            _ => lo = mid,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::power::{real, Scalar, Series};
    use dashu_ratio::RBig;

    fn r(n: i64, d: u64) -> RBig {
        RBig::from_parts(n.into(), d.into())
    }

    #[test]
    fn sturm_roots_with_multiplicity() {
        let bits = 128;
        let poly = |c: &[i64]| c.iter().map(|&x| real(&r(x, 1), bits)).collect::<Vec<_>>();
        // (x - 1)^2 (x - 3) (x + 2) (3x - 1): positive roots 1/3, 1 (double), 3.
        let a = Series::new(poly(&[1, -2, 1, 0, 0, 0]));
        let b = Series::new(poly(&[-6, -1, 1, 0, 0, 0]));
        let c = Series::new(poly(&[-1, 3, 0, 0, 0, 0]));
        let p = a.mul(&b).mul(&c).c;
        let roots = positive_real_roots(&p, f64::INFINITY);
        assert_eq!(roots.len(), 3, "{roots:?}");
        for (x, want) in roots.iter().zip([1.0 / 3.0, 1.0, 3.0]) {
            assert!((x - want).abs() < 1e-15, "{roots:?}");
        }
        // Limits are inclusive on the right and exclude zero.
        assert_eq!(positive_real_roots(&p, 1.0).len(), 2);
        assert_eq!(positive_real_roots(&p, 0.9).len(), 1);
        let with_zero = Series::new(poly(&[0, -1, 1])).c; // x (x - 1)
        assert_eq!(positive_real_roots(&with_zero, 2.0), vec![1.0]);
        // Two zeros 2^-40 apart are separated.
        let e = real(&r(1, 1 << 40), bits);
        let one = real(&r(1, 1), bits);
        let close = Series::new(vec![
            one.clone(),
            one.zero_like().sub(&one),
            one.zero_like(),
        ])
        .mul(&Series::new(vec![
            one.add(&e),
            one.zero_like().sub(&one),
            one.zero_like(),
        ]))
        .c;
        let roots = positive_real_roots(&close, 10.0);
        assert_eq!(roots.len(), 2, "{roots:?}");
        assert!((roots[1] - roots[0] - 2f64.powi(-40)).abs() < 1e-20);
    }
}
