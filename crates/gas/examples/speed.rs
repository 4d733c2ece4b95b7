//! Quick throughput check (the benchmark proper will be `haff bench emd`).
use gas::init::monodisperse;
use gas::Engine;
use gas::EventDriven;
use restitution::Constant;
fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map_or(100_000, |s| s.parse().unwrap());
    let phi: f64 = std::env::args().nth(2).map_or(0.05, |s| s.parse().unwrap());
    let system = monodisperse::<3>(n, phi, 1.0, 1.0, 1.0, 1).unwrap();
    let mut e = EventDriven::new(system, Box::new(Constant::new(1.0).unwrap())).unwrap();
    e.run_collisions(n as u64); // warm up
    let (c0, ev0) = (e.counters().collisions, e.counters().events);
    let t = std::time::Instant::now();
    e.run_collisions(10 * n as u64);
    let dt = t.elapsed().as_secs_f64();
    let (c, ev) = (e.counters().collisions - c0, e.counters().events - ev0);
    println!(
        "N={n} phi={phi}: {:.3e} collisions/s, {:.3e} events/s",
        c as f64 / dt,
        ev as f64 / dt
    );
}
