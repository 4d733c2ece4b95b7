//! One step of the spatial engine: stream, sort into cells (on several ranks: migrate
//! first), collide in every cell with the kernel's exact process, sum over the cells
//! exactly. Generic over the records ([`super::record`]): smooth and rough particles run
//! the same code, the tangential kick compiled for rough records only.

use super::super::kernel::{self, scaled, Collider, Moments, SpeciesTally};
use super::flow::stream_one;
use super::record::{with_records, Particle};
use super::sums::{mass_and_momentum, spread_about_mean};
use super::SpatialDsmc;
use crate::dsmc::rough::Spin;
use crate::rng::{Purpose, Stream};
use crate::system::Vector;
use crate::theory;
use rayon::prelude::*;
use std::time::Instant;

impl<const D: usize> SpatialDsmc<D> {
    /// One step of time dt: stream, sort into cells (on several ranks: migrate first),
    /// collide in every cell, sum over the cells exactly.
    pub(super) fn step(&mut self, dt: f64) {
        with_records!(self, records => self.step_records(&mut records, dt));
    }

    /// [`SpatialDsmc::step`] of `records` (the engine's, moved out for the step).
    fn step_records<R: Particle<D>>(&mut self, records: &mut Vec<R>, dt: f64) {
        let clock = Instant::now();
        let (sides, cells, width) = (self.sides, self.cells, self.widths());
        let cell_count = self.cell_count();
        let key = |p: &R| cell_key(&p.body().position, &width, &cells);
        let faces = self.sliding_faces(dt);
        let stream = |p: &mut R| stream_one(p.body_mut(), dt, &sides, faces);
        let starts = if self.comm.size() == 1 && self.walls.is_some() {
            self.stream_in_container(records, dt);
            self.sorter
                .update_and_sort(records, cell_count, |_| {}, key)
        } else if self.comm.size() == 1 {
            self.sorter
                .update_and_sort(records, cell_count, stream, key)
        } else if self.walls.is_some() {
            // Each rank streams its particles in the container, then they migrate.
            self.stream_in_container(records, dt);
            self.stream_and_sort_over_ranks(records, 0.0)
        } else {
            self.stream_and_sort_over_ranks(records, dt)
        };
        if self.tracks.is_some() {
            self.follow_tracks(records, dt);
        }
        let groups = split_at_starts(records, &starts);
        let collider = Collider {
            rough: self.spin.as_ref().and_then(Spin::kernel),
            law: self.law.as_ref(),
            species: &self.species,
            pairs: self.pairs.as_deref(),
        };
        let cell_volume = if crate::system::is_cube(&self.sides) {
            width[0].powi(D as i32)
        } else {
            width.iter().product()
        };
        let pair_rate = theory::cross_section_factor::<D>() * self.species.max_weight * self.weight
            / cell_volume;
        let (seed, step, species) = (self.seed, self.steps, &self.species);
        let with_virial = self.virial.is_some();
        let results: Vec<(SpeciesTally, Moments<D>)> = groups
            .into_par_iter()
            .map(|cell| {
                let mut tally = SpeciesTally::new(species.len());
                tally.virial = with_virial.then(crate::shear::Virial::default);
                let (mass, momentum) = mass_and_momentum(cell, species);
                if cell.len() < 2 {
                    return (tally, spread_about_mean(cell, species, mass, momentum));
                }
                let mean = scaled(&momentum, mass);
                let mut bound = kernel::speed_bound(cell, &mean);
                let mut rng = Stream::new(seed, Purpose::Cell, step, key(&cell[0]));
                collider.run_for(
                    cell,
                    &mean,
                    pair_rate,
                    (0.0, dt),
                    &mut bound,
                    &mut rng,
                    &mut tally,
                );
                if tally.counters.collisions == 0 {
                    return (tally, spread_about_mean(cell, species, mass, momentum));
                }
                let (mass, momentum) = mass_and_momentum(cell, species);
                (tally, spread_about_mean(cell, species, mass, momentum))
            })
            .collect();
        let (tally, spread, species_collisions, virial, sliding) = self.sum_over_cells(&results);
        self.tally.add(&tally);
        if let Some(spin) = self.spin.as_mut() {
            spin.sliding += sliding;
        }
        if let (Some(total), Some(step)) = (self.virial.as_mut(), &virial) {
            total.merge(step);
        }
        kernel::add_counts(&mut self.species_collisions, &species_collisions);
        self.temperature = spread / (self.total * D) as f64;
        self.steps += 1;
        self.traffic.steps += 1;
        self.traffic.step_seconds += clock.elapsed().as_secs_f64();
    }
}

/// Linear index of the cell holding x (in [0, L)^D): the last axis most significant.
#[inline]
pub(super) fn cell_key<const D: usize>(x: &Vector<D>, width: &[f64; D], cells: &[u64; D]) -> u64 {
    (0..D).rev().fold(0, |key, k| {
        key * cells[k] + cell_index(x[k], width[k], cells[k])
    })
}

/// The index along one axis of the cell holding coordinate x (in [0, L)).
#[inline]
pub(super) fn cell_index(x: f64, width: f64, cells: u64) -> u64 {
    // Through i64 (x / width is in [0, cells)): the same value as `as u64`, which x86
    // converts with a branchy sequence of instructions.
    ((x / width) as i64 as u64).min(cells - 1)
}

fn split_at_starts<'a, T>(mut data: &'a mut [T], starts: &[usize]) -> Vec<&'a mut [T]> {
    let mut parts = Vec::with_capacity(starts.len());
    let mut at = 0;
    for &next in starts.iter().skip(1) {
        let (head, tail) = data.split_at_mut(next - at);
        parts.push(head);
        data = tail;
        at = next;
    }
    parts.push(data);
    parts
}
