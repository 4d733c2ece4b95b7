//! `system.initial` (issue 38): runs from particle files and from another run's
//! check-point. Oracles: a file round trip is exact (the writers print the shortest form
//! that reads back to the same bits), so every format and the run's own check-point start
//! the same run bit for bit; that run continues the first one (to the rounding of the
//! clock's origin, amplified by the chaos of hard spheres); drawn velocities have the
//! temperature asked for and no momentum (exact sums); refusals name the key or the file.

use sim::particles::{self, Configuration, Format};
use sim::{Error, Simulation};
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("haff-initial-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

const LAW: &str = "[collision]\nlaw = \"constant\"\nrestitution = 0.8\n";

fn run_text(system: &str, cpp: f64, samples: usize) -> String {
    format!(
        "[system]\n{system}\n{LAW}[run]\ncollisions_per_particle = {cpp}\nsamples = {samples}\n"
    )
}

fn simulation(text: &str) -> Result<Simulation, Error> {
    Simulation::from_toml(text, Path::new("test.toml"))
}

/// A 2D gas run to 5 collisions per particle, saved in `dir`.
fn first_run(dir: &Path, system: &str) -> Simulation {
    let mut run = simulation(&run_text(system, 5.0, 5)).unwrap();
    run.run(&mut (), None).unwrap();
    run.save(dir).unwrap();
    run
}

fn quoted(path: &Path) -> String {
    format!("{:?}", path.display().to_string())
}

/// Oracle: exact round trips. The check-point of a run written in every format and read
/// back starts the same run as `initial = { run = DIR }`: every sample equal bit for bit;
/// its first sample is the saved run's last (temperature, a2 bit for bit).
#[test]
fn every_format_and_the_run_start_the_same_run() {
    let dir = scratch("formats");
    let system = "dimension = 2\nparticles = 300\npacking_fraction = 0.25\nseed = 4";
    let mut first = first_run(&dir, system);
    let last = first.samples().last().unwrap().clone();
    let from_run = run_text(
        &format!("dimension = 2\ninitial = {{ run = {} }}", quoted(&dir)),
        1.0,
        4,
    );
    let mut reference = simulation(&from_run).unwrap();
    reference.run(&mut (), None).unwrap();
    let start = &reference.samples()[0];
    assert_eq!(start.temperature.to_bits(), last.temperature.to_bits());
    assert_eq!(start.a2.to_bits(), last.a2.to_bits());
    let configuration = first.configuration();
    let mut formats = vec![
        (Format::Csv, "state.csv"),
        (Format::LammpsDump, "state.dump"),
        (Format::Xyz, "state.xyz"),
        (Format::Vtk, "state.vtu"),
        (Format::LammpsData, "state.data"),
    ];
    if cfg!(feature = "h5md") {
        formats.push((Format::H5md, "state.h5md"));
    }
    for (format, name) in formats {
        let path = dir.join(name);
        particles::write(&path, format, &configuration).unwrap();
        let text = run_text(
            &format!(
                "dimension = 2\ninitial = {{ file = {}, format = \"{}\" }}",
                quoted(&path),
                format.name()
            ),
            1.0,
            4,
        );
        let mut run = simulation(&text).unwrap();
        run.run(&mut (), None).unwrap();
        assert_eq!(run.samples(), reference.samples(), "{name}");
        assert_eq!(run.description().system, {
            let mut s = reference.description().system.clone();
            let i = s.initial.as_mut().unwrap();
            i.run = None;
            i.file = Some(std::path::absolute(&path).unwrap().display().to_string());
            i.format = Some(format.name().into());
            i.frame = Some(-1);
            s
        });
    }
}

/// Oracle: the uninterrupted run. From the check-point at 5 collisions per particle, 5
/// more reach the temperature of one run to 10: the runs differ only by the origin of the
/// clock (event times near t = 5 rounded, not near 0), a relative 1e-16 that the chaos of
/// hard spheres amplifies by e^(lambda t); measured 2e-9 after 5 collisions per particle
/// (N = 400, phi = 0.2), so 1e-7 bounds it with room for the exponent's spread while an
/// error of the continuation (a lost particle, a velocity off by one ulp of v ~ 1e-16 and
/// amplified likewise, a drawn velocity: O(1)) shows.
#[test]
fn a_continued_run_follows_the_uninterrupted_one() {
    let dir = scratch("continued");
    let system = "dimension = 2\nparticles = 400\npacking_fraction = 0.2";
    first_run(&dir, system);
    let mut long = simulation(&run_text(system, 10.0, 10)).unwrap();
    long.run(&mut (), None).unwrap();
    let text = run_text(
        &format!("dimension = 2\ninitial = {{ run = {} }}", quoted(&dir)),
        5.0,
        5,
    );
    let mut continued = simulation(&text).unwrap();
    continued.run(&mut (), None).unwrap();
    let (a, b) = (
        long.samples().last().unwrap(),
        continued.samples().last().unwrap(),
    );
    assert!(
        (a.temperature / b.temperature - 1.0).abs() < 1e-7,
        "{} {}",
        a.temperature,
        b.temperature
    );
}

/// A file of `n` particles on a square lattice of spacing 2 in 2D, without velocities.
fn lattice(n: usize, diameters: Option<Vec<f64>>) -> Configuration {
    let side = (n as f64).sqrt().ceil() as usize;
    Configuration {
        dimension: 2,
        sides: vec![2.0 * side as f64; 2],
        positions: (0..n)
            .map(|i| {
                [
                    1.0 + 2.0 * (i % side) as f64,
                    1.0 + 2.0 * (i / side) as f64,
                    0.0,
                ]
            })
            .collect(),
        velocities: None,
        diameters,
        masses: None,
        species: None,
        spins: None,
        time: None,
    }
}

/// Oracle: exact sums. Velocities drawn for a file without them have sum m v = 0 and sum
/// m v^2 / (N D) = system.temperature to round-off (1e-12 relative), with the masses of
/// `initial.density` (m = density pi d^2 / 4).
#[test]
fn velocities_drawn_have_the_temperature_and_no_momentum() {
    let dir = scratch("drawn");
    let n = 200;
    let diameters: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 1.0 } else { 1.5 }).collect();
    let path = dir.join("lattice.csv");
    particles::write(&path, Format::Csv, &lattice(n, Some(diameters.clone()))).unwrap();
    let text = run_text(
        &format!(
            "dimension = 2\ntemperature = 2.5\ninitial = {{ file = {}, density = 3.0 }}",
            quoted(&path)
        ),
        1.0,
        2,
    );
    let mut run = simulation(&text).unwrap();
    let p = run.particles();
    let (mut momentum, mut energy) = ([0.0; 2], 0.0);
    for (i, (&d, &m)) in diameters.iter().zip(&p.masses).enumerate() {
        let expected = 3.0 * std::f64::consts::PI * d * d / 4.0;
        assert!((m / expected - 1.0).abs() < 1e-15);
        for (k, total) in momentum.iter_mut().enumerate() {
            let v = p.velocities[2 * i + k];
            *total += m * v;
            energy += m * v * v;
        }
    }
    assert!(momentum.iter().all(|x| x.abs() < 1e-12), "{momentum:?}");
    assert!((energy / (2 * n) as f64 / 2.5 - 1.0).abs() < 1e-12);
    let species = &run.description().system.species.as_ref().unwrap();
    assert_eq!(species.len(), 2);
    assert_eq!((species[0].fraction, species[1].fraction), (100.0, 100.0));
    run.run(&mut (), None).unwrap();
}

