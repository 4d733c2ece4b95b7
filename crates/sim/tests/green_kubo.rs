//! `summary.json`'s `green_kubo`: the equilibrium shear viscosity of elastic hard spheres
//! by the Einstein–Helfand form of Green–Kubo (`sim::green_kubo`), and the runs it refuses.
//!
//! Oracle: Chapman–Enskog's viscosity of the dilute gas, 1.016034 eta0 (the converged Sonine
//! series; its second and third orders are computed in `gas::theory::transport`'s tests),
//! over Enskog's chi at the DSMC's packing fraction.

use sim::Simulation;

fn green_kubo(text: &str) -> serde_json::Value {
    let mut run = Simulation::from_toml(text, "green-kubo.toml".as_ref()).unwrap();
    run.run(&mut (), None).unwrap();
    let series = run.pressure().expect("output.pressure");
    run.green_kubo(series)
}

/// An elastic run of `engine` with pressure sampled `samples` times until `end`.
fn text(engine: &str, particles: usize, phi: f64, restitution: f64, stop: &str) -> String {
    format!(
        "[system]\ndimension = 3\nparticles = {particles}\npacking_fraction = {phi}\nseed = 5\n\
         [collision]\nlaw = \"constant\"\nrestitution = {restitution}\n\
         [run]\n{engine}{stop}spacing = \"linear\"\n\
         [output]\npressure = true\n"
    )
}

/// The dilute gas of the DSMC (exact scheme: the Boltzmann equation's collisions), 100
/// spheres for 60 000 mean free times sampled ten times per mean free time: eta / eta0 is
/// Chapman–Enskog's 1.016034 / chi within 3 % (the bound) and 4 standard errors (the
/// estimate's error is 1 %: 10 batches; the sampled kinetic part's bias is below 0.5 % at this
/// interval, docs/shear.md).
#[test]
fn the_dilute_viscosity_is_chapman_enskogs() {
    let phi = 1e-4;
    let n = 6.0 * phi / std::f64::consts::PI;
    let chi = gas::theory::contact_value::<3>(phi);
    let tau = 1.0 / (4.0 * std::f64::consts::PI.sqrt() * n * chi);
    let stop = format!("end_time = {}\nsamples = 600000\n", 60_000.0 * tau);
    let gk = green_kubo(&text(
        "engine = \"dsmc\"\ndsmc_scheme = \"exact\"\n",
        100,
        phi,
        1.0,
        &stop,
    ));
    let eta = gk["reduced_viscosity"]["mean"].as_f64().unwrap();
    let error = gk["reduced_viscosity"]["error"].as_f64().unwrap();
    let expected = gas::theory::transport::ELASTIC_VISCOSITY_SONINE_FACTOR / chi;
    assert!(
        (eta - expected).abs() < (0.03 * expected).min(4.0 * error),
        "eta / eta0 = {eta} +- {error}, Chapman-Enskog {expected}: {gk}"
    );
    assert!(error < 0.015, "{gk}");
    assert_eq!(gk["batches"], 10);
    assert_eq!(
        gk["theory"]["chapman_enskog_dilute"].as_f64(),
        Some(gas::theory::transport::ELASTIC_VISCOSITY_SONINE_FACTOR)
    );
}

/// What has no equilibrium viscosity, or too few samples for one, says why instead.
#[test]
fn runs_without_an_equilibrium_viscosity_say_why() {
    let emd = "engine = \"event-driven\"\n";
    let skipped = |gk: serde_json::Value| gk["skipped"].as_str().unwrap_or("").to_string();
    let inelastic = green_kubo(&text(emd, 200, 0.1, 0.9, "end_time = 50\nsamples = 1000\n"));
    let why = skipped(inelastic);
    assert!(
        why.contains("not elastic") && why.contains("restitution = 0.9"),
        "{why}"
    );
    let by_collisions = green_kubo(&text(
        emd,
        200,
        0.1,
        1.0,
        "collisions_per_particle = 50\nsamples = 1000\n",
    ));
    assert!(skipped(by_collisions).contains("run.end_time"));
    let coarse = green_kubo(&text(emd, 200, 0.1, 1.0, "end_time = 300\nsamples = 300\n"));
    assert!(skipped(coarse).contains("mean free times apart"));
    let short = green_kubo(&text(emd, 200, 0.1, 1.0, "end_time = 50\nsamples = 1000\n"));
    assert!(skipped(short).contains("mean free times long"));
}
