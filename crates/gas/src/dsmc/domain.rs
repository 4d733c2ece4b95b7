//! The domain decomposition of the spatial DSMC engine over ranks: slabs of whole planes of
//! collision cells along the last axis, balanced by particle count; the migration of
//! particles between ranks after streaming, in the order that makes the run independent of
//! the number of ranks; and the per-rank tally of what that costs.
//!
//! Why the result does not depend on the ranks: the single-process engine keeps its
//! particles sorted by cell key (a stable sort after every streaming), and the cell key's
//! most significant digit is the plane along the last axis. A rank owns a contiguous range
//! of planes, hence of keys, so the single process's order is the concatenation of the
//! ranks' local orders in rank order. After streaming, a rank receives the particles whose
//! new cell it owns and lays them out in that global order (source rank by source rank, its
//! own in its place), then sorts them stably by cell: the single process's order restricted
//! to its cells. Each cell's collisions draw from the stream keyed (seed, step, cell), and
//! sums over cells are exact ([`crate::exact_sum`]), so every number is the single
//! process's, bit for bit.

use super::spatial::record::Particle;
use crate::parallel::{Communicator, RankReport};
use std::time::Instant;

/// Steps between re-balancings of the slabs (an all-reduce of one count per plane).
pub const REBALANCE_STEPS: u64 = 20;

/// Contiguous ranges of planes of cells, one per rank.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Slabs {
    /// Planes (cells per side) and cells in a plane (cells per side^(D - 1)).
    planes: u64,
    cells_per_plane: u64,
    /// Rank r owns planes bounds[r] .. bounds[r + 1].
    bounds: Vec<u64>,
    /// The owner of each plane (a lookup: this runs for every particle every step).
    owners: Vec<u32>,
}

impl Slabs {
    /// Slabs over `ranks` ranks balancing the particle `counts` per plane: rank r's slab
    /// starts at the first plane where the particles before reach r N / ranks, every slab at
    /// least one plane. Needs ranks <= planes.
    pub fn balanced(counts: &[u64], cells_per_plane: u64, ranks: usize) -> Slabs {
        let planes = counts.len() as u64;
        assert!(ranks as u64 <= planes && ranks > 0, "ranks <= planes");
        let total: u128 = counts.iter().map(|&c| c as u128).sum();
        let mut bounds = vec![0u64; ranks + 1];
        bounds[ranks] = planes;
        let mut before: u128 = 0; // particles in planes below `plane`
        let mut plane = 0u64;
        for r in 1..ranks {
            let lowest = bounds[r - 1] + 1;
            let highest = planes - (ranks - r) as u64;
            while plane < lowest {
                before += counts[plane as usize] as u128;
                plane += 1;
            }
            while plane < highest && before * (ranks as u128) < (r as u128) * total {
                before += counts[plane as usize] as u128;
                plane += 1;
            }
            bounds[r] = plane;
        }
        let owners = (0..ranks)
            .flat_map(|r| std::iter::repeat_n(r as u32, (bounds[r + 1] - bounds[r]) as usize))
            .collect();
        Slabs {
            planes,
            cells_per_plane,
            bounds,
            owners,
        }
    }

    pub fn ranks(&self) -> usize {
        self.bounds.len() - 1
    }

    /// The rank owning `plane`.
    #[inline]
    pub fn owner(&self, plane: u64) -> usize {
        self.owners[plane as usize] as usize
    }

    /// The first cell key of `rank`'s slab and its number of cells.
    pub fn keys(&self, rank: usize) -> (u64, u64) {
        let (first, end) = (self.bounds[rank], self.bounds[rank + 1]);
        (
            first * self.cells_per_plane,
            (end - first) * self.cells_per_plane,
        )
    }

    /// The slabs re-balanced for the particles of all ranks (`plane` gives each local
    /// particle's plane): one all-reduce of a count per plane.
    pub fn rebalanced<T>(
        &self,
        local: &[T],
        plane: impl Fn(&T) -> u64,
        comm: &dyn Communicator,
    ) -> Slabs {
        let mut counts = vec![0i64; self.planes as usize];
        for p in local {
            counts[plane(p) as usize] += 1;
        }
        comm.sum_i64(&mut counts);
        let counts: Vec<u64> = counts.iter().map(|&c| c as u64).collect();
        Slabs::balanced(&counts, self.cells_per_plane, self.ranks())
    }
}

