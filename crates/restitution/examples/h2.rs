use restitution::exact::{solve_with_tolerance, Criterion};
fn main() {
    for crit in [Criterion::Improved, Criterion::Naive] {
    for &v in &[1e-4f64, 3e-4, 1e-3, 3e-3, 1e-2] {
        let a = solve_with_tolerance(v, crit, 1e-14).unwrap();
        let r = (a.eps - 1.0) / (v * v);
        let r4 = (a.eps - 1.0 + 1.153448856 * v * v) / v.powi(4);
        println!("{crit} v*={v:e} (eps-1)/v^2 = {:.12}  (eps-1-h2 v^2)/v^4 = {:.8}", r, r4);
    }}
}
