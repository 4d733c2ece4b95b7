use restitution::exact::{solve, solve_with_tolerance, Criterion};
fn main() {
    let h = [1.0, 0.0, -1.153448856, 0.0, 0.7982665581, 0.2666666667, -0.5228825657, -0.4613795424, 0.3487426737, 0.4523510496, -0.1464314644];
    for &v in &[0.0, 1e-4, 1e-3, 0.01, 0.1, 0.3, 0.5, 1.0, 1.25, 2.0, 5.0, 10.0, 30.0, 100.0, 1e3, 1e4] {
        let t = std::time::Instant::now();
        let a = solve(v, Criterion::Improved).unwrap();
        let dt = t.elapsed();
        let b = solve(v, Criterion::Naive).unwrap();
        let a2 = solve_with_tolerance(v, Criterion::Improved, 1e-11).unwrap();
        let b2 = solve_with_tolerance(v, Criterion::Naive, 1e-11).unwrap();
        let ser: f64 = h.iter().enumerate().map(|(k, c)| c * v.powi(k as i32)).sum();
        println!("v*={v:8.1e} imp={:.15e} ({:.1e}) naive={:.15e} ({:.1e}) tc={:.6} xmax={:.6} tmax={:.6} ser-imp={:.2e} {:?}",
            a.eps, (a.eps - a2.eps) / a.eps, b.eps, (b.eps - b2.eps) / b.eps, a.duration, a.max_compression, a.time_of_max_compression, ser - a.eps, dt);
    }
}
