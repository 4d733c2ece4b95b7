//! LAMMPS data files (`format = "lammps-data"`) against LAMMPS itself.
//!
//! The files in tests/data/lammps were written by LAMMPS "29 Sep 2021 - Update 2" (Debian 12)
//! from the inputs beside them: `write_data` of 50 spheres of two types (2D and 3D), then the
//! same file read back by LAMMPS' `read_data` and dumped with `%.17g`. Oracle: that dump,
//! what LAMMPS holds per atom after reading the file — the masses LAMMPS computes from the
//! diameter and density (in 2D too: the volume of a sphere), positions, velocities, spins,
//! types — read by haff's `lammps-dump` reader; haff's `lammps-data` reader must give the
//! same bits. And, where `lmp` is on the PATH, LAMMPS reads the data files haff writes.

use sim::particles::{self, Configuration, Format};
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/lammps")
        .join(name)
}

#[test]
fn lammps_written_data_files_read_as_lammps_reads_them() {
    for (dimension, lo) in [(2, [-5.0, 0.0]), (3, [-5.0, 0.0])] {
        let path = data(&format!("sphere{dimension}d.data"));
        let mine = particles::read(&path, Format::LammpsData, dimension, -1).unwrap();
        let dump = data(&format!("sphere{dimension}d.dump"));
        let lammps = particles::read(&dump, Format::LammpsDump, dimension, -1).unwrap();
        assert_eq!(mine.len(), 50);
        assert_eq!(mine, lammps, "{dimension}D");
        // The file's atoms are out of id order and its box starts at x = -5: the first
        // atom by id is the dump's first line, shifted.
        let first = std::fs::read_to_string(&dump).unwrap();
        let line: Vec<f64> = first
            .lines()
            .nth(9)
            .unwrap()
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        assert_eq!(line[0], 1.0);
        assert_eq!(mine.positions[0][0], line[4] - lo[0]);
        assert_eq!(mine.masses.as_ref().unwrap()[0], line[2]);
        // Two types of diameters 1.2 and 0.8 and densities 2.5 and 0.7.
        let m = mine.masses.as_ref().unwrap();
        for (i, s) in mine.species.as_ref().unwrap().iter().enumerate() {
            let (d, rho) = [(1.2, 2.5), (0.8, 0.7)][*s];
            assert_eq!(mine.diameters.as_ref().unwrap()[i], d);
            let sphere = rho * std::f64::consts::PI / 6.0 * d * d * d;
            assert!((m[i] - sphere).abs() < 1e-15 * sphere, "{} {sphere}", m[i]);
        }
        mine.check(&path, false).unwrap();
    }
}

/// A configuration with every field and atoms of three types (no overlaps).
fn sample(dimension: usize) -> Configuration {
    let n_side = 4usize;
    let n = n_side.pow(dimension as u32);
    let positions = (0..n)
        .map(|i| {
            let mut p = [0.0; 3];
            let mut m = i;
            for x in p.iter_mut().take(dimension) {
                *x = 2.0 * (m % n_side) as f64 + 0.5 + 0.01 * (i as f64).sqrt();
                m /= n_side;
            }
            p
        })
        .collect();
    let spin = |i: usize| {
        let w = 0.1 * i as f64 - 1.0 / 3.0;
        if dimension == 2 {
            [0.0, 0.0, w]
        } else {
            [w, -w / 7.0, 1e-7 * w]
        }
    };
    Configuration {
        dimension,
        sides: vec![2.0 * n_side as f64; dimension],
        positions,
        velocities: Some(
            (0..n)
                .map(|i| {
                    let v = [(i as f64).sin(), (i as f64).cos() / 3.0, 1e-9 * i as f64];
                    if dimension == 2 {
                        [v[0], v[1], 0.0]
                    } else {
                        v
                    }
                })
                .collect(),
        ),
        diameters: Some((0..n).map(|i| 0.9 + 0.003 * i as f64).collect()),
        masses: Some((0..n).map(|i| 1.0 / (1.0 + i as f64)).collect()),
        species: Some((0..n).map(|i| i % 3).collect()),
        spins: Some((0..n).map(spin).collect()),
        time: None,
    }
}

/// Where `lmp` runs: haff writes a data file, LAMMPS `read_data`s it and dumps every atom
/// (`%.17g`). Oracle: the configuration haff wrote, bit for bit, and the masses haff's own
/// reader computes from the file (LAMMPS' formula). Skipped, saying so, without `lmp`.
#[test]
fn lammps_reads_the_data_files_haff_writes() {
    let found = std::process::Command::new("lmp")
        .arg("-h")
        .stdout(std::process::Stdio::null())
        .status()
        .is_ok();
    if !found {
        eprintln!("skipped: no `lmp` on the PATH (apt-get install lammps)");
        return;
    }
    let dir = std::env::temp_dir().join(format!("haff-lammps-data-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for dimension in [2, 3] {
        let original = sample(dimension);
        let file = dir.join(format!("haff{dimension}d.data"));
        particles::write(&file, Format::LammpsData, &original).unwrap();
        let input = format!(
            "units lj\ndimension {dimension}\nboundary p p p\natom_style sphere\n\
             pair_style zero 1.0\nread_data {}\npair_coeff * *\n\
             write_dump all custom {} id type mass radius x y z vx vy vz omegax omegay \
             omegaz modify sort id format float %.17g\n",
            file.display(),
            dir.join("out.dump").display()
        );
        let script = dir.join("in.lmp");
        std::fs::write(&script, input).unwrap();
        let out = std::process::Command::new("lmp")
            .args([
                "-in",
                script.to_str().unwrap(),
                "-log",
                "none",
                "-screen",
                "none",
            ])
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "lmp: {}",
            String::from_utf8_lossy(&out.stdout)
        );
        let lammps =
            particles::read(&dir.join("out.dump"), Format::LammpsDump, dimension, -1).unwrap();
        let mine = particles::read(&file, Format::LammpsData, dimension, -1).unwrap();
        assert_eq!(
            lammps, mine,
            "{dimension}D: LAMMPS and haff read the file alike"
        );
        let masses = original.masses.clone();
        assert_eq!(
            Configuration {
                masses,
                ..lammps.clone()
            },
            original
        );
        for (a, b) in original.masses.unwrap().iter().zip(lammps.masses.unwrap()) {
            assert!(a.to_bits().abs_diff(b.to_bits()) <= 1, "{a} {b}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
