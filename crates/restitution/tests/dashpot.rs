//! Tests of the linear dash-pot (`restitution::dashpot`) against an independent numerical
//! integration of the equation of motion, Eq. (9) of SP2008, with event location.
//!
//! The reference solver is classical RK4 with a fixed step `h`, the end-of-collision event
//! located inside the crossing step by bisection on the length of a partial RK4 step, and
//! Richardson extrapolation of the results at `h` and `h/2` (RK4 is fourth order). It uses
//! no closed form of the trajectory.

mod common;

use common::rel;

use restitution::dashpot::{
    damping_ratio, dashpot, duration, paper_eq12, DashpotCriterion, DashpotOutcome,
};
use restitution::Error;
use std::f64::consts::{FRAC_1_SQRT_2, PI};

use DashpotCriterion::{Improved, Naive};

// ---------------------------------------------------------------------------------------
// Independent reference: RK4 + event location + Richardson extrapolation.
// ---------------------------------------------------------------------------------------

/// `x'' = −a x − c x'`, `x(0) = 0`, `x'(0) = v` (physical form: `a = k/m_eff`,
/// `c = γ/m_eff`; scaled form: `a = 1`, `c = 2R`, `v = 1`).
#[derive(Clone, Copy)]
struct Oscillator {
    a: f64,
    c: f64,
    v: f64,
}

impl Oscillator {
    fn scaled(ratio: f64) -> Self {
        Oscillator {
            a: 1.0,
            c: 2.0 * ratio,
            v: 1.0,
        }
    }

    fn accel(&self, (x, p): (f64, f64)) -> f64 {
        -self.a * x - self.c * p
    }

    fn rk4(&self, y: (f64, f64), h: f64) -> (f64, f64) {
        let f = |(x, p): (f64, f64)| (p, self.accel((x, p)));
        let k1 = f(y);
        let k2 = f((y.0 + 0.5 * h * k1.0, y.1 + 0.5 * h * k1.1));
        let k3 = f((y.0 + 0.5 * h * k2.0, y.1 + 0.5 * h * k2.1));
        let k4 = f((y.0 + h * k3.0, y.1 + h * k3.1));
        (
            y.0 + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
            y.1 + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
        )
    }

    /// `true` once the end-of-collision event has happened: `x <= 0` (naive, Eq. (7)) or
    /// `x'' >= 0`, i.e. the force `k x + γ x'` no longer repulsive (improved, Eq. (8)).
    fn ended(&self, y: (f64, f64), criterion: DashpotCriterion) -> bool {
        match criterion {
            Naive => y.0 <= 0.0,
            Improved => self.accel(y) >= 0.0,
        }
    }

