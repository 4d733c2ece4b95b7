//! `output.snapshots` in its formats (issue 38): the trajectories `snapshots.lammpstrj` and
//! `snapshots.xyz` hold one frame per snapshot, the same particles bit for bit as the
//! `.vtu` of the same sample (oracle: the `.vtu`'s binary f64 arrays, the state itself);
//! the `.vtu` holds the box; a resumed run continues the trajectories byte for byte as one
//! that ran through; the format key takes a name or a list, keeps one name a plain string,
//! and refuses bad values naming the key and the allowed names.

use sim::particles::{self, Format};
use sim::{Error, RunDescription, Simulation};
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("haff-snapshots-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn text(dimension: usize, format: &str) -> String {
    let sides = ["[100.0]", "[14.0, 11.0]", "[9.0, 8.0, 7.0]"][dimension - 1];
    format!(
        "[system]\ndimension = {dimension}\nparticles = 40\nbox = {sides}\nseed = 7\n\
         species = [{{ diameter = 1.0, mass = 1.0, fraction = 1 }}, \
         {{ diameter = 0.5, mass = 0.25, fraction = 1 }}]\n\
         [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
         [run]\ncollisions_per_particle = 6\nsamples = 7\nspacing = \"linear\"\n\
         [output]\nsnapshots = {{ every = 2, format = {format} }}\n"
    )
}

fn run(text: &str, dir: &Path) -> Simulation {
    let mut run = Simulation::from_toml(text, "t.toml".as_ref()).unwrap();
    run.set_output_dir(dir);
    run.run(&mut (), None).unwrap();
    run.write(dir).unwrap();
    run
}

#[test]
fn trajectories_hold_the_particles_of_the_vtu_bit_for_bit() {
    for dimension in [1, 2, 3] {
        let dir = scratch(&format!("frames{dimension}"));
        let sim = run(
            &text(dimension, "[\"vtk\", \"lammps-dump\", \"xyz\"]"),
            &dir,
        );
        let records = &sim.space_records().snapshots;
        let names: Vec<&str> = records.iter().map(|(_, n)| n.as_str()).collect();
        assert_eq!(
            names,
            [0, 2, 4, 6].map(|k| format!("snapshot_{k:06}.vtu")),
            "{dimension}D"
        );
        let sides = RunDescription::from_toml(&text(dimension, "\"vtk\""), "t".as_ref())
            .unwrap()
            .box_sides();
        for (frame, (time, name)) in records.iter().enumerate() {
            let vtu = particles::read(&dir.join(name), Format::Vtk, dimension, -1).unwrap();
            assert_eq!(vtu.sides, sides);
            assert_eq!(vtu.len(), 40);
            assert_eq!(vtu.species.as_ref().unwrap().iter().max(), Some(&1));
            let xyz = dir.join("snapshots.xyz");
            let xyz = particles::read(&xyz, Format::Xyz, dimension, frame as i64).unwrap();
            assert_eq!(xyz.time, Some(*time));
            assert_eq!(
                xyz,
                sim::particles::Configuration {
                    time: Some(*time),
                    ..vtu.clone()
                }
            );
            let dump = dir.join("snapshots.lammpstrj");
            let dump = particles::read(&dump, Format::LammpsDump, dimension, frame as i64).unwrap();
            assert_eq!(dump, vtu, "{dimension}D frame {frame}");
        }
        // Four frames: the fifth is not there, the last (-1) is the fourth.
        let xyz = dir.join("snapshots.xyz");
        assert!(particles::read(&xyz, Format::Xyz, dimension, 4).is_err());
        let last = particles::read(&xyz, Format::Xyz, dimension, -1).unwrap();
        assert_eq!(last.time, Some(records[3].0));
        assert!(dir.join("snapshots.pvd").exists());
        std::fs::remove_dir_all(&dir).ok();
    }
}

