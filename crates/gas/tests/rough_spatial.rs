//! Rough particles in the spatial DSMC engine, what only it has: spins that travel with
//! their particles through the sort into cells, a container's walls and the slabs of
//! ranks; energy kept by perfectly rough elastic particles, walls and gravity included;
//! the same run bit for bit on any number of ranks and from a check-point taken on
//! others; and the cooling state's ratio T_rot / T_tr of the homogeneous DSMC, where the
//! Maxwellian theory is 7 % off. (`tests/rough.rs` holds the tests all rough engines
//! share: beta = -1 is the smooth gas, the relaxation from rest against the theory,
//! check-points.)

mod common;

use common::{constant, mean_and_error};
use gas::dsmc::{point_gas, Scheme, SpatialOptions, SpatialSnapshot};
use gas::observe::{kinetic_energy, temperature};
use gas::parallel::{Communicator, InProcess, Local};
use gas::rotation::Rotation;
use gas::system::System;
use gas::theory::rough::RoughMaxwellian;
use gas::walls::{Side, Wall, WallKind, Walls};
use gas::{Checkpoint, Counters, Engine, HomogeneousDsmc, SpatialDsmc};
use restitution::rough::{Rough, Tangential};
use restitution::Restitution;
use std::sync::Arc;

fn rough(alpha: f64, beta: f64, friction: Option<f64>) -> Box<dyn Restitution> {
    Box::new(Rough::new(constant(alpha), Tangential::new(beta, friction).unwrap()).unwrap())
}

/// Walls on the last axis: elastic below, thermal (T = 1.2) above.
fn container<const D: usize>(seed: u64) -> Walls<D> {
    let wall = |side, kind| Wall {
        axis: D - 1,
        side,
        kind,
    };
    let list = vec![
        wall(Side::Low, WallKind::Elastic),
        wall(Side::High, WallKind::Thermal { temperature: 1.2 }),
    ];
    Walls::new(list, seed).unwrap()
}

/// Each particle's spin is its label (w_x = its index at the start) and beta = -1: no
/// tangential impulse, so the spins are never changed and the gas is the smooth one bit
/// for bit. After 10 collisions per particle (50 steps of sorting, streaming through the
/// periodic faces or against a container's walls under gravity), the record at each
/// place must be the particle its label names. The oracle is the engine's tracks, which
/// follow each particle by an identity the spins know nothing of: the labelled particle's
/// start plus the tracked displacement is where the record is now, to rounding, up to
/// whole box sides.
#[test]
fn spins_travel_with_their_particles() {
    for walled in [false, true] {
        let n = 3000;
        let system = point_gas::<3>(n, 25.0, 1.0, 1.0, 1.0, 21).unwrap();
        let labels = Rotation {
            inertia: vec![0.4; n],
            angular: (0..n).map(|i| [i as f64, 0.0, 0.0]).collect(),
            sliding: 0,
        };
        let make = |law: Box<dyn Restitution>| {
            let mut e =
                SpatialDsmc::new(system.clone(), 0.05, law, 3, SpatialOptions::default()).unwrap();
            if walled {
                e.set_walls(Some(container(3))).unwrap();
                e.set_gravity(Some([0.0, 0.0, -0.02]), 0.0).unwrap();
            }
            e.set_tracking(true).unwrap();
            e
        };
        let mut smooth = make(constant(0.8));
        let mut spun = make(rough(0.8, -1.0, None));
        spun.set_rotation(Some(labels)).unwrap();
        smooth.run_collisions(5 * n as u64);
        spun.run_collisions(5 * n as u64);
        assert_eq!(smooth.system(), spun.system(), "walls: {walled}");
        assert_eq!(smooth.counters(), spun.counters());
        let now = spun.system().clone();
        let moved = spun.displacements().unwrap();
        let angular = spun.rotation().unwrap().angular.clone();
        let mut seen = vec![false; n];
        for (k, w) in angular.iter().enumerate() {
            let j = w[0] as usize;
            assert!(w[0] == j as f64 && w[1] == 0.0 && w[2] == 0.0, "{w:?}");
            assert!(!seen[j], "label {j} twice");
            seen[j] = true;
            let (start, here) = (&system.positions[j], &now.positions[k]);
            for (axis, step) in moved[k].iter().enumerate() {
                let laps = (start[axis] + step - here[axis]) / now.sides[axis];
                assert!(
                    (laps - laps.round()).abs() < 1e-9,
                    "walls {walled}: record {k} carries the spin of particle {j}, axis {axis}: {laps}"
                );
            }
        }
    }
}

