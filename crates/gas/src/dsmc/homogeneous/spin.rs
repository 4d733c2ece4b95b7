//! Rough particles in the homogeneous DSMC engine: the records become [`Spun`] (velocity,
//! species, angular velocity), the kernel adds the tangential half of each collision
//! (`kernel::Collider::rough_kick`); the rotation is given and taken in the order of
//! [`Engine::system`], every rank its share (collective).

use super::{HomogeneousDsmc, Spin, Store};
use crate::dsmc::kernel::{Spun, Tagged};
use crate::engine::Engine;
use crate::error::{Error, Result};
use crate::rotation::{Inverses, Rotation};
use crate::system::Vector;

impl<const D: usize> HomogeneousDsmc<D> {
    /// Gives the particles `rotation` (None: takes it away, refused for a rough law).
    /// The inertia factor must be one per species (the records carry their species
    /// only). Collective.
    pub(super) fn set_rotation_of(&mut self, rotation: Option<Rotation>) -> Result<()> {
        let Some(rotation) = rotation else {
            if self.core.law.tangential().is_some() {
                return Err(Error::out_of_range(
                    "rotation",
                    "none",
                    "a rotation for every particle: the law is rough",
                ));
            }
            self.take_rotation();
            return Ok(());
        };
        rotation.check(self.core.total, D)?;
        let system = self.system().clone();
        let mut inertia: Vec<Option<f64>> = vec![None; self.core.species.len()];
        for (i, (&r, &m)) in system.radii.iter().zip(&system.masses).enumerate() {
            let s = (0..self.core.species.len())
                .find(|&s| self.core.species.radii[s] == r && self.core.species.masses[s] == m)
                .expect("the engine's own species");
            match inertia[s] {
                None => inertia[s] = Some(rotation.inertia[i]),
                Some(q) if q == rotation.inertia[i] => {}
                Some(q) => {
                    return Err(Error::out_of_range(
                        format!("inertia[{i}]"),
                        rotation.inertia[i],
                        format!("{q}, the inertia factor of its species (one per species in DSMC)"),
                    ))
                }
            }
        }
        let inertia = inertia.into_iter().map(|q| q.unwrap_or(0.4)).collect();
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
        let species = &self.core.species;
        let inverses = (0..species.len())
            .map(|s| Inverses::of(species.masses[s], species.radii[s], inertia[s]))
            .collect();
        let tangential = self.rules_per_pair();
        self.core.spin = Some(Spin {
            tangential,
            inertia,
            inverses,
            sliding,
        });
        // The classes of the exact scheme hold the records' order: sort anew.
        self.core.classes = None;
    }

    /// The law's tangential rules per pair of the engine's species (row-major), one rule
    /// for all, or none for a smooth law. A species the law's table lacks takes the
    /// table's first rule (the sim layer names a rule for every species).
    fn rules_per_pair(&self) -> Vec<restitution::rough::Tangential> {
        let law = self.core.law.as_ref();
        let (Some(one), species) = (law.tangential(), &self.core.species) else {
            return Vec::new();
        };
        let Some(table) = law.tangential_pairs() else {
            return vec![*one];
        };
        let kind = |s: usize| {
            table
                .kind_of(species.radii[s], species.masses[s])
                .unwrap_or(0)
        };
        let n = species.len();
        (0..n * n)
            .map(|k| *table.rule(kind(k / n), kind(k % n)))
            .collect()
    }

    /// Smooth records again (the spins dropped).
    fn take_rotation(&mut self) {
        if let Store::Rough(now, _) =
            std::mem::replace(&mut self.store, Store::Uniform(Vec::new(), Vec::new()))
        {
            self.store = if self.core.species.len() == 1 {
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
            };
            self.core.classes = None;
        } else {
            self.store = std::mem::replace(&mut self.store, Store::Uniform(Vec::new(), Vec::new()));
        }
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
        let spin = self.core.spin.as_ref()?;
        let Store::Rough(now, _) = &self.store else {
            return None;
        };
        let (inertia, sliding) = (spin.inertia.clone(), spin.sliding);
        let all = super::gathered(now, &mut self.core);
        self.rotation = Some(Rotation {
            inertia: all.iter().map(|r| inertia[r.species as usize]).collect(),
            angular: all.iter().map(|r| r.angular).collect(),
            sliding,
        });
        self.rotation.as_ref()
    }
}
