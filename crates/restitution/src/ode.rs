//! A stiff-capable, high-accuracy integrator for two-dimensional ODEs y' = f(t, y).
//!
//! The collision equations of this crate are tiny (two unknowns) but must be solved to
//! near machine precision over regimes that range from smooth to extremely stiff (the
//! overdamped creep of a strongly dissipative viscoelastic collision). We therefore use the
//! 3-stage Radau IIA collocation method (order 5, L-stable; Hairer & Wanner, *Solving ODEs II*,
//! Sec. IV.5) with full Newton iterations on the 6x6 stage system, step-size control by step
//! doubling, and event location by root-finding on the step size (every trial point is itself
//! an accurate step from the last accepted point, so an event is located to the accuracy of
//! the integration, without a low-order dense output).

/// The state of a two-dimensional system.
pub type State = [f64; 2];

/// A two-dimensional ODE with its Jacobian (needed by the implicit stages).
pub trait System {
    fn rhs(&self, t: f64, y: State) -> State;
    fn jacobian(&self, t: f64, y: State) -> [[f64; 2]; 2];
}

/// Radau IIA (s = 3) nodes c_i and coefficients a_ij; b_j = a_3j (stiffly accurate).
pub(crate) mod tableau {
    const S6: f64 = 2.449_489_742_783_178; // sqrt(6)
    pub const C: [f64; 3] = [(4.0 - S6) / 10.0, (4.0 + S6) / 10.0, 1.0];
    pub const A: [[f64; 3]; 3] = [
        [
            (88.0 - 7.0 * S6) / 360.0,
            (296.0 - 169.0 * S6) / 1800.0,
            (-2.0 + 3.0 * S6) / 225.0,
        ],
        [
            (296.0 + 169.0 * S6) / 1800.0,
            (88.0 + 7.0 * S6) / 360.0,
            (-2.0 - 3.0 * S6) / 225.0,
        ],
        [(16.0 - S6) / 36.0, (16.0 + S6) / 36.0, 1.0 / 9.0],
    ];
}

/// A scalar event function g(t, y); an event is a sign change of g across a step.
pub type EventFn<'a> = &'a dyn Fn(f64, State) -> f64;

/// Where an integration stopped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stop {
    pub t: f64,
    pub y: State,
    /// Index of the event that stopped the integration, `None` if `t_end` was reached.
    pub event: Option<usize>,
}

/// Why an integration stopped short of its end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum IntegrationFailure {
    /// The step size fell below what the time can resolve at `t`.
    StepUnderflow { t: f64 },
    /// More than `max` steps were needed.
    TooManySteps { max: usize },
    /// The start of an integration was not finite.
    NonFinite { t: f64 },
}

impl std::fmt::Display for IntegrationFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            IntegrationFailure::StepUnderflow { t } => {
                write!(f, "step size underflow at t = {t:e}")
            }
            IntegrationFailure::TooManySteps { max } => write!(f, "more than {max} steps"),
            IntegrationFailure::NonFinite { t } => write!(f, "non-finite state at t = {t:e}"),
        }
    }
}

impl std::error::Error for IntegrationFailure {}

/// Radau IIA integrator with relative error control.
#[derive(Debug, Clone)]
pub struct Radau5 {
    /// Relative tolerance per step.
    pub rtol: f64,
    /// Absolute floor of the error scale, per component.
    pub atol: State,
    /// Maximal number of accepted plus rejected steps per `integrate` call.
    pub max_steps: usize,
    /// Accepted steps so far (statistics).
    pub steps: usize,
    /// The step size proposed after the last accepted step (to restart efficiently).
    pub next_step: f64,
}

impl Radau5 {
    pub fn new(rtol: f64) -> Self {
        Radau5 {
            rtol,
            atol: [1e-300, 1e-300],
            max_steps: 200_000,
            steps: 0,
            next_step: 0.0,
        }
    }

