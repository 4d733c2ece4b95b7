//! The ranks a run is spread over. By default a run is this process alone; a binary built
//! with the cargo feature `mpi` and launched by `mpirun -n R` runs the spatial DSMC engine
//! on R ranks (Open MPI through the `mpi` crate, rsmpi). The engine sees only
//! [`gas::parallel::Communicator`]; this module supplies MPI's, once per process
//! ([`start`]), as the [`world`] every [`crate::Simulation`] takes.
//!
//! A run is the same, bit for bit, on any number of ranks (`gas::dsmc` domain
//! decomposition). Every rank runs the same driver (schedule, observers, check-point state:
//! the engine gathers the gas for them); rank 0 writes the files.

use crate::error::{Error, Result};
use crate::validate::Plan;
pub use gas::parallel::{Communicator, InProcess, Local, RankReport};
use std::sync::{Arc, OnceLock};

/// The communicator of this process, set by [`start`].
static WORLD: OnceLock<Arc<dyn Communicator>> = OnceLock::new();

/// The ranks runs of this process are spread over: MPI's world after [`start`] under
/// mpirun, else this process alone.
pub fn world() -> Arc<dyn Communicator> {
    WORLD.get().cloned().unwrap_or_else(|| Arc::new(Local))
}

/// The environment variables by which launchers tell a process how many ranks there are
/// (Open MPI's mpirun, MPICH's and Intel MPI's Hydra).
const LAUNCHER_SIZES: [&str; 2] = ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE"];

/// How many ranks a launcher started this process among, if one did.
pub fn launched_ranks() -> Option<usize> {
    LAUNCHER_SIZES
        .iter()
        .find_map(|name| std::env::var(name).ok()?.trim().parse().ok())
}

/// Whether this binary was built with MPI (the cargo feature `mpi`).
pub const WITH_MPI: bool = cfg!(feature = "mpi");

/// The MPI session of this process: holds MPI open until dropped (then MPI_Finalize).
pub struct Session {
    #[cfg(feature = "mpi")]
    _universe: Option<mpi::environment::Universe>,
}

/// Joins the ranks this process was launched among (MPI_Init), if it was launched by an
/// MPI launcher, and makes them the [`world`]. Without the feature `mpi`, a launch on
/// several ranks is an error (it would run the same run R times, each writing the same
/// files). Keep the session until the end of the process.
pub fn start() -> Result<Session> {
    let launched = launched_ranks();
    #[cfg(feature = "mpi")]
    {
        if launched.is_none() {
            return Ok(Session { _universe: None });
        }
        let (universe, _) = mpi::initialize_with_threading(mpi::Threading::Serialized)
            .ok_or_else(|| Error::input("mpirun", "MPI was already initialized"))?;
        let _ = WORLD.set(Arc::new(mpi_world::Mpi {
            world: universe.world(),
        }));
        Ok(Session {
            _universe: Some(universe),
        })
    }
    #[cfg(not(feature = "mpi"))]
    match launched {
        Some(ranks) if ranks > 1 => Err(Error::input(
            "mpirun",
            format!(
                "launched on {ranks} ranks, but this haff was built without MPI: build it with \
                 `cargo build --release --features mpi` and launch target/release/haff"
            ),
        )),
        _ => Ok(Session {}),
    }
}

/// Ends all ranks at once with exit code `code` (MPI_Abort) when one fails alone, so that
/// the others do not wait for it forever; nothing on one rank.
pub fn abort_others(code: i32) {
    #[cfg(feature = "mpi")]
    if world().size() > 1 {
        use mpi::topology::Communicator as _;
        mpi::topology::SimpleCommunicator::world().abort(code);
    }
    let _ = code;
}

/// Which engines spread over ranks, for error messages.
pub(crate) fn spreading() -> String {
    format!(
        "only run.engine = {} spreads over ranks",
        crate::engines::kinds_that(|a| a.ranks)
    )
}