/// Oracle: the momentum summed here. `momentum = "remove"` subtracts the mass-weighted
/// mean velocity; the report gives the file's total momentum either way.
#[test]
fn the_momentum_is_reported_and_removed_on_request() {
    let dir = scratch("momentum");
    let mut c = lattice(100, None);
    c.velocities = Some(
        (0..100)
            .map(|i| [0.5 + (i as f64 * 0.37).sin(), 0.1, 0.0])
            .collect(),
    );
    let total: f64 = c.velocities.as_ref().unwrap().iter().map(|v| v[0]).sum();
    let path = dir.join("drift.xyz");
    particles::write(&path, Format::Xyz, &c).unwrap();
    for (policy, removed) in [("keep", false), ("remove", true)] {
        let text = run_text(
            &format!(
                "dimension = 2\ninitial = {{ file = {}, momentum = \"{policy}\" }}",
                quoted(&path)
            ),
            1.0,
            2,
        );
        let mut run = simulation(&text).unwrap();
        let note = run.plan().notes.last().unwrap().clone();
        assert!(note.contains("total momentum"), "{note}");
        let p = run.particles();
        let now: f64 = (0..100).map(|i| p.velocities[2 * i]).sum();
        if removed {
            assert!(now.abs() < 1e-12, "{now}");
        } else {
            assert_eq!(now, total);
        }
        let dir = dir.join(policy);
        std::fs::create_dir_all(&dir).unwrap();
        run.run(&mut (), None).unwrap();
        run.write(&dir).unwrap();
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        let report = &summary["initial_particles"];
        assert_eq!(report["momentum"][0].as_f64().unwrap(), total);
        assert_eq!(report["momentum_removed"], removed);
    }
}