    /// One Radau IIA step of size h from (t, y); `None` if the Newton iteration fails.
    ///
    /// Simplified Newton: the iteration matrix I - h (A ⊗ J_j) is factorized once, with
    /// the Jacobians at the initial stage guesses, and refreshed only when the iteration
    /// contracts slowly.
    pub fn step<S: System>(&self, sys: &S, t: f64, y: State, h: f64) -> Option<State> {
        use tableau::{A, C};
        let f0 = sys.rhs(t, y);
        let mut z = [[0.0; 2]; 3];
        for (zi, ci) in z.iter_mut().zip(C) {
            *zi = [ci * h * f0[0], ci * h * f0[1]];
        }
        let stage = |z: &[[f64; 2]; 3], j: usize| [y[0] + z[j][0], y[1] + z[j][1]];
        let newton_matrix = |z: &[[f64; 2]; 3]| {
            let jac: [[[f64; 2]; 2]; 3] =
                std::array::from_fn(|j| sys.jacobian(t + C[j] * h, stage(z, j)));
            let mut m = [[0.0; 6]; 6];
            for i in 0..3 {
                for k in 0..2 {
                    for j in 0..3 {
                        for l in 0..2 {
                            m[2 * i + k][2 * j + l] = -h * A[i][j] * jac[j][k][l];
                        }
                    }
                    m[2 * i + k][2 * i + k] += 1.0;
                }
            }
            Lu6::factor(m)
        };
        let mut lu = newton_matrix(&z)?;
        let mut last_norm = f64::INFINITY;
        for _ in 0..40 {
            let f: [State; 3] = std::array::from_fn(|j| sys.rhs(t + C[j] * h, stage(&z, j)));
            // Residual r = -(Z - h A F(Z)).
            let r: [f64; 6] = std::array::from_fn(|row| {
                let (i, k) = (row / 2, row % 2);
                -(z[i][k] - h * (0..3).map(|j| A[i][j] * f[j][k]).sum::<f64>())
            });
            let dz = lu.solve(r);
            let mut norm: f64 = 0.0;
            for i in 0..3 {
                for k in 0..2 {
                    z[i][k] += dz[2 * i + k];
                    let scale = self.atol[k].max(y[k].abs()).max((y[k] + z[i][k]).abs());
                    norm = norm.max(dz[2 * i + k].abs() / scale);
                }
            }
            if !norm.is_finite() {
                return None;
            }
            let done = [y[0] + z[2][0], y[1] + z[2][1]];
            if norm <= 1e-3 * self.rtol.min(1e-10) || norm == 0.0 {
                return Some(done);
            }
            // Stalled at round-off: accept if tiny.
            if norm >= last_norm && norm < 1e-13 {
                return Some(done);
            }
            if norm > 0.5 * last_norm {
                if norm > 2.0 * last_norm && last_norm < 1.0 {
                    return None;
                }
                lu = newton_matrix(&z)?;
            }
            last_norm = norm;
        }
        None
    }

    /// Step doubling: the result of two half steps and its estimated error norm (<= 1 is
    /// within tolerance). `None` if a Newton iteration failed.
    fn doubled_step<S: System>(&self, sys: &S, t: f64, y: State, h: f64) -> Option<(State, f64)> {
        let full = self.step(sys, t, y, h)?;
        let mid = self.step(sys, t, y, 0.5 * h)?;
        let half = self.step(sys, t + 0.5 * h, mid, 0.5 * h)?;
        let mut err: f64 = 0.0;
        for k in 0..2 {
            let scale = self.atol[k].max(y[k].abs()).max(half[k].abs());
            err = err.max((half[k] - full[k]).abs() / 31.0 / (self.rtol * scale));
        }
        // Local Richardson extrapolation: the two-half-step result plus its error estimate
        // is of order 6; the estimate above (of the unextrapolated result) stays pessimistic.
        let extrapolated = [
            half[0] + (half[0] - full[0]) / 31.0,
            half[1] + (half[1] - full[1]) / 31.0,
        ];
        err.is_finite().then_some((extrapolated, err))
    }

