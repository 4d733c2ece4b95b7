//! The fast path of [`crate::exact::solve`]: a Taylor-series (automatic-differentiation)
//! integrator of Eq. (9) of MP2011 in the charts and units of [`crate::exact`], with the
//! slow-manifold ending of [`crate::manifold`] for overdamped naive collisions.
//!
//! In both charts the right-hand sides are built from +, *, / and sqrt, so the Taylor
//! coefficients of the solution at a point follow from short recurrences (Moore 1966;
//! Jorba & Zou, Exp. Math. 14 (2005) 99). With the scaling of [`Scaling`]
//! (X'' = -sqrt(X) (c_el X + c_d X'), delta = c_el / c_d, g = X' + delta X):
//!
//! - **root chart**, independent w = sqrt(X), state (v, T), v = p = X' or v = g, r = 1/p:
//!   `dv/dw = -2 c_d w^2 - 2 c_el w^4 r (+ 2 delta w if v = g)`, `dT/dw = 2 w r`
//!   (from dp/dT = -w (c_el w^2 + c_d p), dw/dT = p/(2w));
//!   `r_k = -r_0 sum_{j=1}^k p_j r_{k-j}`, and w^2, w^4 are polynomials of degree 2, 4;
//! - **time chart**, independent T, state (X, v), s = sqrt(X):
//!   `X' = p`, `p' = -s (c_el X + c_d p)` or `g' = -c_d s g + delta p`;
//!   `s_k = (X_k - sum_{j=1}^{k-1} s_j s_{k-j}) / (2 s_0)`.
//!
//! Each step expands the state to order [`ORDER`] in u = (t - t_i)/eta (eta the previous
//! step, so that the coefficients stay O(1)) and takes the step h at which the last two
//! terms of every series fall below [`TOL`] times the size of its component (Jorba & Zou,
//! Sec. 3.2). Events (p = 0.7, maximal compression p = 0, zero force, the chart switch
//! X = X_max/4) are roots of the step polynomials, found by safeguarded Newton: the
//! polynomial is the solution to the accuracy of the step everywhere in it, so events
//! cost no extra steps.
//!
//! Phases as in the Radau path: root chart from contact to p = 0.7 (1/2 there); time
//! chart through maximal compression to zero force (improved) or X = X_max/4; root chart
//! down to zero force or w = 0. A naive collision with A > 1 that has joined the slow manifold at
//! y <= [`manifold::Y_MAX`] ends in closed form instead (see [`crate::manifold`]).

use crate::error::{Error, Result};
use crate::exact::{Collision, Criterion, Scaling};
use crate::manifold;

/// Order of the Taylor polynomials.
pub(crate) const ORDER: usize = 24;
const LEN: usize = ORDER + 1;

/// Size of the last two terms of a step's series relative to its component.
pub(crate) const TOL: f64 = 1e-16;

/// Largest step, in units of the previous one.
const MAX_GROWTH: f64 = 8.0;

/// Give up after this many steps (a collision needs ~10-60).
const MAX_STEPS: usize = 20_000;

/// The manifold ending is taken once |p - p_manifold| y <= DEVIATION |p|: the time error
/// this leaves, ~ (|p - p_M|/|p|) y / (ln(x A^4) + K) relative (the off-manifold part
/// decays within a time A y from x on, shifting the creep by that much), stays < 1e-17.
const DEVIATION: f64 = 1e-16;

/// The compression ends in the root chart at p = SWITCH_SPEED.
const SWITCH_SPEED: f64 = 0.7;

type Series = [f64; LEN];

/// 1/(k+1).
const INV: Series = {
    let mut a = [0.0; LEN];
    let mut k = 0;
    while k < LEN {
        a[k] = 1.0 / (k as f64 + 1.0);
        k += 1;
    }
    a
};

