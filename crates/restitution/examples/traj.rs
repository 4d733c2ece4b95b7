fn main() {
    let (c, pts) = restitution::exact::trajectory(2.0, restitution::Criterion::Improved, 101).unwrap();
    println!("{:?}", c);
    for p in pts { println!("{:.6} {:.6} {:.6}", p.tau, p.x, p.xdot); }
}