/// Checks the plan against the ranks the run is launched on: `run.ranks` must match, and
/// only the spatial DSMC engine and the homogeneous one's block scheme spread over ranks.
pub fn check_ranks(plan: &Plan, size: usize) -> Result<()> {
    if let Some(wanted) = plan.description.run.ranks {
        if wanted != size {
            let how = if WITH_MPI {
                format!("launch it with `mpirun -n {wanted} haff run FILE`")
            } else {
                format!(
                    "that needs haff built with MPI (`cargo build --release --features mpi`), \
                     launched with `mpirun -n {wanted} target/release/haff run FILE`"
                )
            };
            return Err(Error::input(
                "run.ranks",
                format!("the run asks for {wanted} ranks and runs on {size}: {how}"),
            ));
        }
    }
    if size > 1 && !plan.engine.abilities().ranks {
        return Err(Error::input(
            "run.engine",
            format!(
                "launched on {size} ranks: {}; run this engine in one process",
                spreading()
            ),
        ));
    }
    Ok(())
}

/// The `parallel` entry of `summary.json`: ranks, every rank's report, and per step the
/// mean migration volume and communication time per rank.
pub fn summary(ranks: &[RankReport], dimension: usize) -> serde_json::Value {
    let n = ranks.len().max(1) as f64;
    let steps = ranks.first().map_or(0, |r| r.steps).max(1) as f64;
    let mean = |f: fn(&RankReport) -> f64| ranks.iter().map(f).sum::<f64>() / n;
    serde_json::json!({
        "ranks": ranks.len(),
        "steps": ranks.first().map_or(0, |r| r.steps),
        "bytes_sent_per_rank_per_step": mean(|r| r.bytes_sent as f64) / steps,
        "reduction_bytes_per_rank_per_step": gas::parallel::reduction_bytes(dimension),
        "communication_seconds_per_step": mean(|r| r.communication_seconds) / steps,
        "step_seconds": mean(|r| r.step_seconds) / steps,
        "communication_fraction": mean(|r| r.communication_seconds) / mean(|r| r.step_seconds).max(1e-300),
        "load_imbalance": ranks.iter().map(|r| r.particles).max().unwrap_or(0) as f64
            / (ranks.iter().map(|r| r.particles).sum::<usize>() as f64 / n).max(1e-300),
        "per_rank": ranks,
    })
}

#[cfg(feature = "mpi")]
mod mpi_world {
    //! [`Communicator`] on MPI_COMM_WORLD.
    use super::Communicator;
    use mpi::datatype::{Partition, PartitionMut};
    use mpi::topology::Communicator as _;
    use mpi::traits::*;
    use mpi::Count;

    pub(super) struct Mpi {
        pub world: mpi::topology::SimpleCommunicator,
    }

    // SAFETY: MPI is initialized with MPI_THREAD_SERIALIZED, and a run drives its engine
    // (the only caller) from one thread at a time.
    unsafe impl Send for Mpi {}
    unsafe impl Sync for Mpi {}

    /// Counts and displacements (in elements) of parts of these lengths, as MPI's ints.
    fn layout(lengths: &[usize]) -> (Vec<Count>, Vec<Count>) {
        let counts: Vec<Count> = lengths
            .iter()
            .map(|&l| Count::try_from(l).expect("a message of at most 2^31 values"))
            .collect();
        let displs = counts
            .iter()
            .scan(0 as Count, |at, &c| {
                let start = *at;
                *at += c;
                Some(start)
            })
            .collect();
        (counts, displs)
    }

    /// `flat` cut into parts of `counts` values.
    fn split(flat: Vec<f64>, counts: &[Count]) -> Vec<Vec<f64>> {
        let mut at = 0;
        counts
            .iter()
            .map(|&c| {
                let part = flat[at..at + c as usize].to_vec();
                at += c as usize;
                part
            })
            .collect()
    }

