use restitution::{exact::{solve, Criterion}, fast::Fast};
fn main() {
    for crit in [Criterion::Improved, Criterion::Naive] {
        let t = std::time::Instant::now();
        let f = Fast::new(crit);
        println!("{crit}: build {:?}", t.elapsed());
        let mut worst: (f64, f64) = (0.0, 0.0);
        let n = 3000;
        for i in 0..=n {
            let v = 1e-4f64 * (1e8f64).powf((i as f64 + 0.37) / n as f64);
            if v > 1e4 { continue; }
            let e = solve(v, crit).unwrap().eps;
            let r = (f.eval(v) - e).abs() / e;
            if r > worst.0 { worst = (r, v); }
        }
        println!("{crit}: worst rel err {:.3e} at v*={:.4e}", worst.0, worst.1);
        for v in [1e-5, 9.9e-5, 1.01e4, 3e4] {
            let e = solve(v, crit).unwrap().eps;
            println!("  outside v*={v:e}: rel err {:.2e}", (f.eval(v) - e).abs() / e);
        }
    }
}
