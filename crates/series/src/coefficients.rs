//! The coefficients h, c, a, b of SP2008 by the chain of their Appendices B and C: from the
//! exact trajectory to the time and value of maximal compression (a_n, b_n), the naive
//! coefficient of restitution (c_n), the premature end of contact (Eqs. C4, C5) and the
//! delayed-recovery series h_k (Eq. C7).
//!
//! All in the natural units of Eq. (9) of MP2011 (impact speed 1, A = v*^2):
//!
//! 1. **Elastic turning point.** tau_max^0 is the root of x_0'(tau) (Eq. 28 gives it in
//!    Gamma functions; here it is found from the series itself, to the working precision).
//! 2. **Maximal compression (App. B).** x(tau_max^0 + d; A) is expanded in d with
//!    coefficients that are power series in A: x and x' at tau_max^0 come from the exact
//!    trajectory, all higher d-derivatives from the equation of motion by the Taylor
//!    recurrence at that regular point (this avoids differentiating the slowly converging
//!    sqrt(tau) series many times). Then x'(tau_max^0 + d) = 0 gives d = sum a_n A^n (Eq. B3)
//!    and x_max = sum b_n A^n (Eq. B5), by Newton iteration on power series.
//! 3. **Naive end (App. B).** The inverse collision (time reversed, damping -A, speed eps)
//!    reaches the same maximal compression: b(A) = e^4 b(-A e) with e = eps^(1/5) (Eq. B6 in
//!    these units); eps_naive = e^5 = sum c_n A^n (Eq. B9).
//! 4. **Premature end (App. C).** In the inverse collision with damping parameter B the
//!    force vanishes at T = B phi, x_inv(T) = B x_inv'(T) (Eq. C1); with b = B^(1/2) phi and
//!    G = x_inv'(T) are power series in b with *rational* coefficients (Eqs. C4, C5).
//! 5. **eps = eps_naive(A) G(b)** with b = (A e)^(1/2) = v* e^(1/2) (Eq. C6): h_k.

use crate::power::{real, Real, Scalar, Series};
use crate::trajectory::Trajectory;
use crate::Error;
use dashu_ratio::RBig;

/// Largest index k of one family that the haff command and Python compute (h_100 takes
/// about a minute).
pub const MAX_ORDER: usize = 100;
/// Most significant digits printed of a coefficient.
pub const MAX_DIGITS: usize = 60;
/// The longest a call of the haff command or Python may compute coefficients (bounded
/// work; see [`Settings::estimated_seconds`]).
pub const MAX_SECONDS: f64 = 60.0;

/// How far and how precisely to compute.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Settings {
    /// Highest power K of v* in eps = sum_{k<=K} h_k v*^k.
    pub order: usize,
    /// Order N of the trajectory series in sqrt(tau) (SP2008 use 150 for K = 20).
    pub trajectory_order: usize,
    /// Working precision in bits.
    pub bits: usize,
}

impl Settings {
    /// Defaults that converge every coefficient to more than 18 significant digits for
    /// K <= 60 (N = 150 for K <= 25, as SP2008; see the convergence tests).
    pub fn for_order(order: usize) -> Self {
        Settings {
            order,
            trajectory_order: 150.max(100 + 2 * order),
            bits: 256.max(128 + 4 * order),
        }
    }

    /// The seconds the chain takes on this machine kind, fitted to measurements of
    /// `haff cor coefficients` (chain order K, trajectory order N, bits): (20, 150, 256)
    /// 0.32 s, (20, 300, 256) 2.3 s, (20, 150, 1024) 0.50 s, (40, 300, 256) 7.1 s,
    /// (c: 100, 300, 512) 33 s, (h: 100, 300, 528) 40 s; the fit is within 15 % of each.
    pub fn estimated_seconds(&self) -> f64 {
        0.32 * (self.trajectory_order as f64 / 150.0).powf(2.85)
            * (self.bits as f64 / 256.0).powf(0.32)
            * (self.order.max(2) as f64 / 20.0).powf(1.6)
    }
}

