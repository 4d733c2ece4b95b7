//! Per-species observables (`species.csv`) against identities and kinetic theory: the
//! mixture temperature is the fraction-weighted mean of the species', the collision
//! frequencies add up to the collision count, an elastic mixture collides at the rates of
//! `gas::theory::MixtureTheory`, and (ignored, heavy) cooling mixtures reach the HCS
//! temperature ratios of the first Sonine approximation.

use gas::theory::MixtureTheory;
use sim::species::SpeciesSample;
use sim::{RunDescription, Simulation};
use std::path::Path;

/// A binary mixture run: engine lines, restitution (TOML: a number or a matrix), particles,
/// collisions per particle, samples, seed, and the two species (diameter, mass, fraction).
#[allow(clippy::too_many_arguments)]
fn mixture(
    engine: &str,
    restitution: impl std::fmt::Display,
    dimension: u32,
    particles: usize,
    phi: f64,
    collisions: f64,
    samples: usize,
    seed: u64,
    species: [(f64, f64, f64); 2],
) -> Simulation {
    let list: Vec<String> = species
        .iter()
        .map(|(d, m, x)| format!("{{ diameter = {d}, mass = {m}, fraction = {x} }}"))
        .collect();
    let text = format!(
        "[system]\ndimension = {dimension}\nparticles = {particles}\npacking_fraction = {phi}\n\
         seed = {seed}\nspecies = [{}]\n[collision]\nlaw = \"constant\"\n\
         restitution = {restitution}\n[run]\n{engine}\ncollisions_per_particle = {collisions}\n\
         samples = {samples}\nspacing = \"linear\"\n",
        list.join(", ")
    );
    let d = RunDescription::from_toml(&text, Path::new("mixture.toml")).unwrap();
    let mut s = Simulation::new(&d).unwrap();
    s.run(&mut (), None).unwrap();
    s
}

const BLOCKS: &str = "engine = \"dsmc\"\ndsmc_scheme = \"blocks\"\nblock_size = 1000";
const SPATIAL: &str = "engine = \"dsmc\"\ndsmc_scheme = \"spatial\"";
const EVENT_DRIVEN: &str = "engine = \"event-driven\"";

/// The rows of species `k`.
fn of(rows: &[SpeciesSample], k: usize) -> Vec<&SpeciesSample> {
    rows.iter().filter(|r| r.species == k).collect()
}

/// For every engine: one row per species and sample; x_0 T_0 + x_1 T_1 is the time
/// series' T (the same sum split, to round-off); between samples, sum_i N_i nu_i dt is
/// twice the collisions counted (exact counts, to round-off); no frequency at the first
/// sample.
#[test]
fn rows_add_up_to_the_mixture() {
    let species = [(1.0, 1.0, 0.75), (1.4, 2.5, 0.25)];
    for engine in [BLOCKS, SPATIAL, EVENT_DRIVEN] {
        let s = mixture(engine, 0.8, 2, 800, 0.1, 20.0, 6, 3, species);
        let rows = s.species_samples().unwrap();
        let samples = s.samples();
        assert_eq!(rows.len(), 2 * samples.len(), "{engine}");
        let (a, b) = (of(rows, 0), of(rows, 1));
        for (k, sample) in samples.iter().enumerate() {
            let t = 0.75 * a[k].temperature + 0.25 * b[k].temperature;
            assert!(
                (t / sample.temperature - 1.0).abs() < 1e-12,
                "{engine}: {t} vs {}",
                sample.temperature
            );
            assert_eq!(a[k].time, sample.time);
            if k == 0 {
                assert!(a[0].collision_frequency.is_none());
                continue;
            }
            let dt = sample.time - samples[k - 1].time;
            let counted =
                800.0 * (sample.collisions_per_particle - samples[k - 1].collisions_per_particle);
            let summed = dt
                * (600.0 * a[k].collision_frequency.unwrap()
                    + 200.0 * b[k].collision_frequency.unwrap());
            assert!(
                (summed / counted - 1.0).abs() < 1e-9,
                "{engine}: {summed} vs {counted}"
            );
        }
    }
}

