//! `haff run`: the outputs of every engine, check-points that continue bit for bit, and
//! bad run files refused before the run, naming the key.

mod common;

use common::{
    assert_rejected, assert_run_rejected, haff, number, parse_csv, read, run_full_and_chunked,
    run_ok,
};
use serde_json::Value;

/// `haff run`: the timeseries contract, the summary, and keys checked before the run.
#[test]
fn run_writes_timeseries_and_summary() {
    let dir = std::env::temp_dir().join(format!("haff-run-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let good = "[system]\ndimension = 3\nparticles = 300\npacking_fraction = 0.05\nseed = 3\n\
                [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
                [run]\ncollisions_per_particle = 10\nsamples = 12\n";
    let file = dir.join("gas.toml");
    std::fs::write(&file, good).unwrap();
    let out = dir.join("out");
    let result = haff(&[
        "run",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    let csv = std::fs::read_to_string(out.join("timeseries.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(
        header.starts_with("time,collisions_per_particle,temperature,a2"),
        "{header}"
    );
    assert_eq!(csv.lines().count(), 13);
    let last: Vec<f64> = csv
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    assert!((last[1] - 10.0).abs() < 0.01, "{last:?}");
    // Cooling per collision (independent of the code): a collision of equal masses m with
    // constant eps dissipates (1 - eps^2) m (g.n)^2 / 4 of the kinetic energy
    // E = N d T / 2 (T = m <v^2> / d, total momentum 0). Under the collision weighting
    // |g.n| of Maxwellian velocities, g.n has the density (g / (2T/m)) exp(-g^2 / (4T/m)),
    // so <(g.n)^2> = 4T/m and a collision removes (1 - eps^2) T on average. With
    // c = 2 (collisions) / N this is dT/dc = -(1 - eps^2) T / d, so
    // T(c) = T0 exp(-(1 - eps^2) c / d) at any collision rate (0.5308 T0 here).
    // Statistical error: ln(T/T0) sums K = N c / 2 relative losses
    // delta = (1 - eps^2) m (g.n)^2 / (4E), of mean 2 (1 - eps^2) / (N d) and equal standard
    // deviation ((g.n)^2 is exponential under the weighting), so
    // sd(ln T) = sqrt(K) 2 (1 - eps^2) / (N d) = (1 - eps^2) sqrt(2c/N) / d = 0.0164.
    // Systematic: a2 of the cooling state (van Noije-Ernst, d = 3, eps = 0.9: -0.0146)
    // changes the loss per collision by (1 + 3 a2/16)/(1 - a2/16) - 1 ~ a2/4, i.e. ln T by
    // at most |a2|/4 (1 - eps^2) c/d = 0.0024. Tolerance 5 sd + that (false failure 6e-7
    // for a normal deviation). Measured over seeds 1..40: mean deviation -0.003, sd 0.019
    // (largest 0.046), so the bound is 4.4 measured sd; seed 3: T/T0 = 0.5420.
    let (eps, d, n, c): (f64, f64, f64, f64) = (0.9, 3.0, 300.0, last[1]);
    let first: Vec<f64> = csv
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(first[1], 0.0);
    let t0 = first[2];
    let rate = (1.0 - eps * eps) / d;
    let sd = (1.0 - eps * eps) * (2.0 * c / n).sqrt() / d;
    let deviation = (last[2] / t0).ln() + rate * c;
    eprintln!(
        "T(c = {c}) / T0 = {:.4}, exp(-(1 - eps^2) c / d) = {:.4}, ln deviation {deviation:.4} \
         (sd {sd:.4})",
        last[2] / t0,
        (-rate * c).exp()
    );
    assert!(
        deviation.abs() < 5.0 * sd + 0.0146 / 4.0 * rate * c,
        "T/T0 = {} against {}",
        last[2] / t0,
        (-rate * c).exp()
    );
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["collisions"].as_u64(), Some(1500));
    let png = std::fs::read(out.join("temperature.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    assert!(summary["events_per_second"].as_f64().unwrap() > 0.0);
    for (bad, key) in [
        ("restitution = 0.9", "restitution = 1.5"),
        ("packing_fraction = 0.05", "packing_fraction = 0.65"),
        ("seed = 3", "seed = 3\ncolour = 1"),
        (
            "collisions_per_particle = 10",
            "end_time = 1\ncollisions_per_particle = 10",
        ),
    ]
    .iter()
    .map(|(from, to)| {
        (
            good.replace(from, to),
            to.split(' ').next().unwrap().to_string(),
        )
    }) {
        std::fs::write(&file, &bad).unwrap();
        let key = if key.starts_with("end_time") {
            "collisions_per_particle".into()
        } else {
            key
        };
        let key = if key.starts_with("seed") {
            "colour".into()
        } else {
            key
        };
        let r = haff(&[
            "run",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(2), "{stderr}");
        assert!(
            stderr.contains(&key) && stderr.lines().count() == 1,
            "{key}: {stderr}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Check-points: a run stopped after 6 of 12 samples and resumed repeats the uninterrupted
/// run (same check-point interval) bit for bit.
#[test]
fn resumed_run_repeats_the_uninterrupted_one() {
    let dir = std::env::temp_dir().join(format!("haff-resume-test-{}", std::process::id()));
    let (full, chunked) = run_full_and_chunked(
        &dir,
        "[system]\nparticles = 400\npacking_fraction = 0.1\nseed = 9\n\
         [collision]\nlaw = \"constant\"\nrestitution = 0.8\n\
         [run]\ncollisions_per_particle = 20\nsamples = 12\n",
    );
    let a = read(&full, "timeseries.csv");
    assert_eq!(a.lines().count(), 13);
    assert_eq!(a, read(&chunked, "timeseries.csv"));
    assert!(!full.join("velocity_histograms.csv").exists());
    assert_rejected(
        &["run", "--resume", dir.join("nothing").to_str().unwrap()],
        "--resume",
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The TC model (eps = 0.5, collisions within tc of the last one are elastic): the last
/// collision times go into the check-point, so the resumed run is still bit-identical (with
/// tc = 0.01 it is not if they are dropped on resume);
/// velocity histograms before and after the interruption are the same too.
#[test]
fn resumed_tc_run_with_histograms_repeats_the_uninterrupted_one() {
    let dir = std::env::temp_dir().join(format!("haff-resume-tc-{}", std::process::id()));
    // Sample targets 0, 0.02, 0.04, ..., 0.32 | 0.63, ... 20; the run stops after 0.32.
    let toml = "[system]\nparticles = 400\npacking_fraction = 0.1\nseed = 9\n\
                [collision]\nlaw = \"constant\"\nrestitution = 0.5\ntc = 1e-2\n\
                [run]\ncollisions_per_particle = 20\nsamples = 12\n\
                histogram_at = [20.0, 0.1, 0.0, 3.0]\nhistogram_bins = 30\n";
    let (full, chunked) = run_full_and_chunked(&dir, toml);
    let a = read(&full, "timeseries.csv");
    assert_eq!(a.lines().count(), 13);
    assert_eq!(a, read(&chunked, "timeseries.csv"));
    let h = read(&full, "velocity_histograms.csv");
    assert_eq!(h, read(&chunked, "velocity_histograms.csv"));
    let (header, rows) = parse_csv(&h);
    assert_eq!(
        header,
        "target,time,collisions_per_particle,c,density,maxwellian"
    );
    assert_eq!(rows.len(), 4 * 30);
    let targets: Vec<f64> = rows.iter().step_by(30).map(|r| r[0]).collect();
    assert_eq!(targets, [0.0, 0.1, 3.0, 20.0]);
    for block in rows.chunks(30) {
        assert!((block[0][2] - block[0][0]).abs() < 0.01, "{:?}", block[0]);
        let integral: f64 = block.iter().map(|r| r[4] * 10.0 / 30.0).sum();
        assert!(integral > 0.99 && integral <= 1.0 + 1e-12, "{integral}");
    }
    // The TC model is on: the same run without it differs.
    let plain = dir.join("plain");
    let file = dir.join("plain.toml");
    std::fs::write(&file, toml.replace("tc = 1e-2", "tc = 0")).unwrap();
    run_ok(&[file.to_str().unwrap(), "--out", plain.to_str().unwrap()]);
    assert_ne!(a, read(&plain, "timeseries.csv"));
    std::fs::remove_dir_all(&dir).ok();
}

/// A binary mixture stopped by time, with histograms between the samples.
#[test]
fn resumed_mixture_run_by_time_repeats_the_uninterrupted_one() {
    let dir = std::env::temp_dir().join(format!("haff-resume-mix-{}", std::process::id()));
    let (full, chunked) = run_full_and_chunked(
        &dir,
        "[system]\nparticles = 500\npacking_fraction = 0.1\nseed = 4\n\
         species = [{ diameter = 1.0, mass = 1.0, fraction = 0.5 }, \
                    { diameter = 1.4, mass = 2.744, fraction = 0.5 }]\n\
         [collision]\nlaw = \"constant\"\nrestitution = 0.7\ntc = 1e-2\n\
         [run]\nend_time = 10.0\nsamples = 12\nspacing = \"linear\"\n\
         histogram_at = [0.3, 5.0, 7.7]\n",
    );
    let a = read(&full, "timeseries.csv");
    assert_eq!(a.lines().count(), 13);
    assert_eq!(a, read(&chunked, "timeseries.csv"));
    let h = read(&full, "velocity_histograms.csv");
    assert_eq!(h, read(&chunked, "velocity_histograms.csv"));
    let (_, rows) = parse_csv(&h);
    assert_eq!(rows.len(), 3 * 60);
    for block in rows.chunks(60) {
        assert_eq!(block[0][0], block[0][1], "time = target: {:?}", block[0]);
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A binary mixture: the initial state and the outputs (timeseries, summary parameters,
/// histograms close to the Maxwellian at t = 0).
#[test]
fn binary_mixture_run() {
    let dir = std::env::temp_dir().join(format!("haff-mixture-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("mix.toml");
    std::fs::write(
        &file,
        "[system]\ndimension = 2\nparticles = 2000\npacking_fraction = 0.2\n\
         temperature = 2.0\nseed = 5\n\
         species = [{ diameter = 1.0, mass = 1.0, fraction = 3 }, \
                    { diameter = 2.0, mass = 4.0, fraction = 1 }]\n\
         [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
         [run]\ncollisions_per_particle = 5\nsamples = 6\nhistogram_at = [0.0, 5.0]\n",
    )
    .unwrap();
    let out = dir.join("out");
    run_ok(&[file.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let (header, rows) = parse_csv(&read(&out, "timeseries.csv"));
    assert!(header.starts_with("time,collisions_per_particle,temperature,a2"));
    assert_eq!(rows.len(), 6);
    assert!((rows[0][2] - 2.0).abs() < 1e-12, "T(0) = {}", rows[0][2]);
    assert!(rows[0][3].abs() < 0.1, "a2(0) = {}", rows[0][3]);
    assert!((rows[5][1] - 5.0).abs() < 1e-9 && rows[5][2] < 2.0);
    let summary: Value = serde_json::from_str(&read(&out, "summary.json")).unwrap();
    let system = &summary["parameters"]["system"];
    assert_eq!(system["species"][1]["mass"].as_f64(), Some(4.0));
    assert!(system.get("diameter").is_none(), "{system}");
    assert_eq!(summary["collisions"].as_u64(), Some(5000));
    let (header, rows) = parse_csv(&read(&out, "velocity_histograms.csv"));
    assert_eq!(
        header,
        "target,time,collisions_per_particle,c,density,maxwellian"
    );
    assert_eq!(rows.len(), 2 * 60);
    let width = 10.0 / 60.0;
    let integral: f64 = rows[..60].iter().map(|r| r[4] * width).sum();
    assert!((integral - 1.0).abs() < 1e-12, "{integral}");
    for r in &rows[..60] {
        assert!((r[5] - (-r[3] * r[3]).exp() / std::f64::consts::PI.sqrt()).abs() < 1e-15);
        // About 160 of the 4000 components per bin near c = 0.
        if r[3].abs() < 1.0 {
            assert!((r[4] - r[5]).abs() < 0.3 * r[5], "{r:?}");
        }
    }
    // Fraction with |c| < 1 (bins -1..1 exactly): erf(1) = 0.8427 for a Maxwellian.
    let inner: f64 = rows[..60]
        .iter()
        .filter(|r| r[3].abs() < 1.0)
        .map(|r| r[4] * width)
        .sum();
    assert!((inner - 0.8427).abs() < 0.02, "{inner}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_species_tc_and_histograms_are_rejected() {
    let good = "[system]\nparticles = 300\npacking_fraction = 0.05\n\
                species = [{ diameter = 1.0, mass = 1.0, fraction = 0.5 }, \
                           { diameter = 1.4, mass = 2.744, fraction = 0.5 }]\n\
                [collision]\nlaw = \"constant\"\nrestitution = 0.9\ntc = 1e-4\n\
                [run]\ncollisions_per_particle = 10\nsamples = 4\n\
                histogram_at = [0.0, 10.0]\nhistogram_bins = 40\n";
    let cases = [
        (
            "packing_fraction = 0.05",
            "packing_fraction = 0.05\ndiameter = 1.0",
            "system.species",
        ),
        (
            "packing_fraction = 0.05",
            "packing_fraction = 0.05\nmass = 2.0",
            "system.diameter/system.mass",
        ),
        ("mass = 2.744", "mass = -1", "system.species[1].mass"),
        ("mass = 2.744", "mass = inf", "system.species[1].mass"),
        (
            "{ diameter = 1.0,",
            "{ diameter = 0.0,",
            "system.species[0].diameter",
        ),
        (
            "fraction = 0.5 }]",
            "fraction = 0 }]",
            "system.species[1].fraction",
        ),
        ("fraction = 0.5 }]", "fraction = 1e-6 }]", "system.species"),
        (
            "fraction = 0.5 }]",
            "fraction = 0.5, radius = 1 }]",
            "radius",
        ),
        ("fraction = 0.5 }, ", "}, ", "fraction"),
        (
            "packing_fraction = 0.05",
            "packing_fraction = 0.65",
            "packing_fraction",
        ),
        ("tc = 1e-4", "tc = -1e-4", "collision.tc"),
        ("tc = 1e-4", "tc = nan", "collision.tc"),
        ("tc = 1e-4", "tc = inf", "collision.tc"),
        ("[0.0, 10.0]", "[0.0, 10.5]", "run.histogram_at"),
        ("[0.0, 10.0]", "[-1.0]", "run.histogram_at"),
        ("[0.0, 10.0]", "[nan]", "run.histogram_at"),
        ("[0.0, 10.0]", "[2.0, 1.0, 2.0]", "run.histogram_at"),
        (
            "histogram_bins = 40",
            "histogram_bins = 3",
            "run.histogram_bins",
        ),
        (
            "histogram_bins = 40",
            "histogram_bins = 10001",
            "run.histogram_bins",
        ),
    ];
    for (from, to, key) in cases {
        assert!(good.contains(from), "{from}");
        assert_run_rejected(&good.replacen(from, to, 1), key);
    }
    let species = "species = [{ diameter = 1.0, mass = 1.0, fraction = 0.5 }, \
                   { diameter = 1.4, mass = 2.744, fraction = 0.5 }]";
    assert_run_rejected(&good.replace(species, "species = []"), "system.species");
    // In time units when the run stops by time.
    assert_run_rejected(
        &good.replace("collisions_per_particle = 10", "end_time = 5.0"),
        "run.histogram_at",
    );
}

/// DSMC runs share the sampling loop and check-points of eMD: a resumed run of each scheme
/// repeats the uninterrupted one bit for bit (the random streams continue where they were).
#[test]
fn resumed_dsmc_runs_repeat_the_uninterrupted_ones() {
    for scheme in ["blocks", "exact", "spatial"] {
        let dir =
            std::env::temp_dir().join(format!("haff-resume-dsmc-{scheme}-{}", std::process::id()));
        let toml = format!(
            "[system]\nparticles = 3000\npacking_fraction = 0.05\nseed = 4\n\
             [collision]\nlaw = \"viscoelastic\"\nbeta = 0.3\nform = \"fast\"\n\
             [run]\nengine = \"dsmc\"\ndsmc_scheme = \"{scheme}\"\n\
             collisions_per_particle = 20\nsamples = 12\nhistogram_at = [0.0, 10.0]\n"
        );
        let (full, chunked) = run_full_and_chunked(&dir, &toml);
        let a = read(&full, "timeseries.csv");
        assert_eq!(a.lines().count(), 13, "{scheme}");
        assert_eq!(a, read(&chunked, "timeseries.csv"), "{scheme}");
        assert_eq!(
            read(&full, "velocity_histograms.csv"),
            read(&chunked, "velocity_histograms.csv")
        );
        let (_, rows) = parse_csv(&a);
        let last = rows.last().unwrap();
        assert!(last[2] < 1.0 && last[2] > 0.0, "{scheme}: T = {}", last[2]);
        std::fs::remove_dir_all(&dir).ok();
    }
}

#[test]
fn bad_dsmc_keys_are_rejected() {
    let base = "[system]\nparticles = 100\npacking_fraction = 0.05\n\
                [collision]\nlaw = \"constant\"\nrestitution = 0.9\n";
    let run = |extra: &str| format!("{base}[run]\ncollisions_per_particle = 5\n{extra}");
    assert_run_rejected(&run("engine = \"monte-carlo\"\n"), "run.engine");
    assert_run_rejected(
        &run("engine = \"dsmc\"\ndsmc_scheme = \"bird\"\n"),
        "run.dsmc_scheme",
    );
    assert_run_rejected(
        &run("engine = \"dsmc\"\nblock_size = 1\n"),
        "run.block_size",
    );
    assert_run_rejected(
        &run("engine = \"dsmc\"\ncollisions_per_step = 0.0\n"),
        "run.collisions_per_step",
    );
    assert_run_rejected(
        &run("engine = \"dsmc\"\ntime_step = -1.0\n"),
        "run.time_step",
    );
    assert_run_rejected(
        &run("engine = \"dsmc\"\ndsmc_scheme = \"exact\"\nblock_size = 100\n"),
        "run.block_size",
    );
    assert_run_rejected(
        &run("engine = \"dsmc\"\ndsmc_scheme = \"spatial\"\ncollision_cell_width = 0.0\n"),
        "run.collision_cell_width",
    );
    assert_run_rejected(&run("block_size = 100\n"), "run.block_size");
    assert_run_rejected(&run("particle_weight = 0.5\n"), "run.particle_weight");
    assert_run_rejected(
        &run("engine = \"dsmc\"\nparticle_weight = 0.5\n"),
        "run.particle_weight",
    );
    for weight in ["0.0", "-1.0", "1e7", "nan"] {
        assert_run_rejected(
            &run(&format!(
                "engine = \"dsmc\"\ndsmc_scheme = \"spatial\"\nparticle_weight = {weight}\n"
            )),
            "run.particle_weight",
        );
    }
    assert_run_rejected(
        &format!(
            "{}tc = 0.1\n[run]\nengine = \"dsmc\"\ncollisions_per_particle = 5\n",
            base
        ),
        "collision.tc",
    );
}

/// Inelastic collapse (1D, eps = 0.5, dense): without the TC model the run stops with an
/// error naming collision.tc instead of looping at a standing time; with it, it finishes.
#[test]
fn inelastic_collapse_is_reported_and_tc_prevents_it() {
    let toml = "[system]\ndimension = 1\nparticles = 100\npacking_fraction = 0.5\nseed = 3\n\
                [collision]\nlaw = \"constant\"\nrestitution = 0.5\n\
                [run]\nend_time = 100.0\nsamples = 5\n";
    assert_run_rejected(toml, "collision.tc");
    let dir = std::env::temp_dir().join(format!("haff-collapse-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("tc.toml");
    std::fs::write(
        &file,
        toml.replace("restitution = 0.5\n", "restitution = 0.5\ntc = 1e-3\n"),
    )
    .unwrap();
    run_ok(&[
        file.to_str().unwrap(),
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    let summary: Value = serde_json::from_str(&read(&dir.join("out"), "summary.json")).unwrap();
    assert!(number(&summary["tc_elastic_collisions"]) > 0.0);
    std::fs::remove_dir_all(&dir).ok();
}

/// Giese's stochastic law on a 1D ring from cold baths: the baths and the position of the
/// random stream go into the check-point (the resumed run is bit-identical), the
/// timeseries gains a bath_temperature column, and translational plus bath energy is
/// conserved: N (T/2 + N_modes T_bath) stays N/2 (T0 = 1).
#[test]
fn resumed_stochastic_run_repeats_the_uninterrupted_one() {
    let dir = std::env::temp_dir().join(format!("haff-resume-giese-{}", std::process::id()));
    let toml = "[system]\ndimension = 1\nparticles = 300\npacking_fraction = 0.3\nseed = 4\n\
                [collision]\nlaw = \"stochastic\"\nmodes = 6\n\
                [run]\ncollisions_per_particle = 30\nsamples = 12\nspacing = \"linear\"\n";
    let (full, chunked) = run_full_and_chunked(&dir, toml);
    let a = read(&full, "timeseries.csv");
    assert_eq!(a, read(&chunked, "timeseries.csv"));
    let (header, rows) = parse_csv(&a);
    assert_eq!(
        header,
        "time,collisions_per_particle,temperature,a2,energy_lost,pressure,events,bath_temperature"
    );
    let (first, last) = (&rows[0], &rows[rows.len() - 1]);
    assert_eq!(first[7], 0.0);
    // Temperature T = m <c^2> about the mean velocity, which is zero by construction.
    for row in &rows {
        let energy = 0.5 * row[2] + 6.0 * row[7];
        assert!((energy - 0.5 * first[2]).abs() < 1e-9, "{row:?}");
    }
    assert!(
        last[7] > 0.5 * first[2] / 6.5 * 0.8,
        "baths took up energy: {last:?}"
    );
    // Other engines and stray keys are refused with the key named.
    let bad = dir.join("bad.toml");
    for (text, key) in [
        (toml.replace("modes = 6", ""), "collision.modes"),
        (toml.replace("modes = 6", "modes = 0"), "collision.modes"),
        (
            toml.replace("[run]", "[run]\nengine = \"dsmc\""),
            "run.engine",
        ),
        (
            toml.replace(
                "law = \"stochastic\"",
                "law = \"constant\"\nrestitution = 0.9",
            ),
            "collision.modes",
        ),
        (
            toml.replace("modes = 6", "modes = 6\ndistribution = \"x\""),
            "collision.distribution",
        ),
        (
            toml.replace("modes = 6", "modes = 6\ndistribution = \"tabulated\""),
            "collision.table",
        ),
        (
            toml.replace("modes = 6", "modes = 6\nbath_temperature = -1"),
            "collision.bath_temperature",
        ),
    ] {
        std::fs::write(&bad, text).unwrap();
        assert_rejected(&["run", bad.to_str().unwrap()], key);
    }
    std::fs::remove_dir_all(&dir).ok();
}