/// What a rank spent on being one of many: the tally behind
/// [`crate::parallel::RankReport`].
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Traffic {
    pub steps: u64,
    pub migrants_sent: u64,
    pub bytes_sent: u64,
    pub bytes_received: u64,
    /// Seconds in collective operations of the steps (migration and sums).
    pub communication_seconds: f64,
    /// Seconds in the steps, all in.
    pub step_seconds: f64,
    /// Seconds gathering the state for samples and check-points.
    pub gather_seconds: f64,
}

impl Traffic {
    /// Every rank's report (collective): this rank holds `particles` and `groups` collision
    /// groups (cells, blocks). None on one rank.
    pub fn reports(
        &self,
        comm: &dyn Communicator,
        particles: usize,
        groups: u64,
    ) -> Option<Vec<RankReport>> {
        if comm.size() == 1 {
            return None;
        }
        let mine = [
            particles as f64,
            groups as f64,
            self.steps as f64,
            self.migrants_sent as f64,
            self.bytes_sent as f64,
            self.bytes_received as f64,
            self.step_seconds,
            self.communication_seconds,
            self.gather_seconds,
        ];
        let all = comm.all_gather(mine.to_vec());
        Some(
            all.iter()
                .enumerate()
                .map(|(rank, v)| RankReport {
                    rank,
                    particles: v[0] as usize,
                    cells: v[1] as u64,
                    steps: v[2] as u64,
                    migrants_sent: v[3] as u64,
                    bytes_sent: v[4] as u64,
                    bytes_received: v[5] as u64,
                    step_seconds: v[6],
                    communication_seconds: v[7],
                    gather_seconds: v[8],
                })
                .collect(),
        )
    }
}

/// Moves the (already streamed) local particles to the ranks owning their cells and lays
/// this rank's particles out in the global order before the sort into cells (each
/// particle travels with its place in it). `ordinals` are the places of the local
/// particles when the global order is not rank by rank (before the first step); after,
/// it is rank by rank. The general path: the first step, and cells too fine for
/// [`exchange_into_holes`] with its counting sort.
pub(crate) fn migrate<const D: usize, R: Particle<D>>(
    local: &mut Vec<R>,
    ordinals: Option<Vec<u64>>,
    owner: impl Fn(&R) -> usize,
    comm: &dyn Communicator,
    traffic: &mut Traffic,
) {
    let (rank, ranks) = (comm.rank(), comm.size());
    let place = |i: usize| match &ordinals {
        Some(o) => o[i],
        None => ((rank as u64) << 40) | i as u64,
    };
    let mut outgoing: Vec<Vec<f64>> = vec![Vec::new(); ranks];
    let mut placed: Vec<(u64, R)> = Vec::with_capacity(local.len());
    for (i, p) in local.iter().enumerate() {
        let to = owner(p);
        if to == rank {
            placed.push((place(i), *p));
        } else {
            p.encode(&mut outgoing[to], place(i));
            traffic.migrants_sent += 1;
        }
    }
    traffic.bytes_sent += outgoing.iter().map(|o| 8 * o.len() as u64).sum::<u64>();
    let clock = Instant::now();
    let incoming = comm.all_to_all(outgoing);
    traffic.communication_seconds += clock.elapsed().as_secs_f64();
    traffic.bytes_received += incoming.iter().map(|o| 8 * o.len() as u64).sum::<u64>();
    placed.extend(
        incoming
            .iter()
            .flat_map(|v| v.chunks_exact(R::VALUES))
            .map(|v| (v[2 * D + 1].to_bits(), R::decode(v))),
    );
    // Ranks + 1 runs, each in increasing places: the stable sort merges the runs it finds.
    placed.sort_by_key(|e| e.0);
    local.clear();
    local.extend(placed.into_iter().map(|e| e.1));
}

