//! Accuracy of the Padé approximants of Table I (MP2011) and of the truncated series against
//! the exact law, and local slopes d ln eps / d ln v* (figures quoted in docs/).
//! `cargo run --release -p haff-restitution --example padeerr`
use restitution::exact::{solve, Criterion};
use restitution::pade::Pade;
use restitution::series::{Series, TABLE_V};

fn exact(v: f64, c: Criterion) -> f64 {
    solve(v, c).unwrap().eps
}

fn main() {
    let grid: Vec<f64> = (0..=4000).map(|i| 100.0 * i as f64 / 4000.0).collect();
    let reference: Vec<f64> = grid
        .iter()
        .map(|&v| exact(v, Criterion::Improved))
        .collect();
    for (m, n) in [(0, 3), (1, 4), (2, 5), (3, 6)] {
        let p = Pade::table_i(m, n).unwrap();
        let (err, at) = grid
            .iter()
            .zip(&reference)
            .map(|(&v, e)| ((p.eval(v) - e).abs(), v))
            .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
        let recomputed = Pade::from_series(&TABLE_V, m, n).unwrap();
        println!("[{m}/{n}] max |pade - exact| on [0,100]: {err:.3e} at v* = {at:.3}; positive poles {:?}", p.positive_poles(1e4));
        println!(
            "      from Table V: a = {:?}, b = {:?}",
            recomputed.numerator(),
            recomputed.denominator()
        );
    }
    let series = Series::table_v(20).unwrap();
    for v in [0.05, 0.1, 0.2, 0.3, 0.5] {
        println!(
            "series:20 - exact at v* = {v}: {:.3e}",
            series.eval(v) - exact(v, Criterion::Improved)
        );
    }
    for v in [3.0f64, 4.5, 5.0, 10.0, 30.0, 100.0, 1e3, 1e4] {
        let slope = |c| (exact(v * 1.001, c) / exact(v / 1.001, c)).ln() / (2.0 * 1.001f64.ln());
        println!(
            "slope at v* = {v}: improved {:.6}, naive {:.6}",
            slope(Criterion::Improved),
            slope(Criterion::Naive)
        );
    }
}
