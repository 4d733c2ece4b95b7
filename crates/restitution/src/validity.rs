//! Where an approximate form of eps(v*) means what it claims: a Padé approximant up to its
//! first positive pole or the first v* where it leaves [0, 1]; a truncated series up to
//! the radius of convergence of the full series (and, within it, to where the truncation
//! leaves [0, 1]). The exact and fast laws hold at every v*.
//!
//! Zeros are found exactly for the stored coefficients (Sturm sequences,
//! `series::sturm::positive_real_roots`), so no crossing is missed between grid points.

use crate::law::ScaledForm;
use std::fmt;

/// The radius of convergence of eps = sum h_k v*^k, rounded down: the root test
/// max_{k-9..k} |h_k|^(-1/k) on the computed h_k gives 1.071 (k = 50), 1.070 (60),
/// 1.069 (80), 1.068 (100) (docs/collision-laws.md; test
/// `validity::series_radius_from_the_root_test`). Beyond it every truncation diverges
/// (Fig. 1 of MP2011).
pub const SERIES_RADIUS: f64 = 1.06;

/// Why a form stops being valid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Breakdown {
    /// A pole of the Padé approximant (eps -> +-inf).
    Pole,
    /// eps crosses 0.
    BelowZero,
    /// eps crosses 1 (more energy after the collision than before).
    AboveOne,
    /// The radius of convergence of the series.
    Divergence,
}

impl fmt::Display for Breakdown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Breakdown::Pole => "it has a pole there",
            Breakdown::BelowZero => "eps falls below 0 there",
            Breakdown::AboveOne => "eps rises above 1 there",
            Breakdown::Divergence => "the series diverges beyond its radius of convergence",
        })
    }
}

/// The range 0 <= v* < `below` where a form is valid; `breakdown` says what happens at
/// `below` (none: valid everywhere, `below` infinite).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Validity {
    pub below: f64,
    pub breakdown: Option<Breakdown>,
}

impl Validity {
    const EVERYWHERE: Validity = Validity {
        below: f64::INFINITY,
        breakdown: None,
    };

    /// Whether the form is valid at `vstar`.
    pub fn contains(&self, vstar: f64) -> bool {
        vstar < self.below
    }

    /// The first breakdown of `candidates` (a v* and its reason); a pole within 1e-6 of it
    /// (a pole-zero pair, where eps runs through every value) is named as the reason.
    fn first(candidates: impl IntoIterator<Item = (f64, Breakdown)>) -> Validity {
        let candidates: Vec<(f64, Breakdown)> = candidates.into_iter().collect();
        let Some(&(below, why)) = candidates.iter().min_by(|a, b| a.0.total_cmp(&b.0)) else {
            return Validity::EVERYWHERE;
        };
        let pole_nearby = candidates
            .iter()
            .any(|&(at, w)| w == Breakdown::Pole && at - below <= 1e-6 * below);
        Validity {
            below,
            breakdown: Some(if pole_nearby { Breakdown::Pole } else { why }),
        }
    }
}

impl fmt::Display for Validity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.breakdown {
            None => f.write_str("valid at every v*"),
            Some(why) => write!(f, "valid for v* < {:.6} only ({why})", self.below),
        }
    }
}

/// The first positive zero of the polynomial `c` (ascending), if any.
fn first_zero(c: &[f64]) -> Option<f64> {
    series::sturm::positive_real_roots_of_floats(c, f64::INFINITY)?
        .first()
        .copied()
}

/// `c` minus 1 (the polynomial whose zeros are where `c` equals 1).
fn minus_one(c: &[f64]) -> Vec<f64> {
    let mut d = c.to_vec();
    d[0] -= 1.0;
    d
}

/// `a - b`, coefficient by coefficient.
fn difference(a: &[f64], b: &[f64]) -> Vec<f64> {
    (0..a.len().max(b.len()))
        .map(|i| a.get(i).unwrap_or(&0.0) - b.get(i).unwrap_or(&0.0))
        .collect()
}

impl ScaledForm {
    /// Where this form of eps(v*) is valid (see the module documentation).
    pub fn validity(&self) -> Validity {
        match self {
            ScaledForm::Exact(_) | ScaledForm::Fast(_) => Validity::EVERYWHERE,
            ScaledForm::Pade(p) => {
                let (num, den) = (p.numerator(), p.denominator());
                Validity::first(
                    [
                        (first_zero(den), Breakdown::Pole),
                        (first_zero(num), Breakdown::BelowZero),
                        (first_zero(&difference(num, den)), Breakdown::AboveOne),
                    ]
                    .into_iter()
                    .filter_map(|(at, why)| Some((at?, why))),
                )
            }
            ScaledForm::Series(s) => {
                let h = s.coefficients();
                Validity::first(
                    [
                        (first_zero(h), Breakdown::BelowZero),
                        (first_zero(&minus_one(h)), Breakdown::AboveOne),
                        (Some(SERIES_RADIUS), Breakdown::Divergence),
                    ]
                    .into_iter()
                    .filter_map(|(at, why)| Some((at?, why))),
                )
            }
        }
    }
}
