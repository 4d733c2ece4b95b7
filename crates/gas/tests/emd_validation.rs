//! Validations of the event-driven engine (issue 4) beyond `tests/emd.rs`: the viscoelastic
//! gas with the exact and the fast law, energy and momentum over 1e7 elastic collisions,
//! the TC model of Luding & McNamara, and binary mixtures against Enskog theory.
//!
//! Every bound is a computed statistical error (sample spread over seeds, batch means) or
//! a round-off model calibrated in the same run; none is a fitted margin.
//!
//! Default tests (about 10 s in release, single-threaded):
//! `cargo test --release -p haff-gas --test emd_validation`
//! The heavy versions (a few minutes, figures printed):
//! `cargo test --release -p haff-gas --test emd_validation -- --ignored --nocapture`

mod common;

use common::{constant, viscoelastic};
use gas::init::{monodisperse, polydisperse, Species};
use gas::observe::temperature;
use gas::Engine;
use gas::EventDriven;
use restitution::{Restitution, Viscoelastic};
use std::f64::consts::PI;
use std::sync::{Arc, Mutex};
use std::time::Instant;

// ---------------------------------------------------------------------------------------
// Helpers: statistics, exact (double-double) sums, laws that record what the engine asks.
// ---------------------------------------------------------------------------------------

fn mean(x: &[f64]) -> f64 {
    x.iter().sum::<f64>() / x.len() as f64
}

/// Sample standard deviation (n - 1 in the denominator).
fn sample_sd(x: &[f64]) -> f64 {
    let m = mean(x);
    (x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (x.len() - 1) as f64).sqrt()
}

/// A sum carried as hi + lo (Knuth's TwoSum, products split with one FMA): error of order
/// u^2 = 1.2e-32 times the terms, so the change of the energy of a whole gas is obtained
/// exactly enough to see the round-off of a single collision (~1e-16 of a pair energy).
#[derive(Debug, Clone, Copy, Default)]
struct Exact {
    hi: f64,
    lo: f64,
}

impl Exact {
    fn add(&mut self, x: f64) {
        let s = self.hi + x;
        let b = s - self.hi;
        self.lo += (self.hi - (s - b)) + (x - b);
        self.hi = s;
    }

    /// Adds a * b exactly (up to u^2).
    fn add_product(&mut self, a: f64, b: f64) {
        let p = a * b;
        self.add(p);
        self.lo += a.mul_add(b, -p);
    }

    /// Adds m * x^2 (m x^2 = m (p + e) with x^2 = p + e exactly).
    fn add_mass_square(&mut self, m: f64, x: f64) {
        let p = x * x;
        let e = x.mul_add(x, -p);
        self.add_product(m, p);
        self.lo += m * e;
    }

    /// self - other, rounded once.
    fn minus(&self, other: &Exact) -> f64 {
        (self.hi - other.hi) + (self.lo - other.lo)
    }

    fn value(&self) -> f64 {
        self.hi + self.lo
    }
}

/// Twice the kinetic energy, sum m v^2, of the particles `which`, exactly.
fn twice_energy<const D: usize>(
    velocities: &[[f64; D]],
    masses: &[f64],
    which: impl Iterator<Item = usize>,
) -> Exact {
    let mut e = Exact::default();
    for i in which {
        for x in velocities[i] {
            e.add_mass_square(masses[i], x);
        }
    }
    e
}

/// Total momentum of the particles `which`, exactly, per component.
fn momentum<const D: usize>(
    velocities: &[[f64; D]],
    masses: &[f64],
    which: impl Iterator<Item = usize> + Clone,
) -> [Exact; D] {
    std::array::from_fn(|k| {
        let mut p = Exact::default();
        for i in which.clone() {
            p.add_product(masses[i], velocities[i][k]);
        }
        p
    })
}

/// A law whose eps the engine uses, checked at every call against a reference law: the
/// largest relative difference and the number of calls are recorded.
#[derive(Debug, Clone)]
struct Checked {
    law: Viscoelastic,
    reference: Viscoelastic,
    record: Arc<Mutex<(f64, u64)>>,
}

impl Restitution for Checked {
    fn eps(&self, speed: f64) -> f64 {
        let (a, b) = (self.law.eps(speed), self.reference.eps(speed));
        let mut r = self.record.lock().unwrap();
        r.0 = r.0.max((a - b).abs() / b);
        r.1 += 1;
        a
    }
    fn describe(&self) -> String {
        format!(
            "{} checked against {}",
            self.law.describe(),
            self.reference.describe()
        )
    }
    fn box_clone(&self) -> Box<dyn Restitution> {
        Box::new(self.clone())
    }
}

/// A law that records every normal impact speed it is asked for.
#[derive(Debug, Clone)]
struct Recording {
    law: Viscoelastic,
    speeds: Arc<Mutex<Vec<f64>>>,
}

impl Restitution for Recording {
    fn eps(&self, speed: f64) -> f64 {
        self.speeds.lock().unwrap().push(speed);
        self.law.eps(speed)
    }
    fn describe(&self) -> String {
        format!("{} (recording)", self.law.describe())
    }
    fn box_clone(&self) -> Box<dyn Restitution> {
        Box::new(self.clone())
    }
}

/// Steps until one more collision has been processed (false if nothing moves).
fn next_collision<const D: usize>(e: &mut EventDriven<D>) -> bool {
    let target = e.counters().collisions + 1;
    while e.counters().collisions < target {
        if !e.step() {
            return false;
        }
    }
    true
}

// ---------------------------------------------------------------------------------------
// 1. Viscoelastic gas: the exact law and the fast law.
// ---------------------------------------------------------------------------------------

/// ln T at the given times of a 3D gas (m = sigma = 1, T0 = 1) cooling with `law`.
fn log_temperatures(
    law: Box<dyn Restitution>,
    n: usize,
    phi: f64,
    seed: u64,
    times: &[f64],
) -> Vec<f64> {
    let system = monodisperse::<3>(n, phi, 1.0, 1.0, 1.0, seed).unwrap();
    let mut e = EventDriven::new(system, law).unwrap();
    common::log_temperatures(&mut e, times)
}

