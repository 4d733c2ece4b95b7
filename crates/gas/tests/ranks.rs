//! The spatial DSMC engine spread over ranks gives the single process's run bit for bit:
//! ranks run as threads of this process ([`InProcess`], the collectives MPI's would be), so
//! the argument of `gas::dsmc::domain` is checked without MPI. (The MPI build runs the same
//! engine through `mpirun`: crates/cli/tests/mpi.rs.)

use gas::dsmc::{point_gas, SpatialOptions, SpatialSnapshot, StepSize};
use gas::parallel::{Communicator, InProcess};
use gas::Engine;
use gas::{Checkpoint, Counters, SpatialDsmc, System};
use restitution::{Constant, Restitution};
use std::sync::Arc;

fn law() -> Box<dyn Restitution> {
    Box::new(Constant::new(0.8).unwrap())
}

/// What a run ends with: the state in the engine's order, the counters (energy and virial
/// sums included), the step temperature and the time.
#[derive(Debug, Clone, PartialEq)]
struct End<const D: usize> {
    system: System<D>,
    counters: Counters,
    temperature: f64,
    time: f64,
}

fn end<const D: usize>(engine: &mut SpatialDsmc<D>) -> End<D> {
    End {
        system: engine.system().clone(),
        counters: engine.counters(),
        temperature: engine.step_temperature(),
        time: engine.time(),
    }
}

/// Runs `system` for `collisions` collisions on `ranks` in-process ranks; every rank must
/// end with the same (gathered) result, which is returned.
fn on_ranks<const D: usize>(
    ranks: usize,
    system: &System<D>,
    options: SpatialOptions,
    collisions: u64,
) -> End<D> {
    let ends = InProcess::run(ranks, |comm| {
        let comm: Arc<dyn Communicator> = Arc::new(comm);
        let mut e = SpatialDsmc::distributed(system.clone(), 0.1, law(), 7, options, comm).unwrap();
        e.run_collisions(collisions);
        end(&mut e)
    });
    ends.iter()
        .for_each(|e| same(e, &ends[0], "rank against rank 0"));
    ends.into_iter().next().unwrap()
}

/// Asserts equal ends, printing the counters (not the particles) if they differ.
fn same<const D: usize>(got: &End<D>, want: &End<D>, what: &str) {
    assert!(
        got == want,
        "{what}: {:?} T = {} t = {} where the single process has {:?} T = {} t = {}",
        got.counters,
        got.temperature,
        got.time,
        want.counters,
        want.temperature,
        want.time
    );
}

/// Half the particles of `system` heavier and larger: a mixture of two species.
fn mixture<const D: usize>(mut system: System<D>) -> System<D> {
    for i in (1..system.len()).step_by(2) {
        system.radii[i] = 0.7;
        system.masses[i] = 2.0;
    }
    system
}

fn assert_identical<const D: usize>(system: &System<D>, options: SpatialOptions, collisions: u64) {
    let mut single = SpatialDsmc::new(system.clone(), 0.1, law(), 7, options).unwrap();
    single.run_collisions(collisions);
    let want = end(&mut single);
    assert!(want.counters.collisions >= collisions);
    for ranks in [1, 2, 3, 4] {
        let got = on_ranks(ranks, system, options, collisions);
        same(&got, &want, &format!("{ranks} ranks, {D}D"));
    }
}

/// 3D, one species and a mixture, the default step: long enough for the slabs to be
/// re-balanced several times (every 20 steps); and cells so fine that the ranks sort by
/// comparison.
#[test]
fn three_dimensions_on_1_2_3_4_ranks() {
    let system = point_gas::<3>(3000, 20.0, 1.0, 1.0, 1.0, 11).unwrap();
    assert_identical(&system, SpatialOptions::default(), 30_000);
    assert_identical(&mixture(system.clone()), SpatialOptions::default(), 30_000);
    // Cells narrow enough that a rank has more than 4 per particle: the comparison sort.
    let fine = SpatialOptions {
        cell_width: Some(1.0),
        ..Default::default()
    };
    assert_identical(&system, fine, 10_000);
}

