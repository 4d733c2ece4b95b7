//! The homogeneous DSMC engine's block scheme spread over ranks gives the single process's
//! run bit for bit: the same blocks, lanes and random streams, lanes moved between ranks
//! and exact sums over blocks (crates/gas/src/dsmc/homogeneous/blocks.rs). Ranks run as
//! threads of this process ([`InProcess`]); the MPI build runs the same engine through
//! `mpirun` (crates/cli/tests/mpi.rs).

use gas::dsmc::{point_gas, HomogeneousSnapshot, Scheme, StepSize};
use gas::parallel::{Communicator, InProcess};
use gas::Engine;
use gas::{Checkpoint, Counters, HomogeneousDsmc, System};
use restitution::{Constant, Restitution};
use std::sync::Arc;

fn law() -> Box<dyn Restitution> {
    Box::new(Constant::new(0.7).unwrap())
}

fn blocks(block_size: usize) -> Scheme {
    Scheme::Blocks {
        block_size,
        step: StepSize::Auto,
    }
}

/// What a run ends with: the velocities in the engine's order, the counters (energy and
/// virial sums included), the step temperature, the time and the exact-sum statistics.
#[derive(Debug, Clone, PartialEq)]
struct End<const D: usize> {
    system: System<D>,
    counters: Counters,
    temperature: f64,
    time: f64,
    statistics: (f64, f64),
}

fn end<const D: usize>(engine: &mut HomogeneousDsmc<D>) -> End<D> {
    let s = engine.velocity_statistics().unwrap();
    End {
        system: engine.system().clone(),
        counters: engine.counters(),
        temperature: engine.step_temperature(),
        time: engine.time(),
        statistics: (s.temperature, s.a2),
    }
}

fn gas<const D: usize>(n: usize, seed: u64, mixed: bool) -> System<D> {
    let mut system = point_gas::<D>(n, 10.0, 1.0, 1.0, 1.0, seed).unwrap();
    if mixed {
        for i in (1..n).step_by(3) {
            system.radii[i] = 0.6;
            system.masses[i] = 0.3;
        }
    }
    system
}

/// Runs on `ranks` in-process ranks; every rank must end with the same (gathered) result.
fn on_ranks<const D: usize>(
    ranks: usize,
    system: &System<D>,
    scheme: Scheme,
    collisions: u64,
) -> End<D> {
    let ends = InProcess::run(ranks, |comm| {
        let comm: Arc<dyn Communicator> = Arc::new(comm);
        let mut e =
            HomogeneousDsmc::distributed(system.clone(), 0.1, law(), 11, scheme, comm).unwrap();
        e.run_collisions(collisions);
        end(&mut e)
    });
    assert!(ends.iter().all(|e| *e == ends[0]), "ranks disagree");
    ends.into_iter().next().unwrap()
}

fn assert_identical<const D: usize>(system: &System<D>, scheme: Scheme, collisions: u64) {
    let mut single = HomogeneousDsmc::new(system.clone(), 0.1, law(), 11, scheme).unwrap();
    single.run_collisions(collisions);
    let want = end(&mut single);
    assert!(want.counters.collisions >= collisions);
    for ranks in [1, 2, 3, 4] {
        let got = on_ranks(ranks, system, scheme, collisions);
        assert!(
            got == want,
            "{ranks} ranks, {D}D: {:?} T = {} where the single process has {:?} T = {}",
            got.counters,
            got.temperature,
            want.counters,
            want.temperature
        );
    }
}

/// One species in 3D and a mixture in 2D; blocks whose size leaves a remainder beyond the
/// whole lanes, gases that do not split into equal blocks, several steps.
#[test]
fn blocks_on_1_2_3_4_ranks_run_as_one_process() {
    assert_identical(&gas::<3>(2_003, 3, false), blocks(90), 20_000);
    assert_identical(&gas::<2>(1_500, 4, true), blocks(130), 15_000);
}

/// A snapshot taken on 3 ranks (the gathered gas) continues on 2 ranks and on 1 exactly as
/// the single process run in the same two pieces (the last steps of a piece are shortened
/// to its target).
#[test]
fn a_snapshot_from_3_ranks_continues_on_2_and_on_1() {
    let system = gas::<3>(1_200, 5, true);
    let scheme = blocks(100);
    let mut single = HomogeneousDsmc::new(system.clone(), 0.1, law(), 11, scheme).unwrap();
    single.run_collisions(5_000);
    single.run_collisions(12_000 - single.counters().collisions);
    let want = end(&mut single);
    let snapshots: Vec<HomogeneousSnapshot<3>> = InProcess::run(3, |comm| {
        let comm: Arc<dyn Communicator> = Arc::new(comm);
        let mut e =
            HomogeneousDsmc::distributed(system.clone(), 0.1, law(), 11, scheme, comm).unwrap();
        e.run_collisions(5_000);
        e.save()
    });
    assert!(snapshots.iter().all(|s| s.system == snapshots[0].system));
    let collisions = 12_000 - snapshots[0].counters.collisions;
    for ranks in [2, 1] {
        let ends = InProcess::run(ranks, |comm| {
            let comm: Arc<dyn Communicator> = Arc::new(comm);
            let mut e =
                HomogeneousDsmc::restore_distributed(snapshots[0].clone(), law(), comm).unwrap();
            e.run_collisions(collisions);
            end(&mut e)
        });
        assert!(ends.iter().all(|e| *e == want), "resumed on {ranks} ranks");
    }
}

/// The exact scheme on several ranks and more ranks than blocks are refused, naming
/// `ranks`; rank reports add up to the gas, what one rank sends another receives, and the
/// lanes sent are whole lanes of records.
#[test]
fn refusals_and_reports() {
    let system = gas::<3>(400, 6, false);
    let errors = InProcess::run(5, |comm| {
        let comm: Arc<dyn Communicator> = Arc::new(comm);
        let exact = HomogeneousDsmc::distributed(
            system.clone(),
            0.1,
            law(),
            11,
            Scheme::Exact,
            comm.clone(),
        );
        let too_many =
            HomogeneousDsmc::distributed(system.clone(), 0.1, law(), 11, blocks(100), comm);
        [exact, too_many].map(|e| e.err().map(|e| e.to_string()).unwrap_or_default())
    });
    let [exact, too_many] = &errors[0];
    assert!(
        exact.contains("ranks") && exact.contains("exact scheme"),
        "{exact}"
    );
    assert!(
        too_many.contains("ranks") && too_many.contains("at most the 4 blocks"),
        "{too_many}"
    );
    let reports = InProcess::run(2, |comm| {
        let comm: Arc<dyn Communicator> = Arc::new(comm);
        let mut e =
            HomogeneousDsmc::distributed(system.clone(), 0.1, law(), 11, blocks(50), comm).unwrap();
        e.run_collisions(2_000);
        e.rank_reports().unwrap()
    });
    assert_eq!(reports[0], reports[1]);
    let r = &reports[0];
    assert_eq!(r.iter().map(|x| x.particles).sum::<usize>(), 400);
    assert_eq!(r.iter().map(|x| x.cells).sum::<u64>(), 8);
    assert_eq!(r[0].bytes_sent, r[1].bytes_received);
    assert_eq!(r[0].bytes_sent, 8 * 3 * r[0].migrants_sent);
    assert!(r[0].steps > 0 && r[0].migrants_sent.is_multiple_of(16));
}
