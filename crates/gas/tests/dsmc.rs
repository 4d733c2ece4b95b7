//! The DSMC engines against conservation laws, Enskog kinetic theory, each other, and
//! themselves (thread-count independence, snapshots).
//!
//! `cargo test --release -p haff-gas --test dsmc` (the heavy validations:
//! `cargo test --release -p haff-gas --test dsmc -- --ignored --nocapture`).

mod common;

use common::mean_and_error;
use gas::dsmc::{point_gas, HomogeneousDsmc, Scheme, SpatialDsmc, SpatialOptions, StepSize};
use gas::observe::{kinetic_energy, mean_velocity, sonine_a2, temperature};
use gas::system::{ball_volume, System};
use gas::theory::{
    collision_frequency, haff_collisions_per_particle, haff_time, mean_free_path,
    van_noije_ernst_a2, SonineHierarchy,
};
use gas::{Checkpoint, Engine};
use restitution::{Constant, Restitution};

fn law(eps: f64) -> Box<dyn Restitution> {
    Box::new(Constant::new(eps).unwrap())
}

/// A Maxwellian gas of unit spheres (diameter 1, mass 1, T = 1) for the homogeneous engine.
fn gas<const D: usize>(n: usize, seed: u64) -> System<D> {
    point_gas::<D>(n, 1.0, 1.0, 1.0, 1.0, seed).unwrap()
}

fn blocks(block_size: usize) -> Scheme {
    Scheme::Blocks {
        block_size,
        step: StepSize::Auto,
    }
}

fn homogeneous<const D: usize>(
    n: usize,
    phi: f64,
    eps: f64,
    seed: u64,
    scheme: Scheme,
) -> HomogeneousDsmc<D> {
    HomogeneousDsmc::new(gas::<D>(n, seed), phi, law(eps), seed, scheme).unwrap()
}

/// Enskog collision frequency at T = 1 of a particle among N - 1 others in the engine's
/// volume (unit spheres, unit mass).
fn omega_of<const D: usize>(e: &HomogeneousDsmc<D>, phi: f64, t: f64) -> f64 {
    let others = (e.len() - 1) as f64 / e.volume();
    collision_frequency::<D>(others, 1.0, 1.0, t, phi)
}

/// Velocities of one speed in random directions: a2 = D/(D+2) - 1, far from a Maxwellian.
fn one_speed<const D: usize>(n: usize, seed: u64) -> System<D> {
    let mut s = gas::<D>(n, seed);
    for v in &mut s.velocities {
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        v.iter_mut().for_each(|x| *x /= norm);
    }
    let (mean, _) = mean_velocity(&s);
    for v in &mut s.velocities {
        (0..D).for_each(|k| v[k] -= mean[k]);
    }
    s
}

fn elastic_relaxation<const D: usize>(scheme: Scheme) {
    let n = 20_000;
    let system = one_speed::<D>(n, 3);
    let a2_start = sonine_a2(&system);
    let e0 = kinetic_energy(&system);
    let mut e = HomogeneousDsmc::new(system, 0.1, law(1.0), 4, scheme).unwrap();
    e.run_collisions(10 * n as u64 / 2);
    let s = e.system().clone();
    let drift = (kinetic_energy(&s) - e0).abs() / e0;
    let (_, p) = mean_velocity(&s);
    let a2 = sonine_a2(&s);
    eprintln!("D = {D}, {scheme:?}: energy drift {drift:.1e}, a2 {a2_start:.3} -> {a2:.4}");
    assert!(drift < 1e-12, "energy drift {drift}");
    assert!(p.iter().all(|x| x.abs() < 1e-10), "momentum {p:?}");
    // a2 of N Maxwellian velocities: standard deviation sqrt(8 / (D (D + 2) N)) < 0.007.
    assert!(a2.abs() < 0.03, "a2 = {a2}");
    assert_eq!(e.counters().energy_lost, 0.0);
}

/// Elastic gas: energy conserved to round-off, momentum conserved, one speed relaxes to a
/// Maxwellian (a2 from -0.4 or -0.5 to 0) in both schemes, in 2D and 3D.
#[test]
fn elastic_gas_conserves_energy_and_relaxes_to_a_maxwellian() {
    for scheme in [Scheme::Exact, blocks(2048)] {
        elastic_relaxation::<2>(scheme);
        elastic_relaxation::<3>(scheme);
    }
}

