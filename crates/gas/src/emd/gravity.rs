//! Gravity in the event-driven engine: every sphere falls with the same acceleration g.
//!
//! The engine keeps each sphere in the frame that falls with g from the time
//! `reference` on: y = x − g τ²/2 and w = v − g τ with τ = t − reference. In that frame
//! every flight is a straight line, and the relative motion of two spheres is the same as
//! in the box (y_j − y_i = x_j − x_i, w_j − w_i = v_j − v_i at one instant), so the pair
//! predictions and the collision rule run unchanged: the periodic box's pair code is the
//! gravity's too. Only what refers to the box itself needs the box's frame: cell faces
//! and walls (crossings are roots of g s²/2 + v s + x − b, [`fall_exit`]), wall contacts
//! (the bounce acts on v), the state reported (`system`) and saved. The frame is moved
//! to the present when the offset g τ²/2 outgrows the box (rounding of y then stays that
//! of positions in the box) and at every synchronization (check-points then hold box
//! values exactly).

use super::EventDriven;
use crate::error::{Error, Result};
use crate::system::Vector;

/// The field of an engine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Field<const D: usize> {
    pub(super) g: Vector<D>,
    /// When the falling frame coincides with the box.
    pub(super) reference: f64,
    /// The frame moves to the present once τ exceeds this (g τ²/2 = L).
    pub(super) horizon: f64,
}

impl<const D: usize> Field<D> {
    /// Box position and velocity at time t of a sphere at y, w (falling frame, at t).
    #[inline]
    pub(super) fn to_box(self, y: &Vector<D>, w: &Vector<D>, t: f64) -> (Vector<D>, Vector<D>) {
        let tau = t - self.reference;
        (
            std::array::from_fn(|k| y[k] + 0.5 * self.g[k] * tau * tau),
            std::array::from_fn(|k| w[k] + self.g[k] * tau),
        )
    }

    /// The inverse of [`Self::to_box`].
    #[inline]
    pub(super) fn to_falling(self, x: &Vector<D>, v: &Vector<D>, t: f64) -> (Vector<D>, Vector<D>) {
        let tau = t - self.reference;
        (
            std::array::from_fn(|k| x[k] - 0.5 * self.g[k] * tau * tau),
            std::array::from_fn(|k| v[k] - self.g[k] * tau),
        )
    }
}

pub(super) use crate::walls::fall_exit;

impl<const D: usize> EventDriven<D> {
    /// Lets every sphere fall with the acceleration `g` (None: no field), a floor's
    /// contacts sending spheres off at least as fast as a bounce of `rest_height` needs
    /// (sqrt(2 |g_k| h), the resting rule of docs/walls.md), and predicts every event
    /// anew. Gravity needs walls on both sides of every axis it acts along (set
    /// [`Self::set_walls`] first) and no driving.
    pub fn set_gravity(&mut self, g: Option<Vector<D>>, rest_height: f64) -> Result<()> {
        self.synchronize();
        let Some(g) = g else {
            self.field = None;
            return Ok(());
        };
        if g.iter().all(|&x| x == 0.0) && rest_height.is_finite() {
            self.field = None;
            return Ok(());
        }
        if self.kicks.is_some() {
            return Err(Error::out_of_range(
                "gravity",
                format!("{g:?}"),
                "no gravity with driving",
            ));
        }
        crate::walls::fit_gravity(self.walls.as_mut(), &g, rest_height)?;
        let length = self.system.shortest_side();
        let largest = g.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        self.field = Some(Field {
            g,
            reference: self.time,
            horizon: (2.0 * length / largest).sqrt(),
        });
        self.synchronize();
        Ok(())
    }

    /// The acceleration of the spheres, if any.
    pub fn gravity(&self) -> Option<Vector<D>> {
        self.field.map(|f| f.g)
    }

    /// Box position and velocity of particle i now.
    #[inline]
    pub(super) fn in_box_now(&self, i: usize) -> (Vector<D>, Vector<D>) {
        let (y, w) = self.now(i);
        match &self.field {
            None => (y, w),
            Some(f) => f.to_box(&y, &w, self.time),
        }
    }

    /// Moves the falling frame to now (no event changes: they are absolute times, and
    /// the cells are the box's).
    pub(super) fn move_frame(&mut self) {
        let Some(field) = self.field else {
            return;
        };
        let moved = Field {
            reference: self.time,
            ..field
        };
        for p in &mut self.particles {
            let (x, v) = field.to_box(&p.position, &p.velocity, p.valid_at);
            (p.position, p.velocity) = moved.to_falling(&x, &v, p.valid_at);
        }
        self.field = Some(moved);
    }

    /// Moves the frame once the offset g τ²/2 outgrows the box.
    #[inline]
    pub(super) fn keep_frame_near(&mut self) {
        if let Some(f) = &self.field {
            if self.time - f.reference > f.horizon {
                self.move_frame();
            }
        }
    }
}
