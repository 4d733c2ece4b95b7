//! `haff demo` (issue 39): the main job on built-in run files. Oracles: kinetic theory for
//! what it reports (Haff's law, van Noije & Ernst's a2), `haff run` of the run files it
//! leaves for the run it made (bit for bit), and the earlier demo's table for `--table`.

mod common;

use common::{haff, stdout_of};

/// The number after `label` in `text`.
fn number_after(text: &str, label: &str) -> f64 {
    let start = text
        .find(label)
        .unwrap_or_else(|| panic!("{label} in {text}"))
        + label.len();
    let rest = text[start..].trim_start();
    let end = rest
        .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == 'e'))
        .unwrap_or(rest.len());
    rest[..end]
        .parse()
        .unwrap_or_else(|_| panic!("a number after {label}: {rest}"))
}

#[test]
fn the_demo_runs_gases_and_says_what_it_shows() {
    let dir = std::env::temp_dir().join(format!("haff-demo-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let stdout = stdout_of(&["demo", "--out", dir.to_str().unwrap()]);

    // Haff's law with the Enskog rate and the HCS's a2, no fit: T of N = 4000 spheres has a
    // relative statistical error sqrt(2 / (3 N)) = 1.3 %; 5 of it, plus 3 % for the
    // Enskog contact value at phi = 0.05 and the first-Sonine cooling rate, bound the ratio
    // (the bound of the example notebook's test).
    let ratio = number_after(&stdout, "T / T_Haff =");
    let bound = 5.0 * (2.0 / (3.0 * 4000.0f64)).sqrt() + 0.03;
    assert!((ratio - 1.0).abs() < bound, "T/T_Haff = {ratio}\n{stdout}");
    // a2 of the cooling state against van Noije & Ernst's first Sonine approximation:
    // 4 batch-means standard errors, plus 0.002 for the second Sonine terms (about a tenth
    // of a2 at eps = 0.9: Brilliantov & Pöschel, Europhys. Lett. 74, 424 (2006)).
    let a2 = number_after(&stdout, "Sonine a2 =");
    let error = number_after(&stdout, "+-");
    let theory = number_after(&stdout, "van Noije & Ernst:");
    assert!(
        (theory + 0.0146).abs() < 1e-4,
        "a2(eps = 0.9, 3D) = {theory}"
    );
    assert!(error > 0.0 && error < 0.01, "standard error {error}");
    assert!(
        (a2 - theory).abs() < 4.0 * error + 0.002,
        "a2 = {a2} +- {error} vs {theory}"
    );

    for file in [
        "cooling.toml",
        "cooling/temperature.png",
        "velocity-distribution.png",
        "clustering.png",
        "clustering/snapshots.pvd",
    ] {
        let path = dir.join(file).display().to_string();
        assert!(stdout.contains(&path), "{file} not announced:\n{stdout}");
    }
    for file in [
        "cooling.toml",
        "cooling/temperature.png",
        "cooling/timeseries.csv",
        "velocity-distribution.png",
        "clustering.toml",
        "clustering.png",
        "clustering/snapshots.pvd",
        "clustering/fields_000020.png",
    ] {
        assert!(dir.join(file).exists(), "{file} missing");
    }
    let png = std::fs::read(dir.join("clustering.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert!(stdout.contains("pade:3/6"), "the eps(v) table");

    // The run file the demo leaves runs the demo's run, bit for bit.
    let again = dir.join("again");
    let out = haff(&[
        "run",
        dir.join("cooling.toml").to_str().unwrap(),
        "--out",
        again.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let read = |p: std::path::PathBuf| std::fs::read(p).unwrap();
    assert_eq!(
        read(dir.join("cooling/timeseries.csv")),
        read(again.join("timeseries.csv"))
    );

    // A second demo into the same directory replaces the first.
    assert!(haff(&["demo", "--out", dir.to_str().unwrap()])
        .status
        .success());
    let _ = std::fs::remove_dir_all(&dir);
}
