//! The event-driven engine against conservation laws and kinetic theory.

mod common;

use common::mean_and_error;
use gas::init::monodisperse;
use gas::observe::{kinetic_energy, mean_velocity, temperature};
use gas::system::dot;
use gas::Engine;
use gas::EventDriven;
use restitution::Constant;

fn engine<const D: usize>(n: usize, phi: f64, eps: f64, seed: u64) -> EventDriven<D> {
    let system = monodisperse::<D>(n, phi, 1.0, 1.0, 1.0, seed).unwrap();
    EventDriven::new(system, Box::new(Constant::new(eps).unwrap())).unwrap()
}

/// Elastic gas: energy and momentum conserved to round-off, no overlap created.
#[test]
fn elastic_gas_conserves_energy_and_momentum() {
    for phi in [0.05, 0.3] {
        let mut e = engine::<3>(500, phi, 1.0, 7);
        let e0 = kinetic_energy(e.system());
        e.run_collisions(100_000);
        let s = e.system().clone();
        let drift = (kinetic_energy(&s) - e0).abs() / e0;
        assert!(drift < 1e-12, "phi = {phi}: energy drift {drift}");
        let (_, p) = mean_velocity(&s);
        assert!(p.iter().all(|x| x.abs() < 1e-10), "momentum {p:?}");
        let mut closest = f64::INFINITY;
        for i in 0..s.len() {
            for j in i + 1..s.len() {
                let d = s.separation(&s.positions[i], &s.positions[j]);
                closest = closest.min(dot(&d, &d).sqrt());
            }
        }
        assert!(
            closest > 1.0 - 1e-9,
            "phi = {phi}: overlap, closest pair at {closest}"
        );
        assert!(e.counters().events > e.counters().collisions);
    }
}

/// Constant eps: each collision removes (1 - eps^2) T on average (Maxwellian impact speeds),
/// so d ln T / d(collisions per particle) = -(1 - eps^2)/D, times (1 + a2/4) in the
/// homogeneous cooling state (a2 = -0.0146 at eps = 0.9 in 3D, van Noije & Ernst 1998).
#[test]
fn cooling_per_collision_matches_kinetic_theory() {
    let eps: f64 = 0.9;
    let mut e = engine::<3>(4000, 0.05, eps, 11);
    e.run_collisions(20_000); // let a2 relax to its HCS value
    let (t0, c0) = (temperature(e.system()), e.collisions_per_particle());
    e.run_collisions(40_000);
    let (t1, c1) = (temperature(e.system()), e.collisions_per_particle());
    let slope = (t1 / t0).ln() / (c1 - c0);
    let theory = -(1.0 - eps * eps) / 3.0 * (1.0 - 0.0146 / 4.0);
    eprintln!("d ln T / d(collisions per particle): {slope:.5}, theory {theory:.5}");
    assert!(
        (slope / theory - 1.0).abs() < 0.02,
        "slope {slope}, theory {theory}"
    );
}

/// The same code in one and two dimensions: elastic runs conserve energy.
#[test]
fn one_and_two_dimensions() {
    let mut e1 = engine::<1>(200, 0.3, 1.0, 3);
    let a = kinetic_energy(e1.system());
    e1.run_collisions(20_000);
    assert!((kinetic_energy(e1.system()) - a).abs() / a < 1e-12);
    let mut e2 = engine::<2>(400, 0.2, 1.0, 3);
    let b = kinetic_energy(e2.system());
    e2.run_collisions(50_000);
    assert!((kinetic_energy(e2.system()) - b).abs() / b < 1e-12);
}

/// Cell size changes only the crossing events: the same initial state run with cells one
/// diameter wide and with 4 cells per side gives the same collisions, and the calendar
/// never holds a pair collision later than both particles' scheduled events.
#[test]
fn cell_size_changes_only_crossings() {
    let system = monodisperse::<3>(60, 0.1, 1.0, 1.0, 1.0, 5).unwrap();
    let law = || Box::new(Constant::new(0.8).unwrap());
    let quarter = system.sides[0] / 4.0;
    let mut cells = EventDriven::with_cell_width(system.clone(), law(), 0.0).unwrap();
    let mut pairs = EventDriven::with_cell_width(system.clone(), law(), quarter).unwrap();
    for _ in 0..300 {
        assert_eq!(cells.missed_collision(), None, "at t = {}", cells.time());
        cells.step();
    }
    let mut cells = EventDriven::with_cell_width(system.clone(), law(), 0.0).unwrap();
    cells.run_collisions(100);
    pairs.run_collisions(100);
    assert!((cells.time() - pairs.time()).abs() < 1e-9 * pairs.time());
    let (a, b) = (cells.system().clone(), pairs.system().clone());
    for (u, v) in a.velocities.iter().zip(&b.velocities) {
        for k in 0..3 {
            assert!((u[k] - v[k]).abs() < 1e-8, "{u:?} vs {v:?}");
        }
    }
    assert!(
        cells.counters().events > pairs.counters().events,
        "cells add crossing events"
    );
}