/// In 1D an elastic collision of equal masses exchanges the velocities: the set of
/// velocities never changes (the 1D Boltzmann gas does not relax).
#[test]
fn one_dimensional_elastic_collisions_exchange_velocities() {
    let system = gas::<1>(1000, 5);
    let mut before: Vec<f64> = system.velocities.iter().map(|v| v[0]).collect();
    let mut e = HomogeneousDsmc::new(system, 0.2, law(1.0), 6, Scheme::Exact).unwrap();
    e.run_collisions(20_000);
    let mut after: Vec<f64> = e.system().velocities.iter().map(|v| v[0]).collect();
    before.sort_by(f64::total_cmp);
    after.sort_by(f64::total_cmp);
    for (a, b) in before.iter().zip(&after) {
        assert!((a - b).abs() < 1e-12, "{a} vs {b}");
    }
}

/// The tally's dissipated energy is the loss of kinetic energy, in every dimension and
/// scheme; momentum is conserved.
#[test]
fn dissipated_energy_is_the_kinetic_energy_lost() {
    fn check<const D: usize>(scheme: Scheme) {
        let mut e = homogeneous::<D>(5000, 0.1, 0.7, 8, scheme);
        let e0 = kinetic_energy(e.system());
        e.run_collisions(20_000);
        let s = e.system().clone();
        let lost = e.counters().energy_lost;
        assert!(lost > 0.1 * e0, "D = {D}: lost {lost}");
        let balance = (e0 - kinetic_energy(&s) - lost).abs() / e0;
        assert!(balance < 1e-12, "D = {D}, {scheme:?}: {balance}");
        let (_, p) = mean_velocity(&s);
        assert!(p.iter().all(|x| x.abs() < 1e-10), "momentum {p:?}");
    }
    for scheme in [Scheme::Exact, blocks(512)] {
        check::<1>(scheme);
        check::<2>(scheme);
        check::<3>(scheme);
    }
}

/// Elastic gas in equilibrium: collisions per particle per time against the Enskog
/// frequency omega = g2 n sigma^(D-1) S_D sqrt(T / (pi m)) in D = 1, 2, 3 (n = (N-1)/V), both
/// schemes. The count is Poisson: relative error 1/sqrt(collisions) = 0.3 %.
#[test]
fn collision_frequency_is_enskog_in_every_dimension() {
    fn check<const D: usize>(scheme: Scheme) {
        let phi = 0.2;
        let n = 10_000;
        let mut e = homogeneous::<D>(n, phi, 1.0, 12, scheme);
        let t = 10.0 / omega_of(&e, phi, 1.0);
        e.run_until(t);
        let measured = e.collisions_per_particle() / e.time();
        let t_now = temperature(e.system());
        let theory = omega_of(&e, phi, t_now);
        let sigma = (2.0 * e.counters().collisions as f64).sqrt() / e.counters().collisions as f64;
        eprintln!(
            "D = {D}, {scheme:?}: omega / omega_Enskog = {:.4} (+- {sigma:.4})",
            measured / theory
        );
        assert!((measured / theory - 1.0).abs() < 5.0 * sigma, "D = {D}");
    }
    for scheme in [Scheme::Exact, blocks(1024)] {
        check::<1>(scheme);
        check::<2>(scheme);
        check::<3>(scheme);
    }
}

