//! Accepted collisions per second of the homogeneous DSMC engine (block scheme, all cores)
//! for N = 1e6 and 1e7, with a constant eps = 0.9 and the fast viscoelastic law.
//!
//! `cargo run --release -p haff-gas --example dsmc_speed [-- N1,N2,... [collisions per particle]]`
//! (RAYON_NUM_THREADS=k limits the threads.)

use gas::dsmc::{point_gas, HomogeneousDsmc, Scheme};
use gas::Engine;
use restitution::{Constant, Restitution, ScaledForm, Viscoelastic};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let sizes: Vec<usize> = match args.get(1) {
        Some(list) => list
            .split(',')
            .map(|x| x.parse::<f64>().map(|v| v as usize))
            .collect::<Result<_, _>>()?,
        None => vec![1_000_000, 10_000_000],
    };
    let per_particle: f64 = args.get(2).map_or(Ok(4.0), |x| x.parse())?;
    let laws: Vec<(&str, Box<dyn Restitution>)> = vec![
        ("constant 0.9", Box::new(Constant::new(0.9)?)),
        (
            "viscoelastic fast (beta 0.1)",
            Box::new(Viscoelastic::new(0.1, "fast".parse::<ScaledForm>()?)?),
        ),
    ];
    println!(
        "threads: {}; {per_particle} collisions per particle timed after 1 of warm-up",
        rayon::current_num_threads()
    );
    println!(
        "N,law,collisions,seconds,collisions_per_s,candidates_per_collision,bytes_per_particle"
    );
    for &n in &sizes {
        for (name, law) in &laws {
            let system = point_gas::<3>(n, 1.0, 1.0, 1.0, 1.0, 1)?;
            let mut engine = HomogeneousDsmc::new(system, 0.05, law.clone(), 7, Scheme::default())?;
            engine.run_collisions(n as u64 / 2);
            let before = engine.counters();
            let start = Instant::now();
            engine.run_collisions((per_particle * n as f64 / 2.0) as u64);
            let seconds = start.elapsed().as_secs_f64();
            let after = engine.counters();
            let collisions = after.collisions - before.collisions;
            let candidates = after.events - before.events;
            println!(
                "{n},{name},{collisions},{seconds:.3},{:.4e},{:.3},{:.1}",
                collisions as f64 / seconds,
                candidates as f64 / collisions as f64,
                engine.memory_bytes() as f64 / n as f64
            );
        }
    }
    Ok(())
}