    impl Mpi {
        /// MPI_Alltoallv, after MPI_Alltoall of the counts.
        fn all_to_all_everyone(&self, outgoing: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
            let lengths: Vec<usize> = outgoing.iter().map(Vec::len).collect();
            let (send_counts, send_displs) = layout(&lengths);
            let mut receive_counts = vec![0 as Count; self.size()];
            self.world
                .all_to_all_into(&send_counts[..], &mut receive_counts[..]);
            let flat: Vec<f64> = outgoing.concat();
            let lengths: Vec<usize> = receive_counts.iter().map(|&c| c as usize).collect();
            let (receive_counts, receive_displs) = layout(&lengths);
            let mut incoming = vec![0.0; lengths.iter().sum()];
            {
                let send = Partition::new(&flat[..], &send_counts[..], &send_displs[..]);
                let mut receive =
                    PartitionMut::new(&mut incoming[..], &receive_counts[..], &receive_displs[..]);
                self.world.all_to_all_varcount_into(&send, &mut receive);
            }
            split(incoming, &receive_counts)
        }
    }

    impl Communicator for Mpi {
        fn rank(&self) -> usize {
            self.world.rank() as usize
        }

        fn size(&self) -> usize {
            self.world.size() as usize
        }

        /// Where every rank sends only to ranks within a distance h (periodically) with
        /// 2 h < ranks, as slabs after a step: 2 h exchanges with neighbours (MPI_Sendrecv),
        /// after an all-reduce of h; cost independent of the number of ranks. Else
        /// MPI_Alltoallv.
        fn all_to_all(&self, mut outgoing: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
            let (rank, size) = (self.rank(), self.size());
            let distance = |to: usize| {
                let forward = (to + size - rank) % size;
                forward.min(size - forward)
            };
            let reach = (0..size)
                .filter(|&to| !outgoing[to].is_empty())
                .map(distance)
                .max()
                .unwrap_or(0) as i64;
            let mut farthest = 0i64;
            self.world.all_reduce_into(
                &reach,
                &mut farthest,
                mpi::collective::SystemOperation::max(),
            );
            let farthest = farthest as usize;
            if 2 * farthest >= size {
                return self.all_to_all_everyone(outgoing);
            }
            let mut incoming = vec![Vec::new(); size];
            incoming[rank] = std::mem::take(&mut outgoing[rank]);
            for d in 1..=farthest {
                let (up, down) = ((rank + d) % size, (rank + size - d) % size);
                for (to, from) in [(up, down), (down, up)] {
                    let (target, source) = (
                        self.world.process_at_rank(to as i32),
                        self.world.process_at_rank(from as i32),
                    );
                    let (count, _): (u64, _) = mpi::point_to_point::send_receive(
                        &(outgoing[to].len() as u64),
                        &target,
                        &source,
                    );
                    let mut values = vec![0.0; count as usize];
                    mpi::point_to_point::send_receive_into(
                        &outgoing[to][..],
                        &target,
                        &mut values[..],
                        &source,
                    );
                    incoming[from] = values;
                }
            }
            incoming
        }

        fn all_gather(&self, mine: Vec<f64>) -> Vec<Vec<f64>> {
            let length = Count::try_from(mine.len()).expect("at most 2^31 values");
            let mut counts = vec![0 as Count; self.size()];
            self.world.all_gather_into(&length, &mut counts[..]);
            let lengths: Vec<usize> = counts.iter().map(|&c| c as usize).collect();
            let (counts, displs) = layout(&lengths);
            let mut all = vec![0.0; lengths.iter().sum()];
            {
                let mut receive = PartitionMut::new(&mut all[..], &counts[..], &displs[..]);
                self.world.all_gather_varcount_into(&mine[..], &mut receive);
            }
            split(all, &counts)
        }

        fn sum_i64(&self, values: &mut [i64]) {
            let mine = values.to_vec();
            self.world
                .all_reduce_into(&mine[..], values, mpi::collective::SystemOperation::sum());
        }
    }
}
