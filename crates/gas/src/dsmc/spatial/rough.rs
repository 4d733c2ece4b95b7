//! Rough particles in the spatial DSMC engine: the records become [`Rolling`] (the smooth
//! record and the angular velocity), the kernel adds the tangential half of each
//! collision (`kernel::Collider::rough_kick`, compiled for rough records only). A spin
//! travels with its record: streaming leaves it alone (free rotation, no torque: gravity
//! acts on the centre, walls are smooth), the sort into cells moves it with the record, a
//! record that leaves its rank's slab takes it along ([`super::record::Particle`]'s
//! message row). The rotation is given and taken in the order of [`crate::Engine::system`]
//! (collective).

use super::record::{each, with_records, Particle, Records, Rolling};
use super::SpatialDsmc;
use crate::dsmc::rough::{self, Spin};
use crate::engine::Report;
use crate::error::Result;
use crate::rotation::Rotation;

impl<const D: usize> SpatialDsmc<D> {
    /// Gives the particles `rotation` (None: takes it away, refused for a rough law).
    /// The inertia factor must be one per species (the records carry their species
    /// only). Collective.
    pub(super) fn set_rotation_of(&mut self, rotation: Option<Rotation>) -> Result<()> {
        let Some(rotation) = rotation else {
            if self.law.tangential().is_some() {
                return Err(rough::rotation_needed());
            }
            self.take_rotation();
            return Ok(());
        };
        rotation.check(self.total, D)?;
        let kinds: Vec<usize> = with_records!(self, records => self
            .in_global_order(&records)
            .iter()
            .map(|p| p.body().species as usize)
            .collect());
        let inertia = rough::inertia_per_species(&rotation, kinds.into_iter(), self.species.len())?;
        self.give_rotation(&rotation.angular, inertia, rotation.sliding);
        Ok(())
    }

    /// Turns the records into rough ones with the angular velocities `angular` (of all
    /// particles, in the order of [`crate::Engine::system`]: each rank takes its
    /// records') and the species' inertia factors. Collective.
    pub(super) fn give_rotation(&mut self, angular: &[[f64; 3]], inertia: Vec<f64>, sliding: u64) {
        let places = self.global_places();
        let rolling: Vec<Rolling<D>> = each!(std::mem::take(&mut self.records), records => records
            .into_iter()
            .zip(places)
            .map(|(p, i)| Rolling {
                body: *p.body(),
                angular: angular[i],
            })
            .collect());
        self.records = Records::Rough(rolling);
        self.spin = Some(Spin::new(
            self.law.as_ref(),
            &self.species,
            inertia,
            sliding,
        ));
    }

    /// Smooth records again (the spins dropped).
    fn take_rotation(&mut self) {
        self.records = match std::mem::take(&mut self.records) {
            Records::Rough(rolling) => {
                Records::Smooth(rolling.into_iter().map(|r| r.body).collect())
            }
            smooth => smooth,
        };
        self.spin = None;
        self.rotation = None;
    }

    /// A fresh engine of a rough law: solid spheres (disks) at rest until given their
    /// rotation (`Engine::set_rotation`).
    pub(super) fn start_rough_at_rest(&mut self) {
        if self.law.tangential().is_some() {
            let solid = if D == 2 { 0.5 } else { 0.4 };
            let inertia = vec![solid; self.species.len()];
            self.give_rotation(&vec![[0.0; 3]; self.total], inertia, 0);
        }
    }

    /// The place of each of this rank's records in the order of [`crate::Engine::system`]
    /// (collective): before the first step on several ranks, `ordinals`; after, rank by
    /// rank.
    fn global_places(&self) -> Vec<usize> {
        if let Some(ordinals) = &self.ordinals {
            return ordinals.iter().map(|&o| o as usize).collect();
        }
        let mine = self.records.len();
        let offset = if self.comm.size() == 1 {
            0
        } else {
            let all = self.comm.all_gather(vec![mine as f64]);
            all[..self.comm.rank()].iter().map(|v| v[0] as usize).sum()
        };
        (offset..offset + mine).collect()
    }

    /// `records` (this rank's) with those of all other ranks, in the order of
    /// [`crate::Engine::system`] (collective; on one rank, `records` themselves).
    fn in_global_order<'a, R: Particle<D>>(
        &mut self,
        records: &'a [R],
    ) -> std::borrow::Cow<'a, [R]> {
        if self.comm.size() == 1 {
            std::borrow::Cow::Borrowed(records)
        } else {
            std::borrow::Cow::Owned(self.gathered(records))
        }
    }

    /// The rotation of all particles in the order of [`crate::Engine::system`]
    /// (collective); None for smooth ones.
    pub(super) fn rotation_now(&mut self) -> Option<&Rotation> {
        self.spin.as_ref()?;
        let Records::Rough(records) = std::mem::take(&mut self.records) else {
            unreachable!("rough records while the spins' companion is there")
        };
        let rotation = {
            let all = self.in_global_order(&records);
            let kinds = all.iter().map(|r| r.body.species as usize);
            let spin = self.spin.as_ref().expect("checked above");
            spin.rotation(kinds, all.iter().map(|r| r.angular).collect())
        };
        self.records = Records::Rough(records);
        self.rotation = Some(rotation);
        self.rotation.as_ref()
    }

    /// Rough particles: the section `rotation` (contacts that slid, all ranks); empty for
    /// smooth ones.
    pub(super) fn rough_report(&self) -> Report {
        Report {
            sections: self
                .spin
                .as_ref()
                .map(|spin| {
                    let r = Rotation {
                        inertia: Vec::new(),
                        angular: Vec::new(),
                        sliding: spin.sliding,
                    };
                    r.report(self.tally.collisions)
                })
                .into_iter()
                .collect(),
        }
    }
}
