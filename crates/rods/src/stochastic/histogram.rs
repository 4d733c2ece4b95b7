//! Histogram of ε² samples with their distribution function.

use crate::error::{positive, Error, Result};

/// One bin of [`eps2_histogram`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Eps2Bin {
    /// Centre of the bin.
    pub eps2: f64,
    /// Probability density of ε² in the bin (fraction of all samples / bin width).
    pub density: f64,
    /// Distribution function P(ε² < upper edge of the bin).
    pub cdf: f64,
}

/// Histogram of ε² from the samples `eps` of ε on `bins` equal bins of [0, `max`). Samples
/// with ε² ≥ `max` count in no bin but in the normalization, so the last `cdf` is the
/// fraction of samples below `max`.
pub fn eps2_histogram(eps: &[f64], bins: usize, max: f64) -> Result<Vec<Eps2Bin>> {
    if eps.is_empty() {
        return Err(Error::out_of_range("eps (samples)", "none", ">= 1 sample"));
    }
    if bins == 0 {
        return Err(Error::out_of_range("bins", 0, ">= 1"));
    }
    positive("max", max)?;
    let width = max / bins as f64;
    let mut counts = vec![0usize; bins];
    for e in eps {
        let k = (e * e / width) as usize;
        if k < bins {
            counts[k] += 1;
        }
    }
    let n = eps.len() as f64;
    let mut below = 0;
    Ok(counts
        .iter()
        .enumerate()
        .map(|(k, &c)| {
            below += c;
            Eps2Bin {
                eps2: (k as f64 + 0.5) * width,
                density: c as f64 / (n * width),
                cdf: below as f64 / n,
            }
        })
        .collect())
}

/// The mean of eps^2 over samples of eps and the fraction with eps^2 > 1 (an energy gain
/// from the bath), as printed beside Fig. 3 of Giese.
pub fn eps2_summary(eps: &[f64]) -> (f64, f64) {
    let n = eps.len().max(1) as f64;
    let mean = eps.iter().map(|e| e * e).sum::<f64>() / n;
    let above = eps.iter().filter(|e| **e > 1.0).count() as f64 / n;
    (mean, above)
}

/// The quantiles of eps^2 at the probabilities `levels` (each in [0, 1]) from samples of
/// eps: order statistics of eps^2 interpolated linearly (position p (n - 1) in the sorted
/// sample), as printed beside Fig. 3 of Giese. Empty if there are no samples.
pub fn eps2_quantiles(eps: &[f64], levels: &[f64]) -> Vec<f64> {
    let mut sorted: Vec<f64> = eps.iter().map(|e| e * e).collect();
    sorted.sort_by(f64::total_cmp);
    if sorted.is_empty() {
        return Vec::new();
    }
    let last = (sorted.len() - 1) as f64;
    levels
        .iter()
        .map(|&p| {
            let x = p.clamp(0.0, 1.0) * last;
            let k = x.floor() as usize;
            let next = sorted[(k + 1).min(sorted.len() - 1)];
            sorted[k] + (x - k as f64) * (next - sorted[k])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_by_hand() {
        // eps^2 = 0, 1, 4, 9: the median halfway between 1 and 4, the ends exact
        let q = eps2_quantiles(&[-3.0, 0.0, 2.0, 1.0], &[0.0, 0.5, 0.25, 1.0]);
        assert_eq!(q, vec![0.0, 2.5, 0.75, 9.0]);
        assert!(eps2_quantiles(&[], &[0.5]).is_empty());
    }

    #[test]
    fn counts_by_hand() {
        // ε² = 0.01, 0.25, 0.64, 1.44 (beyond max = 1) on 2 bins of width 0.5
        let h = eps2_histogram(&[0.1, -0.5, 0.8, 1.2], 2, 1.0).unwrap();
        assert_eq!(h.len(), 2);
        assert_eq!(
            h[0],
            Eps2Bin {
                eps2: 0.25,
                density: 2.0 / (4.0 * 0.5),
                cdf: 0.5
            }
        );
        assert_eq!(
            h[1],
            Eps2Bin {
                eps2: 0.75,
                density: 1.0 / (4.0 * 0.5),
                cdf: 0.75
            }
        );
        let integral: f64 = h.iter().map(|b| b.density * 0.5).sum();
        assert_eq!(integral, h[1].cdf);
    }

    #[test]
    fn guards_name_parameters() {
        let e = eps2_histogram(&[], 2, 1.0).unwrap_err().to_string();
        assert!(e.contains("eps"), "{e}");
        let e = eps2_histogram(&[0.5], 0, 1.0).unwrap_err().to_string();
        assert!(e.contains("bins"), "{e}");
        let e = eps2_histogram(&[0.5], 2, 0.0).unwrap_err().to_string();
        assert!(e.contains("max"), "{e}");
    }
}
