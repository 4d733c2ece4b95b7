//! An independent reference solution of the scaled collision equation of viscoelastic
//! spheres, Eq. (9) of MP2011,
//!
//! ```text
//! x'' + x^{3/2} + A x' sqrt(x) = 0,   x(0) = 0,  x'(0) = 1,   A = v*^2,
//! ```
//!
//! written from scratch (no code of the crate is used):
//!
//! 1. **Start at the singular point** x = 0 by the Puiseux series in sigma = sqrt(tau)
//!    ([`puiseux`]), summed at a sigma_0 where its tail is below round-off.
//! 2. **Taylor-series integrator** (automatic-differentiation recurrences) of order ~28 for
//!    x' = p, p' = -sqrt(x) (x + A p) in tau, with the step chosen from the size of the
//!    last two Taylor coefficients (Jorba & Zou, Exp. Math. 14 (2005) 99).
//! 3. **Events on the step polynomial**: maximal compression (p = 0), the improved end
//!    (g = x + A p = 0) and the naive end x = 0 (see [`Reference::solve`]).

#![allow(dead_code)]

// ---------------------------------------------------------------------------------------
// Puiseux series at contact
// ---------------------------------------------------------------------------------------

/// The coefficient ring of the Puiseux recurrence: f64 for numbers, [`Poly`] for exact
/// polynomials in the damping parameter.
pub trait Ring: Clone {
    fn zero() -> Self;
    fn constant(c: f64) -> Self;
    fn add(&self, o: &Self) -> Self;
    fn mul(&self, o: &Self) -> Self;
    fn scale(&self, c: f64) -> Self;
}

impl Ring for f64 {
    fn zero() -> Self {
        0.0
    }
    fn constant(c: f64) -> Self {
        c
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    fn scale(&self, c: f64) -> Self {
        self * c
    }
}

/// A polynomial in one variable (coefficient of power k at index k).
#[derive(Clone, Debug)]
pub struct Poly(pub Vec<f64>);

impl Poly {
    pub fn coef(&self, k: usize) -> f64 {
        self.0.get(k).copied().unwrap_or(0.0)
    }
}

impl Ring for Poly {
    fn zero() -> Self {
        Poly(Vec::new())
    }
    fn constant(c: f64) -> Self {
        Poly(vec![c])
    }
    fn add(&self, o: &Self) -> Self {
        let n = self.0.len().max(o.0.len());
        Poly((0..n).map(|k| self.coef(k) + o.coef(k)).collect())
    }
    fn mul(&self, o: &Self) -> Self {
        if self.0.is_empty() || o.0.is_empty() {
            return Poly::zero();
        }
        let mut c = vec![0.0; self.0.len() + o.0.len() - 1];
        for (i, a) in self.0.iter().enumerate() {
            for (j, b) in o.0.iter().enumerate() {
                c[i + j] += a * b;
            }
        }
        Poly(c)
    }
    fn scale(&self, c: f64) -> Self {
        Poly(self.0.iter().map(|a| a * c).collect())
    }
}

/// Puiseux series of the solution of `x'' = -sqrt(x) (c_el x + c_d x')`, `x(0) = 0`,
/// `x'(0) = 1`, in sigma = sqrt(tau):
///
/// `x = sum_j X_j sigma^j` (j = 0..=n, X_0 = X_1 = 0, X_2 = 1) and
/// `x' = dx/dtau = sum_m P_m sigma^m` (m = 0..=n-2, P_m = (m+2)/2 X_{m+2}).
///
/// Derivation: sqrt(x) = sigma Q(sigma) with Q = sqrt(x/sigma^2), Q_0 = 1,
/// Q_m = (X_{m+2} - sum_{i=1}^{m-1} Q_i Q_{m-i}) / 2; x'' = sum_j (j/2) P_j sigma^{j-2};
/// x^{3/2} = sigma^3 [(x/sigma^2) Q] and x' sqrt(x) = sigma [Q P]. Matching sigma^{j-2}:
/// P_0 = 1 (free: the impact velocity) and for j >= 1
/// `P_j = -(2/j) (c_el [(x/sigma^2) Q]_{j-5} + c_d [Q P]_{j-3})`, `[.]_m = 0` for m < 0.
pub fn puiseux<T: Ring>(n: usize, c_el: &T, c_d: &T) -> (Vec<T>, Vec<T>) {
    assert!(n >= 4);
    let mut xs = vec![T::zero(); n + 1];
    let mut ps = vec![T::zero(); n - 1];
    let mut qs = vec![T::zero(); n - 1];
    xs[2] = T::constant(1.0);
    ps[0] = T::constant(1.0);
    qs[0] = T::constant(1.0);
    for j in 1..=n - 2 {
        let mut acc = T::zero();
        if j >= 5 {
            let m = j - 5;
            let mut e = T::zero();
            for i in 0..=m {
                e = e.add(&xs[i + 2].mul(&qs[m - i]));
            }
            acc = acc.add(&c_el.mul(&e));
        }
        if j >= 3 {
            let m = j - 3;
            let mut d = T::zero();
            for i in 0..=m {
                d = d.add(&qs[i].mul(&ps[m - i]));
            }
            acc = acc.add(&c_d.mul(&d));
        }
        ps[j] = acc.scale(-2.0 / j as f64);
        xs[j + 2] = ps[j].scale(2.0 / (j + 2) as f64);
        let mut r = xs[j + 2].clone();
        for i in 1..j {
            r = r.add(&qs[i].mul(&qs[j - i]).scale(-1.0));
        }
        qs[j] = r.scale(0.5);
    }
    (xs, ps)
}

fn eval(c: &[f64], t: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &a| acc * t + a)
}