/// T(t) of a viscoelastic gas (beta = 1: v* = beta^(1/2) g^(1/10) ~ 0.7 .. 1.1 for the
/// normal impact speeds g of T = 1e-4 .. 1, where eps = 0.6 .. 0.37 varies fastest; Eq. (7)
/// of MP2011), `exact_seeds` runs with the exact law against `fast_seeds` independent runs
/// with the fast law. At each time the two-sample statistic
///
///   z = (<ln T>_exact - <ln T>_fast) / (s sqrt(1/K_exact + 1/K_fast))
///
/// uses the spread s of ln T over the fast runs (K_fast - 1 degrees of freedom) for both
/// laws: under the hypothesis tested they are the same physics (eps equal to 1e-12), so
/// they have the same variance. |z| < 4 at every time: a false alarm has probability
/// ~6e-5 per time for Gaussian means. The exact runs evaluate the fast law alongside and
/// report the largest relative eps difference over all their collisions. The power of the
/// test is shown with independent fast-law runs at beta = 1.1 (v* 4.9 % larger), compared
/// with the exact runs in the same way.
fn exact_against_fast(
    n: usize,
    times: &[f64],
    exact_seeds: u64,
    fast_seeds: u64,
) -> (Vec<f64>, Vec<f64>, f64, u64) {
    let (phi, beta) = (0.05, 1.0);
    let record = Arc::new(Mutex::new((0.0, 0)));
    let clock = Instant::now();
    let exact: Vec<Vec<f64>> = (1..=exact_seeds)
        .map(|seed| {
            let law = Checked {
                law: viscoelastic(beta, "exact"),
                reference: viscoelastic(beta, "fast"),
                record: record.clone(),
            };
            log_temperatures(Box::new(law), n, phi, seed, times)
        })
        .collect();
    let exact_time = clock.elapsed().as_secs_f64();
    let runs = |beta: f64, first: u64| -> Vec<Vec<f64>> {
        (first..first + fast_seeds)
            .map(|seed| log_temperatures(Box::new(viscoelastic(beta, "fast")), n, phi, seed, times))
            .collect()
    };
    let fast = runs(beta, 1001);
    let perturbed = runs(1.1 * beta, 2001);
    let (worst, calls) = *record.lock().unwrap();
    eprintln!(
        "N = {n}: {exact_seeds} exact runs ({calls} collisions, {:.3} ms each), {fast_seeds} fast runs; worst |eps_fast/eps_exact - 1| = {worst:.2e}",
        1e3 * exact_time / calls as f64
    );
    let column = |runs: &Vec<Vec<f64>>, k: usize| runs.iter().map(|r| r[k]).collect::<Vec<f64>>();
    let (mut z, mut z_perturbed) = (vec![], vec![]);
    for (k, t) in times.iter().enumerate() {
        let (e, f, p) = (column(&exact, k), column(&fast, k), column(&perturbed, k));
        let s = sample_sd(&f);
        let sigma = s * (1.0 / exact_seeds as f64 + 1.0 / fast_seeds as f64).sqrt();
        z.push((mean(&e) - mean(&f)) / sigma);
        z_perturbed.push((mean(&e) - mean(&p)) / sigma);
        eprintln!(
            "t = {t:>6}: T_exact = {:.5e}, T_fast = {:.5e}, sd(ln T) per run {s:.4}, sigma of the difference {sigma:.4}, z = {:+.2}; fast at 1.1 beta: z = {:+.1}",
            mean(&e).exp(),
            mean(&f).exp(),
            z[k],
            z_perturbed[k]
        );
    }
    (z, z_perturbed, worst, calls)
}

/// The default version: N = 250, 4 exact runs to t = 50 (T falls to 0.025, about 13
/// collisions per particle, 6600 exact collisions), 64 fast runs. The spread of ln T per
/// run is 0.04 .. 0.07 here, so this resolves differences of T of about 10 % (4 sigma);
/// the heavy version below resolves 4 %. Measured: |z| <= 1.15, eps agreement 6.6e-14.
#[test]
fn viscoelastic_exact_and_fast_laws_cool_alike() {
    let times = [2.0, 5.0, 10.0, 20.0, 50.0];
    let (z, _, worst, calls) = exact_against_fast(250, &times, 4, 64);
    assert!(calls > 5000, "{calls}");
    assert!(worst < 1e-12, "eps differs by {worst}");
    for (t, z) in times.iter().zip(&z) {
        assert!(z.abs() < 4.0, "t = {t}: z = {z}");
    }
}

/// The heavy version: N = 1000, 8 exact runs to t = 5000 (T falls to 7e-6, about 50
/// collisions per particle, 2e5 exact collisions), 64 fast runs; sigma of the difference
/// of ln T about 0.011. That the test has power is asserted too: the fast law at
/// beta = 1.1 is resolved (|z| > 4) at the last time (with beta = 1.05 we measured z = 4.2
/// there, so 1.1 is expected near 8). Measured (116 s; 0.23 .. 0.41 ms per exact collision
/// on a shared machine): |z| <= 2.15 over the 11 times, eps agreement 6.7e-14 over all
/// 2.0e5 exact collisions, beta = 1.1 resolved with z = 8.5.
/// `cargo test --release -p haff-gas --test emd_validation -- --ignored --nocapture viscoelastic_exact_and_fast_laws_cool_alike_heavy`
#[test]
#[ignore]
fn viscoelastic_exact_and_fast_laws_cool_alike_heavy() {
    let times = [
        2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0, 5000.0,
    ];
    let (z, z_perturbed, worst, _) = exact_against_fast(1000, &times, 8, 64);
    assert!(worst < 1e-12, "eps differs by {worst}");
    for (t, z) in times.iter().zip(&z) {
        assert!(z.abs() < 4.0, "t = {t}: z = {z}");
    }
    assert!(z_perturbed.last().unwrap().abs() > 4.0, "{z_perturbed:?}");
}

