//! Wall time per exact collision (the benchmark proper is `haff bench cor`).
//! `cargo run --release -p haff-restitution --example timing`
use restitution::exact::{solve, Criterion};

fn main() {
    for c in [Criterion::Improved, Criterion::Naive] {
        for v in [0.0, 0.01, 0.3, 1.0, 3.0, 10.0, 100.0, 1e4] {
            let n = 200;
            let start = std::time::Instant::now();
            for _ in 0..n {
                std::hint::black_box(solve(std::hint::black_box(v), c).unwrap());
            }
            println!(
                "{c} v* = {v}: {:.1} us",
                start.elapsed().as_secs_f64() * 1e6 / n as f64
            );
        }
    }
}