/// Constant eps in the homogeneous cooling state: d ln T / d(collisions per particle) =
/// -(1 - eps^2)/D (1 + a2/4) (van Noije–Ernst a2), in 2D and 3D, both schemes.
#[test]
fn cooling_per_collision_matches_kinetic_theory() {
    fn check<const D: usize>(scheme: Scheme) {
        let eps: f64 = 0.9;
        let n = 20_000;
        let mut e = homogeneous::<D>(n, 0.1, eps, 61, scheme);
        e.run_collisions(10 * n as u64 / 2);
        let (t0, c0) = (temperature(e.system()), e.collisions_per_particle());
        e.run_collisions(40 * n as u64 / 2);
        let (t1, c1) = (temperature(e.system()), e.collisions_per_particle());
        let slope = (t1 / t0).ln() / (c1 - c0);
        let a2 = van_noije_ernst_a2::<D>(eps);
        let theory = -(1.0 - eps * eps) / D as f64 * (1.0 + a2 / 4.0);
        eprintln!("D = {D}, {scheme:?}: d ln T / dc = {slope:.5}, theory {theory:.5}");
        assert!((slope / theory - 1.0).abs() < 0.01, "D = {D}: {slope}");
    }
    for scheme in [Scheme::Exact, Scheme::default()] {
        check::<2>(scheme);
        check::<3>(scheme);
    }
}

/// Haff's law in time with no fitted parameter: T(t) = T0 / (1 + t/tau)^2, 1/tau =
/// (1 - eps^2) omega0 (1 + 3 a2/16) / (2 D) (van Noije–Ernst a2, D = 2, 3), and the collisions
/// per particle omega0 (1 - a2/16) tau ln(1 + t/tau); up to t = 4 tau.
fn haff_check<const D: usize>(scheme: Scheme, n: usize, seeds: u64, tolerance: f64) {
    let (phi, eps) = (0.1, 0.9);
    let a2 = van_noije_ernst_a2::<D>(eps);
    let mut worst: f64 = 0.0;
    let times = [0.5, 1.0, 2.0, 4.0];
    let mut ratios = vec![vec![]; times.len()];
    let mut counts = vec![vec![]; times.len()];
    for seed in 0..seeds {
        let mut e = homogeneous::<D>(n, phi, eps, 40 + seed, scheme);
        let omega0 = omega_of(&e, phi, 1.0);
        let tau = haff_time::<D>(eps, omega0 * (1.0 + 3.0 * a2 / 16.0));
        for (k, &x) in times.iter().enumerate() {
            e.run_until(x * tau);
            ratios[k].push(temperature(e.system()) * (1.0 + x).powi(2));
            let expected = haff_collisions_per_particle(omega0 * (1.0 - a2 / 16.0), tau, x * tau);
            counts[k].push(e.collisions_per_particle() / expected);
        }
    }
    for (k, &x) in times.iter().enumerate() {
        let (r, dr) = mean_and_error(&ratios[k]);
        let (c, dc) = mean_and_error(&counts[k]);
        eprintln!(
            "D = {D}, {scheme:?}: t/tau = {x}: T/T_Haff = {r:.4} +- {dr:.4}, collisions/theory = {c:.4} +- {dc:.4}"
        );
        worst = worst.max((r - 1.0).abs()).max((c - 1.0).abs());
    }
    assert!(worst < tolerance, "D = {D}: {worst}");
}

#[test]
fn haff_law_in_time_in_two_and_three_dimensions() {
    haff_check::<2>(Scheme::Exact, 20_000, 2, 0.01);
    haff_check::<3>(Scheme::Exact, 20_000, 2, 0.01);
    haff_check::<3>(blocks(2048), 20_000, 2, 0.01);
}

/// The block scheme (1e6 particles, default blocks) against Haff's law:
/// `cargo test --release -p haff-gas --test dsmc -- --ignored --nocapture haff_law_large`
#[test]
#[ignore]
fn haff_law_large_systems() {
    haff_check::<3>(Scheme::default(), 1_000_000, 2, 0.003);
    haff_check::<2>(Scheme::default(), 1_000_000, 2, 0.003);
}

/// a2 of the homogeneous cooling state: the mean over snapshots from `from` to `to`
/// collisions per particle, its error from batch means over time and seeds.
fn hcs_a2<const D: usize>(eps: f64, scheme: Scheme, n: usize, seeds: u64) -> (f64, f64) {
    let (from, to, batches, per_batch) = (8.0, 48.0, 5, 8);
    let mut batch_means = vec![];
    for seed in 0..seeds {
        let mut e = homogeneous::<D>(n, 0.1, eps, 70 + seed, scheme);
        e.run_collisions((from * n as f64 / 2.0) as u64);
        let spacing = (to - from) / (batches * per_batch) as f64;
        for _ in 0..batches {
            let mut sum = 0.0;
            for _ in 0..per_batch {
                e.run_collisions((spacing * n as f64 / 2.0) as u64);
                sum += sonine_a2(e.system());
            }
            batch_means.push(sum / per_batch as f64);
        }
    }
    mean_and_error(&batch_means)
}