/// The fast law (tabulated twice: in v* to ~1e-13, and in the physical speed v on top)
/// equals the exact law at the impact speeds a cooling viscoelastic gas actually produces:
/// a fast-law run (N = 1000, beta = 1, 100 collisions per particle) records all 5e4
/// normal impact speeds (measured: 1.6e-6 .. 4.3, v* 0.26 .. 1.16, eps 0.31 .. 0.92); the exact law is evaluated at 1001 of them evenly
/// spaced in rank (the slowest and fastest included). Bound: 1e-12 relative, the sum of
/// the two tables' interpolation errors (<= 1e-13 each, docs/collision-laws.md) and the
/// exact solver's own tolerance (1e-12, `laws::exact_law_tolerance_ladder`).
#[test]
fn fast_law_equals_exact_law_at_the_impact_speeds_of_a_gas() {
    let speeds = Arc::new(Mutex::new(Vec::new()));
    let law = Recording {
        law: viscoelastic(1.0, "fast"),
        speeds: speeds.clone(),
    };
    let system = monodisperse::<3>(1000, 0.05, 1.0, 1.0, 1.0, 5).unwrap();
    let mut e = EventDriven::new(system, Box::new(law)).unwrap();
    e.run_collisions(50_000);
    let mut speeds = speeds.lock().unwrap().clone();
    speeds.sort_by(f64::total_cmp);
    let (fast, exact) = (viscoelastic(1.0, "fast"), viscoelastic(1.0, "exact"));
    let mut worst: f64 = 0.0;
    let (mut eps_min, mut eps_max) = (1.0f64, 0.0f64);
    for r in 0..=1000 {
        let v = speeds[r * (speeds.len() - 1) / 1000];
        let (a, b) = (fast.eps(v), exact.eps(v));
        worst = worst.max((a - b).abs() / b);
        eps_min = eps_min.min(b);
        eps_max = eps_max.max(b);
    }
    eprintln!(
        "{} impact speeds from {:.3e} to {:.3e} (v* {:.3} .. {:.3}, eps {eps_min:.4} .. {eps_max:.4}): worst relative difference {worst:.2e}",
        speeds.len(),
        speeds[0],
        speeds[speeds.len() - 1],
        exact.vstar(speeds[0]),
        exact.vstar(speeds[speeds.len() - 1])
    );
    assert!(worst < 1e-12, "{worst}");
    // The run covers the regime where eps varies, from strongly to weakly dissipative
    // (measured: eps from 0.311 to 0.924, v* from 0.26 to 1.16).
    assert!(eps_min < 0.35 && eps_max > 0.9, "{eps_min} {eps_max}");
}

// ---------------------------------------------------------------------------------------
// 2. Elastic gas: energy and momentum to round-off.
// ---------------------------------------------------------------------------------------

/// Round-off of energy and momentum over `total` elastic collisions, against a model of the
/// round-off calibrated on `calibration` collisions of the same run, evenly spread over it.
///
/// Energy and momentum change only in collisions, by round-off of the velocity update and
/// of the unit normal (any exactly unit normal conserves both). For each calibration
/// collision the pair that collided is identified and its change of sum m v^2 and of
/// sum m v computed exactly (double-double, [`Exact`]): per-collision mean mu and spread s.
/// For the other M = total - K collisions the model (independent round-off errors,
/// sampled evenly, so that a slow change of their distribution is averaged alike) predicts
/// the change M mu_hat with variance M s^2 + M^2 s^2 / K (random walk plus the uncertainty
/// of the calibrated bias); the measured change (exact, from the whole state) must lie
/// within 5 such standard deviations. An error beyond round-off would exceed it.
///
/// Measured: the round-off is biased when the contact distance is a power of two
/// (sigma = 1 or 2: mean +0.29 standard deviations, +5.5e-16 of sum m v^2 ~ 6 T per
/// collision; none at sigma = 0.75, 1.2, 1.5), so the energy drifts linearly, by
/// 5.5e-16 M / (3 N T): 9.5e-15 after 1e5 collisions of N = 2000, 1.8e-13 after 1e7 of
/// N = 1e4. In isolation |r/|r||^2 - 1 has mean +0.62 u and spread 1.16 u for |r| near 1
/// (a binade boundary), and the energy error of an elastic collision is
/// 2 mu (g.n)^2 (|n|^2 - 1). The model calibrates the bias, so the test still checks that
/// nothing but this round-off changes the energy.
/// Returns the relative energy drift |dE|/E and the relative momentum |dP| / sum m |v|
/// over the whole run.
fn conservation_to_round_off(e: &mut EventDriven<3>, calibration: u64, total: u64) -> (f64, f64) {
    let n = e.system().len();
    let masses = e.system().masses.clone();
    let all = 0..n;
    let (e0, p0) = {
        let v = &e.system().velocities;
        (
            twice_energy(v, &masses, all.clone()),
            momentum(v, &masses, all.clone()),
        )
    };
    let scale: f64 = {
        let s = e.system();
        (0..n)
            .map(|i| s.masses[i] * (s.velocities[i].iter().map(|x| x * x).sum::<f64>()).sqrt())
            .sum()
    };
    let stride = total / calibration;
    let (mut de, mut dp) = (Vec::new(), Vec::new());
    let (mut cal_energy, mut cal_momentum) = (0.0, [0.0; 3]);
    let mut before = e.system().velocities.clone();
    for _ in 0..calibration {
        e.run_collisions(stride - 1);
        before.copy_from_slice(&e.system().velocities);
        assert!(next_collision(e));
        let after = &e.system().velocities;
        let changed: Vec<usize> = (0..n).filter(|&i| after[i] != before[i]).collect();
        assert!(changed.len() <= 2, "{changed:?}");
        let pair = || changed.iter().cloned();
        let delta =
            twice_energy(after, &masses, pair()).minus(&twice_energy(&before, &masses, pair()));
        de.push(delta);
        cal_energy += delta;
        let (after_p, before_p) = (
            momentum(after, &masses, pair()),
            momentum(&before, &masses, pair()),
        );
        for k in 0..3 {
            let d = after_p[k].minus(&before_p[k]);
            dp.push(d);
            cal_momentum[k] += d;
        }
    }
    e.run_collisions(total - stride * calibration);
    let (e1, p1) = {
        let v = &e.system().velocities;
        (
            twice_energy(v, &masses, all.clone()),
            momentum(v, &masses, all.clone()),
        )
    };
    let m = (total - calibration) as f64;
    let k = calibration as f64;
    let check = |name: &str, samples: &[f64], measured: f64| {
        let (mu, s) = (mean(samples), sample_sd(samples));
        let sigma = (m * s * s + m * m * s * s / k).sqrt();
        let z = (measured - m * mu) / sigma;
        eprintln!(
            "  {name}: per collision mean {mu:+.3e}, sd {s:.3e} (bias/sd = {:+.4}); other collisions: {measured:+.3e}, predicted {:+.3e} +- {sigma:.2e}, z = {z:+.2}",
            mu / s,
            m * mu
        );
        assert!(z.abs() < 5.0, "{name}: z = {z}");
    };
    let drift_e = e1.minus(&e0);
    check("sum m v^2", &de, drift_e - cal_energy);
    for c in 0..3 {
        let d = p1[c].minus(&p0[c]);
        check(
            &format!("P_{c}"),
            &dp[c..].iter().step_by(3).cloned().collect::<Vec<_>>(),
            d - cal_momentum[c],
        );
    }
    let dp_norm = (0..3)
        .map(|c| p1[c].minus(&p0[c]).powi(2))
        .sum::<f64>()
        .sqrt();
    (drift_e.abs() / e0.value(), dp_norm / scale)
}

