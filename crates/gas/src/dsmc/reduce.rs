//! The DSMC engines' sums over the groups of a step (cells, blocks) and over the particles
//! of all ranks: exact ([`crate::exact_sum`]), so the same bits however groups and
//! particles are spread over threads and ranks.

use super::domain::Traffic;
use super::kernel::{scaled, Moments, Record, SpeciesTally};
use super::species::Species;
use crate::engine::{Counters, VelocityStatistics};
use crate::exact_sum::{sums_of, ExactSum, LIMBS};
use crate::parallel::Communicator;
use crate::system::{dot, Vector};
use std::time::Instant;

/// A step's totals over the groups of all ranks.
pub(crate) struct StepSums<const D: usize> {
    pub tally: Counters,
    pub mass: f64,
    pub momentum: Vector<D>,
    /// The sum of the groups' `Moments::spread` (when asked for; else 0): meaningful when
    /// all groups measured it about the same center.
    pub spread: f64,
    /// Collisions suffered by the particles of each species (empty for one species).
    pub species_collisions: Vec<u64>,
    /// The tensor virial of the step's collisions, if the groups summed it.
    pub virial: Option<crate::shear::Virial>,
    /// Rough contacts that slid (summed over the ranks when asked for).
    pub sliding: u64,
}

impl<const D: usize> StepSums<D> {
    /// The mass-weighted mean velocity of all particles.
    pub fn mean(&self) -> Vector<D> {
        scaled(&self.momentum, self.mass)
    }
}

/// The counters, mass and momentum (and, if `with_spread`, the spreads) of the groups of a
/// step, `results`, summed over all ranks exactly (and the tensor virial, if
/// `with_tensor`: the groups summed it), with the collisions of each of the
/// `species` (if more than one) and, if `with_sliding`, the rough contacts that slid:
/// one all-reduce of [`crate::parallel::reduction_bytes`] (with the spread; 8 B more per
/// species of a mixture, 8 B for the sliding contacts) per rank.
#[allow(clippy::too_many_arguments)]
pub(crate) fn step_sums<const D: usize>(
    results: &[(SpeciesTally, Moments<D>)],
    species: usize,
    with_spread: bool,
    with_tensor: bool,
    with_sliding: bool,
    comm: &dyn Communicator,
    traffic: &mut Traffic,
) -> StepSums<D> {
    // Mass, momentum, energy lost, virial, spread, the tensor virial if summed; then
    // collisions, events, TC-elastic.
    let spread_at = D + 3;
    let tensor_at = spread_at + with_spread as usize;
    let count = tensor_at + if with_tensor { 6 } else { 0 };
    let sums = sums_of(results, count, |(tally, m), s| {
        let t = &tally.counters;
        s[0].add(m.mass);
        (0..D).for_each(|k| s[1 + k].add(m.momentum[k]));
        s[D + 1].add(t.energy_lost);
        s[D + 2].add(t.virial);
        if with_spread {
            s[spread_at].add(m.spread);
        }
        if let Some(v) = &tally.virial {
            (0..6).for_each(|c| s[tensor_at + c].add(v.0[c]));
        }
    });
    let counter =
        |f: fn(&Counters) -> u64| results.iter().map(|(t, _)| f(&t.counters) as i64).sum();
    let counters: [i64; 3] = [
        counter(|t| t.collisions),
        counter(|t| t.events),
        counter(|t| t.tc_elastic),
    ];
    let mut packed: Vec<i64> = sums.iter().flat_map(|s| s.to_limbs()).collect();
    packed.extend_from_slice(&counters);
    let by_species = if species > 1 { species } else { 0 };
    let start = packed.len();
    packed.resize(start + by_species, 0);
    for (t, _) in results {
        for (total, c) in packed[start..].iter_mut().zip(&t.collisions) {
            *total += *c as i64;
        }
    }
    if with_sliding {
        packed.push(results.iter().map(|(t, _)| t.sliding as i64).sum());
    }
    all_ranks_sum(&mut packed, comm, traffic);
    let sliding = if with_sliding {
        packed.pop().unwrap_or(0) as u64
    } else {
        0
    };
    let values: Vec<f64> = packed
        .chunks_exact(LIMBS + 1)
        .take(count)
        .map(|limbs| ExactSum::from_limbs(limbs).value())
        .collect();
    let counters = &packed[count * (LIMBS + 1)..];
    StepSums {
        tally: Counters {
            collisions: counters[0] as u64,
            events: counters[1] as u64,
            energy_lost: values[D + 1],
            virial: values[D + 2],
            tc_elastic: counters[2] as u64,
        },
        mass: values[0],
        momentum: std::array::from_fn(|k| values[1 + k]),
        spread: if with_spread { values[spread_at] } else { 0.0 },
        species_collisions: packed[start..].iter().map(|&c| c as u64).collect(),
        sliding,
        virial: with_tensor
            .then(|| crate::shear::Virial(std::array::from_fn(|c| values[tensor_at + c]))),
    }
}

