//! The observers of space (`[output]`): files and their columns, VTK files read back by a VTK
//! reader (vtkio's parser), the normalization of the modes in an elastic gas, and the shear
//! instability: a box below L_c stays homogeneous, one above it grows a shear mode at the
//! rate of Navier–Stokes hydrodynamics.

use gas::theory::HcsTransport;
use sim::{Error, Simulation};
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("haff-space-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run_2d(
    particles: usize,
    phi: f64,
    eps: f64,
    cpp: f64,
    samples: usize,
    output: &str,
    dir: &Path,
) -> Simulation {
    let text = format!(
        "[system]\ndimension = 2\nparticles = {particles}\npacking_fraction = {phi}\nseed = 3\n\
         [collision]\nlaw = \"constant\"\nrestitution = {eps}\n\
         [run]\ncollisions_per_particle = {cpp}\nsamples = {samples}\nspacing = \"linear\"\n\
         [output]\n{output}\n"
    );
    let mut run = Simulation::from_toml(&text, "test.toml".as_ref()).unwrap();
    run.set_output_dir(dir);
    run.run(&mut (), None).unwrap();
    run.write(dir).unwrap();
    run
}

/// modes.csv rows: (time, cpp, k, transverse, longitudinal, density).
fn modes(dir: &Path) -> Vec<[f64; 6]> {
    let text = std::fs::read_to_string(dir.join("modes.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "time,collisions_per_particle,k,transverse_energy,longitudinal_energy,density_power"
    );
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2], v[3], v[4], v[5]]
        })
        .collect()
}

#[test]
fn output_files_and_vtk_read_back() {
    let dir = scratch("files");
    run_2d(
        2000,
        0.2,
        0.9,
        10.0,
        6,
        "modes = true\nstructure = true\nfields = { every = 2, grid = 16 }\n\
         snapshots = { every = 5, format = \"vtk\" }",
        &dir,
    );
    assert_eq!(modes(&dir).len(), 6 * 2); // shells |n|² = 1, 2 (3 is empty in 2D)
    let structure = std::fs::read_to_string(dir.join("structure.csv")).unwrap();
    assert!(structure.starts_with("time,collisions_per_particle,function,x,value\n"));
    assert!(structure.contains(",S,") && structure.contains(",g,"));
    for (pvd, files) in [("snapshots.pvd", 2), ("fields.pvd", 3)] {
        let text = std::fs::read_to_string(dir.join(pvd)).unwrap();
        assert_eq!(text.matches("<DataSet ").count(), files, "{pvd}");
    }
    let snapshot = vtkio::Vtk::import(dir.join("snapshot_000005.vtu")).unwrap();
    let vtkio::model::DataSet::UnstructuredGrid { pieces, .. } = snapshot.data else {
        panic!("not an unstructured grid")
    };
    let vtkio::model::Piece::Inline(piece) = &pieces[0] else {
        panic!("no inline piece")
    };
    assert_eq!(piece.num_points(), 2000);
    let names: Vec<&str> = piece.data.point.iter().map(|a| a.name()).collect();
    for name in ["radius", "mass", "velocity", "species", "collisions"] {
        assert!(names.contains(&name), "{names:?}");
    }
    let fields = vtkio::Vtk::import(dir.join("fields_000004.vti")).unwrap();
    assert!(matches!(
        fields.data,
        vtkio::model::DataSet::ImageData { .. }
    ));
    for sample in [0, 2, 4] {
        let png = dir.join(format!("fields_{sample:06}.png"));
        assert_eq!(png_size(&png), sim::maps::SIZE, "{}", png.display());
    }
    assert!(!dir.join("fields_000001.png").exists());
}

