//! Rough spheres and disks in the event-driven engine and DSMC (homogeneous and
//! spatial): energy kept to round-off when alpha = beta = 1, the smooth rule bit for bit
//! when beta = -1, the rotational temperature's rise from rest against the Maxwellian
//! theory (`gas::theory::rough`), and a check-point's continuation bit for bit. (What
//! only the spatial engine has: `tests/rough_spatial.rs`.)

mod common;

use common::{constant, mean_and_error};
use gas::dsmc::{Scheme, SpatialOptions};
use gas::observe::{kinetic_energy, sonine_a2, temperature};
use gas::rotation::Rotation;
use gas::theory::rough::RoughMaxwellian;
use gas::{Checkpoint, Engine, EventDriven, HomogeneousDsmc, SpatialDsmc};
use restitution::rough::{Rough, Tangential};
use restitution::Restitution;

fn rough(alpha: f64, beta: f64, friction: Option<f64>) -> Box<dyn Restitution> {
    Box::new(Rough::new(constant(alpha), Tangential::new(beta, friction).unwrap()).unwrap())
}

fn rotational_temperature<const D: usize>(engine: &mut EventDriven<D>) -> f64 {
    let system = engine.system().clone();
    engine.rotation().unwrap().temperature(&system, None)
}

fn total_energy<const D: usize>(engine: &mut EventDriven<D>) -> f64 {
    let system = engine.system().clone();
    kinetic_energy(&system) + engine.rotation().unwrap().energy(&system)
}

/// alpha = beta = 1: no energy is lost, translation and rotation exchange it (the
/// oracle: conservation, to round-off over 20 000 collisions).
#[test]
fn perfectly_rough_elastic_spheres_keep_their_energy() {
    let system = gas::init::monodisperse::<3>(500, 0.1, 1.0, 1.0, 1.0, 4).unwrap();
    let rotation = Rotation::thermal(&system, vec![0.4; 500], 0.3, 4);
    let mut engine = EventDriven::new(system, rough(1.0, 1.0, None)).unwrap();
    engine.set_rotation(Some(rotation)).unwrap();
    let start = total_energy(&mut engine);
    let t_rot = rotational_temperature(&mut engine);
    engine.run_collisions(20_000);
    let end = total_energy(&mut engine);
    assert!((end - start).abs() < 1e-11 * start, "{start} -> {end}");
    assert!(engine.counters().energy_lost.abs() < 1e-11 * start);
    // The rotational temperature left 0.3 for equipartition's 1 - ...: it moved.
    let after = rotational_temperature(&mut engine);
    assert!(after > t_rot + 0.2, "{t_rot} -> {after}");
}

/// beta = -1: the same collisions as the smooth law bit for bit, spins untouched.
#[test]
fn beta_minus_one_is_the_smooth_gas_bit_for_bit() {
    let system = gas::init::monodisperse::<2>(400, 0.2, 1.0, 1.0, 1.0, 8).unwrap();
    let rotation = Rotation::thermal(&system, vec![0.5; 400], 1.0, 8);
    let mut smooth = EventDriven::new(system.clone(), constant(0.7)).unwrap();
    let mut rough_engine = EventDriven::new(system, rough(0.7, -1.0, None)).unwrap();
    rough_engine.set_rotation(Some(rotation.clone())).unwrap();
    smooth.run_collisions(5000);
    rough_engine.run_collisions(5000);
    assert_eq!(smooth.system(), rough_engine.system());
    assert_eq!(smooth.counters(), rough_engine.counters());
    assert_eq!(rough_engine.rotation().unwrap().angular, rotation.angular);
    // DSMC: the rough records (with their spins) run the smooth gas's process.
    for scheme in [Scheme::Exact, Scheme::default()] {
        let system = gas::init::monodisperse::<3>(2000, 0.1, 1.0, 1.0, 1.0, 8).unwrap();
        let rotation = Rotation::thermal(&system, vec![0.4; 2000], 1.0, 8);
        let mut smooth =
            HomogeneousDsmc::new(system.clone(), 0.1, constant(0.7), 3, scheme).unwrap();
        let mut spun =
            HomogeneousDsmc::new(system, 0.1, rough(0.7, -1.0, None), 3, scheme).unwrap();
        spun.set_rotation(Some(rotation.clone())).unwrap();
        smooth.run_collisions(5000);
        spun.run_collisions(5000);
        assert_eq!(smooth.system(), spun.system(), "{scheme:?}");
        assert_eq!(smooth.counters(), spun.counters());
        // The blocks permute the records: compare the sets of spins.
        assert_same_spins(&rotation, spun.rotation().unwrap());
    }
    // Spatial DSMC likewise (its records sorted into cells every step; that each spin
    // stays with its particle: `tests/rough_spatial.rs`).
    let system = gas::init::monodisperse::<2>(2000, 0.1, 1.0, 1.0, 1.0, 8).unwrap();
    let rotation = Rotation::thermal(&system, vec![0.5; 2000], 1.0, 8);
    let options = SpatialOptions::default();
    let mut smooth = SpatialDsmc::new(system.clone(), 0.1, constant(0.7), 3, options).unwrap();
    let mut spun = SpatialDsmc::new(system, 0.1, rough(0.7, -1.0, None), 3, options).unwrap();
    spun.set_rotation(Some(rotation.clone())).unwrap();
    smooth.run_collisions(5000);
    spun.run_collisions(5000);
    assert_eq!(smooth.system(), spun.system(), "spatial");
    assert_eq!(smooth.counters(), spun.counters());
    assert_same_spins(&rotation, spun.rotation().unwrap());
}

