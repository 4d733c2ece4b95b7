//! The temperature ratio of a cooling binary mixture in time, DSMC (blocks, N = 2e5, mean
//! and standard error over 4 seeds) against the HCS of kinetic theory in the Maxwellian
//! and first Sonine approximations: docs/mixture-temperature-ratio.png.
//!
//!     cargo run --release -p haff-sim --example mixture_hcs

use gas::theory::MixtureTheory;
use sim::plot::Figure;
use sim::{RunDescription, Simulation};
use std::path::Path;

fn main() {
    let (alpha, phi, seeds) = (0.8, 0.1, 4);
    let mut per_seed: Vec<Vec<(f64, f64)>> = Vec::new();
    for seed in 0..seeds {
        let text = format!(
            "[system]\ndimension = 3\nparticles = 200000\npacking_fraction = {phi}\nseed = {}\n\
             species = [{{ diameter = 1.0, mass = 1.0, fraction = 0.5 }}, \
             {{ diameter = 1.0, mass = 4.0, fraction = 0.5 }}]\n\
             [collision]\nlaw = \"constant\"\nrestitution = {alpha}\n\
             [run]\nengine = \"dsmc\"\ncollisions_per_particle = 40\nsamples = 41\n\
             spacing = \"linear\"\n",
            10 + seed
        );
        let d = RunDescription::from_toml(&text, Path::new("mixture.toml")).unwrap();
        let mut s = Simulation::new(&d).unwrap();
        s.run(&mut (), None).unwrap();
        let rows = s.species_samples().unwrap();
        per_seed.push(
            rows.chunks(2)
                .map(|p| {
                    (
                        p[0].collisions_per_particle,
                        p[1].temperature / p[0].temperature,
                    )
                })
                .collect(),
        );
    }
    let n = seeds as f64;
    let points: Vec<(f64, f64, f64)> = (0..per_seed[0].len())
        .map(|k| {
            let values: Vec<f64> = per_seed.iter().map(|s| s[k].1).collect();
            let mean = values.iter().sum::<f64>() / n;
            let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
            (per_seed[0][k].0, mean, (var / n).sqrt())
        })
        .collect();
    let theory = MixtureTheory::<3>::new(
        &[1.0, 4.0],
        &[1.0, 1.0],
        &[0.5, 0.5],
        &[vec![alpha; 2], vec![alpha; 2]],
        phi,
    )
    .unwrap();
    let ratio = |r: &[f64]| r[1] / r[0];
    let maxwell = ratio(&theory.hcs(1.0).unwrap().temperature_ratios);
    let sonine = ratio(&theory.hcs_sonine(1.0).unwrap().temperature_ratios);
    let end = points.last().unwrap().0;
    let late: Vec<&(f64, f64, f64)> = points.iter().filter(|p| p.0 >= 25.0).collect();
    let mean = late.iter().map(|p| p.1).sum::<f64>() / late.len() as f64;
    println!("T1/T0 after 25 collisions per particle: {mean:.4}; Maxwellian {maxwell:.4}, Sonine {sonine:.4}");
    Figure::new(
        "binary mixture, m1/m0 = 4, equal sizes, alpha = 0.8, phi = 0.1 (3D)",
        "collisions per particle",
        "T1 / T0",
    )
    .measured("DSMC, N = 2e5 (mean of 4 seeds)", points)
    .theory(
        format!("HCS, Maxwellian approximation ({maxwell:.4})"),
        vec![(0.0, maxwell), (end, maxwell)],
    )
    .theory(
        format!("HCS, first Sonine approximation ({sonine:.4})"),
        vec![(0.0, sonine), (end, sonine)],
    )
    .write_png(Path::new("docs/mixture-temperature-ratio.png"))
    .unwrap();
}
