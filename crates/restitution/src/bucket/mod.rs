//! Piecewise polynomials on binary-exponent buckets: a fast table for a positive, smoothly
//! varying function on a range of many octaves, evaluated without any logarithm.
//!
//! The bucket of x is read off its IEEE-754 bits: the binary exponent selects the octave, the
//! leading mantissa bits one of `2^sub_bits` equal parts of it; the remaining mantissa bits
//! are the position t in [-1, 1) inside the bucket, where a polynomial of low degree (a
//! Chebyshev interpolant written in monomials) gives f. Because a bucket spans at most a
//! factor 1 + 2^-sub_bits in x, f changes little across it and the interpolant has a small
//! *relative* error even where f spans many decades over the whole range.

#[cfg(target_arch = "x86_64")]
mod avx2;

/// Polynomial degree per bucket.
pub const DEGREE: usize = 11;

/// f on [2^min_exponent, 2^max_exponent), bucketed by exponent and leading mantissa bits.
#[derive(Debug, Clone)]
pub struct BucketTable {
    min_exponent: i32,
    max_exponent: i32,
    sub_bits: u32,
    lo: f64,
    hi: f64,
    coefficients: Vec<[f64; DEGREE + 1]>,
}

impl BucketTable {
    /// Interpolates `f` on [2^min_exponent, 2^max_exponent) with 2^sub_bits buckets per
    /// octave (`min_exponent` > -1022 so that every x in range is a normal number).
    pub fn new(
        min_exponent: i32,
        max_exponent: i32,
        sub_bits: u32,
        f: impl Fn(f64) -> f64,
    ) -> Self {
        assert!(min_exponent > -1022 && max_exponent < 1023 && min_exponent < max_exponent);
        let parts = 1usize << sub_bits;
        let coefficients = (min_exponent..max_exponent)
            .flat_map(|e| (0..parts).map(move |k| (e, k)))
            .map(|(e, k)| {
                let octave = 2f64.powi(e);
                let width = octave / parts as f64;
                let left = octave + k as f64 * width;
                chebyshev_monomials(|t| f(left + 0.5 * (t + 1.0) * width))
            })
            .collect();
        BucketTable {
            min_exponent,
            max_exponent,
            sub_bits,
            lo: 2f64.powi(min_exponent),
            hi: 2f64.powi(max_exponent),
            coefficients,
        }
    }

    /// Whether x lies in the table (false for NaN).
    #[inline]
    pub fn contains(&self, x: f64) -> bool {
        x >= self.lo && x < self.hi
    }

    /// f(x) for x in the table (check with [`BucketTable::contains`] first).
    #[inline(always)]
    pub fn eval(&self, x: f64) -> f64 {
        debug_assert!(self.contains(x));
        let bits = x.to_bits();
        let shift = 52 - self.sub_bits;
        // The biased exponent and the leading mantissa bits, read together, count buckets
        // from the first bucket of 2^min_exponent (x > 0: the sign bit is 0).
        let first = ((1023 + self.min_exponent) as u64) << self.sub_bits;
        let index = ((bits >> shift) - first) as usize;
        let rest = bits & ((1u64 << shift) - 1);
        // t = rest / 2^(shift - 1) - 1, exactly, without a u64 -> f64 conversion (a slow
        // instruction sequence on x86_64 before AVX-512): m = 1 + rest / 2^shift in [1, 2)
        // from its bits, and 2 m - 3 is exact.
        let m = f64::from_bits((1023u64 << 52) | (rest << self.sub_bits));
        let t = 2.0 * m - 3.0;
        estrin(&self.coefficients[index], t)
    }

    /// f at every x of `xs` into `out`, `outside(x)` where x is not in the table,
    /// bit-identical to [`BucketTable::eval`]: four values at a time on x86_64 processors
    /// with AVX2 ([`avx2`]), else one loop with the table's constants in registers.
    pub fn eval_slice(&self, xs: &[f64], out: &mut [f64], outside: impl Fn(f64) -> f64) {
        assert_eq!(xs.len(), out.len(), "eval_slice: lengths differ");
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor supports AVX2 (checked just above).
            unsafe { avx2::eval_slice(self, xs, out, &outside) };
            return;
        }
        for (o, &x) in out.iter_mut().zip(xs) {
            *o = if self.contains(x) {
                self.eval(x)
            } else {
                outside(x)
            };
        }
    }

    /// Memory held by the coefficients.
    pub fn bytes(&self) -> usize {
        self.coefficients.len() * std::mem::size_of::<[f64; DEGREE + 1]>()
    }

    pub fn range(&self) -> (f64, f64) {
        (self.lo, self.hi)
    }

    pub fn exponents(&self) -> (i32, i32) {
        (self.min_exponent, self.max_exponent)
    }
}

