//! The spatial engine behind the engine interface ([`Engine`]) and its check-points
//! ([`Checkpoint`]).

use super::super::SpatialSnapshot;
use super::SpatialDsmc;
use crate::engine::{Checkpoint, Counters, Engine};
use crate::error::Result;
use crate::parallel::Local;
use crate::system::{System, Vector};
use restitution::Restitution;
use std::sync::Arc;

impl<const D: usize> Engine<D> for SpatialDsmc<D> {
    /// Runs until the time reaches `t` (the last step shortened to end there).
    fn run_until(&mut self, t: f64) {
        self.run(t, u64::MAX, u64::MAX);
    }

    /// Runs until `collisions` more collisions have happened, at the end of a step (the last
    /// steps shortened to the expected remaining count).
    fn run_collisions(&mut self, collisions: u64) {
        let target = self.tally.collisions.saturating_add(collisions);
        self.run(f64::INFINITY, target, u64::MAX);
    }

    /// Runs toward `end` and `collisions`, pausing at the end of the step where the tally
    /// reaches `pause` (see [`crate::Engine::run_paused`]).
    fn run_paused(&mut self, end: f64, collisions: u64, pause: u64) {
        self.run(end, collisions, pause);
    }

    fn time(&self) -> f64 {
        self.time
    }

    fn counters(&self) -> Counters {
        self.tally
    }

    /// Physical particles per simulated particle, F = phi V_box / (sum of sphere volumes).
    fn weight(&self) -> f64 {
        self.weight
    }

    /// The current state in the engine's current order (sorted by cell every step); on
    /// several ranks, gathered from all of them in rank order (the same order; collective).
    /// Under shear, velocities relative to the flow (peculiar: v - a y e_x).
    fn system(&mut self) -> &System<D> {
        self.fill_system(true);
        &self.system
    }

    fn shear(&self) -> Option<crate::shear::Shear> {
        self.shear
    }

    fn set_shear(&mut self, shear: Option<crate::shear::Shear>) -> Result<()> {
        SpatialDsmc::set_shear(self, shear)
    }

    fn set_tracking(&mut self, on: bool) -> Result<()> {
        SpatialDsmc::set_tracking(self, on)
    }

    /// The displacements in the engine's current order (that of [`Engine::system`]).
    fn displacements(&mut self) -> Option<Vec<Vector<D>>> {
        SpatialDsmc::displacements(self)
    }

    fn virial_tensor(&self) -> Option<crate::shear::Virial> {
        self.virial
    }

    /// Sums the tensor virial of the collisions (the impact direction's n n), from zero
    /// unless summed already.
    fn set_virial_tensor(&mut self, on: bool) -> Result<()> {
        if !on {
            self.virial = None;
        } else if self.virial.is_none() {
            self.virial = Some(crate::shear::Virial::default());
        }
        Ok(())
    }

    /// The collisions of each species' particles so far (each collision counts for both).
    fn species_collisions(&self) -> Option<Vec<crate::engine::SpeciesCollisions>> {
        Some(super::super::species::by_species(
            &self.species,
            &self.species_collisions,
            &self.tally,
        ))
    }

    /// Bytes held between steps: records, the sort's scratch (4 per particle and per
    /// cell), the output of [`SpatialDsmc::system`] once taken, the species tables. A step
    /// also allocates one entry per occupied cell, freed at its end.
    fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        let s = &self.system;
        self.records.memory_bytes()
            + self.sorter.memory_bytes()
            + (s.positions.capacity() + s.velocities.capacity()) * size_of::<Vector<D>>()
            + (s.radii.capacity() + s.masses.capacity()) * size_of::<f64>()
            + self.species.memory_bytes()
    }

    fn particles(&self) -> usize {
        self.len()
    }

    fn walls(&self) -> Option<Vec<crate::walls::WallRecord>> {
        self.walls.as_ref().map(|w| w.records())
    }

    fn rank_reports(&self) -> Option<Vec<crate::parallel::RankReport>> {
        self.reports_of_ranks()
    }

    /// Exact sums over ranks; under shear None (the observers take the peculiar
    /// velocities of [`Engine::system`]).
    fn velocity_statistics(&mut self) -> Option<crate::engine::VelocityStatistics> {
        if self.shear.is_some() {
            return None;
        }
        self.exact_velocity_statistics()
    }

    /// Gives the particles `rotation` in the order of [`Engine::system`] (collective);
    /// the inertia factor must be one per species.
    fn set_rotation(&mut self, rotation: Option<crate::rotation::Rotation>) -> Result<()> {
        self.set_rotation_of(rotation)
    }

    /// The particles' rotation in the order of [`Engine::system`] (collective).
    fn rotation(&mut self) -> Option<&crate::rotation::Rotation> {
        self.rotation_now()
    }

    /// Rough particles: the section `rotation` (contacts that slid, all ranks).
    fn report(&self) -> crate::engine::Report {
        self.rough_report()
    }
}

impl<const D: usize> Checkpoint<D> for SpatialDsmc<D> {
    type State = SpatialSnapshot<D>;
    /// The collision law.
    type Needs = Box<dyn Restitution>;

    fn save(&mut self) -> SpatialSnapshot<D> {
        self.snapshot()
    }

    /// Continues the run of `state` bit for bit with the law it used, in this process
    /// ([`SpatialDsmc::restore_distributed`] over ranks).
    fn restore(state: SpatialSnapshot<D>, law: Box<dyn Restitution>) -> Result<Self> {
        Self::restore_distributed(state, law, Arc::new(Local))
    }
}