/// Where the particles of a rank stand after [`exchange_into_holes`], for
/// `CellSorter::sort_keyed_in_sequence`: the indices of the particles that come before all
/// others in the global order (arrivals from lower ranks) and after them (staying particles
/// moved from the end into holes, then arrivals from higher ranks).
pub(crate) struct Sequence {
    pub first: Vec<usize>,
    pub last: Vec<usize>,
}

/// Moves the particles at the indices `leaving` (ascending; streamed, their `owner` another
/// rank) to their ranks, and puts the arrivals into the holes they leave (then at the end;
/// holes left over are filled with the last staying particles). `keys` holds a key per
/// particle (as `key` gives; the leaving ones' are replaced). Every other particle keeps
/// its place: with the returned [`Sequence`], the stable sort by key gives the global order
/// of the single process restricted to this rank, while moving few particles.
pub(crate) fn exchange_into_holes<const D: usize, R: Particle<D>>(
    local: &mut Vec<R>,
    keys: &mut Vec<u32>,
    leaving: &[usize],
    owner: impl Fn(&R) -> usize,
    key: impl Fn(&R) -> u32,
    comm: &dyn Communicator,
    traffic: &mut Traffic,
) -> Sequence {
    let (rank, ranks) = (comm.rank(), comm.size());
    let mut outgoing: Vec<Vec<f64>> = vec![Vec::new(); ranks];
    for &i in leaving {
        let p = &local[i];
        p.encode(&mut outgoing[owner(p)], 0);
    }
    traffic.migrants_sent += leaving.len() as u64;
    traffic.bytes_sent += outgoing.iter().map(|o| 8 * o.len() as u64).sum::<u64>();
    let clock = Instant::now();
    let incoming = comm.all_to_all(outgoing);
    traffic.communication_seconds += clock.elapsed().as_secs_f64();
    traffic.bytes_received += incoming.iter().map(|o| 8 * o.len() as u64).sum::<u64>();
    let mut holes = leaving.iter().copied();
    let (mut first, mut upper) = (Vec::new(), Vec::new());
    for from in (0..ranks).filter(|&r| r != rank) {
        for v in incoming[from].chunks_exact(R::VALUES) {
            let p = R::decode(v);
            let slot = match holes.next() {
                Some(h) => {
                    local[h] = p;
                    keys[h] = key(&p);
                    h
                }
                None => {
                    local.push(p);
                    keys.push(key(&p));
                    local.len() - 1
                }
            };
            if from < rank {
                first.push(slot);
            } else {
                upper.push(slot);
            }
        }
    }
    // Holes left: drop those at the end, fill the others (lowest first) with the last
    // particle, a staying one (it comes after the other staying ones, in the order of its
    // old index).
    let mut left: Vec<usize> = holes.collect();
    let mut moved = Vec::new();
    let mut next = 0;
    while next < left.len() {
        let end = local.len() - 1;
        if left.last() == Some(&end) {
            left.pop();
        } else {
            let h = left[next];
            local[h] = local[end];
            keys[h] = keys[end];
            moved.push(h);
            next += 1;
        }
        local.pop();
        keys.pop();
    }
    moved.reverse();
    moved.extend(upper);
    Sequence { first, last: moved }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Balanced slabs split the particles evenly where the planes allow, give every rank a
    /// plane, and each key one owner.
    #[test]
    fn slabs_balance_and_cover() {
        let even = Slabs::balanced(&[10; 8], 4, 4);
        assert_eq!(even.bounds, vec![0, 2, 4, 6, 8]);
        // A cluster in plane 5: rank 1 takes it with the planes below, ranks 2 and 3 one
        // plane each (every rank keeps at least one).
        let clustered = Slabs::balanced(&[1, 1, 1, 1, 1, 100, 1, 1], 4, 4);
        assert_eq!(clustered.bounds, vec![0, 5, 6, 7, 8]);
        let crowded = Slabs::balanced(&[0, 0, 0, 50], 4, 4);
        assert_eq!(crowded.bounds, vec![0, 1, 2, 3, 4]);
        for slabs in [even, clustered, crowded] {
            for key in 0..slabs.planes * 4 {
                let r = slabs.owner(key / 4);
                let (first, cells) = slabs.keys(r);
                assert!((first..first + cells).contains(&key));
            }
        }
    }
}
