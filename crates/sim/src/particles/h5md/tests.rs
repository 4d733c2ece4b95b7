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