/// a2 of the homogeneous cooling state against van Noije & Ernst (first Sonine
/// approximation) at eps = 0.5, 0.7, 0.9 in 3D. The bound is 3 standard errors plus the
/// error of the approximation itself, which grows with dissipation (Brilliantov & Pöschel
/// 2006; Santos & Montanero 2009): 0.005 + 0.04 (1 - eps)^2.
#[test]
fn sonine_a2_of_the_homogeneous_cooling_state() {
    for eps in [0.5, 0.7, 0.9] {
        let (a2, error) = hcs_a2::<3>(eps, blocks(2048), 20_000, 2);
        let theory = van_noije_ernst_a2::<3>(eps);
        let allowed = 3.0 * error + 0.005 + 0.04 * (1.0 - eps) * (1.0 - eps);
        eprintln!("eps = {eps}: a2 = {a2:.4} +- {error:.4}, van Noije-Ernst {theory:.4}");
        assert!((a2 - theory).abs() < allowed, "eps = {eps}: a2 = {a2}");
    }
}

/// The block scheme samples the same homogeneous cooling state as the exact scheme: a2
/// and the temperature after 30 collisions per particle agree within statistical error.
#[test]
fn block_scheme_agrees_with_the_exact_scheme() {
    let eps = 0.7;
    let (exact, exact_error) = hcs_a2::<3>(eps, Scheme::Exact, 10_000, 2);
    let (blocked, blocked_error) = hcs_a2::<3>(eps, blocks(512), 10_000, 2);
    let error = (exact_error.powi(2) + blocked_error.powi(2)).sqrt();
    eprintln!(
        "a2: exact {exact:.4} +- {exact_error:.4}, blocks {blocked:.4} +- {blocked_error:.4}"
    );
    assert!((exact - blocked).abs() < 4.0 * error + 1e-3);
    let temperatures = |scheme: Scheme| -> Vec<f64> {
        (0..4)
            .map(|seed| {
                let mut e = homogeneous::<3>(10_000, 0.1, eps, 90 + seed, scheme);
                let t = 30.0 / omega_of(&e, 0.1, 1.0);
                e.run_until(t);
                temperature(e.system())
            })
            .collect()
    };
    let (te, dte) = mean_and_error(&temperatures(Scheme::Exact));
    let (tb, dtb) = mean_and_error(&temperatures(blocks(512)));
    eprintln!("T(t): exact {te:.5} +- {dte:.5}, blocks {tb:.5} +- {dtb:.5}");
    assert!((te - tb).abs() < 4.0 * (dte * dte + dtb * dtb).sqrt() + 1e-3 * te);
}

/// The bias of the block scheme (see `Scheme::Blocks`): T after 30 collision times of the
/// initial state at eps = 0.7 over 24 seeds, exact scheme against blocks. Measured:
/// exact 0.07928 +- 0.00013; B = 64: +0.6 %, +1.5 %, +4.2 % at 0.5, 2, 8 collisions per
/// particle per step; B = 512 at 2: +0.2 %.
/// `cargo test --release -p haff-gas --test dsmc -- --ignored --nocapture block_bias`
#[test]
#[ignore]
fn block_bias_grows_with_step_over_block_size() {
    let eps = 0.7;
    let temperatures = |scheme: Scheme| -> (f64, f64) {
        let t: Vec<f64> = (0..24)
            .map(|seed| {
                let mut e = homogeneous::<3>(10_000, 0.1, eps, 1000 + seed, scheme);
                let t = 30.0 / omega_of(&e, 0.1, 1.0);
                e.run_until(t);
                temperature(e.system())
            })
            .collect();
        mean_and_error(&t)
    };
    let (exact, exact_error) = temperatures(Scheme::Exact);
    let (default, default_error) = temperatures(Scheme::default());
    let coarse = Scheme::Blocks {
        block_size: 64,
        step: StepSize::CollisionsPerParticle(8.0),
    };
    let (biased, _) = temperatures(coarse);
    eprintln!(
        "T: exact {exact:.5} +- {exact_error:.5}, default blocks {default:.5} +- {default_error:.5}, B = 64 at 8 per step {biased:.5}"
    );
    let error = (exact_error.powi(2) + default_error.powi(2)).sqrt();
    assert!((default - exact).abs() < 4.0 * error);
    assert!(biased / exact - 1.0 > 0.02);
}