/// The polynomial c_0 + c_1 t + ... + c_11 t^11 by Estrin's scheme: pairs, then powers
/// t^2, t^4, t^8 combine them in a tree of depth 4 instead of Horner's chain of 11 dependent
/// steps, so that evaluations of a loop overlap in the processor (3x the throughput of
/// Horner in `haff bench cor`). For |t| <= 1 and the decaying coefficients of a Chebyshev
/// interpolant the rounding is that of Horner, a few ulp.
#[inline]
fn estrin(c: &[f64; DEGREE + 1], t: f64) -> f64 {
    const _: () = assert!(DEGREE == 11, "estrin is written for 12 coefficients");
    let t2 = t * t;
    let t4 = t2 * t2;
    let t8 = t4 * t4;
    let pair = |k: usize| c[k] + c[k + 1] * t;
    let low = pair(0) + pair(2) * t2 + (pair(4) + pair(6) * t2) * t4;
    let high = pair(8) + pair(10) * t2;
    low + high * t8
}

/// Chebyshev interpolant of f on [-1, 1] at `DEGREE + 1` Chebyshev nodes, converted to
/// monomial coefficients (well conditioned for this low degree on [-1, 1]).
pub fn chebyshev_monomials(f: impl Fn(f64) -> f64) -> [f64; DEGREE + 1] {
    let n = DEGREE + 1;
    let angle = |j: usize| std::f64::consts::PI * (j as f64 + 0.5) / n as f64;
    let values: Vec<f64> = (0..n).map(|j| f(angle(j).cos())).collect();
    let mut out = [0.0; DEGREE + 1];
    // T_0 = 1, T_1 = t, T_{k+1} = 2 t T_k - T_{k-1}, as monomial coefficient arrays.
    let (mut prev, mut cur) = ([0.0; DEGREE + 1], [0.0; DEGREE + 1]);
    prev[0] = 1.0;
    cur[1] = 1.0;
    for k in 0..n {
        let sum: f64 = (0..n)
            .map(|j| values[j] * (k as f64 * angle(j)).cos())
            .sum();
        let ck = sum * 2.0 / n as f64 * if k == 0 { 0.5 } else { 1.0 };
        let tk = if k == 0 { &prev } else { &cur };
        for (o, t) in out.iter_mut().zip(tk) {
            *o += ck * t;
        }
        if k >= 1 {
            let mut next = [0.0; DEGREE + 1];
            for p in 0..DEGREE {
                next[p + 1] = 2.0 * cur[p];
            }
            for (nx, pv) in next.iter_mut().zip(&prev) {
                *nx -= pv;
            }
            prev = cur;
            cur = next;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduces_smooth_functions_over_many_octaves() {
        // Smooth on the scale of a bucket: varies with ln x, not x.
        let f = |x: f64| (1.0 + x).powf(-10.0 / 3.0) * (1.0 + 0.1 * x.ln().sin());
        let table = BucketTable::new(-20, 20, 3, f);
        for i in 0..10_000 {
            let x = 2f64.powf(-20.0 + 40.0 * (i as f64 + 0.5) / 10_000.0);
            let r = (table.eval(x) - f(x)).abs() / f(x);
            assert!(r < 1e-13, "x = {x}: {r}");
        }
        // Bucket edges.
        for e in -20..20 {
            let x = 2f64.powi(e);
            assert!((table.eval(x) - f(x)).abs() / f(x) < 1e-13);
        }
        assert!(!table.contains(f64::NAN) && !table.contains(2f64.powi(20)));
    }

    #[test]
    fn chebyshev_is_exact_for_polynomials() {
        let f = |t: f64| 1.0 - 2.0 * t + 3.0 * t.powi(5) - t.powi(11);
        let c = chebyshev_monomials(f);
        for i in 0..=100 {
            let t = -1.0 + 0.02 * i as f64;
            let p = c.iter().rev().fold(0.0, |acc, ck| acc * t + ck);
            assert!((p - f(t)).abs() < 1e-14, "t = {t}: {p} vs {}", f(t));
        }
    }
}