/// An elastic mixture stays Maxwellian at equal temperatures: DSMC's per-species collision
/// frequencies are the Enskog rates nu_i = sum_j nu_ij of kinetic theory at the measured
/// temperatures. The counts are Poisson-like: each species' total count C_i over the run
/// has a relative error 1/sqrt(C_i); agreement within 4 of them.
#[test]
fn elastic_frequencies_are_kinetic_theory() {
    let species = [(1.0, 1.0, 0.6), (1.5, 3.0, 0.4)];
    for (dimension, phi) in [(3, 0.2), (2, 0.3)] {
        let s = mixture(BLOCKS, 1.0, dimension, 20_000, phi, 10.0, 6, 7, species);
        let rows = s.species_samples().unwrap();
        let theory = |t: &[f64]| -> Vec<f64> {
            let (m, d, x) = ([1.0, 3.0], [1.0, 1.5], [0.6, 0.4]);
            let alpha = vec![vec![1.0; 2]; 2];
            match dimension {
                2 => MixtureTheory::<2>::new(&m, &d, &x, &alpha, phi)
                    .unwrap()
                    .collision_frequencies(t),
                _ => MixtureTheory::<3>::new(&m, &d, &x, &alpha, phi)
                    .unwrap()
                    .collision_frequencies(t),
            }
        };
        let (a, b) = (of(rows, 0), of(rows, 1));
        let counts = [12_000.0, 8_000.0];
        for (k, series) in [&a, &b].iter().enumerate() {
            let (mut measured, mut predicted, mut time) = (0.0, 0.0, 0.0);
            for n in 1..series.len() {
                let dt = series[n].time - series[n - 1].time;
                let t = |r: usize| 0.5 * (a[r].temperature + a[r - 1].temperature);
                let u = |r: usize| 0.5 * (b[r].temperature + b[r - 1].temperature);
                measured += series[n].collision_frequency.unwrap() * dt;
                predicted += theory(&[t(n), u(n)])[k] * dt;
                time += dt;
            }
            let collisions = measured * counts[k];
            let error = 4.0 / collisions.sqrt();
            assert!(
                (measured / predicted - 1.0).abs() < error,
                "{dimension}D species {k}: nu {} vs theory {} (4 sigma {error})",
                measured / time,
                predicted / time
            );
        }
    }
}

/// One HCS case: dimension, (diameter, mass, fraction) of both species, restitution.
struct Case {
    dimension: u32,
    species: [(f64, f64, f64); 2],
    alpha: [[f64; 2]; 2],
}

impl Case {
    /// `collision.restitution` in TOML.
    fn restitution(&self) -> String {
        let a = self.alpha;
        if a[0][0] == a[0][1] && a[0][0] == a[1][1] {
            format!("{}", a[0][0])
        } else {
            format!("[[{}, {}], [{}, {}]]", a[0][0], a[0][1], a[1][0], a[1][1])
        }
    }
}

/// The Maxwellian and Sonine HCS ratios T_1/T_0 and a2 of both species for a case.
fn theory_of(case: &Case, phi: f64) -> (f64, f64, [f64; 2]) {
    let [(d0, m0, x0), (d1, m1, x1)] = case.species;
    let (m, d, x) = ([m0, m1], [d0, d1], [x0 / (x0 + x1), x1 / (x0 + x1)]);
    let alpha: Vec<Vec<f64>> = case.alpha.iter().map(|r| r.to_vec()).collect();
    let (maxwell, sonine) = match case.dimension {
        2 => {
            let t = MixtureTheory::<2>::new(&m, &d, &x, &alpha, phi).unwrap();
            (t.hcs(1.0).unwrap(), t.hcs_sonine(1.0).unwrap())
        }
        _ => {
            let t = MixtureTheory::<3>::new(&m, &d, &x, &alpha, phi).unwrap();
            (t.hcs(1.0).unwrap(), t.hcs_sonine(1.0).unwrap())
        }
    };
    let ratio = |r: &[f64]| r[1] / r[0];
    (
        ratio(&maxwell.temperature_ratios),
        ratio(&sonine.temperature_ratios),
        [sonine.a2[0], sonine.a2[1]],
    )
}

/// The mean over seeds of a run's late-time T_1/T_0 and a2_i (samples from 25 collisions
/// per particle on: the HCS), with standard errors over the seeds.
fn measured(engine: &str, case: &Case, particles: usize, phi: f64, seeds: u64) -> [(f64, f64); 3] {
    let per_seed: Vec<[f64; 3]> = (0..seeds)
        .map(|seed| {
            let s = mixture(
                engine,
                case.restitution(),
                case.dimension,
                particles,
                phi,
                60.0,
                25,
                100 + seed,
                case.species,
            );
            let rows = s.species_samples().unwrap();
            let (a, b) = (of(rows, 0), of(rows, 1));
            let late: Vec<usize> = (0..a.len())
                .filter(|&k| a[k].collisions_per_particle >= 25.0)
                .collect();
            let mean = |f: &dyn Fn(usize) -> f64| -> f64 {
                late.iter().map(|&k| f(k)).sum::<f64>() / late.len() as f64
            };
            [
                mean(&|k| b[k].temperature / a[k].temperature),
                mean(&|k| a[k].a2),
                mean(&|k| b[k].a2),
            ]
        })
        .collect();
    std::array::from_fn(|q| {
        let values: Vec<f64> = per_seed.iter().map(|v| v[q]).collect();
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (mean, (var / n).sqrt())
    })
}