fn elastic_run(n: usize, phi: f64, calibration: u64, total: u64) {
    let system = monodisperse::<3>(n, phi, 1.0, 1.0, 1.0, 42).unwrap();
    let mut e = EventDriven::new(system, constant(1.0)).unwrap();
    let clock = Instant::now();
    let (energy, momentum) = conservation_to_round_off(&mut e, calibration, total);
    eprintln!(
        "N = {n}, phi = {phi}, {total} collisions ({} per particle) in {:.1} s: |dE|/E = {energy:.2e}, |dP|/sum m|v| = {momentum:.2e}, energy lost (tally) {}",
        e.collisions_per_particle(),
        clock.elapsed().as_secs_f64(),
        e.counters().energy_lost
    );
    assert_eq!(e.counters().collisions, total);
    assert_eq!(e.counters().energy_lost, 0.0);
}

/// N = 2000, phi = 0.1, 1e5 collisions (every 20th for the calibration). Measured:
/// |dE|/E = 9.5e-15, |dP| / sum m|v| = 8e-18.
#[test]
fn elastic_energy_and_momentum_to_round_off() {
    elastic_run(2000, 0.1, 5_000, 100_000);
}

/// N = 1e4, phi = 0.1, 1e7 collisions (2000 per particle; every 500th for the calibration).
/// Measured: |dE|/E = 1.83e-13 (z = +0.27 against the calibrated round-off),
/// |dP| / sum m|v| = 2.3e-17; 46 s.
/// `cargo test --release -p haff-gas --test emd_validation -- --ignored --nocapture elastic_energy_over_1e7_collisions`
#[test]
#[ignore]
fn elastic_energy_over_1e7_collisions() {
    elastic_run(10_000, 0.1, 20_000, 10_000_000);
}

// ---------------------------------------------------------------------------------------
// 3. The TC model (Luding & McNamara, Granular Matter 1, 113 (1998)): a collision is
//    elastic if either partner collided less than tc before.
// ---------------------------------------------------------------------------------------

/// Every bit of the state, the time and the tally.
fn fingerprint<const D: usize>(e: &mut EventDriven<D>) -> Vec<u64> {
    let t = e.counters();
    let mut bits = vec![
        e.time().to_bits(),
        t.collisions,
        t.events,
        t.energy_lost.to_bits(),
        t.virial.to_bits(),
    ];
    let s = e.system();
    bits.extend(
        s.positions
            .iter()
            .chain(&s.velocities)
            .flatten()
            .map(|x| x.to_bits()),
    );
    bits
}

/// (a) tc = 0 is the engine without the TC model, bit for bit: positions, velocities,
/// time and tally after 5e4 collisions of an inelastic gas (eps = 0.8), also when the
/// model was switched on and off again before the run.
#[test]
fn tc_zero_is_the_engine_without_tc_bit_for_bit() {
    let system = monodisperse::<3>(500, 0.1, 1.0, 1.0, 1.0, 9).unwrap();
    let mut plain = EventDriven::new(system.clone(), constant(0.8)).unwrap();
    let mut zero = EventDriven::new(system.clone(), constant(0.8)).unwrap();
    zero.set_tc_model(0.0, None).unwrap();
    assert!(zero.tc_model().is_none());
    let mut toggled = EventDriven::new(system, constant(0.8)).unwrap();
    toggled.set_tc_model(0.5, None).unwrap();
    assert!(toggled.tc_model().is_some());
    toggled.set_tc_model(0.0, None).unwrap();
    for e in [&mut plain, &mut zero, &mut toggled] {
        e.run_collisions(50_000);
    }
    let reference = fingerprint(&mut plain);
    assert_eq!(reference, fingerprint(&mut zero));
    assert_eq!(reference, fingerprint(&mut toggled));
    assert!(plain.counters().energy_lost > 0.0);
}

/// The rate of collisions of a particle that has just collided, over the mean rate, in an
/// elastic 3D gas: kappa = <R^2>/<R>^2 with R(v) = <|v - w|>_w the mean relative speed of a
/// particle of speed v (a collision picks particles with weight R(v), and in equilibrium
/// the post-collisional velocities have the pre-collisional distribution). With x = v/s,
/// s = sqrt(T/m): R = s sqrt(2/pi) [exp(-x^2/2) + (x + 1/x) sqrt(pi/2) erf(x/sqrt 2)]
/// (the mean relative speed of a test particle in a Maxwellian gas; R(0) = <|w|>,
/// R -> v for v >> s). Midpoint quadrature over the Maxwell speed density
/// ~ x^2 exp(-x^2/2), checked by <R> = 4 s / sqrt(pi) = sqrt(2) <|v|>.
fn post_collision_rate_factor() -> f64 {
    let erf = |x: f64| {
        // Abramowitz & Stegun 7.1.26 is too coarse; integrate exp(-t^2) instead.
        let steps = 2000;
        let h = x / steps as f64;
        (0..steps)
            .map(|i| (-(h * (i as f64 + 0.5)).powi(2)).exp())
            .sum::<f64>()
            * h
            * 2.0
            / PI.sqrt()
    };
    let r = |x: f64| {
        (2.0 / PI).sqrt()
            * ((-x * x / 2.0).exp() + (x + 1.0 / x) * (PI / 2.0).sqrt() * erf(x / 2f64.sqrt()))
    };
    let (mut w, mut r1, mut r2) = (0.0, 0.0, 0.0);
    let h = 1e-3;
    for i in 0..12_000 {
        let x = h * (i as f64 + 0.5);
        let density = x * x * (-x * x / 2.0).exp();
        let rx = r(x);
        w += density;
        r1 += density * rx;
        r2 += density * rx * rx;
    }
    assert!((r1 / w - 4.0 / PI.sqrt()).abs() < 1e-6, "{}", r1 / w);
    (r2 / w) / (r1 / w).powi(2)
}

