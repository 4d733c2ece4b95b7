//! The ranges of the arguments that the `haff` command and the Python bindings both accept,
//! written once, next to the quantity they bound. A [`Range`] names the quantity and its
//! bounds; [`Range::describe`] is the wording the command prints after `allowed:`.
//!
//! This crate's ranges are those of one collision ([`BETA`], [`VSTAR`]); the rods crate
//! keeps Giese's (`rods::ranges`) with the same type.

use crate::exact::VSTAR_MAX;

/// The values an argument accepts: `low ..= high` (or `low .. high` exclusive of both ends,
/// [`Range::open`]), always finite, with the quantity's name for messages.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// The quantity as messages name it, e.g. `v*`.
    pub name: &'static str,
    /// Smallest value (excluded if [`Range::open`]).
    pub low: f64,
    /// Largest value (excluded if [`Range::open`]).
    pub high: f64,
    /// Whether both bounds are excluded.
    pub open: bool,
}

impl Range {
    /// The closed range `low <= name <= high`.
    pub const fn closed(name: &'static str, low: f64, high: f64) -> Self {
        Range {
            name,
            low,
            high,
            open: false,
        }
    }

    /// The open range `low < name < high`.
    pub const fn open(name: &'static str, low: f64, high: f64) -> Self {
        Range {
            name,
            low,
            high,
            open: true,
        }
    }

    /// Whether `x` is accepted (never NaN or an infinity).
    pub fn contains(&self, x: f64) -> bool {
        x.is_finite()
            && if self.open {
                self.low < x && x < self.high
            } else {
                self.low <= x && x <= self.high
            }
    }

    /// The range in words, as the command prints it after `allowed:`, e.g. `0 <= v* <= 1e6`
    /// or `0 < h kappa < 1` (bounds of magnitude 1e4 or more in exponent form).
    pub fn describe(&self) -> String {
        let sign = if self.open { "<" } else { "<=" };
        format!(
            "{} {sign} {} {sign} {}",
            bound(self.low),
            self.name,
            bound(self.high)
        )
    }
}

/// A bound for messages: `1e6` rather than `1000000`, `0.001` rather than `1e-3`, and the
/// exponent form below 1e-5 (the command's number format for smaller magnitudes).
fn bound(x: f64) -> String {
    let a = x.abs();
    if a >= 1e4 || (a < 1e-5 && x != 0.0) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// The beta (any unit system) of v* = beta^(1/2) v^(1/10) that `haff cor eps --beta` and
/// Python's `eps_v` accept: beyond it the speeds of v* <= 1e6, v <= (1e6 / beta^(1/2))^10,
/// underflow (or overflow) f64.
pub const BETA: Range = Range::closed("beta", 1e-30, 1e30);

/// The scaled impact speeds every law accepts, `0 <= v* <= VSTAR_MAX`.
pub const VSTAR: Range = Range::closed("v*", 0.0, VSTAR_MAX);

/// Every range of this module.
pub const ALL: [Range; 2] = [BETA, VSTAR];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_are_ordered_and_finite() {
        for r in ALL {
            assert!(
                r.low.is_finite() && r.high.is_finite() && r.low < r.high,
                "{r:?}"
            );
            assert_eq!(r.contains(r.low), !r.open, "{r:?}");
            assert_eq!(r.contains(r.high), !r.open, "{r:?}");
            assert!(r.contains(0.5 * (r.low + r.high)), "{r:?}");
        }
    }

    #[test]
    fn describe_gives_the_command_wording() {
        assert_eq!(BETA.describe(), "1e-30 <= beta <= 1e30");
        assert_eq!(VSTAR.describe(), "0 <= v* <= 1e6");
        assert_eq!(
            Range::open("h kappa", 0.0, 1.0).describe(),
            "0 < h kappa < 1"
        );
        assert_eq!(
            Range::closed("x", 1e-4, 1e3).describe(),
            "0.0001 <= x <= 1000"
        );
    }

    #[test]
    fn contains_rejects_nan_and_infinities() {
        let r = Range::closed("x", f64::MIN, f64::MAX);
        assert!(!r.contains(f64::NAN) && !r.contains(f64::INFINITY));
        assert!(!VSTAR.contains(-1e-300) && !VSTAR.contains(VSTAR_MAX * 1.000001));
        let open = Range::open("x", 0.0, 1.0);
        assert!(!open.contains(0.0) && !open.contains(1.0) && open.contains(0.25));
    }
}