/// The pixel size of a PNG file, after decoding all of it.
fn png_size(path: &Path) -> (u32, u32) {
    let decoder = png::Decoder::new(std::fs::File::open(path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buffer = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buffer).unwrap();
    (info.width, info.height)
}

/// Field maps: the mid-plane of a 3D run, none in 1D.
#[test]
fn field_maps_in_3d_and_not_in_1d() {
    for (dimension, particles, png) in [(3, 2000, true), (1, 200, false)] {
        let dir = scratch(&format!("maps{dimension}"));
        let text = format!(
            "[system]\ndimension = {dimension}\nparticles = {particles}\n\
             packing_fraction = 0.1\nseed = 3\n\
             [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
             [run]\ncollisions_per_particle = 2\nsamples = 2\nspacing = \"linear\"\n\
             [output]\nfields = {{ every = 1, grid = 8 }}\n"
        );
        let mut run = Simulation::from_toml(&text, "t.toml".as_ref()).unwrap();
        run.set_output_dir(&dir);
        run.run(&mut (), None).unwrap();
        run.write(&dir).unwrap();
        assert!(dir.join("fields_000001.vti").exists());
        let path = dir.join("fields_000001.png");
        assert_eq!(path.exists(), png, "{dimension}D");
        if png {
            assert_eq!(png_size(&path), sim::maps::SIZE);
        }
    }
}

#[test]
fn homogeneous_dsmc_refuses_observers_of_space() {
    let text = "[system]\nparticles = 100\npacking_fraction = 0.05\n\
                [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
                [run]\nengine = \"dsmc\"\ncollisions_per_particle = 1\n[output]\nmodes = true\n";
    match Simulation::from_toml(text, "t.toml".as_ref()) {
        Err(Error::Input { key, .. }) => assert_eq!(key, "output.modes"),
        other => panic!("{:?}", other.err()),
    }
    let text = text
        .replace("engine = \"dsmc\"\n", "")
        .replace("modes = true", "fields = { every = 1, grid = 2 }");
    match Simulation::from_toml(&text, "t.toml".as_ref()) {
        Err(Error::Input { key, message }) => {
            assert_eq!(key, "output.fields.grid");
            assert!(message.contains("3 ..= 256"), "{message}");
        }
        other => panic!("{:?}", other.err()),
    }
}

/// Fields or snapshots without an output directory: the run is refused before it takes a
/// sample (an input error naming the key), and goes on unchanged once a directory is set.
#[test]
fn files_without_a_directory_are_refused_before_the_run() {
    let text = "[system]\ndimension = 2\nparticles = 200\npacking_fraction = 0.1\nseed = 2\n\
                [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
                [run]\ncollisions_per_particle = 2\nsamples = 3\n\
                [output]\nmodes = true\n";
    for (output, key) in [
        ("snapshots = { every = 1 }", "output.snapshots"),
        ("fields = { every = 2, grid = 4 }", "output.fields"),
    ] {
        let text = format!("{text}{output}\n");
        let mut run = Simulation::from_toml(&text, "t.toml".as_ref()).unwrap();
        assert_eq!(run.output_dir(), None);
        match run.run(&mut (), None) {
            Err(Error::Input { key: k, .. }) => assert_eq!(k, key),
            other => panic!("{other:?}"),
        }
        assert!(run.samples().is_empty() && run.space_records().modes.is_empty());
        let dir = scratch(key);
        run.set_output_dir(&dir);
        assert_eq!(run.output_dir(), Some(dir.as_path()));
        assert!(run.run(&mut (), None).unwrap().complete);
        assert_eq!(run.samples().len(), 3);
        assert_eq!(run.space_records().modes.len(), 3);
    }
}

/// An elastic gas (N = 400, phi = 0.1, L = 56 sigma): every mode averages 1. The samples are
/// 40 collisions per particle apart, longer than the decay time of the slowest mode
/// (1/(nu k²) ≈ 25 collisions per particle), so the 100 samples are nearly independent; each
/// normalized power of a shell with v wave vectors has relative s.d. 1/sqrt(v × components);
/// the tolerance is five standard errors of the mean over the shells |n|² = 1, 2, 4, 5.
#[test]
fn elastic_gas_modes_average_one() {
    let dir = scratch("elastic");
    run_2d(
        400,
        0.1,
        1.0,
        4000.0,
        101,
        "modes = true\nmode_shells = 5",
        &dir,
    );
    let rows = modes(&dir);
    let shells = 4;
    let samples = &rows[shells..]; // skip the initial state
    let n = (samples.len() / shells) as f64;
    for (column, name) in [(3, "transverse"), (4, "longitudinal"), (5, "density")] {
        let mean = samples.iter().map(|r| r[column]).sum::<f64>() / samples.len() as f64;
        // each row averages v = 2, 2, 2, 4 exponential powers (one component per vector)
        let error = [2.0, 2.0, 2.0, 4.0]
            .iter()
            .map(|v| 1.0 / v)
            .sum::<f64>()
            .sqrt()
            / shells as f64
            / n.sqrt();
        assert!(
            (mean - 1.0).abs() < 5.0 * error,
            "{name}: {mean} (error {error})"
        );
    }
}

/// The shear instability (2D, phi = 0.05, eps = 0.9, L_c = 126 sigma): a box of L_c / 2
/// keeps its lowest transverse mode near its stationary value 1/(1 − (k_c/k)²) = 4/3, while
/// a box of 4 L_c grows it as exp(2 s c / omega) with s/omega from hydrodynamics. The growth
/// is fitted from where the mode's energy has reached 4 (above the thermal noise that feeds
/// it, so the slope of ln E is the growth rate) to c = 60 (E stays below N/40, the onset of
/// the nonlinear regime); tolerance 15 % (the aim; several seeds and boxes are
/// measured in docs/structure.md).
#[test]
fn shear_mode_below_and_above_the_critical_length() {
    let (phi, eps) = (0.05, 0.9);
    let n = 4.0 * phi / PI;
    let theory = HcsTransport::new::<2>(n, 1.0, 1.0, 1.0, phi, eps);
    let lc = theory.critical_length();
    let particles = |l: f64| (n * l * l).round() as usize;

    let dir = scratch("below");
    run_2d(
        particles(0.5 * lc),
        phi,
        eps,
        200.0,
        101,
        "modes = true\nmode_shells = 1",
        &dir,
    );
    let rows = modes(&dir);
    let late: Vec<f64> = rows[rows.len() / 2..].iter().map(|r| r[3]).collect();
    let mean = late.iter().sum::<f64>() / late.len() as f64;
    assert!(mean < 3.0, "below L_c: transverse energy {mean}");

    let dir = scratch("above");
    let l = 4.0 * lc;
    let shells = "modes = true\nmode_shells = 1";
    run_2d(particles(l), phi, eps, 60.0, 61, shells, &dir);
    let rows = modes(&dir);
    let start = rows
        .iter()
        .position(|r| r[3] >= 4.0)
        .expect("the shear mode grows");
    let fit: Vec<(f64, f64)> = rows[start..].iter().map(|r| (r[1], r[3].ln())).collect();
    assert!(fit.len() >= 20, "fit over {} samples", fit.len());
    let last = rows.last().unwrap()[3];
    assert!(last < particles(l) as f64 / 40.0, "nonlinear: {last}");
    let (mx, my) = fit.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
    let (mx, my) = (mx / fit.len() as f64, my / fit.len() as f64);
    let slope = fit.iter().map(|(x, y)| (x - mx) * (y - my)).sum::<f64>()
        / fit.iter().map(|(x, _)| (x - mx).powi(2)).sum::<f64>();
    let expected = 2.0 * theory.transverse_growth_per_collision(2.0 * PI / l);
    assert!(
        (slope / expected - 1.0).abs() < 0.15,
        "above L_c: growth {slope} per collision vs theory {expected}"
    );
}

/// A run stopped and resumed from its check-point writes the same modes, structure,
/// field (VTK and PNG maps) and snapshot files, bit for bit, as one that ran through (both check-pointing every sample,
/// which synchronizes the event-driven engine at the same places).
#[test]
fn resumed_runs_write_the_same_files() {
    let text = "[system]\ndimension = 2\nparticles = 3000\npacking_fraction = 0.2\nseed = 5\n\
                [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
                [run]\ncollisions_per_particle = 20\nsamples = 6\nspacing = \"linear\"\n\
                [output]\nmodes = true\nstructure = true\nsnapshots = { every = 2 }\n\
                fields = { every = 2, grid = 16 }\n";
    let (whole, parts) = (scratch("whole"), scratch("parts"));
    let mut run = Simulation::from_toml(text, "t.toml".as_ref()).unwrap();
    run.set_checkpoints(&whole, Some(1));
    run.set_output_dir(&whole);
    run.run(&mut (), None).unwrap();
    run.write(&whole).unwrap();
    let mut first = Simulation::from_toml(text, "t.toml".as_ref()).unwrap();
    first.set_checkpoints(&parts, Some(1));
    first.set_output_dir(&parts);
    first.run(&mut (), Some(3)).unwrap();
    let mut rest = Simulation::resume(&parts).unwrap();
    rest.set_output_dir(&parts);
    rest.run(&mut (), None).unwrap();
    rest.write(&parts).unwrap();
    for file in [
        "modes.csv",
        "structure.csv",
        "snapshot_000004.vtu",
        "snapshots.pvd",
        "fields_000004.vti",
        "fields_000004.png",
        "fields.pvd",
    ] {
        let (a, b) = (whole.join(file), parts.join(file));
        assert!(
            std::fs::read(a).unwrap() == std::fs::read(b).unwrap(),
            "{file}"
        );
    }
}