/// 1D and 2D, with a step so long that particles cross several slabs in one step (the
/// migration then goes beyond the neighbouring ranks).
#[test]
fn long_steps_in_one_and_two_dimensions() {
    let long = SpatialOptions {
        cell_width: None,
        step: StepSize::CollisionsPerParticle(2.0),
    };
    let plane = point_gas::<2>(2000, 60.0, 1.0, 1.0, 1.0, 12).unwrap();
    assert_identical(&plane, long, 20_000);
    let line = point_gas::<1>(1000, 2000.0, 1.0, 1.0, 1.0, 13).unwrap();
    assert_identical(&mixture(line), long, 10_000);
}

/// A snapshot taken on 3 ranks (it is the whole gas, gathered) continues on 2 ranks, and on
/// one, as the uninterrupted single-process run.
#[test]
fn a_snapshot_from_3_ranks_continues_on_2_and_on_1() {
    let system = point_gas::<3>(2000, 18.0, 1.0, 1.0, 1.0, 14).unwrap();
    let options = SpatialOptions::default();
    // The reference runs in the same two pieces (the last steps of a piece are shortened
    // to its target).
    let mut single = SpatialDsmc::new(system.clone(), 0.1, law(), 7, options).unwrap();
    single.run_collisions(9_000);
    single.run_collisions(20_000 - single.counters().collisions);
    let want = end(&mut single);
    let snapshots: Vec<SpatialSnapshot<3>> = InProcess::run(3, |comm| {
        let comm: Arc<dyn Communicator> = Arc::new(comm);
        let mut e = SpatialDsmc::distributed(system.clone(), 0.1, law(), 7, options, comm).unwrap();
        e.run_collisions(9_000);
        e.save()
    });
    assert!(snapshots.iter().all(|s| s.system == snapshots[0].system));
    let snapshot = snapshots.into_iter().next().unwrap();
    let remaining = 20_000 - snapshot.counters.collisions;
    let ends = InProcess::run(2, |comm| {
        let comm: Arc<dyn Communicator> = Arc::new(comm);
        let mut e = SpatialDsmc::restore_distributed(snapshot.clone(), law(), comm).unwrap();
        e.run_collisions(remaining);
        end(&mut e)
    });
    same(&ends[0], &want, "restored on 2 ranks");
    same(&ends[1], &want, "restored on 2 ranks");
    let mut one = SpatialDsmc::restore(snapshot, law()).unwrap();
    one.run_collisions(remaining);
    same(&end(&mut one), &want, "restored on 1 rank");
}

/// More ranks than planes of cells: refused, naming `ranks` and the limit. Rank reports
/// add up to the gas.
#[test]
fn ranks_beyond_the_planes_are_refused_and_reports_add_up() {
    let system = point_gas::<3>(200, 10.0, 1.0, 1.0, 1.0, 15).unwrap();
    let errors = InProcess::run(5, |comm| {
        let comm: Arc<dyn Communicator> = Arc::new(comm);
        let options = SpatialOptions {
            cell_width: Some(2.5),
            ..Default::default()
        };
        SpatialDsmc::distributed(system.clone(), 0.1, law(), 7, options, comm)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    });
    assert!(
        errors[0].contains("ranks") && errors[0].contains("at most 4"),
        "{}",
        errors[0]
    );
    let reports = InProcess::run(2, |comm| {
        let comm: Arc<dyn Communicator> = Arc::new(comm);
        let mut e =
            SpatialDsmc::distributed(system.clone(), 0.1, law(), 7, Default::default(), comm)
                .unwrap();
        e.run_collisions(500);
        e.rank_reports().unwrap()
    });
    assert_eq!(reports[0], reports[1]);
    let r = &reports[0];
    assert_eq!(r.iter().map(|x| x.particles).sum::<usize>(), 200);
    assert_eq!(r[0].bytes_sent, r[1].bytes_received);
    assert_eq!(r[0].bytes_sent, 8 * 8 * r[0].migrants_sent);
    assert!(r[0].steps > 0 && r[0].steps == r[1].steps);
}