/// a2 of the HCS (DSMC, 2·10⁵ particles, 4 seeds; 2D and 3D) against the Sonine hierarchy
/// (`gas::theory::SonineHierarchy`, quadrature of the collisional moments), which is
/// independent of the engine. Its truncations
/// (nonlinear terms kept) converge at eps = 0.7 and 0.9 (K = 3 … 8 change a2 by ≤ 3e-4,
/// the last orders by ≤ 3e-5) but oscillate at eps = 0.5 (the breakdown of the Sonine
/// expansion, Brilliantov & Pöschel, EPL 74, 424 (2006): in 2D K = 3 … 8 give 0.065 …
/// 0.087 with growing swings). The reference is the middle of the range of the last three
/// orders K = 4, 5, 6 and its error the half-range (3D: 0.04783 ± 0.00113,
/// −0.00056 ± 0.00004, −0.01579 ± 0.00001; 2D: 0.07357 ± 0.00562, −0.00189 ± 0.00014,
/// −0.03005 ± 0.00002 at eps = 0.5, 0.7, 0.9). Tolerance: that half-range plus 5
/// standard errors of the DSMC a2 (batch means over time and seeds, 20 batches: t test
/// with 19 degrees of freedom, P(|t| > 5) = 8e-5 each). Measured (≈ 70 s on 2 cores):
/// 3D 0.04677 ± 0.00022, −0.00062 ± 0.00019, −0.01543 ± 0.00022; 2D 0.07267 ± 0.00036,
/// −0.00256 ± 0.00036, −0.03017 ± 0.00023 (at most 1.9 standard errors from the
/// converged orders at eps = 0.7, 0.9). The first Sonine approximation (van Noije–Ernst)
/// is printed for comparison: it is off by 0.006 (3D) and 0.010 (2D) at eps = 0.5.
/// `cargo test --release -p haff-gas --test dsmc -- --ignored --nocapture sonine_a2_precise`
#[test]
#[ignore]
fn sonine_a2_precise() {
    for eps in [0.5, 0.7, 0.9] {
        let (a3, e3) = hcs_a2::<3>(eps, Scheme::default(), 200_000, 4);
        let (a2d, e2d) = hcs_a2::<2>(eps, Scheme::default(), 200_000, 4);
        for (d, a2, error, vne) in [
            (3, a3, e3, van_noije_ernst_a2::<3>(eps)),
            (2, a2d, e2d, van_noije_ernst_a2::<2>(eps)),
        ] {
            let orders: Vec<f64> = (4..=6)
                .map(|k| {
                    SonineHierarchy::new(d, k, eps)
                        .unwrap()
                        .coefficients()
                        .unwrap()[0]
                })
                .collect();
            let lo = orders.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = orders.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let (reference, half_range) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            let shown: Vec<String> = orders.iter().map(|x| format!("{x:.5}")).collect();
            eprintln!(
                "eps = {eps}, {d}D: a2 = {a2:.5} +- {error:.5}; Sonine K = 4..6 {shown:?} -> \
                 {reference:.5} +- {half_range:.5}; vNE {vne:.5}"
            );
            assert!(
                (a2 - reference).abs() < 5.0 * error + half_range,
                "eps = {eps}, {d}D: a2 = {a2} against {reference} +- {half_range}"
            );
        }
    }
}