/// Homogeneous cooling of binary mixtures: T_1/T_0 and a2_i from DSMC (blocks, N = 2e5, 5
/// seeds) and from the event-driven engine (N = 2000 at phi = 0.05 and alpha = 0.9, small
/// enough to stay homogeneous; 8 seeds) against the Maxwellian and first-Sonine theory.
/// Prints the table of docs/mixtures.md. Asserted, with the standard errors over seeds:
/// where the two theories differ by more than 4 of them, the measured ratio is nearer the
/// Sonine one; where a Sonine a2 exceeds 4 of them, the measured a2 has its sign.
#[test]
#[ignore = "heavy: ~1 minute; cargo test --release -p haff-sim --test species -- --ignored --nocapture"]
fn cooling_mixtures_follow_the_sonine_theory() {
    let cases = [
        Case {
            dimension: 3,
            species: [(1.0, 1.0, 0.5), (1.0, 4.0, 0.5)],
            alpha: [[0.8; 2]; 2],
        },
        Case {
            dimension: 3,
            species: [(1.0, 1.0, 0.3), (1.5, 2.0, 0.7)],
            alpha: [[0.9; 2]; 2],
        },
        Case {
            dimension: 3,
            species: [(1.0, 1.0, 0.8), (1.0, 10.0, 0.2)],
            alpha: [[0.7; 2]; 2],
        },
        Case {
            dimension: 3,
            species: [(1.0, 1.0, 0.5), (1.0, 4.0, 0.5)],
            alpha: [[0.5; 2]; 2],
        },
        Case {
            dimension: 2,
            species: [(1.0, 1.0, 0.5), (1.2, 3.0, 0.5)],
            alpha: [[0.8; 2]; 2],
        },
        Case {
            dimension: 3,
            species: [(1.0, 1.0, 0.5), (1.0, 4.0, 0.5)],
            alpha: [[0.9, 0.6], [0.6, 0.75]],
        },
    ];
    println!("| engine | D | phi | (sigma, m, x) of species 0 and 1 | alpha | T1/T0 measured | Maxwellian | Sonine | a2_0 measured / Sonine | a2_1 measured / Sonine |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let check = |engine: &str, name: &str, case: &Case, particles: usize, phi: f64, seeds: u64| {
        let (maxwell, sonine, a2) = theory_of(case, phi);
        let [(ratio, error), (a0, e0), (a1, e1)] = measured(engine, case, particles, phi, seeds);
        println!(
            "| {name} | {} | {phi} | {:?} | {} | {ratio:.4} ± {error:.4} | {maxwell:.4} | {sonine:.4} | {a0:.4} ± {e0:.4} / {:.4} | {a1:.4} ± {e1:.4} / {:.4} |",
            case.dimension, case.species, case.restitution(), a2[0], a2[1]
        );
        if (maxwell - sonine).abs() > 4.0 * error {
            assert!(
                (ratio - sonine).abs() < (ratio - maxwell).abs(),
                "{name} {:?}: {ratio} nearer Maxwellian {maxwell} than Sonine {sonine}",
                case.species
            );
        }
        for (got, e, want) in [(a0, e0, a2[0]), (a1, e1, a2[1])] {
            if want.abs() > 4.0 * e {
                assert!(
                    got * want > 0.0,
                    "{name} {:?}: a2 {got} vs {want}",
                    case.species
                );
            }
        }
    };
    for case in &cases {
        check(BLOCKS, "DSMC", case, 200_000, 0.1, 5);
    }
    let dilute = Case {
        dimension: 3,
        species: [(1.0, 1.0, 0.5), (1.0, 4.0, 0.5)],
        alpha: [[0.9; 2]; 2],
    };
    check(BLOCKS, "DSMC", &dilute, 200_000, 0.05, 5);
    check(EVENT_DRIVEN, "eMD", &dilute, 2_000, 0.05, 8);
}

