use restitution::exact::{solve_with_tolerance, Criterion};
fn main() {
    for &v in &[0.0, 0.1, 1.0, 10.0] {
        for &tol in &[1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15] {
            let t = std::time::Instant::now();
            let a = solve_with_tolerance(v, Criterion::Improved, tol).unwrap();
            println!("v*={v} tol={tol:e} eps={:.16e} tc={:.16e} {:?}", a.eps, a.duration, t.elapsed());
        }
    }
}
