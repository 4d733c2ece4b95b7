//! Exact sums of floating-point numbers: the same bits whatever the order of the terms.
//!
//! A distributed engine adds per-cell quantities (mass, momentum, energy dissipated) that
//! live on different ranks and threads; a floating-point sum depends on the order and the
//! grouping of its terms, so the run would change with the number of ranks. [`ExactSum`]
//! keeps the sum as an exact fixed-point integer (every f64 is an integer multiple of
//! 2^-1074), in 32-bit digits held in i64 limbs, so partial sums from any split of the terms
//! add to the same integer, which is rounded to f64 once, to nearest.

/// Bits per digit; a limb holds its digit plus carries of up to 2^31 additions.
const DIGIT_BITS: u32 = 32;
/// Digits spanning 2^-1074 ..= 2^1024 (2098 bits), plus two for carries beyond.
pub const LIMBS: usize = 68;
/// Additions between carry propagations: each adds less than 2^32 in magnitude to a limb,
/// so limbs stay below 2^62.
const ADDS_BETWEEN_CARRIES: u32 = 1 << 29;

/// An exact sum of f64 values (finite ones; a non-finite term makes the sum NaN).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExactSum {
    limbs: [i64; LIMBS],
    adds: u32,
    /// A term was NaN or infinite.
    non_finite: bool,
}

impl Default for ExactSum {
    fn default() -> Self {
        ExactSum {
            limbs: [0; LIMBS],
            adds: 0,
            non_finite: false,
        }
    }
}

impl ExactSum {
    /// Adds `x` exactly.
    #[inline]
    pub fn add(&mut self, x: f64) {
        if x == 0.0 {
            return;
        }
        if !x.is_finite() {
            self.non_finite = true;
            return;
        }
        let bits = x.to_bits();
        let exponent = ((bits >> 52) & 0x7ff) as u32;
        let fraction = bits & ((1u64 << 52) - 1);
        // x = mantissa * 2^(position - 1074).
        let (mantissa, position) = if exponent == 0 {
            (fraction, 0)
        } else {
            (fraction | (1u64 << 52), exponent - 1)
        };
        let limb = (position / DIGIT_BITS) as usize;
        let shifted = (mantissa as u128) << (position % DIGIT_BITS);
        let digits = [
            (shifted & 0xffff_ffff) as i64,
            ((shifted >> 32) & 0xffff_ffff) as i64,
            (shifted >> 64) as i64,
        ];
        if x < 0.0 {
            digits
                .iter()
                .enumerate()
                .for_each(|(k, d)| self.limbs[limb + k] -= d);
        } else {
            digits
                .iter()
                .enumerate()
                .for_each(|(k, d)| self.limbs[limb + k] += d);
        }
        self.adds += 1;
        if self.adds >= ADDS_BETWEEN_CARRIES {
            self.carry();
        }
    }

    /// Adds the exact sum `other` (exactly).
    pub fn merge(&mut self, other: &ExactSum) {
        let mut other = other.clone();
        other.carry();
        self.carry();
        for (a, b) in self.limbs.iter_mut().zip(&other.limbs) {
            *a += b;
        }
        self.non_finite |= other.non_finite;
        self.carry();
    }

    /// Propagates carries: every limb but the last to 0 <= limb < 2^32 (the last carries
    /// the sign), a representation unique to the value.
    fn carry(&mut self) {
        for k in 0..LIMBS - 1 {
            let carry = self.limbs[k] >> DIGIT_BITS; // floor division
            self.limbs[k] -= carry << DIGIT_BITS;
            self.limbs[k + 1] += carry;
        }
        self.adds = 0;
    }

    /// The limbs in their unique (carried) form, one more value saying whether a term was
    /// not finite: what ranks add up element-wise to sum their sums
    /// ([`ExactSum::from_limbs`] of the element-wise sum of up to 2^30 ranks' limbs).
    pub fn to_limbs(&self) -> Vec<i64> {
        let mut me = self.clone();
        me.carry();
        let mut limbs = me.limbs.to_vec();
        limbs.push(me.non_finite as i64);
        limbs
    }

    /// The sum whose limbs (element-wise sums of [`ExactSum::to_limbs`]) are `limbs`.
    pub fn from_limbs(limbs: &[i64]) -> ExactSum {
        assert_eq!(limbs.len(), LIMBS + 1, "limbs of an exact sum");
        let mut sum = ExactSum::default();
        sum.limbs.copy_from_slice(&limbs[..LIMBS]);
        sum.non_finite = limbs[LIMBS] != 0;
        sum.carry();
        sum
    }

    /// The sum rounded to the nearest f64 (ties to even); NaN if a term was not finite,
    /// infinite beyond the range of f64.
    pub fn value(&self) -> f64 {
        if self.non_finite {
            return f64::NAN;
        }
        let mut me = self.clone();
        me.carry();
        let negative = me.limbs[LIMBS - 1] < 0;
        if negative {
            // Two's complement of the whole number, limb by limb, then carried again.
            me.limbs.iter_mut().for_each(|l| *l = -*l);
            me.carry();
        }
        let Some(top) = me.limbs.iter().rposition(|&l| l != 0) else {
            return 0.0;
        };
        // The top three digits (at least 65 significant bits) and a sticky bit for any
        // below: rounding this u128 to f64 rounds the whole number.
        let low = top.saturating_sub(2);
        let mut head: u128 = 0;
        for k in (low..=top).rev() {
            head = (head << DIGIT_BITS) | me.limbs[k] as u128;
        }
        let sticky = me.limbs[..low].iter().any(|&l| l != 0);
        // Make room for the sticky bit below the digits taken.
        head = (head << 1) | sticky as u128;
        let magnitude =
            scale_by_power_of_two(head as f64, (low as i32) * DIGIT_BITS as i32 - 1074 - 1);
        if negative {
            -magnitude
        } else {
            magnitude
        }
    }
}