/// The coefficients 0..=`order` of `kind`, computed with `settings` (whose chain order
/// must cover `kind.chain_order(order)`). Only h needs the premature end of contact, the
/// costly part at high order; a, b and c come from the naive chain.
pub fn of_kind(kind: Kind, order: usize, settings: Settings) -> Result<Vec<Real>, crate::Error> {
    let chain = if kind == Kind::H {
        compute(settings)
    } else {
        compute_naive(settings)
    };
    let values = chain.of(kind);
    if values.len() <= order {
        return Err(crate::Error::OrderBeyondChain {
            order,
            provided: values.len(),
        });
    }
    Ok(values[..=order].to_vec())
}

/// Every coefficient of the chain.
#[derive(Debug, Clone)]
pub struct Coefficients {
    pub settings: Settings,
    /// tau_max^0, the time of maximal compression of the elastic collision (Eq. 28).
    pub tau_max0: Real,
    /// a_0 = tau_max^0, a_n: tau_max = sum a_n A^n (Eq. B3, Table III).
    pub a: Vec<Real>,
    /// b_n: x_max = sum b_n A^n (Eq. B5, Table III).
    pub b: Vec<Real>,
    /// c_n: eps_naive = sum c_n A^n, c_0 = 1 (Eq. B9, Table III).
    pub c: Vec<Real>,
    /// h_k: eps = sum h_k v*^k, h_0 = 1 (Eq. C7, Table V).
    pub h: Vec<Real>,
}

/// Runs the whole chain.
pub fn compute(settings: Settings) -> Coefficients {
    run(settings, true)
}

/// Runs the chain up to the naive coefficient of restitution only (a, b, c; `h` is left
/// empty): what `settings.order` = 2K costs for c_0..c_K without the premature end.
pub fn compute_naive(settings: Settings) -> Coefficients {
    run(settings, false)
}

fn run(settings: Settings, with_delayed_recovery: bool) -> Coefficients {
    let k = settings.order;
    let degree = k.div_ceil(2).max(1);
    let premature_len = if with_delayed_recovery { k + 1 } else { 0 };
    let order = settings.trajectory_order.max(premature_len + 2);
    let trajectory = Trajectory::new(order, degree.max(premature_len / 2 + 1));
    let bits = settings.bits;
    let tau_max0 = elastic_turning_time(&trajectory, bits);
    let (a, b) = maximal_compression(&trajectory, &tau_max0, degree, bits);
    let e = naive_fifth_root(&b);
    let five_c = e.power(5, 1);
    let h = if with_delayed_recovery {
        let one = Series::constant(real(&RBig::ONE, bits), premature_len);
        let (_, g) = premature_end(&trajectory, &one.c[0], premature_len);
        delayed_recovery(&five_c, &e, &g, premature_len)
    } else {
        Series::constant(tau_max0.zero_like(), 1)
    };
    let mut a_all = vec![tau_max0.clone()];
    a_all.extend(a.c.into_iter().skip(1));
    Coefficients {
        settings,
        tau_max0,
        a: a_all,
        b: b.c,
        c: five_c.c,
        h: if with_delayed_recovery {
            h.c
        } else {
            Vec::new()
        },
    }
}

/// The root of x_0'(tau) = sum_j X_j(0) (j/2) s^(j-2) = 0 in s = sqrt(tau), by Newton from
/// the f64 value of Eq. (28); returns tau.
fn elastic_turning_time(trajectory: &Trajectory, bits: usize) -> Real {
    let elastic: Vec<(usize, Real)> = trajectory
        .terms()
        .filter(|(_, i, _)| *i == 0)
        .map(|(j, _, c)| (j, real(c, bits)))
        .collect();
    let mut s = real(&RBig::ONE, bits).ratio_like(12685, 10000);
    for _ in 0..(bits / 8 + 10) {
        let (mut f, mut df) = (s.zero_like(), s.zero_like());
        for (j, c) in &elastic {
            let half_j = s.ratio_like(*j as i64, 2);
            f = f.add(&c.mul(&half_j).mul(&pow(&s, j - 2)));
            if *j > 2 {
                let factor = half_j.mul(&s.ratio_like(*j as i64 - 2, 1));
                df = df.add(&c.mul(&factor).mul(&pow(&s, j - 3)));
            }
        }
        let step = f.div(&df);
        s = s.sub(&step);
        if step.is_zero() || step.to_f64().value().abs() < 2f64.powi(-(bits as i32) + 8) {
            break;
        }
    }
    s.mul(&s)
}