    /// Integrates from (t0, y0) towards `t_end` (either direction) starting with step `h0`
    /// (its sign is ignored), stopping at `t_end` or at the first sign change of an event,
    /// located to the accuracy of the integration.
    pub fn integrate<S: System>(
        &mut self,
        sys: &S,
        t0: f64,
        y0: State,
        t_end: f64,
        h0: f64,
        events: &[EventFn<'_>],
    ) -> Result<Stop, IntegrationFailure> {
        self.integrate_until(sys, t0, y0, t_end, h0, events, &[])
    }

    /// As [`Radau5::integrate`], with `soft` events in addition that are not located: the
    /// integration stops at the end of the first step after which one of them has changed
    /// sign, reported as event `events.len() + k`. For chart switches, where any point in
    /// the right region will do.
    #[allow(clippy::too_many_arguments)]
    pub fn integrate_until<S: System>(
        &mut self,
        sys: &S,
        t0: f64,
        y0: State,
        t_end: f64,
        h0: f64,
        events: &[EventFn<'_>],
        soft: &[EventFn<'_>],
    ) -> Result<Stop, IntegrationFailure> {
        // A NaN start would never reach t_end (every comparison with it is false).
        if !(t0.is_finite() && h0.is_finite() && y0.iter().all(|x| x.is_finite())) {
            return Err(IntegrationFailure::NonFinite { t: t0 });
        }
        let dir = if t_end >= t0 { 1.0 } else { -1.0 };
        let mut h = h0.abs().min((t_end - t0).abs()) * dir;
        let (mut t, mut y) = (t0, y0);
        let mut g_old: Vec<f64> = events.iter().map(|g| g(t, y)).collect();
        let soft_old: Vec<f64> = soft.iter().map(|g| g(t, y)).collect();
        for _ in 0..self.max_steps {
            if (t_end - t) * dir <= 0.0 {
                return Ok(Stop { t, y, event: None });
            }
            let last = (t + h - t_end) * dir >= 0.0;
            if last {
                h = t_end - t;
            }
            let Some((y1, err)) = self.doubled_step(sys, t, y, h) else {
                h *= 0.25;
                if h.abs() <= 1e-300 || t + h == t {
                    return Err(IntegrationFailure::StepUnderflow { t });
                }
                continue;
            };
            if err > 1.0 {
                h *= (0.9 * err.powf(-1.0 / 6.0)).clamp(0.1, 0.5);
                if t + h == t {
                    return Err(IntegrationFailure::StepUnderflow { t });
                }
                continue;
            }
            self.steps += 1;
            let t1 = if last { t_end } else { t + h };
            // Of the events that change sign in this step, the earliest one wins.
            let earliest = sign_changes(events, &g_old, t1, y1)
                .into_iter()
                .map(|(k, gk)| {
                    let (te, ye) = self.locate(sys, t, y, (h, y1), events[k], (g_old[k], gk));
                    (k, te, ye)
                })
                .min_by(|a, b| ((a.1 - t) * dir).total_cmp(&((b.1 - t) * dir)));
            if let Some((k, te, ye)) = earliest {
                return Ok(Stop {
                    t: te,
                    y: ye,
                    event: Some(k),
                });
            }
            if let Some((k, _)) = sign_changes(soft, &soft_old, t1, y1).first() {
                return Ok(Stop {
                    t: t1,
                    y: y1,
                    event: Some(events.len() + k),
                });
            }
            for (go, g) in g_old.iter_mut().zip(events) {
                *go = g(t1, y1);
            }
            t = t1;
            y = y1;
            h *= (0.9 * err.max(1e-12).powf(-1.0 / 6.0)).clamp(0.2, 4.0);
            self.next_step = h.abs();
        }
        Err(IntegrationFailure::TooManySteps {
            max: self.max_steps,
        })
    }

    /// An accurate step of size s, split into halves (up to `depth` times) where a Newton
    /// iteration fails; NaN only if every split failed.
    fn robust_step<S: System>(&self, sys: &S, t: f64, y: State, s: f64, depth: u32) -> State {
        if let Some((ys, _)) = self.doubled_step(sys, t, y, s) {
            return ys;
        }
        if depth == 0 {
            return [f64::NAN; 2];
        }
        let mid = self.robust_step(sys, t, y, 0.5 * s, depth - 1);
        self.robust_step(sys, t + 0.5 * s, mid, 0.5 * s, depth - 1)
    }

    /// Finds the step size s in (0, h) at which g(step(s)) = 0 (Illinois regula falsi);
    /// `y1` is the accepted step's end, the answer if no trial step inside succeeds (stiff
    /// creeping tails, where a Newton iteration of a partial step can fail).
    fn locate<S: System>(
        &self,
        sys: &S,
        t: f64,
        y: State,
        (h, y1): (f64, State),
        g: EventFn<'_>,
        (g0, g1): (f64, f64),
    ) -> (f64, State) {
        let eval = |s: f64| -> (f64, State) {
            let ys = self.robust_step(sys, t, y, s, 6);
            (g(t + s, ys), ys)
        };
        let (mut a, mut ga) = (0.0, g0);
        let (mut b, mut gb) = (h, g1);
        let mut best = y1;
        let mut best_s = h;
        let mut side = 0i8;
        let mut previous = f64::NAN;
        for _ in 0..200 {
            let mut s = (a * gb - b * ga) / (gb - ga);
            if !s.is_finite() || (s - a) * (s - b) >= 0.0 {
                s = 0.5 * (a + b);
            }
            let (mut gs, mut ys) = eval(s);
            if !gs.is_finite() {
                s = 0.5 * (a + b);
                (gs, ys) = eval(s);
                if !gs.is_finite() {
                    break;
                }
            }
            if ys.iter().all(|x| x.is_finite()) {
                (best, best_s) = (ys, s);
            }
            // Converged when g vanishes or the step size stops moving at round-off level.
            if gs == 0.0 || (s - previous).abs() <= 2.0 * f64::EPSILON * (t.abs() + s.abs()) {
                return (t + best_s, best);
            }
            previous = s;
            if (gs > 0.0) == (ga > 0.0) {
                a = s;
                ga = gs;
                if side == -1 {
                    gb *= 0.5;
                }
                side = -1;
            } else {
                b = s;
                gb = gs;
                if side == 1 {
                    ga *= 0.5;
                }
                side = 1;
            }
            if (b - a).abs() <= 4.0 * f64::EPSILON * (t.abs() + b.abs()) {
                break;
            }
        }
        let s = 0.5 * (a + b);
        let (_, ys) = eval(s);
        if ys.iter().all(|x| x.is_finite()) {
            (best, best_s) = (ys, s);
        }
        (t + best_s, best)
    }
}

/// The events whose function changes sign between `g_old` and (t, y), with their new value.
fn sign_changes(events: &[EventFn<'_>], g_old: &[f64], t: f64, y: State) -> Vec<(usize, f64)> {
    events
        .iter()
        .zip(g_old)
        .enumerate()
        .filter_map(|(k, (g, &go))| {
            let gn = g(t, y);
            (go != 0.0 && (gn == 0.0 || (gn > 0.0) != (go > 0.0))).then_some((k, gn))
        })
        .collect()
}

/// LU factorization with partial pivoting of a 6x6 matrix.
struct Lu6 {
    lu: [[f64; 6]; 6],
    perm: [usize; 6],
}

impl Lu6 {
    /// `None` if the matrix is singular or not finite.
    fn factor(mut m: [[f64; 6]; 6]) -> Option<Self> {
        let mut perm = [0, 1, 2, 3, 4, 5];
        for col in 0..6 {
            let piv = (col..6).max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))?;
            if m[piv][col] == 0.0 || !m[piv][col].is_finite() {
                return None;
            }
            m.swap(col, piv);
            perm.swap(col, piv);
            let (upper, lower) = m.split_at_mut(col + 1);
            let pivot_row = &upper[col];
            for row in lower.iter_mut() {
                let factor = row[col] / pivot_row[col];
                row[col] = factor;
                for (x, p) in row[col + 1..].iter_mut().zip(&pivot_row[col + 1..]) {
                    *x -= factor * p;
                }
            }
        }
        Some(Lu6 { lu: m, perm })
    }

    fn solve(&self, r: [f64; 6]) -> [f64; 6] {
        let mut x: [f64; 6] = std::array::from_fn(|i| r[self.perm[i]]);
        for row in 1..6 {
            let s: f64 = (0..row).map(|k| self.lu[row][k] * x[k]).sum();
            x[row] -= s;
        }
        for row in (0..6).rev() {
            let s: f64 = (row + 1..6).map(|k| self.lu[row][k] * x[k]).sum();
            x[row] = (x[row] - s) / self.lu[row][row];
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Radau IIA(3) tableau satisfies B(5) and C(3) (Hairer & Wanner, Table IV.5.6).
    #[test]
    fn tableau_order_conditions() {
        use tableau::{A, C};
        for q in 1..=5 {
            let s: f64 = (0..3).map(|j| A[2][j] * C[j].powi(q - 1)).sum();
            assert!((s - 1.0 / q as f64).abs() < 1e-15, "B({q})");
        }
        for i in 0..3 {
            for q in 1..=3 {
                let s: f64 = (0..3).map(|j| A[i][j] * C[j].powi(q - 1)).sum();
                assert!(
                    (s - C[i].powi(q) / q as f64).abs() < 1e-15,
                    "C({q}) row {i}"
                );
            }
        }
    }

    struct Oscillator;
    impl System for Oscillator {
        fn rhs(&self, _t: f64, y: State) -> State {
            [y[1], -y[0]]
        }
        fn jacobian(&self, _t: f64, _y: State) -> [[f64; 2]; 2] {
            [[0.0, 1.0], [-1.0, 0.0]]
        }
    }

    #[test]
    fn harmonic_oscillator_and_event() {
        let mut rk = Radau5::new(1e-13);
        let stop = rk
            .integrate(
                &Oscillator,
                0.0,
                [0.0, 1.0],
                10.0,
                0.1,
                &[&|_, y| y[0] + 0.0],
            )
            .unwrap();
        // First zero of sin after t = 0 is pi.
        assert_eq!(stop.event, Some(0));
        assert!((stop.t - std::f64::consts::PI).abs() < 1e-12, "{}", stop.t);
        assert!((stop.y[1] + 1.0).abs() < 1e-12);
        let end = rk
            .integrate(&Oscillator, 0.0, [0.0, 1.0], 20.0, 0.1, &[])
            .unwrap();
        assert!((end.y[0] - 20f64.sin()).abs() < 1e-11);
    }

    /// A very stiff linear system decays onto its slow manifold without step-size collapse.
    struct Stiff;
    impl System for Stiff {
        fn rhs(&self, t: f64, y: State) -> State {
            [-1e9 * (y[0] - t.cos()), -y[1]]
        }
        fn jacobian(&self, _t: f64, _y: State) -> [[f64; 2]; 2] {
            [[-1e9, 0.0], [0.0, -1.0]]
        }
    }

    #[test]
    fn stiff_problem() {
        let mut rk = Radau5::new(1e-12);
        let end = rk
            .integrate(&Stiff, 0.0, [0.0, 1.0], 5.0, 1e-3, &[])
            .unwrap();
        assert!((end.y[1] - (-5f64).exp()).abs() < 1e-12);
        // Slow manifold y0 = cos t + sin t * 1e-9 + O(1e-18).
        assert!((end.y[0] - (5f64.cos() + 5f64.sin() * 1e-9)).abs() < 1e-12);
        assert!(rk.steps < 5000, "steps {}", rk.steps);
    }
}
