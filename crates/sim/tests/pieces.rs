//! A run driven in pieces: interrupted between them (`Progress::keep_going`), advanced to
//! points between samples (`Simulation::advance`), saved there and loaded. Every way of
//! cutting a run gives the samples of the uninterrupted run, bit for bit (the engines'
//! pieces compose: crates/gas/tests/pieces.rs), and points outside the run are refused.

use sim::{Point, Progress, Simulation, PIECE_COLLISIONS};

fn toml(engine: &str, stop: &str) -> String {
    format!(
        "[system]\nparticles = 3000\npacking_fraction = 0.1\nseed = 9\n\
         [collision]\nlaw = \"constant\"\nrestitution = 0.8\n\
         [run]\n{engine}{stop}\nsamples = 6\n"
    )
}

/// The run descriptions cut here: event-driven and DSMC, stopped by collisions and by time.
fn runs() -> Vec<String> {
    let mut out = Vec::new();
    for engine in [
        "",
        "engine = \"dsmc\"\n",
        "engine = \"dsmc\"\ndsmc_scheme = \"spatial\"\n",
    ] {
        out.push(toml(engine, "collisions_per_particle = 150"));
    }
    out.push(toml("", "end_time = 6.0"));
    out
}

/// A progress that interrupts the run at its `at`-th question.
struct InterruptAt {
    asked: usize,
    at: usize,
}

impl Progress for InterruptAt {
    fn keep_going(&mut self) -> bool {
        self.asked += 1;
        self.asked != self.at
    }
}

fn whole(text: &str) -> Simulation {
    let mut run = Simulation::from_toml(text, "test.toml".as_ref()).unwrap();
    run.run(&mut (), None).unwrap();
    run
}

#[test]
fn interrupted_runs_go_on_as_if_never_interrupted() {
    // 3000 particles, 150 collisions per particle: 225000 collisions, several pieces.
    const { assert!(PIECE_COLLISIONS < 225_000 / 3) };
    for text in runs() {
        let reference = whole(&text);
        let mut run = Simulation::from_toml(&text, "test.toml".as_ref()).unwrap();
        let mut interrupts = 0;
        for at in [2, 1, 3] {
            match run.run(&mut InterruptAt { asked: 0, at }, None) {
                Err(sim::Error::Interrupted { time }) => {
                    interrupts += 1;
                    assert_eq!(time, run.time());
                }
                other => panic!("{text}: not interrupted: {:?}", other.map(|o| o.complete)),
            }
            assert!(!run.is_complete());
        }
        assert_eq!(interrupts, 3);
        run.run(&mut (), None).unwrap();
        assert_eq!(run.samples(), reference.samples(), "{text}");
        assert_eq!(run.counters(), reference.counters(), "{text}");
    }
}

