//! The particles' tracks in spatial DSMC: the periodic images each has crossed into,
//! counted after each step's streaming from its position before it plus its flight v dt
//! (exact whatever the step: the flight is the streaming's own, up to gravity's g dt^2 / 2),
//! by the particle's identity (`Simulator::id`: the sorts into cells reorder the records).
//! Not under shear (the flow carries particles along x), not over several ranks
//! (identities stay on their rank).

use super::record::{each, Particle};
use super::SpatialDsmc;
use crate::error::{Error, Result};
use crate::system::Vector;
use crate::tail::Tracks;

impl<const D: usize> SpatialDsmc<D> {
    /// Tracks the displacements from now on (`true`; kept if tracked already), or stops.
    /// Fails under shear and over several ranks.
    pub fn set_tracking(&mut self, on: bool) -> Result<()> {
        if !on {
            self.tracks = None;
            self.tracked_positions = Vec::new();
            return Ok(());
        }
        if self.shear.is_some() {
            return Err(crate::tail::tracking_under_shear());
        }
        if self.comm.size() > 1 {
            return Err(Error::out_of_range(
                "tracking",
                format!("{} ranks", self.comm.size()),
                "one process (particles' identities stay on their rank)",
            ));
        }
        if self.records.len() > u32::MAX as usize {
            return Err(Error::out_of_range(
                "tracking",
                self.records.len(),
                "at most 2^32 - 1 particles",
            ));
        }
        let by_id = each!(&self.records, records => positions_by_id(records));
        if self.tracks.is_none() {
            self.tracks = Some(Tracks::new(&by_id));
        }
        self.tracked_positions = by_id;
        Ok(())
    }

    /// Each particle's displacement since tracking began, in the engine's current order
    /// (that of [`crate::Engine::system`]); None if not tracked.
    pub fn displacements(&self) -> Option<Vec<Vector<D>>> {
        let tracks = self.tracks.as_ref()?;
        let sides = &self.sides;
        let displacement = |p: &super::Simulator<D>| -> Vector<D> {
            let i = p.id as usize;
            std::array::from_fn(|k| {
                p.position[k] + tracks.images[D * i + k] as f64 * sides[k]
                    - tracks.origins[D * i + k]
            })
        };
        Some(each!(&self.records, records => records
            .iter()
            .map(|p| displacement(p.body()))
            .collect()))
    }

    /// Counts the wraps of the streaming of a step of `dt` just done (before its
    /// collisions change the velocities). Out of line: a step without tracks keeps its
    /// code as before they existed.
    #[inline(never)]
    pub(super) fn follow_tracks<R: Particle<D>>(&mut self, records: &[R], dt: f64) {
        let Some(tracks) = self.tracks.as_mut() else {
            return;
        };
        let periodic: [bool; D] =
            std::array::from_fn(|k| !self.walls.as_ref().is_some_and(|w| w.closed(k)));
        for p in records {
            let p = p.body();
            let i = p.id as usize;
            let last = &mut self.tracked_positions[i];
            let expected: Vector<D> = std::array::from_fn(|k| last[k] + dt * p.velocity[k]);
            tracks.follow(i, &expected, &p.position, &self.sides, &periodic);
            *last = p.position;
        }
    }

    /// The tracks in the records' current order, for a snapshot (a restored engine's
    /// identities are the records' places in it).
    pub(super) fn tracks_in_order(&self) -> Option<Tracks> {
        let tracks = self.tracks.as_ref()?;
        let mut ordered = Tracks {
            origins: Vec::with_capacity(tracks.origins.len()),
            images: Vec::with_capacity(tracks.images.len()),
        };
        each!(&self.records, records => for p in records {
            let i = D * p.body().id as usize;
            ordered.origins.extend_from_slice(&tracks.origins[i..i + D]);
            ordered.images.extend_from_slice(&tracks.images[i..i + D]);
        });
        Some(ordered)
    }
}

/// The positions of `records` indexed by the particles' identities.
fn positions_by_id<const D: usize, R: Particle<D>>(records: &[R]) -> Vec<Vector<D>> {
    let mut by_id = vec![[0.0; D]; records.len()];
    for p in records {
        by_id[p.body().id as usize] = p.body().position;
    }
    by_id
}