/// (b) tc much smaller than the mean free time (tc = 1e-3 / omega_0, omega_0 the Enskog
/// collision frequency at T0) in a cooling 3D gas (N = 1000, phi = 0.05, eps = 0.8):
///
/// 1. the TC run is bit-identical to the run without TC up to its first TC collision, where
///    the run without TC loses energy and the TC run does not (same time, same count);
/// 2. the number of TC collisions matches the rate at which a particle that just collided
///    collides again, 2 kappa omega tc per collision (both partners; kappa from
///    [`post_collision_rate_factor`], omega measured in the run), within 4 Poisson sigma:
///    a fraction of about 1e-3 (2 omega tc = 2e-3 at the start, less as the gas cools);
/// 3. ln T at 2, 5, 10, 20 and 30 collisions per particle matches the runs without TC
///    within 4 sigma (pooled spread over the seeds, sqrt(2/K) for the difference of two
///    means; the paired runs are positively correlated, which only makes this
///    conservative), after the predicted shift: each TC collision keeps the energy
///    (1 - eps^2) T that an inelastic one removes on average, raising ln T at a given
///    collision count by (1 - eps^2) 2/(N D) (cooling per collision does not depend on T).
///    The shift is at most 3.4e-3, a third of sigma.
///
/// Measured: kappa = 1.042; 113 TC collisions of 120000, predicted 115.8; |z| <= 1.7.
#[test]
fn tc_much_smaller_than_the_free_time_changes_nothing_measurable() {
    let (n, phi, eps, seeds) = (1000, 0.05, 0.8f64, 8u64);
    let density = phi / (PI / 6.0);
    let chi = (1.0 - phi / 2.0) / (1.0 - phi).powi(3);
    let omega0 = 4.0 * PI.sqrt() * density * chi; // T0 = m = sigma = 1
    let tc = 1e-3 / omega0;
    let kappa = post_collision_rate_factor();
    let per_particle = [2.0, 5.0, 10.0, 20.0, 30.0];
    let (mut plain_runs, mut tc_runs) = (vec![], vec![]);
    let (mut tc_count, mut predicted, mut collisions) = (0u64, 0.0, 0u64);
    let mut tc_at = vec![0.0; per_particle.len()];
    for seed in 1..=seeds {
        let system = monodisperse::<3>(n, phi, 1.0, 1.0, 1.0, 100 + seed).unwrap();
        // 1. Lockstep up to the first TC collision.
        let mut a = EventDriven::new(system.clone(), constant(eps)).unwrap();
        let mut b = EventDriven::new(system.clone(), constant(eps)).unwrap();
        b.set_tc_model(tc, None).unwrap();
        loop {
            let lost = b.counters().energy_lost;
            assert!(a.step() && b.step());
            assert_eq!(a.time().to_bits(), b.time().to_bits());
            assert_eq!(a.counters().collisions, b.counters().collisions);
            assert_eq!(a.counters().events, b.counters().events);
            if a.counters().energy_lost != b.counters().energy_lost {
                // The first difference: a collision that the TC run made elastic. Up to it
                // the states are identical: same positions, velocities different for the
                // colliding pair only.
                assert_eq!(b.counters().energy_lost, lost, "seed {seed}");
                assert!(a.counters().energy_lost > lost);
                let (sa, sb) = (a.system().clone(), b.system().clone());
                assert_eq!(sa.positions, sb.positions);
                let differ = (0..n)
                    .filter(|&i| sa.velocities[i] != sb.velocities[i])
                    .count();
                assert_eq!(differ, 2, "seed {seed}");
                break;
            }
            assert!(
                b.counters().collisions < 20_000,
                "seed {seed}: no TC collision"
            );
        }
        // 2. and 3. Fresh runs sampled at fixed collision counts.
        let mut plain = EventDriven::new(system.clone(), constant(eps)).unwrap();
        let mut with = EventDriven::new(system, constant(eps)).unwrap();
        with.set_tc_model(tc, None).unwrap();
        let (mut p, mut w) = (vec![], vec![]);
        let mut chunk_start = (0.0, 0u64);
        let mut seed_count = 0u64;
        for (k, &c) in per_particle.iter().enumerate() {
            let target = (c * n as f64 / 2.0) as u64;
            plain.run_collisions(target - plain.counters().collisions);
            p.push(temperature(plain.system()).ln());
            while with.counters().collisions < target {
                let lost = with.counters().energy_lost;
                assert!(next_collision(&mut with));
                if with.counters().energy_lost == lost {
                    seed_count += 1;
                }
                if with.counters().collisions % 500 == 0 {
                    let (t0, c0) = chunk_start;
                    let dc = with.counters().collisions - c0;
                    let omega = 2.0 * dc as f64 / (n as f64 * (with.time() - t0));
                    predicted += 2.0 * kappa * omega * tc * dc as f64;
                    chunk_start = (with.time(), with.counters().collisions);
                }
            }
            w.push(temperature(with.system()).ln());
            tc_at[k] += seed_count as f64;
        }
        collisions += with.counters().collisions;
        tc_count += seed_count;
        plain_runs.push(p);
        tc_runs.push(w);
    }
    let fraction = tc_count as f64 / collisions as f64;
    let z_count = (tc_count as f64 - predicted) / predicted.sqrt();
    eprintln!(
        "kappa = {kappa:.4}; TC collisions: {tc_count} of {collisions} (fraction {fraction:.2e}), predicted {predicted:.1}, z = {z_count:+.2}"
    );
    assert!(z_count.abs() < 4.0, "{tc_count} vs {predicted}");
    for (k, c) in per_particle.iter().enumerate() {
        let (p, w): (Vec<f64>, Vec<f64>) = (
            plain_runs.iter().map(|r| r[k]).collect(),
            tc_runs.iter().map(|r| r[k]).collect(),
        );
        let pooled = ((sample_sd(&p).powi(2) + sample_sd(&w).powi(2)) / 2.0).sqrt();
        let sigma = pooled * (2.0 / seeds as f64).sqrt();
        let shift = (1.0 - eps * eps) * 2.0 / (3.0 * n as f64) * tc_at[k] / seeds as f64;
        let z = (mean(&w) - mean(&p) - shift) / sigma;
        eprintln!(
            "{c:>4} collisions per particle: ln T with TC - without = {:+.5}, predicted shift {shift:+.5}, sigma {sigma:.5}, z = {z:+.2}",
            mean(&w) - mean(&p)
        );
        assert!(z.abs() < 4.0, "{c}: z = {z}");
    }
}

