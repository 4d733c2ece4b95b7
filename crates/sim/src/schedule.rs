//! The sampling schedule: where a run stops to observe.

/// What the values of a schedule's targets measure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    Time,
    /// Collisions per particle (each collision counts for two particles).
    CollisionsPerParticle,
}

/// The stops of a run, in order, and what their values measure.
#[derive(Debug, Clone, PartialEq)]
pub struct Schedule {
    pub targets: Vec<Target>,
    pub measure: Measure,
}

impl Schedule {
    /// A sample at each of `values` (increasing), no histograms.
    pub fn samples_at(values: &[f64], measure: Measure) -> Self {
        Schedule {
            targets: schedule(values, &[]),
            measure,
        }
    }

    /// The samples of the whole schedule.
    pub fn samples(&self) -> usize {
        self.targets.iter().filter(|t| t.sample.is_some()).count()
    }

    /// The samples among the first `done` targets.
    pub fn samples_before(&self, done: usize) -> usize {
        self.targets[..done.min(self.targets.len())]
            .iter()
            .filter(|t| t.sample.is_some())
            .count()
    }
}

/// A point where the run stops to observe: a row of the time series, a velocity histogram
/// or both.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Target {
    /// Collisions per particle or time (the unit of the stop criterion).
    pub value: f64,
    /// Index of the sample taken here.
    pub sample: Option<usize>,
    /// Whether a velocity histogram is taken here.
    pub histogram: bool,
}

/// `count` sample targets from 0 to `end` inclusive: equally spaced, or (log) 0 and then
/// log-spaced from end/1000 to end.
pub fn sample_targets(end: f64, count: usize, log: bool) -> Vec<f64> {
    let first = end * 1e-3;
    (0..count)
        .map(|k| {
            let x = k as f64 / (count - 1) as f64;
            match (k, log) {
                (0, _) => 0.0,
                (_, true) if k == count - 1 => end,
                (_, true) => {
                    first * (end / first).powf((k as f64 - 1.0) / (count - 2).max(1) as f64)
                }
                (_, false) => end * x,
            }
        })
        .collect()
}

/// The sample targets and the histogram targets merged in order (a histogram at a sample
/// target is taken at that stop).
pub fn schedule(samples: &[f64], histograms: &[f64]) -> Vec<Target> {
    let mut histograms = histograms.to_vec();
    histograms.sort_by(f64::total_cmp);
    let mut h = histograms.into_iter().peekable();
    let mut out = Vec::with_capacity(samples.len() + h.len());
    for (k, &value) in samples.iter().enumerate() {
        while let Some(x) = h.next_if(|&x| x < value) {
            out.push(Target {
                value: x,
                sample: None,
                histogram: true,
            });
        }
        out.push(Target {
            value,
            sample: Some(k),
            histogram: h.next_if(|&x| x == value).is_some(),
        });
    }
    out.extend(h.map(|value| Target {
        value,
        sample: None,
        histogram: true,
    }));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_targets_end_exactly_at_the_end() {
        for count in [2, 3, 12, 200] {
            for log in [true, false] {
                let t = sample_targets(7.3, count, log);
                assert_eq!(t.len(), count);
                assert_eq!((t[0], t[count - 1]), (0.0, 7.3), "{count} {log}");
                assert!(t.windows(2).all(|w| w[0] < w[1]), "{t:?}");
            }
        }
    }

    #[test]
    fn histogram_targets_merge_into_the_samples() {
        let plan = schedule(&[0.0, 1.0, 2.0], &[2.0, 0.5, 0.0, 1.5]);
        let got: Vec<(f64, Option<usize>, bool)> = plan
            .iter()
            .map(|t| (t.value, t.sample, t.histogram))
            .collect();
        assert_eq!(
            got,
            [
                (0.0, Some(0), true),
                (0.5, None, true),
                (1.0, Some(1), false),
                (1.5, None, true),
                (2.0, Some(2), true),
            ]
        );
        assert_eq!(schedule(&[0.0, 1.0], &[]).len(), 2);
    }
}
