//! The complete state of the event-driven engine, and the engine interface.

use super::{BathState, EventDriven, Particle};
use crate::cells::NONE;
use crate::driving::Drive;
use crate::engine::{Checkpoint, Counters, Engine};
use crate::error::{Error, Result};
use crate::serde_util;
use crate::shear::Virial;
use crate::sorter::SorterKind;
use crate::system::{wrap, System, Vector};
use crate::tail::Tail;
use crate::walls::{WallRecord, WallsState};
use restitution::Restitution;
use serde::{Deserialize, Serialize};

impl<const D: usize> EventDriven<D> {
    /// Brings every particle to the current time, rebuilds the cell lists and predicts
    /// every event afresh: the state is then a function of (positions, velocities, time)
    /// alone, so a run restored from a snapshot taken here continues bit for bit.
    pub fn synchronize(&mut self) {
        let n = self.particles.len();
        self.heads.iter_mut().for_each(|h| *h = NONE);
        self.occupied.iter_mut().for_each(|w| *w = 0);
        for i in 0..n {
            self.bring_to_now(i);
            if self.shear.is_some() {
                let p = &self.particles[i];
                let (x, v) = self.brought_into_box(&p.position, &p.velocity);
                let p = &mut self.particles[i];
                (p.position, p.velocity) = (x, v);
            }
        }
        if let Some(le) = self.shear {
            // The interval of shifts from the time alone (the canonical form).
            self.shear = Some(self.lees_edwards(le.shear));
        }
        // With gravity, the falling frame is the box's now: positions are the box's.
        self.move_frame();
        for i in 0..n {
            let p = &mut self.particles[i];
            p.collision = f64::INFINITY;
            p.crossing = f64::INFINITY;
            p.partner = NONE;
            let position = p.position;
            let c = self.cell_of(&position);
            self.insert(i, c);
        }
        self.predict_all();
    }

    /// Fills the output system with every position at the current time (wrapped into the
    /// box) and the lab velocities, or the peculiar ones (`peculiar`, under shear).
    fn fill_system(&mut self, peculiar: bool) {
        let (time, sides) = (self.time, self.system.sides);
        let mut positions = std::mem::take(&mut self.system.positions);
        let mut velocities = std::mem::take(&mut self.system.velocities);
        let (mut radii, mut masses) = (
            std::mem::take(&mut self.system.radii),
            std::mem::take(&mut self.system.masses),
        );
        positions.clear();
        velocities.clear();
        radii.clear();
        masses.clear();
        for p in &self.particles {
            let (x, v) = match &self.field {
                None => (p.position_at(time), p.velocity),
                Some(f) => f.to_box(&p.position_at(time), &p.velocity, time),
            };
            let (x, v) = self.brought_into_box(&x, &v);
            let v = if peculiar { self.peculiar(&x, &v) } else { v };
            positions.push(std::array::from_fn(|k| wrap(x[k], sides[k])));
            velocities.push(v);
            radii.push(p.radius);
            masses.push(p.mass);
        }
        let s = &mut self.system;
        (s.positions, s.velocities, s.radii, s.masses) = (positions, velocities, radii, masses);
    }

    /// Collision counts per particle modulo 2^32 (for snapshots; contacts with walls
    /// are not collisions).
    pub fn counts(&self) -> Vec<u64> {
        self.particles
            .iter()
            .map(|p| p.count.wrapping_sub(p.wall_hits) as u64)
            .collect()
    }
}

/// The TC model in a saved state.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TcState {
    /// Contact duration.
    pub duration: f64,
    /// Each particle's last collision time (null before its first).
    #[serde(with = "serde_util::never_as_null")]
    pub last: Vec<f64>,
}

/// Everything an [`EventDriven`] engine needs to continue bit for bit (with its law),
/// taken after [`EventDriven::synchronize`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EventDrivenState<const D: usize> {
    pub time: f64,
    /// Positions at `time`, velocities, radii and masses.
    pub system: System<D>,
    /// Collision count of each particle (modulo 2^32), which stamps predictions.
    pub counts: Vec<u64>,
    pub counters: Counters,
    /// The smallest cell width asked for (0: one diameter).
    pub min_cell_width: f64,
    pub sorter: SorterKind,
    /// The TC model, if on.
    pub tc: Option<TcState>,
    /// The baths of a stochastic law.
    pub baths: Option<BathState>,
    /// Collisions without time advancing since `stall_since` (collapse detection).
    pub stall_since: f64,
    pub stall_collisions: u64,
    /// The walls' tallies in a container, the shear, the tensor virial (absent from
    /// periodic runs' states, which stay as they were byte for byte; the last field, so
    /// that a reader of postcard can take the end of the data for None:
    /// [`crate::tail::Tail`]).
    #[serde(default, skip_serializing_if = "Tail::is_empty")]
    pub tail: Tail<WallsState>,
}

