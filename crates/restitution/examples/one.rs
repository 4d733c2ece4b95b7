use restitution::exact::{solve, Criterion};
fn main() {
    let v: f64 = std::env::args().nth(1).unwrap().parse().unwrap();
    let c: Criterion = std::env::args().nth(2).unwrap().parse().unwrap();
    let t = std::time::Instant::now();
    println!("{:?} {:?}", solve(v, c), t.elapsed());
}