/// Elastic hard spheres in equilibrium: collision frequency against Enskog,
/// omega = 4 sqrt(pi) n sigma^2 sqrt(T/m) chi with the Carnahan–Starling
/// chi = (1 - phi/2)/(1 - phi)^3, and the pressure from the collision virial,
/// P/(nT) = 1 + sum(impulse * sigma) / (3 N T t), against Z = (1 + phi + phi^2 - phi^3)/(1 - phi)^3.
fn enskog_check(phi: f64, n: usize, per_particle: u64, tolerance: f64) {
    let mut e = engine::<3>(n, phi, 1.0, 21);
    e.run_collisions(30 * n as u64 / 2); // equilibrate (melts the lattice above phi = 0.3)
    let (t0, tally0) = (e.time(), e.counters());
    e.run_collisions(per_particle * n as u64 / 2);
    let (dt, tally) = (e.time() - t0, e.counters());
    let temperature = temperature(e.system());
    let s = e.system();
    let density = n as f64 / s.volume();
    let chi = (1.0 - phi / 2.0) / (1.0 - phi).powi(3);
    let enskog = 4.0 * std::f64::consts::PI.sqrt() * density * temperature.sqrt() * chi;
    let collisions = (tally.collisions - tally0.collisions) as f64;
    let frequency = 2.0 * collisions / (n as f64 * dt);
    let z = 1.0 + (tally.virial - tally0.virial) / (3.0 * n as f64 * temperature * dt);
    let cs = (1.0 + phi + phi * phi - phi.powi(3)) / (1.0 - phi).powi(3);
    eprintln!(
        "phi = {phi}: omega/omega_E = {:.4}, Z/Z_CS = {:.4}",
        frequency / enskog,
        z / cs
    );
    assert!(
        (frequency / enskog - 1.0).abs() < tolerance,
        "phi = {phi}: collision frequency"
    );
    assert!((z / cs - 1.0).abs() < tolerance, "phi = {phi}: pressure");
}

#[test]
fn enskog_and_carnahan_starling() {
    enskog_check(0.05, 2000, 40, 0.02);
    enskog_check(0.3, 2000, 40, 0.02);
}

/// The 1 % validation of issue 4 over phi = 0.05 .. 0.4:
/// `cargo test --release -p haff-gas --test emd -- --ignored --nocapture`
#[test]
#[ignore]
fn enskog_and_carnahan_starling_one_percent() {
    for phi in [0.05, 0.1, 0.2, 0.3, 0.4] {
        enskog_check(phi, 20_000, 100, 0.01);
    }
}

/// Viscoelastic spheres (fast law, beta = 1): T(t) approaches t^(-5/3) at late times
/// (Brilliantov & Pöschel, Kinetic Theory of Granular Gases, Ch. 8). Measured with
/// `haff run` (N = 2000, 3000 collisions per particle): local exponent -1.671.
#[test]
fn viscoelastic_gas_cools_as_t_to_minus_five_thirds() {
    use restitution::{ScaledForm, Viscoelastic};
    let system = monodisperse::<3>(1000, 0.05, 1.0, 1.0, 1.0, 4).unwrap();
    let law = Viscoelastic::new(1.0, "fast".parse::<ScaledForm>().unwrap()).unwrap();
    let mut e = EventDriven::new(system, Box::new(law)).unwrap();
    e.run_collisions(1000 * 500 / 2); // 500 collisions per particle
    let (t0, temp0) = (e.time(), temperature(e.system()));
    e.run_collisions(1000 * 1000 / 2); // to 1500 per particle
    let (t1, temp1) = (e.time(), temperature(e.system()));
    let exponent = (temp1 / temp0).ln() / (t1 / t0).ln();
    eprintln!("local exponent of T(t): {exponent:.4}");
    assert!((exponent + 5.0 / 3.0).abs() < 0.05, "{exponent}");
}

