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
use crate::walls::Side;

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
    pub(super) fn to_box(&self, y: &Vector<D>, w: &Vector<D>, t: f64) -> (Vector<D>, Vector<D>) {
        let tau = t - self.reference;
        (
            std::array::from_fn(|k| y[k] + 0.5 * self.g[k] * tau * tau),
            std::array::from_fn(|k| w[k] + self.g[k] * tau),
        )
    }

    /// The inverse of [`Self::to_box`].
    #[inline]
    pub(super) fn to_falling(
        &self,
        x: &Vector<D>,
        v: &Vector<D>,
        t: f64,
    ) -> (Vector<D>, Vector<D>) {
        let tau = t - self.reference;
        (
            std::array::from_fn(|k| x[k] - 0.5 * self.g[k] * tau * tau),
            std::array::from_fn(|k| v[k] - self.g[k] * tau),
        )
    }
}

/// The first time s > 0 at which a sphere at x moving with v along an axis with
/// acceleration g (≠ 0) reaches `low` or `high` (low <= x <= high, up to rounding), and
/// whether that is `high`. Cancellation-free roots of g s²/2 + v s + x − b = 0: against
/// the pull (a distance d, upward speed u > 0) s = 2 d / (u + sqrt(u² − 2 a d)) when
/// u² >= 2 a d (a = |g|), else along it (a distance e): s = (u + S) / a for u >= 0 and
/// s = 2 e / (S − u) for u < 0, S = sqrt(u² + 2 a e) (always a root).
pub(super) fn fall_exit(x: f64, v: f64, g: f64, low: f64, high: f64) -> (f64, bool) {
    let a = g.abs();
    // "Up" is against the pull.
    let (up_distance, down_distance, u) = if g < 0.0 {
        (high - x, x - low, v)
    } else {
        (x - low, high - x, -v)
    };
    let (d, e) = (up_distance.max(0.0), down_distance.max(0.0));
    let reach = u * u - 2.0 * a * d;
    if u > 0.0 && reach >= 0.0 {
        return (2.0 * d / (u + reach.sqrt()), g < 0.0);
    }
    let s = (u * u + 2.0 * a * e).sqrt();
    let time = if u >= 0.0 {
        (u + s) / a
    } else {
        2.0 * e / (s - u)
    };
    (time, g > 0.0)
}

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
        if g.iter().any(|x| !x.is_finite()) {
            return Err(Error::out_of_range(
                "gravity",
                format!("{g:?}"),
                "finite components",
            ));
        }
        if !(rest_height.is_finite() && rest_height >= 0.0) {
            return Err(Error::out_of_range(
                "rest_height",
                rest_height,
                "a finite height >= 0",
            ));
        }
        if g.iter().all(|&x| x == 0.0) {
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
        let Some(walls) = self.walls.as_mut() else {
            return Err(Error::out_of_range(
                "gravity",
                format!("{g:?}"),
                "components along axes closed by walls only",
            ));
        };
        if let Some(k) = (0..D).find(|&k| g[k] != 0.0 && !walls.closed(k)) {
            return Err(Error::out_of_range(
                "gravity",
                format!("{} along the periodic axis {k}", g[k]),
                "components along axes closed by walls only",
            ));
        }
        for k in (0..D).filter(|&k| g[k] != 0.0) {
            let floor = if g[k] < 0.0 { Side::Low } else { Side::High };
            if let Some(index) = walls.at(k, floor) {
                walls.set_min_speed(index, (2.0 * g[k].abs() * rest_height).sqrt());
            }
        }
        let length = self.system.length;
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

#[cfg(test)]
mod tests {
    use super::fall_exit;

    /// Oracle: the roots of the quadratic by the textbook formula, where it is accurate.
    #[test]
    fn fall_exits_are_the_quadratics_roots() {
        // Thrown up from 0.2 in [0, 1] at 1 with g = -1: reaches 1 if 1 >= 2 * 0.8? No:
        // falls back to 0 at s = 1 + sqrt(1 + 0.4).
        let (s, up) = fall_exit(0.2, 1.0, -1.0, 0.0, 1.0);
        assert!(!up && (s - (1.0 + 1.4f64.sqrt())).abs() < 1e-15, "{s}");
        // Fast enough: reaches 1 at the smaller root of s^2/2 - 2 s + 0.8 = 0.
        let (s, up) = fall_exit(0.2, 2.0, -1.0, 0.0, 1.0);
        assert!(
            up && (s - (2.0 - (4.0f64 - 1.6).sqrt())).abs() < 1e-15,
            "{s}"
        );
        // Falling: s^2/2 + 0.5 s - 0.2 = 0.
        let (s, up) = fall_exit(0.2, -0.5, -1.0, 0.0, 1.0);
        assert!(
            !up && (s - (-0.5 + (0.25f64 + 0.4).sqrt())).abs() < 1e-15,
            "{s}"
        );
        // Mirror: g > 0 pulls towards high.
        let (s, up) = fall_exit(0.8, -1.0, 1.0, 0.0, 1.0);
        assert!(up && (s - (1.0 + 1.4f64.sqrt())).abs() < 1e-15, "{s}");
        // Just crossed upwards at the face: back after 2 v / g.
        let (s, up) = fall_exit(0.0, 0.3, -2.0, 0.0, 1.0);
        assert!(!up && (s - 0.3).abs() < 1e-16, "{s}");
        // At rest on the low face: 0, downwards.
        assert_eq!(fall_exit(0.0, 0.0, -1.0, 0.0, 1.0), (0.0, false));
    }
}
