//! The exact coefficient of restitution of viscoelastic spheres, by integrating the scaled
//! collision equation, Eq. (9) of MP2011,
//!
//! ```text
//! x'' + x^{3/2} + v*^2 x' sqrt(x) = 0,   x(0) = 0,  x'(0) = 1,
//! ```
//!
//! with either end-of-collision criterion: the *improved* one, the force vanishes
//! (x'' = 0, Eq. (6) of MP2011 / Eq. (8) of SP2008), or the *naive* one, the overlap
//! vanishes (x = 0, Eq. (7) of SP2008). Then eps = -x'(tau_c) (Eq. 5 of MP2011).
//!
//! ## Numerical method
//! The right-hand side is not smooth at x = 0 (x''' diverges, Eq. (24) of SP2008), and for
//! large v* the collision becomes a stiff, overdamped creep. Three devices keep the result
//! at relative accuracy ~1e-12 for every v* from 0 to 1e4 and beyond:
//!
//! 1. **Two charts.** Near x = 0 the independent variable is w = sqrt(x), in which the
//!    equations `dp/dw = -2 w^2 (w^2 + A p)/p`, `dtau/dw = 2w/p` (A = v*^2, p = x') are
//!    analytic; near maximal compression (p -> 0) the independent variable is tau.
//! 2. **Rescaling.** For A > 1 compression and time are measured in units of A^(-2/3),
//!    the scale on which damping stops the particles, so that all state variables are O(1).
//! 3. **The force variable.** For A > 1 the velocity-like state is g = p + delta*X
//!    (proportional to the force), not p: near the end of a strongly damped collision
//!    p = -delta*X + g with |g| << |p|, and carrying g avoids the cancellation that would
//!    otherwise destroy eps ~ v*^(-10/3) (improved) or ~ v*^(-10) (naive).
//!
//! Two integrators work in these charts and units. [`solve`] uses a Taylor-series method of
//! order 24 ([`crate::taylor`]), which ends overdamped naive collisions on the slow manifold
//! in closed form ([`crate::manifold`]): ~15-45 steps, a few microseconds, within 3e-15 of
//! the independent reference of the tests. [`solve_radau`] (and [`trajectory`]) use the
//! L-stable Radau IIA method of [`crate::ode`], with events (maximal compression, zero
//! force, chart switches) located to full accuracy: the independent cross-check, ~50x
//! slower, within 1.6e-13 of the reference.

use crate::error::{require_non_negative, Error, Result};
use crate::ode::{EventFn, Radau5, State, Stop, System};
use std::fmt;
use std::str::FromStr;

/// The end-of-collision criterion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Criterion {
    /// The collision ends when the force vanishes (Eq. 8 of SP2008): delayed recovery.
    Improved,
    /// The collision ends when the overlap vanishes (Eq. 7 of SP2008).
    Naive,
}

impl FromStr for Criterion {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "improved" => Ok(Criterion::Improved),
            "naive" => Ok(Criterion::Naive),
            other => Err(Error::parse(
                "criterion",
                format!("'{other}' (allowed: improved, naive)"),
            )),
        }
    }
}

impl fmt::Display for Criterion {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Criterion::Improved => "improved",
            Criterion::Naive => "naive",
        })
    }
}

/// Largest v* accepted: beyond it eps of the naive criterion underflows f64.
pub const VSTAR_MAX: f64 = 1e6;

/// Default relative tolerance per step of the integrator.
pub const DEFAULT_RTOL: f64 = 1e-12;

