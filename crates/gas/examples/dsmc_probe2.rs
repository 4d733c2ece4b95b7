use gas::dsmc::{point_gas, HomogeneousDsmc, Scheme, StepSize};
use restitution::Constant;
fn main() {
    let n = 2048;
    let scheme = Scheme::Blocks {
        block_size: 2048,
        step: StepSize::CollisionsPerParticle(20.0),
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
    for _ in 0..40 {
        e.run_collisions(50_000);
        let t = e.tally();
        println!(
            "t {:.4e} T {:.4e} coll {} cand {} steps {} a2 {:.3}",
            e.time(),
            e.step_temperature(),
            t.collisions,
            t.candidates,
            e.steps(),
            gas::observe::sonine_a2(e.system())
        );
    }
}