/// Without `vtk` no `.vtu` nor `.pvd`; the records name the trajectory.
#[test]
fn one_trajectory_alone() {
    let dir = scratch("alone");
    let sim = run(&text(2, "\"xyz\""), &dir);
    let names: Vec<&str> = sim
        .space_records()
        .snapshots
        .iter()
        .map(|(_, n)| n.as_str())
        .collect();
    assert_eq!(names, ["snapshots.xyz"; 4]);
    assert!(!dir.join("snapshots.pvd").exists());
    assert!(!dir.join("snapshot_000000.vtu").exists());
    assert!(!dir.join("snapshots.lammpstrj").exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// A run stopped at a check-point, with bytes written after it (as a run killed after its
/// check-point writes frames the check-point does not know of), then resumed: the same
/// trajectories, byte for byte, as a run that went through (both check-pointing every
/// sample); resumed into another directory, the trajectories there hold the frames from the
/// check-point on; a trajectory cut shorter than the check-point says is refused.
#[test]
fn resumed_runs_continue_the_trajectories_exactly() {
    let text = text(3, "[\"lammps-dump\", \"xyz\", \"vtk\"]");
    let (whole, parts) = (scratch("whole"), scratch("parts"));
    let mut run = Simulation::from_toml(&text, "t.toml".as_ref()).unwrap();
    run.set_checkpoints(&whole, Some(1));
    run.set_output_dir(&whole);
    run.run(&mut (), None).unwrap();
    run.write(&whole).unwrap();
    let mut first = Simulation::from_toml(&text, "t.toml".as_ref()).unwrap();
    first.set_checkpoints(&parts, Some(1));
    first.set_output_dir(&parts);
    first.run(&mut (), Some(4)).unwrap();
    for name in ["snapshots.xyz", "snapshots.lammpstrj"] {
        let mut f = std::fs::OpenOptions::new()
            .append(true)
            .open(parts.join(name))
            .unwrap();
        std::io::Write::write_all(&mut f, b"40\nhalf a frame\n").unwrap();
    }
    let mut rest = Simulation::resume(&parts).unwrap();
    rest.set_output_dir(&parts);
    rest.run(&mut (), None).unwrap();
    rest.write(&parts).unwrap();
    for file in [
        "snapshots.xyz",
        "snapshots.lammpstrj",
        "snapshot_000006.vtu",
        "snapshots.pvd",
    ] {
        let (a, b) = (whole.join(file), parts.join(file));
        assert!(
            std::fs::read(a).unwrap() == std::fs::read(b).unwrap(),
            "{file}"
        );
    }
    // Resumed into another directory: the trajectories there start at the check-point,
    // the bytes of the run that went through from the check-point's length on.
    let (elsewhere, before) = (scratch("elsewhere"), scratch("before"));
    let mut first = Simulation::from_toml(&text, "t.toml".as_ref()).unwrap();
    first.set_checkpoints(&before, Some(1));
    first.set_output_dir(&before);
    first.run(&mut (), Some(4)).unwrap();
    let mut rest = Simulation::resume(&before).unwrap();
    rest.set_output_dir(&elsewhere);
    rest.run(&mut (), None).unwrap();
    for name in ["snapshots.xyz", "snapshots.lammpstrj"] {
        let (part, all) = (
            std::fs::read(before.join(name)).unwrap(),
            std::fs::read(whole.join(name)).unwrap(),
        );
        assert!(
            std::fs::read(elsewhere.join(name)).unwrap() == all[part.len()..],
            "{name}"
        );
    }
    // Cut the trajectory below the check-point's length: refused, naming the key.
    let mut first = Simulation::from_toml(&text, "t.toml".as_ref()).unwrap();
    first.set_checkpoints(&parts, Some(1));
    first.set_output_dir(&parts);
    first.run(&mut (), Some(4)).unwrap();
    std::fs::write(parts.join("snapshots.xyz"), "").unwrap();
    let mut rest = Simulation::resume(&parts).unwrap();
    rest.set_output_dir(&parts);
    let e = rest.run(&mut (), None).unwrap_err();
    assert!(
        e.is_input()
            && e.to_string().starts_with("output.snapshots: ")
            && e.to_string().contains("snapshots.xyz"),
        "{e}"
    );
    for dir in [whole, parts, elsewhere, before] {
        std::fs::remove_dir_all(dir).ok();
    }
}

/// One format is written back as a plain string (the `parameters` of summary.json and the
/// check-points of existing runs keep their bytes), several as a list; the default is
/// `"vtk"`.
#[test]
fn the_format_key_reads_a_name_or_a_list() {
    let parameters = |format: &str| {
        let d = RunDescription::from_toml(&text(2, format), "t".as_ref()).unwrap();
        let json = serde_json::to_value(&d).unwrap();
        json["output"]["snapshots"]["format"].clone()
    };
    assert_eq!(parameters("\"vtk\""), serde_json::json!("vtk"));
    assert_eq!(parameters("[\"xyz\"]"), serde_json::json!("xyz"));
    assert_eq!(
        parameters("[\"xyz\", \"vtk\"]"),
        serde_json::json!(["xyz", "vtk"])
    );
    let default = text(2, "\"vtk\"").replace(", format = \"vtk\"", "");
    let d = RunDescription::from_toml(&default, "t".as_ref()).unwrap();
    assert_eq!(
        serde_json::to_value(&d).unwrap()["output"]["snapshots"],
        serde_json::json!({"every": 2, "format": "vtk"})
    );
    // And back: the TOML of the description reads as the same `[output]`.
    let d =
        RunDescription::from_toml(&text(2, "[\"lammps-dump\", \"vtk\"]"), "t".as_ref()).unwrap();
    let again = RunDescription::from_toml(&toml::to_string(&d).unwrap(), "t".as_ref()).unwrap();
    assert_eq!(again.output, d.output);
}

#[test]
fn bad_formats_are_refused_naming_the_key_and_the_names() {
    for (format, says) in [
        (
            "\"pdb\"",
            "`pdb` is not a snapshot format; allowed: vtk, lammps-dump, xyz, h5md",
        ),
        ("[\"vtk\", \"pdb\"]", "`pdb` is not a snapshot format"),
        ("[]", "an empty list"),
        ("[\"xyz\", \"vtk\", \"xyz\"]", "`xyz` given twice"),
        (
            "3",
            "a snapshot format (vtk, lammps-dump, xyz, h5md) or a list of them",
        ),
    ] {
        let e = RunDescription::from_toml(&text(2, format), "t".as_ref()).unwrap_err();
        let message = e.to_string();
        assert!(
            matches!(e, Error::Input { .. })
                && message.starts_with("output.snapshots.format: ")
                && message.contains(says),
            "{format}: {message}"
        );
    }
    // Without the feature `h5md` its format is refused by validation, saying why.
    if cfg!(not(feature = "h5md")) {
        let e =
            sim::validate(&RunDescription::from_toml(&text(2, "\"h5md\""), "t".as_ref()).unwrap())
                .unwrap_err()
                .to_string();
        assert!(
            e.starts_with("output.snapshots.format: ") && e.contains("without H5MD"),
            "{e}"
        );
    }
}

/// `format = "h5md"` (the feature `h5md`): `snapshots.h5md` holds a frame per snapshot, the
/// particles of the `.vtu` of the same sample bit for bit (oracle: the `.vtu`, the state),
/// with the observables `temperature` and `energy_lost` equal to `timeseries` at those
/// samples (T: the same sum, 1e-14 relative for its order); a run resumed from a check-point
/// after writing a frame the check-point does not know of ends with the same frames as one
/// that went through.
#[cfg(feature = "h5md")]
#[test]
fn h5md_trajectories_hold_the_frames_and_resume() {
    let text = text(2, "[\"vtk\", \"h5md\"]");
    let dir = scratch("h5md");
    // Check-pointed at every sample as the stopped run below is (a check-point brings
    // the event-driven engine's particles to the present: the same run bit for bit).
    let mut sim = Simulation::from_toml(&text, "t.toml".as_ref()).unwrap();
    sim.set_checkpoints(&dir, Some(1));
    sim.set_output_dir(&dir);
    sim.run(&mut (), None).unwrap();
    let path = dir.join("snapshots.h5md");
    let records = &sim.space_records().snapshots;
    assert_eq!(records.len(), 4);
    for (frame, (time, name)) in records.iter().enumerate() {
        let vtu = particles::read(&dir.join(name), Format::Vtk, 2, -1).unwrap();
        let h5 = particles::read(&path, Format::H5md, 2, frame as i64).unwrap();
        assert_eq!(h5.time, Some(*time));
        assert_eq!(
            h5,
            particles::Configuration {
                time: Some(*time),
                ..vtu
            }
        );
    }
    assert!(particles::read(&path, Format::H5md, 2, 4).is_err());
    let file = hdf5::File::open(&path).unwrap();
    let temperature: Vec<f64> = file
        .dataset("observables/temperature/value")
        .unwrap()
        .read_raw()
        .unwrap();
    let lost: Vec<f64> = file
        .dataset("observables/energy_lost/value")
        .unwrap()
        .read_raw()
        .unwrap();
    let samples = sim.samples();
    for (k, sample) in [0, 2, 4, 6].iter().enumerate() {
        let s = &samples[*sample];
        assert!((temperature[k] / s.temperature - 1.0).abs() < 1e-14, "{k}");
        assert_eq!(lost[k], s.energy_lost, "{k}");
    }
    drop(file);
    // Stopped at a check-point after 4 samples (snapshots 0 and 2 written, and 4 written
    // by a run killed after its check-point of sample 3), resumed: the frames of the run
    // that went through.
    let parts = scratch("h5md-parts");
    let mut first = Simulation::from_toml(&text, "t.toml".as_ref()).unwrap();
    first.set_checkpoints(&parts, Some(1));
    first.set_output_dir(&parts);
    first.run(&mut (), Some(4)).unwrap();
    let mut ahead = Simulation::resume(&parts).unwrap();
    ahead.set_output_dir(&parts);
    ahead.set_checkpoints(&scratch("h5md-nowhere"), Some(1000));
    ahead.run(&mut (), Some(6)).unwrap();
    let mut rest = Simulation::resume(&parts).unwrap();
    rest.set_output_dir(&parts);
    rest.run(&mut (), None).unwrap();
    for frame in 0..4 {
        let a = particles::read(&path, Format::H5md, 2, frame).unwrap();
        let b = particles::read(&parts.join("snapshots.h5md"), Format::H5md, 2, frame).unwrap();
        assert_eq!(a, b, "frame {frame}");
    }
    assert!(particles::read(&parts.join("snapshots.h5md"), Format::H5md, 2, 4).is_err());
    for d in [dir, parts] {
        std::fs::remove_dir_all(d).ok();
    }
}