/// A run from a file resumes from its own check-point bit for bit without the file (the
/// check-point's description holds the particles it resolved).
#[test]
fn a_run_from_a_file_resumes_without_the_file() {
    let dir = scratch("resume");
    let path = dir.join("lattice.csv");
    particles::write(&path, Format::Csv, &lattice(144, None)).unwrap();
    let text = run_text(
        &format!("dimension = 2\ninitial = {{ file = {} }}", quoted(&path)),
        4.0,
        4,
    );
    let mut whole = simulation(&text).unwrap();
    whole.run(&mut (), None).unwrap();
    let mut half = simulation(&text).unwrap();
    half.run(&mut (), Some(2)).unwrap();
    let saved = dir.join("saved");
    std::fs::create_dir_all(&saved).unwrap();
    half.save(&saved).unwrap();
    std::fs::remove_file(&path).unwrap();
    let mut resumed = Simulation::load(&saved).unwrap();
    resumed.run(&mut (), None).unwrap();
    assert_eq!(resumed.samples(), whole.samples());
}

/// Each engine starts from a file: soft-sphere MD, homogeneous and spatial DSMC (their
/// particles are points: overlaps are not checked) run and keep the file's particles.
#[test]
fn every_engine_starts_from_a_file() {
    let dir = scratch("engines");
    let path = dir.join("lattice.csv");
    particles::write(&path, Format::Csv, &lattice(144, None)).unwrap();
    for engine in [
        "engine = \"soft-sphere\"\nyoung = 1e5\npoisson = 0.3\ndissipative_constant = 0.01\n",
        "engine = \"dsmc\"\n",
        "engine = \"dsmc\"\ndsmc_scheme = \"spatial\"\n",
    ] {
        let law = if engine.contains("soft") {
            "[collision]\nlaw = \"viscoelastic\"\nyoung = 1e5\npoisson = 0.3\ndissipative_constant = 0.01\n"
        } else {
            LAW
        };
        let run_keys = engine.replace(
            "young = 1e5\npoisson = 0.3\ndissipative_constant = 0.01\n",
            "",
        );
        let text = format!(
            "[system]\ndimension = 2\ninitial = {{ file = {} }}\n{law}[run]\n{run_keys}\
             collisions_per_particle = 1\nsamples = 2\n",
            quoted(&path)
        );
        let mut run = simulation(&text).unwrap_or_else(|e| panic!("{engine}: {e}"));
        assert_eq!(run.particles().radii.len(), 144);
        run.run(&mut (), None)
            .unwrap_or_else(|e| panic!("{engine}: {e}"));
    }
}

fn refusal(text: &str) -> String {
    match simulation(text) {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => {
            assert!(e.is_input(), "{e}");
            e.to_string()
        }
    }
}

