//! LAMMPS data files: haff's round trip (bit for bit but the masses, which a data file holds
//! as densities: within one ulp, the oracle the mass itself), LAMMPS' mass formula, and bad
//! files refused naming the line and field. What LAMMPS itself writes and reads:
//! crates/sim/tests/lammps_data.rs.

use super::super::tests::{sample, scratch};
use super::super::{read, write, Format};
use super::{density, mass};

/// The distance in ulps of two positive floats.
fn ulps(a: f64, b: f64) -> u64 {
    a.to_bits().abs_diff(b.to_bits())
}

#[test]
fn a_data_file_reads_back_what_haff_wrote() {
    let dir = scratch("lammps-data");
    assert_eq!(
        Format::parse("format", "lammps-data").unwrap(),
        Format::LammpsData
    );
    for dimension in [2, 3] {
        let original = sample(dimension, 7, 10 + dimension as u64);
        let path = dir.join(format!("{dimension}d.data"));
        write(&path, Format::LammpsData, &original).unwrap();
        let back = read(&path, Format::LammpsData, dimension, -1).unwrap();
        let (m0, m1) = (
            original.masses.clone().unwrap(),
            back.masses.clone().unwrap(),
        );
        let exact = m0.iter().zip(&m1).filter(|(a, b)| a == b).count();
        assert!(m0.iter().zip(&m1).all(|(a, b)| ulps(*a, *b) <= 1));
        // Most densities have a product that is the mass itself.
        assert!(exact * 10 >= m0.len() * 7, "{exact} of {}", m0.len());
        assert_eq!(
            super::super::Configuration {
                masses: original.masses.clone(),
                ..back.clone()
            },
            original,
            "{dimension}D"
        );
        back.check(&path, false).unwrap();
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Oracle: the sphere's volume 4 pi r^3 / 3 in closed form (to rounding), and the
/// writer's density turned back by LAMMPS' formula.
#[test]
fn the_mass_is_the_density_times_the_volume_of_the_sphere() {
    let v = mass(1.0, 1.0);
    assert!((v - std::f64::consts::PI / 6.0).abs() < 1e-15);
    assert_eq!(mass(0.0, 2.5), 2.5, "a point particle: density = mass");
    for (d, m) in [(1.2, 2.2619467105846507), (0.8, 0.3), (1e-3, 7e-9)] {
        assert!(ulps(mass(d, density(d, m)), m) <= 1);
    }
}

#[test]
fn bad_data_files_are_refused_naming_the_line_and_field() {
    let dir = scratch("lammps-data-bad");
    let head = "title\n\n2 atoms\n2 atom types\n0 4 xlo xhi\n0 4 ylo yhi\n0 4 zlo zhi\n\n";
    let cases: [(&str, String, &str); 11] = [
        ("a", "title\n\n0 4 xlo xhi\n".into(), "no `N atoms` line"),
        (
            "b",
            format!("{head}Atoms # atomic\n\n1 1 1 1 1\n2 1 2 2 2\n"),
            "line 9: atom style `atomic`; allowed: sphere",
        ),
        (
            "c",
            head.replace("0 4 zlo zhi\n", "0 4 zlo zhi\n0.5 0 0 xy xz yz\n"),
            "line 8: a tilted (triclinic) box",
        ),
        (
            "d",
            format!("{head}Atoms\n\n1 1 1 1 1 1 1\n2 3 1 1 2 2 2\n"),
            "line 12: column `atom-type`: `3`; allowed: 1 ..= 2",
        ),
        (
            "e",
            format!("{head}Atoms\n\n1 1 1 1 1 1 1\n1 1 1 1 3 3 3\n"),
            "line 12: column `atom-ID`: atom id 1 appears twice",
        ),
        (
            "f",
            format!("{head}Atoms\n\n1 1 1 1 1 1 1\n2 1 1 0 3 3 3\n"),
            "line 12: column `density`: 0 is not a finite number > 0",
        ),
        (
            "g",
            format!("{head}Atoms\n\n1 1 1 1 1 1 1\n"),
            "the Atoms section ends after 1 of 2 atoms",
        ),
        (
            "h",
            format!("{head}Atoms\n\n1 1 1 1 1 1 1\n2 1 1 1 3 abc 3\n"),
            "line 12: column `y`: `abc` is not a number",
        ),
        (
            "i",
            format!("{head}Atoms\n\n1 1 1 1 1 1 1 0 0\n2 1 1 1 3 3 3\n"),
            "line 11: 9 values; allowed: 7",
        ),
        (
            "j",
            format!(
                "{head}Atoms\n\n1 1 1 1 1 1 1\n2 1 1 1 3 3 3\n\nVelocities\n\n1 0 0 0 0 0 0\n\
                 3 0 0 0 0 0 0\n"
            ),
            "line 17: column `atom-ID`: atom id 3 is not in the Atoms section",
        ),
        (
            "k",
            format!("{head}Atoms\n\n1 1 1 1 1 1 1 0 0 x\n2 1 1 1 3 3 3\n"),
            "column `iz`: `x` is not an image flag",
        ),
    ];
    for (name, text, says) in cases {
        let path = dir.join(format!("{name}.data"));
        std::fs::write(&path, text).unwrap();
        let e = read(&path, Format::LammpsData, 3, -1)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with(&path.display().to_string()) && e.contains(says),
            "{name}: {e}"
        );
    }
    let path = dir.join("a.data");
    std::fs::write(
        &path,
        format!("{head}Atoms\n\n1 1 1 1 1 1 1\n2 1 1 1 3 3 3\n"),
    )
    .unwrap();
    let e = read(&path, Format::LammpsData, 3, 1)
        .unwrap_err()
        .to_string();
    assert!(e.contains("frame 1 of a file of 1 frames"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}
