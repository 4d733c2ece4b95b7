//! A binary mixture driven by white noise (docs/data/driven-mixture.toml: 3D, masses 1 and
//! 4, alpha = 0.8, phi = 0.1, xi^2 = 1, DSMC blocks, N = 2e5): each species heats from
//! T = 1 to its steady temperature, against the white-noise balance of kinetic theory
//! (`MixtureTheory::white_noise`, first Sonine; the Maxwellian balance differs by 0.1 %, a
//! line's width, and is printed): docs/driven-mixture.png.
//!
//!     cargo run --release -p haff-sim --example driven_mixture

use gas::theory::MixtureTheory;
use sim::plot::Figure;
use sim::{RunDescription, Simulation};
use std::path::Path;

fn main() {
    let path = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/data/driven-mixture.toml"
    ));
    let text = std::fs::read_to_string(path).unwrap();
    let d = RunDescription::from_toml(&text, path).unwrap();
    let mut s = Simulation::new(&d).unwrap();
    s.run(&mut (), None).unwrap();
    let rows = s.species_samples().unwrap();
    let theory = MixtureTheory::<3>::new(
        &[1.0, 4.0],
        &[1.0, 1.0],
        &[0.5, 0.5],
        &[vec![0.8; 2], vec![0.8; 2]],
        0.1,
    )
    .unwrap();
    let block = gas::dsmc::DEFAULT_BLOCK_SIZE as f64;
    let noise = [1.0 - 1.0 / block; 2];
    let sonine = theory.white_noise(&noise, true).unwrap().temperatures;
    let maxwell = theory.white_noise(&noise, false).unwrap().temperatures;
    let end = rows.last().unwrap().collisions_per_particle;
    let measured = |k: usize| -> Vec<(f64, f64)> {
        rows.chunks(2)
            .map(|p| (p[k].collisions_per_particle, p[k].temperature))
            .collect()
    };
    let level = |t: f64| vec![(0.0, t), (end, t)];
    println!("steady temperatures: Sonine {sonine:?}, Maxwellian {maxwell:?}");
    Figure::new(
        "binary mixture driven by white noise, m1/m0 = 4, alpha = 0.8, phi = 0.1 (3D)",
        "collisions per particle",
        "species temperature",
    )
    .noisy("DSMC, species 0 (m = 1)", measured(0))
    .noisy("DSMC, species 1 (m = 4)", measured(1))
    .theory(
        format!("Sonine balance, T0 = {:.4}", sonine[0]),
        level(sonine[0]),
    )
    .theory(
        format!("Sonine balance, T1 = {:.4}", sonine[1]),
        level(sonine[1]),
    )
    .theory(
        format!("Maxwellian balance, T1 = {:.4}", maxwell[1]),
        level(maxwell[1]),
    )
    .write_png(Path::new("docs/driven-mixture.png"))
    .unwrap();
}
