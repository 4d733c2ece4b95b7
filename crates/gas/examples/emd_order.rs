//! Does the memory order of the particles matter to the event-driven engine? The same
//! elastic gas (random sequential addition, so the particles start in random order) is run
//! once as built and once with its particles renumbered along a Morton (Z-order) curve of
//! their positions, the order a periodic re-ordering during a run would restore. Prints the
//! collisions per second of each (one core; warm-up of a quarter of the timed events).
//!
//! `cargo run --release -p haff-gas --example emd_order -- [N] [PHI] [EVENTS] [REPEATS]`
//! (defaults 100000 0.05 3000000 3; pin it with `taskset -c 1`).
use gas::Engine;
use gas::{init, EventDriven, System};

/// Interleaves the bits of three 21-bit cell coordinates.
fn morton(cell: [u64; 3]) -> u64 {
    (0..21).fold(0, |key, bit| {
        (0..3).fold(key, |key, d| {
            key | (((cell[d] >> bit) & 1) << (3 * bit + d))
        })
    })
}

fn renumbered_along_morton(system: &mut System<3>) {
    let l = system.sides[0];
    let key = |x: &[f64; 3]| morton(x.map(|c| (c / l * 1024.0) as u64));
    let mut order: Vec<usize> = (0..system.len()).collect();
    order.sort_by_key(|&i| key(&system.positions[i]));
    system.positions = order.iter().map(|&i| system.positions[i]).collect();
    system.velocities = order.iter().map(|&i| system.velocities[i]).collect();
}

fn rate(n: usize, phi: f64, events: u64, seed: u64, morton_order: bool) -> f64 {
    let mut system = init::monodisperse::<3>(n, phi, 1.0, 1.0, 1.0, seed).expect("system");
    if morton_order {
        renumbered_along_morton(&mut system);
    }
    let law = Box::new(restitution::Constant::new(1.0).expect("law"));
    let mut engine = EventDriven::new(system, law).expect("engine");
    for _ in 0..events / 4 {
        engine.step();
    }
    let before = engine.counters().collisions;
    let start = std::time::Instant::now();
    for _ in 0..events {
        engine.step();
    }
    (engine.counters().collisions - before) as f64 / start.elapsed().as_secs_f64()
}

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: &str| args.get(i).cloned().unwrap_or(default.into());
    let n: usize = arg(0, "100000").parse().expect("N: an integer");
    let phi: f64 = arg(1, "0.05").parse().expect("PHI: a number");
    let events: u64 = arg(2, "3000000").parse().expect("EVENTS: an integer");
    let repeats: u64 = arg(3, "3").parse().expect("REPEATS: an integer");
    let (mut random, mut ordered) = (Vec::new(), Vec::new());
    for seed in 1..=repeats {
        random.push(rate(n, phi, events, seed, false));
        ordered.push(rate(n, phi, events, seed, true));
    }
    let (a, b) = (median(random), median(ordered));
    println!(
        "N = {n}, phi = {phi}: random order {a:.3e}, Morton order {b:.3e} collisions/s \
         (medians of {repeats}), ratio {:.3}",
        b / a
    );
}
