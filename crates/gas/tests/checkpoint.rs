//! Every engine saved through JSON and restored continues bit for bit: the state of
//! `gas::Checkpoint` is complete (the TC model, baths and random streams included).

mod common;

use common::constant;
use gas::dsmc::{point_gas, Scheme, SpatialOptions};
use gas::{Checkpoint, Engine, EventDriven, HomogeneousDsmc, SpatialDsmc};
use restitution::{Glauber, Restitution};

/// Runs `engine` in two halves with a JSON round trip of its state between them, and
/// uninterrupted; both must agree exactly.
fn continues_bit_for_bit<const D: usize, E: Checkpoint<D, Needs = Box<dyn Restitution>>>(
    mut engine: E,
    law: &dyn Restitution,
    collisions: u64,
) {
    engine.run_collisions(collisions);
    let text = serde_json::to_string(&engine.save()).unwrap();
    let mut restored = E::restore(serde_json::from_str(&text).unwrap(), law.box_clone()).unwrap();
    engine.run_collisions(collisions);
    restored.run_collisions(collisions);
    assert_eq!(engine.time(), restored.time());
    assert_eq!(engine.counters(), restored.counters());
    assert_eq!(engine.system(), restored.system());
    assert_eq!(engine.bath_temperatures(), restored.bath_temperatures());
}

#[test]
fn event_driven_with_tc_model_and_baths() {
    let system = gas::init::monodisperse::<2>(400, 0.3, 1.0, 1.0, 1.0, 3).unwrap();
    let law = constant(0.5);
    let mut engine = EventDriven::new(system.clone(), law.box_clone()).unwrap();
    engine.set_tc_model(1e-3, None).unwrap();
    continues_bit_for_bit(engine, law.as_ref(), 4000);
    let glauber: Box<dyn Restitution> = Box::new(Glauber::new(10).unwrap());
    let mut engine = EventDriven::new(system, glauber.box_clone()).unwrap();
    engine.set_baths(vec![0.2; 400], 9).unwrap();
    continues_bit_for_bit(engine, glauber.as_ref(), 4000);
}

#[test]
fn dsmc_engines() {
    let law = constant(0.8);
    let system = point_gas::<3>(2000, 20.0, 1.0, 1.0, 1.0, 5).unwrap();
    for scheme in [Scheme::Exact, Scheme::default()] {
        let engine = HomogeneousDsmc::new(system.clone(), 0.1, law.box_clone(), 5, scheme).unwrap();
        continues_bit_for_bit(engine, law.as_ref(), 5000);
    }
    let engine =
        SpatialDsmc::new(system, 0.1, law.box_clone(), 5, SpatialOptions::default()).unwrap();
    continues_bit_for_bit(engine, law.as_ref(), 5000);
}

#[test]
fn a_state_of_another_dimension_is_refused() {
    let system = gas::init::monodisperse::<2>(100, 0.1, 1.0, 1.0, 1.0, 3).unwrap();
    let mut engine = EventDriven::new(system, constant(0.9)).unwrap();
    let text = serde_json::to_string(&engine.save()).unwrap();
    let error = serde_json::from_str::<gas::EventDrivenState<3>>(&text).unwrap_err();
    assert!(error.to_string().contains("3 components"), "{error}");
}

