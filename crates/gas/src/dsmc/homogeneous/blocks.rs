//! The block scheme of the homogeneous engine: the gas cut into blocks that run the exact
//! process side by side for a step, then re-mix (every block takes each lane of LANE
//! particles from a random block). Over ranks, each holds a run of whole blocks and the
//! lanes travel between ranks ([`exchange_lanes`]); the step is the single process's, bit
//! for bit: the same blocks, lanes and random streams, and exact sums over the blocks.
//!
//! Uniform shear flow (`Core::shear`, u = a y e_x): the records are the peculiar velocities
//! V, which between collisions obey dV_x/dt = -a V_y (the USF in the frame moving with the
//! flow; Brey, Ruiz-Montero & Moreno, Phys. Rev. E 55, 2846 (1997)). The streaming is
//! solved exactly, V_x -= a V_y t, for half a step before and half after each step's
//! collisions (Strang splitting: the step's error is of third order in dt, the error at
//! a fixed time of second order; the thermostat's scaling follows the step).

use super::{Core, HomogeneousRecord};
use crate::driving::Driving;
use crate::dsmc::domain::Traffic;
use crate::dsmc::kernel::{self, add_counts, Moments, Record, SpeciesTally};
use crate::dsmc::reduce;
use crate::dsmc::{
    frequency_estimate, positive, StepSize, DEFAULT_BLOCK_COLLISIONS_PER_STEP,
    SHEARED_BLOCK_COLLISIONS_PER_STEP,
};
use crate::parallel::Communicator;
use crate::prefetch::prefetch;
use crate::rng::{Purpose, Stream};
use crate::shear::Virial;
use crate::system::{dot, Vector};
use crate::theory;
use rayon::prelude::*;
use std::time::Instant;

/// Particles per lane of the block re-mixing: a lane moves to another block as a whole.
const LANE: usize = 16;

/// How N particles split into blocks: `count` blocks, the first `longer` of them with
/// `size + 1` particles, the rest with `size`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Blocks {
    pub count: usize,
    size: usize,
    longer: usize,
}

impl Blocks {
    pub fn new(n: usize, block_size: usize) -> Self {
        let count = ((n as f64 / block_size as f64).round() as usize).clamp(1, n / 2);
        Blocks {
            count,
            size: n / count,
            longer: n % count,
        }
    }

    pub fn start(&self, b: usize) -> usize {
        b * self.size + b.min(self.longer)
    }

    fn len(&self, b: usize) -> usize {
        self.size + (b < self.longer) as usize
    }

    /// Whole lanes every block has.
    fn lanes(&self) -> usize {
        self.size / LANE
    }

    /// The blocks `share` of `data` (which holds exactly them).
    fn split<'a, T>(&self, mut data: &'a mut [T], share: Share) -> Vec<&'a mut [T]> {
        let mut parts = Vec::with_capacity(share.end - share.first);
        for b in share.first..share.end {
            let (head, tail) = data.split_at_mut(self.len(b));
            parts.push(head);
            data = tail;
        }
        parts
    }

    /// The blocks rank `rank` of `ranks` holds: the (`rank` + 1)-th of `ranks` nearly
    /// equal runs.
    pub fn share(&self, rank: usize, ranks: usize) -> Share {
        Share {
            first: rank * self.count / ranks,
            end: (rank + 1) * self.count / ranks,
        }
    }

    /// The rank holding block `b` ([`Blocks::share`] inverted: the rank r with
    /// floor(r c / P) <= b < floor((r + 1) c / P), i.e. r = ceil((b + 1) P / c) - 1).
    fn owner(&self, b: usize, ranks: usize) -> usize {
        ((b + 1) * ranks - 1) / self.count
    }
}

/// A run of blocks, `first..end`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Share {
    pub first: usize,
    pub end: usize,
}

