//! Rough particles in the homogeneous DSMC engine: the records become [`Spun`] (velocity,
//! species, angular velocity), the kernel adds the tangential half of each collision
//! (`kernel::Collider::rough_kick`); the rotation is given and taken in the order of
//! [`Engine::system`], every rank its share (collective).

use super::{HomogeneousDsmc, Store};
use crate::dsmc::kernel::{Spun, Tagged};
use crate::dsmc::rough::{self, Spin};
use crate::engine::Engine;
use crate::error::Result;
use crate::rotation::Rotation;
use crate::system::Vector;

impl<const D: usize> HomogeneousDsmc<D> {
    /// Gives the particles `rotation` (None: takes it away, refused for a rough law).
    /// The inertia factor must be one per species (the records carry their species
    /// only). Collective.
    pub(super) fn set_rotation_of(&mut self, rotation: Option<Rotation>) -> Result<()> {
        let Some(rotation) = rotation else {
            if self.core.law.tangential().is_some() {
                return Err(rough::rotation_needed());
            }
            self.take_rotation();
            return Ok(());
        };
        rotation.check(self.core.total, D)?;
        let system = self.system().clone();
        let species = &self.core.species;
        let kinds = system.radii.iter().zip(&system.masses).map(|(&r, &m)| {
            (0..species.len())
                .find(|&s| species.radii[s] == r && species.masses[s] == m)
                .expect("the engine's own species")
        });
        let inertia = rough::inertia_per_species(&rotation, kinds, species.len())?;
        self.give_rotation(rotation.angular, inertia, rotation.sliding);
        Ok(())
    }

    /// Turns the records into rough ones with the angular velocities `angular` (all
    /// particles, in the order of `system`: this rank takes its share) and the species'
    /// inertia factors. Collective.
    pub(super) fn give_rotation(
        &mut self,
        angular: Vec<[f64; 3]>,
        inertia: Vec<f64>,
        sliding: u64,
    ) {
        let offset = self.rank_offset();
        let spun = |velocity: Vector<D>, species: u32, i: usize| Spun {
            velocity,
            species,
            angular: angular[offset + i],
        };
        let records: Vec<Spun<D>> =
            match std::mem::replace(&mut self.store, Store::Uniform(Vec::new(), Vec::new())) {
                Store::Uniform(now, _) => now
                    .into_iter()
                    .enumerate()
                    .map(|(i, v)| spun(v, 0, i))
                    .collect(),
                Store::Mixed(now, _) => now
                    .into_iter()
                    .enumerate()
                    .map(|(i, r)| spun(r.velocity, r.species, i))
                    .collect(),
                Store::Rough(now, _) => now
                    .into_iter()
                    .enumerate()
                    .map(|(i, r)| spun(r.velocity, r.species, i))
                    .collect(),
            };
        self.store = Store::Rough(records, Vec::new());
        self.core.spin = Some(Spin::new(
            self.core.law.as_ref(),
            &self.core.species,
            inertia,
            sliding,
        ));
        // The classes of the exact scheme hold the records' order: sort anew.
        self.core.classes = None;
    }

    /// Smooth records again (the spins dropped).
    fn take_rotation(&mut self) {
        // (Smooth records stay as they are: replacing them by the placeholder's empty
        // store once dropped the gas of a smooth engine asked to take away no rotation.)
        self.store =
            match std::mem::replace(&mut self.store, Store::Uniform(Vec::new(), Vec::new())) {
                Store::Rough(now, _) => {
                    self.core.classes = None;
                    if self.core.species.len() == 1 {
                        Store::Uniform(now.into_iter().map(|r| r.velocity).collect(), Vec::new())
                    } else {
                        Store::Mixed(
                            now.into_iter()
                                .map(|r| Tagged {
                                    velocity: r.velocity,
                                    species: r.species,
                                })
                                .collect(),
                            Vec::new(),
                        )
                    }
                }
                smooth => smooth,
            };
        self.core.spin = None;
    }

    /// The particles before this rank's in the order of `system` (collective).
    fn rank_offset(&self) -> usize {
        let comm = &self.core.comm;
        if comm.size() == 1 {
            return 0;
        }
        let mine = match &self.store {
            Store::Uniform(now, _) => now.len(),
            Store::Mixed(now, _) => now.len(),
            Store::Rough(now, _) => now.len(),
        };
        let all = comm.all_gather(vec![mine as f64]);
        all[..comm.rank()].iter().map(|v| v[0] as usize).sum()
    }

    /// The rotation of all particles in the order of `system` (collective); None for
    /// smooth ones.
    pub(super) fn rotation_now(&mut self) -> Option<&Rotation> {
        self.core.spin.as_ref()?;
        let Store::Rough(now, _) = &self.store else {
            return None;
        };
        let all = super::gathered(now, &mut self.core);
        let spin = self.core.spin.as_ref()?;
        let kinds = all.iter().map(|r| r.species as usize);
        self.rotation = Some(spin.rotation(kinds, all.iter().map(|r| r.angular).collect()));
        self.rotation.as_ref()
    }
}