/// From rest (T_rot = 0) with Gaussian velocities the rotational temperature rises as
/// the Maxwellian theory's exact solution of its linear equations says
/// (`RoughMaxwellian::evolve`), in the event-driven engine and the three DSMC schemes.
/// Tolerance: 4 standard errors over 4 seeds plus |a2| measured at the end (the first
/// Sonine corrections to the rates are of order a2 with coefficients below one, Santos,
/// Kremer & Garzó 2010).
#[test]
fn rotation_rises_from_rest_as_the_maxwellian_theory_says() {
    fn case<const D: usize>(engine: &str, alpha: f64, beta: f64, q: f64) {
        let n = 4000;
        let (mut ratios, mut translational, mut a2) = (vec![], vec![], 0.0f64);
        let mut tau = 0.0;
        for seed in 0..4 {
            let system = gas::init::monodisperse::<D>(n, 0.05, 1.0, 1.0, 1.0, seed).unwrap();
            let t0 = temperature(&system);
            let law = rough(alpha, beta, None);
            let mut engine: Box<dyn Engine<D>> = match engine {
                "event-driven" => Box::new(EventDriven::new(system, law).unwrap()),
                "exact" => {
                    Box::new(HomogeneousDsmc::new(system, 0.05, law, seed, Scheme::Exact).unwrap())
                }
                "spatial" => Box::new(
                    SpatialDsmc::new(system, 0.05, law, seed, SpatialOptions::default()).unwrap(),
                ),
                _ => Box::new(
                    HomogeneousDsmc::new(system, 0.05, law, seed, Scheme::default()).unwrap(),
                ),
            };
            engine.set_rotation(Some(Rotation::at_rest(n, q))).unwrap();
            engine.run_collisions(n as u64 / 2);
            tau = engine.collisions_per_particle();
            let system = engine.system().clone();
            let t_rot = engine.rotation().unwrap().temperature(&system, None);
            ratios.push(t_rot / t0);
            translational.push(temperature(&system) / t0);
            a2 = a2.max(sonine_a2(&system).abs());
        }
        let theory = RoughMaxwellian {
            dimension: D,
            alpha,
            beta,
            inertia: q,
        };
        let [t_tr, t_rot] = theory.evolve([1.0, 0.0], tau);
        for (what, values, expected) in [("T_rot", &ratios, t_rot), ("T_tr", &translational, t_tr)]
        {
            let (mean, error) = mean_and_error(values);
            let tolerance = 4.0 * error + a2 * expected;
            assert!(
                (mean - expected).abs() < tolerance,
                "{engine} D = {D}, alpha {alpha}, beta {beta}: {what} {mean} ± {error} vs {expected} (a2 {a2}, tau {tau})"
            );
        }
    }
    for engine in ["event-driven", "exact", "blocks", "spatial"] {
        case::<3>(engine, 0.9, 0.4, 0.4);
        case::<2>(engine, 0.8, 0.8, 0.5);
    }
}