fn eval_d(c: &[f64], t: f64) -> (f64, f64) {
    let mut f = 0.0;
    let mut df = 0.0;
    for &a in c.iter().rev() {
        df = df * t + f;
        f = f * t + a;
    }
    (f, df)
}

/// The state (tau_0, x_0, p_0) a short time after contact, from the Puiseux series.
///
/// The series is built in the units natural for the damping: for A <= 1 none; for A > 1
/// x and tau in units a = A^(-2/3), in which X'' = -sqrt(X) (A^(-5/3) X + X') (coefficients
/// O(1), no overflow). sigma_0 is the largest value at which each of the last few terms of
/// both series is below `tol` times the leading term, i.e. where the (geometrically
/// converging) series has converged to round-off.
pub fn start(damping: f64, n: usize, tol: f64) -> (f64, f64, f64) {
    let (unit, c_el, c_d) = if damping <= 1.0 {
        (1.0, 1.0, damping)
    } else {
        (damping.powf(-2.0 / 3.0), damping.powf(-5.0 / 3.0), 1.0)
    };
    let (xs, ps) = puiseux(n, &c_el, &c_d);
    let mut sigma = f64::INFINITY;
    for (j, x) in xs.iter().enumerate().take(n + 1).skip(n - 5) {
        if *x != 0.0 {
            sigma = sigma.min((tol / x.abs()).powf(1.0 / (j - 2) as f64));
        }
    }
    for (m, p) in ps.iter().enumerate().take(n - 1).skip(n - 7) {
        if *p != 0.0 {
            sigma = sigma.min((tol / p.abs()).powf(1.0 / m as f64));
        }
    }
    // Stay well inside the compression phase (the scaled time of maximal compression is
    // >= 1.3 for every A).
    sigma = sigma.min(1.0);
    let big_x = eval(&xs, sigma);
    let big_p = eval(&ps, sigma);
    assert!(
        big_p > 0.0 && big_x > 0.0,
        "series start beyond maximal compression"
    );
    (unit * sigma * sigma, unit * big_x, big_p)
}

// ---------------------------------------------------------------------------------------
// Taylor integrator
// ---------------------------------------------------------------------------------------

/// Taylor coefficients of x, p and g = x + A p at one point in the normalized time
/// u = (tau - tau_i)/eta (index k: coefficient of u^k). eta is the previous step, so that
/// the coefficients stay O(1) times the solution even when the radius of convergence is
/// tiny (near x = 0 the k-th tau-coefficient grows like (|p|/x)^k and would overflow).
struct Jet {
    x: Vec<f64>,
    p: Vec<f64>,
    g: Vec<f64>,
    s: Vec<f64>,
}

impl Jet {
    fn new(n: usize) -> Self {
        Jet {
            x: vec![0.0; n + 1],
            p: vec![0.0; n + 1],
            g: vec![0.0; n + 1],
            s: vec![0.0; n + 1],
        }
    }

