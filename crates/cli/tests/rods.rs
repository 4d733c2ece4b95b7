//! `haff rods ...`: Giese's rods from the command line.

mod common;

use common::{assert_rejected, haff, parse_csv, read, run_ok, stdout_of};
use serde_json::Value;

/// `haff rods deterministic`: the solved eps of Eq. (3) last, beside the paper's closed
/// form (right for 1/2 < gamma < 2) and the generalized one (right below 1/2 too);
/// equal rods collide elastically.
#[test]
fn rods_deterministic_solves_eq3() {
    let text = stdout_of(&[
        "rods",
        "deterministic",
        "--gamma",
        "0.3,0.6173",
        "--kappa",
        "100",
    ]);
    let (header, rows) = parse_csv(&text);
    assert_eq!(header, "gamma,kappa,closed_form,closed_form_general,eps");
    // gamma = 1 (closed forms undefined, eps = 1): inputs::undefined_closed_forms_are_empty.
    let (low, mid) = (&rows[0], &rows[1]);
    assert!((mid[4] - mid[2]).abs() < 1e-6, "{mid:?}");
    assert!(
        (low[4] - low[3]).abs() < 1e-3 && (low[4] - low[2]).abs() > 5e-3,
        "{low:?}"
    );
    assert_rejected(
        &["rods", "deterministic", "--gamma", "0", "--kappa", "100"],
        "--gamma",
    );
    assert_rejected(
        &["rods", "deterministic", "--gamma", "1", "--kappa", "x"],
        "--kappa",
    );
}

/// `haff rods collide`: cold baths give the deterministic eps in every realization; a
/// warm bath gives a distribution whose histogram integrates to the fraction below --max.
#[test]
fn rods_collide_samples_and_histogram() {
    let cold = stdout_of(&[
        "rods",
        "collide",
        "--gamma",
        "0.6173",
        "--kappa",
        "100",
        "--realizations",
        "3",
    ]);
    let (header, rows) = parse_csv(&cold);
    assert_eq!(header, "realization,eps,eps2");
    assert!(
        rows.iter()
            .all(|r| (r[1] - 0.66338).abs() < 1e-4 && r[1] == rows[0][1]),
        "{rows:?}"
    );
    let args = [
        "rods",
        "collide",
        "--gamma",
        "0.6173",
        "--kappa",
        "100",
        "--bath-ratio",
        "10",
        "--realizations",
        "300",
        "--histogram",
        "40",
        "--max",
        "2",
    ];
    let (header, rows) = parse_csv(&stdout_of(&args));
    assert_eq!(header, "eps2,density,cdf");
    assert_eq!(rows.len(), 40);
    let integral: f64 = rows.iter().map(|r| r[1] * 0.05).sum();
    let last = rows[39][2];
    assert!(
        (integral - last).abs() < 1e-12 && last > 0.95 && last <= 1.0,
        "{integral} {last}"
    );
    for (flag, value) in [
        ("--bath-ratio", "-1"),
        ("--realizations", "0"),
        ("--histogram", "0"),
    ] {
        let mut bad = vec![
            "rods", "collide", "--gamma", "0.5", "--kappa", "100", flag, value,
        ];
        if flag != "--histogram" {
            bad.extend(["--histogram", "10"]);
        }
        assert_rejected(&bad, flag);
    }
}

