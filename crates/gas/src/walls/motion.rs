//! Vibrating walls: a wall that moves along its axis, displaced d(t) = A (1 + w(2 pi f t))
//! into the box from its face, and the first contact of a sphere's flight with it.
//!
//! The waveforms w start at their lowest, -1, so every wall is at the box's face at t = 0
//! and sweeps the layer [0, 2A] inside the box (cells and starts need no margin):
//! - sine: w = -cos(2 pi f t) (d = A (1 - cos 2 pi f t));
//! - triangle: w rises linearly from -1 to 1 over half a period and falls back (wall speed
//!   +-4 A f);
//! - sawtooth: w rises linearly from -1 to 1 over a period (wall speed 2 A f into the box),
//!   then the wall jumps back to the face (away from the gas: it can leave a sphere behind,
//!   never overlap one).

use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// The shape of a wall's motion over one period.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Waveform {
    Sine,
    Triangle,
    Sawtooth,
}

/// A wall's motion: d(t) = A (1 + w(2 pi f t)) into the box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    pub amplitude: f64,
    pub frequency: f64,
    pub waveform: Waveform,
}

impl Motion {
    /// The fraction of the period elapsed at t, in [0, 1).
    #[inline]
    fn phase(&self, t: f64) -> f64 {
        let p = (self.frequency * t).fract();
        if p < 0.0 {
            p + 1.0
        } else {
            p
        }
    }

    /// Displacement into the box at time t, in [0, 2A].
    pub fn displacement(&self, t: f64) -> f64 {
        let p = self.phase(t);
        let a = self.amplitude;
        match self.waveform {
            Waveform::Sine => a * (1.0 - (TAU * p).cos()),
            Waveform::Triangle => a * if p < 0.5 { 4.0 * p } else { 4.0 - 4.0 * p },
            Waveform::Sawtooth => 2.0 * a * p,
        }
    }

    /// Velocity into the box at time t (on a kink, the velocity after it).
    pub fn velocity(&self, t: f64) -> f64 {
        let p = self.phase(t);
        let (a, f) = (self.amplitude, self.frequency);
        match self.waveform {
            Waveform::Sine => a * TAU * f * (TAU * p).sin(),
            Waveform::Triangle => {
                if p < 0.5 {
                    4.0 * a * f
                } else {
                    -4.0 * a * f
                }
            }
            Waveform::Sawtooth => 2.0 * a * f,
        }
    }

    /// A bound on |acceleration| between kinks.
    pub fn max_acceleration(&self) -> f64 {
        match self.waveform {
            Waveform::Sine => self.amplitude * (TAU * self.frequency).powi(2),
            Waveform::Triangle | Waveform::Sawtooth => 0.0,
        }
    }

    /// The first kink (velocity jump, or the sawtooth's jump back) after t; infinity for
    /// the sine.
    pub fn next_kink(&self, t: f64) -> f64 {
        let period = 1.0 / self.frequency;
        let start = (self.frequency * t).floor() * period;
        match self.waveform {
            Waveform::Sine => f64::INFINITY,
            Waveform::Triangle => {
                let half = start + 0.5 * period;
                if half > t {
                    half
                } else {
                    start + period
                }
            }
            Waveform::Sawtooth => start + period,
        }
        .max(t)
    }

    /// The largest |velocity|.
    pub fn max_speed(&self) -> f64 {
        let (a, f) = (self.amplitude, self.frequency);
        match self.waveform {
            Waveform::Sine => a * TAU * f,
            Waveform::Triangle => 4.0 * a * f,
            Waveform::Sawtooth => 2.0 * a * f,
        }
    }
}

/// Iterations of [`first_contact`] before it returns an early check (a contact time at
/// which the sphere may not yet touch: the engine then only predicts again).
const MAX_STEPS: usize = 10_000;