/// A 3D spatial gas in a periodic box of 5 mean free paths (simulated particles standing
/// for fewer physical ones, ~30 per cell) against Haff's law, like the homogeneous engine.
fn spatial_engine(n: usize, eps: f64, seed: u64) -> (SpatialDsmc<3>, f64) {
    let phi = 0.1;
    let density = phi / ball_volume::<3>(0.5);
    let length = 5.0 * mean_free_path::<3>(density, 1.0, phi);
    let system = point_gas::<3>(n, length, 1.0, 1.0, 1.0, seed).unwrap();
    let e = SpatialDsmc::new(system, phi, law(eps), seed, SpatialOptions::default()).unwrap();
    let omega0 = collision_frequency::<3>(density, 1.0, 1.0, 1.0, phi);
    (e, omega0)
}

#[test]
fn spatial_engine_follows_haff_law() {
    let eps = 0.9;
    let a2 = van_noije_ernst_a2::<3>(eps);
    let (mut e, omega0) = spatial_engine(20_000, eps, 3);
    eprintln!(
        "weight {:.4}, cell width {:.3}, particles per cell {:.1}",
        e.weight(),
        e.cell_width(),
        e.particles_per_cell()
    );
    let tau = haff_time::<3>(eps, omega0 * (1.0 + 3.0 * a2 / 16.0));
    let mut worst: f64 = 0.0;
    for x in [1.0, 4.0] {
        e.run_until(x * tau);
        let ratio = temperature(e.system()) * (1.0 + x).powi(2);
        let expected = haff_collisions_per_particle(omega0 * (1.0 - a2 / 16.0), tau, x * tau);
        let count = e.collisions_per_particle() / expected;
        eprintln!("spatial: t/tau = {x}: T/T_Haff = {ratio:.4}, collisions/theory = {count:.4}");
        worst = worst.max((ratio - 1.0).abs()).max((count - 1.0).abs());
    }
    assert!(worst < 0.02, "{worst}");
}

/// The spatial engine in an elastic equilibrium: energy and momentum conserved, positions
/// stay in the box, collision frequency of Enskog.
#[test]
fn spatial_engine_conserves_and_collides_at_the_enskog_rate() {
    let (mut e, omega0) = spatial_engine(10_000, 1.0, 5);
    let e0 = kinetic_energy(e.system());
    e.run_until(20.0 / omega0);
    let s = e.system().clone();
    assert!((kinetic_energy(&s) - e0).abs() / e0 < 1e-12);
    let (_, p) = mean_velocity(&s);
    assert!(p.iter().all(|x| x.abs() < 1e-10), "{p:?}");
    assert!(s
        .positions
        .iter()
        .all(|x| x.iter().all(|&c| (0.0..s.sides[0]).contains(&c))));
    // Per particle (N - 1)/N of the physical density's rate.
    let ratio = e.collisions_per_particle() / (e.time() * omega0 * (1.0 - 1.0 / 10_000.0));
    eprintln!("spatial: omega / omega_Enskog = {ratio:.4}");
    assert!((ratio - 1.0).abs() < 0.02, "{ratio}");
}

fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

/// The parallel schemes give the same bits with 1 and 2 threads.
#[test]
fn results_do_not_depend_on_the_number_of_threads() {
    let homogeneous_run = || {
        let scheme = Scheme::Blocks {
            block_size: 256,
            step: StepSize::CollisionsPerParticle(0.5),
        };
        let mut e = homogeneous::<3>(20_000, 0.1, 0.8, 21, scheme);
        e.run_collisions(100_000);
        e.snapshot()
    };
    let one = in_pool(1, homogeneous_run);
    let two = in_pool(2, homogeneous_run);
    assert!(one.steps > 10);
    assert_eq!(one, two);
    let spatial_run = || {
        let (mut e, _) = spatial_engine(10_000, 0.8, 22);
        e.run_collisions(50_000);
        e.snapshot()
    };
    let one = in_pool(1, spatial_run);
    let two = in_pool(2, spatial_run);
    assert!(one.steps > 10);
    assert_eq!(one, two);
}