/// The block scheme: steps until the time reaches `end` or the collisions `target`.
#[allow(clippy::too_many_arguments)]
pub(super) fn run_blocks<const D: usize, R: HomogeneousRecord<D>>(
    core: &mut Core<D>,
    now: &mut Vec<R>,
    spare: &mut Vec<R>,
    block_size: usize,
    step: StepSize,
    end: f64,
    target: u64,
    pause: u64,
) {
    let n = core.total;
    let layout = Blocks::new(n, block_size);
    while core.tally.collisions < target.min(pause) && core.time < end {
        let omega =
            frequency_estimate::<D>(&core.species, n as f64 - 1.0, core.volume, core.temperature);
        if !positive(omega) {
            // At rest: no collision ever.
            if end.is_finite() {
                core.time = end;
            }
            return;
        }
        let mut dt = match step {
            StepSize::Auto if core.shear.is_some() => SHEARED_BLOCK_COLLISIONS_PER_STEP / omega,
            StepSize::Auto => DEFAULT_BLOCK_COLLISIONS_PER_STEP / omega,
            StepSize::CollisionsPerParticle(x) => x / omega,
            StepSize::Fixed(dt) => dt,
        };
        if target != u64::MAX {
            // Expected collisions in dt: N omega dt / 2.
            let remaining = (target - core.tally.collisions) as f64;
            dt = dt.min(2.0 * remaining / (n as f64 * omega));
        }
        let last = dt >= end - core.time;
        if last {
            dt = end - core.time;
        }
        let clock = Instant::now();
        let sums = block_step(core, now, spare, &layout, dt);
        std::mem::swap(now, spare);
        core.tally.add(&sums.tally);
        if let (Some(total), Some(step)) = (core.virial.as_mut(), &sums.virial) {
            total.merge(step);
        }
        add_counts(&mut core.species_collisions, &sums.species_collisions);
        if let Some(spin) = &mut core.spin {
            spin.sliding += sums.sliding;
        }
        // The spread about the mean u from the spread about the reference r:
        // sum m |v - r|^2 - M |u - r|^2.
        let mean = sums.mean();
        let d: Vector<D> = std::array::from_fn(|k| mean[k] - core.reference[k]);
        core.reference = mean;
        core.temperature = (sums.spread - sums.mass * dot(&d, &d)) / (n * D) as f64;
        if let Some(Driving::Thermostat(thermostat)) = core.driving {
            // Every rank scales its blocks by the same factor (the temperature is the
            // gas's, summed exactly over all blocks).
            let factor = thermostat.factor(core.temperature);
            let mean = core.reference;
            now.par_iter_mut().for_each(|r| {
                let v = r.velocity_mut();
                for k in 0..D {
                    v[k] = mean[k] + factor * (v[k] - mean[k]);
                }
            });
            core.temperature *= factor * factor;
        }
        core.steps += 1;
        core.time = if last { end } else { core.time + dt };
        core.traffic.steps += 1;
        core.traffic.step_seconds += clock.elapsed().as_secs_f64();
    }
}

