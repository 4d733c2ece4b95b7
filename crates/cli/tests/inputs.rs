//! Every input refused that cannot be simulated, naming what the user gave (issue 12):
//! meaningless physics, keys of another law, tables of other rods, approximations beyond
//! their validity, errors that named the wrong argument, and work beyond a minute.

mod common;

use common::{assert_rejected, assert_run_rejected, haff, parse_csv};

/// A run file: `[system]` of 100 spheres, then `collision` and `run` sections.
fn gas(collision: &str, run: &str) -> String {
    format!(
        "[system]\nparticles = 100\npacking_fraction = 0.1\n\
         [collision]\n{collision}\n[run]\n{run}\n"
    )
}

#[test]
fn sticking_spheres_need_the_tc_model() {
    let run = "collisions_per_particle = 5";
    assert_run_rejected(
        &gas("law = \"constant\"\nrestitution = 0.0", run),
        "collision.restitution",
    );
    // With the TC model, or in DSMC (no collapse), restitution 0 is a run.
    for file in [
        gas("law = \"constant\"\nrestitution = 0.0\ntc = 1e-3", run),
        gas(
            "law = \"constant\"\nrestitution = 0.0",
            "engine = \"dsmc\"\ncollisions_per_particle = 5",
        ),
    ] {
        let dir = std::env::temp_dir().join(format!("haff-eps0-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(format!("{}.toml", file.len()));
        std::fs::write(&path, &file).unwrap();
        let out = haff(&[
            "run",
            path.to_str().unwrap(),
            "--out",
            dir.join(format!("o{}", file.len())).to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn keys_of_another_law_are_refused() {
    let run = "collisions_per_particle = 5";
    for (collision, key) in [
        (
            "law = \"constant\"\nrestitution = 0.5\nbeta = 0.1",
            "collision.beta",
        ),
        (
            "law = \"constant\"\nrestitution = 0.5\nform = \"fast\"",
            "collision.form",
        ),
        (
            "law = \"viscoelastic\"\nbeta = 0.1\nrestitution = 0.5",
            "collision.restitution",
        ),
        (
            "law = \"dashpot\"\ndamping_ratio = 0.1\nmodes = 3",
            "collision.modes",
        ),
        (
            "law = \"viscoelastic\"\nbeta = 0.1\ncriterion = \"naive\"",
            "collision.criterion",
        ),
    ] {
        assert_run_rejected(&gas(collision, run), key);
    }
}

/// series:20 diverges beyond v* = 1.06; 1000 spheres at T = 1 reach g = (6000)^(1/2),
/// v* = beta^(1/2) 77.5^(1/10) = 1.545 at beta = 1 (refused), 0.846 at beta = 0.3.
#[test]
fn approximations_beyond_their_validity_are_refused_in_runs() {
    let file = |form: &str, beta: f64| {
        format!(
            "[system]\nparticles = 1000\npacking_fraction = 0.1\n[collision]\n\
             law = \"viscoelastic\"\nbeta = {beta}\nform = \"{form}\"\n\
             [run]\ncollisions_per_particle = 1\n"
        )
    };
    assert_run_rejected(&file("series:20", 1.0), "collision.form");
    assert_run_rejected(&file("pade:2/1", 1.0), "collision.form");
    // v* = 1e150: beyond the exact law's range (and a Padé form's polynomials overflow).
    assert_run_rejected(&file("pade:3/6", 1e300), "collision.beta");
    let dir = std::env::temp_dir().join(format!("haff-valid-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (k, (form, beta)) in [("series:20", 0.3), ("pade-paper:3/6", 1.0), ("fast", 100.0)]
        .into_iter()
        .enumerate()
    {
        let path = dir.join(format!("ok{k}.toml"));
        std::fs::write(&path, file(form, beta)).unwrap();
        let out = dir.join(format!("out{k}"));
        let o = haff(&[
            "run",
            path.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(
            o.status.success(),
            "{form}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

/// In `haff cor eps` the values are printed (someone may study the divergence) with a
/// warning on stderr; inside the range of validity there is no warning.
#[test]
fn approximations_beyond_their_validity_warn_in_cor_eps() {
    for (law, vstar) in [("series:20", "5"), ("pade:2/1", "10"), ("pade:50/1", "0.9")] {
        let out = haff(&["cor", "eps", "--law", law, "--vstar", vstar]);
        assert!(out.status.success());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            stderr.starts_with("haff: warning: --law"),
            "{law}: {stderr}"
        );
        assert!(stderr.contains("valid for v* <"), "{law}: {stderr}");
        assert_eq!(stderr.lines().count(), 1);
    }
    let out = haff(&["cor", "eps", "--law", "pade:3/6", "--vstar", "0.5,10,1000"]);
    assert!(out.status.success() && out.stderr.is_empty());
}

#[test]
fn errors_name_the_argument_given() {
    assert_rejected(
        &["cor", "eps", "--law", "fast", "--beta", "1e300", "--v", "1"],
        "--beta",
    );
    assert_rejected(
        &[
            "cor",
            "eps",
            "--law",
            "fast",
            "--material",
            "ice",
            "--radius",
            "0.01",
            "--dissipative-constant",
            "0",
            "--v",
            "1",
        ],
        "--dissipative-constant",
    );
    assert_rejected(
        &["cor", "eps", "--law", "pade:1/1", "--vstar", "1"],
        "--law",
    );
    assert_rejected(
        &[
            "rods",
            "collide",
            "--gamma",
            "0.6",
            "--kappa",
            "10",
            "--histogram",
            "8",
            "--plot",
            "/nonexistent-dir/x.png",
        ],
        "--plot",
    );
}

/// A run file's errors name the file, not a placeholder.
#[test]
fn run_file_errors_name_the_file() {
    let dir = std::env::temp_dir().join(format!("haff-named-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("chain.toml");
    std::fs::write(&path, "[chain]\nrods = 10\nmodes = -1\n").unwrap();
    let p = path.to_str().unwrap();
    assert_rejected(&["rods", "chain", p], p);
    assert_rejected(&["rods", "chain"], "haff rods chain");
}

/// The tabulated law of a chain comparison was built for gamma = 0.6173: rods of equal
/// length (gamma = 1) are refused; the rods of the table (0.80865 / 1.31001) pass the check.
#[test]
fn tables_of_other_rods_are_refused() {
    let table = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/data/giese-table-gamma0.6173.json"
    );
    let dir = std::env::temp_dir().join(format!("haff-table-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = |lengths: &str| {
        format!(
            "[chain]\nrods = 10\nlengths = {lengths}\nmodes = 4\nalpha = 5000.0\n\
             temperature = 1e-4\n[run]\nend_time = 5.0\nsamples = 2\n\
             compare = [\"tabulated\"]\ntable = \"{table}\"\n"
        )
    };
    let bad = dir.join("equal.toml");
    std::fs::write(&bad, file("[1.0, 1.0]")).unwrap();
    assert_rejected(&["rods", "chain", bad.to_str().unwrap()], "run.table");
    let good = dir.join("table.toml");
    std::fs::write(&good, file("[0.80865, 1.31001]")).unwrap();
    let out = dir.join("out");
    let o = haff(&[
        "rods",
        "chain",
        good.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// `rods deterministic --gamma 1`: the closed forms (ln 0) are empty cells with a warning,
/// the solved eps is 1 (equal rods exchange their momenta: an elastic collision).
#[test]
fn undefined_closed_forms_are_empty() {
    let out = haff(&["rods", "deterministic", "--gamma", "1", "--kappa", "100"]);
    assert!(out.status.success());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        !stdout.contains("inf") && !stdout.contains("NaN"),
        "{stdout}"
    );
    let row = stdout.lines().nth(1).unwrap();
    let cells: Vec<&str> = row.split(',').collect();
    assert_eq!(&cells[2..4], ["", ""]);
    let eps: f64 = cells[4].parse().unwrap();
    assert!((eps - 1.0).abs() < 1e-6, "{eps}");
    assert!(String::from_utf8_lossy(&out.stderr).contains("warning"));
}

/// Work beyond about a minute is refused with an estimate, before it starts.
#[test]
fn unbounded_work_is_refused() {
    assert_rejected(
        &["rods", "deterministic", "--gamma", "1e-3", "--kappa", "100"],
        "--gamma",
    );
    assert_rejected(
        &[
            "rods",
            "collide",
            "--gamma",
            "0.01",
            "--kappa",
            "1e4",
            "--histogram",
            "8",
        ],
        "--realizations",
    );
    assert_rejected(
        &[
            "cor",
            "coefficients",
            "--kind",
            "c",
            "--order",
            "100",
            "--digits",
            "60",
            "--bits",
            "8192",
            "--trajectory-order",
            "2000",
        ],
        "--order",
    );
    assert_rejected(&["cor", "pade", "--m", "60", "--n", "60"], "--m/--n");
    let run = gas("law = \"constant\"\nrestitution = 0.9", "engine = \"dsmc\"\ndsmc_scheme = \"spatial\"\ncollisions_per_step = 1e-300\ncollisions_per_particle = 3");
    assert_run_rejected(&run, "run.collisions_per_step");
    let fixed = gas(
        "law = \"constant\"\nrestitution = 0.9",
        "engine = \"dsmc\"\ntime_step = 0.1\ncollisions_per_particle = 3",
    );
    assert_run_rejected(&fixed, "run.time_step");
    let tiny = gas(
        "law = \"constant\"\nrestitution = 0.9",
        "engine = \"dsmc\"\ntime_step = 1e-12\nend_time = 1.0",
    );
    assert_run_rejected(&tiny, "run.time_step");
}

/// The naive-criterion trajectory at the top of the range (the creeping tail, sampled at
/// 201 points) used to fail numerically (exit 1); its eps is the asymptote
/// 5.158381704 v*^(-10) (docs/collision-laws.md), here to 1e-6.
#[test]
fn naive_trajectory_at_the_top_of_the_range() {
    let out = haff(&["cor", "collision", "--vstar", "1e6", "--criterion", "naive"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let summary = String::from_utf8_lossy(&out.stderr);
    let eps: f64 = summary
        .split("eps = ")
        .nth(1)
        .and_then(|s| s.split(',').next())
        .unwrap()
        .parse()
        .unwrap();
    assert!((eps / 5.158381704e-60 - 1.0).abs() < 1e-6, "{eps}");
    let (_, rows) = parse_csv(&String::from_utf8_lossy(&out.stdout));
    assert_eq!(rows.len(), 201);
    assert!(rows.iter().flatten().all(|x| x.is_finite()));
}

/// Particles from a file (`system.initial`): a file a run cannot start from is refused with
/// exit 2 naming the file and the records, the keys the file replaces naming the key.
#[test]
fn bad_initial_particle_files_are_refused() {
    let dir = std::env::temp_dir().join(format!("haff-initial-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("overlap.csv");
    std::fs::write(
        &file,
        "# box = 10 10\nx,y,vx,vy\n1,1,0.5,0\n1.5,1,-0.5,0\n5,5,0,1\n",
    )
    .unwrap();
    let clean = dir.join("clean.csv");
    std::fs::write(
        &clean,
        "# box = 10 10\nx,y,vx,vy\n1,1,0.5,0\n3,1,-0.5,0\n5,5,0,1\n",
    )
    .unwrap();
    let run = |file: &std::path::Path, extra: &str| {
        format!(
            "[system]\ndimension = 2\ninitial = {{ file = {:?} }}\n{extra}\n\
             [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
             [run]\ncollisions_per_particle = 1\n",
            file.display().to_string()
        )
    };
    assert_run_rejected(&run(&file, ""), "records 0 and 1");
    assert_run_rejected(&run(&clean, "particles = 3"), "system.particles");
    assert_run_rejected(&run(&clean, "temperature = 2.0"), "system.temperature");
}
