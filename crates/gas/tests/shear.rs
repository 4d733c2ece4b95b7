//! Uniform shear flow: Lees–Edwards boundaries in the event-driven engine, the USF of the
//! homogeneous DSMC in the frame of the flow, the tensor virial, their check-points.
//!
//! Oracles: the O(N^2) search for a collision the engine would miss, over every image
//! across the sliding faces; the exact solution of the streaming V_x(t) = V_x - a V_y t; the
//! trace of the tensor virial, which is the scalar virial summed independently; a restored
//! engine that must continue bit for bit; the kinetic theory of the sheared gas's energy
//! balance dT/dt = -2 a P_xy / (D n) - zeta T (Garzó & Santos 2003, Eq. (2.16)), with
//! the cooling measured by the engine's own tally of lost energy.

use gas::dsmc::{Scheme, StepSize};
use gas::observe::{pressure_tensor, temperature};
use gas::shear::{Shear, Virial};
use gas::{Checkpoint, Engine, EventDriven, HomogeneousDsmc};
use restitution::Constant;

fn law(eps: f64) -> Box<Constant> {
    Box::new(Constant::new(eps).unwrap())
}

fn sheared<const D: usize>(n: usize, phi: f64, eps: f64, rate: f64, seed: u64) -> EventDriven<D> {
    let system = gas::init::monodisperse::<D>(n, phi, 1.0, 1.0, 1.0, seed).unwrap();
    let mut engine = EventDriven::new(system, law(eps)).unwrap();
    engine.set_shear(Some(Shear::new(rate).unwrap())).unwrap();
    engine.set_virial_tensor(true);
    engine
}

/// No pair ever comes closer than contact unseen: every 40 events, the earliest collision
/// over all pairs and all their images across the sliding faces is not earlier than the
/// scheduled events (or the next shift of the columns, when every sphere is checked
/// against the columns its windows gained), and every sphere lies in its cell of the rows
/// that slide with the flow. Rates fast enough that the images slide several boxes along x;
/// in the dilute case spheres fly boxes along x between their events.
fn no_collision_is_missed<const D: usize>(n: usize, phi: f64, rate: f64) {
    let mut engine = sheared::<D>(n, phi, 0.9, rate, 3);
    for step in 0..30_000 {
        assert!(engine.step());
        if step % 40 == 0 {
            if let Some((i, j, t)) = engine.missed_collision() {
                panic!("{D}D rate {rate}: pair ({i}, {j}) collides at {t} unseen (step {step})");
            }
            if let Some(i) = engine.misplaced_sphere() {
                panic!("{D}D rate {rate}: sphere {i} is outside its cell (step {step})");
            }
        }
    }
    let sides = engine.system().sides;
    let slid = rate * sides[1] * engine.time() / sides[0];
    assert!(slid.abs() > 2.0, "the images slid {slid} boxes only");
}

#[test]
fn no_collision_is_missed_across_the_sliding_faces_2d() {
    no_collision_is_missed::<2>(300, 0.25, 1.5);
    no_collision_is_missed::<2>(300, 0.25, -0.7);
    no_collision_is_missed::<2>(300, 0.03, 1.0);
}

#[test]
fn no_collision_is_missed_across_the_sliding_faces_3d() {
    no_collision_is_missed::<3>(400, 0.25, 2.0);
    no_collision_is_missed::<3>(400, 0.25, -1.0);
    no_collision_is_missed::<3>(400, 0.03, 1.0);
}

/// A sheared engine saved and restored continues bit for bit (positions, lab velocities
/// in the state, the tensor virial), and its state says it is sheared.
#[test]
fn a_sheared_engine_continues_bit_for_bit_after_a_restore() {
    let mut engine = sheared::<3>(500, 0.2, 0.85, 0.8, 11);
    engine.run_collisions(3000);
    let state = engine.save();
    assert_eq!(state.tail.shear, Some(Shear { rate: 0.8 }));
    let mut copy = EventDriven::restore(state, law(0.85)).unwrap();
    engine.run_collisions(5000);
    copy.run_collisions(5000);
    assert_eq!(engine.time(), copy.time());
    assert_eq!(engine.counters(), copy.counters());
    assert_eq!(engine.virial_tensor(), copy.virial_tensor());
    assert!(engine.system() == copy.system(), "the restored run differs");
}

/// The tensor virial's trace is the scalar virial, summed independently; under shear the
/// collisional stress has the sign of momentum carried down the gradient (P_xy < 0 for
/// a > 0).
#[test]
fn the_tensor_virial_traces_to_the_scalar_virial_and_opposes_the_shear() {
    let mut engine = sheared::<2>(1000, 0.3, 0.9, 0.5, 5);
    engine.run_collisions(20_000);
    let v = engine.virial_tensor().unwrap();
    let trace = v.get(0, 0) + v.get(1, 1);
    let scalar = engine.counters().virial;
    assert!(
        (trace - scalar).abs() <= 1e-10 * scalar,
        "{trace} vs {scalar}"
    );
    assert!(v.get(0, 1) < 0.0, "collisional xy {}", v.get(0, 1));
}

