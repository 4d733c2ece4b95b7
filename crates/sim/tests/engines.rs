//! A run of every engine from Rust code, without the CLI (the example of
//! docs/architecture.md): through the run driver from a run description, and directly
//! through the engine interface. Each run is checked against Haff's law in collisions per
//! particle, T(c) = T0 exp(-(1 - eps^2) c / d), which holds for any collision rate: each
//! collision removes (1 - eps^2) m_red (g.n)^2 / 2, on average (1 - eps^2) T per
//! collision of a Maxwellian pair (Brilliantov & Pöschel, Kinetic Theory of Granular Gases,
//! Ch. 7; gas::theory). The homogeneous cooling state deviates from the Maxwellian by a2:
//! the cooling per collision is larger by (1 + 3 a2/16) / (1 - a2/16) ~ 1 + a2/4, with
//! |a2| < 0.01 for eps = 0.9 (van Noije & Ernst 1998), i.e. < 0.3 % per unit of
//! (1 - eps^2) c / d. The statistical error of T measured over N particles in d
//! dimensions is sqrt(2 / (N d)) (m v_k^2 / T is chi-squared with one degree of freedom,
//! variance 2); the tests allow 5 of it (false failure < 1e-6) plus the a2 bound.

use gas::{Checkpoint, Engine};
use restitution::Constant;
use sim::Simulation;

const EPS: f64 = 0.9;

/// Haff's law in collisions per particle and the tolerance of T/T_Haff - 1.
fn haff(t0: f64, collisions_per_particle: f64, d: usize, particles: usize) -> (f64, f64) {
    let exponent = (1.0 - EPS * EPS) * collisions_per_particle / d as f64;
    let statistical = 5.0 * (2.0 / (particles * d) as f64).sqrt();
    (t0 * (-exponent).exp(), statistical + 0.003 * exponent)
}

fn toml(engine: &str) -> String {
    format!(
        "[system]\nparticles = 2000\npacking_fraction = 0.05\nseed = 4\n\
         [collision]\nlaw = \"constant\"\nrestitution = {EPS}\n\
         [run]\n{engine}collisions_per_particle = 20\nsamples = 5\n"
    )
}

#[test]
fn every_engine_runs_from_a_run_description() {
    for engine in [
        "",
        "engine = \"dsmc\"\ndsmc_scheme = \"exact\"\n",
        "engine = \"dsmc\"\n",
        "engine = \"dsmc\"\ndsmc_scheme = \"spatial\"\n",
    ] {
        let mut run = Simulation::from_toml(&toml(engine), "test.toml".as_ref()).unwrap();
        let outcome = run.run(&mut (), None).unwrap();
        assert!(outcome.complete && run.is_complete());
        let samples = run.samples();
        let (first, last) = (&samples[0], &samples[samples.len() - 1]);
        assert_eq!(samples.len(), 5);
        let (expected, tolerance) = haff(first.temperature, last.collisions_per_particle, 3, 2000);
        let error = last.temperature / expected - 1.0;
        assert!(
            error.abs() < tolerance,
            "{engine}: T = {} vs Haff {expected} (tolerance {tolerance})",
            last.temperature
        );
    }
}

#[test]
fn engines_run_directly_through_the_engine_interface() {
    let n = 1000;
    let system = gas::init::monodisperse::<2>(n, 0.1, 1.0, 1.0, 1.0, 7).unwrap();
    let law = Box::new(Constant::new(EPS).unwrap());
    let mut engine = gas::EventDriven::new(system.clone(), law.clone()).unwrap();
    let mut dsmc =
        gas::HomogeneousDsmc::new(system, 0.1, law, 7, gas::dsmc::Scheme::Exact).unwrap();
    let engines: [&mut dyn Engine<2>; 2] = [&mut engine, &mut dsmc];
    for engine in engines {
        engine.run_collisions(10 * n as u64 / 2);
        let t = gas::observe::temperature(engine.system());
        let (expected, tolerance) = haff(1.0, engine.collisions_per_particle(), 2, n);
        assert!((t / expected - 1.0).abs() < tolerance, "{t} vs {expected}");
    }
    // Saved and restored, the event-driven engine continues bit for bit.
    let mut copy =
        gas::EventDriven::restore(engine.save(), Box::new(Constant::new(EPS).unwrap())).unwrap();
    engine.run_collisions(1000);
    copy.run_collisions(1000);
    assert_eq!(engine.system(), copy.system());
    assert_eq!(Engine::counters(&engine), Engine::counters(&copy));
}