/// A rough gas with Walton's friction continues bit for bit from its check-point
/// (spins, sliding count and all).
#[test]
fn a_rough_gas_continues_from_its_checkpoint() {
    let system = gas::init::monodisperse::<3>(300, 0.15, 1.0, 1.0, 1.0, 2).unwrap();
    let rotation = Rotation::thermal(&system, vec![0.4; 300], 1.0, 2);
    let law = rough(0.8, 0.5, Some(0.2));
    let mut engine = EventDriven::new(system, law.clone()).unwrap();
    engine.set_rotation(Some(rotation)).unwrap();
    engine.run_collisions(3000);
    let text = serde_json::to_string(&engine.save()).unwrap();
    let mut restored =
        EventDriven::<3>::restore(serde_json::from_str(&text).unwrap(), law).unwrap();
    engine.run_collisions(3000);
    restored.run_collisions(3000);
    assert_eq!(engine.system(), restored.system());
    assert_eq!(engine.counters(), restored.counters());
    let (a, b) = (
        engine.rotation().unwrap().clone(),
        restored.rotation().unwrap().clone(),
    );
    assert_eq!(a, b);
    assert!(
        a.sliding > 0 && a.sliding < 6000,
        "some contacts slide: {}",
        a.sliding
    );
    let start = || {
        let system = gas::init::monodisperse::<2>(1000, 0.15, 1.0, 1.0, 1.0, 2).unwrap();
        let rotation = Rotation::thermal(&system, vec![0.5; 1000], 1.0, 2);
        (system, rotation, rough(0.8, 0.5, Some(0.2)))
    };
    for scheme in [Scheme::Exact, Scheme::default()] {
        let (system, rotation, law) = start();
        let engine = HomogeneousDsmc::new(system, 0.15, law.clone(), 4, scheme).unwrap();
        resumes_bit_for_bit(engine, rotation, law, &format!("{scheme:?}"));
    }
    let (system, rotation, law) = start();
    let engine = SpatialDsmc::new(system, 0.15, law.clone(), 4, SpatialOptions::default()).unwrap();
    resumes_bit_for_bit(engine, rotation, law, "spatial");
}

/// A DSMC engine given `rotation`, run 3000 collisions, saved through JSON and restored
/// with `law`, continues 3000 more as the uninterrupted engine, spins and sliding count too.
fn resumes_bit_for_bit<E>(mut engine: E, rotation: Rotation, law: Box<dyn Restitution>, what: &str)
where
    E: Checkpoint<2, Needs = Box<dyn Restitution>>,
{
    engine.set_rotation(Some(rotation)).unwrap();
    engine.run_collisions(3000);
    let text = serde_json::to_string(&engine.save()).unwrap();
    let mut restored = E::restore(serde_json::from_str(&text).unwrap(), law).unwrap();
    engine.run_collisions(3000);
    restored.run_collisions(3000);
    assert_eq!(engine.system(), restored.system(), "{what}");
    assert_eq!(engine.counters(), restored.counters(), "{what}");
    let (a, b) = (
        engine.rotation().unwrap().clone(),
        restored.rotation().unwrap().clone(),
    );
    assert_eq!(a, b, "{what}");
    assert!(a.sliding > 0, "{what}: some contacts slide");
}

/// `set_rotation(None)`: on a gas without rotation it leaves the particles as they are
/// (the homogeneous engine once dropped them all: its smooth records were swapped for the
/// placeholder's empty store); on a spinning gas of a smooth law it takes the spins away
/// and keeps the rest; a rough law's gas refuses it. Homogeneous and spatial DSMC.
#[test]
fn taking_the_rotation_away_keeps_the_particles() {
    let system = gas::init::monodisperse::<3>(500, 0.1, 1.0, 1.0, 1.0, 6).unwrap();
    let rotation = Rotation::thermal(&system, vec![0.4; 500], 1.0, 6);
    let make = |scheme: &str, law: Box<dyn Restitution>| -> Box<dyn Engine<3>> {
        let s = system.clone();
        match scheme {
            "exact" => Box::new(HomogeneousDsmc::new(s, 0.1, law, 1, Scheme::Exact).unwrap()),
            "blocks" => Box::new(HomogeneousDsmc::new(s, 0.1, law, 1, Scheme::default()).unwrap()),
            _ => Box::new(SpatialDsmc::new(s, 0.1, law, 1, SpatialOptions::default()).unwrap()),
        }
    };
    for scheme in ["exact", "blocks", "spatial"] {
        let mut e = make(scheme, constant(0.8));
        let before = e.system().clone();
        e.set_rotation(None).unwrap();
        assert_eq!(e.system(), &before, "{scheme}: no rotation to take");
        e.set_rotation(Some(rotation.clone())).unwrap();
        assert_eq!(e.rotation().unwrap().angular, rotation.angular);
        e.set_rotation(None).unwrap();
        assert!(e.rotation().is_none());
        assert_eq!(e.system(), &before, "{scheme}: spins taken away");
        let mut rough_engine = make(scheme, rough(0.8, 0.3, None));
        assert!(rough_engine.set_rotation(None).is_err(), "{scheme}");
    }
}

