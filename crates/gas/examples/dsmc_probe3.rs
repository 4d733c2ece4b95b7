use gas::dsmc::{point_gas, theory, HomogeneousDsmc, Scheme, StepSize};
use restitution::Constant;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let bs: usize = args[1].parse().unwrap();
    let cps: f64 = args[2].parse().unwrap();
    let seeds: u64 = args[3].parse().unwrap();
    let scheme = if bs == 0 {
        Scheme::Exact
    } else {
        Scheme::Blocks {
            block_size: bs,
            step: StepSize::CollisionsPerParticle(cps),
        }
    };
    let mut ts = vec![];
    for seed in 0..seeds {
        let n = 10_000;
        let system = point_gas::<3>(n, 1.0, 1.0, 1.0, 1.0, 1000 + seed).unwrap();
        let mut e = HomogeneousDsmc::new(
            system,
            0.1,
            Box::new(Constant::new(0.7).unwrap()),
            seed,
            scheme,
        )
        .unwrap();
        let omega =
            theory::collision_frequency::<3>((n - 1) as f64 / e.volume(), 1.0, 1.0, 1.0, 0.1);
        e.run_until(30.0 / omega);
        ts.push(gas::observe::temperature(e.system()));
    }
    let m = ts.iter().sum::<f64>() / ts.len() as f64;
    let v = ts.iter().map(|t| (t - m).powi(2)).sum::<f64>() / (ts.len() - 1) as f64;
    println!(
        "B {bs} cps {cps}: T = {m:.5} +- {:.5}",
        (v / ts.len() as f64).sqrt()
    );
}
