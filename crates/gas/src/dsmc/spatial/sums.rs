//! The spatial engine's sums over cells and particles: exact ([`crate::exact_sum`]), so
//! the same bits however cells and particles are spread over threads and ranks.

use super::super::kernel::{scaled, Moments, Record, Simulator};
use super::super::species::Species;
use super::SpatialDsmc;
use crate::engine::{Counters, VelocityStatistics};
use crate::exact_sum::{sums_of, ExactSum, LIMBS};
use crate::system::{dot, Vector};
use std::time::Instant;

impl<const D: usize> SpatialDsmc<D> {
    /// The counters of a step and the spread of all velocities about their mean, summed
    /// over the cells of all ranks exactly ([`crate::exact_sum`]): the same bits however
    /// the cells are spread over ranks and threads. The spread pools the cells' spreads
    /// about their own means (parallel-axis theorem: sum of spread_c + M_c |u_c - u|^2, no
    /// cancellation however large the mean velocity), so it
    /// takes two sums: mass and momentum first.
    pub(super) fn sum_over_cells(&mut self, results: &[(Counters, Moments<D>)]) -> (Counters, f64) {
        // Mass, momentum, energy lost, virial; then collisions, events, TC-elastic.
        let sums = sums_of(results, D + 3, |(t, m), s| {
            s[0].add(m.mass);
            (0..D).for_each(|k| s[1 + k].add(m.momentum[k]));
            s[D + 1].add(t.energy_lost);
            s[D + 2].add(t.virial);
        });
        let count = |f: fn(&Counters) -> u64| results.iter().map(|(t, _)| f(t) as i64).sum();
        let counts: [i64; 3] = [
            count(|t| t.collisions),
            count(|t| t.events),
            count(|t| t.tc_elastic),
        ];
        let mut packed: Vec<i64> = sums.iter().flat_map(|s| s.to_limbs()).collect();
        packed.extend_from_slice(&counts);
        self.all_ranks_sum(&mut packed);
        let values: Vec<f64> = packed
            .chunks_exact(LIMBS + 1)
            .take(D + 3)
            .map(|limbs| ExactSum::from_limbs(limbs).value())
            .collect();
        let counts = &packed[(D + 3) * (LIMBS + 1)..];
        let momentum: Vector<D> = std::array::from_fn(|k| values[1 + k]);
        let mean = scaled(&momentum, values[0]);
        let spread = sums_of(results, 1, |(_, m), s| {
            let u = m.mean();
            let d: Vector<D> = std::array::from_fn(|k| u[k] - mean[k]);
            s[0].add(m.spread + m.mass * dot(&d, &d));
        });
        let spread = self.global_values(&spread)[0];
        let tally = Counters {
            collisions: counts[0] as u64,
            events: counts[1] as u64,
            energy_lost: values[D + 1],
            virial: values[D + 2],
            tc_elastic: counts[2] as u64,
        };
        (tally, spread)
    }

    /// The temperature and Sonine a2 of all particles and the box volume, from exact sums
    /// over the particles of all ranks (collective): the definitions of
    /// [`crate::observe::temperature`] and [`crate::observe::sonine_a2`], the same bits on
    /// any number of ranks, without gathering the gas. On several ranks, one rank's cost
    /// per sample is a pass over its particles and two all-reduces.
    pub fn velocity_statistics(&mut self) -> Option<VelocityStatistics> {
        let clock = Instant::now();
        // A copy (one per species): the sums below borrow the engine mutably.
        let masses = self.species.masses.clone();
        let equal_masses = masses.iter().all(|&m| m == masses[0]);
        let first = sums_of(&self.simulators, D + 1, |p, s| {
            let m = masses[p.species as usize];
            s[0].add(m);
            (0..D).for_each(|k| s[1 + k].add(m * p.velocity[k]));
        });
        let first = self.global_values(&first);
        let mean: Vector<D> = std::array::from_fn(|k| first[1 + k] / first[0]);
        let second = sums_of(&self.simulators, 3, |p, s| {
            let m = masses[p.species as usize];
            let c: Vector<D> = std::array::from_fn(|k| p.velocity[k] - mean[k]);
            let c2 = dot(&c, &c);
            let x = if equal_masses { c2 } else { m * c2 };
            s[0].add(m * c2);
            s[1].add(x);
            s[2].add(x * x);
        });
        let [spread, c2, c4] = self.global_values(&second)[..] else {
            unreachable!("three sums")
        };
        let n = self.total as f64;
        let a2 = crate::observe::sonine_a2_of_sums::<D>(c2, c4, n);
        self.traffic.gather_seconds += clock.elapsed().as_secs_f64();
        Some(VelocityStatistics {
            temperature: spread / (self.total * D) as f64,
            a2,
            volume: self.length.powi(D as i32),
        })
    }

    /// The values of exact sums added over all ranks.
    fn global_values(&mut self, sums: &[ExactSum]) -> Vec<f64> {
        let mut limbs: Vec<i64> = sums.iter().flat_map(|s| s.to_limbs()).collect();
        self.all_ranks_sum(&mut limbs);
        limbs
            .chunks_exact(LIMBS + 1)
            .map(|l| ExactSum::from_limbs(l).value())
            .collect()
    }

    /// Element-wise sums over the ranks (timed as communication).
    fn all_ranks_sum(&mut self, values: &mut [i64]) {
        if self.comm.size() > 1 {
            let clock = Instant::now();
            self.comm.sum_i64(values);
            self.traffic.communication_seconds += clock.elapsed().as_secs_f64();
        }
    }
}

/// The mass and momentum of a cell, summed in the order of [`Moments::of`] (so bit for bit
/// its values), in one pass, without a mass lookup per particle for one species.
#[inline]
pub(super) fn mass_and_momentum<const D: usize>(
    cell: &[Simulator<D>],
    species: &Species,
) -> (f64, Vector<D>) {
    // -0.0: the start of std's float `Sum`, which `Moments::of` uses.
    let mut mass = -0.0;
    let mut momentum = [-0.0; D];
    let mut add = |m: f64, v: &Vector<D>| {
        mass += m;
        for k in 0..D {
            momentum[k] += m * v[k];
        }
    };
    if species.len() == 1 {
        let m = species.masses[0];
        cell.iter().for_each(|r| add(m, &r.velocity));
    } else {
        cell.iter()
            .for_each(|r| add(species.masses[r.species()], &r.velocity));
    }
    (mass, momentum)
}

/// The [`Moments`] of a cell from its mass and momentum (as [`Moments::of`] computes them,
/// bit for bit): the spread sum of m |v - mean|^2 in a second pass.
#[inline]
pub(super) fn spread_about_mean<const D: usize>(
    cell: &[Simulator<D>],
    species: &Species,
    mass: f64,
    momentum: Vector<D>,
) -> Moments<D> {
    let mean = scaled(&momentum, mass);
    let term = |m: f64, v: &Vector<D>| {
        let d: Vector<D> = std::array::from_fn(|k| v[k] - mean[k]);
        m * dot(&d, &d)
    };
    let spread = if species.len() == 1 {
        let m = species.masses[0];
        cell.iter().map(|r| term(m, &r.velocity)).sum()
    } else {
        cell.iter()
            .map(|r| term(species.masses[r.species()], &r.velocity))
            .sum()
    };
    Moments {
        mass,
        momentum,
        spread,
    }
}