/// Items per task of [`sums_of`]: below this a sum stays on the calling thread (for 1000
/// items the split into tasks, each with its own sums, cost 20 times the sum itself).
const ITEMS_PER_TASK: usize = 4096;

/// `n` exact sums over `items`, in parallel: `terms` adds an item's terms to the sums (the
/// same bits whatever the split over threads).
pub fn sums_of<T: Sync>(
    items: &[T],
    n: usize,
    terms: impl Fn(&T, &mut [ExactSum]) + Sync,
) -> Vec<ExactSum> {
    use rayon::prelude::*;
    items
        .par_iter()
        .with_min_len(ITEMS_PER_TASK)
        .fold(
            || vec![ExactSum::default(); n],
            |mut sums, item| {
                terms(item, &mut sums);
                sums
            },
        )
        .reduce(
            || vec![ExactSum::default(); n],
            |mut a, b| {
                a.iter_mut().zip(&b).for_each(|(x, y)| x.merge(y));
                a
            },
        )
}

/// x 2^k, exact while the result is a normal f64 (applied in steps that stay in range).
fn scale_by_power_of_two(mut x: f64, mut k: i32) -> f64 {
    while k > 0 {
        let step = k.min(1000);
        x *= f64::from_bits(((1023 + step) as u64) << 52);
        k -= step;
    }
    while k < 0 {
        let step = (-k).min(1000);
        x *= f64::from_bits(((1023 - step) as u64) << 52);
        k += step;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sum(values: &[f64]) -> f64 {
        let mut s = ExactSum::default();
        values.iter().for_each(|&x| s.add(x));
        s.value()
    }

    /// Values whose exact sum is known: cancellation that floating point loses, integers,
    /// the extremes of the range, subnormals, signs.
    #[test]
    fn sums_are_exact() {
        assert_eq!(sum(&[1e100, 1.0, -1e100]), 1.0);
        // 0.1, 0.2, 0.3 are 3602879701896397 2^-55, 3602879701896397 2^-54 and
        // 5404319552844595 2^-54: their sum is 2^-55 (floating point: 2^-54).
        assert_eq!(sum(&[0.1, 0.2, -0.3]), 2f64.powi(-55));
        let big: Vec<f64> = (1..=100_000).map(|i| i as f64).collect();
        assert_eq!(sum(&big), 5_000_050_000.0);
        assert_eq!(sum(&[f64::MAX, -f64::MAX, 5e-324]), 5e-324);
        assert_eq!(sum(&[5e-324, 5e-324]), 1e-323);
        assert_eq!(sum(&[f64::MAX, f64::MAX]), f64::INFINITY);
        assert_eq!(sum(&[-3.5, 1.25]), -2.25);
        assert_eq!(sum(&[]), 0.0);
        assert!(sum(&[1.0, f64::NAN]).is_nan());
        // 1 + 2^-53 + 2^-53: the exact 1 + 2^-52 (floating point gives 1).
        let half_ulp = f64::EPSILON / 2.0;
        assert_eq!(sum(&[1.0, half_ulp, half_ulp]), 1.0 + f64::EPSILON);
        // Round to nearest even at exactly half an ulp, away from the tie with a sticky bit.
        assert_eq!(sum(&[1.0, half_ulp]), 1.0);
        assert_eq!(sum(&[1.0, half_ulp, 1e-300]), 1.0 + f64::EPSILON);
    }

    /// Every order and every split into partial sums gives the same bits, and they agree
    /// with a compensated (Neumaier) sum to within one rounding.
    #[test]
    fn order_and_split_do_not_matter() {
        let mut state = 3u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            state
        };
        let values: Vec<f64> = (0..2000)
            .map(|_| {
                let r = next();
                let mantissa = (r >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                mantissa * 2f64.powi((next() % 80) as i32 - 40)
            })
            .collect();
        let whole = sum(&values);
        let mut reversed = values.clone();
        reversed.reverse();
        assert_eq!(sum(&reversed).to_bits(), whole.to_bits());
        for parts in [2, 3, 7, 64] {
            let size = values.len().div_ceil(parts);
            let mut limbs = vec![0i64; LIMBS + 1];
            for chunk in values.chunks(size) {
                let mut s = ExactSum::default();
                chunk.iter().for_each(|&x| s.add(x));
                limbs
                    .iter_mut()
                    .zip(s.to_limbs())
                    .for_each(|(a, b)| *a += b);
            }
            assert_eq!(
                ExactSum::from_limbs(&limbs).value().to_bits(),
                whole.to_bits()
            );
        }
        let (mut s, mut c) = (0.0f64, 0.0f64);
        for &x in &values {
            let t = s + x;
            c += if s.abs() >= x.abs() {
                (s - t) + x
            } else {
                (x - t) + s
            };
            s = t;
        }
        let neumaier = s + c;
        assert!((neumaier - whole).abs() <= f64::EPSILON * whole.abs());
    }
}
