//! The linear dash-pot: coefficient of restitution and collision duration in closed form.
//!
//! The force of the linear dash-pot, Eq. (9) of SP2008, is `F = k ξ + γ ξ̇`, so the
//! compression `ξ` obeys
//!
//! ```text
//! m_eff ξ̈ = −k ξ − γ ξ̇   ⇔   ξ̈ + 2β ξ̇ + ω0² ξ = 0,   ξ(0) = 0,  ξ̇(0) = v,
//! β = γ / (2 m_eff),   ω0 = √(k / m_eff).
//! ```
//!
//! Everything depends on the single dimensionless **damping ratio** `R = β / ω0`; the
//! coefficient of restitution `ε = −ξ̇(t_c) / v` does not depend on `v`. Two definitions of
//! the end of the collision `t_c` are supported ([`DashpotCriterion`]):
//!
//! * **Naive**, Eq. (7): `ξ(t_c) = 0`. For `R < 1` this gives Eq. (10),
//!   `ε = exp(−π R / √(1 − R²))`, `ω0 t_c = π / √(1 − R²)`. For `R ≥ 1` the compression
//!   never returns to zero: the particles never separate (dissipative capture), reported as
//!   `ε = 0`, `ω0 t_c = ∞`, `separated = false`.
//! * **Improved** (delayed recovery), Eq. (8): `F(t_c) = 0`, i.e. `ξ̈(t_c) = 0`. With
//!   `ω = √(ω0² − β²)` the trajectory is `ξ = (v/ω) e^{−βt} sin ωt`, and `ξ̈ = 0` gives
//!   `tan ωt_c = 2βω / (β² − ω²)` with `ωt_c ∈ (0, π)`, i.e. `ωt_c = atan2(2βω, β² − ω²)`,
//!   and then exactly `ε = exp(−β t_c)`. In the overdamped case (`ω = √(β² − ω0²)`)
//!   `ωt_c = ln((β + ω)/(β − ω))`, and at critical damping `t_c = 2/β`, `ε = e^{−2}`.
//!
//! All three regimes of the improved criterion are one analytic function of `R`:
//!
//! ```text
//! ω0 t_c = 2 arccos(R) / √(1 − R²)     (R < 1)
//!        = 2                           (R = 1)
//!        = 2 arcosh(R) / √(R² − 1)     (R > 1),        ε = exp(−R ω0 t_c),
//! ```
//!
//! which is what [`dashpot`] evaluates (with a power series in `1 − R²` near `R = 1`, so
//! there is no `0/0` and the result is smooth across `R = 1/√2` and `R = 1`).
//!
//! # The misprint in Eq. (12) of SP2008
//!
//! The middle branch of Eq. (12), for `β ∈ (ω0/√2, ω0)`, is printed as
//! `exp(−(β/ω) arctan(2βω / (ω² − β²)))`. In that range `ω² < β²`, so the arctangent is
//! *negative* and the printed expression gives `ε > 1` — an energy gain. The principal
//! branch of the arctangent was taken in the wrong half-plane: the root of `ξ̈ = 0` is
//! `ωt_c = atan2(2βω, β² − ω²) ∈ (0, π/2)` there, i.e. the correct middle branch is
//! `exp(−(β/ω) arctan(2βω / (β² − ω²)))`. (The first branch,
//! `π − arctan(2βω/(ω² − β²))`, is the same `atan2` value in the range `ω² > β²`, and the
//! third branch is correct.) [`dashpot`] implements the corrected, continuous form;
//! [`paper_eq12`] evaluates the formula exactly as printed, for comparison only.

use crate::error::{require_non_negative, require_positive, Error, Result};
use std::f64::consts::{FRAC_1_SQRT_2, LN_2, PI};

/// Which event ends the collision.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DashpotCriterion {
    /// The force vanishes, `F(t_c) = 0` (Eq. (8) of SP2008): delayed recovery, the particles
    /// lose contact before the compression has returned to zero. Always separates.
    Improved,
    /// The compression returns to zero, `ξ(t_c) = 0` (Eq. (7) of SP2008). Implies an
    /// attractive force at the end of the collision (Eq. (11)); never separates for `R ≥ 1`.
    Naive,
}

