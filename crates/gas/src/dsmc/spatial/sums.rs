//! The spatial engine's sums over cells and particles: exact ([`super::super::reduce`]),
//! so the same bits however cells and particles are spread over threads and ranks.

use super::super::kernel::{scaled, Moments, Record, SpeciesTally};
use super::super::reduce;
use super::super::species::Species;
use super::record::each;
use super::SpatialDsmc;
use crate::engine::{Counters, VelocityStatistics};
use crate::exact_sum::sums_of;
use crate::system::{dot, Vector};

impl<const D: usize> SpatialDsmc<D> {
    /// The counters of a step and the spread of all velocities about their mean, summed
    /// over the cells of all ranks exactly ([`crate::exact_sum`]): the same bits however
    /// the cells are spread over ranks and threads. The spread pools the cells' spreads
    /// about their own means (parallel-axis theorem: sum of spread_c + M_c |u_c - u|^2, no
    /// cancellation however large the mean velocity), so it takes two sums: mass and
    /// momentum first. Rough particles: also the contacts that slid.
    #[allow(clippy::type_complexity)]
    pub(super) fn sum_over_cells(
        &mut self,
        results: &[(SpeciesTally, Moments<D>)],
    ) -> (Counters, f64, Vec<u64>, Option<crate::shear::Virial>, u64) {
        let comm = self.comm.as_ref();
        let kinds = self.species.len();
        let with_tensor = self.virial.is_some();
        let totals = reduce::step_sums(
            results,
            kinds,
            false,
            with_tensor,
            self.spin.is_some(),
            comm,
            &mut self.traffic,
        );
        let mean = totals.mean();
        // Under shear the cells' means follow the flow: the spread (which sets the step)
        // is then the cells' own, about their means.
        let pooled = self.shear.is_none();
        let spread = sums_of(results, 1, |(_, m), s| {
            let u = m.mean();
            let d: Vector<D> = std::array::from_fn(|k| u[k] - mean[k]);
            let between = if pooled { m.mass * dot(&d, &d) } else { 0.0 };
            s[0].add(m.spread + between);
        });
        let spread = reduce::global_values(&spread, comm, &mut self.traffic)[0];
        (
            totals.tally,
            spread,
            totals.species_collisions,
            totals.virial,
            totals.sliding,
        )
    }

    /// The temperature and Sonine a2 of all particles and the box volume, from exact sums
    /// over the particles of all ranks (collective; [`reduce::velocity_statistics`]).
    pub(super) fn exact_velocity_statistics(&mut self) -> Option<VelocityStatistics> {
        let volume = crate::system::box_volume(&self.sides);
        Some(each!(&self.records, records => reduce::velocity_statistics(
            records,
            &self.species,
            self.total,
            volume,
            self.comm.as_ref(),
            &mut self.traffic,
        )))
    }
}

/// The mass and momentum of a cell, summed in the order of [`Moments::of`] (so bit for bit
/// its values), in one pass, without a mass lookup per particle for one species.
#[inline]
pub(super) fn mass_and_momentum<const D: usize, R: Record<D>>(
    cell: &[R],
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
        cell.iter().for_each(|r| add(m, r.velocity()));
    } else {
        cell.iter()
            .for_each(|r| add(species.masses[r.species()], r.velocity()));
    }
    (mass, momentum)
}

/// The [`Moments`] of a cell from its mass and momentum (as [`Moments::of`] computes them,
/// bit for bit): the spread sum of m |v - mean|^2 in a second pass.
#[inline]
pub(super) fn spread_about_mean<const D: usize, R: Record<D>>(
    cell: &[R],
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
        cell.iter().map(|r| term(m, r.velocity())).sum()
    } else {
        cell.iter()
            .map(|r| term(species.masses[r.species()], r.velocity()))
            .sum()
    };
    Moments {
        mass,
        momentum,
        spread,
    }
}
