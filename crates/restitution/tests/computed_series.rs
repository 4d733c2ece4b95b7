//! The h_k computed by the computer-algebra chain (`haff-series`) against the exact law:
//! the independent proof of their digits (figures measured with this test, `--nocapture`).

use restitution::exact::{solve_with_tolerance, Criterion};
use restitution::series::Series;

fn exact(v: f64) -> f64 {
    solve_with_tolerance(v, Criterion::Improved, 1e-14)
        .unwrap()
        .eps
}

/// Truncation at K = 60 leaves |h_61| v*^61 ~ 1e-33 at v* = 0.3: the difference is the
/// error of the coefficients plus that of the exact law (~1e-15).
#[test]
fn series_of_order_60_matches_the_exact_law() {
    let series = Series::computed(60).unwrap();
    for v in [0.05, 0.1, 0.2, 0.3, 0.4] {
        let d = (series.eval(v) - exact(v)).abs();
        eprintln!("v* = {v}: |series:60 - exact| = {d:.2e}");
        assert!(d < 1e-13, "v* = {v}: {d}");
    }
}

/// With the computed h_2 the residual of Table V's h_2 (2e-9) is gone: series:20 matches
/// the exact law to round-off at small v*.
#[test]
fn computed_series_20_is_exact_at_small_vstar() {
    let series = Series::computed(20).unwrap();
    for v in [0.01, 0.05, 0.1] {
        let d = (series.eval(v) - exact(v)).abs();
        assert!(d < 1e-14, "v* = {v}: {d}");
    }
}

/// tau_max^0 of the chain (root of the elastic series) equals the time of maximal
/// compression of the numerically integrated elastic collision.
#[test]
fn elastic_turning_time_matches_the_integration() {
    let chain = series::chain::compute(series::chain::Settings::for_order(4));
    let tau0 = chain.tau_max0.to_f64().value();
    let ode = solve_with_tolerance(0.0, Criterion::Improved, 1e-14).unwrap();
    assert!((tau0 - ode.time_of_max_compression).abs() < 1e-13, "{tau0}");
    assert!((chain.b[0].to_f64().value() - ode.max_compression).abs() < 1e-13);
}