impl<const D: usize> EventDrivenState<D> {
    /// Checks the state for what a check-point could hold wrongly: time, positions in the
    /// box, finite velocities, positive radii and masses, one count per particle, finite
    /// counters, TC and bath arrays of the right length and range.
    pub fn check(&self) -> Result<()> {
        let n = self.system.len();
        if !(self.time.is_finite() && self.time >= 0.0) {
            return Err(Error::out_of_range(
                "time",
                self.time,
                "a finite number >= 0",
            ));
        }
        self.system.check(true)?;
        if self.counts.len() != n {
            return Err(Error::LengthMismatch {
                what: "collision counts and particles".into(),
            });
        }
        self.counters.check("events")?;
        self.tail.check()?;
        if !(self.min_cell_width.is_finite() && self.min_cell_width >= 0.0) {
            return Err(Error::out_of_range(
                "min_cell_width",
                self.min_cell_width,
                "a finite number >= 0",
            ));
        }
        if !(self.stall_since.is_finite() && self.stall_since <= self.time) {
            return Err(Error::out_of_range(
                "stall_since",
                self.stall_since,
                "a finite time <= time",
            ));
        }
        if let Some(tc) = &self.tc {
            if let Some(i) = tc
                .last
                .iter()
                .position(|&t| !(t == f64::NEG_INFINITY || (t.is_finite() && t <= self.time)))
            {
                return Err(Error::out_of_range(
                    format!("tc.last[{i}]"),
                    tc.last[i],
                    "a collision time <= time (or none)",
                ));
            }
        }
        Ok(())
    }
}

impl<const D: usize> Engine<D> for EventDriven<D> {
    fn collision_counts(&self) -> Option<Vec<u32>> {
        Some(
            self.particles
                .iter()
                .map(|p| p.count.wrapping_sub(p.wall_hits))
                .collect(),
        )
    }

    fn walls(&self) -> Option<Vec<WallRecord>> {
        self.walls.as_ref().map(|w| w.records())
    }

    /// Runs until the time reaches `t` (events at later times stay pending), or stops at
    /// inelastic collapse (see [`Engine::collapsed`]).
    fn run_until(&mut self, t: f64) {
        while let Some(next) = self.upcoming() {
            if next > t || !self.step() {
                break;
            }
        }
        if self.collapsed.is_none() {
            self.time = self.time.max(t);
        }
    }

    /// Runs until `collisions` more collisions have happened (or nothing moves).
    fn run_collisions(&mut self, collisions: u64) {
        let target = self.tally.collisions + collisions;
        while self.tally.collisions < target && self.step() {}
    }

    fn run_paused(&mut self, end: f64, collisions: u64, pause: u64) {
        EventDriven::run_bounded(self, end, collisions.min(pause))
    }

    fn time(&self) -> f64 {
        self.time
    }

    fn counters(&self) -> Counters {
        self.tally
    }

    fn particles(&self) -> usize {
        self.particles.len()
    }

    /// The state with every position at the current time (wrapped into the box); under
    /// shear, velocities relative to the flow (peculiar: v - a y e_x).
    fn system(&mut self) -> &System<D> {
        self.fill_system(true);
        &self.system
    }

    /// The tensor virial summed so far, if asked for
    /// ([`EventDriven::set_virial_tensor`]).
    fn virial_tensor(&self) -> Option<Virial> {
        self.virial
    }

    fn set_virial_tensor(&mut self, on: bool) -> Result<()> {
        EventDriven::set_virial_tensor(self, on);
        Ok(())
    }

    fn shear(&self) -> Option<crate::shear::Shear> {
        EventDriven::shear(self)
    }

    fn set_tracking(&mut self, on: bool) -> Result<()> {
        EventDriven::set_tracking(self, on)
    }

    fn displacements(&mut self) -> Option<Vec<Vector<D>>> {
        EventDriven::displacements(self)
    }

    fn set_shear(&mut self, shear: Option<crate::shear::Shear>) -> Result<()> {
        EventDriven::set_shear(self, shear)
    }

    fn set_rotation(&mut self, rotation: Option<crate::rotation::Rotation>) -> Result<()> {
        EventDriven::set_rotation(self, rotation)
    }

    fn rotation(&mut self) -> Option<&crate::rotation::Rotation> {
        self.rotation.as_ref()
    }

    /// Rough particles: the section `rotation` (contacts that slid).
    fn report(&self) -> crate::engine::Report {
        crate::engine::Report {
            sections: self
                .rotation
                .as_ref()
                .map(|r| r.report(self.tally.collisions))
                .into_iter()
                .collect(),
        }
    }