/// One step: every destination block gathers its particles (lane c from block
/// b + offset_c) and their speed bound about the reference velocity (the gas's mean at the
/// end of the last step), runs the exact process for `dt` with the kernel's single
/// majorant (speed classes halve the candidates here but cost twice the time: the blocks are
/// small and re-sorted every step; docs/performance.md), shuffles itself and sums its
/// mass, momentum and m |v - reference|^2. Returns these summed over the blocks of all
/// ranks, with the tally.
fn block_step<const D: usize, R: HomogeneousRecord<D>>(
    core: &mut Core<D>,
    now: &[R],
    spare: &mut Vec<R>,
    layout: &Blocks,
    dt: f64,
) -> reduce::StepSums<D> {
    if spare.len() != now.len() {
        spare.clear();
        spare.extend_from_slice(now);
    }
    let mut mixing = Stream::new(core.seed, Purpose::Mixing, core.steps, 0);
    let offsets: Vec<usize> = (0..layout.lanes())
        .map(|_| mixing.below(layout.count as u64) as usize)
        .collect();
    let share = layout.share(core.comm.rank(), core.comm.size());
    let distributed = core.comm.size() > 1;
    if distributed {
        exchange_lanes(
            now,
            spare,
            layout,
            share,
            &offsets,
            core.comm.as_ref(),
            &mut core.traffic,
        );
    }
    let collider = super::collider(
        core.law.as_ref(),
        &core.species,
        core.pairs.as_deref(),
        core.spin.as_ref(),
    );
    let (seed, steps, species) = (core.seed, core.steps, &core.species);
    let noise = match core.driving {
        Some(Driving::WhiteNoise(noise)) => Some(noise),
        _ => None,
    };
    let reference = core.reference;
    let (shear, with_virial) = (core.shear, core.virial.is_some());
    let base = layout.start(share.first);
    let base_rate =
        theory::cross_section_factor::<D>() * core.species.max_weight * (core.total as f64 - 1.0)
            / core.volume;
    let results: Vec<(SpeciesTally, Moments<D>)> = layout
        .split(spare, share)
        .into_par_iter()
        .enumerate()
        .map(|(i, block)| {
            let b = share.first + i;
            let mut bound = if distributed {
                // The lanes arrived; the rest of the block stays.
                let own = &now[layout.start(b) - base..][..block.len()];
                let done = layout.lanes() * LANE;
                block[done..].copy_from_slice(&own[done..]);
                kernel::speed_bound(block, &reference)
            } else {
                gather(now, layout, &offsets, b, block, &reference).sqrt()
            };
            let mut rng = Stream::new(seed, Purpose::Block, steps, b as u64);
            let mut tally = SpeciesTally::new(species.len());
            tally.virial = with_virial.then(Virial::default);
            if let Some(shear) = &shear {
                stream_sheared(block, shear.rate, 0.5 * dt);
                bound = kernel::speed_bound(block, &reference);
            }
            // Driving: half the step's kicks before the collisions, half after (symmetric
            // splitting: the state at the end of a step is that of continuous noise to
            // second order in the step).
            if let Some(noise) = noise {
                noise.kick(block, 0.5 * dt, species, &mut rng);
                bound = kernel::speed_bound(block, &reference);
            }
            // Pair rate over a volume V (B - 1)/(N - 1): each particle's frequency is the gas's.
            let pair_rate = base_rate / (block.len() as f64 - 1.0);
            collider.run_for(
                block,
                &reference,
                pair_rate,
                (0.0, dt),
                &mut bound,
                &mut rng,
                &mut tally,
            );
            if let Some(noise) = noise {
                noise.kick(block, 0.5 * dt, species, &mut rng);
            }
            if let Some(shear) = &shear {
                stream_sheared(block, shear.rate, 0.5 * dt);
            }
            kernel::shuffle(block, &mut rng);
            (tally, kernel::sums_about(block, species, &reference))
        })
        .collect();
    let kinds = core.species.len();
    let comm = core.comm.as_ref();
    let rough = core.spin.is_some();
    reduce::step_sums(
        &results,
        kinds,
        true,
        with_virial,
        rough,
        comm,
        &mut core.traffic,
    )
}

/// The peculiar velocities of a uniform shear flow of rate `rate` streamed for a time `t`:
/// V_x -= rate V_y t, the exact solution of dV_x/dt = -rate V_y (V_y, V_z constant).
fn stream_sheared<const D: usize, R: Record<D>>(block: &mut [R], rate: f64, t: f64) {
    let skew = rate * t;
    for r in block {
        let v = r.velocity_mut();
        v[0] -= skew * v[1];
    }
}