/// A matrix `collision.restitution` is checked against `system.species`, naming the entry:
/// its shape, the range of each value, symmetry; a matrix without species is refused.
#[test]
fn restitution_matrices_are_checked() {
    let file = |restitution: &str, species: bool| {
        let list = if species {
            "species = [{ diameter = 1.0, mass = 1.0, fraction = 0.5 }, \
             { diameter = 1.0, mass = 2.0, fraction = 0.5 }]\n"
        } else {
            ""
        };
        format!(
            "[system]\nparticles = 100\npacking_fraction = 0.1\n{list}[collision]\n\
             law = \"constant\"\nrestitution = {restitution}\n[run]\nengine = \"dsmc\"\n\
             collisions_per_particle = 1\nsamples = 2\n"
        )
    };
    let error = |text: String| {
        let e = Simulation::from_toml(&text, Path::new("m.toml"))
            .err()
            .unwrap();
        assert!(e.is_input(), "{e}");
        e.to_string()
    };
    let cases = [
        (
            "[[0.9, 0.6], [0.5, 0.8]]",
            true,
            "collision.restitution[0][1]",
            "symmetric",
        ),
        ("[[0.9, 0.6]]", true, "collision.restitution", "2 x 2"),
        (
            "[[0.9, 1.5], [1.5, 0.8]]",
            true,
            "collision.restitution[0][1]",
            "0 <= eps <= 1",
        ),
        (
            "[[0.9, 0.6], [0.6, 0.8]]",
            false,
            "collision.restitution",
            "system.species",
        ),
        ("\"x\"", true, "collision.restitution", "matrix"),
    ];
    for (value, species, key, allowed) in cases {
        let e = error(file(value, species));
        assert!(e.contains(key) && e.contains(allowed), "{value}: {e}");
    }
    let ok = Simulation::from_toml(&file("[[0.9, 0.6], [0.6, 0.8]]", true), Path::new("m.toml"));
    assert!(ok.is_ok());
}

/// White-noise driving (3D, alpha = 0.8, xi^2 = 1, DSMC blocks, N = 1e5): the steady
/// temperature (samples from 20 to 60 collisions per particle) within 1 % of the energy
/// balance zeta(T) T = m xi^2 (1 - 1/B) of the first Sonine theory (measured here: -0.3 %,
/// statistical error ~0.1 %; the Maxwellian and Sonine balances differ by 0.1 %), the same
/// with steps of 0.5 and 0.25 collisions per particle (the kicks converged), a2 of the
/// white-noise state's sign (van Noije & Ernst: -0.0087); and the energy lost by collisions
/// between two late samples is the energy the kicks fed in, to the fluctuations of the
/// kinetic energy and of the kicks' work.
#[test]
fn white_noise_reaches_the_energy_balance() {
    let (n, xi2, alpha) = (100_000usize, 1.0, 0.8);
    let theory = MixtureTheory::<3>::new(&[1.0], &[1.0], &[1.0], &[vec![alpha]], 0.1).unwrap();
    let block = gas::dsmc::DEFAULT_BLOCK_SIZE as f64;
    let effective = xi2 * (1.0 - 1.0 / block);
    let steady = theory.white_noise(&[effective], true).unwrap();
    for step in ["", "collisions_per_step = 0.5\n"] {
        let text = format!(
            "[system]\ndimension = 3\nparticles = {n}\npacking_fraction = 0.1\nseed = 3\n\
             [collision]\nlaw = \"constant\"\nrestitution = {alpha}\n\
             [driving]\nkind = \"white-noise\"\nstrength = {xi2}\n\
             [run]\nengine = \"dsmc\"\ncollisions_per_particle = 60\n{step}samples = 31\n\
             spacing = \"linear\"\n"
        );
        let d = RunDescription::from_toml(&text, Path::new("driven.toml")).unwrap();
        let mut s = Simulation::new(&d).unwrap();
        s.run(&mut (), None).unwrap();
        let late: Vec<_> = s
            .samples()
            .iter()
            .filter(|x| x.collisions_per_particle >= 20.0)
            .collect();
        let mean = |f: &dyn Fn(&sim::observer::Sample) -> f64| {
            late.iter().map(|x| f(x)).sum::<f64>() / late.len() as f64
        };
        let t = mean(&|x| x.temperature);
        let want = steady.temperatures[0];
        assert!((t / want - 1.0).abs() < 0.01, "{step}: T {t} vs {want}");
        let a2 = mean(&|x| x.a2);
        assert!(a2 < 0.0, "a2 {a2}");
        let (first, last) = (late[0], late[late.len() - 1]);
        let fed = 0.5 * n as f64 * 3.0 * effective * (last.time - first.time);
        let lost = last.energy_lost - first.energy_lost;
        // Kinetic energy 3 N T / 2 fluctuates by sqrt(3 N / 2) T per sample (Maxwellian),
        // the work of the kicks, sum m v.dv, by sqrt(N D T xi^2 time): 4 standard deviations.
        let kinetic = |x: &sim::observer::Sample| 1.5 * n as f64 * x.temperature;
        let work = n as f64 * 3.0 * t * effective * (last.time - first.time);
        let noise = 4.0 * (2.0 * 1.5 * n as f64 * t * t + work).sqrt();
        assert!(
            (fed - lost - (kinetic(last) - kinetic(first))).abs() < noise,
            "fed {fed}, lost {lost}"
        );
    }
}

