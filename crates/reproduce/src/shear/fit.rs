//! The growth rate of a mode from the seed-averaged energies (the fit of the module
//! documentation, with its jackknife error), and the straight line through a case's shells.

use super::cases::{simulate, Case, Run};
use crate::mean_and_error;
use gas::theory::HcsTransport;
use sim::error::Result;

/// The lowest shell's energy, in units of N, at which the fit window ends.
pub(super) const NONLINEAR_FRACTION: f64 = 1.0 / 200.0;

/// The fit of the module documentation over the points (c, E > 0): the sum of squared
/// differences of ln E, profiled over lambda (golden section on (0, 12 / c_max]) with A and
/// B at each lambda from iteratively reweighted linear least squares (weights 1 / model^2,
/// which makes the residuals relative, i.e. those of ln E to first order). None for fewer
/// than 6 points; else (lambda, B).
pub(super) fn fit_growth(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    if points.len() < 6 || points.iter().any(|p| p.1.is_nan() || p.1 <= 0.0) {
        return None;
    }
    // (residual of ln E, A, B) at fixed lambda.
    let at = |lambda: f64| -> (f64, f64, f64) {
        let mut model: Vec<f64> = points.iter().map(|p| p.1).collect();
        let (mut a, mut c0) = (1.0, 0.0);
        for _ in 0..6 {
            let (mut suu, mut su, mut s1, mut sue, mut se) = (0.0, 0.0, 0.0, 0.0, 0.0);
            for (&(c, e), &m) in points.iter().zip(&model) {
                let (u, w) = ((lambda * c).exp(), 1.0 / (m * m));
                suu += w * u * u;
                su += w * u;
                s1 += w;
                sue += w * u * e;
                se += w * e;
            }
            // Normal equations of E = A u + C (C = -B).
            let det = suu * s1 - su * su;
            a = (sue * s1 - su * se) / det;
            c0 = (suu * se - su * sue) / det;
            for (m, &(c, e)) in model.iter_mut().zip(points) {
                let fitted = a * (lambda * c).exp() + c0;
                *m = if fitted > 0.0 { fitted } else { e };
            }
        }
        let residual = points
            .iter()
            .map(|&(c, e)| {
                let fitted = a * (lambda * c).exp() + c0;
                if fitted > 0.0 {
                    (fitted.ln() - e.ln()).powi(2)
                } else {
                    f64::INFINITY
                }
            })
            .sum();
        (residual, a, -c0)
    };
    let c_max = points.last().map(|p| p.0).unwrap_or(1.0).max(1e-9);
    let (mut lo, mut hi) = (1e-4 / c_max, 12.0 / c_max);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if at(x1).0 < at(x2).0 {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    let lambda = 0.5 * (lo + hi);
    Some((lambda, at(lambda).2))
}

/// A shell's measured growth against theory.
pub(super) struct ShellResult {
    pub(super) k_over_kc: f64,
    /// The growth per collision of the seed-averaged energy and its jackknife error; None
    /// where the shell grew less than e^[`MIN_GROWTH`] in the window.
    pub(super) measured: Option<(f64, f64)>,
    pub(super) theory: f64,
}

/// The least growth exponent lambda c_end that separates a shell's growth from its noise
/// term (E grows at least 4.5-fold in the window).
pub(super) const MIN_GROWTH: f64 = 1.5;

/// The mean over `runs` (all but `skip`) of each shell's energy at each sample, and the
/// mean collisions per particle.
pub(super) fn averaged(runs: &[Run], skip: Option<usize>) -> (Vec<f64>, Vec<Vec<f64>>) {
    let kept: Vec<&Run> = runs
        .iter()
        .enumerate()
        .filter(|(i, _)| Some(*i) != skip)
        .map(|(_, r)| r)
        .collect();
    let samples = kept.iter().map(|r| r.collisions.len()).min().unwrap_or(0);
    let n = kept.len() as f64;
    let collisions = (0..samples)
        .map(|i| kept.iter().map(|r| r.collisions[i]).sum::<f64>() / n)
        .collect();
    let energies = (0..kept[0].energies.len())
        .map(|shell| {
            (0..samples)
                .map(|i| kept.iter().map(|r| r.energies[shell][i]).sum::<f64>() / n)
                .collect()
        })
        .collect();
    (collisions, energies)
}

/// The growth rate of every shell of `case`: the fit of the seed-averaged energies up to
/// where the lowest shell's mean reaches N x [`NONLINEAR_FRACTION`], with the jackknife
/// error over seeds (each seed left out in turn).
pub(super) fn growth_rates(case: &Case) -> Result<(Vec<ShellResult>, Vec<Run>, f64)> {
    let runs: Vec<Run> = (0..case.seeds)
        .map(|s| simulate(case, 1000 + s))
        .collect::<Result<_>>()?;
    let theory = case.theory();
    let kc = theory.critical_wave_number();
    let ceiling = NONLINEAR_FRACTION * runs[0].particles as f64;
    let (collisions, energies) = averaged(&runs, None);
    let end = energies[0]
        .iter()
        .position(|&e| e > ceiling)
        .unwrap_or(collisions.len());
    let c_end = collisions[end.saturating_sub(1)];
    let fit = |collisions: &[f64], energies: &[f64]| -> Option<f64> {
        let points: Vec<(f64, f64)> = collisions[..end]
            .iter()
            .copied()
            .zip(energies[..end].iter().copied())
            .collect();
        fit_growth(&points).map(|f| f.0)
    };
    let leave_one_out: Vec<(Vec<f64>, Vec<Vec<f64>>)> =
        (0..runs.len()).map(|i| averaged(&runs, Some(i))).collect();
    let mut out = Vec::new();
    for (shell, &k) in runs[0].wave_numbers.iter().enumerate() {
        let measured = fit(&collisions, &energies[shell])
            .filter(|&lambda| lambda * c_end >= MIN_GROWTH)
            .and_then(|lambda| {
                let others: Vec<f64> = leave_one_out
                    .iter()
                    .filter_map(|(c, e)| fit(c, &e[shell]))
                    .collect();
                let n = others.len() as f64;
                if others.len() < 2 {
                    return None;
                }
                let mean = others.iter().sum::<f64>() / n;
                let variance =
                    (n - 1.0) / n * others.iter().map(|x| (x - mean).powi(2)).sum::<f64>();
                Some((lambda, variance.sqrt()))
            });
        out.push(ShellResult {
            k_over_kc: k / kc,
            measured,
            theory: 2.0 * theory.transverse_growth_per_collision(k),
        });
    }
    Ok((out, runs, c_end))
}

/// The samples before the lowest shell of `run` exceeds N x [`NONLINEAR_FRACTION`].
pub(super) fn linear_window(run: &Run) -> usize {
    let ceiling = NONLINEAR_FRACTION * run.particles as f64;
    run.energies[0]
        .iter()
        .position(|&e| e > ceiling)
        .unwrap_or(run.energies[0].len())
}

/// A straight line y = a - b x through the resolved shells of a case, x = (k/k_c)^2 and
/// y = lambda / (zeta/omega) (theory: a = b = 1), weighted with the jackknife errors.
pub(super) struct Line {
    pub(super) intercept: f64,
    pub(super) intercept_error: f64,
    pub(super) slope: f64,
    pub(super) slope_error: f64,
}

pub(super) fn straight_line(shells: &[ShellResult], scale: f64) -> Option<Line> {
    let points: Vec<(f64, f64, f64)> = shells
        .iter()
        .filter_map(|s| {
            s.measured
                .filter(|m| m.1 > 0.0)
                .map(|(m, e)| (s.k_over_kc.powi(2), m / scale, 1.0 / (e / scale).powi(2)))
        })
        .collect();
    if points.len() < 3 {
        return None;
    }
    let (mut sw, mut sx, mut sy, mut sxx, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for &(x, y, w) in &points {
        sw += w;
        sx += w * x;
        sy += w * y;
        sxx += w * x * x;
        sxy += w * x * y;
    }
    let det = sw * sxx - sx * sx;
    let slope = (sw * sxy - sx * sy) / det;
    let intercept = (sxx * sy - sx * sxy) / det;
    Some(Line {
        intercept,
        intercept_error: (sxx / det).sqrt(),
        slope: -slope,
        slope_error: (sw / det).sqrt(),
    })
}

/// T / T_Haff(t) averaged over `runs` at each sample (T_Haff with the theory's cooling rate
/// at T0 = 1), with the mean collisions per particle.
pub(super) fn haff_ratio(runs: &[Run], theory: &HcsTransport) -> Vec<(f64, f64, f64)> {
    let samples = runs.iter().map(|r| r.times.len()).min().unwrap_or(0);
    (0..samples)
        .map(|i| {
            let ratios: Vec<f64> = runs
                .iter()
                .map(|r| {
                    let haff = 1.0 / (1.0 + 0.5 * theory.cooling_rate * r.times[i]).powi(2);
                    r.temperatures[i] / haff
                })
                .collect();
            let c = runs.iter().map(|r| r.collisions[i]).sum::<f64>() / runs.len() as f64;
            let (mean, error) = mean_and_error(&ratios);
            (c, mean, error)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fit recovers lambda and B of noiseless data E = A e^{lambda c} - B, for a fast
    /// mode and for a slow one whose noise term dominates early.
    #[test]
    fn fit_recovers_a_known_growth() {
        for (lambda, b) in [(0.09, 0.07), (0.03, 1.3)] {
            let points: Vec<(f64, f64)> = (0..60)
                .map(|i| {
                    let c = i as f64;
                    (c, (1.0 + b) * (lambda * c).exp() - b)
                })
                .collect();
            let (fitted, noise) = fit_growth(&points).unwrap();
            assert!((fitted / lambda - 1.0).abs() < 1e-6, "{fitted} vs {lambda}");
            assert!((noise / b - 1.0).abs() < 1e-4, "{noise} vs {b}");
        }
    }
}
