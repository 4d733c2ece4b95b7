//! `Engine::run_paused` pieces compose: a run cut into pieces by collision pauses (as the
//! run driver cuts it, to look for interruptions between pieces) is bit-identical to the
//! same run in one piece, by time and by collisions, for every engine.

mod common;

use common::constant;
use gas::dsmc::{point_gas, Scheme, SpatialOptions};
use gas::{Engine, EventDriven, HomogeneousDsmc, SpatialDsmc};

/// Runs `a` to time `end` at once and `b` to it in pieces of `piece` collisions; then `a`
/// by `collisions` at once and `b` to the same total in pieces. Both must agree exactly.
fn pieces_compose<const D: usize>(
    mut a: Box<dyn Engine<D>>,
    mut b: Box<dyn Engine<D>>,
    end: f64,
    collisions: u64,
    piece: u64,
) {
    a.run_until(end);
    while b.time() < end {
        let pause = (b.counters().collisions / piece + 1) * piece;
        b.run_paused(end, u64::MAX, pause);
    }
    assert!(
        a.counters().collisions > 4 * piece,
        "too few collisions to cut"
    );
    assert_eq!(a.time(), b.time());
    assert_eq!(a.counters(), b.counters());
    assert_eq!(a.system(), b.system());

    a.run_collisions(collisions);
    let total = b.counters().collisions + collisions;
    loop {
        let have = b.counters().collisions;
        if have >= total {
            break;
        }
        b.run_paused(f64::INFINITY, total, (have / piece + 1) * piece);
    }
    assert_eq!(a.time(), b.time());
    assert_eq!(a.counters(), b.counters());
    assert_eq!(a.system(), b.system());
}

#[test]
fn event_driven() {
    let system = gas::init::monodisperse::<3>(500, 0.2, 1.0, 1.0, 1.0, 3).unwrap();
    let make = || -> Box<dyn Engine<3>> {
        Box::new(EventDriven::new(system.clone(), constant(0.8)).unwrap())
    };
    pieces_compose(make(), make(), 3.0, 3000, 317);
}

#[test]
fn dsmc_engines() {
    let system = point_gas::<3>(2000, 20.0, 1.0, 1.0, 1.0, 5).unwrap();
    for scheme in [Scheme::Exact, Scheme::default()] {
        let make = || -> Box<dyn Engine<3>> {
            Box::new(HomogeneousDsmc::new(system.clone(), 0.1, constant(0.8), 5, scheme).unwrap())
        };
        pieces_compose(make(), make(), 20.0, 5000, 317);
    }
    let make = || -> Box<dyn Engine<3>> {
        Box::new(
            SpatialDsmc::new(
                system.clone(),
                0.1,
                constant(0.8),
                5,
                SpatialOptions::default(),
            )
            .unwrap(),
        )
    };
    pieces_compose(make(), make(), 20.0, 5000, 317);
}