/// The temperature and Sonine a2 of the `total` particles of all ranks (`records` here)
/// in the volume `volume`, from exact sums (collective): the definitions of
/// [`crate::observe::temperature`] and [`crate::observe::sonine_a2`], the same bits on any
/// number of ranks, without gathering the gas. One rank's cost per sample is a pass over
/// its particles and two all-reduces.
pub(crate) fn velocity_statistics<const D: usize, R: Record<D>>(
    records: &[R],
    species: &Species,
    total: usize,
    volume: f64,
    comm: &dyn Communicator,
    traffic: &mut Traffic,
) -> VelocityStatistics {
    let clock = Instant::now();
    let masses = &species.masses;
    let equal_masses = masses.iter().all(|&m| m == masses[0]);
    let first = sums_of(records, D + 1, |r, s| {
        let m = masses[r.species()];
        s[0].add(m);
        (0..D).for_each(|k| s[1 + k].add(m * r.velocity()[k]));
    });
    let first = global_values(&first, comm, traffic);
    let mean: Vector<D> = std::array::from_fn(|k| first[1 + k] / first[0]);
    let second = sums_of(records, 3, |r, s| {
        let m = masses[r.species()];
        let c: Vector<D> = std::array::from_fn(|k| r.velocity()[k] - mean[k]);
        let c2 = dot(&c, &c);
        let x = if equal_masses { c2 } else { m * c2 };
        s[0].add(m * c2);
        s[1].add(x);
        s[2].add(x * x);
    });
    let [spread, c2, c4] = global_values(&second, comm, traffic)[..] else {
        unreachable!("three sums")
    };
    let a2 = crate::observe::sonine_a2_of_sums::<D>(c2, c4, total as f64);
    traffic.gather_seconds += clock.elapsed().as_secs_f64();
    VelocityStatistics {
        temperature: spread / (total * D) as f64,
        a2,
        volume,
    }
}

/// The values of exact sums added over all ranks.
pub(crate) fn global_values(
    sums: &[ExactSum],
    comm: &dyn Communicator,
    traffic: &mut Traffic,
) -> Vec<f64> {
    let mut limbs: Vec<i64> = sums.iter().flat_map(|s| s.to_limbs()).collect();
    all_ranks_sum(&mut limbs, comm, traffic);
    limbs
        .chunks_exact(LIMBS + 1)
        .map(|l| ExactSum::from_limbs(l).value())
        .collect()
}

/// Element-wise sums over the ranks (timed as communication).
fn all_ranks_sum(values: &mut [i64], comm: &dyn Communicator, traffic: &mut Traffic) {
    if comm.size() > 1 {
        let clock = Instant::now();
        comm.sum_i64(values);
        traffic.communication_seconds += clock.elapsed().as_secs_f64();
    }
}

/// The walls' contact sums of a step over all ranks, exactly (the counts and the limbs of
/// every exact sum in one all-reduce): every rank then holds the same totals, those of the
/// run in one process.
pub(crate) fn contact_sums_over_ranks(
    sums: &[crate::walls::ContactSums],
    comm: &dyn Communicator,
    traffic: &mut Traffic,
) -> Vec<crate::walls::ContactSums> {
    let width = 2 + 3 * (LIMBS + 1);
    let mut values: Vec<i64> = Vec::with_capacity(width * sums.len());
    for s in sums {
        values.push(s.collisions as i64);
        values.push(s.lifts as i64);
        for sum in [&s.momentum, &s.energy, &s.lift_energy] {
            values.extend(sum.to_limbs());
        }
    }
    all_ranks_sum(&mut values, comm, traffic);
    values
        .chunks_exact(width)
        .map(|v| {
            let limbs = |i: usize| {
                let start = 2 + i * (LIMBS + 1);
                ExactSum::from_limbs(&v[start..start + LIMBS + 1])
            };
            crate::walls::ContactSums {
                collisions: v[0] as u64,
                lifts: v[1] as u64,
                momentum: limbs(0),
                energy: limbs(1),
                lift_energy: limbs(2),
            }
        })
        .collect()
}