/// A run restored from a snapshot continues bit for bit (exact, blocks, spatial).
#[test]
fn restored_runs_continue_bit_for_bit() {
    for scheme in [Scheme::Exact, blocks(256)] {
        let mut a = homogeneous::<2>(5000, 0.2, 0.8, 31, scheme);
        a.run_collisions(12_345);
        a.run_until(a.time() * 1.5);
        let snapshot = a.snapshot();
        let mut b =
            <HomogeneousDsmc<2> as Checkpoint<2>>::restore(snapshot.clone(), law(0.8)).unwrap();
        assert_eq!(b.snapshot(), snapshot);
        for e in [&mut a, &mut b] {
            e.run_collisions(10_000);
            let t = e.time();
            e.run_until(t * 1.2);
        }
        assert_eq!(a.snapshot(), b.snapshot(), "{scheme:?}");
    }
    let (mut a, _) = spatial_engine(5000, 0.8, 32);
    a.run_collisions(10_000);
    let mut b = <SpatialDsmc<3> as Checkpoint<3>>::restore(a.snapshot(), law(0.8)).unwrap();
    a.run_collisions(10_000);
    b.run_collisions(10_000);
    assert_eq!(a.snapshot(), b.snapshot());
}

/// A binary mixture (two masses, two diameters), elastic: energy conserved and the two
/// species share the temperature (equipartition) in both engines.
#[test]
fn elastic_mixture_reaches_equipartition() {
    let mut s = gas::<3>(10_000, 41);
    for i in (0..s.len()).step_by(2) {
        s.masses[i] = 3.0;
        s.radii[i] = 0.7;
        // Start the heavy species at four times the temperature of the light one.
        s.velocities[i]
            .iter_mut()
            .for_each(|x| *x *= (4.0f64 / 3.0).sqrt());
    }
    let e0 = kinetic_energy(&s);
    let species_temperatures = |s: &System<3>| -> (f64, f64) {
        let t = |parity: usize| {
            let (mut sum, mut count) = (0.0, 0.0);
            for i in (parity..s.len()).step_by(2) {
                sum += s.masses[i] * s.velocities[i].iter().map(|x| x * x).sum::<f64>();
                count += 3.0;
            }
            sum / count
        };
        (t(0), t(1))
    };
    let mut e = HomogeneousDsmc::new(s.clone(), 0.1, law(1.0), 42, blocks(512)).unwrap();
    e.run_collisions(100_000);
    let after = e.system().clone();
    assert!((kinetic_energy(&after) - e0).abs() / e0 < 1e-12);
    let (heavy, light) = species_temperatures(&after);
    eprintln!("mixture: T_heavy / T_light = {:.4}", heavy / light);
    assert!((heavy / light - 1.0).abs() < 0.05);
    assert_eq!(after.masses.iter().filter(|&&m| m == 3.0).count(), 5000);
    let mut spatial = s;
    spatial.sides = [20.0; 3];
    let mut e = SpatialDsmc::new(spatial, 0.1, law(1.0), 43, SpatialOptions::default()).unwrap();
    e.run_collisions(100_000);
    let after = e.system().clone();
    assert!((kinetic_energy(&after) - e0).abs() / e0 < 1e-12);
    let (heavy, light) = species_temperatures(&after);
    assert!((heavy / light - 1.0).abs() < 0.05, "{}", heavy / light);
}

