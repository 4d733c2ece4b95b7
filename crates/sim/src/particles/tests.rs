//! Particle files: round trips through every format (bit for bit: numbers are written in
//! the shortest form that reads back to the same f64), the checks against a brute-force
//! oracle, and bad files refused naming the line and field.

use super::*;
use rand::{Rng, SeedableRng};

/// `n` non-overlapping spheres in a box (placed on a jittered lattice), with every
/// optional column.
pub(super) fn sample(dimension: usize, n_side: usize, seed: u64) -> Configuration {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let spacing = 1.7;
    let sides = vec![spacing * n_side as f64; dimension];
    let n = n_side.pow(dimension as u32);
    let mut positions = Vec::with_capacity(n);
    for m in 0..n {
        let mut p = [0.0; 3];
        let mut m = m;
        for slot in p.iter_mut().take(dimension) {
            *slot = spacing * ((m % n_side) as f64 + 0.5) + rng.random_range(-0.3..0.3);
            m /= n_side;
        }
        positions.push(p);
    }
    let vector = |rng: &mut rand::rngs::StdRng, d: usize| {
        let mut v = [0.0; 3];
        for x in v.iter_mut().take(d) {
            *x = rng.random_range(-1.0..1.0) * 1e3f64.powf(rng.random_range(-2.0..1.0));
        }
        v
    };
    Configuration {
        dimension,
        positions,
        velocities: Some((0..n).map(|_| vector(&mut rng, dimension)).collect()),
        diameters: Some((0..n).map(|_| rng.random_range(0.8..1.0)).collect()),
        masses: Some((0..n).map(|_| rng.random_range(0.5..2.0)).collect()),
        species: Some((0..n).map(|i| i % 3).collect()),
        spins: Some(
            (0..n)
                .map(|_| {
                    let mut w = vector(&mut rng, 3);
                    if dimension == 2 {
                        w[0] = 0.0;
                        w[1] = 0.0;
                    }
                    w
                })
                .collect(),
        ),
        sides,
        time: None,
    }
}