/// The rod chain behind the same interface: a Hamiltonian system, so the total energy
/// (translation + modes + contacts) is conserved; the splitting integrator at c_h = 0.05
/// keeps it to ~1e-10 per collision (docs/giese.md), asserted at 1e-8.
#[test]
fn the_rod_chain_runs_through_the_engine_interface() {
    let text = "[chain]\nrods = 6\nlengths = [0.8, 1.3]\nmodes = 4\nalpha = 200.0\n\
                temperature = 1e-3\n[run]\nend_time = 100.0\nsamples = 3\n";
    let description: sim::rod_ring::RingDescription =
        sim::description::parse_toml(text, "ring.toml".as_ref()).unwrap();
    let ring = description.validate().unwrap();
    let chain = ring.chain(&ring.initial_state()).unwrap();
    let e0 = chain.energy();
    let mut engine = rods::engine::ChainEngine::new(chain);
    let rods: &mut dyn Engine<1> = &mut engine;
    rods.run_collisions(50);
    assert!(rods.counters().collisions >= 50 && rods.time() > 0.0);
    assert_eq!(rods.system().len(), 6);
    let drift = (engine.chain().energy() - e0) / e0;
    assert!(drift.abs() < 1e-8, "{drift}");
}

/// `run.particle_weight` F of spatial DSMC: the box holds N F spheres at phi and the engine
/// gives each simulated particle the physical collision rate, so T(t) follows Haff's law in
/// time with the Enskog frequency of the physical gas whatever F (a wrong weight would
/// change the rate by the factor F). Haff's time with the HCS factors: the cooling rate is
/// (1 - eps^2)/d omega (1 + 3 a2/16) (van Noije & Ernst a2; gas::theory). Tolerance: the
/// statistical 5 sqrt(2/(N d)) of each T plus 1 % for the spatial scheme's finite cells
/// and steps (docs/dsmc.md: within 1 % of the homogeneous engine at 10+ particles per
/// cell). A mixture takes the same weight.
#[test]
fn spatial_dsmc_takes_a_particle_weight() {
    use gas::theory::{collision_frequency, haff_temperature, haff_time, van_noije_ernst_a2};
    let phi = 0.05;
    let omega =
        collision_frequency::<3>(phi / gas::system::ball_volume::<3>(0.5), 1.0, 1.0, 1.0, phi);
    let a2 = van_noije_ernst_a2::<3>(EPS);
    let tau = haff_time::<3>(EPS, omega) / (1.0 + 3.0 * a2 / 16.0);
    let n = 20_000;
    for (weight, system) in [
        ("0.1", ""),
        ("4.0", ""),
        (
            "0.1",
            "species = [{ diameter = 1.0, mass = 1.0, fraction = 1.0 }]\n",
        ),
    ] {
        let text = format!(
            "[system]\nparticles = {n}\npacking_fraction = {phi}\nseed = 4\n{system}\
             [collision]\nlaw = \"constant\"\nrestitution = {EPS}\n\
             [run]\nengine = \"dsmc\"\ndsmc_scheme = \"spatial\"\nparticle_weight = {weight}\n\
             end_time = {}\nsamples = 3\nspacing = \"linear\"\n",
            2.0 * tau
        );
        let mut run = Simulation::from_toml(&text, "test.toml".as_ref()).unwrap();
        run.run(&mut (), None).unwrap();
        let last = run.samples().last().unwrap().clone();
        let expected = haff_temperature(1.0, tau, last.time);
        let tolerance = 5.0 * (2.0 / (3 * n) as f64).sqrt() + 0.01;
        assert!(
            (last.temperature / expected - 1.0).abs() < tolerance,
            "weight {weight} {system}: T = {} vs Haff {expected}",
            last.temperature
        );
    }
}