/// A small table from `haff rods table` drives `law = "stochastic"`,
/// `distribution = "tabulated"`: translational plus bath energy stays constant.
#[test]
fn rods_table_feeds_the_tabulated_law() {
    let dir = std::env::temp_dir().join(format!("haff-rods-table-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let table = dir.join("t.json");
    let t = table.to_str().unwrap();
    let args = [
        "rods",
        "table",
        "--gamma",
        "0.6173",
        "--ratios",
        "0.1,10,3",
        "--realizations",
        "40",
        "--out",
        t,
    ];
    assert!(haff(&args).status.success());
    let toml = format!(
        "[system]\ndimension = 1\nparticles = 200\npacking_fraction = 0.3\n\
         [collision]\nlaw = \"stochastic\"\nmodes = 5\ndistribution = \"tabulated\"\ntable = \"{t}\"\n\
         [run]\ncollisions_per_particle = 20\nsamples = 5\n"
    );
    let file = dir.join("run.toml");
    std::fs::write(&file, toml).unwrap();
    let out = dir.join("out");
    run_ok(&[file.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let (_, rows) = parse_csv(&read(&out, "timeseries.csv"));
    for row in &rows {
        let energy = 0.5 * row[2] + 5.0 * row[7];
        assert!((energy - 0.5 * rows[0][2]).abs() < 1e-9, "{row:?}");
    }
    assert_rejected(
        &[
            "rods", "table", "--gamma", "0.5", "--ratios", "1,2", "--out", t,
        ],
        "--ratios",
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// `haff rods two-rods` and `haff rods chain` write their files; the chain MD conserves
/// energy and the ED + MC run conserves translational plus bath energy.
#[test]
fn rods_two_rods_and_chain_run() {
    let dir = std::env::temp_dir().join(format!("haff-rods-chain-{}", std::process::id()));
    let two = dir.join("two");
    let args = [
        "rods",
        "two-rods",
        "--modes",
        "4",
        "--kappa",
        "100",
        "--collisions",
        "60",
        "--transient",
        "10",
        "--out",
        two.to_str().unwrap(),
    ];
    assert!(haff(&args).status.success());
    let summary: Value = serde_json::from_str(&read(&two, "summary.json")).unwrap();
    assert!(
        summary[0]["energy_drift"].as_f64().unwrap() < 1e-8,
        "{summary}"
    );
    assert_eq!(parse_csv(&read(&two, "two_rods.csv")).1.len(), 60);
    for png in ["energy.png", "entropy.png", "spectrum.png"] {
        assert!(two.join(png).exists());
    }
    let toml =
        "[chain]\nrods = 10\nlengths = [0.8, 1.3]\nmodes = 4\nalpha = 2000.0\ntemperature = 1e-4\n\
                [run]\nend_time = 2000.0\nsamples = 5\ncompare = [\"glauber\"]\n";
    let file = dir.join("chain.toml");
    std::fs::write(&file, toml).unwrap();
    let out = dir.join("chain");
    let status = haff(&[
        "rods",
        "chain",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    for (name, tolerance) in [("timeseries.csv", 1e-7), ("ed_mc_glauber.csv", 1e-12)] {
        let (header, rows) = parse_csv(&read(&out, name));
        assert_eq!(
            header,
            "time,collisions_per_particle,translational_energy,bath_energy,total_energy"
        );
        for r in &rows {
            assert!((r[4] / rows[0][4] - 1.0).abs() < tolerance, "{name}: {r:?}");
        }
        assert!(
            rows[4][1] > 1.0 && rows[4][3] > 0.0,
            "{name}: collisions and bath energy {:?}",
            rows[4]
        );
    }
    for (text, key) in [
        (toml.replace("rods = 10", "rods = 1"), "chain.rods"),
        (toml.replace("[\"glauber\"]", "[\"x\"]"), "run.compare"),
        (
            toml.replace("[\"glauber\"]", "[\"tabulated\"]"),
            "run.table",
        ),
        (toml.replace("alpha = 2000.0", "alpha = -1"), "chain.alpha"),
    ] {
        std::fs::write(&file, text).unwrap();
        assert_rejected(&["rods", "chain", file.to_str().unwrap()], key);
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Giese's ED + Monte Carlo against the rod-chain MD (docs/giese.md; 2 min):
/// cargo test --release -p haff-cli --test rods -- --ignored ed_mc_against_rod_chain
/// Measured: late-time E_tr / equipartition 1.04 (chain), 1.08 (Glauber), 1.01 (tabulated);
/// at t = 500 Glauber / chain = 0.53, tabulated / chain = 0.81.
#[test]
#[ignore]
fn ed_mc_against_rod_chain() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let out = std::env::temp_dir().join(format!("haff-giese-ring-{}", std::process::id()));
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_haff"))
        .current_dir(root)
        .args([
            "rods",
            "chain",
            "docs/data/giese-ring.toml",
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let summary: Value = serde_json::from_str(&read(&out, "summary.json")).unwrap();
    let equilibrium = summary["equipartition_translational_energy"]
        .as_f64()
        .unwrap();
    let late = |name: &str| {
        let (_, rows) = parse_csv(&read(&out, name));
        let tail = &rows[rows.len() / 2..];
        tail.iter().map(|r| r[2]).sum::<f64>() / tail.len() as f64 / equilibrium
    };
    let early = |name: &str| parse_csv(&read(&out, name)).1[1][2];
    for name in ["timeseries.csv", "ed_mc_glauber.csv", "ed_mc_tabulated.csv"] {
        let ratio = late(name);
        eprintln!(
            "{name}: late E_tr / equipartition {ratio:.3}, E_tr(t = 500) {:.4e}",
            early(name)
        );
        assert!((ratio - 1.0).abs() < 0.1, "{name}: {ratio}");
    }
    let chain = early("timeseries.csv");
    let (glauber, tabulated) = (
        early("ed_mc_glauber.csv") / chain,
        early("ed_mc_tabulated.csv") / chain,
    );
    assert!(
        glauber < tabulated && tabulated < 0.95,
        "{glauber} {tabulated}"
    );
    std::fs::remove_dir_all(&out).ok();
}

/// `haff rods chain` in chunks (stopped inside the first repeat, then inside the second,
/// resumed) repeats the uninterrupted run bit for bit, ED + MC included.
#[test]
fn resumed_rod_chain_repeats_the_uninterrupted_one() {
    let dir = std::env::temp_dir().join(format!("haff-rods-resume-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let toml =
        "[chain]\nrods = 8\nlengths = [0.8, 1.3]\nmodes = 4\nalpha = 2000.0\ntemperature = 1e-4\n\
                [run]\nend_time = 1500.0\nsamples = 5\nrepeats = 2\ncompare = [\"glauber\"]\n";
    let file = dir.join("chain.toml");
    std::fs::write(&file, toml).unwrap();
    let (full, chunked) = (dir.join("full"), dir.join("chunked"));
    let ok = |args: &[&str]| {
        let mut all = vec!["rods", "chain"];
        all.extend_from_slice(args);
        let out = haff(&all);
        assert!(
            out.status.success(),
            "{all:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    let f = file.to_str().unwrap();
    ok(&[f, "--out", full.to_str().unwrap()]);
    let c = chunked.to_str().unwrap();
    ok(&[
        f,
        "--out",
        c,
        "--checkpoint-every",
        "2",
        "--stop-after-samples",
        "3",
    ]);
    assert!(!chunked.join("timeseries.csv").exists());
    let saved = |repeat: u64, rows: usize| {
        // The check-point's second line: its records as JSON.
        let bytes = std::fs::read(chunked.join("checkpoint.bin")).unwrap();
        let records = bytes.split(|&b| b == b'\n').nth(1).unwrap();
        let v: Value = serde_json::from_slice(records).unwrap();
        assert_eq!(v["repeat"].as_u64(), Some(repeat));
        assert_eq!(v["rows"].as_array().map(Vec::len), Some(rows));
    };
    saved(0, 3);
    ok(&[
        "--resume",
        c,
        "--checkpoint-every",
        "2",
        "--stop-after-samples",
        "4",
    ]);
    saved(1, 2);
    ok(&["--resume", c]);
    for name in ["timeseries.csv", "ed_mc_glauber.csv"] {
        assert_eq!(read(&full, name), read(&chunked, name), "{name}");
    }
    assert_rejected(
        &[
            "rods",
            "chain",
            "--resume",
            dir.join("none").to_str().unwrap(),
        ],
        "--resume",
    );
    std::fs::remove_dir_all(&dir).ok();
}