    /// Bath temperature of each particle, if the law is stochastic.
    fn bath_temperatures(&self) -> Option<&[f64]> {
        self.baths.as_ref().map(|b| b.temperatures.as_slice())
    }

    /// The time of inelastic collapse, if the engine stopped there: more than
    /// [`super::COLLAPSE_COLLISIONS_PER_PARTICLE`] collisions per particle without time
    /// advancing (a finite-time singularity of inelastic hard spheres; the TC model
    /// prevents it).
    fn collapsed(&self) -> Option<f64> {
        self.collapsed
    }

    /// Drives the gas at the times k `interval` (required; the first after the current
    /// time), white-noise kicks drawn from `seed` (see [`super::driving`]).
    fn set_driving(&mut self, drive: Option<Drive>) -> Result<()> {
        self.drive(drive)
    }

    /// Bytes held by the engine's per-particle and per-cell arrays (state, predictions,
    /// sorter, cell lists, and the snapshot of [`Engine::system`] once taken).
    fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        let s = &self.system;
        let snapshot = (s.positions.capacity() + s.velocities.capacity()) * size_of::<Vector<D>>()
            + (s.radii.capacity() + s.masses.capacity()) * size_of::<f64>();
        let state = self.particles.capacity() * size_of::<Particle<D>>()
            + self.heads.capacity() * size_of::<u32>()
            + self.occupied.capacity() * size_of::<u64>()
            + self.tc.as_ref().map_or(0, |tc| tc.last.capacity() * 8);
        snapshot + state + self.queue.memory_bytes()
    }
}

impl<const D: usize> Checkpoint<D> for EventDriven<D> {
    type State = EventDrivenState<D>;
    /// The collision law.
    type Needs = Box<dyn Restitution>;

    /// Synchronizes the engine (see [`EventDriven::synchronize`]), then takes its state.
    fn save(&mut self) -> EventDrivenState<D> {
        self.synchronize();
        EventDrivenState {
            time: self.time,
            system: {
                // Lab velocities: the flow is part of the state.
                self.fill_system(false);
                self.system.clone()
            },
            counts: self.counts(),
            counters: self.tally,
            min_cell_width: self.min_cell_width,
            sorter: self.queue.kind(),
            tc: self.tc.as_ref().map(|tc| TcState {
                duration: tc.duration,
                last: tc.last.clone(),
            }),
            baths: self.bath_state(),
            stall_since: self.stall.0,
            stall_collisions: self.stall.1,
            tail: Tail {
                walls: self.walls.as_ref().map(|w| w.state()),
                shear: self.shear(),
                virial: self.virial,
                tracks: self.tracks.clone(),
                rotation: self.rotation.clone(),
                history: None,
            },
        }
    }

    /// Checks the state ([`EventDrivenState::check`]), then builds the engine (which
    /// refuses overlapping spheres and inconsistent TC or bath arrays).
    fn restore(state: EventDrivenState<D>, law: Box<dyn Restitution>) -> Result<Self> {
        state.check()?;
        let EventDrivenState {
            time,
            system,
            counts,
            counters,
            min_cell_width,
            sorter,
            tc,
            baths,
            stall_since,
            stall_collisions,
            tail,
        } = state;
        if counts.len() != system.len() {
            return Err(Error::LengthMismatch {
                what: "collision counts and particles".into(),
            });
        }
        // Predicted once, by `synchronize` below.
        let mut engine = Self::assemble(system, law, min_cell_width, tail.shear, time)?;
        engine.time = time;
        for (p, count) in engine.particles.iter_mut().zip(counts) {
            p.valid_at = time;
            // Counts are kept modulo 2^32 (see `Particle::count`).
            p.count = count as u32;
        }
        engine.tally = counters;
        engine.stall = (stall_since, stall_collisions);
        engine.idle = (time, 0);
        // Taken up when the walls are set again (they are not part of the state).
        engine.saved_walls = tail.walls;
        engine.virial = tail.virial;
        if let Some(tracks) = &tail.tracks {
            tracks.check(D * engine.particles.len())?;
        }
        engine.tracks = tail.tracks;
        if let Some(rotation) = tail.rotation {
            engine.set_rotation(Some(rotation))?;
        }
        if sorter != SorterKind::default() {
            engine.set_sorter(sorter);
        }
        engine.synchronize();
        if let Some(baths) = baths {
            engine.set_bath_state(baths)?;
        }
        if let Some(tc) = tc {
            engine.set_tc_model(tc.duration, Some(tc.last))?;
        }
        Ok(engine)
    }
}