/// Refusals name the key or the file and the record.
#[test]
fn bad_initial_descriptions_are_refused_naming_the_key() {
    let dir = scratch("refused");
    let path = dir.join("lattice.csv");
    particles::write(&path, Format::Csv, &lattice(16, None)).unwrap();
    let file = format!("initial = {{ file = {} }}", quoted(&path));
    for (extra, key) in [
        ("particles = 16", "system.particles"),
        ("packing_fraction = 0.1", "system.packing_fraction"),
        ("box = [9.0, 8.0]", "system.box"),
        (
            "species = [{ diameter = 1.0, mass = 1.0, fraction = 1.0 }]",
            "system.species",
        ),
    ] {
        let message = refusal(&run_text(
            &format!("dimension = 2\n{file}\n{extra}"),
            1.0,
            2,
        ));
        assert!(message.contains(key), "{extra}: {message}");
    }
    let missing = dir.join("missing.xyz");
    for (initial, expected) in [
        (format!("{{ file = {} }}", quoted(&missing)), "missing.xyz"),
        (
            format!("{{ file = {}, format = \"pdb\" }}", quoted(&path)),
            "system.initial.format",
        ),
        (
            format!("{{ file = {}, run = \"x\" }}", quoted(&path)),
            "system.initial.run",
        ),
        (
            "{ run = \"/nonexistent/haff\" }".to_string(),
            "system.initial.run",
        ),
        ("{ }".to_string(), "system.initial"),
        (
            format!("{{ file = {}, density = -1.0 }}", quoted(&path)),
            "system.initial.density",
        ),
        (
            format!("{{ file = {}, momentum = \"drop\" }}", quoted(&path)),
            "momentum",
        ),
    ] {
        let message = refusal(&run_text(
            &format!("dimension = 2\ninitial = {initial}"),
            1.0,
            2,
        ));
        assert!(message.contains(expected), "{initial}: {message}");
    }
    // The refusal of a run from `c` written as `name`, with `extra` keys in [system].
    let refused_file = |name: &str, c: &Configuration, extra: &str| {
        let path = dir.join(name);
        particles::write(&path, Format::Csv, c).unwrap();
        refusal(&run_text(
            &format!(
                "dimension = 2\n{extra}initial = {{ file = {} }}",
                quoted(&path)
            ),
            1.0,
            2,
        ))
    };
    // Velocities in the file and a temperature to draw them at.
    let mut moving = lattice(16, None);
    moving.velocities = Some(vec![[1.0, -1.0, 0.0]; 16]);
    let message = refused_file("moving.csv", &moving, "temperature = 1.0\n");
    assert!(message.contains("system.temperature"), "{message}");
    // Overlapping spheres: the file and the records named.
    let mut dense = lattice(16, None);
    dense.positions[1] = [1.5, 1.0, 0.0];
    let message = refused_file("dense.csv", &dense, "");
    assert!(
        message.contains("dense.csv") && message.contains("records 0 and 1"),
        "{message}"
    );
    // Kinds of particle without masses.
    let mut two = lattice(16, Some(vec![1.0; 16]));
    two.diameters.as_mut().unwrap()[3] = 0.5;
    let message = refused_file("two.csv", &two, "");
    assert!(
        message.contains("system.initial") && message.contains("masses"),
        "{message}"
    );
    // The other run's dimension.
    let run_dir = dir.join("run3d");
    std::fs::create_dir_all(&run_dir).unwrap();
    first_run(&run_dir, "particles = 100\npacking_fraction = 0.1");
    let message = refusal(&run_text(
        &format!("dimension = 2\ninitial = {{ run = {} }}", quoted(&run_dir)),
        1.0,
        2,
    ));
    assert!(message.contains("system.dimension"), "{message}");
}

/// A data file LAMMPS wrote (`write_data`, 29 Sep 2021; `tests/data/lammps/`, made by the
/// `.in` beside it) starts a haff run in 2D and 3D: its 50 atoms, box, two types as two
/// species with LAMMPS' masses (density x 4 pi r^3 / 3, in 2D too) and velocities, as the
/// reader gives them (the reader is tested against LAMMPS' own dump of the same atoms in
/// `tests/lammps_data.rs`).
#[test]
fn a_lammps_data_file_starts_a_run() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/lammps");
    for (dimension, name) in [(2, "sphere2d.data"), (3, "sphere3d.data")] {
        let path = data.join(name);
        let c = particles::read(&path, Format::LammpsData, dimension, -1).unwrap();
        let text = run_text(
            &format!(
                "dimension = {dimension}\ninitial = {{ file = {} }}",
                quoted(&path)
            ),
            1.0,
            2,
        );
        let mut run = simulation(&text).unwrap_or_else(|e| panic!("{name}: {e}"));
        let s = &run.description().system;
        assert_eq!(s.particles, 50);
        assert_eq!(s.sides.as_deref(), Some(c.sides.as_slice()));
        assert_eq!(s.species.as_ref().map(Vec::len), Some(2), "{name}");
        let p = run.particles();
        assert_eq!(&p.masses, c.masses.as_ref().unwrap());
        let v: Vec<f64> = c
            .velocities
            .as_ref()
            .unwrap()
            .iter()
            .flat_map(|v| v[..dimension].to_vec())
            .collect();
        assert_eq!(p.velocities, v);
        run.run(&mut (), None).unwrap();
    }
}
