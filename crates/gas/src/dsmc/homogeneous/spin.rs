//! Rough particles in the homogeneous DSMC engine: the records become [`Spun`] (velocity,
//! species, angular velocity), the kernel adds the tangential half of each collision
//! (`kernel::Collider::rough_kick`); the rotation is given and taken in the order of
//! [`Engine::system`], every rank its share (collective).

use super::{each_store, HomogeneousDsmc, Store};
use crate::dsmc::kernel::{Record, SpeciesTag, Spun, Tagged};
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
        let old = std::mem::replace(&mut self.store, Store::Uniform(Vec::new(), Vec::new()));
        let parts: Vec<(Vector<D>, u32)> = each_store!(old, (now, _) => now
            .into_iter()
            .map(|r| (*r.velocity(), r.species() as u32))
            .collect());
        self.store = if self.core.species.len() == 1 {
            Store::RoughUniform(spun(parts, &angular[offset..]), Vec::new())
        } else {
            Store::Rough(spun(parts, &angular[offset..]), Vec::new())
        };
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
        let smooth = |parts: Vec<(Vector<D>, u32)>, kinds: usize| {
            if kinds == 1 {
                Store::Uniform(parts.into_iter().map(|(v, _)| v).collect(), Vec::new())
            } else {
                Store::Mixed(
                    parts
                        .into_iter()
                        .map(|(velocity, species)| Tagged { velocity, species })
                        .collect(),
                    Vec::new(),
                )
            }
        };
        let kinds = self.core.species.len();
        self.store =
            match std::mem::replace(&mut self.store, Store::Uniform(Vec::new(), Vec::new())) {
                Store::Rough(now, _) => {
                    self.core.classes = None;
                    smooth(now.iter().map(|r| (r.velocity, r.species)).collect(), kinds)
                }
                Store::RoughUniform(now, _) => {
                    self.core.classes = None;
                    smooth(now.iter().map(|r| (r.velocity, 0)).collect(), kinds)
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
        let mine = each_store!(&self.store, (now, _) => now.len());
        let all = comm.all_gather(vec![mine as f64]);
        all[..comm.rank()].iter().map(|v| v[0] as usize).sum()
    }

    /// The rotation of all particles in the order of `system` (collective); None for
    /// smooth ones.
    pub(super) fn rotation_now(&mut self) -> Option<&Rotation> {
        self.core.spin.as_ref()?;
        let (kinds, angular): (Vec<usize>, Vec<[f64; 3]>) = match &self.store {
            Store::Rough(now, _) => super::gathered(now, &mut self.core)
                .iter()
                .map(|r| (r.species as usize, r.angular))
                .unzip(),
            Store::RoughUniform(now, _) => super::gathered(now, &mut self.core)
                .iter()
                .map(|r| (0, r.angular))
                .unzip(),
            _ => return None,
        };
        let spin = self.core.spin.as_ref()?;
        self.rotation = Some(spin.rotation(kinds.into_iter(), angular));
        self.rotation.as_ref()
    }
}

/// Rough records of the velocities and species `parts` with the angular velocities
/// `angular` (in one order).
fn spun<const D: usize, S: SpeciesTag>(
    parts: Vec<(Vector<D>, u32)>,
    angular: &[[f64; 3]],
) -> Vec<Spun<D, S>> {
    parts
        .into_iter()
        .zip(angular)
        .map(|((velocity, species), &angular)| Spun {
            velocity,
            species: S::of(species),
            angular,
        })
        .collect()
}