fn pow(x: &Real, n: usize) -> Real {
    (0..n).fold(x.one_like(), |acc, _| acc.mul(x))
}

/// x and x' at tau_max^0 as power series in A (length degree + 1), from the trajectory.
fn state_at(trajectory: &Trajectory, tau: &Real, degree: usize) -> (Series<Real>, Series<Real>) {
    let s = tau.sqrt();
    let powers: Vec<Real> = std::iter::successors(Some(s.one_like()), |p| Some(p.mul(&s)))
        .take(trajectory.order() + 1)
        .collect();
    let mut x = Series::zeros(tau, degree + 1);
    let mut v = Series::zeros(tau, degree + 1);
    for (j, i, c) in trajectory.terms() {
        if i > degree {
            continue;
        }
        let c = real(c, tau.precision());
        x.c[i] = x.c[i].add(&c.mul(&powers[j]));
        let dv = c.mul(&tau.ratio_like(j as i64, 2)).mul(&powers[j - 2]);
        v.c[i] = v.c[i].add(&dv);
    }
    (x, v)
}

/// Taylor coefficients u_k (k < count) of x(tau_max^0 + d) in d, each a series in A, from
/// u_0, u_1 and the equation of motion u'' = -sqrt(u) (u + A u').
fn taylor_at(u0: Series<Real>, u1: Series<Real>, count: usize) -> Vec<Series<Real>> {
    let mut u = vec![u0, u1];
    let mut root: Vec<Series<Real>> = vec![u[0].sqrt()];
    let two_root_inv = root[0].scale(&root[0].c[0].ratio_like(2, 1)).inverse();
    for k in 0..count.saturating_sub(2) {
        if k >= 1 {
            let cross = (1..k).fold(Series::zeros(&u[0].c[0], u[0].len()), |acc, i| {
                acc.add(&root[i].mul(&root[k - i]))
            });
            root.push(u[k].sub(&cross).mul(&two_root_inv));
        }
        // G_i = u_i + A (i + 1) u_{i+1}; H_k = sum_i S_i G_{k-i}.
        let g = |i: usize| {
            let factor = u[i].c[0].ratio_like(i as i64 + 1, 1);
            u[i].add(&u[i + 1].scale(&factor).shift(1))
        };
        let h = (0..=k).fold(Series::zeros(&u[0].c[0], u[0].len()), |acc, i| {
            acc.add(&root[i].mul(&g(k - i)))
        });
        let divisor = u[0].c[0].ratio_like(-((k as i64 + 1) * (k as i64 + 2)), 1);
        u.push(h.scale(&divisor.one_like().div(&divisor)));
    }
    u
}

/// (tau_max - tau_max^0, x_max) as series in A (Eqs. B3, B5).
fn maximal_compression(
    trajectory: &Trajectory,
    tau_max0: &Real,
    degree: usize,
    bits: usize,
) -> (Series<Real>, Series<Real>) {
    let _ = bits;
    let (u0, u1) = state_at(trajectory, tau_max0, degree);
    let u = taylor_at(u0, u1, degree + 3);
    // x'(d) = sum_k (k+1) u_{k+1} d^k and its derivative.
    let weighted = |from: usize, factor: &dyn Fn(usize) -> i64| -> Vec<Series<Real>> {
        (from..u.len())
            .map(|k| u[k].scale(&u[k].c[0].ratio_like(factor(k), 1)))
            .collect()
    };
    let velocity = weighted(1, &|k| k as i64);
    let acceleration = weighted(2, &|k| (k * (k - 1)) as i64);
    let mut d = Series::zeros(&u[0].c[0], degree + 1);
    for _ in 0..newton_iterations(degree + 1) {
        let f = d.compose(&velocity);
        let df = d.compose(&acceleration);
        d = d.sub(&f.mul(&df.inverse()));
        d.c[0] = d.c[0].zero_like();
    }
    let x_max = d.compose(&u);
    (d, x_max)
}