/// Perfectly rough elastic particles (alpha = beta = 1) lose no energy: translation and
/// rotation exchange it, and kinetic plus rotational energy (plus the potential energy
/// in a container under gravity, between elastic walls) is kept to round-off over 20
/// collisions per particle (the oracle: conservation). Disks in a periodic box, spheres
/// in a container.
#[test]
fn perfectly_rough_elastic_particles_keep_their_energy() {
    fn case<const D: usize>(walls: bool) {
        let n = 2000;
        let system = point_gas::<D>(n, 20.0, 1.0, 1.0, 1.0, 5).unwrap();
        let q = if D == 2 { 0.5 } else { 0.4 };
        let rotation = Rotation::thermal(&system, vec![q; n], 0.2, 5);
        let law = rough(1.0, 1.0, None);
        let mut e = SpatialDsmc::new(system, 0.05, law, 9, SpatialOptions::default()).unwrap();
        let g = 0.05;
        if walls {
            let wall = |side| Wall {
                axis: D - 1,
                side,
                kind: WallKind::Elastic,
            };
            let list = vec![wall(Side::Low), wall(Side::High)];
            e.set_walls(Some(Walls::new(list, 1).unwrap())).unwrap();
            let gravity: [f64; D] = std::array::from_fn(|k| if k == D - 1 { -g } else { 0.0 });
            e.set_gravity(Some(gravity), 0.0).unwrap();
        }
        e.set_rotation(Some(rotation)).unwrap();
        let energy = |e: &mut SpatialDsmc<D>| {
            let s = e.system().clone();
            let height: f64 = if walls {
                (0..n)
                    .map(|i| s.masses[i] * g * s.positions[i][D - 1])
                    .sum()
            } else {
                0.0
            };
            let rotation = e.rotation().unwrap();
            (
                kinetic_energy(&s) + rotation.energy(&s) + height,
                rotation.temperature(&s, None),
            )
        };
        let (start, t_rot) = energy(&mut e);
        e.run_collisions(10 * n as u64);
        let (end, after) = energy(&mut e);
        assert!(
            (end - start).abs() < 1e-11 * start,
            "{D}D, walls {walls}: {start} -> {end}"
        );
        assert!(e.counters().energy_lost.abs() < 1e-11 * start);
        // Rotation took its share from 0.2 on (equipartition: about 0.6 in 3D).
        assert!(after > t_rot + 0.1, "{D}D: T_rot {t_rot} -> {after}");
    }
    case::<2>(false);
    case::<3>(true);
}

/// What a rough run ends with: the state, counters, step temperature, time and the
/// rotation (spins and sliding contacts), all in the engine's order.
#[derive(Debug, Clone, PartialEq)]
struct End<const D: usize> {
    system: System<D>,
    counters: Counters,
    temperature: f64,
    time: f64,
    rotation: Rotation,
}

fn end<const D: usize>(e: &mut SpatialDsmc<D>) -> End<D> {
    End {
        system: e.system().clone(),
        counters: e.counters(),
        temperature: e.step_temperature(),
        time: e.time(),
        rotation: e.rotation().unwrap().clone(),
    }
}

/// A rough gas with Walton's friction (alpha 0.8, beta 0.4, mu 0.2), in a periodic box
/// and in a container, on 1 to 4 ranks (threads standing for MPI ranks): the records
/// cross the slabs with their spins, the sliding contacts are summed over the ranks, and
/// every rank ends with the single process's state, counters and rotation bit for bit.
/// The messages carry 11 values per rough record in 3D (position, velocity, species,
/// place, spin). A check-point taken on 3 ranks continues on 2 and on 1 as the
/// uninterrupted run.
#[test]
fn a_rough_gas_on_ranks_is_the_single_process_run() {
    let system = point_gas::<3>(3000, 20.0, 1.0, 1.0, 1.0, 11).unwrap();
    let rotation = Rotation::thermal(&system, vec![0.35; 3000], 0.5, 11);
    let law = || rough(0.8, 0.4, Some(0.2));
    let make = |walled: bool, comm: Arc<dyn Communicator>| {
        let options = SpatialOptions::default();
        let mut e = SpatialDsmc::distributed(system.clone(), 0.1, law(), 7, options, comm).unwrap();
        if walled {
            e.set_walls(Some(container(7))).unwrap();
        }
        e.set_rotation(Some(rotation.clone())).unwrap();
        e
    };
    for walled in [false, true] {
        let mut single = make(walled, Arc::new(Local));
        single.run_collisions(30_000);
        let want = end(&mut single);
        let sliding = want.rotation.sliding;
        assert!(sliding > 100 && sliding < 30_000, "some slide: {sliding}");
        for ranks in [2, 3, 4] {
            let got = InProcess::run(ranks, |c| {
                let mut e = make(walled, Arc::new(c));
                e.run_collisions(30_000);
                (end(&mut e), e.rank_reports().unwrap())
            });
            for (rank, (got, reports)) in got.iter().enumerate() {
                assert!(
                    *got == want,
                    "walls {walled}, {ranks} ranks, rank {rank}: {:?} vs {:?}",
                    got.counters,
                    want.counters
                );
                let sent: u64 = reports.iter().map(|r| r.bytes_sent).sum();
                let migrants: u64 = reports.iter().map(|r| r.migrants_sent).sum();
                assert!(migrants > 0);
                assert_eq!(sent, 8 * 11 * migrants);
            }
        }
    }
    let mut single = make(false, Arc::new(Local));
    single.run_collisions(12_000);
    single.run_collisions(30_000 - single.counters().collisions);
    let want = end(&mut single);
    let snapshots: Vec<SpatialSnapshot<3>> = InProcess::run(3, |c| {
        let mut e = make(false, Arc::new(c));
        e.run_collisions(12_000);
        e.save()
    });
    let snapshot = snapshots.into_iter().next().unwrap();
    let text = serde_json::to_string(&snapshot).unwrap();
    let remaining = 30_000 - snapshot.counters.collisions;
    let ends = InProcess::run(2, |c| {
        let snapshot = serde_json::from_str(&text).unwrap();
        let mut e = SpatialDsmc::restore_distributed(snapshot, law(), Arc::new(c)).unwrap();
        e.run_collisions(remaining);
        end(&mut e)
    });
    assert!(ends.iter().all(|e| *e == want), "restored on 2 ranks");
    let mut one = SpatialDsmc::<3>::restore(serde_json::from_str(&text).unwrap(), law()).unwrap();
    one.run_collisions(remaining);
    assert!(end(&mut one) == want, "restored on 1 rank");
}