/// The outcome of one collision in the scaled units of Eq. (9) of MP2011: compression in
/// units of (rho/m_eff)^(-2/5) v^(4/5), time in units of (rho/m_eff)^(-2/5) v^(-1/5).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Collision {
    pub vstar: f64,
    pub criterion: Criterion,
    /// Coefficient of restitution, -x'(tau_c).
    pub eps: f64,
    /// Scaled duration tau_c.
    pub duration: f64,
    /// Scaled maximal compression x_max.
    pub max_compression: f64,
    /// Scaled time of maximal compression.
    pub time_of_max_compression: f64,
    /// Scaled compression when the collision ends (> 0 for the improved criterion).
    pub compression_at_end: f64,
    /// Whether the particles separate. Always true for viscoelastic spheres (they creep
    /// apart even when overdamped); kept so that callers can test it.
    pub separated: bool,
}

/// One point of the scaled trajectory (Fig. 3 of SP2008).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TrajectoryPoint {
    pub tau: f64,
    pub x: f64,
    pub xdot: f64,
    pub xddot: f64,
}

/// Units and state variable chosen for a given v* (see the module documentation).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Scaling {
    /// A = v*^2, the damping parameter of Eq. (9).
    pub(crate) damping: f64,
    /// Length and time unit a: x = a X, tau = a T (velocities are unscaled).
    pub(crate) unit: f64,
    /// Coefficients of X'' + c_el X^{3/2} + c_d X' sqrt(X) = 0.
    pub(crate) c_el: f64,
    pub(crate) c_d: f64,
    /// delta = c_el / c_d: the force vanishes where X' = -delta X.
    pub(crate) delta: f64,
    /// Whether the second state variable is g = p + delta X (else p).
    pub(crate) force_form: bool,
}

impl Scaling {
    pub(crate) fn new(vstar: f64) -> Self {
        let damping = vstar * vstar;
        if damping <= 1.0 {
            Scaling {
                damping,
                unit: 1.0,
                c_el: 1.0,
                c_d: damping,
                delta: 1.0 / damping,
                force_form: false,
            }
        } else {
            let unit = damping.powf(-2.0 / 3.0);
            let c_el = damping.powf(-5.0 / 3.0);
            Scaling {
                damping,
                unit,
                c_el,
                c_d: 1.0,
                delta: c_el,
                force_form: true,
            }
        }
    }

    /// Velocity p = X' from compression X and the state variable v.
    pub(crate) fn velocity(&self, x: f64, v: f64) -> f64 {
        if self.force_form {
            v - self.delta * x
        } else {
            v
        }
    }

    /// A quantity with the sign of the repulsive force: zero at the improved end.
    fn force_sign(&self, x: f64, v: f64) -> f64 {
        if self.force_form {
            v
        } else {
            self.c_el * x + self.c_d * v
        }
    }
}

/// The tau chart: state (X, v), independent variable T.
struct TimeChart(Scaling);

impl System for TimeChart {
    fn rhs(&self, _t: f64, y: State) -> State {
        let s = &self.0;
        let sx = y[0].max(0.0).sqrt();
        if s.force_form {
            let p = y[1] - s.delta * y[0];
            [p, -s.c_d * sx * y[1] + s.delta * p]
        } else {
            [y[1], -sx * (s.c_el * y[0] + s.c_d * y[1])]
        }
    }

    fn jacobian(&self, _t: f64, y: State) -> [[f64; 2]; 2] {
        let s = &self.0;
        let sx = y[0].max(1e-300).sqrt();
        if s.force_form {
            [
                [-s.delta, 1.0],
                [
                    -s.c_d * y[1] / (2.0 * sx) - s.delta * s.delta,
                    -s.c_d * sx + s.delta,
                ],
            ]
        } else {
            [
                [0.0, 1.0],
                [
                    -(s.c_el * y[0] + s.c_d * y[1]) / (2.0 * sx) - s.c_el * sx,
                    -s.c_d * sx,
                ],
            ]
        }
    }
}

/// The w = sqrt(X) chart: state (v, T), independent variable w.
struct RootChart(Scaling);

