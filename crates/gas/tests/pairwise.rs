//! Pairwise laws (`restitution::pairwise::Pairwise`): every engine gives a collision of
//! species a with species b the pair's law. Checked exactly: a head-on collision of unlike
//! spheres in the event-driven engine separates at alpha_ab times the approach speed, and
//! a table whose pairs all hold one law runs bit for bit as that law alone (DSMC blocks,
//! exact, spatial; event-driven).

use gas::dsmc::{Scheme, SpatialOptions, StepSize};
use gas::init::{polydisperse, Species};
use gas::Engine;
use gas::{EventDriven, HomogeneousDsmc, SpatialDsmc, System};
use restitution::pairwise::Pairwise;
use restitution::{Constant, Restitution};

fn constant(eps: f64) -> Box<dyn Restitution> {
    Box::new(Constant::new(eps).unwrap())
}

/// Kinds of [`mixture`]: (radius, mass).
const KINDS: [(f64, f64); 2] = [(0.5, 1.0), (0.75, 3.0)];

fn table(alpha: [[f64; 2]; 2]) -> Box<dyn Restitution> {
    let laws = alpha
        .iter()
        .map(|row| row.iter().map(|&a| constant(a)).collect())
        .collect();
    Box::new(Pairwise::new(KINDS.to_vec(), laws).unwrap())
}

fn mixture<const D: usize>(n: usize, phi: f64, seed: u64) -> System<D> {
    let species = [
        Species {
            diameter: 1.0,
            mass: 1.0,
            fraction: 0.6,
        },
        Species {
            diameter: 1.5,
            mass: 3.0,
            fraction: 0.4,
        },
    ];
    polydisperse::<D>(n, phi, &species, 1.0, seed).unwrap()
}

/// Two spheres of unlike species approach head-on at speed 2 and leave at 2 alpha_01, the
/// off-diagonal law, not the others.
#[test]
fn unlike_spheres_collide_with_their_pair_s_law() {
    let system = System::<3> {
        sides: [20.0; 3],
        positions: vec![[5.0, 10.0, 10.0], [8.0, 10.0, 10.0]],
        velocities: vec![[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]],
        radii: vec![KINDS[0].0, KINDS[1].0],
        masses: vec![KINDS[0].1, KINDS[1].1],
    };
    let mut engine = EventDriven::new(system, table([[0.3, 0.7], [0.7, 0.2]])).unwrap();
    engine.run_collisions(1);
    let v = &engine.system().velocities;
    let separation = v[1][0] - v[0][0];
    assert!((separation - 0.7 * 2.0).abs() < 1e-12, "{separation}");
    // Momentum is conserved: 1 * 1 + 3 * (-1) = -2.
    assert!((v[0][0] + 3.0 * v[1][0] + 2.0).abs() < 1e-12);
}

/// A table holding one law for every pair is that law (same bits).
#[test]
fn a_uniform_table_is_the_law_itself() {
    let one = [[0.8; 2]; 2];
    let system = mixture::<3>(3000, 0.1, 4);
    let blocks = Scheme::Blocks {
        block_size: 500,
        step: StepSize::Auto,
    };
    for scheme in [blocks, Scheme::Exact] {
        let run = |law| {
            let mut e = HomogeneousDsmc::new(system.clone(), 0.1, law, 9, scheme).unwrap();
            e.run_collisions(20_000);
            (e.system().clone(), e.counters())
        };
        assert_eq!(run(table(one)), run(constant(0.8)), "{scheme:?}");
    }
    let run = |law| {
        let mut e =
            SpatialDsmc::new(system.clone(), 0.1, law, 9, SpatialOptions::default()).unwrap();
        e.run_collisions(20_000);
        (e.system().clone(), e.counters())
    };
    assert_eq!(run(table(one)), run(constant(0.8)), "spatial");
    let small = mixture::<3>(500, 0.1, 5);
    let run = |law| {
        let mut e = EventDriven::new(small.clone(), law).unwrap();
        e.run_collisions(5_000);
        (e.system().clone(), e.counters())
    };
    assert_eq!(run(table(one)), run(constant(0.8)), "event-driven");
}

/// Only one pair inelastic: the energy the DSMC tally records as lost is the energy the
/// gas lost (to round-off), and the species that never dissipates among itself still cools
/// through the cross collisions.
#[test]
fn energy_lost_is_the_pairs_dissipation() {
    let system = mixture::<3>(4000, 0.1, 6);
    let energy = |s: &System<3>| -> f64 {
        s.velocities
            .iter()
            .zip(&s.masses)
            .map(|(v, m)| 0.5 * m * v.iter().map(|x| x * x).sum::<f64>())
            .sum()
    };
    let before = energy(&system);
    let blocks = Scheme::Blocks {
        block_size: 1000,
        step: StepSize::Auto,
    };
    let mut e =
        HomogeneousDsmc::new(system, 0.1, table([[1.0, 0.5], [0.5, 1.0]]), 3, blocks).unwrap();
    e.run_collisions(40_000);
    let after = energy(e.system());
    let lost = e.counters().energy_lost;
    assert!(lost > 0.1 * before);
    assert!(
        ((before - after) / lost - 1.0).abs() < 1e-10,
        "{} vs {lost}",
        before - after
    );
}