/// The first time s in [0, horizon] at which a gap h(s) >= 0 closes with the gap
/// decreasing, where `gap(s)` gives (h, h') and |h''| <= `curvature` between the kinks of
/// `next_kink(s)` (the first kink after s: h' may jump there, h is continuous or jumps
/// up). Conservative advancement: from s, the gap is at least h + h' tau - K tau^2 / 2,
/// which stays positive up to its first root; no step passes a contact, so none is
/// missed, grazing ones included (the steps near a tangency shrink like the square root of
/// the gap). A gap within `tolerance` and closing is a contact. None if the gap stays open
/// up to `horizon`.
pub fn first_contact(
    gap: impl Fn(f64) -> (f64, f64),
    curvature: f64,
    next_kink: impl Fn(f64) -> f64,
    horizon: f64,
    tolerance: f64,
) -> Option<f64> {
    let mut s = 0.0;
    for _ in 0..MAX_STEPS {
        let (h, dh) = gap(s);
        if h <= tolerance && dh <= 0.0 {
            return Some(s);
        }
        let h = h.max(0.0);
        // The first root of h + dh tau - K tau^2 / 2, without cancellation.
        let tau = if curvature > 0.0 {
            let root = (dh * dh + 2.0 * curvature * h).sqrt();
            if dh >= 0.0 {
                (dh + root) / curvature
            } else {
                2.0 * h / (root - dh)
            }
        } else if dh < 0.0 {
            h / -dh
        } else {
            f64::INFINITY
        };
        let kink = next_kink(s);
        let next = s + tau;
        if next >= kink.min(horizon) {
            if kink >= horizon {
                return None;
            }
            // Past the kink the bound starts again from the new slope.
            s = if kink > s {
                kink
            } else {
                s + f64::EPSILON * s.max(1.0)
            };
            continue;
        }
        // Progress even when the step is below the resolution of s.
        s = if next > s {
            next
        } else {
            s + f64::EPSILON * s.max(1.0)
        };
    }
    Some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn motion(waveform: Waveform) -> Motion {
        Motion {
            amplitude: 0.1,
            frequency: 2.0,
            waveform,
        }
    }

    /// Oracle: the waveforms' closed forms, and velocity as the derivative of displacement
    /// (central differences, error O(dt^2)).
    #[test]
    fn waveforms_start_at_the_face_and_have_their_derivative() {
        for w in [Waveform::Sine, Waveform::Triangle, Waveform::Sawtooth] {
            let m = motion(w);
            assert_eq!(m.displacement(0.0), 0.0);
            for t in [0.01, 0.1, 0.2, 0.3, 0.37, 0.49] {
                let d = m.displacement(t);
                assert!((0.0..=0.2 + 1e-15).contains(&d), "{w:?} {t}: {d}");
                let h = 1e-6;
                let slope = (m.displacement(t + h) - m.displacement(t - h)) / (2.0 * h);
                assert!((slope - m.velocity(t)).abs() < 1e-6, "{w:?} {t}: {slope}");
                assert!(m.velocity(t).abs() <= m.max_speed() * (1.0 + 1e-12));
            }
        }
        assert!((motion(Waveform::Sine).displacement(0.25) - 0.2).abs() < 1e-15);
        assert!((motion(Waveform::Triangle).displacement(0.125) - 0.1).abs() < 1e-15);
        assert!((motion(Waveform::Sawtooth).displacement(0.375) - 0.15).abs() < 1e-15);
        assert_eq!(motion(Waveform::Triangle).next_kink(0.3), 0.5);
        assert_eq!(motion(Waveform::Sawtooth).next_kink(0.3), 0.5);
    }

    /// Oracle: a flight against a sine wall whose contact time is known in closed form, and
    /// a grazing flight (gap minimum 0 at a known time) found, a near miss (minimum
    /// 1e-9) not taken for a contact.
    #[test]
    fn first_contacts_are_found_and_never_passed() {
        // h(s) = 1 - s: linear, K = 0.
        let s = first_contact(|s| (1.0 - s, -1.0), 0.0, |_| f64::INFINITY, 5.0, 1e-14);
        assert_eq!(s, Some(1.0));
        // h(s) = cos(s) + 0.5 - ... : h = 1.5 - s - (1 - cos s) closes where
        // s + 1 - cos s = 1.5; K = 1.
        let gap = |s: f64| (1.5 - s - (1.0 - s.cos()), -1.0 - s.sin());
        let s = first_contact(gap, 1.0, |_| f64::INFINITY, 5.0, 1e-14).unwrap();
        assert!((s + 1.0 - s.cos() - 1.5).abs() < 1e-13, "{s}");
        // Grazing: h(s) = (s - 2)^2 / 2 touches 0 at s = 2 with h' = 0 there.
        let graze = |s: f64| (0.5 * (s - 2.0) * (s - 2.0), s - 2.0);
        let s = first_contact(graze, 1.0, |_| f64::INFINITY, 5.0, 1e-14).unwrap();
        assert!((s - 2.0).abs() < 1e-6, "{s}");
        // Near miss: minimum 1e-9 at s = 2.
        let miss = |s: f64| (0.5 * (s - 2.0) * (s - 2.0) + 1e-9, s - 2.0);
        assert_eq!(
            first_contact(miss, 1.0, |_| f64::INFINITY, 5.0, 1e-14),
            None
        );
        // Opening gap: none within the horizon.
        assert_eq!(
            first_contact(|s| (s, 1.0), 0.0, |_| f64::INFINITY, 5.0, 1e-14),
            None
        );
    }
}