/// Haff's law in time: T(t) = T0 / (1 + t / t0)^2, 1/t0 = zeta0 / 2 with the cooling rate
/// zeta0 = (1 - eps^2)/3 omega_E (1 + a2/4), omega_E the Enskog collision frequency at T0
/// (Carnahan–Starling chi) and a2 = -0.0146 of the homogeneous cooling state (eps = 0.9).
/// No parameter is fitted; measured T/T_Haff = 1.0003, 1.0048, 1.0160, 1.0091 at t/t0 =
/// 0.5, 1, 2, 4.
#[test]
fn haff_law_in_time() {
    let (n, phi, eps) = (4000, 0.05, 0.9f64);
    let mut e = engine::<3>(n, phi, eps, 17);
    let density = n as f64 / e.system().volume();
    let chi = (1.0 - phi / 2.0) / (1.0 - phi).powi(3);
    let omega = 4.0 * std::f64::consts::PI.sqrt() * density * chi;
    let zeta0 = (1.0 - eps * eps) / 3.0 * omega * (1.0 - 0.0146 / 4.0);
    let t0 = 2.0 / zeta0;
    let mut worst: f64 = 0.0;
    for t in [0.5 * t0, t0, 2.0 * t0, 4.0 * t0] {
        e.run_until(t);
        let haff = 1.0 / (1.0 + t / t0).powi(2);
        let ratio = temperature(e.system()) / haff;
        eprintln!("t/t0 = {:.1}: T/T_Haff = {ratio:.4}", t / t0);
        worst = worst.max((ratio - 1.0).abs());
    }
    assert!(worst < 0.03, "{worst}");
}

/// The Sonine coefficient a2 of the homogeneous cooling state against van Noije & Ernst
/// (1998), a2 = 16 (1 - eps)(1 - 2 eps^2) / (81 - 17 eps + 30 eps^2 (1 - eps)) in 3D: the
/// mean of 70 snapshots from 5 to 40 collisions per particle, its standard error from 7
/// batches. The first-order Sonine value itself is uncertain by about 0.01 at eps = 0.5
/// (second-order corrections, Brilliantov & Pöschel 2006), which the bound includes.
/// Measured: eps = 0.5: 0.0618 (theory 0.0525), eps = 0.9: -0.0197 (theory -0.0146). This
/// box (L = 15 mean free paths) is near the size at which the HCS turns unstable; the
/// precise comparison with the exact Enskog–Boltzmann value (DSMC) is `sonine_a2_study`.
#[test]
fn sonine_a2_of_the_homogeneous_cooling_state() {
    for (eps, seed) in [(0.5f64, 31), (0.9, 32)] {
        let mut e = engine::<3>(4000, 0.05, eps, seed);
        e.run_collisions(5 * 4000 / 2);
        let batches: Vec<f64> = (0..7)
            .map(|_| {
                (0..10)
                    .map(|_| {
                        e.run_collisions(4000 / 4);
                        gas::observe::sonine_a2(e.system())
                    })
                    .sum::<f64>()
                    / 10.0
            })
            .collect();
        let a2 = batches.iter().sum::<f64>() / 7.0;
        let var = batches.iter().map(|b| (b - a2).powi(2)).sum::<f64>() / 6.0;
        let error = (var / 7.0).sqrt();
        let theory = 16.0 * (1.0 - eps) * (1.0 - 2.0 * eps * eps)
            / (81.0 - 17.0 * eps + 30.0 * eps * eps * (1.0 - eps));
        eprintln!("eps = {eps}: a2 = {a2:.4} +- {error:.4}, van Noije-Ernst {theory:.4}");
        assert!(
            (a2 - theory).abs() < 3.0 * error + 0.01,
            "eps = {eps}: a2 = {a2}"
        );
    }
}

/// Dense initial states are melted: no particle is left on its lattice site, the
/// temperature is the requested one, and the state is fixed by the seed.
#[test]
fn dense_states_are_melted_lattices() {
    let a = monodisperse::<3>(1000, 0.4, 1.0, 1.0, 2.0, 8).unwrap();
    let b = monodisperse::<3>(1000, 0.4, 1.0, 1.0, 2.0, 8).unwrap();
    assert_eq!(a, b);
    assert!((temperature(&a) - 2.0).abs() < 1e-10);
    let side = 10.0;
    let spacing = a.sides[0] / side;
    let on_site = a
        .positions
        .iter()
        .filter(|p| {
            p.iter()
                .all(|x| ((x / spacing - 0.5) - (x / spacing - 0.5).round()).abs() < 1e-6)
        })
        .count();
    assert_eq!(on_site, 0);
}

