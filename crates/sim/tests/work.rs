//! The work of an event-driven run is told before it starts (`sim::engines::work`): runs
//! whose estimate is absurd are refused naming the key that makes them so, large ones carry
//! a note. The estimate of events per collision (1 + 2 c_D lambda / w: the cell crossings
//! of two free paths) is checked against runs: within 10 % where the crossings dominate
//! (dilute gases, the cells widened by the engine's cap on their number), within a factor
//! 1.3 at phi = 0.3, where stale predictions (not counted by the estimate) add events.

use sim::{Error, Simulation};

fn gas(particles: usize, phi: f64, collisions: f64, more: &str) -> String {
    format!(
        "[system]\nparticles = {particles}\npacking_fraction = {phi}\n\
         [collision]\nlaw = \"constant\"\nrestitution = 1.0\n\
         [run]\ncollisions_per_particle = {collisions}\nsamples = 2\n{more}"
    )
}

fn refused_key(toml: &str) -> String {
    match Simulation::from_toml(toml, "work.toml".as_ref()) {
        Err(Error::Input { key, message }) => {
            assert!(message.contains("events"), "{message}");
            key
        }
        Err(other) => panic!("not an input error: {other}"),
        Ok(_) => panic!("accepted: {toml}"),
    }
}

#[test]
fn absurd_runs_are_refused_naming_the_key() {
    // Driving every 1e-12 time units: 1e15 applications of the driving.
    let driven = gas(
        2000,
        0.05,
        5.0,
        "[driving]\nkind = \"white-noise\"\nstrength = 1.0\ninterval = 1e-12\n",
    );
    assert_eq!(refused_key(&driven), "driving.interval");
    // phi = 1e-9: a mean free path of 1e8 diameters through cells of ~100 (4e6 events per
    // collision) for 2.5e6 collisions.
    assert_eq!(
        refused_key(&gas(100_000, 1e-9, 50.0, "")),
        "system.packing_fraction"
    );
    // 5e10 collisions of a dense gas.
    assert_eq!(
        refused_key(&gas(1_000_000, 0.1, 1e5, "")),
        "run.collisions_per_particle"
    );
    // The same dilute gas for 5 collisions per particle of 2000 particles: ~2e10 events,
    // accepted with a note.
    let run = Simulation::from_toml(&gas(2000, 1e-9, 5.0, ""), "work.toml".as_ref()).unwrap();
    assert_eq!(run.plan().notes.len(), 1, "{:?}", run.plan().notes);
    assert!(run.plan().notes[0].contains("events per collision"));
}

#[test]
fn events_per_collision_as_estimated() {
    for (phi, tolerance) in [(1e-4, 0.1), (0.05, 0.1), (0.3, 0.3)] {
        let mut run =
            Simulation::from_toml(&gas(2000, phi, 5.0, ""), "work.toml".as_ref()).unwrap();
        let estimate = sim::engines::work(run.plan()).unwrap().events_per_collision;
        run.run(&mut (), None).unwrap();
        let c = run.counters();
        let measured = c.events as f64 / c.collisions as f64;
        assert!(
            (estimate / measured - 1.0).abs() < tolerance,
            "phi = {phi}: estimated {estimate}, measured {measured}"
        );
    }
}