/// sum_j a[j] b[j] over the common length, in four independent partial sums. A
/// coefficient of a Cauchy product, sum_j a_j b_{k-j}, is such a sum with b stored in
/// reverse order (the `*_rev` arrays: `c_rev[ORDER - k] = c[k]`), so that both run forward
/// and vectorize.
#[inline(always)]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0f64; 4];
    for (ca, cb) in a.chunks_exact(4).zip(b.chunks_exact(4)) {
        for i in 0..4 {
            acc[i] += ca[i] * cb[i];
        }
    }
    let r = n % 4;
    let tail: f64 = a[n - r..].iter().zip(&b[n - r..]).map(|(x, y)| x * y).sum();
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

#[inline(always)]
fn eval(c: &Series, u: f64) -> f64 {
    let mut acc = c[ORDER];
    for k in (0..ORDER).rev() {
        acc = acc * u + c[k];
    }
    acc
}

#[inline(always)]
fn eval_d(c: &Series, u: f64) -> (f64, f64) {
    let (mut f, mut df) = (c[ORDER], 0.0);
    for k in (0..ORDER).rev() {
        df = df * u + f;
        f = f * u + c[k];
    }
    (f, df)
}

/// The u in [lo, hi] where the polynomial c equals `level`; c - level changes sign on
/// [lo, hi] (or vanishes at hi). Safeguarded Newton: bisection when Newton leaves the
/// bracket.
fn root(c: &Series, level: f64, mut lo: f64, mut hi: f64) -> f64 {
    let above_at_lo = eval(c, lo) > level;
    let mut u = 0.5 * (lo + hi);
    for _ in 0..200 {
        let (f, df) = eval_d(c, u);
        let f = f - level;
        if f == 0.0 {
            return u;
        }
        if (f > 0.0) == above_at_lo {
            lo = u;
        } else {
            hi = u;
        }
        let mut next = u - f / df;
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        let done = (next - u).abs() <= 4.0 * f64::EPSILON * u.abs()
            || hi - lo <= 4.0 * f64::EPSILON * hi.abs();
        u = next;
        if done {
            break;
        }
    }
    u
}

/// Jorba-Zou step (in u): the largest h at which the terms of order k = ORDER-1 and
/// ORDER of each series are below TOL times the size of its component, max(|c_0|, |c_1|,
/// |c_2|) (T = w^2 + ... starts with two zero coefficients at contact):
/// h = min_k (TOL / max_c |c_k|/scale_c)^(1/k).
///
/// `span` orders are inspected instead of two at contact, where the series of the nearly
/// elastic collision are nearly series in w^5 (exactly so for A = 0: p^2 = 1 - (4/5) w^5),
/// so that the last two terms can vanish by symmetry rather than by convergence.
#[inline(always)]
fn step_size(series: &[&Series], span: usize) -> f64 {
    let mut worst = [0.0f64; LEN];
    for c in series {
        let scale = c[0].abs().max(c[1].abs()).max(c[2].abs());
        if scale == 0.0 {
            continue;
        }
        for k in ORDER + 1 - span..=ORDER {
            worst[k] = worst[k].max(c[k].abs() / scale);
        }
    }
    let mut h = MAX_GROWTH;
    for (k, &m) in worst.iter().enumerate().skip(ORDER + 1 - span) {
        if m > 0.0 {
            h = h.min((TOL / m).powf(1.0 / k as f64));
        }
    }
    h
}

/// Taylor coefficients in the root chart.
struct RootJet {
    v: Series,
    p: Series,
    t: Series,
    r: Series,
    r_rev: Series,
    /// w^2 as a series (degree 2).
    w2: [f64; 3],
}

impl RootJet {
    fn new() -> Self {
        RootJet {
            v: [0.0; LEN],
            p: [0.0; LEN],
            t: [0.0; LEN],
            r: [0.0; LEN],
            r_rev: [0.0; LEN],
            w2: [0.0; 3],
        }
    }