/// Newton iterations to fix `len` coefficients of a power series (doubling per step).
fn newton_iterations(len: usize) -> usize {
    (usize::BITS - len.leading_zeros()) as usize + 2
}

/// e = eps_naive^(1/5) from b(A) = e^4 b(-A e) (Eqs. B6–B9).
fn naive_fifth_root(b: &Series<Real>) -> Series<Real> {
    let len = b.len();
    let one = b.c[0].one_like();
    let derivative: Vec<Real> = (1..len)
        .map(|n| b.c[n].mul(&one.ratio_like(n as i64, 1)))
        .collect();
    let mut e = Series::constant(one.clone(), len);
    for _ in 0..newton_iterations(len) {
        let y = e.shift(1).scale(&one.ratio_like(-1, 1));
        let e4 = e.power(4, 1);
        let by = y.compose_scalar(&b.c);
        let dby = y.compose_scalar(&derivative);
        let f = e4.mul(&by).sub(b);
        let df = e
            .power(3, 1)
            .mul(&by)
            .scale(&one.ratio_like(4, 1))
            .sub(&e4.mul(&dby).shift(1));
        e = e.sub(&f.mul(&df.inverse()));
    }
    e
}

/// phi and G of the premature end (App. C) as series in b = B^(1/2), length `len`:
/// T = B phi(b) and x_inv'(T) = G(b). Exact with T = RBig.
pub fn premature_end<T: Scalar + FromRational>(
    trajectory: &Trajectory,
    model: &T,
    len: usize,
) -> (Series<T>, Series<T>) {
    // Terms w b^e with w = c_{j,i} (-1)^i, e = j + 2 i - 2 < len.
    let terms: Vec<(usize, usize, T)> = trajectory
        .terms()
        .filter(|(j, i, _)| j + 2 * i - 2 < len)
        .map(|(j, i, c)| {
            let w = T::from_rational(c, model);
            let w = if i % 2 == 1 {
                model.zero_like().sub(&w)
            } else {
                w
            };
            (j, j + 2 * i - 2, w)
        })
        .collect();
    let one = model.one_like();
    let mut phi = Series::constant(one.clone(), len);
    let max_j = terms.iter().map(|t| t.0).max().unwrap_or(2);
    let term_sum = |r_pow: &[Series<T>], f: &dyn Fn(usize) -> Option<(T, usize)>| {
        terms
            .iter()
            .fold(Series::zeros(model, len), |acc, (j, e, w)| match f(*j) {
                Some((factor, power)) => acc.add(&r_pow[power].scale(&w.mul(&factor)).shift(*e)),
                None => acc,
            })
    };
    let powers_of = |phi: &Series<T>| -> Vec<Series<T>> {
        let r = phi.power(1, 2);
        std::iter::successors(Some(Series::constant(one.clone(), len)), |p| {
            Some(p.mul(&r))
        })
        .take(max_j + 1)
        .collect()
    };
    for _ in 0..newton_iterations(len) {
        let r_pow = powers_of(&phi);
        let half = |j: usize| one.ratio_like(j as i64, 2);
        // F = sum w b^e (r^j - (j/2) r^(j-2)), F' = sum w b^e ((j/2) r^(j-2) - (j/2)(j/2-1) r^(j-4)).
        let f = term_sum(&r_pow, &|j| Some((one.clone(), j)))
            .sub(&term_sum(&r_pow, &|j| Some((half(j), j - 2))));
        let df = term_sum(&r_pow, &|j| Some((half(j), j - 2))).sub(&term_sum(&r_pow, &|j| {
            (j >= 4).then(|| (half(j).mul(&half(j).sub(&one)), j - 4))
        }));
        phi = phi.sub(&f.mul(&df.inverse()));
    }
    let r_pow = powers_of(&phi);
    let g = term_sum(&r_pow, &|j| Some((one.ratio_like(j as i64, 2), j - 2)));
    (phi, g)
}

/// Scalars that can be made from an exact rational.
pub trait FromRational: Scalar {
    fn from_rational(r: &RBig, model: &Self) -> Self;
}

impl FromRational for RBig {
    fn from_rational(r: &RBig, _model: &Self) -> Self {
        r.clone()
    }
}

