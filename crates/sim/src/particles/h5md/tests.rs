//! H5MD: the round trip bit for bit (one frame and trajectories; oracle: the configuration
//! written), the file's structure read back through the HDF5 library against the H5MD 1.1
//! specification, and bad or damaged files refused naming the file and the object.

use super::super::tests::{sample, scratch};
use super::super::{read, write, Configuration, Format};
use super::Trajectory;

#[test]
fn one_frame_reads_back_bit_for_bit() {
    let dir = scratch("h5md");
    for dimension in [2, 3] {
        for timed in [None, Some(2.5)] {
            let original = Configuration {
                time: timed,
                ..sample(dimension, 7, dimension as u64)
            };
            let path = dir.join(format!("{dimension}d.h5"));
            write(&path, Format::H5md, &original).unwrap();
            let back = read(&path, Format::H5md, dimension, -1).unwrap();
            assert_eq!(back, original, "{dimension}D");
        }
        // A configuration with nothing but positions.
        let bare = Configuration {
            velocities: None,
            diameters: None,
            masses: None,
            species: None,
            spins: None,
            ..sample(dimension, 3, 5)
        };
        let path = dir.join("bare.h5");
        write(&path, Format::H5md, &bare).unwrap();
        assert_eq!(read(&path, Format::H5md, dimension, 0).unwrap(), bare);
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_trajectory_keeps_every_frame() {
    let dir = scratch("h5md-trajectory");
    let path = dir.join("t.h5");
    let frames: Vec<Configuration> = (0..4)
        .map(|k| {
            let mut c = sample(3, 4, 1);
            for v in c.velocities.as_mut().unwrap() {
                v[0] += k as f64;
            }
            c.time = Some(0.5 * k as f64);
            c
        })
        .collect();
    let mut t = Trajectory::create(&path).unwrap();
    for (k, c) in frames.iter().enumerate() {
        t.append(10 * k as u64, 0.5 * k as f64, c).unwrap();
        t.observable("temperature", 10 * k as u64, 0.5 * k as f64, k as f64)
            .unwrap();
    }
    // A frame of other particles is refused, naming the frame.
    let e = t.append(40, 2.0, &sample(3, 3, 1)).unwrap_err().to_string();
    assert!(
        e.contains("t.h5: frame 4: ") && e.contains("frame 0"),
        "{e}"
    );
    t.close().unwrap();
    for (k, c) in frames.iter().enumerate() {
        assert_eq!(&read(&path, Format::H5md, 3, k as i64).unwrap(), c);
    }
    assert_eq!(read(&path, Format::H5md, 3, -1).unwrap(), frames[3]);
    let e = read(&path, Format::H5md, 3, 4).unwrap_err().to_string();
    assert!(e.contains("frame 4 of a file of 4 frames"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Oracle: the H5MD 1.1 specification's layout, read with the HDF5 library directly.
#[test]
fn the_layout_is_the_specification_s() {
    let dir = scratch("h5md-layout");
    let path = dir.join("l.h5");
    let c = Configuration {
        time: Some(1.25),
        ..sample(2, 5, 3)
    };
    write(&path, Format::H5md, &c).unwrap();
    let f = hdf5::File::open(&path).unwrap();
    let version: Vec<i32> = f
        .group("h5md")
        .unwrap()
        .attr("version")
        .unwrap()
        .read_raw()
        .unwrap();
    assert_eq!(version, [1, 1]);
    let creator = f.group("h5md/creator").unwrap();
    let name: hdf5::types::VarLenUnicode = creator.attr("name").unwrap().read_scalar().unwrap();
    assert_eq!(name.as_str(), "haff");
    assert!(f.group("h5md/author").unwrap().attr("name").is_ok());
    let b = f.group("particles/all/box").unwrap();
    let d: i32 = b.attr("dimension").unwrap().read_scalar().unwrap();
    assert_eq!(d, 2);
    let boundary: Vec<hdf5::types::VarLenUnicode> = b.attr("boundary").unwrap().read_raw().unwrap();
    assert_eq!(
        boundary.iter().map(|s| s.as_str()).collect::<Vec<_>>(),
        ["periodic"; 2]
    );
    let edges: Vec<f64> = b.dataset("edges").unwrap().read_raw().unwrap();
    assert_eq!(edges, c.sides);
    let n = c.len();
    for (name, width) in [("position", 2), ("velocity", 2), ("angular_velocity", 3)] {
        let g = f.group(&format!("particles/all/{name}")).unwrap();
        assert_eq!(g.dataset("value").unwrap().shape(), [1, n, width], "{name}");
        let step: Vec<i64> = g.dataset("step").unwrap().read_raw().unwrap();
        let time: Vec<f64> = g.dataset("time").unwrap().read_raw().unwrap();
        assert_eq!((step, time), (vec![0], vec![1.25]));
    }
    let species: Vec<i32> = f
        .dataset("particles/all/species")
        .unwrap()
        .read_raw()
        .unwrap();
    assert_eq!(species.len(), n);
    let value: Vec<f64> = f
        .dataset("particles/all/position/value")
        .unwrap()
        .read_raw()
        .unwrap();
    assert_eq!(value[2..4], c.positions[1][..2]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_and_damaged_files_are_refused_naming_the_file() {
    let dir = scratch("h5md-bad");
    let path = dir.join("g.h5");
    write(&path, Format::H5md, &sample(3, 4, 2)).unwrap();
    let says = |p: &std::path::Path, dimension: usize, what: &str| {
        let e = read(p, Format::H5md, dimension, -1)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with(&p.display().to_string()) && e.contains(what) && !e.contains('\n'),
            "{e}"
        );
    };
    says(
        &path,
        2,
        "particles/all/box: dimension 3 in the file; the run asks for 2",
    );
    let text = dir.join("t.h5");
    std::fs::write(&text, "not hdf5").unwrap();
    says(&text, 3, "file: not an HDF5 file");
    // Truncated files (a cut anywhere) and flipped bytes: an error, never a panic.
    let bytes = std::fs::read(&path).unwrap();
    let cut = dir.join("cut.h5");
    for k in 1..16 {
        std::fs::write(&cut, &bytes[..bytes.len() * k / 16]).unwrap();
        assert!(read(&cut, Format::H5md, 3, -1).is_err(), "cut at {k}/16");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Frame `k` of a trajectory of the particles of `sample(3, 3, 1)`, moved: positions,
/// velocities and spins of another seed.
fn moved(k: u64, seed: u64) -> Configuration {
    let other = sample(3, 3, seed);
    Configuration {
        positions: other.positions,
        velocities: other.velocities,
        spins: other.spins,
        time: Some(0.25 * k as f64),
        ..sample(3, 3, 1)
    }
}

/// Appends frame `k` and the observables a run would write with it: `temperature` once,
/// `energy` twice, `late` only from frame `late`.
fn sample_frame(t: &mut Trajectory, k: u64, c: &Configuration, late: u64) {
    let time = 0.25 * k as f64;
    t.append(10 * k, time, c).unwrap();
    let v = c.velocities.as_ref().unwrap()[0][0];
    t.observable("temperature", 10 * k, time, v).unwrap();
    t.observable("energy", 10 * k, time, 2.0 * v).unwrap();
    t.observable("energy", 10 * k + 5, time + 0.125, 3.0 * v)
        .unwrap();
    if k >= late {
        t.observable("late", 10 * k, time, -v).unwrap();
    }
}

/// Every dataset of the file, as bits, by HDF5 path (oracle: the HDF5 library).
fn contents(path: &std::path::Path) -> Vec<(String, Vec<u64>)> {
    let f = hdf5::File::open(path).unwrap();
    let mut out = Vec::new();
    let mut series = vec![
        "particles/all/position".to_string(),
        "particles/all/velocity".into(),
        "particles/all/angular_velocity".into(),
    ];
    for name in f.group("observables").unwrap().member_names().unwrap() {
        series.push(format!("observables/{name}"));
    }
    for s in series {
        let steps: Vec<i64> = f.dataset(&format!("{s}/step")).unwrap().read_raw().unwrap();
        out.push((
            format!("{s}/step"),
            steps.iter().map(|&x| x as u64).collect(),
        ));
        for d in ["time", "value"] {
            let x: Vec<f64> = f.dataset(&format!("{s}/{d}")).unwrap().read_raw().unwrap();
            out.push((format!("{s}/{d}"), x.iter().map(|x| x.to_bits()).collect()));
        }
    }
    for d in ["mass", "diameter", "box/edges"] {
        let x: Vec<f64> = f
            .dataset(&format!("particles/all/{d}"))
            .unwrap()
            .read_raw()
            .unwrap();
        out.push((d.into(), x.iter().map(|x| x.to_bits()).collect()));
    }
    let species: Vec<i32> = f
        .dataset("particles/all/species")
        .unwrap()
        .read_raw()
        .unwrap();
    out.push((
        "species".into(),
        species.iter().map(|&s| s as u64).collect(),
    ));
    out
}

/// A run killed after 5 frames and resumed from its check-point at 3 writes the file a run
/// never killed writes. The killed file: the bytes on disk after the 5th frame while the
/// writer still holds it (a kill), and the file of a writer dropped without `close`.
#[test]
fn a_resumed_trajectory_equals_one_written_straight() {
    let dir = scratch("h5md-resume");
    let first: Vec<Configuration> = (0..5).map(|k| moved(k, 10 + k)).collect();
    let again: Vec<Configuration> = (3..5).map(|k| moved(k, 20 + k)).collect();
    let straight = dir.join("straight.h5");
    let mut t = Trajectory::create(&straight).unwrap();
    for (k, c) in first[..3].iter().chain(&again).enumerate() {
        sample_frame(&mut t, k as u64, c, 4);
    }
    t.close().unwrap();
    let expected = contents(&straight);
    let (killed, dropped) = (dir.join("killed.h5"), dir.join("dropped.h5"));
    let mut t = Trajectory::create(&dropped).unwrap();
    for (k, c) in first.iter().enumerate() {
        sample_frame(&mut t, k as u64, c, 3);
    }
    std::fs::copy(&dropped, &killed).unwrap();
    drop(t);
    for path in [&killed, &dropped] {
        // `late` began after the check-point: not listed, cut to nothing.
        let counts = [("temperature", 3), ("energy", 6)];
        let mut t = Trajectory::resume(path, &first[2], 3, &counts).unwrap();
        assert_eq!(read(path, Format::H5md, 3, -1).unwrap(), first[2]);
        for (k, c) in again.iter().enumerate() {
            sample_frame(&mut t, 3 + k as u64, c, 4);
        }
        t.close().unwrap();
        let back = contents(path);
        for ((name, a), (_, b)) in back.iter().zip(&expected) {
            assert_eq!(a, b, "{}: {name}", path.display());
        }
        assert_eq!(back, expected, "{}", path.display());
        for (k, c) in first[..3].iter().chain(&again).enumerate() {
            assert_eq!(&read(path, Format::H5md, 3, k as i64).unwrap(), c);
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// After every frame the file on disk is a whole H5MD file: its bytes, copied while the
/// writer holds it (what a kill leaves), read back to the frame just appended.
#[test]
fn a_trajectory_is_readable_after_every_append() {
    let dir = scratch("h5md-live");
    let (path, copy) = (dir.join("live.h5"), dir.join("copy.h5"));
    let mut t = Trajectory::create(&path).unwrap();
    for k in 0..4 {
        let c = moved(k, 30 + k);
        t.append(k, 0.25 * k as f64, &c).unwrap();
        std::fs::copy(&path, &copy).unwrap();
        assert_eq!(read(&copy, Format::H5md, 3, -1).unwrap(), c, "frame {k}");
        assert_eq!(read(&path, Format::H5md, 3, -1).unwrap(), c, "frame {k}");
        t.observable("temperature", k, 0.25 * k as f64, k as f64)
            .unwrap();
    }
    t.close().unwrap();
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn resume_refuses_a_file_it_cannot_continue() {
    let dir = scratch("h5md-refuse");
    let path = dir.join("r.h5");
    let c = moved(0, 40);
    let mut t = Trajectory::create(&path).unwrap();
    t.append(0, 0.0, &c).unwrap();
    t.append(1, 0.25, &c).unwrap();
    t.close().unwrap();
    let says = |p: &std::path::Path, c: &Configuration, frames: usize, what: &str| {
        let e = match Trajectory::resume(p, c, frames, &[]) {
            Ok(_) => panic!("{} resumed", p.display()),
            Err(e) => e.to_string(),
        };
        assert!(
            e.starts_with(&p.display().to_string()) && e.contains(what) && !e.contains('\n'),
            "{e}"
        );
    };
    says(
        &path,
        &sample(3, 2, 1),
        2,
        "particles/all/position: 27 particles in the file; the run has 8",
    );
    says(
        &path,
        &sample(2, 3, 1),
        2,
        "particles/all/box: dimension 3 in the file; the run asks for 2",
    );
    let heavier = Configuration {
        masses: Some(vec![2.0; c.len()]),
        ..c.clone()
    };
    says(&path, &heavier, 2, "particles/all: the box, species");
    says(&path, &c, 3, "frame 2 of a file of 2 frames");
    let text = dir.join("t.h5");
    std::fs::write(&text, "not hdf5").unwrap();
    says(&text, &c, 1, "file: not an HDF5 file");
    let other = dir.join("o.h5");
    hdf5::File::create(&other)
        .unwrap()
        .create_group("data")
        .unwrap();
    says(&other, &c, 1, "h5md: no group `h5md`");
    let e = Trajectory::resume(&other, &c, 0, &[("temperature", 2)])
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("h5md/creator: name \"\""), "{e}");
    says(&dir.join("none.h5"), &c, 1, "file: no such file");
    // A file cut anywhere (a kill during a write, a full disk): an error, never a panic.
    let bytes = std::fs::read(&path).unwrap();
    let cut = dir.join("cut.h5");
    for k in 1..16 {
        std::fs::write(&cut, &bytes[..bytes.len() * k / 16]).unwrap();
        assert!(
            Trajectory::resume(&cut, &c, 1, &[]).is_err(),
            "cut at {k}/16"
        );
    }
    // Nothing written yet: a new file, whatever was there.
    let t = Trajectory::resume(&text, &c, 0, &[("temperature", 0)]).unwrap();
    t.close().unwrap();
    assert!(hdf5::File::open(&text).unwrap().group("h5md").is_ok());
    // The same particles resume (the file is left as the check-point had it).
    Trajectory::resume(&path, &c, 1, &[])
        .unwrap()
        .close()
        .unwrap();
    assert_eq!(read(&path, Format::H5md, 3, -1).unwrap().time, Some(0.0));
    std::fs::remove_dir_all(&dir).ok();
}