    /// Expands the state (v0, t0) at w0 in u = (w - w0)/eta.
    #[inline(always)]
    fn expand(&mut self, s: &Scaling, w0: f64, eta: f64, v0: f64, t0: f64) {
        let w = [w0, eta];
        let w2 = [w0 * w0, 2.0 * w0 * eta, eta * eta];
        let w4 = [
            w2[0] * w2[0],
            2.0 * w2[0] * w2[1],
            2.0 * w2[0] * w2[2] + w2[1] * w2[1],
            2.0 * w2[1] * w2[2],
            w2[2] * w2[2],
        ];
        self.w2 = w2;
        let force = s.force_form;
        self.v[0] = v0;
        self.t[0] = t0;
        for k in 0..=ORDER {
            let w2k = if k < 3 { w2[k] } else { 0.0 };
            self.p[k] = if force {
                self.v[k] - s.delta * w2k
            } else {
                self.v[k]
            };
            // r_k = -r_0 sum_{j=1}^k p_j r_{k-j}; r_rev[ORDER-k+1+i] = r_{k-1-i}.
            self.r[k] = if k == 0 {
                1.0 / self.p[0]
            } else {
                -self.r[0] * dot(&self.p[1..=k], &self.r_rev[ORDER + 1 - k..])
            };
            self.r_rev[ORDER - k] = self.r[k];
            if k == ORDER {
                break;
            }
            // sum_{j=0}^{min(k,4)} (w^4)_j r_{k-j}.
            let w4r = dot(&w4[..=k.min(4)], &self.r_rev[ORDER - k..]);
            let wr = w0 * self.r[k] + if k > 0 { eta * self.r[k - 1] } else { 0.0 };
            let mut dv = -2.0 * s.c_d * w2k - 2.0 * s.c_el * w4r;
            if force && k < 2 {
                dv += 2.0 * s.delta * w[k];
            }
            let f = eta * INV[k];
            self.v[k + 1] = f * dv;
            self.t[k + 1] = f * 2.0 * wr;
        }
    }

    /// The series of the force-like quantity (zero at the improved end).
    fn force(&self, s: &Scaling) -> Series {
        if s.force_form {
            self.v
        } else {
            let mut f = self.p;
            for (k, fk) in f.iter_mut().enumerate() {
                *fk *= s.c_d;
                if k < 3 {
                    *fk += s.c_el * self.w2[k];
                }
            }
            f
        }
    }
}

/// Taylor coefficients in the time chart.
struct TimeJet {
    x: Series,
    v: Series,
    p: Series,
    /// c_el X + c_d p or g: the force-like quantity.
    f: Series,
    s: Series,
    f_rev: Series,
    s_rev: Series,
}

impl TimeJet {
    fn new() -> Self {
        TimeJet {
            x: [0.0; LEN],
            v: [0.0; LEN],
            p: [0.0; LEN],
            f: [0.0; LEN],
            s: [0.0; LEN],
            f_rev: [0.0; LEN],
            s_rev: [0.0; LEN],
        }
    }