impl FromRational for Real {
    fn from_rational(r: &RBig, model: &Self) -> Self {
        real(r, model.precision())
    }
}

/// eps = eps_naive(A) G(b), b = v* e(A)^(1/2), as a series in v* of length `len` (Eq. C6).
fn delayed_recovery(
    eps_naive: &Series<Real>,
    e: &Series<Real>,
    g: &Series<Real>,
    len: usize,
) -> Series<Real> {
    let naive = eps_naive.spread(2, len);
    let b = e.spread(2, len).power(1, 2).shift(1);
    naive.mul(&b.compose_scalar(&g.c))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(n: i64, d: u64) -> RBig {
        RBig::from_parts(n.into(), d.into())
    }

    /// Eq. (C4): T = B + (4/35) B^(7/2) + (2/75) B^6 + (21271/2734875) B^(17/2), exactly.
    #[test]
    fn premature_end_time_eq_c4() {
        let t = Trajectory::new(24, 12);
        let (phi, _) = premature_end(&t, &RBig::ONE, 18);
        assert_eq!(phi.c[0], r(1, 1));
        assert_eq!(phi.c[5], r(4, 35));
        assert_eq!(phi.c[10], r(2, 75));
        assert_eq!(phi.c[15], r(21271, 2734875));
        for k in [1, 2, 3, 4, 6, 7, 8, 9, 11, 12, 13, 14, 16, 17] {
            assert_eq!(phi.c[k], RBig::ZERO, "b^{k}");
        }
    }
}

/// The coefficient families of the chain.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// eps = sum h_k v*^k (Table V of SP2008).
    H,
    /// eps_naive = sum c_k A^k (Table III).
    C,
    /// tau_max = sum a_k A^k, a_0 = tau_max^0 (Table III).
    A,
    /// x_max = sum b_k A^k (Table III).
    B,
}

impl std::str::FromStr for Kind {
    type Err = Error;
    /// One of the names of [`Kind::name`]; anything else is [`Error::UnknownKind`].
    fn from_str(s: &str) -> Result<Self, Error> {
        Kind::ALL
            .into_iter()
            .find(|kind| kind.name() == s)
            .ok_or_else(|| Error::UnknownKind {
                given: s.to_string(),
            })
    }
}

impl Kind {
    /// Every family, in the order error messages list them.
    pub const ALL: [Kind; 4] = [Kind::H, Kind::C, Kind::A, Kind::B];

    /// The name that parses to this family: "h", "c", "a" or "b".
    pub fn name(self) -> &'static str {
        match self {
            Kind::H => "h",
            Kind::C => "c",
            Kind::A => "a",
            Kind::B => "b",
        }
    }

    /// The chain order K needed for coefficients 0..=k of this family.
    pub fn chain_order(self, k: usize) -> usize {
        match self {
            Kind::H => k,
            _ => 2 * k,
        }
    }
}

impl Coefficients {
    /// The coefficients of one family (as many as the chain's order provides).
    pub fn of(&self, kind: Kind) -> &[Real] {
        match kind {
            Kind::H => &self.h,
            Kind::C => &self.c,
            Kind::A => &self.a,
            Kind::B => &self.b,
        }
    }
}

/// x as a decimal string with exactly `digits` significant digits (trailing zeros kept).
pub fn decimal(x: &Real, digits: usize) -> String {
    if *x == x.zero_like() {
        return "0".to_string();
    }
    let d = x.to_decimal().value();
    let mut text = d.with_precision(digits).value().to_string();
    if text.contains(['e', 'E']) {
        return text;
    }
    let significant = text
        .chars()
        .filter(char::is_ascii_digit)
        .skip_while(|&c| c == '0')
        .count();
    if significant < digits {
        if !text.contains('.') {
            text.push('.');
        }
        text.extend(std::iter::repeat_n('0', digits - significant));
    }
    text
}

/// h_0 ..= h_k as f64 (for laws), computed with the default settings.
pub fn restitution_coefficients_f64(k: usize) -> Vec<f64> {
    compute(Settings::for_order(k))
        .h
        .iter()
        .map(|x| x.to_f64().value())
        .collect()
}