impl System for RootChart {
    fn rhs(&self, w: f64, y: State) -> State {
        let s = &self.0;
        let w2 = w * w;
        let p = s.velocity(w2, y[0]);
        let dv = if s.force_form {
            -2.0 * s.c_d * w2 * y[0] / p + 2.0 * s.delta * w
        } else {
            -2.0 * w2 * (s.c_el * w2 + s.c_d * p) / p
        };
        [dv, 2.0 * w / p]
    }

    fn jacobian(&self, w: f64, y: State) -> [[f64; 2]; 2] {
        let s = &self.0;
        let w2 = w * w;
        let p = s.velocity(w2, y[0]);
        let d = if s.force_form {
            2.0 * s.c_d * s.delta * w2 * w2 / (p * p)
        } else {
            2.0 * s.c_el * w2 * w2 / (p * p)
        };
        [[d, 0.0], [-2.0 * w / (p * p), 0.0]]
    }
}

/// Uniform samples of the trajectory taken while integrating.
struct Sampler {
    targets: Vec<f64>,
    next: usize,
    points: Vec<TrajectoryPoint>,
}

impl Sampler {
    fn none() -> Self {
        Sampler {
            targets: Vec::new(),
            next: 0,
            points: Vec::new(),
        }
    }
    fn target(&self) -> Option<f64> {
        self.targets.get(self.next).copied()
    }
}

/// Which chart a phase runs in: decides how to read tau and X from (t, y).
#[derive(Clone, Copy)]
enum Chart {
    Time,
    Root,
}

struct Solver {
    s: Scaling,
    rk: Radau5,
}

impl Solver {
    fn new(vstar: f64, rtol: f64) -> Self {
        Solver {
            s: Scaling::new(vstar),
            rk: Radau5::new(rtol),
        }
    }

    /// (tau, X, v) at a point of a chart.
    fn point(&self, chart: Chart, t: f64, y: State) -> (f64, f64, f64) {
        match chart {
            Chart::Time => (self.s.unit * t, y[0], y[1]),
            Chart::Root => (self.s.unit * y[1], t * t, y[0]),
        }
    }

    fn record(&self, chart: Chart, t: f64, y: State) -> TrajectoryPoint {
        let (tau, x, v) = self.point(chart, t, y);
        let s = &self.s;
        let p = s.velocity(x, v);
        let xs = s.unit * x;
        TrajectoryPoint {
            tau,
            x: xs,
            xdot: p,
            xddot: -xs.max(0.0).sqrt() * (xs + s.damping * p),
        }
    }

