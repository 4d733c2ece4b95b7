use restitution::exact::{solve_with_tolerance, Criterion};
fn main() {
    for i in 0..12 {
        let v = 1.69 + 0.004 * i as f64;
        let a = solve_with_tolerance(v, Criterion::Naive, 1e-12).unwrap();
        let b = solve_with_tolerance(v, Criterion::Naive, 1e-14).unwrap();
        println!("v*={v:.4} eps={:.15e} d={:.2e} tc={:.10} end_x={:e}", a.eps, (a.eps-b.eps)/b.eps, a.duration, a.compression_at_end);
    }
}