/// A driven event-driven run (white noise, then the thermostat) saved mid-way and restored,
/// its driving set again, continues bit for bit: the applications so far follow from the
/// time and each draws from its own stream. Also when the state is taken right at an
/// application (`run_until` a multiple of the interval).
#[test]
fn driven_event_driven_continues_bit_for_bit() {
    use gas::driving::{Drive, Driving, Thermostat, WhiteNoise};
    let system = gas::init::monodisperse::<3>(500, 0.1, 1.0, 1.0, 1.0, 4).unwrap();
    let law = constant(0.8);
    let interval = 0.01;
    for driving in [
        Driving::WhiteNoise(WhiteNoise::new(1.0).unwrap()),
        Driving::Thermostat(Thermostat::new(1.0).unwrap()),
    ] {
        let drive = Drive {
            driving,
            interval: Some(interval),
            seed: 7,
        };
        for halfway in [None, Some(2.0)] {
            let mut engine = EventDriven::new(system.clone(), law.box_clone()).unwrap();
            engine.set_driving(Some(drive)).unwrap();
            match halfway {
                None => engine.run_collisions(3000),
                Some(t) => engine.run_until(t),
            }
            let text = serde_json::to_string(&engine.save()).unwrap();
            let mut restored =
                EventDriven::restore(serde_json::from_str(&text).unwrap(), law.box_clone())
                    .unwrap();
            restored.set_driving(Some(drive)).unwrap();
            let end = engine.time() + 2.0;
            engine.run_until(end);
            restored.run_until(end);
            assert_eq!(engine.counters(), restored.counters());
            assert_eq!(engine.system(), restored.system());
            assert!(engine.counters().collisions > 1000);
        }
    }
}

/// A state tampered with (one velocity made NaN, one position moved out of the box) is
/// refused by every way back from a state: `Checkpoint::restore` of every engine, and the
/// DSMC engines' restore over ranks. The oracle is the state check each engine documents
/// (`EventDrivenState::check`, `Snapshot::check`, the soft-sphere restore), which no path
/// may skip.
#[test]
fn a_tampered_state_is_refused_through_every_path() {
    use gas::parallel::Local;
    use gas::soft::contact::ViscoelasticMaterial;
    use gas::{SoftSphere, SoftSphereOptions};
    use std::sync::Arc;
    let system = gas::init::monodisperse::<3>(200, 0.1, 1.0, 1.0, 1.0, 3).unwrap();
    let points = point_gas::<3>(200, system.sides, 1.0, 1.0, 1.0, 3).unwrap();
    let law = constant(0.9);
    let nan_velocity = |s: &mut gas::System<3>| s.velocities[7][1] = f64::NAN;
    let outside = |s: &mut gas::System<3>| s.positions[7][0] = 3.0 * s.sides[0];
    for (k, tamper) in [nan_velocity, outside].into_iter().enumerate() {
        let mut engine = EventDriven::new(system.clone(), law.box_clone()).unwrap();
        engine.run_collisions(100);
        let mut state = engine.save();
        tamper(&mut state.system);
        assert!(EventDriven::restore(state, law.box_clone()).is_err());

        for scheme in [Scheme::Exact, Scheme::default()] {
            let mut engine =
                HomogeneousDsmc::new(points.clone(), 0.1, law.box_clone(), 3, scheme).unwrap();
            engine.run_collisions(100);
            let mut state = engine.save();
            if k == 0 {
                tamper(&mut state.system);
            } else {
                // The homogeneous engine has no positions: a negative time instead.
                state.time = -1.0;
            }
            let local = Arc::new(Local);
            assert!(HomogeneousDsmc::restore(state.clone(), law.box_clone()).is_err());
            assert!(HomogeneousDsmc::restore_distributed(state, law.box_clone(), local).is_err());
        }

        let options = SpatialOptions::default();
        let mut engine =
            SpatialDsmc::new(points.clone(), 0.1, law.box_clone(), 3, options).unwrap();
        engine.run_collisions(100);
        let mut state = engine.save();
        tamper(&mut state.system);
        let local = Arc::new(Local);
        assert!(SpatialDsmc::restore(state.clone(), law.box_clone()).is_err());
        assert!(SpatialDsmc::restore_distributed(state, law.box_clone(), local).is_err());

        let material = ViscoelasticMaterial::new(1e5, 0.3, 0.01).unwrap();
        let mut engine =
            SoftSphere::new(system.clone(), material, SoftSphereOptions::default()).unwrap();
        engine.run_collisions(20);
        let mut state = engine.save();
        tamper(&mut state.system);
        assert!(SoftSphere::restore(state, ()).is_err());
    }
}
