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
            // The first Sonine approximation beside it: the gas crate's numbers bit for bit.
            let sonine = gas::theory::rough_sonine::hcs(&gas::theory::rough::RoughMaxwellian {
                dimension: dimension as usize,
                alpha: 0.85,
                beta: 0.3,
                inertia: 0.35,
            })
            .unwrap();
            let section = &theory["sonine"];
            assert_eq!(section["hcs_ratio"], sonine.ratio);
            assert_eq!(section["a20"], sonine.a20);
            assert_eq!(section["a02"], sonine.a02);
            assert_eq!(section["a11"], sonine.a11);
            assert_eq!(
                section["hcs_cooling_per_collision"],
                sonine.cooling_per_collision
            );
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

/// A soft-sphere gas made rough by `collision.friction` alone.
fn soft_gas(dimension: u32, extra_system: &str, extra_collision: &str) -> String {
    format!(
        "[system]\ndimension = {dimension}\nparticles = 200\npacking_fraction = 0.1\nseed = 5\n\
         {extra_system}\n[collision]\nlaw = \"viscoelastic\"\nyoung = 1e4\npoisson = 0.3\n\
         dissipative_constant = 1e-3\n{extra_collision}\n\
         [run]\nengine = \"soft-sphere\"\ncollisions_per_particle = 2\nsamples = 6\n\
         spacing = \"linear\"\n"
    )
}