/// A 1D run of `budget` collisions: the time of every collision and, with the TC model on,
/// how many collisions it made elastic. The model's rule is applied independently of the
/// engine: after each collision the particles whose last-collision time changed are the
/// pair (fewer than two if a partner had collided at this very time, which is within tc),
/// and the collision is elastic iff one of them had collided less than tc before. The
/// engine's energy tally must agree: nothing lost in the collisions the rule makes elastic.
struct Run1d {
    times: Vec<f64>,
    elastic: u64,
    /// Collisions the rule makes elastic in which the engine nevertheless lost energy.
    elastic_with_loss: u64,
    /// Kinetic energy at the start and at the end, energy lost (tally).
    energy: (f64, f64, f64),
    /// The engine's collapse time, if it stopped there.
    collapsed: Option<f64>,
}

fn run_1d(n: usize, phi: f64, eps: f64, tc: f64, budget: u64, seed: u64) -> Run1d {
    let system = monodisperse::<1>(n, phi, 1.0, 1.0, 1.0, seed).unwrap();
    let mut e = EventDriven::new(system, constant(eps)).unwrap();
    e.set_tc_model(tc, None).unwrap();
    let e0 = twice_energy(&e.system().velocities, &vec![1.0; n], 0..n).value() / 2.0;
    let mut shadow = vec![f64::NEG_INFINITY; n];
    let (mut times, mut elastic, mut elastic_with_loss) = (Vec::new(), 0, 0);
    while e.counters().collisions < budget && e.counters().events < 20 * budget {
        let (collisions, lost) = (e.counters().collisions, e.counters().energy_lost);
        if !e.step() {
            assert!(
                e.collapsed().is_some(),
                "the engine stopped without collapse"
            );
            break;
        }
        if e.counters().collisions == collisions {
            continue;
        }
        let t = e.time();
        times.push(t);
        if let Some((_, last)) = e.tc_model() {
            let changed: Vec<usize> = (0..n)
                .filter(|&i| last[i].to_bits() != shadow[i].to_bits())
                .collect();
            assert!(changed.len() <= 2 && changed.iter().all(|&i| last[i] == t));
            if changed.len() < 2 || changed.iter().any(|&i| t - shadow[i] < tc) {
                elastic += 1;
                if e.counters().energy_lost != lost {
                    elastic_with_loss += 1;
                }
            }
            for i in changed {
                shadow[i] = t;
            }
        }
    }
    let e1 = twice_energy(&e.system().velocities, &vec![1.0; n], 0..n).value() / 2.0;
    Run1d {
        times,
        elastic,
        elastic_with_loss,
        energy: (e0, e1, e.counters().energy_lost),
        collapsed: e.collapsed(),
    }
}

/// The shortest time spanned by `window` consecutive collisions.
fn shortest_span(times: &[f64], window: usize) -> f64 {
    times
        .windows(window)
        .map(|w| w[window - 1] - w[0])
        .fold(f64::INFINITY, f64::min)
}

