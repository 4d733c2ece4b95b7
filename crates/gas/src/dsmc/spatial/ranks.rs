//! The spatial engine's side of being spread over ranks (see [`super::super::domain`]):
//! the step's streaming, migration and sort, the state gathered in the global order, and
//! each rank's report.

use super::super::cell_sort::CellSorter;
use super::super::domain::{self, REBALANCE_STEPS};
use super::record::Particle;
use super::{cell_index, cell_key, SpatialDsmc};
use crate::parallel::RankReport;
use rayon::prelude::*;
use std::time::Instant;

impl<const D: usize> SpatialDsmc<D> {
    /// Every rank's particles, cells and communication so far (collective: every rank
    /// calls it); None on one rank.
    pub(super) fn reports_of_ranks(&self) -> Option<Vec<RankReport>> {
        let (_, cells) = self.slabs.keys(self.comm.rank());
        self.traffic
            .reports(self.comm.as_ref(), self.records.len(), cells)
    }

    /// The particles of all ranks in the global order (collective), from this rank's
    /// `records`.
    pub(super) fn gathered<R: Particle<D>>(&mut self, records: &[R]) -> Vec<R> {
        let clock = Instant::now();
        // Before the first step the global order is the places of `ordinals`; after,
        // rank by rank.
        let places = self.ordinals.as_ref();
        let width = R::VALUES;
        let mut mine = Vec::with_capacity(width * records.len());
        for (i, p) in records.iter().enumerate() {
            p.encode(&mut mine, places.map_or(0, |o| o[i]));
        }
        let all = self.comm.all_gather(mine);
        let mut rows: Vec<&[f64]> = all.iter().flat_map(|v| v.chunks_exact(width)).collect();
        if places.is_some() {
            // One run per rank, each in increasing places: merged by the stable sort.
            rows.sort_by_key(|v| v[2 * D + 1].to_bits());
        }
        let gathered = rows.into_iter().map(R::decode).collect();
        self.traffic.gather_seconds += clock.elapsed().as_secs_f64();
        gathered
    }

    /// Streams the particles `records` (this rank's) for `dt` (0: streamed already, in
    /// a container), moves those that left the rank's slab to their ranks and receives
    /// the arrivals, and sorts the rank's particles by cell in the global order; returns
    /// where each non-empty cell starts.
    pub(super) fn stream_and_sort_over_ranks<R: Particle<D>>(
        &mut self,
        records: &mut Vec<R>,
        dt: f64,
    ) -> Vec<usize> {
        let (sides, cells, width) = (self.sides, self.cells, self.widths());
        let key = |p: &R| cell_key(&p.body().position, &width, &cells);
        // The most significant digit of the key.
        let plane = |p: &R| {
            let x = p.body().position[D - 1];
            cell_index(x, width[D - 1], cells[D - 1])
        };
        let faces = self.sliding_faces(dt);
        let stream = |p: &mut R| {
            if dt != 0.0 {
                super::flow::stream_one(p.body_mut(), dt, &sides, faces);
            }
        };
        if self.steps > 0 && self.steps.is_multiple_of(REBALANCE_STEPS) {
            let clock = Instant::now();
            self.slabs = self.slabs.rebalanced(records, plane, self.comm.as_ref());
            self.traffic.communication_seconds += clock.elapsed().as_secs_f64();
        }
        let (slabs, rank) = (&self.slabs, self.comm.rank());
        let (start, count) = slabs.keys(rank);
        let owner = |p: &R| slabs.owner(plane(p));
        if self.ordinals.is_none() && CellSorter::counts_cells(records.len(), count) {
            // One pass: stream, and key or mark as leaving; then arrivals into the holes.
            const CHUNK: usize = 4096;
            let keys = self.sorter.keys();
            keys.resize(records.len(), 0);
            let leaving: Vec<usize> = records
                .par_chunks_mut(CHUNK)
                .zip(keys.par_chunks_mut(CHUNK))
                .enumerate()
                .map(|(c, (items, keys))| {
                    let mut leaving = Vec::new();
                    for (j, (p, k)) in items.iter_mut().zip(keys).enumerate() {
                        stream(p);
                        if owner(p) == rank {
                            *k = (key(p) - start) as u32;
                        } else {
                            leaving.push(c * CHUNK + j);
                        }
                    }
                    leaving
                })
                .collect::<Vec<_>>()
                .concat();
            let sequence = domain::exchange_into_holes(
                records,
                keys,
                &leaving,
                owner,
                |p| (key(p) - start) as u32,
                self.comm.as_ref(),
                &mut self.traffic,
            );
            self.sorter
                .sort_keyed_in_sequence(records, count, &sequence.first, &sequence.last)
        } else {
            records.par_iter_mut().for_each(stream);
            domain::migrate(
                records,
                self.ordinals.take(),
                owner,
                self.comm.as_ref(),
                &mut self.traffic,
            );
            self.sorter
                .update_and_sort(records, count, |_| {}, |p| key(p) - start)
        }
    }
}
