use gas::dsmc::{point_gas, HomogeneousDsmc, Scheme, StepSize};
use restitution::Constant;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args[1].parse::<f64>().unwrap() as usize;
    let cps: f64 = args[2].parse().unwrap();
    let bs: usize = args[3].parse().unwrap();
    let scheme = if bs == 0 {
        Scheme::Exact
    } else {
        Scheme::Blocks {
            block_size: bs,
            step: StepSize::CollisionsPerParticle(cps),
        }
    };
    let system = point_gas::<3>(n, 1.0, 1.0, 1.0, 1.0, 1).unwrap();
    let mut e = HomogeneousDsmc::new(
        system,
        0.05,
        Box::new(Constant::new(0.9).unwrap()),
        7,
        scheme,
    )
    .unwrap();
    e.run_collisions(n as u64 / 2);
    let t0 = e.tally();
    let start = Instant::now();
    let per: f64 = args.get(4).map_or(4.0, |x| x.parse().unwrap());
    e.run_collisions((per * n as f64 / 2.0) as u64);
    let s = start.elapsed().as_secs_f64();
    let t1 = e.tally();
    let c = (t1.collisions - t0.collisions) as f64;
    println!(
        "ns/collision {:.1}  ns/candidate {:.1} cand/coll {:.2} steps {}",
        s * 1e9 / c,
        s * 1e9 / (t1.candidates - t0.candidates) as f64,
        (t1.candidates - t0.candidates) as f64 / c,
        e.steps()
    );
}
