//! The particles' tracks in the event-driven engine: the periodic images each has crossed
//! into (counted where its position is wrapped, `EventDriven::bring_to_now`), for the
//! displacements of the mean-square displacement. Under shear the flow carries spheres
//! along x and the faces move them by the images' offset: not tracked there.

use super::EventDriven;
use crate::error::Result;
use crate::system::Vector;
use crate::tail::Tracks;

impl<const D: usize> EventDriven<D> {
    /// Tracks the displacements from now on (`true`; kept if tracked already), or stops.
    /// Fails under shear.
    pub fn set_tracking(&mut self, on: bool) -> Result<()> {
        if !on {
            self.tracks = None;
            return Ok(());
        }
        if self.shear.is_some() {
            return Err(crate::tail::tracking_under_shear());
        }
        if self.tracks.is_none() {
            let now = self.box_positions();
            self.tracks = Some(Tracks::new(&now));
        }
        Ok(())
    }

    /// Each particle's displacement since tracking began; None if not tracked.
    pub fn displacements(&mut self) -> Option<Vec<Vector<D>>> {
        let tracks = self.tracks.as_ref()?;
        let now = self.box_positions();
        Some(tracks.displacements(&now, &self.system.sides))
    }

    /// Positions now, not wrapped since their last wrap (in the box's frame under gravity).
    fn box_positions(&self) -> Vec<Vector<D>> {
        (0..self.particles.len())
            .map(|i| self.in_box_now(i).0)
            .collect()
    }
}