    /// First event time `t_c > 0` and `ε = −x'(t_c)/v`, with fixed step `h`, or `None` if
    /// there is no event before `t_max`. Grid points are `n h` (no accumulated rounding);
    /// the event is located in its step by bisection on a partial step to ~1e-16 relative.
    fn event(&self, criterion: DashpotCriterion, h: f64, t_max: f64) -> Option<(f64, f64)> {
        let mut y = (0.0, self.v);
        let mut n: u64 = 0;
        loop {
            let t = n as f64 * h;
            if t > t_max {
                return None;
            }
            let next = self.rk4(y, h);
            if self.ended(next, criterion) {
                let (mut lo, mut hi) = (0.0, h);
                for _ in 0..200 {
                    let mid = 0.5 * (lo + hi);
                    if mid <= lo || mid >= hi {
                        break;
                    }
                    if self.ended(self.rk4(y, mid), criterion) {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                let tau = 0.5 * (lo + hi);
                let at = self.rk4(y, tau);
                return Some((t + tau, -at.1 / self.v));
            }
            y = next;
            n += 1;
        }
    }

    /// Richardson extrapolation (order 4) of [`Self::event`] at `h` and `h/2`.
    fn event_extrapolated(&self, criterion: DashpotCriterion, h: f64) -> (f64, f64) {
        let (t1, e1) = self.event(criterion, h, 1e4).expect("event at step h");
        let (t2, e2) = self
            .event(criterion, 0.5 * h, 1e4)
            .expect("event at step h/2");
        (t2 + (t2 - t1) / 15.0, e2 + (e2 - e1) / 15.0)
    }
}

fn eval(ratio: f64, criterion: DashpotCriterion) -> DashpotOutcome {
    dashpot(ratio, criterion).expect("valid damping ratio")
}

const RATIOS: [f64; 22] = [
    0.0,
    0.01,
    0.05,
    0.3,
    0.6,
    0.7,
    FRAC_1_SQRT_2 - 1e-5,
    FRAC_1_SQRT_2,
    0.7072,
    0.75,
    0.9,
    0.99,
    0.999,
    0.9999,
    1.0,
    1.0001,
    1.001,
    1.01,
    1.5,
    3.0,
    10.0,
    30.0,
];

/// Step of the reference integration: resolves both `1/ω0` and the fast overdamped rate
/// `β + √(β² − ω0²) ≈ 2β`.
fn step_for(ratio: f64) -> f64 {
    1e-3 / (1.0 + 2.0 * ratio)
}

// ---------------------------------------------------------------------------------------
// Closed forms against the ODE.
// ---------------------------------------------------------------------------------------

/// Compares the closed form with the ODE at every ratio of `ratios`; returns the worst
/// relative error of t_c and eps.
fn check_against_ode(criterion: DashpotCriterion, ratios: impl Iterator<Item = f64>) -> f64 {
    let mut worst: f64 = 0.0;
    for r in ratios {
        let (t_ref, eps_ref) = Oscillator::scaled(r).event_extrapolated(criterion, step_for(r));
        let out = eval(r, criterion);
        assert!(out.separated);
        let (et, ee) = (rel(out.scaled_duration, t_ref), rel(out.eps, eps_ref));
        eprintln!(
            "{criterion:?} R = {r:<10} t_c = {:.15} (ode {t_ref:.15}, rel {et:.1e})  \
             eps = {:.15e} (ode {eps_ref:.15e}, rel {ee:.1e})",
            out.scaled_duration, out.eps
        );
        assert!(
            et <= 1e-9,
            "R = {r}: t_c {} vs ODE {t_ref}",
            out.scaled_duration
        );
        assert!(ee <= 1e-9, "R = {r}: eps {} vs ODE {eps_ref}", out.eps);
        worst = worst.max(et).max(ee);
    }
    worst
}

#[test]
fn improved_matches_ode_in_all_regimes() {
    let worst = check_against_ode(Improved, RATIOS.iter().copied());
    eprintln!("improved: max relative error vs ODE = {worst:.2e}");
}

#[test]
fn naive_matches_ode_when_underdamped() {
    let worst = check_against_ode(Naive, RATIOS.iter().copied().filter(|&r| r < 1.0));
    eprintln!("naive: max relative error vs ODE = {worst:.2e}");
}

#[test]
fn naive_never_separates_when_not_underdamped() {
    for &r in &[1.0, 1.001, 1.5, 3.0, 10.0, 1e6] {
        let out = eval(r, Naive);
        assert!(!out.separated, "R = {r}");
        assert_eq!(out.eps, 0.0);
        assert_eq!(out.scaled_duration, f64::INFINITY);
        assert!(!out.eps.is_nan() && !out.scaled_duration.is_nan());
    }
    // The ODE agrees: the compression stays positive (no ξ = 0 event) for a long time,
    // while the improved event (force = 0) does happen.
    for &r in &[1.0, 1.001, 1.5, 3.0, 10.0] {
        let osc = Oscillator::scaled(r);
        assert!(osc.event(Naive, step_for(r), 60.0).is_none(), "R = {r}");
        assert!(osc.event(Improved, step_for(r), 60.0).is_some(), "R = {r}");
    }
}

#[test]
fn physical_wrappers_match_ode_in_physical_units() {
    // m ξ'' = −k ξ − γ ξ', ξ(0) = 0, ξ'(0) = v, in physical units.
    let (k, m) = (3.0, 0.4);
    for &gamma in &[0.3, 1.2, 1.6, 2.5] {
        let r = damping_ratio(k, gamma, m).unwrap();
        assert!(rel(r, gamma / (2.0 * (k * m).sqrt())) < 1e-15);
        let osc = Oscillator {
            a: k / m,
            c: gamma / m,
            v: 2.5,
        };
        let h = 1e-3 / (k / m).sqrt() / (1.0 + 2.0 * r);
        let criteria: &[DashpotCriterion] = if r < 1.0 {
            &[Improved, Naive]
        } else {
            &[Improved]
        };
        for &criterion in criteria {
            let (t_ref, eps_ref) = osc.event_extrapolated(criterion, h);
            let t_c = duration(r, criterion, k, m).unwrap();
            let eps = eval(r, criterion).eps;
            assert!(
                rel(t_c, t_ref) < 1e-9,
                "gamma = {gamma} {criterion:?}: {t_c} vs {t_ref}"
            );
            assert!(
                rel(eps, eps_ref) < 1e-9,
                "gamma = {gamma} {criterion:?}: {eps} vs {eps_ref}"
            );
        }
    }
    assert_eq!(duration(2.0, Naive, k, m).unwrap(), f64::INFINITY);
    assert!(rel(damping_ratio(4.0, 2.0, 1.0).unwrap(), 0.5) < 1e-15);
    assert!(rel(duration(0.0, Improved, 4.0, 1.0).unwrap(), PI / 2.0) < 1e-15);
}

// ---------------------------------------------------------------------------------------
// Known values, limits, continuity, ordering.
// ---------------------------------------------------------------------------------------

#[test]
fn known_values() {
    for criterion in [Improved, Naive] {
        let out = eval(0.0, criterion);
        assert_eq!(out.eps, 1.0);
        assert!(rel(out.scaled_duration, PI) < 1e-15);
        assert!(out.separated);
    }
    // Critical damping: t_c = 2/β, ε = e^{-2}.
    let crit = eval(1.0, Improved);
    assert!(rel(crit.scaled_duration, 2.0) < 1e-15);
    assert!(rel(crit.eps, (-2.0f64).exp()) < 1e-15);
    // R = 1/√2: ω = β, ω t_c = π/2, so ω0 t_c = π/√2 and ε = e^{-π/2}.
    let mid = eval(FRAC_1_SQRT_2, Improved);
    assert!(rel(mid.scaled_duration, PI * FRAC_1_SQRT_2) < 1e-14);
    assert!(rel(mid.eps, (-PI / 2.0).exp()) < 1e-14);
    let mid_naive = eval(FRAC_1_SQRT_2, Naive);
    assert!(rel(mid_naive.eps, (-PI).exp()) < 1e-14);
    // Strong damping: ω0 t_c = 2 arcosh(R)/√(R²−1) → 2 ln(2R)/R and ε → 1/(4R²).
    for &r in &[1e9, 1e12, 1e100] {
        let out = eval(r, Improved);
        assert!(
            rel(out.scaled_duration, 2.0 * (2.0 * r).ln() / r) < 1e-14,
            "R = {r}"
        );
        assert!(out.separated && out.eps.is_finite() && out.eps >= 0.0);
    }
    assert!(rel(eval(1e9, Improved).eps, 0.25e-18) < 1e-12);
    let huge = eval(f64::MAX, Improved);
    assert!(huge.scaled_duration.is_finite() && huge.scaled_duration > 0.0);
    assert!(huge.eps == 0.0);
}

#[test]
fn naive_closed_form_and_limits() {
    for i in 0..1000 {
        let r = i as f64 / 1000.0;
        let out = eval(r, Naive);
        let exponent = PI * r / (1.0 - r * r).sqrt();
        let expected = (-exponent).exp();
        // `1 − r·r` in the reference loses ~ulp/(1 − R²) relative; ε amplifies it by the
        // exponent.
        let tol = 4e-16 * (1.0 + (1.0 + exponent) / (1.0 - r * r));
        assert!(rel(out.eps, expected) < tol, "R = {r}");
        assert!(
            rel(out.scaled_duration, PI / (1.0 - r * r).sqrt()) < tol,
            "R = {r}"
        );
    }
    // Weak damping: ε = 1 − πR + O(R²).
    let r = 1e-9;
    assert!((eval(r, Naive).eps - (1.0 - PI * r)).abs() < 1e-16);
    assert!((eval(r, Improved).eps - (1.0 - PI * r)).abs() < 1e-16);
    // R → 1⁻: ε → 0 and t_c → ∞, without NaN.
    let below = f64::from_bits(1.0f64.to_bits() - 1);
    let out = eval(below, Naive);
    assert!(out.separated && out.eps >= 0.0 && out.eps < 1e-300);
    assert!(out.scaled_duration.is_finite() && out.scaled_duration > 1e7);
}

/// Neighbouring `f64` values around `x`.
fn neighbours(x: f64) -> [f64; 2] {
    [
        f64::from_bits(x.to_bits() - 1),
        f64::from_bits(x.to_bits() + 1),
    ]
}

#[test]
fn improved_is_continuous_at_branch_points() {
    let e = |r: f64| eval(r, Improved);
    for &r0 in &[FRAC_1_SQRT_2, 1.0] {
        let centre = e(r0);
        for &d in &[1e-15, 1e-12, 1e-9, 1e-6, 1e-4] {
            for r in [r0 - d, r0 + d] {
                let out = e(r);
                // |dε/dR| and |d(ω0 t_c)/dR| are O(1) here.
                assert!((out.eps - centre.eps).abs() < 2.0 * d + 1e-15, "R = {r}");
                assert!(
                    (out.scaled_duration - centre.scaled_duration).abs() < 4.0 * d + 1e-15,
                    "R = {r}"
                );
            }
        }
        for r in neighbours(r0) {
            assert!((e(r).eps - centre.eps).abs() < 1e-15);
        }
    }
    // The switch between closed form and series near R = 1 (|1 − R²| = 1e-3) is seamless.
    for u in [1e-3f64, -1e-3] {
        let r0 = (1.0 - u).sqrt();
        let mut r = f64::from_bits(r0.to_bits() - 8);
        let mut prev = e(r);
        for _ in 0..16 {
            r = f64::from_bits(r.to_bits() + 1);
            let out = e(r);
            // Neighbouring R change ω0 t_c by ~1e-16: only rounding (a few ulps) remains.
            assert!(
                rel(out.scaled_duration, prev.scaled_duration) < 1e-15,
                "R = {r}"
            );
            assert!(rel(out.eps, prev.eps) < 1e-15, "R = {r}");
            prev = out;
        }
    }
}

#[test]
fn improved_is_smooth_and_monotone() {
    // On a fine grid across both branch points: ε strictly decreasing, ω0 t_c strictly
    // decreasing, and second differences bounded (|ε''| ≤ π² + 4 at R = 0 and smaller
    // elsewhere), which rules out jumps above ~1e-7 and kinks above ~1e-3.
    let n = 40_000;
    let dr = 4.0 / n as f64;
    let values: Vec<DashpotOutcome> = (0..=n).map(|i| eval(i as f64 * dr, Improved)).collect();
    for w in values.windows(2) {
        assert!(w[1].eps < w[0].eps);
        assert!(w[1].scaled_duration < w[0].scaled_duration);
    }
    for (i, w) in values.windows(3).enumerate() {
        let d2 = (w[2].eps - 2.0 * w[1].eps + w[0].eps) / (dr * dr);
        let d2t =
            (w[2].scaled_duration - 2.0 * w[1].scaled_duration + w[0].scaled_duration) / (dr * dr);
        assert!(
            d2.abs() < 20.0 && d2t.abs() < 20.0,
            "R = {}",
            (i + 1) as f64 * dr
        );
    }
}

#[test]
fn delayed_recovery_raises_eps_and_shortens_contact() {
    for i in 1..=3000 {
        let r = i as f64 / 1000.0;
        let (imp, nai) = (eval(r, Improved), eval(r, Naive));
        assert!(imp.eps > nai.eps, "R = {r}: {} <= {}", imp.eps, nai.eps);
        assert!(imp.scaled_duration < nai.scaled_duration, "R = {r}");
        assert!(imp.eps > 0.0 && imp.eps < 1.0);
        assert!((0.0..1.0).contains(&nai.eps));
    }
}

// ---------------------------------------------------------------------------------------
// The misprint of Eq. (12) of SP2008.
// ---------------------------------------------------------------------------------------

#[test]
fn printed_middle_branch_of_eq12_is_a_misprint() {
    // In (1/√2, 1) the printed formula gives ε > 1 (energy gain) — impossible — while the
    // corrected formula, confirmed by the ODE above, gives ε < 1.
    for &r in &[0.7072, 0.75, 0.8, 0.9, 0.99, 0.999] {
        let printed = paper_eq12(r).unwrap();
        let corrected = eval(r, Improved).eps;
        assert!(printed > 1.0, "R = {r}: printed {printed}");
        assert!(corrected < 1.0);
        // Printed middle branch = 1/corrected, since it flips the sign of the arctangent.
        assert!(rel(printed, 1.0 / corrected) < 1e-12, "R = {r}");
    }
    // Outside that interval the printed branches are right.
    for &r in &[
        0.0,
        0.05,
        0.3,
        0.6,
        0.7,
        FRAC_1_SQRT_2 - 1e-5,
        1.001,
        1.5,
        3.0,
        10.0,
    ] {
        let printed = paper_eq12(r).unwrap();
        assert!(rel(printed, eval(r, Improved).eps) < 1e-12, "R = {r}");
    }
    // 0/0 at R = 1.
    assert!(matches!(paper_eq12(1.0), Err(Error::OutOfRange { .. })));
}

// ---------------------------------------------------------------------------------------
// Validation.
// ---------------------------------------------------------------------------------------

#[test]
fn invalid_arguments_are_rejected() {
    for bad in [-1.0, -1e-300, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for criterion in [Improved, Naive] {
            assert!(
                matches!(dashpot(bad, criterion), Err(Error::OutOfRange { .. })),
                "R = {bad}"
            );
            assert!(duration(bad, criterion, 1.0, 1.0).is_err());
        }
        assert!(paper_eq12(bad).is_err());
    }
    assert!(duration(0.5, Improved, 0.0, 1.0).is_err());
    assert!(duration(0.5, Improved, 1.0, -1.0).is_err());
    assert!(duration(0.5, Improved, f64::NAN, 1.0).is_err());
    assert!(damping_ratio(0.0, 1.0, 1.0).is_err());
    assert!(damping_ratio(1.0, -1.0, 1.0).is_err());
    assert!(damping_ratio(1.0, 1.0, 0.0).is_err());
    assert!(damping_ratio(1.0, f64::INFINITY, 1.0).is_err());
    assert_eq!(damping_ratio(1.0, 0.0, 1.0).unwrap(), 0.0);
    let msg = dashpot(-2.0, Improved).unwrap_err().to_string();
    assert!(msg.contains("damping ratio") && msg.contains("-2"), "{msg}");
}
