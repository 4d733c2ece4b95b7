//! The coefficients a, b, c, h and G of SP2008 at chosen order K, trajectory order N and
//! precision, to compare runs for convergence.
//! `cargo run --release -p haff-series --example coefficients -- K N BITS` (default 20 150 256)
use dashu_ratio::RBig;
use series::coefficients::{compute, premature_end, Settings};
use series::trajectory::Trajectory;
fn main() {
    let k: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse().unwrap())
        .unwrap_or(20);
    let n: usize = std::env::args()
        .nth(2)
        .map(|s| s.parse().unwrap())
        .unwrap_or(150);
    let bits: usize = std::env::args()
        .nth(3)
        .map(|s| s.parse().unwrap())
        .unwrap_or(256);
    let t0 = std::time::Instant::now();
    let c = compute(Settings {
        order: k,
        trajectory_order: n,
        bits,
    });
    println!("K={k} N={n} bits={bits}: {:?}", t0.elapsed());
    let d = |x: &series::power::Real| {
        x.to_decimal()
            .value()
            .with_precision(22)
            .value()
            .to_string()
    };
    println!("tau_max0 = {}", d(&c.tau_max0));
    for i in 0..c.b.len().min(11) {
        println!("i={i} a={} b={} c={}", d(&c.a[i]), d(&c.b[i]), d(&c.c[i]));
    }
    for (i, h) in c.h.iter().enumerate() {
        println!("h{i} = {}", d(h));
    }
    let t = Trajectory::new(30, 12);
    let (_, g) = premature_end(&t, &RBig::ONE, 22);
    for (i, x) in g.c.iter().enumerate() {
        if *x != RBig::ZERO {
            println!("G b^{i}: {x}");
        }
    }
}
