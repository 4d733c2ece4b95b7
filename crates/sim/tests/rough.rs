//! Rough particles through the driver (`collision.tangential_restitution`,
//! `collision.friction`, `system.inertia`, `system.rotational_temperature`): the columns
//! and sections they add, check-points, the smooth default unchanged bit for bit,
//! refusals naming the key, and energy kept by perfectly rough elastic particles.

use sim::{Point, Simulation};

/// The engines that have rough particles, as `[run]` lines.
const ENGINES: [&str; 4] = [
    "engine = \"event-driven\"",
    "engine = \"dsmc\"\ndsmc_scheme = \"blocks\"",
    "engine = \"dsmc\"\ndsmc_scheme = \"exact\"",
    "engine = \"dsmc\"\ndsmc_scheme = \"spatial\"",
];

fn gas(dimension: u32, engine: &str, extra_system: &str, extra_collision: &str) -> String {
    format!(
        "[system]\ndimension = {dimension}\nparticles = 600\npacking_fraction = 0.1\nseed = 5\n\
         {extra_system}\n[collision]\nlaw = \"constant\"\nrestitution = 0.85\n{extra_collision}\n\
         [run]\n{engine}\ncollisions_per_particle = 6\nsamples = 8\nspacing = \"linear\"\n"
    )
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("haff-rough-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A rough run writes `rotational_temperature` after the other columns of
/// `timeseries.csv`, the `rotation` section and `rough_theory` in `summary.json`, the
/// angular velocities in its snapshots, and resumes bit for bit from a check-point.
#[test]
fn rough_runs_write_their_rotation_and_resume_bit_for_bit() {
    for engine in ENGINES {
        for dimension in [2, 3] {
            // Snapshots need positions (not homogeneous DSMC).
            let positions = engine.contains("event-driven") || engine.contains("spatial");
            let mut text = gas(
                dimension,
                engine,
                "inertia = 0.35",
                "tangential_restitution = 0.3\n",
            );
            if positions {
                text += "[output]\nsnapshots = { every = 4 }\n";
            }
            let mut run = Simulation::from_toml(&text, "rough.toml".as_ref()).unwrap();
            let dir = temp_dir(&format!("{dimension}"));
            run.set_output_dir(&dir);
            assert!(run
                .advance(Point::CollisionsPerParticle(2.5), &mut ())
                .unwrap());
            let file = dir.join("rough.bin");
            run.save(&file).unwrap();
            let mut loaded = Simulation::load(&file).unwrap();
            run.run(&mut (), None).unwrap();
            loaded.set_output_dir(&dir);
            loaded.run(&mut (), None).unwrap();
            assert_eq!(loaded.samples(), run.samples(), "{engine}, {dimension}D");
            run.write(&dir).unwrap();
            let csv = std::fs::read_to_string(dir.join("timeseries.csv")).unwrap();
            assert_eq!(
                csv.lines().next().unwrap(),
                "time,collisions_per_particle,temperature,a2,energy_lost,pressure,events,\
                 rotational_temperature"
            );
            let last = run.samples().last().unwrap();
            let t_rot = last.rotational_temperature.unwrap();
            assert!(t_rot > 0.0 && t_rot < 1.0, "{t_rot}");
            let summary: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                    .unwrap();
            let theory = &summary["rough_theory"];
            assert_eq!(theory["beta"], 0.3);
            assert!(theory["hcs_ratio"].as_f64().unwrap() > 0.0);
            assert_eq!(summary["rotation"]["sliding_contacts"], 0);
            if positions {
                let vtu = std::fs::read_to_string(dir.join("snapshot_000004.vtu")).unwrap();
                assert!(vtu.contains("angular_velocity"));
            }
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }
}

/// tangential_restitution = -1 (and an inertia, which then has nothing to act on) is the
/// smooth gas: the same samples bit for bit as without the keys, and no new column.
#[test]
fn the_smooth_default_is_the_gas_without_the_keys() {
    for engine in ENGINES {
        let plain = gas(3, engine, "", "");
        let smooth = gas(
            3,
            engine,
            "inertia = 0.3",
            "tangential_restitution = -1.0\n",
        );
        let mut a = Simulation::from_toml(&plain, "a.toml".as_ref()).unwrap();
        let mut b = Simulation::from_toml(&smooth, "b.toml".as_ref()).unwrap();
        a.run(&mut (), None).unwrap();
        b.run(&mut (), None).unwrap();
        assert_eq!(a.samples(), b.samples(), "{engine}");
        assert!(b
            .samples()
            .iter()
            .all(|s| s.rotational_temperature.is_none()));
    }
}

/// alpha = beta = 1: translation and rotation exchange energy and lose none:
/// (D T + d_rot T_rot) / 2 per particle is kept to round-off (the oracle: conservation).
#[test]
fn perfectly_rough_elastic_particles_keep_their_energy() {
    for engine in ENGINES {
        for (dimension, d_rot) in [(2u32, 1.0), (3, 3.0)] {
            let text = gas(
                dimension,
                engine,
                "rotational_temperature = 0.2",
                "tangential_restitution = 1.0\n",
            )
            .replace("restitution = 0.85", "restitution = 1.0");
            let mut run = Simulation::from_toml(&text, "e.toml".as_ref()).unwrap();
            run.run(&mut (), None).unwrap();
            let energy = |s: &sim::observer::Sample| {
                f64::from(dimension) * s.temperature + d_rot * s.rotational_temperature.unwrap()
            };
            let (first, last) = (&run.samples()[0], run.samples().last().unwrap());
            assert!(
                (energy(last) - energy(first)).abs() < 1e-10 * energy(first),
                "{engine} {dimension}D: {} -> {}",
                energy(first),
                energy(last)
            );
            assert!(last.energy_lost.abs() < 1e-9, "{}", last.energy_lost);
            assert!(
                last.rotational_temperature.unwrap() > 0.5,
                "rotation took energy"
            );
        }
    }
}

/// Per species: inertia factors of their own, and each species' rotational temperature
/// in `species.csv`, whose number-weighted mean is the gas's.
#[test]
fn species_rotate_with_their_own_inertia() {
    for engine in ENGINES {
        let text = format!(
            "[system]\ndimension = 3\nparticles = 600\npacking_fraction = 0.1\nseed = 2\n\
             species = [{{ diameter = 1.0, mass = 1.0, fraction = 0.5, inertia = 0.2 }}, \
             {{ diameter = 1.5, mass = 2.0, fraction = 0.5 }}]\n\
             [collision]\nlaw = \"constant\"\nrestitution = 0.9\ntangential_restitution = 0.5\n\
             [run]\n{engine}\ncollisions_per_particle = 4\nsamples = 4\n"
        );
        let mut run = Simulation::from_toml(&text, "m.toml".as_ref()).unwrap();
        run.run(&mut (), None).unwrap();
        let rows = run.species_samples().unwrap();
        let last = run.samples().last().unwrap();
        let mixed: f64 = rows[rows.len() - 2..]
            .iter()
            .map(|r| 0.5 * r.rotational_temperature.unwrap())
            .sum();
        assert!((mixed - last.rotational_temperature.unwrap()).abs() < 1e-12 * mixed);
        let dir = temp_dir("species");
        run.write(&dir).unwrap();
        let csv = std::fs::read_to_string(dir.join("species.csv")).unwrap();
        assert!(csv
            .lines()
            .next()
            .unwrap()
            .ends_with(",rotational_temperature"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// A tangential restitution per pair of species: with only the pairs of species 0 rough
/// (beta_01 = beta_11 = -1) the spins of species 1 are never touched, so its rotational
/// temperature stays its start's bit for bit, while species 0's changes (the oracle: the
/// rule's beta = -1 is no tangential impulse).
#[test]
fn a_matrix_of_tangential_restitutions_acts_per_pair() {
    for engine in ENGINES {
        let text = format!(
            "[system]\ndimension = 3\nparticles = 600\npacking_fraction = 0.1\nseed = 2\n\
             species = [{{ diameter = 1.0, mass = 1.0, fraction = 0.5 }}, \
             {{ diameter = 1.5, mass = 2.0, fraction = 0.5 }}]\n\
             [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
             tangential_restitution = [[0.5, -1.0], [-1.0, -1.0]]\n\
             [run]\n{engine}\ncollisions_per_particle = 4\nsamples = 4\n"
        );
        let mut run = Simulation::from_toml(&text, "pairs.toml".as_ref()).unwrap();
        run.run(&mut (), None).unwrap();
        let rows = run.species_samples().unwrap();
        let (first, last) = (&rows[..2], &rows[rows.len() - 2..]);
        // The same spins: equal to round-off (DSMC blocks permute the particles every
        // step, so the sum over species 1 runs in another order).
        let (before, after) = (
            first[1].rotational_temperature.unwrap(),
            last[1].rotational_temperature.unwrap(),
        );
        assert!(
            (after - before).abs() < 1e-13 * before,
            "{engine}: species 1 keeps its spins: {before} -> {after}"
        );
        assert_ne!(
            first[0].rotational_temperature,
            last[0].rotational_temperature
        );
    }
}

/// Bad input names the key and the range; nothing runs.
#[test]
fn bad_rough_keys_are_refused_by_name() {
    let cases: [(&str, &str, u32, &str); 12] = [
        (
            "",
            "tangential_restitution = 1.5",
            3,
            "collision.tangential_restitution",
        ),
        (
            "",
            "tangential_restitution = -1.01",
            3,
            "collision.tangential_restitution",
        ),
        (
            "",
            "tangential_restitution = nan",
            3,
            "collision.tangential_restitution",
        ),
        (
            "",
            "tangential_restitution = 0.5\nfriction = -0.1",
            3,
            "collision.friction",
        ),
        (
            "",
            "tangential_restitution = 0.5\nfriction = inf",
            3,
            "collision.friction",
        ),
        ("", "friction = 0.3", 3, "collision.friction"),
        (
            "",
            "tangential_restitution = -1.0\nfriction = 0.3",
            3,
            "collision.friction",
        ),
        (
            "inertia = 0.7",
            "tangential_restitution = 0.5",
            3,
            "system.inertia",
        ),
        (
            "inertia = 0.6",
            "tangential_restitution = 0.5",
            2,
            "system.inertia",
        ),
        ("inertia = 0.0", "", 3, "system.inertia"),
        (
            "",
            "tangential_restitution = 0.5",
            1,
            "collision.tangential_restitution",
        ),
        (
            "rotational_temperature = 1.0",
            "",
            3,
            "system.rotational_temperature",
        ),
    ];
    let mixture = "species = [{ diameter = 1.0, mass = 1.0, fraction = 0.5 }, \
                   { diameter = 1.5, mass = 2.0, fraction = 0.5 }]";
    let matrices: [(&str, &str, &str); 4] = [
        (
            "",
            "tangential_restitution = [[0.5]]",
            "collision.tangential_restitution",
        ),
        (
            mixture,
            "tangential_restitution = [[0.5, 0.1]]",
            "collision.tangential_restitution",
        ),
        (
            mixture,
            "tangential_restitution = [[0.5, 0.1], [0.2, 0.3]]",
            "collision.tangential_restitution[0][1]",
        ),
        (
            mixture,
            "tangential_restitution = [[0.5, 0.1], [0.1, 1.3]]",
            "collision.tangential_restitution[1][1]",
        ),
    ];
    for (system, collision, key) in matrices {
        let text = gas(
            3,
            "engine = \"event-driven\"",
            system,
            &format!("{collision}\n"),
        );
        let error = Simulation::from_toml(&text, "bad.toml".as_ref())
            .err()
            .expect("refused");
        assert!(
            error.is_input() && error.to_string().contains(key),
            "{collision}: {error}"
        );
    }
    for (system, collision, dimension, key) in cases {
        let text = gas(
            dimension,
            "engine = \"event-driven\"",
            system,
            &format!("{collision}\n"),
        );
        let error = match Simulation::from_toml(&text, "bad.toml".as_ref()) {
            Ok(_) => panic!("{system} {collision}: accepted"),
            Err(e) => e,
        };
        assert!(error.is_input(), "{error}");
        assert!(
            error.to_string().contains(key),
            "{system} {collision}: {error}"
        );
    }
}

/// An engine without rough particles (soft-sphere MD) refuses the key, naming it and the
/// engines that have them.
#[test]
fn engines_without_rotation_refuse_the_key() {
    let text = "[system]\nparticles = 40\npacking_fraction = 0.1\n\
                [collision]\nlaw = \"viscoelastic\"\nyoung = 1e5\npoisson = 0.3\n\
                dissipative_constant = 0.01\ntangential_restitution = 0.5\n\
                [run]\nengine = \"soft-sphere\"\nend_time = 0.5\nsamples = 3\n";
    let error = Simulation::from_toml(text, "soft.toml".as_ref())
        .err()
        .expect("refused");
    let message = error.to_string();
    assert!(error.is_input(), "{message}");
    assert!(
        message.contains("collision.tangential_restitution")
            && message.contains("\"event-driven\"")
            && message.contains("\"dsmc\""),
        "{message}"
    );
}

/// The spins are part of a check-point's energy. A perfectly rough elastic gas (alpha =
/// beta = 1: energy kept) resumes from its check-point even where the start's spins,
/// drawn at T_rot0 without rescaling, hold more than N d_rot T_rot0 / 2 (the seeds with
/// T_rot(0) > T_rot0, of which there must be one: the oracle that the bound allows for the
/// draw); a check-point whose last spin was forged to 1e300 is refused, naming the energy
/// (the fuzz harness found such a state run to infinite temperatures).
#[test]
fn a_check_point_s_spins_count_in_its_energy() {
    for engine in ENGINES {
        let mut above = 0;
        for seed in 1..=6 {
            let text = gas(
                3,
                engine,
                "rotational_temperature = 0.5",
                "tangential_restitution = 1.0\n",
            )
            .replace("restitution = 0.85", "restitution = 1.0")
            .replace("seed = 5", &format!("seed = {seed}"));
            let mut run = Simulation::from_toml(&text, "e.toml".as_ref()).unwrap();
            let dir = temp_dir(&format!("energy-{seed}"));
            run.set_output_dir(&dir);
            assert!(run
                .advance(Point::CollisionsPerParticle(2.5), &mut ())
                .unwrap());
            above += (run.samples()[0].rotational_temperature.unwrap() > 0.5) as usize;
            let file = dir.join(sim::checkpoint::FILE_NAME);
            run.save(&file).unwrap();
            if let Err(e) = Simulation::resume(&dir) {
                panic!("{engine}, seed {seed}: {e}");
            }
            // The state ends with the spins, then the sliding contacts (0: one byte).
            let bytes = std::fs::read(&file).unwrap();
            let first = bytes.iter().position(|&b| b == b'\n').unwrap();
            let mut header: serde_json::Value = serde_json::from_slice(&bytes[..first]).unwrap();
            let records = header["records_bytes"].as_u64().unwrap() as usize;
            let mut state = bytes[first + 2 + records..].to_vec();
            let at = state.len() - 9;
            assert_eq!(state[state.len() - 1], 0);
            let w: f64 = f64::from_le_bytes(state[at..at + 8].try_into().unwrap());
            assert!(w.is_finite() && w != 0.0 && w.abs() < 100.0, "a spin: {w}");
            state[at..at + 8].copy_from_slice(&1e300f64.to_le_bytes());
            let mut crc = crc32fast::Hasher::new();
            crc.update(&bytes[first + 1..first + 1 + records]);
            crc.update(&state);
            header["crc32"] = crc.finalize().into();
            let mut forged = serde_json::to_vec(&header).unwrap();
            forged.extend_from_slice(&bytes[first..first + 2 + records]);
            forged.extend(state);
            std::fs::write(&file, forged).unwrap();
            let error = Simulation::resume(&dir)
                .err()
                .expect("a spin of 1e300 refused");
            assert!(error.to_string().contains("energy"), "{engine}: {error}");
            std::fs::remove_dir_all(&dir).unwrap();
        }
        assert!(above > 0, "{engine}: no start drew T_rot above T_rot0");
    }
}
