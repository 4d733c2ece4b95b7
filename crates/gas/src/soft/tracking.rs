//! The particles' tracks in soft-sphere MD: the periodic images each has crossed into,
//! counted after every step from its position before and after (a step moves a sphere less
//! than its radius: `SoftSphere::restore` refuses states that would not), for the
//! displacements of the mean-square displacement. Under shear the flow carries spheres
//! along x and the faces move them by the images' offset: not tracked there.

use super::SoftSphere;
use crate::error::Result;
use crate::system::Vector;
use crate::tail::Tracks;

impl<const D: usize> SoftSphere<D> {
    /// Tracks the displacements from now on (`true`; kept if tracked already), or stops.
    /// Fails under shear.
    pub fn set_tracking(&mut self, on: bool) -> Result<()> {
        if !on {
            self.tracks = None;
            self.tracked_positions = Vec::new();
            return Ok(());
        }
        if self.shear.is_some() {
            return Err(crate::tail::tracking_under_shear());
        }
        if self.tracks.is_none() {
            self.tracks = Some(Tracks::new(&self.system.positions));
        }
        self.tracked_positions = self.system.positions.clone();
        Ok(())
    }

    /// Each particle's displacement since tracking began; None if not tracked.
    pub fn displacements(&self) -> Option<Vec<Vector<D>>> {
        let tracks = self.tracks.as_ref()?;
        Some(tracks.displacements(&self.system.positions, &self.system.sides))
    }

    /// Counts the wraps of the step just taken (after every step while tracking).
    pub(super) fn follow_tracks(&mut self) {
        let Some(tracks) = self.tracks.as_mut() else {
            return;
        };
        let s = &self.system;
        // A step moves a sphere less than its radius: any axis may be counted (a wall's
        // axis finds no wrap).
        let periodic = [true; D];
        for (i, (last, now)) in self
            .tracked_positions
            .iter_mut()
            .zip(&s.positions)
            .enumerate()
        {
            tracks.follow(i, last, now, &s.sides, &periodic);
            *last = *now;
        }
    }
}