#[test]
fn advanced_saved_and_loaded_runs_keep_their_samples() {
    let dir = std::env::temp_dir().join(format!("haff-pieces-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (k, text) in runs().iter().enumerate() {
        let reference = whole(text);
        let mut run = Simulation::from_toml(text, "test.toml".as_ref()).unwrap();
        let by_time = text.contains("end_time");
        // A point between two samples (log-spaced), then one in the other unit.
        let (point, before) = if by_time {
            let before = reference
                .samples()
                .iter()
                .filter(|s| s.time < 2.345)
                .count();
            (Point::Time(2.345), before)
        } else {
            let samples = reference.samples();
            let before = samples
                .iter()
                .filter(|s| s.collisions_per_particle < 47.5)
                .count();
            (Point::CollisionsPerParticle(47.5), before)
        };
        assert!((2..reference.samples().len()).contains(&before));
        assert!(run.advance(point, &mut ()).unwrap());
        assert_eq!(run.samples(), &reference.samples()[..before]);
        assert!(run
            .advance(Point::Time(run.time() * 1.01), &mut ())
            .unwrap());
        // Saved between samples (the event-driven engine is brought to the present: the
        // run goes on as one loaded from there), loaded, both finish alike.
        let file = dir.join(format!("run{k}.bin"));
        run.save(&file).unwrap();
        let mut loaded = Simulation::load(&file).unwrap();
        assert_eq!(
            (loaded.time(), loaded.counters()),
            (run.time(), run.counters())
        );
        run.run(&mut (), None).unwrap();
        loaded.run(&mut (), None).unwrap();
        assert_eq!(loaded.samples(), run.samples(), "{text}");
        assert_eq!(run.samples().len(), reference.samples().len());
        // The samples before the save are the uninterrupted run's. Saving brings the
        // event-driven particles to the present (positions rounded in the last bits, which
        // the chaos of a gas amplifies later): from there on it is another realization.
        assert_eq!(run.samples()[..before], reference.samples()[..before]);
        if !text.contains("dsmc") {
            // Without the save, stopping between samples changes nothing: the engine brings
            // particles to the present lazily.
            let mut advanced = Simulation::from_toml(text, "test.toml".as_ref()).unwrap();
            assert!(advanced.advance(point, &mut ()).unwrap());
            advanced.run(&mut (), None).unwrap();
            assert_eq!(advanced.samples(), reference.samples(), "{text}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn points_outside_the_run_are_refused() {
    let mut run = Simulation::from_toml(&runs()[0], "test.toml".as_ref()).unwrap();
    let refused = |run: &mut Simulation, point: Point, says: &str| {
        let error = run.advance(point, &mut ()).unwrap_err().to_string();
        assert!(error.starts_with(says), "{error}");
    };
    refused(
        &mut run,
        Point::CollisionsPerParticle(151.0),
        "collisions_per_particle: 151",
    );
    refused(
        &mut run,
        Point::CollisionsPerParticle(f64::NAN),
        "collisions_per_particle: NaN",
    );
    refused(&mut run, Point::Time(-1.0), "time: -1");
    assert!(run
        .advance(Point::CollisionsPerParticle(30.0), &mut ())
        .unwrap());
    refused(
        &mut run,
        Point::CollisionsPerParticle(29.0),
        "collisions_per_particle: 29",
    );
    // A time beyond the end of a run stopped by collisions: the run ends first.
    assert!(!run.advance(Point::Time(1e12), &mut ()).unwrap());
    assert!(run.is_complete());
}

/// A dense start (spheres grown: `gas::init`) is told in `summary.json` and kept through
/// check-points; the run goes on from a loaded one as from the saved one, bit for bit.
#[test]
fn dense_starts_are_reported_and_kept_in_checkpoints() {
    let text = "[system]\nparticles = 1500\npacking_fraction = 0.55\nseed = 4\n\
                [collision]\nlaw = \"constant\"\nrestitution = 0.95\n\
                [run]\ncollisions_per_particle = 20\nsamples = 5\n";
    let mut run = Simulation::from_toml(text, "dense.toml".as_ref()).unwrap();
    let grown = *run.initial_state().expect("a grown start");
    assert_eq!(grown.method, sim::InitialMethod::Growth);
    assert_eq!(grown.start_fraction, gas::init::RANDOM_ADDITION_LIMIT);
    assert!(grown.collisions > 0 && grown.events >= grown.collisions);
    assert!(run
        .advance(Point::CollisionsPerParticle(7.5), &mut ())
        .unwrap());
    let dir = std::env::temp_dir().join(format!("haff-dense-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("dense.bin");
    run.save(&file).unwrap();
    let mut loaded = Simulation::load(&file).unwrap();
    assert_eq!(loaded.initial_state(), Some(&grown));
    run.run(&mut (), None).unwrap();
    loaded.run(&mut (), None).unwrap();
    assert_eq!(loaded.samples(), run.samples());
    loaded.write(&dir).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let told = &summary["initial_state"];
    assert_eq!(told["method"], "growth");
    assert_eq!(told["collisions"], grown.collisions);
    // A lattice or random start is not a growth: no record.
    let dilute = Simulation::from_toml(&runs()[0], "test.toml".as_ref()).unwrap();
    assert_eq!(dilute.initial_state(), None);
    std::fs::remove_dir_all(&dir).unwrap();
}