    /// Integrates one phase, taking trajectory samples on the way; stops at `t_end` or at
    /// the first of `events`.
    #[allow(clippy::too_many_arguments)]
    fn phase(
        &mut self,
        chart: Chart,
        t0: f64,
        y0: State,
        t_end: f64,
        h0: f64,
        events: &[EventFn<'_>],
        soft: &[EventFn<'_>],
        sampler: &mut Sampler,
    ) -> Result<Stop> {
        let (mut t, mut y) = (t0, y0);
        let mut h0 = h0;
        let soft_at_start: Vec<f64> = soft.iter().map(|g| g(t0, y0)).collect();
        loop {
            let unit = self.s.unit;
            let clock = |t: f64, y: State| -> f64 {
                match chart {
                    Chart::Time => unit * t,
                    Chart::Root => unit * y[1],
                }
            };
            let stop = match sampler.target() {
                Some(target) => {
                    let sample = move |t: f64, y: State| clock(t, y) - target;
                    let mut all: Vec<EventFn<'_>> = events.to_vec();
                    all.push(&sample);
                    let sys_stop = self.run(chart, t, y, t_end, h0, &all, soft)?;
                    if sys_stop.event == Some(events.len()) {
                        sampler
                            .points
                            .push(self.record(chart, sys_stop.t, sys_stop.y));
                        sampler.next += 1;
                        t = sys_stop.t;
                        y = sys_stop.y;
                        h0 = self.rk.next_step.max(1e-300);
                        // A soft event passed in the step cut short by the sample ends the
                        // phase here (a restart would take the passed state as its start).
                        let passed = soft
                            .iter()
                            .zip(&soft_at_start)
                            .position(|(g, &g0)| (g(t, y) > 0.0) != (g0 > 0.0));
                        if let Some(k) = passed {
                            return Ok(Stop {
                                t,
                                y,
                                event: Some(events.len() + k),
                            });
                        }
                        continue;
                    }
                    sys_stop
                }
                None => self.run(chart, t, y, t_end, h0, events, soft)?,
            };
            return Ok(stop);
        }
    }

    /// Integrates in a chart; a soft event k is reported as `events.len() + k`.
    #[allow(clippy::too_many_arguments)]
    fn run(
        &mut self,
        chart: Chart,
        t: f64,
        y: State,
        t_end: f64,
        h0: f64,
        events: &[EventFn<'_>],
        soft: &[EventFn<'_>],
    ) -> Result<Stop> {
        let s = self.s;
        let out = match chart {
            Chart::Time => self
                .rk
                .integrate_until(&TimeChart(s), t, y, t_end, h0, events, soft),
            Chart::Root => self
                .rk
                .integrate_until(&RootChart(s), t, y, t_end, h0, events, soft),
        };
        out.map_err(|m| {
            Error::Numerical(format!(
                "collision at v* = {}: {m}",
                0.0f64.max(s.damping).sqrt()
            ))
        })
    }

    fn collide(
        &mut self,
        vstar: f64,
        criterion: Criterion,
        sampler: &mut Sampler,
    ) -> Result<Collision> {
        let s = self.s;
        // Without damping the force vanishes only with the overlap: both criteria coincide.
        let improved = criterion == Criterion::Improved && s.damping > 0.0;
        // Phase 1: compression from contact, in the root chart, until p = 1/2.
        let half_speed = |w: f64, y: State| s.velocity(w * w, y[0]) - 0.5;
        let stop = self.phase(
            Chart::Root,
            0.0,
            [1.0, 0.0],
            10.0,
            1e-2,
            &[],
            &[&half_speed],
            sampler,
        )?;
        expect_event(&stop, "p = 1/2 during compression")?;
        // Phase 2: through maximal compression in the time chart.
        let (t1, x1, v1) = (stop.y[1], stop.t * stop.t, stop.y[0]);
        let at_rest = |_t: f64, y: State| s.velocity(y[0], y[1]);
        // dtau = (2w/p) dw carries the step size across the chart change.
        let h = self.rk.next_step * 2.0 * stop.t / 0.5;
        let max = self.phase(
            Chart::Time,
            t1,
            [x1, v1],
            1e300,
            h,
            &[&at_rest],
            &[],
            sampler,
        )?;
        expect_event(&max, "maximal compression")?;
        let (x_max, t_max) = (max.y[0], max.t);
        // Phase 3: expansion in the time chart, until the force vanishes (improved) or the
        // compression has dropped enough for the root chart to take over.
        let zero_force = |_t: f64, y: State| s.force_sign(y[0], y[1]);
        let switch = |_t: f64, y: State| y[0] - 0.25 * x_max;
        let events: Vec<EventFn<'_>> = if improved { vec![&zero_force] } else { vec![] };
        let h = self.rk.next_step;
        let exp = self.phase(
            Chart::Time,
            t_max,
            max.y,
            1e300,
            h,
            &events,
            &[&switch],
            sampler,
        )?;
        expect_event(&exp, "expansion")?;
        let end = if improved && exp.event == Some(0) {
            (Chart::Time, exp.t, exp.y)
        } else {
            // Phase 4: the end of the expansion in the root chart, w decreasing to 0.
            let w = exp.y[0].sqrt();
            let zero_force_root = |w: f64, y: State| s.force_sign(w * w, y[0]);
            let events: Vec<EventFn<'_>> = if improved {
                vec![&zero_force_root]
            } else {
                vec![]
            };
            let p = s.velocity(exp.y[0], exp.y[1]).abs();
            let h = (self.rk.next_step * p / (2.0 * w)).min(0.5 * w);
            let fin = self.phase(
                Chart::Root,
                w,
                [exp.y[1], exp.t],
                0.0,
                h,
                &events,
                &[],
                sampler,
            )?;
            (Chart::Root, fin.t, fin.y)
        };
        let last = self.record(end.0, end.1, end.2);
        let (tau_c, x_end, v_end) = self.point(end.0, end.1, end.2);
        let p_end = s.velocity(x_end, v_end);
        // Dissipation makes eps <= 1 exact; keep integration error (~1e-13) from crossing it.
        let eps = (-p_end).min(1.0);
        sampler.points.push(last);
        Ok(Collision {
            vstar,
            criterion,
            eps,
            duration: tau_c,
            max_compression: s.unit * x_max,
            time_of_max_compression: s.unit * t_max,
            compression_at_end: s.unit * x_end.max(0.0),
            separated: true,
        })
    }
}

fn expect_event(stop: &Stop, what: &str) -> Result<()> {
    if stop.event.is_some() {
        Ok(())
    } else {
        Err(Error::Numerical(format!("{what} was not reached")))
    }
}

fn validate(vstar: f64) -> Result<f64> {
    require_non_negative("vstar", vstar)?;
    if vstar > VSTAR_MAX {
        return Err(Error::out_of_range("vstar", vstar, "0 <= vstar <= 1e6"));
    }
    Ok(vstar)
}

/// Solves one collision at scaled impact speed v* with the given criterion, by the Taylor
/// integrator of [`crate::taylor`] (and, for overdamped naive collisions, the slow-manifold
/// ending of [`crate::manifold`]); agrees with [`solve_radau`] to ~1e-13.
pub fn solve(vstar: f64, criterion: Criterion) -> Result<Collision> {
    let vstar = validate(vstar)?;
    crate::taylor::collide(vstar, criterion)
}

/// As [`solve`], by the Radau IIA integrator of this module at [`DEFAULT_RTOL`]: the
/// independent second method (~50x slower than [`solve`]).
pub fn solve_radau(vstar: f64, criterion: Criterion) -> Result<Collision> {
    solve_with_tolerance(vstar, criterion, DEFAULT_RTOL)
}

/// As [`solve_radau`], with an explicit relative tolerance per step (for convergence
/// studies).
pub fn solve_with_tolerance(vstar: f64, criterion: Criterion, rtol: f64) -> Result<Collision> {
    let vstar = validate(vstar)?;
    Solver::new(vstar, rtol).collide(vstar, criterion, &mut Sampler::none())
}

/// The collision and its trajectory sampled at `points` equidistant scaled times from 0 to
/// tau_c inclusive (Fig. 3 of SP2008).
pub fn trajectory(
    vstar: f64,
    criterion: Criterion,
    points: usize,
) -> Result<(Collision, Vec<TrajectoryPoint>)> {
    let vstar = validate(vstar)?;
    if points < 2 {
        return Err(Error::out_of_range("points", points, "an integer >= 2"));
    }
    // The sampled run below is a Radau run: its duration sets the sampling times.
    let collision = solve_radau(vstar, criterion)?;
    let n = points - 1;
    let targets = (1..n)
        .map(|k| collision.duration * k as f64 / n as f64)
        .collect();
    let mut sampler = Sampler {
        targets,
        next: 0,
        points: vec![TrajectoryPoint {
            tau: 0.0,
            x: 0.0,
            xdot: 1.0,
            xddot: 0.0,
        }],
    };
    // Stopping at the samples changes the steps, hence the result at the 1e-13 level:
    // report the collision of this run so that its last point is the end of collision.
    let sampled = Solver::new(vstar, DEFAULT_RTOL).collide(vstar, criterion, &mut sampler)?;
    Ok((sampled, sampler.points))
}
