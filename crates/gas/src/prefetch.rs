//! Software prefetch: asking the processor for memory a loop will need, so that cache
//! misses overlap instead of following each other. A hint: results never depend on it.

/// Asks the processor to bring every cache line of `records` into cache (a hint: results
/// never depend on it).
#[inline(always)]
pub(crate) fn prefetch<R>(records: &[R]) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        let base = records.as_ptr().cast::<i8>();
        let bytes = std::mem::size_of_val(records);
        let mut offset = 0;
        while offset < bytes {
            // SAFETY: prefetching is a hint that never faults; every address lies in
            // `records`.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(base.add(offset)) };
            offset += 64;
        }
        if bytes > 0 {
            // SAFETY: as above; the last byte of `records`.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(base.add(bytes - 1)) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = records;
}