/// (c) Inelastic collapse in 1D and the TC model against it. N = 100 rods (sigma = 1) on a
/// ring at phi = 0.5 with eps = 0.5, deep in the collapsing regime of McNamara & Young
/// (Phys. Fluids A 4, 496 (1992): a row of N rods collapses once 1 - eps exceeds a
/// threshold of order 1/N), run for 5e5 collisions (5000 per particle) with and without
/// tc = 1e-3 (the initial free time is ~1). Deterministic (fixed seed), 0.5 s.
///
/// Without TC the gas collapses: somewhere 1000 consecutive collisions take less than
/// 1e-10 of the elapsed time (in fact none: the time stops while collisions continue).
///
/// With TC a window of time shorter than tc can hold at most
/// C = N(N-1)/2 + (N/2)(2N - 3) collisions, so every C + 1 consecutive collisions span at
/// least tc. Proof: inside such a window a collision can be inelastic only if neither
/// partner collided earlier in the window, so there are at most N/2 inelastic ones. An
/// elastic collision of equal rods in 1D exchanges the velocities: mapped to point
/// "ghosts" on a ring of length L - N sigma that pass through each other, it is a crossing
/// of two ghosts, and two ghosts with constant velocities cross at most once in a time
/// tc if their relative speed times tc is below the ring length (asserted: 2 v_max tc <
/// L - N sigma, v_max = sqrt(2 E0 / m)). Each pair crosses at most once between inelastic
/// collisions that change either velocity: N(N-1)/2 + (N/2)(2N - 3) crossings in all.
/// So the time after B collisions is at least floor(B/(C+1)) tc: no stall, ever.
/// Also asserted: energy stays positive and the balance E0 = E + (energy lost) holds to
/// round-off (each collision errs by at most ~10 u E0, linear worst case); the engine
/// loses no energy in the collisions the rule makes elastic; and the elastic fraction.
/// Measured: without TC the time stops at t = 16.008528 and the engine declares collapse
/// after 1e5 collisions at that time (`EventDriven::collapsed`); with TC, t = 7.5e5 after 5e5 collisions, every 14801 consecutive
/// collisions span at least 12.1 (the bound is 1e-3), 42 % of the collisions were made
/// elastic, E falls from 50 to 7.6e-9 (Haff-like cooling, never zero), energy balance to
/// 4e-13.
#[test]
fn tc_model_prevents_inelastic_collapse_in_1d() {
    let (n, phi, eps, tc, budget, seed) = (100, 0.5, 0.5, 1e-3, 500_000u64, 3);
    let clock = Instant::now();
    let collapse = run_1d(n, phi, eps, 0.0, budget, seed);
    let collapse_time = *collapse.times.last().unwrap();
    let span_1000 = shortest_span(&collapse.times, 1000);
    let last_1000 = collapse_time - collapse.times[collapse.times.len() - 1000];
    eprintln!(
        "without TC: {} collisions, time {collapse_time:.6}, shortest span of 1000 collisions {span_1000:.3e}, last 1000 collisions {last_1000:.3e}, E = {:.4e} ({:.2} s)",
        collapse.times.len(),
        collapse.energy.1,
        clock.elapsed().as_secs_f64()
    );
    // The engine stops after COLLAPSE_COLLISIONS_PER_PARTICLE * N collisions at a standing
    // time and reports the collapse time.
    assert_eq!(collapse.collapsed, Some(collapse_time));
    assert!((collapse.times.len() as u64) < budget);
    assert!(span_1000 < 1e-10 * collapse_time, "{span_1000}");

    let clock = Instant::now();
    let run = run_1d(n, phi, eps, tc, budget, seed);
    let (e0, e1, lost) = run.energy;
    let length = n as f64 / phi;
    let v_max = (2.0 * e0).sqrt();
    assert!(
        2.0 * v_max * tc < length - n as f64,
        "the bound needs 2 v_max tc < L - N sigma"
    );
    let c = n * (n - 1) / 2 + (n / 2) * (2 * n - 3);
    let span = shortest_span(&run.times, c + 1);
    let time = *run.times.last().unwrap();
    let fraction = run.elastic as f64 / run.times.len() as f64;
    eprintln!(
        "with tc = {tc}: {} collisions, time {time:.4e}, shortest span of {} collisions {span:.3e} (bound tc), elastic fraction {fraction:.4}, E = {e1:.3e} of {e0:.3e}, balance error {:.1e} ({:.2} s)",
        run.times.len(),
        c + 1,
        (e1 + lost - e0).abs() / e0,
        clock.elapsed().as_secs_f64()
    );
    assert_eq!(run.times.len() as u64, budget);
    assert_eq!(run.collapsed, None);
    assert!(span >= tc, "{span}");
    assert!(time >= (budget / (c as u64 + 1)) as f64 * tc);
    assert!(e1 > 0.0 && e1 < e0);
    let u = f64::EPSILON / 2.0;
    assert!((e1 + lost - e0).abs() <= 10.0 * u * e0 * budget as f64);
    assert_eq!(run.elastic_with_loss, 0);
    assert!(fraction > 0.0 && fraction < 1.0, "{fraction}");
}

// ---------------------------------------------------------------------------------------
// 4. Binary mixtures: conservation, and collision frequencies against Enskog theory.
// ---------------------------------------------------------------------------------------

/// Small spheres (d = 1, m = 1) and large ones (d = 2, m = 8, the same material density),
/// half and half in number.
fn binary_mixture() -> [Species; 2] {
    [
        Species {
            diameter: 1.0,
            mass: 1.0,
            fraction: 0.5,
        },
        Species {
            diameter: 2.0,
            mass: 8.0,
            fraction: 0.5,
        },
    ]
}

/// Contact value g_ab of the pair correlation function of a hard-sphere mixture
/// (Boublík, J. Chem. Phys. 53, 471 (1970); Grundke & Henderson, Mol. Phys. 24, 269
/// (1972); Lee & Levesque, Mol. Phys. 26, 1351 (1973) — the contact values consistent with
/// the BMCSL equation of state):
///
///   g_ab = 1/(1 - xi3) + 3 xi2 d_ab / (1 - xi3)^2 + 2 xi2^2 d_ab^2 / (1 - xi3)^3,
///   d_ab = d_a d_b / (d_a + d_b),  xi_k = (pi/6) sum_i n_i d_i^k  (xi3 = phi).
///
/// For one species it is Carnahan–Starling's (1 - phi/2)/(1 - phi)^3. It is exact to first
/// order in density; at phi = 0.02 its error is of order phi^2 ~ 4e-4 (for one species the
/// exact second-order coefficient is 4.59 against CS's 4).
fn contact_value(da: f64, db: f64, xi2: f64, xi3: f64) -> f64 {
    let d = da * db / (da + db);
    1.0 / (1.0 - xi3)
        + 3.0 * xi2 * d / (1.0 - xi3).powi(2)
        + 2.0 * (xi2 * d).powi(2) / (1.0 - xi3).powi(3)
}