pub(super) fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("haff-particles-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn every_format_reads_back_what_it_wrote_bit_for_bit() {
    let dir = scratch("round");
    for dimension in [2, 3] {
        let original = sample(dimension, 7, dimension as u64);
        original.check(Path::new("sample"), false).unwrap();
        for (name, format) in [
            ("csv", Format::Csv),
            ("lammps-dump", Format::LammpsDump),
            ("xyz", Format::Xyz),
            // Binary (base64) f64 arrays: exact; the diameter goes through the radius,
            // d / 2 * 2, exact too.
            ("vtk", Format::Vtk),
        ] {
            assert_eq!(Format::parse("format", name).unwrap(), format);
            let path = dir.join(format!("{dimension}d.{name}"));
            write(&path, format, &original).unwrap();
            let back = read(&path, format, dimension, -1).unwrap();
            assert_eq!(back, original, "{name}, {dimension}D");
            back.check(&path, false).unwrap();
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Oracle: every pair tested (minimum image), against the cell list, on dense random
/// configurations (many overlaps) and on boxes narrower than three cells.
#[test]
fn the_first_overlap_is_the_brute_force_one() {
    let brute = |c: &Configuration| {
        for i in 0..c.len() {
            for j in i + 1..c.len() {
                let mut r2 = 0.0;
                for k in 0..c.dimension {
                    let l = c.sides[k];
                    let x = c.positions[j][k] - c.positions[i][k];
                    let x = x - l * (x / l).round();
                    r2 += x * x;
                }
                let contact = 0.5 * (c.diameter(i) + c.diameter(j));
                if r2 < contact * contact {
                    return Some((i, j, contact - r2.sqrt()));
                }
            }
        }
        None
    };
    let mut rng = rand::rngs::StdRng::seed_from_u64(9);
    for trial in 0..200 {
        let dimension = 1 + trial % 3;
        let n = rng.random_range(2..60);
        let sides: Vec<f64> = (0..dimension)
            .map(|_| rng.random_range(1.5..12.0))
            .collect();
        let positions = (0..n)
            .map(|_| {
                let mut p = [0.0; 3];
                for k in 0..dimension {
                    p[k] = rng.random_range(0.0..sides[k]);
                }
                p
            })
            .collect();
        let diameters = Some((0..n).map(|_| rng.random_range(0.05..0.6)).collect());
        let c = Configuration {
            dimension,
            sides,
            positions,
            velocities: None,
            diameters,
            masses: None,
            species: None,
            spins: None,
            time: None,
        };
        let (mine, oracle) = (first_overlap(&c), brute(&c));
        assert_eq!(
            mine.map(|m| (m.0, m.1)),
            oracle.map(|o| (o.0, o.1)),
            "trial {trial}"
        );
        if let (Some(m), Some(o)) = (mine, oracle) {
            assert_eq!(m.2, o.2);
        }
    }
}

#[test]
fn bad_particles_are_refused_naming_the_record_and_field() {
    let path = Path::new("gas.csv");
    let says = |c: &Configuration, at: &str, what: &str| {
        let e = c.check(path, false).unwrap_err().to_string();
        assert!(
            e.starts_with("gas.csv: ") && e.contains(at) && e.contains(what),
            "{e}"
        );
    };
    let good = sample(3, 4, 1);
    let mut c = good.clone();
    c.positions[5] = c.positions[9];
    says(&c, "records 5 and 9", "overlap");
    let mut c = good.clone();
    c.positions[3][1] = c.sides[1];
    says(&c, "record 3", "position y");
    let mut c = good.clone();
    c.velocities.as_mut().unwrap()[7][2] = f64::NAN;
    says(&c, "record 7", "velocity");
    let mut c = good.clone();
    c.masses.as_mut().unwrap()[2] = 0.0;
    says(&c, "record 2", "mass");
    let mut c = good.clone();
    c.diameters.as_mut().unwrap().pop();
    says(&c, "diameters", "63 values for 64 particles");
    let mut c = good;
    c.sides[0] = f64::INFINITY;
    says(&c, "box", "side 0");
}

#[test]
fn bad_files_are_refused_naming_the_line_and_column() {
    let dir = scratch("bad");
    let cases: [(&str, Format, &str, &str); 9] = [
        ("a.csv", Format::Csv, "x,y,z\n0,0,0\n", "line 1"),
        (
            "b.csv",
            Format::Csv,
            "# box = 4 4 4\nx,y,z,vq\n",
            "column `vq`",
        ),
        (
            "c.csv",
            Format::Csv,
            "# box = 4 4 4\nx,y\n",
            "column `z` is missing",
        ),
        (
            "d.csv",
            Format::Csv,
            "# box = 4 4 4\nx,y,z,vx\n",
            "velocity columns",
        ),
        (
            "e.csv",
            Format::Csv,
            "# box = 4 4 4\nx,y,z\n1,2,abc\n",
            "line 3: column `z`: `abc`",
        ),
        ("f.dump", Format::LammpsDump, "hello\n", "not a LAMMPS dump"),
        (
            "g.dump",
            Format::LammpsDump,
            "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n0 4\n0 4\n\
             0 4\nITEM: ATOMS id x y z\n1 1 1 1\n1 2 2 2\n",
            "atom id 1 appears twice",
        ),
        (
            "h.xyz",
            Format::Xyz,
            "2\nProperties=pos:R:3\n0 0 0\n1 1 1\n",
            "Lattice",
        ),
        (
            "i.xyz",
            Format::Xyz,
            "2\nLattice=\"4 0 0 0 4 0 0 0 4\" Properties=pos:R:3\n0 0 0\n",
            "line 4",
        ),
    ];
    for (name, format, text, says) in cases {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let e = read(&path, format, 3, -1).unwrap_err().to_string();
        assert!(e.contains(name) && e.contains(says), "{name}: {e}");
    }
    let e = read(&dir.join("g.dump"), Format::LammpsDump, 3, 1)
        .unwrap_err()
        .to_string();
    assert!(e.contains("frame 1 of a file of 1 frames"), "{e}");
    let e = Format::parse("system.initial.format", "pdb")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("system.initial.format") && e.contains("csv, lammps-dump, xyz, vtk"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A dump as LAMMPS writes it (atoms out of order, a box from -5, unwrapped and scaled
/// coordinates, extra columns): particles by id, shifted into [0, L).
#[test]
fn lammps_dumps_are_read_as_lammps_writes_them() {
    let dir = scratch("lammps");
    let path = dir.join("dump.txt");
    let text = "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n\
                -5 5\n-5 5\n-5 5\nITEM: ATOMS id type xu yu zu vx vy vz radius c_ke\n\
                2 2 6.0 0 0 1 2 3 0.5 7\n1 1 -4.0 -5 4.5 -1 -2 -3 0.25 8\n\
                ITEM: TIMESTEP\n200\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n\
                0 10\n0 10\n0 10\nITEM: ATOMS id xs ys zs\n1 0.5 0.25 0.125\n2 0 0 0\n";
    std::fs::write(&path, text).unwrap();
    let first = read(&path, Format::LammpsDump, 3, 0).unwrap();
    assert_eq!(first.sides, [10.0; 3]);
    assert_eq!(first.positions, [[1.0, 0.0, 9.5], [1.0, 5.0, 5.0]]);
    assert_eq!(
        first.velocities.unwrap(),
        [[-1.0, -2.0, -3.0], [1.0, 2.0, 3.0]]
    );
    assert_eq!(first.diameters.unwrap(), [0.5, 1.0]);
    assert_eq!(first.species.unwrap(), [0, 1]);
    let last = read(&path, Format::LammpsDump, 3, -1).unwrap();
    assert_eq!(last.positions, [[5.0, 2.5, 1.25], [0.0; 3]]);
    assert!(last.velocities.is_none());
    std::fs::remove_dir_all(&dir).ok();
}

/// Without the feature `h5md`, H5MD files are refused naming the file and saying how to
/// build haff with it (the message is tested in both builds; the refusal in the build
/// without).
#[test]
fn h5md_without_the_feature_says_how_to_build_it() {
    let path = Path::new("gas.h5");
    let e = without_h5md(path).to_string();
    assert!(
        e.starts_with("gas.h5: format `h5md`: ")
            && e.contains("--features h5md")
            && e.contains("libhdf5-dev"),
        "{e}"
    );
    assert_eq!(Format::parse("format", "h5md").unwrap(), Format::H5md);
    if cfg!(not(feature = "h5md")) {
        let c = sample(3, 3, 1);
        assert_eq!(write(path, Format::H5md, &c).unwrap_err().to_string(), e);
        assert_eq!(read(path, Format::H5md, 3, -1).unwrap_err().to_string(), e);
    }
}

/// A `.vtu` holds its box as field data (haff writes it); without it (a `.vtu` from
/// elsewhere, or haff's before the box was added) the sides must be given, and given sides
/// must agree with the file's. Oracle: the configuration written.
#[test]
fn a_vtu_without_its_box_needs_the_sides() {
    let dir = scratch("vtu");
    let original = sample(3, 3, 4);
    let path = dir.join("a.vtu");
    write(&path, Format::Vtk, &original).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("<FieldData><DataArray type=\"Float64\" Name=\"box\""));
    let (start, end) = (
        text.find("<FieldData>").unwrap(),
        text.find("</FieldData>").unwrap() + "</FieldData>".len(),
    );
    let bare = dir.join("bare.vtu");
    std::fs::write(&bare, format!("{}{}", &text[..start], &text[end..])).unwrap();
    let e = read(&bare, Format::Vtk, 3, -1).unwrap_err().to_string();
    assert!(
        e.starts_with(&bare.display().to_string()) && e.contains("box") && e.contains("sides"),
        "{e}"
    );
    let back = read_with_box(&bare, Format::Vtk, 3, -1, Some(&original.sides)).unwrap();
    assert_eq!(back, original);
    let e = read_with_box(&path, Format::Vtk, 3, -1, Some(&[1.0, 2.0, 3.0]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("box") && e.contains("differs"), "{e}");
    let e = read(&path, Format::Vtk, 3, 1).unwrap_err().to_string();
    assert!(e.contains("frame 1 of a file of 1 frames"), "{e}");
    std::fs::write(&bare, "<VTKFile").unwrap();
    let e = read(&bare, Format::Vtk, 3, -1).unwrap_err().to_string();
    assert!(e.contains("not a VTK XML file"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}
