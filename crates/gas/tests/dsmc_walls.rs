//! Spatial DSMC in a container: walls and gravity during streaming, against the
//! barometric law (exact for point particles), conservation of kinetic plus potential
//! energy, the energy balance of inelastic walls, and independence of the threads.

use gas::dsmc::{point_gas, SpatialDsmc, SpatialOptions};
use gas::observe::kinetic_energy;
use gas::system::System;
use gas::walls::{Motion, Side, Wall, WallKind, Walls, Waveform};
use gas::{Checkpoint, Engine};
use restitution::Constant;

/// N points in a cube of side 20 (phi 0.01 of unit spheres: ~0.6 mean free paths per cell
/// side by default), walls `floor` and `ceiling` on the last axis, gravity g along it.
fn column<const D: usize>(
    n: usize,
    eps: f64,
    floor: WallKind,
    ceiling: WallKind,
    g: f64,
    seed: u64,
) -> SpatialDsmc<D> {
    let system = point_gas::<D>(n, 20.0, 1.0, 1.0, 1.0, seed).unwrap();
    let mut e = SpatialDsmc::new(
        system,
        0.01,
        Box::new(Constant::new(eps).unwrap()),
        seed,
        SpatialOptions::default(),
    )
    .unwrap();
    let walls = vec![
        Wall {
            axis: D - 1,
            side: Side::Low,
            kind: floor,
        },
        Wall {
            axis: D - 1,
            side: Side::High,
            kind: ceiling,
        },
    ];
    e.set_walls(Some(Walls::new(walls, seed).unwrap())).unwrap();
    let gravity: [f64; D] = std::array::from_fn(|k| if k == D - 1 { -g } else { 0.0 });
    e.set_gravity(Some(gravity), 0.0).unwrap();
    e
}

fn energy<const D: usize>(s: &System<D>, g: f64) -> f64 {
    let potential: f64 = (0..s.len())
        .map(|i| s.masses[i] * g * s.positions[i][D - 1])
        .sum();
    kinetic_energy(s) + potential
}

/// Elastic points between elastic walls in gravity: kinetic plus potential energy is
/// conserved to round-off (streaming is exact, elastic collisions conserve energy), and
/// the points stay in the box.
#[test]
fn an_elastic_dsmc_column_conserves_its_energy() {
    let g = 0.1;
    let mut e = column::<3>(5000, 1.0, WallKind::Elastic, WallKind::Elastic, g, 3);
    let e0 = energy(e.system(), g);
    e.run_collisions(50_000);
    let s = e.system();
    assert!(s.positions.iter().all(|x| (0.0..20.0).contains(&x[2])));
    let drift = (energy(e.system(), g) - e0).abs() / e0;
    assert!(drift < 1e-11, "drift {drift}");
    assert!(e.walls().unwrap().iter().all(|w| w.tally.collisions > 100));
}

/// Oracle: the barometric law n(z) ∝ exp(−m g z / T), exact in equilibrium for points
/// (no excluded volume) between Maxwell walls at T = 1 (detailed balance). The scale
/// height is 5 (g = 0.2), the box 20 high: the density falls by e^4. Slabs of height 1
/// counted at 80 samples 2 time units apart; each slab's mean count within 5 standard
/// errors of the law, errors from 8 batches of 10 samples (counts are correlated over the
/// ~5 time units a point takes to cross a scale height).
#[test]
fn dsmc_in_gravity_is_barometric() {
    let g = 0.2;
    let thermal = || WallKind::Thermal { temperature: 1.0 };
    let mut e = column::<3>(20_000, 1.0, thermal(), thermal(), g, 5);
    e.run_until(40.0);
    let bins = 20;
    let samples = 80;
    let mut counts = vec![vec![0.0; bins]; samples];
    for (k, count) in counts.iter_mut().enumerate() {
        e.run_until(40.0 + 2.0 * (k + 1) as f64);
        for x in &e.system().positions {
            count[(x[2] as usize).min(bins - 1)] += 1.0;
        }
    }
    // Expected counts: N ∫_slab exp(−g z) dz / ∫_0^20 exp(−g z) dz.
    let norm = (1.0 - (-g * 20.0f64).exp()) / g;
    let mut worst = 0.0f64;
    for b in 0..bins {
        let z = b as f64;
        let expected = 20_000.0 * ((-g * z).exp() - (-g * (z + 1.0)).exp()) / g / norm;
        let batches: Vec<f64> = counts
            .chunks(10)
            .map(|c| c.iter().map(|s| s[b]).sum::<f64>() / 10.0)
            .collect();
        let mean = batches.iter().sum::<f64>() / 8.0;
        let error = (batches.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / 56.0).sqrt();
        worst = worst.max((mean - expected).abs() / error);
        eprintln!("slab {b}: {mean:.1} ± {error:.1} vs {expected:.1}");
        assert!(
            (mean - expected).abs() < 5.0 * error,
            "slab {b}: {mean} ± {error} vs {expected}"
        );
    }
    eprintln!("largest deviation {worst:.2} standard errors");
}

/// Inelastic walls (eps_w = 0.7, a vibrating sine floor) with elastic collisions: the gas's
/// energy changes by what the walls gave, to round-off; the run does not depend on the
/// number of threads (the contacts' sums are exact, thermal draws keyed by the particle);
/// a check-point resumes bit for bit.
#[test]
fn dsmc_walls_balance_energy_and_resume_on_any_threads() {
    let g = 0.1;
    let make = || {
        let floor = WallKind::Vibrating {
            law: Box::new(Constant::new(0.7).unwrap()),
            motion: Motion {
                amplitude: 0.2,
                frequency: 0.5,
                waveform: Waveform::Sine,
            },
        };
        column::<2>(
            4000,
            1.0,
            floor,
            WallKind::Thermal { temperature: 0.5 },
            g,
            8,
        )
    };
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut e = make();
            let e0 = energy(e.system(), g);
            e.run_collisions(40_000);
            let given: f64 = e.walls().unwrap().iter().map(|w| w.tally.energy).sum();
            let change = energy(e.system(), g) - e0;
            assert!((change - given).abs() < 1e-10 * e0, "{change} vs {given}");
            e.system().clone()
        })
    };
    assert_eq!(run(1), run(2));
    let mut e = make();
    e.run_collisions(20_000);
    let state = e.save();
    let mut resumed =
        SpatialDsmc::<2>::restore(state, Box::new(Constant::new(1.0).unwrap())).unwrap();
    let walls = vec![
        Wall {
            axis: 1,
            side: Side::Low,
            kind: WallKind::Vibrating {
                law: Box::new(Constant::new(0.7).unwrap()),
                motion: Motion {
                    amplitude: 0.2,
                    frequency: 0.5,
                    waveform: Waveform::Sine,
                },
            },
        },
        Wall {
            axis: 1,
            side: Side::High,
            kind: WallKind::Thermal { temperature: 0.5 },
        },
    ];
    resumed
        .set_walls(Some(Walls::new(walls, 8).unwrap()))
        .unwrap();
    resumed.set_gravity(Some([0.0, -g]), 0.0).unwrap();
    e.run_collisions(20_000);
    resumed.run_collisions(20_000);
    assert_eq!(e.system().clone(), resumed.system().clone());
    assert_eq!(e.walls(), resumed.walls());
}
