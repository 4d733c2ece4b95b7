//! The Taylor path of `exact::solve` against the Radau path `exact::solve_radau` (two
//! independent integrators of Eq. (9) of MP2011 in this crate) on a dense grid of v* across
//! every regime and switch point, both criteria, every output. The reference of
//! `tests/reference` (a third method) checks both in `exact_reference.rs`.
//!
//! Tolerance 1e-12 relative: the Radau path at its default tolerance is within 1e-12 of
//! itself at 100x finer tolerance for 1e-4 <= v* <= 1e4 (`laws::exact_law_tolerance_ladder`,
//! docs/collision-laws.md), and within 1.6e-13 of the reference; the Taylor path keeps a
//! local error of 1e-16 per step over <= 60 steps. Observed worst: 3.9e-13 (naive tau_c at
//! v* = 1e4, where the Radau creep to x = 0 takes ~2000 steps), all else <= 1.6e-13.

mod common;

use common::rel;
use restitution::exact::{solve, solve_radau, Collision, Criterion};

const BOUND: f64 = 1e-12;

/// Relative differences (eps, tau_c, x_max, tau_max, x_c); for the naive criterion x_c = 0
/// and its entry is |x_c| / x_max.
fn diffs(a: &Collision, b: &Collision) -> [f64; 5] {
    let end = if a.criterion == Criterion::Naive {
        (a.compression_at_end - b.compression_at_end).abs() / b.max_compression
    } else {
        rel(a.compression_at_end, b.compression_at_end)
    };
    [
        rel(a.eps, b.eps),
        rel(a.duration, b.duration),
        rel(a.max_compression, b.max_compression),
        rel(a.time_of_max_compression, b.time_of_max_compression),
        end,
    ]
}

fn fmt(d: &[f64; 5]) -> String {
    d.map(|x| format!("{x:.1e}")).join(" ")
}

fn log_grid(lo: f64, hi: f64, per_decade: usize) -> Vec<f64> {
    let n = ((hi / lo).log10() * per_decade as f64).round() as usize;
    (0..=n)
        .map(|i| lo * (hi / lo).powf(i as f64 / n as f64))
        .collect()
}

/// v* = 0; 1e-4 .. 1e4 at 10 per decade; both sides of v* = 1 (velocity -> force form and
/// rescaling); v* = 4 (calibration of the slow manifold); 2 .. 4 densely (where the naive
/// collision starts to end on the slow manifold instead of in the root chart).
fn grid() -> Vec<f64> {
    let mut vs = vec![0.0, 0.999, 0.999_999, 1.0, 1.000_001, 1.001, 4.0];
    vs.extend(log_grid(1e-4, 1e4, 10));
    vs.extend((0..=40).map(|i| 2.0 + 0.05 * i as f64));
    vs
}

fn compare(vs: &[f64], criterion: Criterion) -> [f64; 5] {
    let mut worst = [0.0f64; 5];
    let mut failures = Vec::new();
    for &v in vs {
        let a = solve(v, criterion).unwrap_or_else(|e| panic!("solve({v}): {e}"));
        let b = solve_radau(v, criterion).unwrap_or_else(|e| panic!("solve_radau({v}): {e}"));
        let d = diffs(&a, &b);
        for (w, x) in worst.iter_mut().zip(d) {
            *w = w.max(x);
        }
        if d.iter().any(|x| x.is_nan() || *x > BOUND) {
            failures.push(format!(
                "v* = {v}: {}\n  taylor {a:?}\n  radau  {b:?}",
                fmt(&d)
            ));
        }
    }
    println!(
        "{criterion}: {} values, worst (eps, tau_c, x_max, tau_max, x_c) {}",
        vs.len(),
        fmt(&worst)
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    worst
}

#[test]
fn taylor_matches_radau_improved() {
    compare(&grid(), Criterion::Improved);
}

#[test]
fn taylor_matches_radau_naive() {
    compare(&grid(), Criterion::Naive);
}

/// Up to VSTAR_MAX = 1e6 (a Radau collision there takes a few ms).
#[test]
fn taylor_matches_radau_at_the_largest_speeds() {
    let vs = [2e4, 1e5, 1e6];
    compare(&vs, Criterion::Improved);
    compare(&vs, Criterion::Naive);
}

/// The naive eps is P* v*^(-10) exactly once the collision ends on the slow manifold
/// (scale invariance, crate::manifold): the Radau path, which knows nothing of it, gives
/// the same power law.
#[test]
fn naive_power_law_beyond_the_manifold_threshold() {
    let base = solve_radau(10.0, Criterion::Naive).unwrap().eps * 1e10;
    for v in [5.0, 30.0, 300.0, 1e4] {
        let radau = solve_radau(v, Criterion::Naive).unwrap().eps * v.powi(10);
        let taylor = solve(v, Criterion::Naive).unwrap().eps * v.powi(10);
        assert!(rel(radau, base) < 1e-12, "radau at {v}: {radau} vs {base}");
        assert!(
            rel(taylor, base) < 1e-12,
            "taylor at {v}: {taylor} vs {base}"
        );
    }
}

/// Where the two paths differ most (the naive tau_c at large v*, 8e-13 at 1e6) the Radau
/// path is the one in error: at 100x finer tolerance it moves onto the Taylor path (the
/// slow-manifold ending), to <= 5e-15 observed. Bound 1e-13: the change of the Radau
/// duration from rtol 1e-13 to 1e-14 is <= 3e-14 at these v*.
#[test]
fn naive_duration_at_large_vstar_against_fine_radau() {
    use restitution::exact::solve_with_tolerance;
    for v in [100.0, 1e4, 1e6] {
        let taylor = solve(v, Criterion::Naive).unwrap().duration;
        let fine = solve_with_tolerance(v, Criterion::Naive, 1e-14)
            .unwrap()
            .duration;
        println!("v* = {v}: rel. diff. {:.1e}", rel(taylor, fine));
        assert!(rel(taylor, fine) <= 1e-13, "v* = {v}: {taylor} vs {fine}");
    }
}
