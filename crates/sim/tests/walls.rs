//! Runs in containers (`[[wall]]`) through the driver: `walls.csv`, `summary.json`'s
//! `walls`, check-points, and the refusals of bad walls naming their key.

use sim::{Point, Simulation};

const BOX: &str = "[system]\ndimension = 2\nparticles = 200\npacking_fraction = 0.1\nseed = 7\n\
                   [collision]\nlaw = \"constant\"\nrestitution = 1.0\n\
                   [run]\ncollisions_per_particle = 40\nsamples = 9\nspacing = \"linear\"\n";

const WALLS: &str = "[[wall]]\naxis = \"y\"\nside = \"low\"\nkind = \"thermal\"\ntemperature = 2.0\n\
                     [[wall]]\naxis = \"y\"\nside = \"high\"\nkind = \"restitution\"\nrestitution = 0.5\n";

fn run_text(walls: &str) -> String {
    format!("{BOX}{walls}")
}

/// `walls.csv` has the header and one row per wall per sample, cumulative;
/// `summary.json` has each wall's pressure and energy flux; a check-point taken mid-run
/// resumes bit for bit, walls included.
#[test]
fn walls_are_written_balanced_and_resumed() {
    let text = run_text(WALLS);
    let mut run = Simulation::from_toml(&text, "walls.toml".as_ref()).unwrap();
    assert!(run
        .advance(Point::CollisionsPerParticle(15.0), &mut ())
        .unwrap());
    let dir = std::env::temp_dir().join(format!("haff-walls-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("walls.bin");
    run.save(&file).unwrap();
    let mut loaded = Simulation::load(&file).unwrap();
    run.run(&mut (), None).unwrap();
    loaded.run(&mut (), None).unwrap();
    assert_eq!(loaded.samples(), run.samples());
    assert_eq!(loaded.wall_samples(), run.wall_samples());
    let rows = run.wall_samples().unwrap();
    assert_eq!(rows.len(), 2 * run.samples().len());
    // Cumulative: the hot thermal wall (T_w = 2 > T = 1) has given energy, the
    // restitution wall taken it (the exact balance is gas/tests/walls.rs's).
    let last = &rows[rows.len() - 2..];
    assert!(last[0].energy > 0.0 && last[1].energy < 0.0, "{last:?}");
    for pair in rows.chunks(2).collect::<Vec<_>>().windows(2) {
        assert!(pair[1][0].collisions >= pair[0][0].collisions);
        assert!(pair[1][0].time > pair[0][0].time);
    }
    loaded.write(&dir).unwrap();
    let csv = std::fs::read_to_string(dir.join("walls.csv")).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "time,collisions_per_particle,axis,side,collisions,momentum,energy"
    );
    assert_eq!(csv.lines().count(), 1 + rows.len());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let walls = summary["walls"].as_array().unwrap();
    assert_eq!(walls.len(), 2);
    assert!(walls[0]["pressure"].as_f64().unwrap() > 0.0);
    assert_eq!(walls[1]["side"], "high");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A periodic run writes no `walls.csv` rows and no `walls` key.
#[test]
fn periodic_runs_have_no_walls() {
    let run = Simulation::from_toml(&run_text(""), "periodic.toml".as_ref()).unwrap();
    assert!(run.wall_samples().is_none());
}

/// Bad walls: exit 2 (an input error) naming the key.
#[test]
fn bad_walls_name_their_key() {
    let one_side = "[[wall]]\naxis = \"y\"\nside = \"low\"\nkind = \"elastic\"\n";
    let cases = [
        (one_side.to_string(), "wall[0].side"),
        (format!("{one_side}{one_side}"), "wall[1].side"),
        (WALLS.replace("\"y\"", "\"z\""), "wall[0].axis"),
        (
            WALLS.replace("temperature = 2.0", "temperature = -1.0"),
            "wall[0].temperature",
        ),
        (
            // Speeds 1e7 times the gas's: beyond the clock's resolution.
            WALLS.replace("temperature = 2.0", "temperature = 1e14"),
            "wall[0].temperature",
        ),
        (
            WALLS.replace("restitution = 0.5", "restitution = 1.5"),
            "wall[1].restitution",
        ),
        (
            WALLS.replace("kind = \"restitution\"", "kind = \"elastic\""),
            "wall[1].restitution",
        ),
        (
            WALLS.replace("temperature = 2.0", "temperature = 2.0\namplitude = 0.1"),
            "wall[0].amplitude",
        ),
        (
            WALLS.replace(
                "kind = \"thermal\"\ntemperature = 2.0",
                "kind = \"vibrating\"",
            ),
            "wall[0].amplitude",
        ),
        (
            WALLS.replace(
                "kind = \"thermal\"\ntemperature = 2.0",
                "kind = \"vibrating\"\namplitude = 20.0\nfrequency = 0.01",
            ),
            "wall[0].amplitude",
        ),
        (
            WALLS.replace(
                "kind = \"thermal\"\ntemperature = 2.0",
                "kind = \"vibrating\"\namplitude = 0.1\nfrequency = 1e8",
            ),
            "wall[0].frequency",
        ),
        (
            WALLS.replace(
                "kind = \"thermal\"\ntemperature = 2.0",
                "kind = \"vibrating\"\namplitude = 0.1\nfrequency = 1.0\ntemperature = 1.0",
            ),
            "wall[0].temperature",
        ),
    ];
    for (walls, key) in cases {
        let text = run_text(&walls);
        let error = Simulation::from_toml(&text, "bad.toml".as_ref())
            .err()
            .unwrap_or_else(|| panic!("accepted:\n{walls}"));
        assert!(error.is_input(), "{error}");
        assert!(error.to_string().contains(key), "{key}: {error}");
    }
    // Homogeneous DSMC refuses walls naming the section; soft-sphere MD refuses thermal
    // walls (`WALLS` has one) naming the kind.
    let soft = "[system]\nparticles = 40\npacking_fraction = 0.1\n\
                [collision]\nlaw = \"viscoelastic\"\nyoung = 1e5\npoisson = 0.3\n\
                dissipative_constant = 0.01\n\
                [run]\nengine = \"soft-sphere\"\nend_time = 0.5\nsamples = 3\n";
    let dsmc = BOX.replace("[run]\n", "[run]\nengine = \"dsmc\"\n");
    for base in [soft.to_string(), dsmc] {
        let text = format!("{base}{WALLS}");
        let error = Simulation::from_toml(&text, "bad.toml".as_ref())
            .err()
            .unwrap();
        assert!(error.is_input(), "{error}");
        assert!(error.to_string().starts_with("wall"), "{error}");
    }
    let soft_restitution = format!(
        "{soft}[[wall]]\naxis = \"z\"\nside = \"low\"\nkind = \"restitution\"\nrestitution = 0.5\n\
         [[wall]]\naxis = \"z\"\nside = \"high\"\nkind = \"elastic\"\n"
    );
    let error = Simulation::from_toml(&soft_restitution, "bad.toml".as_ref())
        .err()
        .unwrap();
    assert!(error.to_string().contains("wall[0].restitution"), "{error}");
}

/// Soft-sphere MD in a container from a run file (a damped bed on a vibrating floor in
/// gravity): walls.csv, and a mid-run check-point resumes bit for bit.
#[test]
fn soft_spheres_in_a_container_resume() {
    let text = "[system]\nparticles = 60\npacking_fraction = 0.05\ntemperature = 0.1\n\
                [collision]\nlaw = \"viscoelastic\"\nyoung = 1e5\npoisson = 0.3\n\
                dissipative_constant = 0.01\n\
                [run]\nengine = \"soft-sphere\"\nend_time = 6.0\nsamples = 4\n\
                [field]\ngravity = [0.0, 0.0, -1.0]\n\
                [[wall]]\naxis = \"z\"\nside = \"low\"\nkind = \"vibrating\"\n\
                amplitude = 0.1\nfrequency = 2.0\n\
                [[wall]]\naxis = \"z\"\nside = \"high\"\nkind = \"elastic\"\n";
    let mut run = Simulation::from_toml(text, "soft.toml".as_ref()).unwrap();
    assert!(run.advance(Point::Time(2.0), &mut ()).unwrap());
    let dir = std::env::temp_dir().join(format!("haff-soft-walls-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("soft.bin");
    run.save(&file).unwrap();
    let mut loaded = Simulation::load(&file).unwrap();
    run.run(&mut (), None).unwrap();
    loaded.run(&mut (), None).unwrap();
    assert_eq!(loaded.samples(), run.samples());
    assert_eq!(loaded.wall_samples(), run.wall_samples());
    let rows = run.wall_samples().unwrap();
    assert!(
        rows[rows.len() - 2].collisions > 10,
        "{:?}",
        rows[rows.len() - 2]
    );
    std::fs::remove_dir_all(&dir).unwrap();
    let bad = text.replace(
        "gravity = [0.0, 0.0, -1.0]",
        "gravity = [0.0, 0.0, -1.0]\nrest_height = 0.01",
    );
    let error = Simulation::from_toml(&bad, "bad.toml".as_ref())
        .err()
        .unwrap();
    assert!(error.to_string().contains("field.rest_height"), "{error}");
}

/// A column in gravity (`[field]`) from a run file: resumes bit for bit from a check-point
/// taken mid-run (the falling frame is the box's at every check-point); the walls' pressures
/// differ by the weight (momentum balance: floor − ceiling = N m g / L over a long span,
/// within the change of the gas's momentum, which the second half's ~8e4 collisions make
/// small: 3 % of the weight allowed).
#[test]
fn gravity_from_a_run_file_resumes_and_weighs_on_the_floor() {
    let text = BOX.replace(
        "collisions_per_particle = 40",
        "collisions_per_particle = 800",
    ) + "[field]\ngravity = [0.0, -0.05]\n"
        + &WALLS.replace(
            "kind = \"restitution\"\nrestitution = 0.5",
            "kind = \"elastic\"",
        );
    let mut run = Simulation::from_toml(&text, "column.toml".as_ref()).unwrap();
    assert!(run
        .advance(Point::CollisionsPerParticle(100.0), &mut ())
        .unwrap());
    let dir = std::env::temp_dir().join(format!("haff-gravity-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("column.bin");
    run.save(&file).unwrap();
    let mut loaded = Simulation::load(&file).unwrap();
    run.run(&mut (), None).unwrap();
    loaded.run(&mut (), None).unwrap();
    assert_eq!(loaded.samples(), run.samples());
    assert_eq!(loaded.wall_samples(), run.wall_samples());
    loaded.write(&dir).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let walls = summary["walls"].as_array().unwrap();
    let pressure = |w: usize| walls[w]["pressure"].as_f64().unwrap();
    let side = (200.0 * std::f64::consts::PI / 4.0 / 0.1f64).sqrt();
    let weight = 200.0 * 0.05 / side;
    let difference = pressure(0) - pressure(1);
    eprintln!("floor - ceiling {difference}, weight per unit length {weight}");
    assert!(
        (difference / weight - 1.0).abs() < 0.03,
        "{difference} vs {weight}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Bad gravity: exit 2 naming the key.
#[test]
fn bad_gravity_names_its_key() {
    let column = format!("{BOX}[field]\ngravity = [0.0, -1.0]\n{WALLS}");
    let cases = [
        (
            column.replace("[0.0, -1.0]", "[-1.0, 0.0]"),
            "field.gravity[0]",
        ),
        (
            column.replace("[0.0, -1.0]", "[0.0, 0.0, -1.0]"),
            "field.gravity",
        ),
        (
            column.replace("[0.0, -1.0]", "[0.0, 1e31]"),
            "field.gravity[1]",
        ),
        (
            column.replace(
                "gravity = [0.0, -1.0]",
                "gravity = [0.0, -1.0]\nrest_height = 2.0",
            ),
            "field.rest_height",
        ),
        (
            column.replace("gravity = [0.0, -1.0]", "gravity = [0.0, -1.0]\nwind = 1.0"),
            "wind",
        ),
        (
            format!("{BOX}[field]\ngravity = [0.0, -1.0]\n"),
            "field.gravity[1]",
        ),
        (
            column.replace("[run]\n", "[run]\nengine = \"dsmc\"\n"),
            "wall",
        ),
        (
            format!("{column}[driving]\nkind = \"white-noise\"\nstrength = 1.0\n"),
            "field.gravity",
        ),
    ];
    for (text, key) in cases {
        let error = Simulation::from_toml(&text, "bad.toml".as_ref())
            .err()
            .unwrap_or_else(|| panic!("accepted:\n{text}"));
        assert!(error.is_input(), "{error}");
        assert!(error.to_string().contains(key), "{key}: {error}");
    }
}

/// A vibrated bed from a run file (sine floor, gravity, inelastic spheres with the TC
/// model): the floor heats it (walls.csv: energy given > 0; the exact balance is
/// `crates/gas/tests/vibrating.rs`'s), and it resumes bit for bit.
#[test]
fn a_vibrated_bed_from_a_run_file_is_heated_and_resumes() {
    let text = "[system]\ndimension = 2\nparticles = 100\npacking_fraction = 0.05\nseed = 3\n\
                [collision]\nlaw = \"constant\"\nrestitution = 0.9\ntc = 1e-4\n\
                [run]\ncollisions_per_particle = 100\nsamples = 5\n\
                [field]\ngravity = [0.0, -1.0]\n\
                [[wall]]\naxis = \"y\"\nside = \"low\"\nkind = \"vibrating\"\n\
                amplitude = 0.5\nfrequency = 1.0\nwaveform = \"sine\"\n\
                [[wall]]\naxis = \"y\"\nside = \"high\"\nkind = \"elastic\"\n";
    let mut run = Simulation::from_toml(text, "bed.toml".as_ref()).unwrap();
    assert!(run
        .advance(Point::CollisionsPerParticle(30.0), &mut ())
        .unwrap());
    let dir = std::env::temp_dir().join(format!("haff-bed-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("bed.bin");
    run.save(&file).unwrap();
    let mut loaded = Simulation::load(&file).unwrap();
    run.run(&mut (), None).unwrap();
    loaded.run(&mut (), None).unwrap();
    assert_eq!(loaded.samples(), run.samples());
    assert_eq!(loaded.wall_samples(), run.wall_samples());
    let walls = run.wall_samples().unwrap();
    let floor = &walls[walls.len() - 2];
    assert!(floor.collisions > 100 && floor.energy > 0.0, "{floor:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Spatial DSMC in a container from a run file (thermal floor and ceiling, gravity,
/// profiles): walls.csv and profiles.csv written, a mid-run check-point resumes bit for
/// bit; several ranks are no longer refused with walls (crates/gas/tests/ranks.rs and the
/// MPI test run them).
#[test]
fn spatial_dsmc_in_a_container_resumes() {
    let text = "[system]\ndimension = 2\nparticles = 2000\npacking_fraction = 0.05\nseed = 4\n\
                [collision]\nlaw = \"constant\"\nrestitution = 0.95\n\
                [run]\nengine = \"dsmc\"\ndsmc_scheme = \"spatial\"\n\
                collisions_per_particle = 20\nsamples = 5\n\
                [output]\nprofiles = { axis = \"y\", bins = 10 }\n\
                [field]\ngravity = [0.0, -0.02]\n\
                [[wall]]\naxis = \"y\"\nside = \"low\"\nkind = \"thermal\"\ntemperature = 1.0\n\
                [[wall]]\naxis = \"y\"\nside = \"high\"\nkind = \"thermal\"\ntemperature = 1.0\n";
    let mut run = Simulation::from_toml(text, "dsmc.toml".as_ref()).unwrap();
    assert!(run
        .advance(Point::CollisionsPerParticle(8.0), &mut ())
        .unwrap());
    let dir = std::env::temp_dir().join(format!("haff-dsmc-walls-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("dsmc.bin");
    run.save(&file).unwrap();
    let mut loaded = Simulation::load(&file).unwrap();
    run.run(&mut (), None).unwrap();
    loaded.run(&mut (), None).unwrap();
    assert_eq!(loaded.samples(), run.samples());
    assert_eq!(loaded.wall_samples(), run.wall_samples());
    assert_eq!(loaded.profile_rows(), run.profile_rows());
    let rows = run.wall_samples().unwrap();
    assert!(rows[rows.len() - 2].collisions > 100);
    std::fs::remove_dir_all(&dir).unwrap();
    let ranks = text.replace(
        "dsmc_scheme = \"spatial\"\n",
        "dsmc_scheme = \"spatial\"\nranks = 2\n",
    );
    // Walls run on several ranks too: this (non-MPI) process refuses only the launch.
    let error = Simulation::from_toml(&ranks, "ranks.toml".as_ref())
        .err()
        .unwrap();
    assert!(
        error.is_input() && error.to_string().starts_with("run.ranks"),
        "{error}"
    );
}

/// A wall may take any law of `[collision]` with its keys (`law = "viscoelastic"`,
/// `beta`; `law = "dashpot"`, `damping_ratio`); keys of another law are refused naming
/// them, as is a beta beyond the exact law's range for the run's impacts. The viscoelastic
/// wall takes energy (walls.csv; the exact balance of any law is
/// `crates/gas/tests/walls.rs`'s).
#[test]
fn walls_take_the_laws_of_collisions() {
    let viscoelastic = WALLS.replace(
        "kind = \"restitution\"\nrestitution = 0.5",
        "kind = \"restitution\"\nlaw = \"viscoelastic\"\nbeta = 0.2",
    );
    let mut run = Simulation::from_toml(&run_text(&viscoelastic), "law.toml".as_ref()).unwrap();
    run.run(&mut (), None).unwrap();
    let rows = run.wall_samples().unwrap();
    assert!(
        rows[rows.len() - 1].energy < 0.0,
        "{:?}",
        rows[rows.len() - 1]
    );
    let bad = [
        (
            "kind = \"restitution\"\nlaw = \"dashpot\"\nrestitution = 0.5",
            "wall[1].restitution",
        ),
        (
            "kind = \"restitution\"\nlaw = \"viscoelastic\"",
            "wall[1].beta",
        ),
        (
            "kind = \"restitution\"\nlaw = \"stochastic\"",
            "wall[1].law",
        ),
        ("kind = \"elastic\"\nbeta = 0.1", "wall[1].beta"),
        (
            "kind = \"restitution\"\nlaw = \"viscoelastic\"\nbeta = 1e30",
            "wall[1].beta",
        ),
    ];
    for (kind, key) in bad {
        let walls = WALLS.replace("kind = \"restitution\"\nrestitution = 0.5", kind);
        let error = Simulation::from_toml(&run_text(&walls), "bad.toml".as_ref())
            .err()
            .unwrap_or_else(|| panic!("accepted: {kind}"));
        assert!(
            error.is_input() || error.to_string().contains(key),
            "{error}"
        );
        assert!(error.to_string().contains(key), "{key}: {error}");
    }
}

/// A viscoelastic wall may be given by its material instead of beta. A wall of the
/// particles' own material (no keys) has beta_w = 2^(-1/5) beta of two such spheres
/// (rho_w / rho = sqrt 2 from R_eff = R instead of R/2, m / m_eff = 2: Eq. (8) of Müller
/// & Pöschel 2011 with the wall's radius and mass infinite); a stiffer wall of another
/// material has E* = 1 / (D_1 + D_2) and the compliance-weighted A (MaterialPair), computed
/// here by hand. Beta and material together, a mixture, and particles without a material
/// are refused naming the key.
#[test]
fn a_viscoelastic_wall_takes_a_material() {
    use sim::validate::{WallLaw, WallSpecKind};
    let gas = "[system]\ndimension = 2\nparticles = 200\npacking_fraction = 0.1\nseed = 7\n\
               [collision]\nlaw = \"viscoelastic\"\nyoung = 1e5\npoisson = 0.3\n\
               dissipative_constant = 1e-3\n\
               [run]\ncollisions_per_particle = 5\nsamples = 3\n";
    let floor = |keys: &str| {
        format!(
            "{gas}[[wall]]\naxis = \"y\"\nside = \"low\"\nkind = \"restitution\"\n\
             law = \"viscoelastic\"\n{keys}\
             [[wall]]\naxis = \"y\"\nside = \"high\"\nkind = \"elastic\"\n"
        )
    };
    let beta_of = |text: &str| -> f64 {
        let run = Simulation::from_toml(text, "wall.toml".as_ref()).unwrap();
        match run.plan().walls[0].kind {
            WallSpecKind::Restitution(WallLaw::Viscoelastic { beta, .. }) => beta,
            ref other => panic!("{other:?}"),
        }
    };
    let pair = match Simulation::from_toml(&floor(""), "pair.toml".as_ref())
        .unwrap()
        .plan()
        .law
    {
        sim::validate::LawSpec::Viscoelastic { beta, .. } => beta,
        ref other => panic!("{other:?}"),
    };
    let own = beta_of(&floor(""));
    assert!(
        (own / (pair * 2f64.powf(-0.2)) - 1.0).abs() < 1e-14,
        "{own} {pair}"
    );
    // A wall ten times stiffer, Poisson 0.2, A = 2e-3 (unit spheres of mass 1).
    let (d1, d2) = ((1.0 - 0.09) / 1e5, (1.0 - 0.04) / 1e6);
    let combined = 1.0 / (d1 + d2);
    let a = (1e-3 * d1 + 2e-3 * d2) / (d1 + d2);
    let expected = 1.5 * a * (4.0 / 3.0 * combined * 0.5f64.sqrt()).powf(0.4);
    let other = beta_of(&floor(
        "young = 1e6\npoisson = 0.2\ndissipative_constant = 2e-3\n",
    ));
    assert!((other / expected - 1.0).abs() < 1e-14, "{other} {expected}");
    let mixture = floor("young = 1e6\n").replace(
        "particles = 200\n",
        "particles = 200\nspecies = [{ diameter = 1.0, mass = 1.0, fraction = 1 }, \
         { diameter = 1.2, mass = 1.5, fraction = 1 }]\n",
    );
    let without = floor("young = 1e6\n").replace(
        "young = 1e5\npoisson = 0.3\ndissipative_constant = 1e-3\n",
        "beta = 0.1\n",
    );
    for (text, key) in [
        (floor("beta = 0.1\nyoung = 1e6\n"), "wall[0].beta"),
        (floor("poisson = 0.7\n"), "wall[0].poisson"),
        (mixture, "wall[0].young"),
        (without, "wall[0].young"),
    ] {
        let error = Simulation::from_toml(&text, "bad.toml".as_ref())
            .err()
            .unwrap_or_else(|| panic!("accepted, expected {key}"));
        assert!(error.is_input(), "{error}");
        assert!(error.to_string().starts_with(key), "{key}: {error}");
    }
}