/// Soft-sphere MD with `collision.friction`: the rotational temperature column, the
/// `rotation` section (no `rough_theory`: no constant beta), snapshots with the angular
/// velocities, resumed bit for bit from a check-point (springs of open contacts, torques
/// and spins in it); spins start at rest (rotational_temperature = 0) and the contacts
/// heat them.
#[test]
fn soft_spheres_are_rough_by_their_friction() {
    for dimension in [2, 3] {
        let text = soft_gas(dimension, "rotational_temperature = 0.0", "friction = 0.4")
            + "[output]\nsnapshots = { every = 3 }\n";
        let mut run = Simulation::from_toml(&text, "soft.toml".as_ref()).unwrap();
        let dir = temp_dir(&format!("soft-{dimension}"));
        run.set_output_dir(&dir);
        assert!(run
            .advance(Point::CollisionsPerParticle(0.9), &mut ())
            .unwrap());
        let file = dir.join("soft.bin");
        run.save(&file).unwrap();
        let mut loaded = Simulation::load(&file).unwrap();
        run.run(&mut (), None).unwrap();
        loaded.set_output_dir(&dir);
        loaded.run(&mut (), None).unwrap();
        assert_eq!(loaded.samples(), run.samples(), "{dimension}D");
        run.write(&dir).unwrap();
        let csv = std::fs::read_to_string(dir.join("timeseries.csv")).unwrap();
        assert!(csv
            .lines()
            .next()
            .unwrap()
            .ends_with(",rotational_temperature"));
        let samples = run.samples();
        assert_eq!(samples[0].rotational_temperature, Some(0.0));
        assert!(samples.last().unwrap().rotational_temperature.unwrap() > 0.0);
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        assert!(summary.get("rough_theory").is_none());
        assert!(summary["rotation"]["sliding_contacts"].as_u64().unwrap() > 0);
        let vtu = std::fs::read_to_string(dir.join("snapshot_000003.vtu")).unwrap();
        assert!(vtu.contains("angular_velocity"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// Hot spins (T_rot = 20 T_tr at the start) heat translation above its initial energy: a
/// check-point of such a soft-sphere run resumes (the energy check counts the spins) and
/// continues bit for bit.
#[test]
fn soft_spheres_with_hot_spins_resume() {
    let text = soft_gas(3, "rotational_temperature = 20.0", "friction = 0.5");
    let mut run = Simulation::from_toml(&text, "hot.toml".as_ref()).unwrap();
    let dir = temp_dir("hot");
    assert!(run
        .advance(Point::CollisionsPerParticle(1.2), &mut ())
        .unwrap());
    assert!(run.samples().last().unwrap().temperature > 1.0);
    let file = dir.join("hot.bin");
    run.save(&file).unwrap();
    let mut loaded = Simulation::load(&file).unwrap();
    run.run(&mut (), None).unwrap();
    loaded.run(&mut (), None).unwrap();
    assert_eq!(loaded.samples(), run.samples());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Soft-sphere MD refuses a tangential restitution (its contact force yields one),
/// rotation in 1D, a rotational temperature of smooth spheres, and a step that does not
/// resolve the tangential oscillation of light-inertia spheres (q = 0.01: 9 times faster
/// than the normal one, 50 steps per contact give 5.5 steps to it, 10 are needed),
/// naming the key.
#[test]
fn soft_spheres_refuse_what_their_contacts_decide() {
    let cases = [
        (
            3,
            "",
            "tangential_restitution = 0.3\nfriction = 0.4",
            "collision.tangential_restitution",
        ),
        (
            3,
            "",
            "tangential_restitution = 0.3",
            "collision.tangential_restitution",
        ),
        (1, "", "friction = 0.4", "collision.friction"),
        (
            3,
            "rotational_temperature = 1.0",
            "",
            "system.rotational_temperature",
        ),
        (3, "", "friction = -0.4", "collision.friction"),
        (3, "inertia = 0.01", "friction = 0.4", "collision.friction"),
    ];
    for (dimension, system, collision, key) in cases {
        let text = soft_gas(dimension, system, collision);
        let error = match Simulation::from_toml(&text, "bad.toml".as_ref()) {
            Ok(mut run) => run.run(&mut (), None).expect_err("refused"),
            Err(e) => e,
        };
        assert!(error.is_input(), "{error}");
        assert!(error.to_string().contains(key), "{collision}: {error}");
    }
}

/// Rough disks under shear with profiles along y: `profiles.csv` appends the rotation
/// columns (each slab's rotational temperature about its mean spin, and that spin), which a
/// check-point resumes bit for bit; smooth runs keep the twelve columns (tested in
/// `profiles.rs`).
#[test]
fn profiles_of_rough_particles_carry_their_spin() {
    let text = "[system]\ndimension = 2\nparticles = 500\npacking_fraction = 0.1\nseed = 4\n\
                [collision]\nlaw = \"constant\"\nrestitution = 0.9\ntangential_restitution = 0.0\n\
                [run]\ncollisions_per_particle = 20\nsamples = 11\nspacing = \"linear\"\n\
                [shear]\nrate = 0.5\n[output]\nprofiles = { axis = \"y\", bins = 4 }\n";
    let mut run = Simulation::from_toml(text, "sheared.toml".as_ref()).unwrap();
    let dir = temp_dir("profiles");
    assert!(run
        .advance(Point::CollisionsPerParticle(7.0), &mut ())
        .unwrap());
    let file = dir.join("sheared.bin");
    run.save(&file).unwrap();
    let mut loaded = Simulation::load(&file).unwrap();
    run.run(&mut (), None).unwrap();
    loaded.run(&mut (), None).unwrap();
    assert_eq!(loaded.profile_rows(), run.profile_rows());
    loaded.write(&dir).unwrap();
    let csv = std::fs::read_to_string(dir.join("profiles.csv")).unwrap();
    let mut lines = csv.lines();
    assert!(lines.next().unwrap().ends_with(
        ",velocity_z,rotational_temperature,angular_velocity_x,angular_velocity_y,\
         angular_velocity_z"
    ));
    let last: Vec<&str> = csv.lines().last().unwrap().split(',').collect();
    assert_eq!(last.len(), 16);
    assert!(last[12].parse::<f64>().unwrap() > 0.0);
    // Disks spin about z only.
    assert_eq!((last[13], last[14]), ("0", "0"));
    std::fs::remove_dir_all(&dir).unwrap();
}