    /// sqrt(x): s_0 = sqrt(x_0), s_k = (x_k - sum_{j=1}^{k-1} s_j s_{k-j}) / (2 s_0).
    #[inline]
    fn sqrt_coef(&mut self, k: usize) {
        if k == 0 {
            self.s[0] = self.x[0].sqrt();
        } else {
            let mut acc = self.x[k];
            for j in 1..k {
                acc -= self.s[j] * self.s[k - j];
            }
            self.s[k] = acc * (0.5 / self.s[0]);
        }
    }

    /// q_k = [s g]_k (Cauchy product).
    #[inline]
    fn q_coef(&self, k: usize) -> f64 {
        let mut q = 0.0;
        for j in 0..=k {
            q += self.s[j] * self.g[k - j];
        }
        q
    }

    /// Automatic-differentiation recurrences for x' = p, p' = -sqrt(x) (x + A p), state
    /// (x, p): g = x + A p; q = s g; x_{k+1} = p_k/(k+1); p_{k+1} = -q_k/(k+1).
    fn expand_velocity(&mut self, damping: f64, eta: f64, x0: f64, p0: f64) {
        let n = self.x.len() - 1;
        self.x[0] = x0;
        self.p[0] = p0;
        for k in 0..n {
            self.sqrt_coef(k);
            self.g[k] = self.x[k] + damping * self.p[k];
            let q = self.q_coef(k);
            let inv = eta / (k + 1) as f64;
            self.x[k + 1] = self.p[k] * inv;
            self.p[k + 1] = -q * inv;
        }
        self.g[n] = self.x[n] + damping * self.p[n];
    }

    /// The same system with state (x, g), g = x + A p (proportional to the force):
    /// x' = p = (g - x)/A, g' = p - A sqrt(x) g. For large A, g at the end of the
    /// collision is far smaller than x and A p, and is lost if it is formed from (x, p);
    /// carried as a state variable it keeps its relative accuracy. Recurrences:
    /// p_k = (g_k - x_k)/A; x_{k+1} = p_k/(k+1); g_{k+1} = (p_k - A q_k)/(k+1).
    fn expand_force(&mut self, damping: f64, eta: f64, x0: f64, g0: f64) {
        let n = self.x.len() - 1;
        let inv_a = 1.0 / damping;
        self.x[0] = x0;
        self.g[0] = g0;
        for k in 0..n {
            self.sqrt_coef(k);
            self.p[k] = (self.g[k] - self.x[k]) * inv_a;
            let q = self.q_coef(k);
            let inv = eta / (k + 1) as f64;
            self.x[k + 1] = self.p[k] * inv;
            self.g[k + 1] = (self.p[k] - damping * q) * inv;
        }
        self.p[n] = (self.g[n] - self.x[n]) * inv_a;
    }

    /// Jorba-Zou step (in u): the largest h for which the last two terms of each state series are
    /// below `tol` times that component's current magnitude.
    fn step(&self, tol: f64, force_form: bool) -> f64 {
        let n = self.x.len() - 1;
        let mut h = f64::INFINITY;
        let second = if force_form { &self.g } else { &self.p };
        for c in [&self.x, second] {
            let scale = c[0].abs();
            for k in [n - 1, n] {
                if c[k] != 0.0 {
                    h = h.min((tol * scale / c[k].abs()).powf(1.0 / k as f64));
                }
            }
        }
        h
    }
}

/// Safeguarded Newton for a root of the polynomial `c` in [lo, hi], where c(lo) and
/// c(hi) have opposite signs (or c(hi) = 0).
fn root(c: &[f64], mut lo: f64, mut hi: f64) -> f64 {
    let positive_at_lo = eval(c, lo) > 0.0;
    let mut t = 0.5 * (lo + hi);
    for _ in 0..300 {
        let (f, df) = eval_d(c, t);
        if f == 0.0 {
            return t;
        }
        if (f > 0.0) == positive_at_lo {
            lo = t;
        } else {
            hi = t;
        }
        let mut next = t - f / df;
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        let done = (next - t).abs() <= 1e-17 * t.abs() || hi - lo <= 1e-16 * hi.abs();
        t = next;
        if done {
            break;
        }
    }
    t
}