/// The temperature and a2 from exact sums over the ranks are those of the gathered gas
/// (`gas::observe`, sequential sums: equal to rounding, 1e-12 relative), the same bits on
/// every number of ranks.
#[test]
fn velocity_statistics_are_the_gathered_gas_s() {
    let system = mixture(point_gas::<3>(3000, 20.0, 1.0, 1.0, 1.0, 16).unwrap());
    let stats = |ranks: usize| {
        InProcess::run(ranks, |comm| {
            let comm: Arc<dyn Communicator> = Arc::new(comm);
            let mut e =
                SpatialDsmc::distributed(system.clone(), 0.1, law(), 7, Default::default(), comm)
                    .unwrap();
            e.run_collisions(5_000);
            let s = e.velocity_statistics().unwrap();
            let gathered = e.system().clone();
            (
                s,
                gas::observe::temperature(&gathered),
                gas::observe::sonine_a2(&gathered),
            )
        })
    };
    let one = stats(1);
    let (s, t, a2) = one[0];
    assert!(
        (s.temperature - t).abs() <= 1e-12 * t,
        "{} {t}",
        s.temperature
    );
    assert!(
        (s.a2 - a2).abs() <= 1e-12 * (1.0 + a2.abs()),
        "{} {a2}",
        s.a2
    );
    assert_eq!(s.volume, 20f64.powi(3));
    for ranks in [2, 3] {
        for (s2, _, _) in stats(ranks) {
            assert_eq!(s2, s, "{ranks} ranks");
        }
    }
}

/// A container on ranks: a 2D column in a box of sides 30 x 60 (the slabs cut across the
/// walls' axis y), a vibrating floor, a thermal ceiling, thermal side walls on x, gravity
/// along y. Each rank streams its particles against the walls (thermal draws keyed by the
/// particle, not the rank) and the walls' tallies are summed over the ranks exactly: the
/// state, counters and every wall's tallies are the single process's, bit for bit, on 1 to
/// 4 ranks.
#[test]
fn a_container_on_ranks_is_the_single_process_run() {
    use gas::walls::{Motion, Side, Wall, WallKind, WallRecord, Walls, Waveform};
    let system = point_gas::<2>(4000, [30.0, 60.0], 1.0, 1.0, 1.0, 11).unwrap();
    let options = SpatialOptions::default();
    let walls = || {
        let wall = |axis, side, kind| Wall { axis, side, kind };
        let floor = WallKind::Vibrating {
            law: Box::new(Constant::new(0.9).unwrap()),
            motion: Motion {
                amplitude: 0.5,
                frequency: 0.3,
                waveform: Waveform::Sine,
            },
        };
        let thermal = || WallKind::Thermal { temperature: 1.5 };
        let list = vec![
            wall(1, Side::Low, floor),
            wall(1, Side::High, thermal()),
            wall(0, Side::Low, thermal()),
            wall(0, Side::High, thermal()),
        ];
        Walls::new(list, 7).unwrap()
    };
    let run = |comm: Arc<dyn Communicator>| -> (End<2>, Vec<WallRecord>) {
        let mut e =
            SpatialDsmc::distributed(system.clone(), 0.05, law(), 7, options, comm).unwrap();
        e.set_walls(Some(walls())).unwrap();
        e.set_gravity(Some([0.0, -0.05]), 1e-3).unwrap();
        e.run_collisions(40_000);
        let records = e.walls().unwrap();
        (end(&mut e), records)
    };
    let want = run(Arc::new(gas::parallel::Local));
    assert!(
        want.1.iter().all(|w| w.tally.collisions > 100),
        "{:?}",
        want.1
    );
    for ranks in [2, 3, 4] {
        let ends = InProcess::run(ranks, |comm| run(Arc::new(comm)));
        for got in &ends {
            same(&got.0, &want.0, &format!("{ranks} ranks in a container"));
            assert_eq!(got.1, want.1, "{ranks} ranks: the walls' tallies");
        }
    }
}