/// `[driving]` is checked: a strength > 0 (white noise) or a temperature > 0 (thermostat),
/// each kind's keys only, an engine that drives (DSMC blocks, event-driven), an interval
/// for the event-driven engine only, a known kind.
#[test]
fn driving_is_checked() {
    let file = |engine: &str, driving: &str| {
        format!(
            "[system]\nparticles = 100\npacking_fraction = 0.1\n[collision]\nlaw = \"constant\"\n\
             restitution = 0.9\n[driving]\n{driving}\n[run]\n{engine}\n\
             collisions_per_particle = 1\nsamples = 2\n"
        )
    };
    let noise = "kind = \"white-noise\"\nstrength = 1.0";
    let cases = [
        (SPATIAL, noise, "driving"),
        (BLOCKS, "kind = \"white-noise\"", "driving.strength"),
        (
            BLOCKS,
            "kind = \"white-noise\"\nstrength = 1.0\ntemperature = 2.0",
            "driving.temperature",
        ),
        (
            BLOCKS,
            "kind = \"gaussian-thermostat\"\nstrength = 1.0",
            "driving.strength",
        ),
        (
            BLOCKS,
            "kind = \"gaussian-thermostat\"\ntemperature = 0.0",
            "driving.temperature",
        ),
        (
            BLOCKS,
            "kind = \"white-noise\"\nstrength = 1.0\ninterval = 0.1",
            "driving.interval",
        ),
        (
            EVENT_DRIVEN,
            "kind = \"white-noise\"\nstrength = 1.0\ninterval = -0.1",
            "driving.interval",
        ),
        (
            BLOCKS,
            "kind = \"white-noise\"\nstrength = -1.0",
            "driving.strength",
        ),
        (
            BLOCKS,
            "kind = \"gaussian\"\nstrength = 1.0",
            "driving.kind",
        ),
    ];
    for (engine, driving, key) in cases {
        let e = Simulation::from_toml(&file(engine, driving), Path::new("d.toml"))
            .err()
            .unwrap();
        assert!(
            e.is_input() && e.to_string().contains(key),
            "{engine} {driving}: {e}"
        );
    }
    for (engine, driving) in [
        (BLOCKS, noise),
        (EVENT_DRIVEN, noise),
        (
            EVENT_DRIVEN,
            "kind = \"gaussian-thermostat\"\ninterval = 0.05",
        ),
        (BLOCKS, "kind = \"gaussian-thermostat\""),
    ] {
        assert!(Simulation::from_toml(&file(engine, driving), Path::new("d.toml")).is_ok());
    }
}

/// A driven binary mixture (docs/data/driven-mixture.toml at N = 5e4): each species' steady
/// temperature within 1 % of the white-noise balance of the first Sonine theory (measured at
/// N = 2e5: within 0.15 %; statistical error here ~0.2 %), so the temperature ratio too:
/// equipartition breaks down more than in the HCS (1.64 against 1.33).
#[test]
fn a_driven_mixture_reaches_the_white_noise_temperatures() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/data/driven-mixture.toml"
    ))
    .unwrap()
    .replace("particles = 200000", "particles = 50000");
    let d = RunDescription::from_toml(&text, Path::new("driven-mixture.toml")).unwrap();
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
    // Equal masses within a block keep (1 - 1/B) of the kicks; a mixture's mass-weighted
    // mean removal differs from that by O(1/B), below the tolerance.
    let want = theory.white_noise(&[1.0 - 1.0 / block; 2], true).unwrap();
    for k in 0..2 {
        let late: Vec<f64> = of(rows, k)
            .iter()
            .filter(|r| r.collisions_per_particle >= 30.0)
            .map(|r| r.temperature)
            .collect();
        let t = late.iter().sum::<f64>() / late.len() as f64;
        let expected = want.temperatures[k];
        assert!(
            (t / expected - 1.0).abs() < 0.01,
            "species {k}: T {t} vs {expected}"
        );
    }
}
