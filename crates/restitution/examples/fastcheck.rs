//! Worst relative error of the fast law against the exact law on a dense log grid.
//! `cargo run --release -p haff-restitution --example fastcheck`
use restitution::exact::{solve, Criterion};
use restitution::fast::Fast;

fn main() {
    for c in [Criterion::Improved, Criterion::Naive] {
        let start = std::time::Instant::now();
        let fast = Fast::new(c);
        println!("{c}: table built in {:?}", start.elapsed());
        let n = 3000;
        let (worst, at) = (0..=n)
            .map(|i| (1e-4f64 * 1e8f64.powf((i as f64 + 0.37) / n as f64)).min(1e4))
            .map(|v| {
                let e = solve(v, c).unwrap().eps;
                ((fast.eval(v) - e).abs() / e, v)
            })
            .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
        println!("{c}: worst relative error {worst:.3e} at v* = {at:.4e}");
        for v in [1e-5, 9.9e-5, 1.01e4, 3e4] {
            let e = solve(v, c).unwrap().eps;
            println!(
                "  outside the table, v* = {v:e}: {:.2e}",
                (fast.eval(v) - e).abs() / e
            );
        }
    }
}
