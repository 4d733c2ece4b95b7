//! The mean-square displacement (`output.msd`) through the driver: `msd.csv`, the
//! self-diffusion coefficient of `summary.json`, check-points, refusals; against two
//! independent references: free flight at short times (msd = D T t^2 / m, exactly while no
//! sphere has collided) and Chapman–Enskog's self-diffusion of elastic hard spheres at long
//! times (the first Sonine value D0 / chi of `gas::theory::NavierStokes` times 1.019, the
//! converged series' factor in 3D: Chapman & Cowling 1970, Sec. 10.5).

use sim::{Point, Simulation};

fn gas(end_time: f64, particles: usize, extra: &str) -> String {
    format!(
        "[system]\ndimension = 3\nparticles = {particles}\npacking_fraction = 0.01\nseed = 21\n\
         [collision]\nlaw = \"constant\"\nrestitution = 1.0\n\
         [run]\nend_time = {end_time}\nsamples = 60\nspacing = \"linear\"\n\
         [output]\nmsd = true\n{extra}"
    )
}

/// The `summary.json` a run wrote into `dir`.
fn summary_in(dir: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

/// (measured D_s, Chapman–Enskog's: 1.019 times the first Sonine value) of a summary.
fn self_diffusion(summary: &serde_json::Value) -> (f64, f64) {
    let d = &summary["self_diffusion"];
    (
        d["coefficient"].as_f64().unwrap(),
        1.019 * d["enskog_elastic_at_initial_temperature"].as_f64().unwrap(),
    )
}

/// Long times: the slope of msd over the second half of 60 mean free times is 6 D_s with
/// D_s Chapman–Enskog's within 5 % (the statistical error of one run of 4000 spheres:
/// about 1.5 %, from the spread of |dr|^2 (relative variance 2/3 per sphere) over the
/// run's independent stretches); `msd.csv` has the header.
#[test]
fn the_self_diffusion_is_chapman_enskogs() {
    // omega = 4 sqrt(pi) chi n: n = 6 phi / pi = 0.0191, mean free time 7.3.
    let mut run = Simulation::from_toml(&gas(440.0, 4000, ""), "msd.toml".as_ref()).unwrap();
    run.run(&mut (), None).unwrap();
    let dir = std::env::temp_dir().join(format!("haff-msd-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    run.write(&dir).unwrap();
    let csv = std::fs::read_to_string(dir.join("msd.csv")).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "time,collisions_per_particle,msd"
    );
    assert_eq!(csv.lines().count(), 1 + run.samples().len());
    let summary = summary_in(&dir);
    std::fs::remove_dir_all(&dir).unwrap();
    let (measured, enskog) = self_diffusion(&summary);
    assert!(
        (measured / enskog - 1.0).abs() < 0.05,
        "D_s = {measured}, Chapman-Enskog {enskog}"
    );
}

/// Short times: before any collision a sphere flies freely, so msd(t) = <v^2> t^2 exactly;
/// by t = 0.02 mean free times about 2 % of the spheres have collided, which changes msd by
/// less than 3 %. A run saved at a sample resumes bit for bit.
#[test]
fn the_short_time_msd_is_free_flight_and_resumes() {
    let text = gas(0.15, 2000, "");
    let mut run = Simulation::from_toml(&text, "msd.toml".as_ref()).unwrap();
    assert!(run.advance(Point::Time(0.06), &mut ()).unwrap());
    let dir = std::env::temp_dir().join(format!("haff-msd-resume-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("msd.bin");
    run.save(&file).unwrap();
    let mut loaded = Simulation::load(&file).unwrap();
    run.run(&mut (), None).unwrap();
    loaded.run(&mut (), None).unwrap();
    assert_eq!(loaded.msd(), run.msd());
    std::fs::remove_dir_all(&dir).unwrap();
    let rows = &run.msd().unwrap().samples;
    let samples = run.samples();
    // <v^2> = D T: the temperature is conserved (elastic), 3 T0 with T0 = 1 (drawn: the
    // sample's T).
    let v2 = 3.0 * samples[0].temperature;
    for row in rows.iter().skip(1) {
        let free = v2 * row.time * row.time;
        assert!(
            (row.msd / free - 1.0).abs() < 0.03,
            "t = {}: msd {} vs free flight {free}",
            row.time,
            row.msd
        );
    }
}

/// The engines that track displacements, as `[run]` lines: the event-driven engine,
/// soft-sphere MD (Hertz contacts, nearly elastic), spatial DSMC.
const TRACKING: [(&str, &str); 3] = [
    ("event-driven", ""),
    ("soft-sphere", "engine = \"soft-sphere\"\n"),
    (
        "spatial dsmc",
        "engine = \"dsmc\"\ndsmc_scheme = \"spatial\"\n",
    ),
];

/// The `[collision]` section of each tracking engine: elastic (soft spheres: nearly).
fn elastic(engine: &str) -> &'static str {
    if engine.contains("soft-sphere") {
        "law = \"viscoelastic\"\nyoung = 1e3\npoisson = 0.3\ndissipative_constant = 1e-4\n"
    } else {
        "law = \"constant\"\nrestitution = 1.0\n"
    }
}

/// Free flight through the periodic box: 3 spheres at phi = 1e-4 (box side 25; a pair meets
/// about once in 700 time units) for t = 80, each crossing the box about five times and none
/// colliding (the premise, asserted): msd(t) = <|v|^2> t^2 = D T t^2 to rounding (relative 1e-9) in every
/// engine that tracks, so every wrap is counted, whichever way and however often; a run
/// saved mid-way resumes bit for bit (the tracks are part of the state; spatial DSMC saves
/// them in its records' order).
#[test]
fn free_flight_unwraps_across_the_box_in_every_tracking_engine() {
    for (name, run_lines) in TRACKING {
        let text = format!(
            "[system]\ndimension = 3\nparticles = 3\npacking_fraction = 1e-4\nseed = 4\n\
             [collision]\n{}\
             [run]\n{run_lines}end_time = 80.0\nsamples = 8\nspacing = \"linear\"\n\
             [output]\nmsd = true\n",
            elastic(run_lines)
        );
        let mut run = Simulation::from_toml(&text, "flight.toml".as_ref()).unwrap();
        assert!(run.advance(Point::Time(30.0), &mut ()).unwrap());
        let dir = std::env::temp_dir().join(format!("haff-flight-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("flight.bin");
        run.save(&file).unwrap();
        let mut loaded = Simulation::load(&file).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        run.run(&mut (), None).unwrap();
        loaded.run(&mut (), None).unwrap();
        assert_eq!(loaded.msd(), run.msd(), "{name}: resumed");
        assert_eq!(
            run.counters().collisions,
            0,
            "{name}: the premise, no collision"
        );
        let v2 = 3.0 * run.samples()[0].temperature;
        let rows = &run.msd().unwrap().samples;
        assert_eq!(rows.len(), run.samples().len(), "{name}");
        let last = rows.last().unwrap();
        assert!(
            v2.sqrt() * last.time > 4.0 * 25.0,
            "{name}: wraps {}",
            last.time
        );
        for row in rows {
            let free = v2 * row.time * row.time;
            assert!(
                (row.msd - free).abs() <= 1e-9 * free,
                "{name}, t = {}: msd {} vs free flight {free}",
                row.time,
                row.msd
            );
        }
    }
}

/// Spatial DSMC's self-diffusion is Chapman–Enskog's, as the event-driven engine's above
/// (same gas, 60 mean free times): 8 simulated particles per physical one in cells of a
/// third of the mean free path (11.8), so that the cell-size error of DSMC's transport
/// coefficients (Alexander, Garcia & Alder 1998: (8/45pi)(w/lambda)^2 for the viscosity,
/// 0.2 % here) stays below the statistical error (32 000 particles: about 1 %); within 4 %.
#[test]
fn spatial_dsmcs_self_diffusion_is_chapman_enskogs() {
    let text = gas(440.0, 32_000, "").replace(
        "[run]\n",
        "[run]\nengine = \"dsmc\"\ndsmc_scheme = \"spatial\"\nparticle_weight = 0.125\n\
         collision_cell_width = 4.0\n",
    );
    let mut run = Simulation::from_toml(&text, "msd.toml".as_ref()).unwrap();
    run.run(&mut (), None).unwrap();
    let dir = std::env::temp_dir().join(format!("haff-msd-dsmc-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    run.write(&dir).unwrap();
    let summary = summary_in(&dir);
    std::fs::remove_dir_all(&dir).unwrap();
    let (measured, enskog) = self_diffusion(&summary);
    assert!(
        (measured / enskog - 1.0).abs() < 0.04,
        "D_s = {measured}, Chapman-Enskog {enskog}"
    );
}

/// Refusals naming the key: homogeneous DSMC (no positions, no identity of particles
/// through its steps), shear.
#[test]
fn bad_msd_names_its_key() {
    let dsmc = gas(1.0, 200, "").replace("[run]\n", "[run]\nengine = \"dsmc\"\n");
    let sheared = gas(1.0, 200, "[shear]\nrate = 0.01\n");
    for text in [dsmc, sheared] {
        let error = Simulation::from_toml(&text, "bad.toml".as_ref())
            .err()
            .unwrap();
        assert!(error.is_input(), "{error}");
        assert!(error.to_string().starts_with("output.msd"), "{error}");
    }
}