/// Rough viscoelastic spheres (the normal restitution of the viscoelastic law, fast form,
/// beta_v = 0.3; tangential beta = 0, q = 0.4) cool per collision as the Maxwellian theory
/// with the collision-averaged normal loss says (`gas::theory::rough_viscoelastic`), from
/// T_rot = T_tr to 40 collisions per particle (T_tr falls ~1e-3), in DSMC exact and blocks.
/// Tolerance: 4 standard errors over 4 seeds plus the first Sonine corrections' order,
/// |a2| per unit of ln T travelled ((1 + |ln(T/T_0)|) |a2| T, a2 the largest measured).
#[test]
fn rough_viscoelastic_spheres_cool_as_the_theory_says() {
    use gas::theory::rough_viscoelastic::RoughViscoelastic;
    use restitution::{ScaledForm, Viscoelastic};
    let (n, q, beta) = (4000, 0.4, 0.0);
    let normal = || Viscoelastic::new(0.3, "fast".parse::<ScaledForm>().unwrap()).unwrap();
    let taus = [10.0, 20.0, 40.0];
    let theory = RoughViscoelastic {
        dimension: 3,
        beta,
        inertia: q,
        mass: 1.0,
    };
    let law_of_speed = normal();
    let expected = theory.evolve(&|g| law_of_speed.eps(g), [1.0, 1.0], &taus, 0.02);
    for scheme in [Scheme::Exact, Scheme::default()] {
        let mut measured = vec![(vec![], vec![]); taus.len()];
        let mut a2 = 0.0f64;
        for seed in 0..4 {
            let system = gas::init::monodisperse::<3>(n, 0.05, 1.0, 1.0, 1.0, seed).unwrap();
            let law = Box::new(
                Rough::new(Box::new(normal()), Tangential::new(beta, None).unwrap()).unwrap(),
            );
            let t0 = temperature(&system);
            let spins = Rotation::thermal(&system, vec![q; n], t0, seed);
            let mut engine = HomogeneousDsmc::new(system, 0.05, law, seed, scheme).unwrap();
            engine.set_rotation(Some(spins)).unwrap();
            for (k, &tau) in taus.iter().enumerate() {
                let target = (tau * n as f64 / 2.0) as u64;
                engine.run_collisions(target - engine.counters().collisions);
                let system = engine.system().clone();
                let t_rot = engine.rotation().unwrap().temperature(&system, None);
                measured[k].0.push(temperature(&system) / t0);
                measured[k].1.push(t_rot / t0);
                a2 = a2.max(sonine_a2(&system).abs());
            }
        }
        for (k, want) in expected.iter().enumerate() {
            for (what, values, expected) in [
                ("T_tr", &measured[k].0, want[0]),
                ("T_rot", &measured[k].1, want[1]),
            ] {
                let (mean, error) = mean_and_error(values);
                let tolerance = 4.0 * error + a2 * (1.0 - expected.ln()) * expected;
                println!(
                    "{scheme:?} tau {}: {what} {mean:.5e} ± {error:.1e} vs {expected:.5e} (a2 {a2:.3})",
                    taus[k]
                );
                assert!(
                    (mean - expected).abs() < tolerance,
                    "{scheme:?} {what} tau {}",
                    taus[k]
                );
            }
        }
    }
}

/// The same angular velocities, in any order (engines that permute their records).
fn assert_same_spins(before: &Rotation, after: &Rotation) {
    let sorted = |r: &Rotation| {
        let mut spins = r.angular.clone();
        spins.sort_by(|a, b| a.partial_cmp(b).unwrap());
        spins
    };
    assert_eq!(sorted(before), sorted(after));
}