/// The peculiar velocities the engine reports have no flow left: their mean is the
/// thermal noise's (|<V_x>| within 5 standard errors sqrt(T / N)), while the lab
/// velocities of the state carry the profile a y.
#[test]
fn the_reported_velocities_are_peculiar() {
    let rate = 0.6;
    let mut engine = sheared::<2>(2000, 0.1, 0.9, rate, 8);
    engine.run_collisions(10_000);
    let s = engine.system().clone();
    let n = s.len() as f64;
    let t = temperature(&s);
    let mean: f64 = s.velocities.iter().map(|v| v[0]).sum::<f64>() / n;
    assert!(mean.abs() < 5.0 * (t / n).sqrt(), "<V_x> = {mean}");
    let lab = engine.save().system;
    let slope = {
        // Least squares of v_x on y.
        let ym = lab.positions.iter().map(|p| p[1]).sum::<f64>() / n;
        let vm = lab.velocities.iter().map(|v| v[0]).sum::<f64>() / n;
        let sxy: f64 = lab
            .positions
            .iter()
            .zip(&lab.velocities)
            .map(|(p, v)| (p[1] - ym) * (v[0] - vm))
            .sum();
        let syy: f64 = lab.positions.iter().map(|p| (p[1] - ym).powi(2)).sum();
        sxy / syy
    };
    assert!(
        (slope - rate).abs() < 0.1 * rate,
        "lab profile slope {slope}"
    );
}

/// The homogeneous DSMC's streaming is exact: in a gas too dilute to collide in the time
/// (phi = 1e-12), V_x(t) = V_x(0) - a V_y(0) t for every particle.
#[test]
fn the_homogeneous_streaming_is_the_exact_solution() {
    let system = gas::init::monodisperse::<3>(2000, 0.1, 1.0, 1.0, 1.0, 2).unwrap();
    let before = system.velocities.clone();
    let scheme = Scheme::Blocks {
        block_size: 2000,
        step: StepSize::Fixed(0.25),
    };
    let mut engine = HomogeneousDsmc::new(system, 1e-12, law(0.9), 1, scheme).unwrap();
    engine.set_shear(Some(Shear::new(0.7).unwrap())).unwrap();
    engine.run_until(2.0);
    assert_eq!(engine.counters().collisions, 0);
    let mut after = engine.system().velocities.clone();
    // The blocks permute particles: compare the sorted components.
    let mut expected: Vec<[f64; 3]> = before
        .iter()
        .map(|v| [v[0] - 0.7 * v[1] * 2.0, v[1], v[2]])
        .collect();
    let key = |v: &[f64; 3]| (v[1].to_bits(), v[2].to_bits());
    expected.sort_by_key(key);
    after.sort_by_key(key);
    for (a, b) in after.iter().zip(&expected) {
        assert!((a[0] - b[0]).abs() < 1e-13, "{a:?} vs {b:?}");
        assert_eq!((a[1], a[2]), (b[1], b[2]));
    }
}

/// The energy balance of the homogeneous USF, dT/dt = -2 a P^k_xy / (D n) - zeta T, holds
/// for the measured kinetic pressure tensor and the engine's own tally of the energy lost
/// (zeta T = 2 ΔE_lost / (D N Δt)) over an interval of the transient: an identity of the
/// scheme (streaming exact, collisions conserving momentum), so only the trapezoid rule
/// of the integral of P_xy errs (samples 0.05 apart, a tenth of a mean free time: below
/// 1e-3 of T). In the homogeneous description the collisions transfer no momentum across a
/// distance, so the collisional stress does no work (the Enskog term is the spatial
/// engines'). A sheared DSMC state restores bit for bit.
#[test]
fn the_homogeneous_usf_balances_its_energy() {
    let n = 20_000;
    let system = gas::init::monodisperse::<3>(n, 0.1, 1.0, 1.0, 1.0, 4).unwrap();
    let scheme = Scheme::Blocks {
        block_size: 128,
        step: StepSize::CollisionsPerParticle(0.02),
    };
    let mut engine = HomogeneousDsmc::new(system, 0.05, law(0.8), 9, scheme).unwrap();
    let rate = 0.5;
    engine.set_shear(Some(Shear::new(rate).unwrap())).unwrap();
    engine.set_virial_tensor(true).unwrap();
    engine.run_collisions(20 * n as u64);
    let state = engine.save();
    let mut copy = HomogeneousDsmc::restore(state, law(0.8)).unwrap();
    let (t0, lost0) = (temperature(engine.system()), engine.counters().energy_lost);
    let volume = engine.volume();
    let kinetic_xy = |e: &mut HomogeneousDsmc<3>| {
        pressure_tensor(e.system(), 1.0, &Virial::default(), 0.0).kinetic[3]
    };
    let mut integral = 0.0;
    let mut last = (engine.time(), kinetic_xy(&mut engine));
    for _ in 0..40 {
        let t = engine.time() + 0.05;
        engine.run_until(t);
        let now = kinetic_xy(&mut engine);
        integral += 0.5 * (engine.time() - last.0) * (now + last.1);
        last = (engine.time(), now);
    }
    let density = n as f64 / volume;
    let lost = engine.counters().energy_lost - lost0;
    let t1 = temperature(engine.system());
    let predicted = t0 - 2.0 * rate * integral / (3.0 * density) - 2.0 * lost / (3.0 * n as f64);
    assert!(
        (t1 - predicted).abs() < 1e-3 * t1,
        "T {t1} vs balance {predicted} (T0 {t0})"
    );
    assert!(last.1 < 0.0, "P^k_xy = {} should oppose the shear", last.1);
    for _ in 0..40 {
        let t = copy.time() + 0.05;
        copy.run_until(t);
    }
    assert!(copy.system() == engine.system(), "the restored run differs");
    assert_eq!(copy.virial_tensor(), engine.virial_tensor());
}