/// Collisions per unit time of one particle of species a in an equilibrium mixture at
/// temperature T (Enskog theory):
///
///   omega_a = sum_b n_b pi sigma_ab^2 <|g|>_ab g_ab = sum_b n_b sigma_ab^2 sqrt(8 pi T / mu_ab) g_ab,
///
/// with sigma_ab = (d_a + d_b)/2, mu_ab = m_a m_b/(m_a + m_b) and <|g|>_ab =
/// sqrt(8 T / (pi mu_ab)) the mean relative speed of two Maxwellian particles (Chapman &
/// Cowling, The Mathematical Theory of Non-Uniform Gases, Ch. 5: the collision rate per
/// volume of species a and b is n_a n_b sigma_ab^2 sqrt(8 pi T/mu_ab), halved for a = b
/// where each collision counts for two particles of a). For one species this is
/// 4 sqrt(pi) n sigma^2 sqrt(T/m) chi of `tests/emd.rs`. In equilibrium positions and
/// velocities are independent, so the rate is exactly n_b times the flux of Maxwellian
/// pairs at contact weighted with g_ab: the only approximation is g_ab.
fn enskog_frequencies(
    species: &[Species],
    numbers: &[usize],
    volume: f64,
    t: f64,
    with_g: bool,
) -> Vec<f64> {
    let density: Vec<f64> = numbers.iter().map(|&k| k as f64 / volume).collect();
    let xi = |k: i32| {
        PI / 6.0
            * species
                .iter()
                .zip(&density)
                .map(|(s, n)| n * s.diameter.powi(k))
                .sum::<f64>()
    };
    let (xi2, xi3) = (xi(2), xi(3));
    species
        .iter()
        .map(|a| {
            species
                .iter()
                .zip(&density)
                .map(|(b, nb)| {
                    let sigma = 0.5 * (a.diameter + b.diameter);
                    let mu = a.mass * b.mass / (a.mass + b.mass);
                    let g = if with_g {
                        contact_value(a.diameter, b.diameter, xi2, xi3)
                    } else {
                        1.0
                    };
                    nb * sigma * sigma * (8.0 * PI * t / mu).sqrt() * g
                })
                .sum()
        })
        .collect()
}

/// An elastic binary mixture at packing fraction `phi`: energy and momentum to round-off
/// over `conservation` collisions (as [`conservation_to_round_off`], which also
/// equilibrates the random-addition state: 30 collisions per particle or more), then the
/// collision frequency of each species, from the particles' collision counts, over
/// `batches` batches of `per_batch` collisions: estimate sum(counts) / (N_a * time), its
/// standard error from the spread of the batch values over sqrt(batches). The temperature
/// is that of the D(N - 1) degrees of freedom left by zero momentum, 2E/(D(N - 1)).
/// Asserts |measured/Enskog - 1| < 4 standard errors (plus the phi^2 ~ 4e-4 uncertainty of
/// g_ab) for each species; prints the same against Boltzmann (g = 1), which the
/// test resolves.
fn mixture_check(n: usize, phi: f64, conservation: (u64, u64), batches: usize, per_batch: u64) {
    let species = binary_mixture();
    let system = polydisperse::<3>(n, phi, &species, 1.0, 77).unwrap();
    let mut e = EventDriven::new(system, constant(1.0)).unwrap();
    let clock = Instant::now();
    let (de, dp) = conservation_to_round_off(&mut e, conservation.0, conservation.1);
    eprintln!(
        "mixture N = {n}, phi = {phi}: {} collisions, |dE|/E = {de:.2e}, |dP|/sum m|v| = {dp:.2e}",
        conservation.1
    );
    let (kind, volume, t) = {
        let s = e.system();
        let kind: Vec<usize> = s
            .masses
            .iter()
            .map(|&m| if m == species[0].mass { 0 } else { 1 })
            .collect();
        let twice = twice_energy(&s.velocities, &s.masses, 0..n).value();
        (kind, s.volume(), twice / (3.0 * (n - 1) as f64))
    };
    let numbers = [
        kind.iter().filter(|&&k| k == 0).count(),
        kind.iter().filter(|&&k| k == 1).count(),
    ];
    let mut rates = vec![vec![]; 2];
    let (mut totals, mut time) = ([0u64; 2], 0.0);
    for _ in 0..batches {
        let (c0, t0) = (e.counts(), e.time());
        e.run_collisions(per_batch);
        let (c1, dt) = (e.counts(), e.time() - t0);
        let mut sums = [0u64; 2];
        for i in 0..n {
            sums[kind[i]] += c1[i].wrapping_sub(c0[i]) & 0xffff_ffff;
        }
        for a in 0..2 {
            rates[a].push(sums[a] as f64 / (numbers[a] as f64 * dt));
            totals[a] += sums[a];
        }
        time += dt;
    }
    let enskog = enskog_frequencies(&species, &numbers, volume, t, true);
    let boltzmann = enskog_frequencies(&species, &numbers, volume, t, false);
    for a in 0..2 {
        let measured = totals[a] as f64 / (numbers[a] as f64 * time);
        let error = sample_sd(&rates[a]) / (batches as f64).sqrt();
        let z = (measured - enskog[a]) / (error + 4e-4 * enskog[a]);
        let z_boltzmann = (measured - boltzmann[a]) / error;
        eprintln!(
            "species {a} (d = {}, m = {}): omega = {measured:.5} +- {error:.5}, Enskog-BMCSL {:.5} (ratio {:.4}, z = {z:+.2}), Boltzmann {:.5} (z = {z_boltzmann:+.1})",
            species[a].diameter,
            species[a].mass,
            enskog[a],
            measured / enskog[a],
            boltzmann[a]
        );
        assert!(z.abs() < 4.0, "species {a}: z = {z}");
    }
    eprintln!("({:.1} s)", clock.elapsed().as_secs_f64());
}

/// N = 2000 at phi = 0.02: 3e4 collisions for conservation, 2e5 for the frequencies
/// (standard error ~0.25 %, where g_ab - 1 = 4 .. 6 %). Measured (2.7 s): |dE|/E = 1.7e-16;
/// omega/Enskog = 1.0020 +- 0.0028 (small) and 1.0007 +- 0.0021 (large); against
/// Boltzmann (g = 1) z = 15, 22.
#[test]
fn binary_mixture_conserves_and_collides_as_enskog_predicts() {
    mixture_check(2000, 0.02, (2_000, 30_000), 20, 10_000);
}

/// N = 20000 at phi = 0.02: 1e6 collisions for conservation, 4e6 for the frequencies.
/// Measured (98 s): |dE|/E = 3.9e-16, |dP| / sum m|v| = 4.2e-18; omega/Enskog = 1.0012
/// +- 0.0006 (small), 1.0009 +- 0.0005 (large); against Boltzmann z = 63, 92.
/// `cargo test --release -p haff-gas --test emd_validation -- --ignored --nocapture binary_mixture_heavy`
#[test]
#[ignore]
fn binary_mixture_heavy() {
    mixture_check(20_000, 0.02, (10_000, 1_000_000), 40, 100_000);
}
