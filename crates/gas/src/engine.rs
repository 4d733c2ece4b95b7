//! One interface for every engine (DynamO's "dynamics", lumol's `Propagator`): advance to
//! a time or by a number of collisions, report one counter type, expose the state for the
//! observables, and save/restore the complete state ([`Checkpoint`]). The run driver
//! (crate `haff-sim`) drives every engine through these two traits only; a new engine
//! (e.g. soft-sphere MD) implements them, and the driver only needs to know its name in the
//! run description and how to build it (docs/architecture.md).

use crate::system::System;
use crate::Result;
use restitution::Restitution;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::fmt::Debug;

/// Counters and accumulators of a run, the same for every engine.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Counters {
    /// Collisions processed (DSMC: accepted candidates).
    pub collisions: u64,
    /// Events processed: event-driven, collisions, cell crossings and stale predictions;
    /// DSMC, candidate collisions drawn from the majorant process.
    pub events: u64,
    /// Kinetic energy dissipated, the sum of (1 - eps^2) m_red (g.e)^2 / 2.
    pub energy_lost: f64,
    /// Sum over collisions of the momentum transfer times the contact distance (the
    /// collisional virial; see [`crate::observe::pressure`]).
    pub virial: f64,
    /// Collisions the TC model made elastic (event-driven).
    pub tc_elastic: u64,
}

impl Counters {
    /// Adds the counts of `other` (one block or cell of a step) to these.
    pub(crate) fn add(&mut self, other: &Counters) {
        self.collisions += other.collisions;
        self.events += other.events;
        self.energy_lost += other.energy_lost;
        self.virial += other.virial;
        self.tc_elastic += other.tc_elastic;
    }
}

/// What [`Engine::velocity_statistics`] gives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityStatistics {
    pub temperature: f64,
    pub a2: f64,
    pub volume: f64,
}

/// The collisions suffered by the particles of one species (told by its radius and mass),
/// a collision counting once for each of its two particles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpeciesCollisions {
    pub radius: f64,
    pub mass: f64,
    pub collisions: u64,
}

/// An engine over N particles in D dimensions.
pub trait Engine<const D: usize> {
    /// Runs until the time reaches `t` (no effect if it already has).
    fn run_until(&mut self, t: f64);

    /// Runs until `collisions` more collisions have happened (stepped engines stop at the
    /// end of a step; see theirs).
    fn run_collisions(&mut self, collisions: u64);

    /// Runs toward `end` in time and `collisions` in the collision tally (a total, not an
    /// increment), stopping at whichever comes first, but pauses once the tally reaches
    /// `pause`: the run driver advances in such pieces to look for interruptions between
    /// them. Pieces compose: running toward (t, c) paused at p1, then at p2 > p1, and so on,
    /// is bit-identical to running toward (t, c) at once (`run_until(t)` when
    /// c = `u64::MAX`, `run_collisions` up to c when t is infinite): stepped engines pause at
    /// the end of a step, and choose their steps by (t, c) only. The default ignores `pause`
    /// (the engine is then interrupted less often, never wrongly) and serves runs bounded by
    /// time or by collisions, not both.
    fn run_paused(&mut self, end: f64, collisions: u64, _pause: u64) {
        if end.is_finite() {
            self.run_until(end);
        } else {
            let have = self.counters().collisions;
            self.run_collisions(collisions.saturating_sub(have));
        }
    }

    fn time(&self) -> f64;

    fn counters(&self) -> Counters;

    /// Number of (simulated) particles.
    fn particles(&self) -> usize;

    /// Collisions per particle so far (each collision counts for two particles).
    fn collisions_per_particle(&self) -> f64 {
        2.0 * self.counters().collisions as f64 / self.particles() as f64
    }

    /// The state now, for the observables of [`crate::observe`]: positions (in the box),
    /// velocities, radii and masses in the engine's current order.
    fn system(&mut self) -> &System<D>;

    /// Physical particles each simulated particle stands for (spatial DSMC may
    /// under-resolve; 1 otherwise): collisional pressures scale with it.
    fn weight(&self) -> f64 {
        1.0
    }

    /// Collisions of each particle modulo 2^32, in the order of [`Engine::system`], if the
    /// engine counts them per particle (the event-driven engine does).
    fn collision_counts(&self) -> Option<Vec<u32>> {
        None
    }

    /// The collisions of each species' particles so far, if the engine counts them by
    /// species (DSMC; the event-driven engine counts per particle instead:
    /// [`Engine::collision_counts`]).
    fn species_collisions(&self) -> Option<Vec<SpeciesCollisions>> {
        None
    }

    /// Bath temperature of each particle, if the law is stochastic (Giese).
    fn bath_temperatures(&self) -> Option<&[f64]> {
        None
    }

    /// The time of inelastic collapse if the engine stopped there.
    fn collapsed(&self) -> Option<f64> {
        None
    }

    /// What the contacts of a force-based engine did (soft-sphere MD); None for engines
    /// of instantaneous collisions.
    fn contact_report(&self) -> Option<crate::soft::ContactReport> {
        None
    }

    /// The temperature and Sonine a2 of all particles ([`crate::observe::temperature`],
    /// [`crate::observe::sonine_a2`]) and the box volume, from sums over the particles where
    /// they are (a distributed engine: exact sums over ranks, collective, the same bits on
    /// any number of ranks); None: compute them from [`Engine::system`].
    fn velocity_statistics(&mut self) -> Option<VelocityStatistics> {
        None
    }

    /// Every rank's share of a distributed run and its communication (collective: every
    /// rank calls it); None for a run in one process.
    fn rank_reports(&self) -> Option<Vec<crate::parallel::RankReport>> {
        None
    }

    /// Bytes held by the engine's per-particle and per-cell data.
    fn memory_bytes(&self) -> usize;
}

/// An engine whose complete state can be saved and restored: a restored engine continues
/// bit for bit as the saved one would have (the law is passed again: laws are not data).
pub trait Checkpoint<const D: usize>: Engine<D> + Sized {
    /// Everything needed to continue, options included, as plain serde data.
    type State: Serialize + DeserializeOwned + Clone + Debug;

    /// The state now. Engines may bring themselves to a canonical form first (the
    /// event-driven engine synchronizes every particle), so a run that saves at given
    /// points is bit-identical to one that saves and restores there.
    fn save(&mut self) -> Self::State;

    /// An engine continuing from `state` with `law`; fails for an inconsistent state.
    fn restore(state: Self::State, law: Box<dyn Restitution>) -> Result<Self>;
}
