//! The two inner loops of g(r) ([`super::pair`]) four pairs at a time with AVX2: the
//! squared distances of one particle to a run of others, of which only those that may be
//! in range are kept (packed to the front of the output by a permutation from a table, no
//! branch per pair), and the bins of the kept ones. Every operation is the scalar one's
//! (IEEE subtractions, multiplications, additions in the same order, no fused
//! multiply-add; square root and division correctly rounded; truncation toward zero), so
//! the counts equal the scalar loops' exactly. They were the bulk of g(r)'s time: about 5
//! cycles per pair looked at, of which 80 % are out of range.

use std::arch::x86_64::*;

/// For each 4-bit mask of lanes, the f32 lanes that move the masked f64 lanes to the
/// front, in order (`_mm256_permutevar8x32_ps`), and how many there are.
const PACK: [([i32; 8], usize); 16] = pack_table();

const fn pack_table() -> [([i32; 8], usize); 16] {
    let mut table = [([0i32; 8], 0usize); 16];
    let mut mask = 0;
    while mask < 16 {
        let mut count = 0;
        let mut lane: i32 = 0;
        while lane < 4 {
            if mask & (1 << lane) != 0 {
                table[mask].0[2 * count] = 2 * lane;
                table[mask].0[2 * count + 1] = 2 * lane + 1;
                count += 1;
            }
            lane += 1;
        }
        table[mask].1 = count;
        mask += 1;
    }
    table
}

/// Writes to the front of `out` the squared distances Σ_a ((x_a[j] − home_a[i]) − shift_a)²,
/// over the i of `homes` and the j of `xs` (D coordinate slices of one length each), that
/// are below `near`, in order, and returns how many. Beyond them `out` may be overwritten.
///
/// # Safety
/// The processor must support AVX2.
#[target_feature(enable = "avx2")]
pub(super) unsafe fn keep_near<const D: usize>(
    xs: [&[f64]; D],
    homes: [&[f64]; D],
    shift: [f64; D],
    near: f64,
    out: &mut [f64],
) -> usize {
    let (n, m) = (xs[0].len(), homes[0].len());
    assert!(xs.iter().all(|x| x.len() == n) && homes.iter().all(|x| x.len() == m));
    assert!(out.len() >= n * m);
    let near4 = _mm256_set1_pd(near);
    let shift4: [__m256d; D] = std::array::from_fn(|a| _mm256_set1_pd(shift[a]));
    let mut kept = 0;
    let groups = n / 4;
    for xi in (0..m).map(|i| std::array::from_fn::<f64, D, _>(|a| homes[a][i])) {
        let xi4: [__m256d; D] = std::array::from_fn(|a| _mm256_set1_pd(xi[a]));
        for g in 0..groups {
            let at = 4 * g;
            let mut r2 = _mm256_setzero_pd();
            for a in 0..D {
                // SAFETY: at + 4 <= n = xs[a].len().
                let x = _mm256_loadu_pd(xs[a].as_ptr().add(at));
                let d = _mm256_sub_pd(_mm256_sub_pd(x, xi4[a]), shift4[a]);
                let d2 = _mm256_mul_pd(d, d);
                // 0 + d² = d² exactly: the first axis may add to zero as the scalar loop does
                r2 = if a == 0 { d2 } else { _mm256_add_pd(r2, d2) };
            }
            let mask = _mm256_movemask_pd(_mm256_cmp_pd(r2, near4, _CMP_LT_OQ)) as usize;
            let (lanes, count) = PACK[mask];
            let packed = _mm256_permutevar8x32_ps(
                _mm256_castpd_ps(r2),
                _mm256_loadu_si256(lanes.as_ptr().cast()),
            );
            // SAFETY: before home i, kept <= i n + at, so kept + 4 <= (i + 1) n <= out.len().
            _mm256_storeu_pd(out.as_mut_ptr().add(kept), _mm256_castps_pd(packed));
            kept += count;
        }
        for j in 4 * groups..n {
            let mut r2 = 0.0;
            for (a, x) in xs.iter().enumerate() {
                let d = (x[j] - xi[a]) - shift[a];
                r2 = if a == 0 { d * d } else { r2 + d * d };
            }
            out[kept] = r2;
            kept += usize::from(r2 < near);
        }
    }
    kept
}

/// Adds one to `counts[bin]` for each squared distance of `squares`: bin = ⌊√r² / dr⌋ (at
/// most `bins`) where √r² < r_max, else `bins`.
///
/// # Safety
/// The processor must support AVX2.
#[target_feature(enable = "avx2")]
pub(super) unsafe fn add_to_bins(
    squares: &[f64],
    r_max: f64,
    dr: f64,
    bins: usize,
    counts: &mut [u64],
) {
    let (r_max4, dr4) = (_mm256_set1_pd(r_max), _mm256_set1_pd(dr));
    let groups = squares.len() / 4;
    for g in 0..groups {
        // SAFETY: 4 g + 4 <= squares.len().
        let r = _mm256_sqrt_pd(_mm256_loadu_pd(squares.as_ptr().add(4 * g)));
        let inside = _mm256_movemask_pd(_mm256_cmp_pd(r, r_max4, _CMP_LT_OQ));
        // r / dr < bins + 1 where inside: no overflow of the 32-bit truncation
        let mut quotients = [0i32; 4];
        _mm_storeu_si128(
            quotients.as_mut_ptr().cast(),
            _mm256_cvttpd_epi32(_mm256_div_pd(r, dr4)),
        );
        for (lane, &q) in quotients.iter().enumerate() {
            let bin = if inside & (1 << lane) != 0 {
                (q as usize).min(bins)
            } else {
                bins
            };
            counts[bin] += 1;
        }
    }
    for &r2 in &squares[4 * groups..] {
        let r = r2.sqrt();
        let bin = if r < r_max {
            ((r / dr) as usize).min(bins)
        } else {
            bins
        };
        counts[bin] += 1;
    }
}
