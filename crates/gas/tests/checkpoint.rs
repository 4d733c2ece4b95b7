//! Every engine saved through JSON and restored continues bit for bit: the state of
//! `gas::Checkpoint` is complete (the TC model, baths and random streams included).

mod common;

use common::constant;
use gas::dsmc::{point_gas, Scheme, SpatialOptions};
use gas::{Checkpoint, EventDriven, HomogeneousDsmc, SpatialDsmc};
use restitution::{Glauber, Restitution};

/// Runs `engine` in two halves with a JSON round trip of its state between them, and
/// uninterrupted; both must agree exactly.
fn continues_bit_for_bit<const D: usize, E: Checkpoint<D>>(
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
    use gas::driving::{Driving, Thermostat, WhiteNoise};
    let system = gas::init::monodisperse::<3>(500, 0.1, 1.0, 1.0, 1.0, 4).unwrap();
    let law = constant(0.8);
    let interval = 0.01;
    for driving in [
        Driving::WhiteNoise(WhiteNoise::new(1.0).unwrap()),
        Driving::Thermostat(Thermostat::new(1.0).unwrap()),
    ] {
        for halfway in [None, Some(2.0)] {
            let mut engine = EventDriven::new(system.clone(), law.box_clone()).unwrap();
            engine.set_driving(Some(driving), interval, 7).unwrap();
            match halfway {
                None => engine.run_collisions(3000),
                Some(t) => engine.run_until(t),
            }
            let text = serde_json::to_string(&engine.save()).unwrap();
            let mut restored =
                EventDriven::restore(serde_json::from_str(&text).unwrap(), law.box_clone())
                    .unwrap();
            restored.set_driving(Some(driving), interval, 7).unwrap();
            let end = engine.time() + 2.0;
            engine.run_until(end);
            restored.run_until(end);
            assert_eq!(engine.counters(), restored.counters());
            assert_eq!(engine.system(), restored.system());
            assert!(engine.counters().collisions > 1000);
        }
    }
}