/// The result of one linear dash-pot collision, in terms of the damping ratio `R = β/ω0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DashpotOutcome {
    /// Coefficient of restitution `ε = −ξ̇(t_c)/v`, in `[0, 1]`; `0` if the particles never
    /// separate.
    pub eps: f64,
    /// Scaled collision duration `ω0 t_c`; `f64::INFINITY` if the particles never separate.
    pub scaled_duration: f64,
    /// `false` only for the naive criterion with `R ≥ 1` (dissipative capture).
    pub separated: bool,
}

/// Below this `|1 − R²|` the improved duration is evaluated from its power series.
const SERIES_THRESHOLD: f64 = 1e-3;
/// Number of terms of the series `Σ c_n u^n`; with `|u| < 1e-3` the remainder is < 1e-27.
const SERIES_TERMS: usize = 9;
/// Above this ratio `√(R² − 1) = R` and `arcosh R = ln 2R` to within `f64` rounding.
const LARGE_RATIO: f64 = 1e8;

/// Coefficient of restitution and scaled duration `ω0 t_c` of the linear dash-pot as a
/// function of the damping ratio `R = β/ω0 = γ / (2√(k m_eff))`.
///
/// * [`DashpotCriterion::Naive`]: Eq. (10) of SP2008, `ε = exp(−πR/√(1−R²))`,
///   `ω0 t_c = π/√(1−R²)` for `R < 1`; for `R ≥ 1` the particles never separate and the
///   outcome is `ε = 0`, `ω0 t_c = ∞`, `separated = false` (the "ε = 0" of the text after
///   Eq. (10)).
/// * [`DashpotCriterion::Improved`]: Eq. (12) of SP2008, with the middle branch corrected
///   (see the module documentation): `ω0 t_c = 2 arccos(R)/√(1−R²)` for `R < 1`, `2` at
///   `R = 1`, `2 arcosh(R)/√(R²−1)` for `R > 1`, and `ε = exp(−R ω0 t_c)`. Continuous (indeed
///   analytic) in `R`, including at `R = 1/√2` and `R = 1`.
///
/// `R = 0` (no damping) gives `ε = 1`, `ω0 t_c = π` for both criteria.
///
/// # Errors
/// [`Error::OutOfRange`] unless `ratio` is finite and `>= 0`.
pub fn dashpot(ratio: f64, criterion: DashpotCriterion) -> Result<DashpotOutcome> {
    let r = require_non_negative("damping ratio R", ratio)?;
    Ok(match criterion {
        DashpotCriterion::Naive => naive(r),
        DashpotCriterion::Improved => {
            let s = improved_scaled_duration(r);
            DashpotOutcome {
                eps: (-r * s).exp(),
                scaled_duration: s,
                separated: true,
            }
        }
    })
}

/// Eq. (10) of SP2008 (end of collision at `ξ = 0`, Eq. (7)).
fn naive(r: f64) -> DashpotOutcome {
    if r >= 1.0 {
        return DashpotOutcome {
            eps: 0.0,
            scaled_duration: f64::INFINITY,
            separated: false,
        };
    }
    // ω/ω0 = √(1 − R²), factored to stay accurate near R = 1.
    let w = ((1.0 - r) * (1.0 + r)).sqrt();
    let s = PI / w;
    DashpotOutcome {
        eps: (-r * s).exp(),
        scaled_duration: s,
        separated: true,
    }
}

/// `ω0 t_c` for the improved criterion (Eq. (8)): the first positive root of `ξ̈ = 0`.
///
/// Underdamped: `ω t_c = atan2(2βω, β² − ω²) = 2 atan2(ω, β)`, i.e.
/// `ω0 t_c = 2 atan2(√(1−R²), R)/√(1−R²)`. Overdamped: `ω t_c = ln((β+ω)/(β−ω)) = 2 ln(β+ω)`
/// (in units of ω0, since `β² − ω² = ω0²`), i.e. `ω0 t_c = 2 ln(R + √(R²−1))/√(R²−1)`.
/// Near `R = 1` both are the series `2 Σ c_n u^n` in `u = 1 − R²` with
/// `c_n = (2n)! / (4^n (n!)² (2n+1))` (the Taylor series of `arcsin(x)/x` in `x²`).
fn improved_scaled_duration(r: f64) -> f64 {
    let u = (1.0 - r) * (1.0 + r);
    if u.abs() < SERIES_THRESHOLD {
        let mut c = 1.0;
        let mut power = 1.0;
        let mut sum = 1.0;
        for n in 1..SERIES_TERMS {
            let k = n as f64;
            c *= (2.0 * k - 1.0) * (2.0 * k - 1.0) / (2.0 * k * (2.0 * k + 1.0));
            power *= u;
            sum += c * power;
        }
        2.0 * sum
    } else if u > 0.0 {
        let w = u.sqrt();
        2.0 * w.atan2(r) / w
    } else if r < LARGE_RATIO {
        let w = (-u).sqrt();
        // arcosh R = ln(1 + (R − 1) + √(R² − 1)), accurate also just above R = 1.
        2.0 * ((r - 1.0) + w).ln_1p() / w
    } else {
        2.0 * (r.ln() + LN_2) / r
    }
}