/// Compensated (Kahan-Babuska-Neumaier) sum for the time, which can take ~1e5 steps.
#[derive(Clone, Copy)]
struct Clock {
    sum: f64,
    comp: f64,
}

impl Clock {
    fn add(&mut self, v: f64) {
        let t = self.sum + v;
        if self.sum.abs() >= v.abs() {
            self.comp += (self.sum - t) + v;
        } else {
            self.comp += (v - t) + self.sum;
        }
        self.sum = t;
    }
    fn at(&self, offset: f64) -> f64 {
        let mut c = *self;
        c.add(offset);
        c.sum + c.comp
    }
}

/// Which end of the collision to find.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum End {
    /// The force vanishes: x + A x' = 0 after maximal compression.
    Force,
    /// The overlap vanishes: x = 0.
    Overlap,
}

/// The reference result (scaled units).
#[derive(Clone, Copy, Debug)]
pub struct RefCollision {
    pub eps: f64,
    pub duration: f64,
    pub max_compression: f64,
    pub time_of_max_compression: f64,
    pub compression_at_end: f64,
    /// -x'(tau_c) (for the improved end; eps is computed as x_c/A there).
    pub minus_p_end: f64,
    pub steps: usize,
}

/// Numerical parameters of the reference.
#[derive(Clone, Copy, Debug)]
pub struct Reference {
    /// Order of the Taylor method.
    pub order: usize,
    /// Relative truncation tolerance per step.
    pub tol: f64,
    /// Order (in sigma) of the Puiseux start.
    pub series_order: usize,
    /// Relative size of the neglected Puiseux terms at the start.
    pub series_tol: f64,
    /// Stop the approach to x = 0 when the remaining change of x' relative to x' is below.
    pub end_tol: f64,
    /// Give up after this many steps.
    pub max_steps: usize,
    /// State variables of the integrator.
    pub form: Form,
}

/// State variables of the Taylor integrator.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Form {
    /// (x, p) for A <= 1, (x, g) for A > 1.
    Auto,
    /// Always (x, p).
    Velocity,
    /// Always (x, g) (A > 0 only).
    Force,
}

impl Default for Reference {
    fn default() -> Self {
        Reference {
            order: 28,
            tol: 1e-17,
            series_order: 60,
            series_tol: 1e-18,
            end_tol: 1e-18,
            max_steps: 50_000_000,
            form: Form::Auto,
        }
    }
}

