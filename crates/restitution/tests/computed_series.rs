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
    let chain = series::coefficients::compute(series::coefficients::Settings::for_order(4));
    let tau0 = chain.tau_max0.to_f64().value();
    let ode = solve_with_tolerance(0.0, Criterion::Improved, 1e-14).unwrap();
    assert!((tau0 - ode.time_of_max_compression).abs() < 1e-13, "{tau0}");
    assert!((chain.b[0].to_f64().value() - ode.max_compression).abs() < 1e-13);
}

/// MP2011: "We checked all orders up to [25/28] and could not find any significant
/// improvement as compared to [3/6]". Measured max |P - eps| on [0, 100]: [3/6] 6.7e-4,
/// [13/16] 2.8e-6, [23/26] 3.4e-7 (docs/series-algebra.md); [4/7] has a pole at 3.687.
#[test]
fn higher_pade_orders_do_improve_on_3_6() {
    use restitution::pade::Pade;
    let grid: Vec<(f64, f64)> = (0..=400)
        .map(|i| 100.0 * (i as f64 / 400.0).powi(2))
        .map(|v| {
            (
                v,
                solve_with_tolerance(v, Criterion::Improved, 1e-12)
                    .unwrap()
                    .eps,
            )
        })
        .collect();
    let max_error = |p: &Pade| {
        grid.iter()
            .map(|&(v, e)| (p.eval(v) - e).abs())
            .fold(0.0, f64::max)
    };
    let e36 = max_error(&Pade::computed(3, 6).unwrap());
    let e1316 = max_error(&Pade::computed(13, 16).unwrap());
    let e2326 = max_error(&Pade::computed(23, 26).unwrap());
    assert!(e36 > 6e-4 && e36 < 7e-4, "{e36}");
    assert!(e1316 < 5e-6, "{e1316}");
    assert!(e2326 < 5e-7, "{e2326}");
    let p47 = Pade::computed(4, 7).unwrap();
    let poles = p47.positive_poles(100.0);
    assert_eq!(poles.len(), 1);
    assert!((poles[0] - 3.6874).abs() < 1e-3, "{poles:?}");
}

/// The radius of convergence behind `validity::SERIES_RADIUS`, by the root test
/// R_k = (max_{k-9..k} |h_k|)^(-1/k) (Cauchy-Hadamard; the window covers the sign pattern
/// of the h_k, which vanish or change sign irregularly): R_50 and R_60 agree to 0.005 (the
/// estimate drifts as O(ln k / k)), and the constant is a lower bound within 0.02 of both.
#[test]
fn series_radius_from_the_root_test() {
    use restitution::validity::SERIES_RADIUS;
    let h = Series::computed(60).unwrap().coefficients().to_vec();
    let root = |k: usize| {
        let largest = h[k - 9..=k].iter().fold(0.0f64, |m, x| m.max(x.abs()));
        largest.powf(-1.0 / k as f64)
    };
    let (r50, r60) = (root(50), root(60));
    eprintln!("root test: R_50 = {r50:.4}, R_60 = {r60:.4}; SERIES_RADIUS = {SERIES_RADIUS}");
    assert!((r50 - r60).abs() < 0.005, "{r50} vs {r60}");
    for r in [r50, r60] {
        assert!((SERIES_RADIUS..SERIES_RADIUS + 0.02).contains(&r), "{r}");
    }
}