/// a2 of the homogeneous cooling state from 10 to 50 collisions per particle in `batches`
/// batch means of 5 collisions per particle (10 snapshots each), after `run(k)` advances
/// k collisions per particle and `a2()` measures.
fn a2_batches(mut run: impl FnMut(f64), mut a2: impl FnMut() -> f64, batches: usize) -> Vec<f64> {
    run(10.0);
    (0..batches)
        .map(|_| {
            (0..10)
                .map(|_| {
                    run(0.5);
                    a2()
                })
                .sum::<f64>()
                / 10.0
        })
        .collect()
}

/// The a2 study of issue 4: a2 of the homogeneous cooling state for eps = 0.3 ... 0.9 by
/// eMD (N = 20000, phi = 0.005, four seeds, 32 batches) against the homogeneous DSMC
/// engine (exact Enskog–Boltzmann HCS, N = 2e5, four seeds, 32 batches), both printed beside van Noije
/// & Ernst (1998). The density is low so that the box (L = 5.8 mean free paths) stays below
/// the size at which the HCS turns unstable: at phi = 0.05, N = 20000 (L = 27 mean free
/// paths) growing shear modes raise a2 by 0.002 at eps = 0.9 and lower it by 0.02 at eps =
/// 0.3 (docs/event-driven.md). Asserted: eMD and DSMC agree within 3 combined errors.
/// `cargo test --release -p haff-gas --test emd sonine_a2_study -- --ignored --nocapture`
#[test]
#[ignore]
fn sonine_a2_study() {
    use gas::dsmc::{point_gas, Scheme};
    use gas::HomogeneousDsmc;
    let (n, phi) = (20_000, 0.005);
    for eps in [0.3f64, 0.5, 0.7, 0.8, 0.9] {
        let mut md = Vec::new();
        for seed in 0..4 {
            let system = monodisperse::<3>(n, phi, 1.0, 1.0, 1.0, 50 + seed).unwrap();
            let law = Box::new(Constant::new(eps).unwrap());
            // Cells of 4 diameters: fewer crossings in this dilute gas.
            let e =
                std::cell::RefCell::new(EventDriven::with_cell_width(system, law, 4.0).unwrap());
            md.extend(a2_batches(
                |k| e.borrow_mut().run_collisions((k * n as f64 / 2.0) as u64),
                || gas::observe::sonine_a2(e.borrow_mut().system()),
                8,
            ));
        }
        let big = 200_000;
        let length = gas::system::monodisperse_box_side::<3>(big, 1.0, phi);
        let mut dsmc = Vec::new();
        for seed in 7..11 {
            let system = point_gas::<3>(big, length, 1.0, 1.0, 1.0, seed).unwrap();
            let law = Box::new(Constant::new(eps).unwrap());
            let d = std::cell::RefCell::new(
                HomogeneousDsmc::new(system, phi, law, seed, Scheme::default()).unwrap(),
            );
            dsmc.extend(a2_batches(
                |k| d.borrow_mut().run_collisions((k * big as f64 / 2.0) as u64),
                || gas::observe::sonine_a2(d.borrow_mut().system()),
                8,
            ));
        }
        let ((a_md, e_md), (a_dsmc, e_dsmc)) = (mean_and_error(&md), mean_and_error(&dsmc));
        let theory = 16.0 * (1.0 - eps) * (1.0 - 2.0 * eps * eps)
            / (81.0 - 17.0 * eps + 30.0 * eps * eps * (1.0 - eps));
        let combined = e_md.hypot(e_dsmc);
        eprintln!(
            "eps = {eps}: eMD a2 = {a_md:.5} +- {e_md:.5}, DSMC {a_dsmc:.5} +- {e_dsmc:.5}, (eMD - DSMC)/error = {:.2}, van Noije-Ernst {theory:.5}",
            (a_md - a_dsmc) / combined
        );
        assert!((a_md - a_dsmc).abs() < 3.0 * combined, "eps = {eps}");
    }
}
