//! Running one engine across processes: the few collective operations a distributed
//! engine needs ([`Communicator`]), the single process ([`Local`]) and ranks run as threads
//! of one process ([`InProcess`], for tests and for checking an MPI build's results without
//! MPI). The MPI implementation lives in the run driver (`sim::parallel`, feature `mpi`): the
//! engines know no MPI.
//!
//! Every operation is collective: all ranks call it, in the same order, with the same
//! lengths where stated.

use std::sync::{Arc, Barrier, Mutex};

/// The collective operations of a distributed engine.
pub trait Communicator: Send + Sync {
    /// This process's rank, 0 <= rank < size.
    fn rank(&self) -> usize;
    /// The number of ranks.
    fn size(&self) -> usize;
    /// Personalized all-to-all: `outgoing[r]` goes to rank r (one vector per rank); returns
    /// what every rank sent here, indexed by the source rank.
    fn all_to_all(&self, outgoing: Vec<Vec<f64>>) -> Vec<Vec<f64>>;
    /// Every rank's `mine`, indexed by rank, on every rank.
    fn all_gather(&self, mine: Vec<f64>) -> Vec<Vec<f64>>;
    /// Element-wise sum over the ranks of `values` (the same length on every rank), in
    /// place on every rank. Integers: the result does not depend on how it is reduced.
    fn sum_i64(&self, values: &mut [i64]);
}

/// What one rank of a distributed run spent on communication, and its share of the work.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RankReport {
    pub rank: usize,
    /// Particles on the rank now.
    pub particles: usize,
    /// Collision cells in its domain.
    pub cells: u64,
    pub steps: u64,
    /// Particles sent to other ranks (all steps).
    pub migrants_sent: u64,
    /// Bytes sent and received in migrations (all steps; the sums add a fixed
    /// [`reduction_bytes`] per step).
    pub bytes_sent: u64,
    pub bytes_received: u64,
    /// Wall-clock seconds in the steps, in their collective operations (migration, sums),
    /// and gathering the state for samples and check-points.
    pub step_seconds: f64,
    pub communication_seconds: f64,
    pub gather_seconds: f64,
}

/// Bytes each rank contributes to the all-reduces of one step of the distributed spatial
/// DSMC in D dimensions: exact sums ([`crate::exact_sum`]) of mass, momentum, energy
/// dissipated, virial and the spread, and three counters.
pub fn reduction_bytes(d: usize) -> usize {
    8 * ((d + 4) * (crate::exact_sum::LIMBS + 1) + 3)
}

/// One process: every collective is the identity.
#[derive(Debug, Clone, Copy, Default)]
pub struct Local;

impl Communicator for Local {
    fn rank(&self) -> usize {
        0
    }
    fn size(&self) -> usize {
        1
    }
    fn all_to_all(&self, outgoing: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
        outgoing
    }
    fn all_gather(&self, mine: Vec<f64>) -> Vec<Vec<f64>> {
        vec![mine]
    }
    fn sum_i64(&self, _values: &mut [i64]) {}
}

/// Ranks that are threads of this process, exchanging through shared memory.
pub struct InProcess {
    rank: usize,
    shared: Arc<Mailboxes>,
}

/// The mailboxes of [`InProcess`] ranks: slot [from][to], and a barrier between phases.
struct Mailboxes {
    size: usize,
    slots: Mutex<Vec<Vec<Vec<f64>>>>,
    sums: Mutex<Vec<Vec<i64>>>,
    barrier: Barrier,
}

impl InProcess {
    /// `size` ranks; hand one to each thread.
    pub fn ranks(size: usize) -> Vec<InProcess> {
        assert!(size > 0, "at least one rank");
        let shared = Arc::new(Mailboxes {
            size,
            slots: Mutex::new(vec![vec![Vec::new(); size]; size]),
            sums: Mutex::new(vec![Vec::new(); size]),
            barrier: Barrier::new(size),
        });
        (0..size)
            .map(|rank| InProcess {
                rank,
                shared: shared.clone(),
            })
            .collect()
    }

    /// Runs `work(rank)` on `size` ranks, one thread each, and returns their results in
    /// rank order.
    pub fn run<T: Send>(size: usize, work: impl Fn(InProcess) -> T + Sync) -> Vec<T> {
        let ranks = InProcess::ranks(size);
        std::thread::scope(|scope| {
            let handles: Vec<_> = ranks
                .into_iter()
                .map(|rank| scope.spawn(|| work(rank)))
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().expect("a rank panicked"))
                .collect()
        })
    }
}

impl Communicator for InProcess {
    fn rank(&self) -> usize {
        self.rank
    }

    fn size(&self) -> usize {
        self.shared.size
    }

    fn all_to_all(&self, outgoing: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
        assert_eq!(outgoing.len(), self.size(), "one vector per rank");
        self.shared.slots.lock().unwrap()[self.rank] = outgoing;
        self.shared.barrier.wait();
        let incoming = {
            let mut slots = self.shared.slots.lock().unwrap();
            (0..self.size())
                .map(|from| std::mem::take(&mut slots[from][self.rank]))
                .collect()
        };
        self.shared.barrier.wait();
        incoming
    }

    fn all_gather(&self, mine: Vec<f64>) -> Vec<Vec<f64>> {
        self.shared.slots.lock().unwrap()[self.rank] = vec![mine];
        self.shared.barrier.wait();
        let all = {
            let slots = self.shared.slots.lock().unwrap();
            (0..self.size())
                .map(|from| slots[from][0].clone())
                .collect()
        };
        self.shared.barrier.wait();
        all
    }

    fn sum_i64(&self, values: &mut [i64]) {
        self.shared.sums.lock().unwrap()[self.rank] = values.to_vec();
        self.shared.barrier.wait();
        {
            let sums = self.shared.sums.lock().unwrap();
            for (k, v) in values.iter_mut().enumerate() {
                *v = sums.iter().map(|s| s[k]).sum();
            }
        }
        self.shared.barrier.wait();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each collective of in-process ranks delivers what MPI's would.
    #[test]
    fn in_process_collectives() {
        let results = InProcess::run(3, |comm| {
            let r = comm.rank() as f64;
            let out: Vec<Vec<f64>> = (0..3).map(|to| vec![10.0 * r + to as f64]).collect();
            let got = comm.all_to_all(out);
            let gathered = comm.all_gather(vec![r; comm.rank() + 1]);
            let mut sums = [comm.rank() as i64, 1];
            comm.sum_i64(&mut sums);
            (got, gathered, sums)
        });
        for (me, (got, gathered, sums)) in results.into_iter().enumerate() {
            let want: Vec<Vec<f64>> = (0..3)
                .map(|from| vec![10.0 * from as f64 + me as f64])
                .collect();
            assert_eq!(got, want);
            assert_eq!(
                gathered,
                vec![vec![0.0], vec![1.0, 1.0], vec![2.0, 2.0, 2.0]]
            );
            assert_eq!(sums, [3, 3]);
        }
    }
}