impl Reference {
    /// Integrates one collision at damping parameter A = v*^2.
    ///
    /// * Maximal compression: p decreases monotonically while p > 0, so the first step whose
    ///   polynomial has p(h) <= 0 brackets it; root by safeguarded Newton on the polynomial.
    /// * Improved end (A > 0): after maximal compression g = x + A p starts at x_max > 0 and
    ///   g' = p - A sqrt(x) g < 0 while g > 0, so again the first step with g(h) <= 0 brackets
    ///   it. eps = x_c / A (equal to -p_c there; for large A, p_c = -(x_c - g)/A is the
    ///   small difference of larger numbers, x_c is not).
    /// * Naive end (and A = 0): tau = tau_c is a branch point of x(tau), so the radius of
    ///   the tau-series is the remaining time ~ x/|p| and the coefficient-based step covers
    ///   a fixed fraction (~ tol^(1/order) ~ 1/4) of it: x decreases geometrically. Instead
    ///   of a fixed threshold on x we stop when the rest of the change of p is negligible:
    ///   with x ~ |p| u (u the remaining time), integrating p' = -sqrt(x)(x + A p) over the
    ///   remaining time T = x/|p| gives Delta p = (2/3) A x^{3/2} - (2/5) x^{5/2}/|p|
    ///   (+ higher orders). We stop when |Delta p| < end_tol |p| and still add Delta p and
    ///   T (so the neglected part is second order in an already negligible quantity).
    /// * A step whose polynomial gives x(h) <= 0 (an overestimated radius) is halved.
    pub fn solve(&self, vstar: f64, end: End) -> RefCollision {
        let damping = vstar * vstar;
        let end = if damping == 0.0 { End::Overlap } else { end };
        let n = self.order;
        let force_form = match self.form {
            Form::Auto => damping > 1.0,
            Form::Velocity => false,
            Form::Force => damping > 0.0,
        };
        let (tau0, mut x, p0) = start(damping, self.series_order, self.series_tol);
        // Second state variable: p, or g = x + A p.
        let mut y = if force_form { x + damping * p0 } else { p0 };
        let mut clock = Clock {
            sum: 0.0,
            comp: 0.0,
        };
        clock.add(tau0);
        let mut jet = Jet::new(n);
        let mut max: Option<(f64, f64)> = None;
        let mut eta = tau0;
        let mut steps = 0;
        loop {
            steps += 1;
            assert!(
                steps <= self.max_steps,
                "reference: too many steps at v* = {vstar}"
            );
            if force_form {
                jet.expand_force(damping, eta, x, y);
            } else {
                jet.expand_velocity(damping, eta, x, y);
            }
            // All polynomials are in u = (tau - tau_i)/eta; h is the step in u.
            let mut h = jet.step(self.tol, force_form).min(10.0);
            assert!(
                h.is_finite() && h > 0.0,
                "reference: bad step {h} at v* = {vstar}, x = {x:e}, y = {y:e}"
            );
            let mut x_new = eval(&jet.x, h);
            while x_new.is_nan() || x_new <= 0.0 {
                h *= 0.5;
                x_new = eval(&jet.x, h);
            }
            let p_new = eval(&jet.p, h);
            let mut lo = 0.0;
            if max.is_none() && p_new <= 0.0 {
                let u1 = root(&jet.p, 0.0, h);
                max = Some((eval(&jet.x, u1), clock.at(eta * u1)));
                lo = u1;
            }
            if let Some((x_max, t_max)) = max {
                if end == End::Force && eval(&jet.g, h) <= 0.0 {
                    let u2 = root(&jet.g, lo, h);
                    let x_c = eval(&jet.x, u2);
                    return RefCollision {
                        eps: x_c / damping,
                        duration: clock.at(eta * u2),
                        max_compression: x_max,
                        time_of_max_compression: t_max,
                        compression_at_end: x_c,
                        minus_p_end: -eval(&jet.p, u2),
                        steps,
                    };
                }
            }
            x = x_new;
            y = eval(if force_form { &jet.g } else { &jet.p }, h);
            let p = p_new;
            clock.add(eta * h);
            eta *= h;
            if let Some((x_max, t_max)) = max {
                if end == End::Overlap {
                    let dp = (2.0 / 3.0) * damping * x.powf(1.5) - 0.4 * x.powf(2.5) / p.abs();
                    if dp.abs() < self.end_tol * p.abs() {
                        let eps = -(p + dp);
                        return RefCollision {
                            eps,
                            duration: clock.at(x / p.abs()),
                            max_compression: x_max,
                            time_of_max_compression: t_max,
                            compression_at_end: 0.0,
                            minus_p_end: eps,
                            steps,
                        };
                    }
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// Gamma function (Stirling series after an upward shift)
// ---------------------------------------------------------------------------------------

/// ln Gamma(z) for z > 0: shift to w = z + k >= 10 by the recurrence, then the Stirling
/// series with Bernoulli numbers B_2 .. B_16 (the first neglected term, B_18/(306 w^17), is
/// < 2e-18 there).
pub fn ln_gamma(z: f64) -> f64 {
    assert!(z > 0.0);
    let mut w = z;
    let mut prod = 1.0;
    while w < 10.0 {
        prod *= w;
        w += 1.0;
    }
    // B_{2k} / (2k (2k-1)).
    let bern = [
        1.0 / 6.0,
        -1.0 / 30.0,
        1.0 / 42.0,
        -1.0 / 30.0,
        5.0 / 66.0,
        -691.0 / 2730.0,
        7.0 / 6.0,
        -3617.0 / 510.0,
    ];
    let mut series = 0.0;
    let w2 = w * w;
    let mut wp = w;
    for (i, b) in bern.iter().enumerate() {
        let k = (i + 1) as f64;
        series += b / (2.0 * k * (2.0 * k - 1.0) * wp);
        wp *= w2;
    }
    (w - 0.5) * w.ln() - w + 0.5 * (2.0 * std::f64::consts::PI).ln() + series - prod.ln()
}