/// Bad parameters are errors naming the parameter, never panics.
#[test]
fn bad_parameters_are_errors() {
    let e = |r: Result<HomogeneousDsmc<3>, gas::Error>| {
        r.err().map(|e| e.to_string()).unwrap_or_default()
    };
    let s = gas::<3>(100, 1);
    assert!(e(HomogeneousDsmc::new(
        s.clone(),
        0.0,
        law(0.9),
        1,
        Scheme::Exact
    ))
    .contains("packing_fraction"));
    assert!(e(HomogeneousDsmc::new(
        s.clone(),
        0.8,
        law(0.9),
        1,
        Scheme::Exact
    ))
    .contains("packing_fraction"));
    assert!(e(HomogeneousDsmc::new(
        s.clone(),
        f64::NAN,
        law(0.9),
        1,
        Scheme::Exact
    ))
    .contains("packing_fraction"));
    assert!(e(HomogeneousDsmc::new(s.clone(), 0.1, law(0.9), 1, blocks(1))).contains("block_size"));
    let bad_step = Scheme::Blocks {
        block_size: 64,
        step: StepSize::CollisionsPerParticle(0.0),
    };
    assert!(
        e(HomogeneousDsmc::new(s.clone(), 0.1, law(0.9), 1, bad_step))
            .contains("collisions_per_step")
    );
    let bad_dt = Scheme::Blocks {
        block_size: 64,
        step: StepSize::Fixed(f64::INFINITY),
    };
    assert!(e(HomogeneousDsmc::new(s.clone(), 0.1, law(0.9), 1, bad_dt)).contains("time_step"));
    let mut one = s.clone();
    one.velocities.truncate(1);
    one.radii.truncate(1);
    one.masses.truncate(1);
    assert!(e(HomogeneousDsmc::new(one, 0.1, law(0.9), 1, Scheme::Exact)).contains("particles"));
    let mut zero_radius = s.clone();
    zero_radius.radii[7] = 0.0;
    assert!(e(HomogeneousDsmc::new(
        zero_radius,
        0.1,
        law(0.9),
        1,
        Scheme::Exact
    ))
    .contains("radii[7]"));
    let mut nan = s.clone();
    nan.velocities[3][1] = f64::NAN;
    assert!(
        e(HomogeneousDsmc::new(nan, 0.1, law(0.9), 1, Scheme::Exact)).contains("velocities[3]")
    );
    let mut short = s.clone();
    short.masses.pop();
    assert!(!e(HomogeneousDsmc::new(short, 0.1, law(0.9), 1, Scheme::Exact)).is_empty());
    let spatial = |options: SpatialOptions| {
        SpatialDsmc::new(s.clone(), 0.1, law(0.9), 1, options)
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default()
    };
    assert!(spatial(SpatialOptions {
        cell_width: Some(-1.0),
        ..Default::default()
    })
    .contains("cell_width"));
    assert!(spatial(SpatialOptions {
        cell_width: Some(1e-9),
        ..Default::default()
    })
    .contains("cell_width"));
    assert!(point_gas::<3>(10, 0.0, 1.0, 1.0, 1.0, 1)
        .unwrap_err()
        .to_string()
        .contains("length"));
    assert!(HomogeneousDsmc::<4>::new(
        System {
            sides: [1.0; 4],
            positions: vec![[0.0; 4]; 3],
            velocities: vec![[0.0; 4]; 3],
            radii: vec![0.5; 3],
            masses: vec![1.0; 3],
        },
        0.1,
        law(0.9),
        1,
        Scheme::Exact
    )
    .err()
    .map(|e| e.to_string())
    .unwrap_or_default()
    .contains("dimension"));
}

/// A gas at rest (no relative motion) neither collides nor hangs.
#[test]
fn a_gas_at_rest_does_nothing() {
    let mut s = gas::<3>(100, 1);
    s.velocities.iter_mut().for_each(|v| *v = [0.5, 0.0, 0.0]);
    for scheme in [Scheme::Exact, blocks(16)] {
        let mut e = HomogeneousDsmc::new(s.clone(), 0.1, law(0.9), 1, scheme).unwrap();
        e.run_collisions(100);
        e.run_until(10.0);
        assert_eq!(e.counters().collisions, 0);
        assert_eq!(e.time(), 10.0);
    }
}

/// Viscoelastic spheres (fast law): T(t) approaches t^(-5/3) at late times (Brilliantov &
/// Pöschel 2004, Ch. 8), as in the event-driven engine's test.
#[test]
fn viscoelastic_gas_cools_as_t_to_minus_five_thirds() {
    use restitution::{ScaledForm, Viscoelastic};
    let law = Viscoelastic::new(1.0, "fast".parse::<ScaledForm>().unwrap()).unwrap();
    let n = 10_000;
    let mut e = HomogeneousDsmc::new(gas::<3>(n, 2), 0.05, Box::new(law), 3, blocks(1024)).unwrap();
    e.run_collisions(500 * n as u64 / 2);
    let (t0, temp0) = (e.time(), temperature(e.system()));
    e.run_collisions(1000 * n as u64 / 2);
    let (t1, temp1) = (e.time(), temperature(e.system()));
    let exponent = (temp1 / temp0).ln() / (t1 / t0).ln();
    eprintln!("local exponent of T(t): {exponent:.4}");
    assert!((exponent + 5.0 / 3.0).abs() < 0.05, "{exponent}");
}
