//! `system.box`: boxes with sides of their own through the driver, in every engine with
//! space; the refusals name the key.

use sim::{Point, Simulation};

/// A 2D channel twice as long as wide, closed across (y) by elastic walls.
const CHANNEL: &str = "[system]\ndimension = 2\nparticles = 300\nbox = [40.0, 20.0]\nseed = 3\n\
                       [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
                       [run]\ncollisions_per_particle = 20\nsamples = 5\nspacing = \"linear\"\n\
                       [output]\nprofiles = { axis = \"x\", bins = 8 }\n\
                       [[wall]]\naxis = \"y\"\nside = \"low\"\nkind = \"elastic\"\n\
                       [[wall]]\naxis = \"y\"\nside = \"high\"\nkind = \"elastic\"\n";

/// A run in a box with sides: the summary's packing fraction is the disks' area over the
/// box's (300 pi / 4 / 800), the profile along the long axis has its bins L_x / 8 wide,
/// the walls their area L_x, and a mid-run check-point resumes bit for bit.
#[test]
fn a_channel_runs_and_resumes() {
    let mut run = Simulation::from_toml(CHANNEL, "channel.toml".as_ref()).unwrap();
    assert!(run
        .advance(Point::CollisionsPerParticle(8.0), &mut ())
        .unwrap());
    let dir = std::env::temp_dir().join(format!("haff-box-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("box.bin");
    run.save(&file).unwrap();
    let mut loaded = Simulation::load(&file).unwrap();
    run.run(&mut (), None).unwrap();
    loaded.run(&mut (), None).unwrap();
    assert_eq!(loaded.samples(), run.samples());
    assert_eq!(loaded.wall_samples(), run.wall_samples());
    assert_eq!(loaded.profile_rows(), run.profile_rows());
    let rows = run.profile_rows().unwrap();
    let positions: Vec<f64> = rows[..8].iter().map(|r| r.position).collect();
    assert_eq!(
        positions,
        (0..8).map(|b| 2.5 + 5.0 * b as f64).collect::<Vec<_>>()
    );
    // Every disk is in one bin: the densities times the slab areas (5 x 20) count them.
    let counted: f64 = rows[..8].iter().map(|r| r.density * 100.0).sum();
    assert!((counted - 300.0).abs() < 1e-9, "{counted}");
    loaded.write(&dir).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(
        summary["parameters"]["system"]["box"],
        serde_json::json!([40.0, 20.0])
    );
    assert!(summary["parameters"]["system"]["packing_fraction"].is_null());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The spatial engines all take a box: spatial DSMC (its particles standing for
/// `particle_weight` each, the packing fraction theirs in the box) and soft-sphere MD.
#[test]
fn every_engine_with_space_takes_a_box() {
    let dsmc = "[system]\ndimension = 3\nparticles = 2000\nbox = [30.0, 15.0, 10.0]\n\
                [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
                [run]\nengine = \"dsmc\"\ndsmc_scheme = \"spatial\"\nparticle_weight = 2.0\n\
                collisions_per_particle = 2\nsamples = 3\n";
    let mut run = Simulation::from_toml(dsmc, "dsmc.toml".as_ref()).unwrap();
    let phi = 2.0 * 2000.0 * std::f64::consts::PI / 6.0 / 4500.0;
    assert!((run.plan().description.packing_fraction() / phi - 1.0).abs() < 1e-12);
    run.run(&mut (), None).unwrap();
    assert!(run.samples().last().unwrap().collisions_per_particle >= 2.0);
    let soft = "[system]\ndimension = 3\nparticles = 300\nbox = [16.0, 8.0, 12.0]\n\
                [collision]\nlaw = \"viscoelastic\"\nyoung = 1e4\npoisson = 0.3\n\
                dissipative_constant = 1e-3\n\
                [run]\nengine = \"soft-sphere\"\ncollisions_per_particle = 1\nsamples = 2\n";
    let mut run = Simulation::from_toml(soft, "soft.toml".as_ref()).unwrap();
    run.run(&mut (), None).unwrap();
    assert!(run.samples().last().unwrap().collisions_per_particle >= 1.0);
}

/// Bad boxes name their key and the allowed range.
#[test]
fn bad_boxes_name_their_key() {
    let modes = CHANNEL.replace("[output]\n", "[output]\nmodes = true\n");
    let homogeneous = CHANNEL
        .replace("[run]\n", "[run]\nengine = \"dsmc\"\n")
        .replace("[output]\nprofiles = { axis = \"x\", bins = 8 }\n", "");
    let homogeneous = homogeneous[..homogeneous.find("[[wall]]").unwrap()].to_string();
    let cases = [
        (
            CHANNEL.replace(
                "box = [40.0, 20.0]",
                "box = [40.0, 20.0]\npacking_fraction = 0.1",
            ),
            "system.box",
        ),
        (
            CHANNEL.replace("box = [40.0, 20.0]\n", ""),
            "system.packing_fraction",
        ),
        (
            CHANNEL.replace("[40.0, 20.0]", "[40.0, 20.0, 1.0]"),
            "system.box",
        ),
        (
            CHANNEL.replace("[40.0, 20.0]", "[40.0, -2.0]"),
            "system.box[1]",
        ),
        (
            CHANNEL.replace("[40.0, 20.0]", "[40.0, nan]"),
            "system.box[1]",
        ),
        // 300 disks in 16 x 10 fill 1.47 of it.
        (
            CHANNEL.replace("[40.0, 20.0]", "[16.0, 10.0]"),
            "system.box",
        ),
        // Fewer than 4 diameters across (the event-driven engine's cells).
        (
            CHANNEL.replace("[40.0, 20.0]", "[400.0, 3.0]"),
            "system.box[1]",
        ),
        (modes, "output.modes"),
        (
            CHANNEL.replace("[output]\n", "[output]\nstructure = true\n"),
            "output.structure",
        ),
        (homogeneous, "system.box"),
    ];
    for (text, key) in cases {
        let error = Simulation::from_toml(&text, "bad.toml".as_ref())
            .err()
            .unwrap_or_else(|| panic!("accepted, expected an error naming {key}"));
        assert!(error.is_input(), "{key}: {error}");
        assert!(
            error.to_string().starts_with(key),
            "expected {key}: {error}"
        );
    }
    // A box of equal sides is a cube: the modes are allowed.
    let cube = CHANNEL
        .replace("[40.0, 20.0]", "[30.0, 30.0]")
        .replace("[output]\n", "[output]\nmodes = true\n");
    assert!(Simulation::from_toml(&cube, "cube.toml".as_ref()).is_ok());
}