/// Moves the lanes of this rank's blocks (`now`, the blocks `share`) to the destination
/// blocks that take them (lane c of block s goes to block s - offsets[c] mod count), on
/// this rank by a copy, to other ranks in one all-to-all, and writes the lanes that arrive
/// into this rank's destination blocks in `spare`. Each rank sends, per destination rank,
/// lane by lane in increasing source block; the receiver reads them in that order.
fn exchange_lanes<const D: usize, R: HomogeneousRecord<D>>(
    now: &[R],
    spare: &mut [R],
    layout: &Blocks,
    share: Share,
    offsets: &[usize],
    comm: &dyn Communicator,
    traffic: &mut Traffic,
) {
    let (me, ranks, count) = (comm.rank(), comm.size(), layout.count);
    let base = layout.start(share.first);
    let lane_at = |b: usize, c: usize| layout.start(b) - base + c * LANE;
    let width = R::VALUES;
    let mut outgoing = vec![Vec::new(); ranks];
    for (c, &offset) in offsets.iter().enumerate() {
        for s in share.first..share.end {
            let d = (s + count - offset) % count;
            let lane = &now[lane_at(s, c)..][..LANE];
            match layout.owner(d, ranks) {
                q if q == me => copy_lane(lane, &mut spare[lane_at(d, c)..][..LANE]),
                q => lane.iter().for_each(|r| r.encode(&mut outgoing[q])),
            }
        }
    }
    let sent: usize = outgoing.iter().map(Vec::len).sum();
    let clock = Instant::now();
    let incoming = comm.all_to_all(outgoing);
    traffic.communication_seconds += clock.elapsed().as_secs_f64();
    let received: usize = incoming.iter().map(Vec::len).sum();
    traffic.migrants_sent += (sent / width) as u64;
    traffic.bytes_sent += 8 * sent as u64;
    traffic.bytes_received += 8 * received as u64;
    let mut cursor = vec![0; ranks];
    for (c, &offset) in offsets.iter().enumerate() {
        // Destination d takes source (d + offset) mod count: in increasing source, first
        // the destinations whose source wrapped around (d >= count - offset).
        let wrap = (count - offset).clamp(share.first, share.end);
        for d in (wrap..share.end).chain(share.first..wrap) {
            let p = layout.owner((d + offset) % count, ranks);
            if p != me {
                let rows = &incoming[p][cursor[p]..][..LANE * width];
                let lane = &mut spare[lane_at(d, c)..][..LANE];
                for (r, row) in lane.iter_mut().zip(rows.chunks_exact(width)) {
                    *r = R::decode(row);
                }
                cursor[p] += LANE * width;
            }
        }
    }
    debug_assert!((0..ranks).all(|p| cursor[p] == incoming[p].len()));
}

/// Lanes ahead of the one being copied whose source [`gather`] asks the processor for.
const PREFETCH_LANES: usize = 4;

/// Copies a lane as a fixed-size array (inline moves rather than a call to memmove).
#[inline(always)]
fn copy_lane<R: Copy>(from: &[R], to: &mut [R]) {
    let from: &[R; LANE] = from.try_into().expect("a lane");
    let to: &mut [R; LANE] = to.try_into().expect("a lane");
    *to = *from;
}

/// Fills destination block `b`: lane c (particles c LANE .. (c+1) LANE) from block
/// (b + offsets[c]) mod count, the rest of the block (fewer than LANE + 1) from block b.
/// Returns the largest |v - reference|^2 in the block.
fn gather<const D: usize, R: Record<D>>(
    now: &[R],
    layout: &Blocks,
    offsets: &[usize],
    b: usize,
    block: &mut [R],
    reference: &Vector<D>,
) -> f64 {
    let mut largest: f64 = 0.0;
    let mut note = |lane: &[R]| {
        for r in lane {
            let d: Vector<D> = std::array::from_fn(|k| r.velocity()[k] - reference[k]);
            largest = largest.max(dot(&d, &d));
        }
    };
    let source_of = |c: usize| layout.start((b + offsets[c]) % layout.count) + c * LANE;
    for c in 0..offsets.len() {
        // The lanes come from all over the records: ask for one a few lanes ahead.
        if c + PREFETCH_LANES < offsets.len() {
            let ahead = source_of(c + PREFETCH_LANES);
            prefetch(&now[ahead..ahead + LANE]);
        }
        let source = source_of(c);
        let lane = &mut block[c * LANE..(c + 1) * LANE];
        copy_lane(&now[source..source + LANE], lane);
        note(lane);
    }
    let done = offsets.len() * LANE;
    let (own, len) = (layout.start(b), block.len());
    block[done..].copy_from_slice(&now[own + done..own + len]);
    note(&block[done..]);
    largest
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every block has exactly one owner, the rank whose share holds it; shares are runs in
    /// rank order that cover the blocks, none empty while ranks <= blocks.
    #[test]
    fn owners_invert_shares() {
        for count in 1..40 {
            let layout = Blocks {
                count,
                size: 10,
                longer: 0,
            };
            for ranks in 1..=count {
                let mut next = 0;
                for rank in 0..ranks {
                    let share = layout.share(rank, ranks);
                    assert_eq!(share.first, next);
                    assert!(share.end > share.first);
                    for b in share.first..share.end {
                        assert_eq!(
                            layout.owner(b, ranks),
                            rank,
                            "{count} blocks, {ranks} ranks"
                        );
                    }
                    next = share.end;
                }
                assert_eq!(next, count);
            }
        }
    }
}