/// The homogeneous cooling state of rough spheres (alpha 0.7, beta 0, q 0.4): the
/// spatial engine's ratio T_rot / T_tr, averaged over collisions 15 to 30 per particle
/// from the Maxwellian ratio, is the homogeneous DSMC's (blocks) within 4 combined
/// standard errors of 8 seeds each, N = 8000 in a box of 4 mean free paths (phi = 0.005:
/// no room for clusters). The Maxwellian theory's ratio, 1.219, is 7 % above both (the
/// correlations it leaves out, docs/rough.md; measured: 1.132 ± 0.004 and 1.132 ± 0.003,
/// some 18 combined standard errors below it): the comparison is between the two
/// engines, the bounds on the theory's ratio only a check that the state is the one
/// meant.
#[test]
fn the_cooling_state_is_the_homogeneous_engine_s() {
    let (alpha, beta, q, n) = (0.7, 0.0, 0.4, 8000);
    let theory = RoughMaxwellian {
        dimension: 3,
        alpha,
        beta,
        inertia: q,
    };
    let maxwellian = theory.hcs().unwrap().ratio;
    let ratio = |spatial: bool, seed: u64| {
        let system = point_gas::<3>(n, 94.3, 1.0, 1.0, 1.0, 100 + seed).unwrap();
        let rotation = Rotation::thermal(&system, vec![q; n], maxwellian, 100 + seed);
        let law = rough(alpha, beta, None);
        let mut e: Box<dyn Engine<3>> = if spatial {
            let options = SpatialOptions::default();
            Box::new(SpatialDsmc::new(system, 0.005, law, seed, options).unwrap())
        } else {
            Box::new(HomogeneousDsmc::new(system, 0.005, law, seed, Scheme::default()).unwrap())
        };
        e.set_rotation(Some(rotation)).unwrap();
        let mut sum = 0.0;
        for tau in 15..=30u64 {
            e.run_collisions((tau * n as u64 / 2).saturating_sub(e.counters().collisions));
            let s = e.system().clone();
            sum += e.rotation().unwrap().temperature(&s, None) / temperature(&s);
        }
        sum / 16.0
    };
    let (spatial, e_s) = mean_and_error(&(0..8).map(|s| ratio(true, s)).collect::<Vec<_>>());
    let (blocks, e_b) = mean_and_error(&(0..8).map(|s| ratio(false, s)).collect::<Vec<_>>());
    let combined = (e_s * e_s + e_b * e_b).sqrt();
    eprintln!(
        "T_rot/T_tr: spatial {spatial} ± {e_s}, blocks {blocks} ± {e_b}, Maxwellian {maxwellian}"
    );
    assert!(
        (spatial - blocks).abs() < 4.0 * combined,
        "spatial {spatial} ± {e_s}, blocks {blocks} ± {e_b}"
    );
    for got in [spatial, blocks] {
        assert!(
            got < 0.97 * maxwellian && got > 0.85 * maxwellian,
            "{got} vs {maxwellian}"
        );
    }
}
