//! A viscoelastic binary mixture cooling: species of unlike materials (their own Young
//! modulus, Poisson ratio and dissipative constant; beta per pair), DSMC (blocks) against
//! the free cooling of the Maxwellian kinetic theory with the pairs' speed-dependent
//! restitution (`MixtureTheory::free_cooling`): each species' temperature in time and the
//! late-time law T ~ t^(-5/3) with the ratio returning to 1: docs/viscoelastic-mixture.png.
//!
//!     cargo run --release -p haff-sim --example viscoelastic_mixture

use gas::theory::MixtureTheory;

use sim::plot::Figure;
use sim::{RunDescription, Simulation};
use std::path::Path;

/// (diameter, mass, fraction, young, poisson, dissipative_constant).
const SPECIES: [(f64, f64, f64, f64, f64, f64); 2] = [
    (1.0, 1.0, 0.5, 1e5, 0.3, 2e-3),
    (1.4, 2.744, 0.5, 1e4, 0.4, 1e-2),
];
const PHI: f64 = 0.1;

fn description(seed: u64, particles: usize, collisions: f64) -> RunDescription {
    let list: Vec<String> = SPECIES
        .iter()
        .map(|(d, m, x, y, nu, a)| {
            format!(
                "{{ diameter = {d}, mass = {m}, fraction = {x}, young = {y:e}, poisson = {nu}, \
                 dissipative_constant = {a:e} }}"
            )
        })
        .collect();
    let text = format!(
        "[system]\ndimension = 3\nparticles = {particles}\npacking_fraction = {PHI}\nseed = {seed}\n\
         species = [{}]\n[collision]\nlaw = \"viscoelastic\"\n[run]\n{}\n\
         collisions_per_particle = {collisions}\nsamples = 30\nspacing = \"log\"\n",
        list.join(", "),
        "engine = \"dsmc\""
    );
    RunDescription::from_toml(&text, Path::new("viscoelastic-mixture.toml")).unwrap()
}

fn main() {
    let (particles, collisions) = (100_000, 2000.0);
    let d = description(1, particles, collisions);
    let plan = sim::validate(&d).unwrap();
    let law = sim::law::build(&plan.law, plan.max_impact_speed()).unwrap();
    let table = law.pairwise().unwrap().clone();
    let mut s = Simulation::new(&d).unwrap();
    s.run(&mut (), None).unwrap();
    let rows = s.species_samples().unwrap();
    let theory = MixtureTheory::<3>::new(
        &SPECIES.map(|x| x.1),
        &SPECIES.map(|x| x.0),
        &SPECIES.map(|x| x.2),
        &[vec![1.0; 2], vec![1.0; 2]],
        PHI,
    )
    .unwrap();
    let eps = |i: usize, j: usize, g: f64| table.law(i, j).eps(g);
    let times: Vec<f64> = rows.chunks(2).map(|p| p[0].time).collect();
    let initial = [rows[0].temperature, rows[1].temperature];
    let predicted = theory.free_cooling(&initial, &eps, &times, 50).unwrap();
    println!("time collisions_per_particle T0 T0_theory T1 T1_theory ratio ratio_theory a2_0 a2_1");
    for (p, q) in rows.chunks(2).zip(&predicted) {
        println!(
            "{:.4e} {:.1} {:.5e} {:.5e} {:.5e} {:.5e} {:.5} {:.5} {:.4} {:.4}",
            p[0].time,
            p[0].collisions_per_particle,
            p[0].temperature,
            q[0],
            p[1].temperature,
            q[1],
            p[1].temperature / p[0].temperature,
            q[1] / q[0],
            p[0].a2,
            p[1].a2
        );
    }
    // Samples after t = 0 (log axes).
    let later = |k: usize| -> Vec<(f64, f64)> {
        rows.chunks(2)
            .skip(1)
            .map(|p| (p[0].time, p[k].temperature))
            .collect()
    };
    let theory_of = |f: &dyn Fn(&[f64]) -> f64| -> Vec<(f64, f64)> {
        times
            .iter()
            .zip(&predicted)
            .skip(1)
            .map(|(t, q)| (*t, f(q)))
            .collect()
    };
    Figure::new(
        "viscoelastic binary mixture of unlike materials (3D, phi = 0.1)",
        "time",
        "species temperature",
    )
    .log(true, true)
    .noisy("DSMC, species 0 (d = 1, m = 1, stiff)", later(0))
    .noisy("DSMC, species 1 (d = 1.4, m = 2.744, soft)", later(1))
    .theory("Maxwellian free cooling, species 0", theory_of(&|q| q[0]))
    .theory("Maxwellian free cooling, species 1", theory_of(&|q| q[1]))
    .write_png(Path::new("docs/viscoelastic-mixture.png"))
    .unwrap();
    let ratio: Vec<(f64, f64)> = rows
        .chunks(2)
        .skip(1)
        .map(|p| (p[0].time, p[1].temperature / p[0].temperature))
        .collect();
    Figure::new(
        "viscoelastic mixture: equipartition breaks, then returns as collisions turn elastic",
        "time",
        "T1 / T0",
    )
    .log(true, false)
    .noisy("DSMC, N = 1e5", ratio)
    .theory("Maxwellian free cooling", theory_of(&|q| q[1] / q[0]))
    .write_png(Path::new("docs/viscoelastic-mixture-ratio.png"))
    .unwrap();
}
