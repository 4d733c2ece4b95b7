//! One interface for every engine (DynamO's "dynamics", lumol's `Propagator`): advance to
//! a time or by a number of collisions, report one counter type, expose the state for the
//! observables, and save/restore the complete state ([`Checkpoint`]). The run driver
//! (crate `haff-sim`) drives every engine through these two traits only; a new engine
//! (e.g. soft-sphere MD) implements them, and the driver only needs to know its name in the
//! run description and how to build it (docs/architecture.md).

use crate::driving::Drive;
use crate::system::System;
use crate::{Error, Result};
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

    /// Checks a restored tally: finite sums and, where every collision is an event
    /// (`events` = the events or candidates it took), no more collisions than events.
    pub(crate) fn check(&self, events: &str) -> Result<()> {
        let counted = events.is_empty() || self.events >= self.collisions;
        if !(self.energy_lost.is_finite() && self.virial.is_finite() && counted) {
            let range = if events.is_empty() {
                "finite sums".to_string()
            } else {
                format!("finite sums and {events} >= collisions")
            };
            return Err(Error::out_of_range("counters", format!("{self:?}"), range));
        }
        Ok(())
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

    /// The walls of a closed container with what each has done so far (None: periodic, or
    /// an engine without walls).
    fn walls(&self) -> Option<Vec<crate::walls::WallRecord>> {
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

    /// What the engine reports of itself beyond the common counters (soft-sphere MD: its
    /// contacts), written into `summary.json` section by section; empty by default.
    fn report(&self) -> Report {
        Report::default()
    }

    /// Drives the gas from now on as `drive` says (None: freely cooling). Not part of the
    /// engine's state: set it again after a restore. The default drives nothing and refuses
    /// any driving.
    fn set_driving(&mut self, drive: Option<Drive>) -> Result<()> {
        match drive {
            None => Ok(()),
            Some(_) => Err(Error::Unsupported {
                what: "driving".into(),
            }),
        }
    }

    /// The uniform shear flow the engine imposes (None: none). Under shear,
    /// [`Engine::system`]'s velocities are the peculiar ones (relative to the flow).
    fn shear(&self) -> Option<crate::shear::Shear> {
        None
    }

    /// Imposes the uniform shear flow u = rate y e_x from now on (None: none), the gas's
    /// velocities taken as the peculiar ones. Part of the engine's state. The default
    /// refuses any shear.
    fn set_shear(&mut self, shear: Option<crate::shear::Shear>) -> Result<()> {
        match shear {
            None => Ok(()),
            Some(_) => Err(Error::Unsupported {
                what: "shear".into(),
            }),
        }
    }

    /// Tracks the particles' displacements from now on (part of the engine's state), or
    /// stops. The default refuses to track.
    fn set_tracking(&mut self, on: bool) -> Result<()> {
        if on {
            return Err(Error::Unsupported {
                what: "tracking displacements".into(),
            });
        }
        Ok(())
    }

    /// Each particle's displacement since tracking began (unwrapped across the periodic
    /// box), in the order of [`Engine::system`]; None if not tracked.
    fn displacements(&mut self) -> Option<Vec<crate::system::Vector<D>>> {
        None
    }

    /// Gives the particles the rotation `rotation` (inertia factors and angular
    /// velocities, in the order of [`Engine::system`]; part of the engine's state) or
    /// takes it away (`None`, only for an engine whose law is smooth). Collisions couple
    /// it to translation if the law is rough ([`restitution::Restitution::tangential`]).
    /// The default refuses rotation.
    fn set_rotation(&mut self, rotation: Option<crate::rotation::Rotation>) -> Result<()> {
        match rotation {
            Some(_) => Err(Error::Unsupported {
                what: "rotation (rough particles)".into(),
            }),
            None => Ok(()),
        }
    }

    /// The particles' rotation in the order of [`Engine::system`]; None without it.
    fn rotation(&mut self) -> Option<&crate::rotation::Rotation> {
        None
    }

    /// The tensor virial of the collisions summed since it was asked for
    /// ([`Engine::set_virial_tensor`]), for the pressure tensor
    /// ([`crate::observe::pressure_tensor`]); None if not summed.
    fn virial_tensor(&self) -> Option<crate::shear::Virial> {
        None
    }

    /// Sums the tensor virial from now on (part of the engine's state), or stops. The
    /// default refuses to sum it.
    fn set_virial_tensor(&mut self, on: bool) -> Result<()> {
        if on {
            return Err(Error::Unsupported {
                what: "the tensor virial".into(),
            });
        }
        Ok(())
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
/// bit for bit as the saved one would have.
pub trait Checkpoint<const D: usize>: Engine<D> + Sized {
    /// Everything needed to continue, options included, as plain serde data.
    type State: Serialize + DeserializeOwned + Clone + Debug;
    /// What a restore needs besides the state: the collision law for engines of
    /// instantaneous collisions (laws are not data), nothing (`()`) for engines whose
    /// dynamics is all in their state (soft-sphere MD: the material; the rod chain).
    type Needs;

    /// The state now. Engines may bring themselves to a canonical form first (the
    /// event-driven engine synchronizes every particle), so a run that saves at given
    /// points is bit-identical to one that saves and restores there.
    fn save(&mut self) -> Self::State;

    /// An engine continuing from `state` (with what it `needs`), after checking the state
    /// for consistency; fails for an inconsistent state. The only way back from a state:
    /// engines have no unchecked restore.
    fn restore(state: Self::State, needs: Self::Needs) -> Result<Self>;
}

/// What an engine reports of itself beyond the counters ([`Engine::report`]): named
/// sections of named numbers (one JSON object per section in `summary.json`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Report {
    pub sections: Vec<ReportSection>,
}

impl Report {
    /// The section called `name`, if the engine reports one.
    pub fn section(&self, name: &str) -> Option<&ReportSection> {
        self.sections.iter().find(|s| s.name == name)
    }
}

/// One section of a [`Report`], e.g. `contacts`.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportSection {
    pub name: &'static str,
    pub values: Vec<(&'static str, ReportValue)>,
}

impl ReportSection {
    /// The value called `key`.
    pub fn get(&self, key: &str) -> Option<ReportValue> {
        self.values.iter().find(|(k, _)| *k == key).map(|(_, v)| *v)
    }

    /// The value called `key` as a real number (NaN if absent).
    pub fn number(&self, key: &str) -> f64 {
        self.get(key).map_or(f64::NAN, ReportValue::as_f64)
    }
}

/// A number of a [`ReportSection`]: a count or a real number.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ReportValue {
    Count(u64),
    Real(f64),
}

impl ReportValue {
    pub fn as_f64(self) -> f64 {
        match self {
            ReportValue::Count(n) => n as f64,
            ReportValue::Real(x) => x,
        }
    }
}

impl Serialize for ReportValue {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match *self {
            ReportValue::Count(n) => s.serialize_u64(n),
            ReportValue::Real(x) => s.serialize_f64(x),
        }
    }
}

impl Serialize for ReportSection {
    /// The values as one object (`{"steps": 120, "time_step": 0.001, ...}`).
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = s.serialize_map(Some(self.values.len()))?;
        for (key, value) in &self.values {
            map.serialize_entry(key, value)?;
        }
        map.end()
    }
}