    /// Expands the state (x0, v0) in u = (T - T_i)/eta.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // k indexes seven series and their recurrences
    fn expand(&mut self, sc: &Scaling, eta: f64, x0: f64, v0: f64) {
        let force = sc.force_form;
        self.x[0] = x0;
        self.v[0] = v0;
        for k in 0..=ORDER {
            if k == 0 {
                self.s[0] = x0.sqrt();
            } else {
                // sum_{j=1}^{k-1} s_j s_{k-j}, folded: 2 sum_{j=1}^{m} s_j s_{k-j} (+ the
                // middle term); s_rev[ORDER-k+1+i] = s_{k-1-i}.
                let m = (k - 1) / 2;
                let mut acc = 2.0 * dot(&self.s[1..=m], &self.s_rev[ORDER + 1 - k..]);
                if k % 2 == 0 {
                    acc += self.s[k / 2] * self.s[k / 2];
                }
                self.s[k] = (self.x[k] - acc) * (0.5 / self.s[0]);
            }
            self.s_rev[ORDER - k] = self.s[k];
            if force {
                self.p[k] = self.v[k] - sc.delta * self.x[k];
                self.f[k] = self.v[k];
            } else {
                self.p[k] = self.v[k];
                self.f[k] = sc.c_el * self.x[k] + sc.c_d * self.p[k];
            }
            self.f_rev[ORDER - k] = self.f[k];
            if k == ORDER {
                break;
            }
            // q_k = sum_{j=0}^k s_j f_{k-j}; f_rev[ORDER-k+i] = f_{k-i}.
            let q = dot(&self.s[..=k], &self.f_rev[ORDER - k..]);
            let f = eta * INV[k];
            self.x[k + 1] = f * self.p[k];
            self.v[k + 1] = if force {
                f * (sc.delta * self.p[k] - sc.c_d * q)
            } else {
                -f * q
            };
        }
    }
}

/// A point of the trajectory on the slow manifold (unscaled compression x and time tau,
/// and y = 1/(A^2 sqrt(x))).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ManifoldPoint {
    pub x: f64,
    pub tau: f64,
    pub y: f64,
}

/// Whether a naive collision may end on the slow manifold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Ending {
    /// Take the closed form as soon as the trajectory is on the manifold.
    Manifold,
    /// Integrate to x = 0, recording the first point found on the manifold.
    Integrate,
}

fn failure(s: &Scaling, what: &str) -> Error {
    Error::Numerical(format!(
        "collision at v* = {} (Taylor): {what}",
        s.damping.sqrt()
    ))
}

/// Solves one collision (v* validated by the caller).
pub(crate) fn collide(vstar: f64, criterion: Criterion) -> Result<Collision> {
    Ok(run(vstar, criterion, Ending::Manifold)?.0)
}

/// P* and K of [`crate::manifold`] from a naive collision at
/// [`manifold::CALIBRATION_VSTAR`] integrated to its end.
pub(crate) fn calibrate() -> Result<manifold::Constants> {
    let v = manifold::CALIBRATION_VSTAR;
    let (c, point) = run(v, Criterion::Naive, Ending::Integrate)?;
    let s = Scaling::new(v);
    let point = point.ok_or_else(|| failure(&s, "the slow manifold was not reached"))?;
    let a = s.damping;
    Ok(manifold::Constants {
        exit_speed: c.eps * a.powi(5),
        offset: (c.duration - point.tau) / a - (point.x * a.powi(4)).ln() - manifold::rest(point.y),
    })
}

/// The deviation test of the manifold ending at (X, g) in the force form.
fn on_manifold(s: &Scaling, x: f64, g: f64) -> Option<f64> {
    let y = s.delta / x.sqrt();
    if y > manifold::Y_MAX {
        return None;
    }
    let g_m = -s.delta * x * manifold::u(y);
    let p = g - s.delta * x;
    ((g - g_m).abs() * y <= DEVIATION * p.abs()).then_some(y)
}

/// [`run_body`] compiled for AVX2 where the processor has it, else for the baseline. The
/// results are bit-identical: no fused multiply-add is enabled, and the only loops the
/// wider registers vectorize keep their four partial sums ([`dot`]).
fn run(
    vstar: f64,
    criterion: Criterion,
    ending: Ending,
) -> Result<(Collision, Option<ManifoldPoint>)> {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor supports AVX2 (checked just above).
        return unsafe { run_avx2(vstar, criterion, ending) };
    }
    run_body(vstar, criterion, ending)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn run_avx2(
    vstar: f64,
    criterion: Criterion,
    ending: Ending,
) -> Result<(Collision, Option<ManifoldPoint>)> {
    run_body(vstar, criterion, ending)
}