/// Eq. (12) of SP2008 evaluated **exactly as printed**, including the misprinted middle
/// branch — for comparison and documentation only; use [`dashpot`] for physics.
///
/// With `R = β/ω0` and `ω_n/ω0 = √|1 − R²|`:
///
/// * `R < 1/√2`: `exp[−(β/ω_n)(π − arctan(2βω_n/(ω_n² − β²)))]` — correct;
/// * `1/√2 ≤ R < 1`: `exp[−(β/ω_n) arctan(2βω_n/(ω_n² − β²))]` — **misprint**: the
///   arctangent is negative there and the result is `ε > 1`;
/// * `R > 1`: `exp[−(β/ω_n) ln((β+ω_n)/(β−ω_n))]` — correct.
///
/// # Errors
/// [`Error::OutOfRange`] unless `ratio` is finite, `>= 0` and `!= 1` (the printed formula
/// is `0/0` at `R = 1`).
pub fn paper_eq12(ratio: f64) -> Result<f64> {
    let r = require_non_negative("damping ratio R", ratio)?;
    if r == 1.0 {
        return Err(Error::out_of_range(
            "damping ratio R",
            r,
            "R != 1 (the printed Eq. (12) is 0/0 at critical damping)",
        ));
    }
    let w = (1.0 - r * r).abs().sqrt();
    let eps = if r < FRAC_1_SQRT_2 {
        (-(r / w) * (PI - (2.0 * r * w / (w * w - r * r)).atan())).exp()
    } else if r < 1.0 {
        (-(r / w) * (2.0 * r * w / (w * w - r * r)).atan()).exp()
    } else {
        (-(r / w) * ((r + w) / (r - w)).ln()).exp()
    };
    Ok(eps)
}

/// Damping ratio `R = β/ω0 = γ / (2√(k m_eff))` of the linear dash-pot `F = kξ + γξ̇`
/// (Eq. (9) of SP2008, with `β = γ/(2 m_eff)`, `ω0 = √(k/m_eff)` as below Eq. (10)).
///
/// # Errors
/// [`Error::OutOfRange`] unless `k > 0`, `m_eff > 0` and `gamma >= 0`, all finite.
pub fn damping_ratio(k: f64, gamma: f64, m_eff: f64) -> Result<f64> {
    let k = require_positive("spring constant k", k)?;
    let gamma = require_non_negative("damping constant gamma", gamma)?;
    let m_eff = require_positive("effective mass m_eff", m_eff)?;
    Ok(gamma / (2.0 * k.sqrt() * m_eff.sqrt()))
}

/// Physical collision duration `t_c = (ω0 t_c)/ω0` with `ω0 = √(k/m_eff)`, for the given
/// damping ratio and criterion (Eq. (10), or Eq. (12) corrected, of SP2008). Returns
/// `f64::INFINITY` when the particles never separate (naive criterion, `R ≥ 1`).
///
/// # Errors
/// [`Error::OutOfRange`] unless `ratio` is finite and `>= 0`, and `k`, `m_eff` are finite
/// and `> 0`.
pub fn duration(ratio: f64, criterion: DashpotCriterion, k: f64, m_eff: f64) -> Result<f64> {
    let k = require_positive("spring constant k", k)?;
    let m_eff = require_positive("effective mass m_eff", m_eff)?;
    let outcome = dashpot(ratio, criterion)?;
    Ok(outcome.scaled_duration * (m_eff / k).sqrt())
}

/// The two end-of-collision criteria are the same for every force law.
impl From<crate::exact::Criterion> for DashpotCriterion {
    fn from(c: crate::exact::Criterion) -> Self {
        match c {
            crate::exact::Criterion::Improved => DashpotCriterion::Improved,
            crate::exact::Criterion::Naive => DashpotCriterion::Naive,
        }
    }
}
