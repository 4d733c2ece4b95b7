//! [`BucketTable::eval_slice`] four values at a time with AVX2: the bucket indices and the
//! positions t from the bits of four v* at once, the four coefficient rows loaded and
//! transposed (three 4x4 blocks), Estrin's scheme on the four lanes. Every operation is
//! the scalar one's (IEEE multiplications and additions in the same order, no fused
//! multiply-add), so the results equal [`BucketTable::eval`] bit for bit; a group with a
//! value outside the table goes the scalar way.

use super::{BucketTable, DEGREE};
use std::arch::x86_64::*;

/// f at every x of `xs` into `out` (`outside(x)` beyond the table).
///
/// # Safety
/// The processor must support AVX2.
#[target_feature(enable = "avx2")]
pub(super) unsafe fn eval_slice(
    table: &BucketTable,
    xs: &[f64],
    out: &mut [f64],
    outside: &impl Fn(f64) -> f64,
) {
    const _: () = assert!(DEGREE == 11, "three 4x4 blocks of coefficients");
    let shift = 52 - table.sub_bits as i64;
    let first = (((1023 + table.min_exponent) as u64) << table.sub_bits) as i64;
    let (lo, hi) = (_mm256_set1_pd(table.lo), _mm256_set1_pd(table.hi));
    let shift_count = _mm_cvtsi64_si128(shift);
    let sub_count = _mm_cvtsi64_si128(table.sub_bits as i64);
    let rest_mask = _mm256_set1_epi64x((1i64 << shift) - 1);
    let one_bits = _mm256_set1_epi64x((1023i64) << 52);
    let first_v = _mm256_set1_epi64x(first);
    let (two, three) = (_mm256_set1_pd(2.0), _mm256_set1_pd(3.0));
    let rows = table.coefficients.as_ptr().cast::<f64>();
    let groups = xs.len() / 4;
    for g in 0..groups {
        let at = 4 * g;
        // SAFETY: at + 4 <= xs.len() == out.len().
        let x = _mm256_loadu_pd(xs.as_ptr().add(at));
        let inside = _mm256_and_pd(
            _mm256_cmp_pd(x, lo, _CMP_GE_OQ),
            _mm256_cmp_pd(x, hi, _CMP_LT_OQ),
        );
        if _mm256_movemask_pd(inside) != 0b1111 {
            for k in at..at + 4 {
                out[k] = if table.contains(xs[k]) {
                    table.eval(xs[k])
                } else {
                    outside(xs[k])
                };
            }
            continue;
        }
        let bits = _mm256_castpd_si256(x);
        let index = _mm256_sub_epi64(_mm256_srl_epi64(bits, shift_count), first_v);
        let rest = _mm256_and_si256(bits, rest_mask);
        let m = _mm256_castsi256_pd(_mm256_or_si256(one_bits, _mm256_sll_epi64(rest, sub_count)));
        let t = _mm256_sub_pd(_mm256_mul_pd(two, m), three);
        let mut lanes = [0i64; 4];
        _mm256_storeu_si256(lanes.as_mut_ptr().cast(), index);
        // SAFETY: every lane is inside the table, so its index is a row of it.
        let row = lanes.map(|i| rows.add(i as usize * (DEGREE + 1)));
        let c = |block: usize| {
            let [a, b, cc, d] = row.map(|r| _mm256_loadu_pd(r.add(4 * block)));
            let (t0, t1) = (_mm256_unpacklo_pd(a, b), _mm256_unpackhi_pd(a, b));
            let (t2, t3) = (_mm256_unpacklo_pd(cc, d), _mm256_unpackhi_pd(cc, d));
            [
                _mm256_permute2f128_pd(t0, t2, 0x20),
                _mm256_permute2f128_pd(t1, t3, 0x20),
                _mm256_permute2f128_pd(t0, t2, 0x31),
                _mm256_permute2f128_pd(t1, t3, 0x31),
            ]
        };
        let ([c0, c1, c2, c3], [c4, c5, c6, c7], [c8, c9, c10, c11]) = (c(0), c(1), c(2));
        // Estrin as in super::estrin, operation by operation.
        let (add, mul) = (|a, b| _mm256_add_pd(a, b), |a, b| _mm256_mul_pd(a, b));
        let t2 = mul(t, t);
        let t4 = mul(t2, t2);
        let t8 = mul(t4, t4);
        let pair = |a, b| add(a, mul(b, t));
        let (p0, p2, p4, p6) = (pair(c0, c1), pair(c2, c3), pair(c4, c5), pair(c6, c7));
        let (p8, p10) = (pair(c8, c9), pair(c10, c11));
        let low = add(add(p0, mul(p2, t2)), mul(add(p4, mul(p6, t2)), t4));
        let high = add(p8, mul(p10, t2));
        _mm256_storeu_pd(out.as_mut_ptr().add(at), add(low, mul(high, t8)));
    }
    for k in 4 * groups..xs.len() {
        out[k] = if table.contains(xs[k]) {
            table.eval(xs[k])
        } else {
            outside(xs[k])
        };
    }
}