#[inline(always)]
fn run_body(
    vstar: f64,
    criterion: Criterion,
    ending: Ending,
) -> Result<(Collision, Option<ManifoldPoint>)> {
    let s = Scaling::new(vstar);
    let improved = criterion == Criterion::Improved && s.damping > 0.0;
    let watch_manifold = !improved && s.force_form;
    let mut steps = 0;
    let count = |steps: &mut usize| {
        *steps += 1;
        if *steps > MAX_STEPS {
            Err(failure(&s, "too many steps"))
        } else {
            Ok(())
        }
    };

    // Phase 1: root chart from contact until p = SWITCH_SPEED.
    let mut rj = RootJet::new();
    let (mut w, mut v, mut t) = (0.0f64, 1.0f64, 0.0f64);
    let mut eta = 0.5;
    loop {
        count(&mut steps)?;
        rj.expand(&s, w, eta, v, t);
        let h = step_size(&[&rj.v, &rj.t], if w == 0.0 { 6 } else { 2 });
        if eval(&rj.p, h) <= SWITCH_SPEED {
            let u = root(&rj.p, SWITCH_SPEED, 0.0, h);
            (w, v, t) = (w + eta * u, eval(&rj.v, u), eval(&rj.t, u));
            eta *= u.max(1e-3 * h);
            break;
        }
        (w, v, t) = (w + eta * h, eval(&rj.v, h), eval(&rj.t, h));
        eta *= h;
    }

    // Phase 2: time chart through maximal compression.
    let mut time = TimeJet::new();
    let mut x = w * w;
    // dT = (2w/p) dw carries the step across the chart change.
    eta *= 2.0 * w / SWITCH_SPEED;
    let mut max: Option<(f64, f64)> = None;
    let mut point = None;
    let end;
    loop {
        count(&mut steps)?;
        time.expand(&s, eta, x, v);
        let h = step_size(&[&time.x, &time.v], 2);
        let mut lo = 0.0;
        if max.is_none() && eval(&time.p, h) <= 0.0 {
            let u = root(&time.p, 0.0, 0.0, h);
            max = Some((eval(&time.x, u), t + eta * u));
            lo = u;
        }
        if let Some((x_max, _)) = max {
            let at_force = (improved && eval(&time.f, h) <= 0.0).then(|| root(&time.f, 0.0, lo, h));
            let switch = x_max / 4.0;
            let at_switch = (eval(&time.x, h) <= switch).then(|| root(&time.x, switch, lo, h));
            match (at_force, at_switch) {
                (Some(u), b) if b.is_none_or(|b| u <= b) => {
                    end = Some((t + eta * u, eval(&time.x, u), eval(&time.v, u)));
                    break;
                }
                (_, Some(u)) => {
                    (x, v, t) = (eval(&time.x, u), eval(&time.v, u), t + eta * u);
                    eta *= u.max(1e-3 * h);
                    end = None;
                    break;
                }
                _ => {}
            }
        }
        (x, v, t) = (eval(&time.x, h), eval(&time.v, h), t + eta * h);
        eta *= h;
        if let (Some((x_max, t_max)), true, None) = (max, watch_manifold, point) {
            if let Some(y) = on_manifold(&s, x, v) {
                let p = ManifoldPoint {
                    x: s.unit * x,
                    tau: s.unit * t,
                    y,
                };
                if ending == Ending::Manifold {
                    let k = manifold::constants();
                    let a = s.damping;
                    let c = Collision {
                        vstar,
                        criterion,
                        eps: (k.exit_speed * a.powi(-5)).min(1.0),
                        duration: p.tau
                            + a * ((p.x * a.powi(4)).ln() + k.offset + manifold::rest(y)),
                        max_compression: s.unit * x_max,
                        time_of_max_compression: s.unit * t_max,
                        compression_at_end: 0.0,
                        separated: true,
                    };
                    return Ok((c, Some(p)));
                }
                point = Some(p);
            }
        }
    }
    let (x_max, t_max) = max.expect("the phase ends after maximal compression");

    let (tau_c, x_end, v_end) = match end {
        Some(e) => e,
        None => {
            // Phase 3: root chart, w decreasing to the zero of the force or to 0.
            let mut w = x.sqrt();
            let p = s.velocity(x, v).abs();
            let mut eta = -(eta * p / (2.0 * w)).min(0.5 * w);
            loop {
                count(&mut steps)?;
                rj.expand(&s, w, eta, v, t);
                let mut h = step_size(&[&rj.v, &rj.t], 2);
                let last = h >= w / -eta;
                if last {
                    h = w / -eta;
                }
                if improved {
                    let f = rj.force(&s);
                    if eval(&f, h) <= 0.0 {
                        // For small A the zero lies at w_c ~ v* << w: the polynomial about
                        // w loses the digits of w_c to cancellation. Re-expand at the root
                        // found and find it again in a window of +-1 % around it.
                        let u = root(&f, 0.0, 0.0, h);
                        let wa = w + eta * u;
                        let (va, ta) = (eval(&rj.v, u), eval(&rj.t, u));
                        let local = -0.01 * wa;
                        rj.expand(&s, wa, local, va, ta);
                        let f = rj.force(&s);
                        let u = if (eval(&f, -1.0) > 0.0) != (eval(&f, 1.0) > 0.0) {
                            root(&f, 0.0, -1.0, 1.0)
                        } else {
                            0.0
                        };
                        let wc = wa + local * u;
                        break (eval(&rj.t, u), wc * wc, eval(&rj.v, u));
                    }
                }
                if last {
                    break (eval(&rj.t, h), 0.0, eval(&rj.v, h));
                }
                (w, v, t) = (w + eta * h, eval(&rj.v, h), eval(&rj.t, h));
                eta *= h;
            }
        }
    };
    let p_end = s.velocity(x_end, v_end);
    Ok((
        Collision {
            vstar,
            criterion,
            eps: (-p_end).min(1.0),
            duration: s.unit * tau_c,
            max_compression: s.unit * x_max,
            time_of_max_compression: s.unit * t_max,
            compression_at_end: s.unit * x_end.max(0.0),
            separated: true,
        },
        point,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The AVX2 build of the integrator gives the same bits as the baseline one.
    #[test]
    fn avx2_and_baseline_agree_bit_for_bit() {
        for c in [Criterion::Improved, Criterion::Naive] {
            for v in [0.0, 1e-3, 0.3, 1.0, 2.0, 3.0, 10.0, 1e3, 1e6] {
                let a = run(v, c, Ending::Manifold).unwrap().0;
                let b = run_body(v, c, Ending::Manifold).unwrap().0;
                assert_eq!(a, b, "{c} {v}");
            }
        }
    }

    /// P* and K are universal: measured again at v* = 6 and 10 (integrating the creep to
    /// x = 0, 2e2 and 1e3 explicit steps), they agree with the calibration at v* = 4. This
    /// checks the scale invariance, the manifold series and the deviation test at once.
    #[test]
    fn manifold_constants_are_universal() {
        let k = manifold::constants();
        for v in [6.0, 10.0] {
            let (c, point) = run(v, Criterion::Naive, Ending::Integrate).unwrap();
            let p = point.unwrap();
            let a = v * v;
            let exit = c.eps * a.powi(5);
            let offset = (c.duration - p.tau) / a - (p.x * a.powi(4)).ln() - manifold::rest(p.y);
            let d = [
                (exit - k.exit_speed).abs() / k.exit_speed,
                (offset - k.offset).abs() / k.offset.abs(),
            ];
            println!(
                "v* = {v}: P* {exit:.16e} K {offset:.16e}, rel. diff. {:.1e} {:.1e}",
                d[0], d[1]
            );
            assert!(d[0] < 1e-13 && d[1] < 1e-12, "v* = {v}: {d:?}");
        }
    }
}
