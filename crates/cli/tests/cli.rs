//! Integration tests of the `haff` binary: output contracts (headers, formats, numbers)
//! and the handling of bad input.

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs `haff` with `args`.
fn haff(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_haff"))
        .args(args)
        .output()
        .expect("the haff binary runs")
}

/// Runs `haff`, checks that it succeeded and returns its stdout.
fn stdout_of(args: &[&str]) -> String {
    let output = haff(args);
    assert!(
        output.status.success(),
        "haff {args:?} failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).expect("stdout is UTF-8")
}

/// A CSV document: its header line and its numeric rows.
fn parse_csv(text: &str) -> (String, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let header = lines.next().expect("a header line").to_string();
    let rows = lines
        .map(|line| {
            line.split(',')
                .map(|cell| cell.parse().expect("a number"))
                .collect()
        })
        .collect();
    (header, rows)
}

fn json_of(args: &[&str]) -> Value {
    serde_json::from_str(&stdout_of(args)).expect("valid JSON")
}

fn number(value: &Value) -> f64 {
    value.as_f64().expect("a JSON number")
}

#[test]
fn eps_at_scaled_speeds() {
    let (header, rows) = parse_csv(&stdout_of(&[
        "cor", "eps", "--law", "exact", "--vstar", "0,1.25",
    ]));
    assert_eq!(header, "vstar,eps");
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0][0], 0.0);
    assert!((rows[0][1] - 1.0).abs() < 1e-12, "eps(0) = {}", rows[0][1]);
    assert_eq!(rows[1][0], 1.25);
    assert!(
        (rows[1][1] - 0.27063).abs() < 1e-4,
        "eps(1.25) = {}",
        rows[1][1]
    );
}

#[test]
fn eps_json_has_the_csv_numbers() {
    let args = [
        "cor",
        "eps",
        "--law",
        "pade:3/6",
        "--vstar",
        "0,0.5,1.25,10",
    ];
    let (_, csv) = parse_csv(&stdout_of(&args));
    let json = json_of(&[&args[..], &["--format", "json"]].concat());
    assert_eq!(json["law"], "pade:3/6");
    let rows = json["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), csv.len());
    for (row, expected) in rows.iter().zip(&csv) {
        assert_eq!(number(&row["vstar"]), expected[0]);
        assert_eq!(number(&row["eps"]), expected[1]);
        assert!(row.get("v").is_none());
    }
}

#[test]
fn eps_at_physical_speeds_in_cgs() {
    let args = [
        "cor",
        "eps",
        "--law",
        "pade:3/6",
        "--v",
        "0.01,1,1000",
        "--beta",
        "1.307",
        "--units",
        "cgs",
    ];
    let (header, rows) = parse_csv(&stdout_of(&args));
    assert_eq!(header, "v,vstar,eps");
    let speeds = [0.01, 1.0, 1000.0];
    // [3/6] of MP2011, Table I, as printed; `pade:3/6` is computed from the exact series
    // coefficients, so the two differ by the rounding of the printed coefficients (half a
    // unit of the last digit: 5e-7 below 1, 5e-6 above), propagated to eps.
    let a = [1.0, 1.07232, 0.574198, 0.141552];
    let b = [1.0, 1.07232, 1.72765, 1.37842, 1.19449, 0.467273, 0.235585];
    let half_unit = |c: f64| {
        if c == 1.0 {
            0.0
        } else if c.abs() >= 1.0 {
            5e-6
        } else {
            5e-7
        }
    };
    for (row, v) in rows.iter().zip(speeds) {
        assert_eq!(row[0], v);
        let vstar = 1.307f64.sqrt() * v.powf(0.1);
        assert!(
            (row[1] - vstar).abs() < 1e-12 * vstar,
            "v* = {} at v = {v}",
            row[1]
        );
        let poly = |c: &[f64]| c.iter().rev().fold(0.0, |acc, &ci| acc * vstar + ci);
        let rounding = |c: &[f64]| {
            c.iter()
                .enumerate()
                .map(|(i, &ci)| half_unit(ci) * vstar.powi(i as i32))
                .sum::<f64>()
        };
        let (num, den) = (poly(&a), poly(&b));
        let eps = num / den;
        let bound = (rounding(&a) + eps * rounding(&b)) / den + 1e-14;
        assert!(
            (row[2] - eps).abs() <= bound,
            "eps = {} at v* = {vstar}, Table I gives {eps} (+- {bound:.1e})",
            row[2]
        );
    }
    let json = json_of(&[&args[..], &["--format", "json"]].concat());
    assert_eq!(number(&json["beta"]), 1.307);
    assert_eq!(json["units"], "cgs");
    for (row, expected) in json["rows"].as_array().expect("rows").iter().zip(&rows) {
        let values = [&row["v"], &row["vstar"], &row["eps"]].map(number);
        assert_eq!(values.to_vec(), *expected);
    }
}

#[test]
fn collision_trajectory_runs_from_zero_to_the_end_of_contact() {
    let points = 11;
    let args = ["cor", "collision", "--vstar", "1.25", "--points", "11"];
    let output = haff(&args);
    assert!(output.status.success());
    let stdout = String::from_utf8(output.stdout).expect("UTF-8");
    assert_eq!(stdout.lines().count(), points + 1);
    let (header, rows) = parse_csv(&stdout);
    assert_eq!(header, "tau,x,xdot,xddot");
    let summary = String::from_utf8(output.stderr).expect("UTF-8");
    assert_eq!(summary.lines().count(), 1);
    assert!(summary.contains("tau_c") && summary.contains("eps"));

    let json = json_of(&[&args[..], &["--format", "json"]].concat());
    let tau_c = number(&json["tau_c"]);
    assert_eq!(rows[0][0], 0.0);
    assert!((rows[points - 1][0] - tau_c).abs() <= 1e-12 * tau_c);
    assert!(rows.windows(2).all(|pair| pair[1][0] > pair[0][0]));
    assert!((number(&json["eps"]) - 0.27063).abs() < 1e-4);
    assert_eq!(json["points"].as_array().expect("points").len(), points);
}

#[test]
fn collision_has_201_points_by_default() {
    let stdout = stdout_of(&["cor", "collision", "--vstar", "0.5", "--criterion", "naive"]);
    assert_eq!(stdout.lines().count(), 202);
}

#[test]
fn dashpot_without_damping_is_elastic() {
    let stdout = stdout_of(&["cor", "dashpot", "--damping-ratio", "0"]);
    let mut lines = stdout.lines();
    assert_eq!(
        lines.next(),
        Some("damping_ratio,criterion,eps,omega0_tc,separated")
    );
    let cells: Vec<&str> = lines.next().expect("a row").split(',').collect();
    assert_eq!(cells[1], "improved");
    assert_eq!(cells[2].parse::<f64>().unwrap(), 1.0);
    assert!((cells[3].parse::<f64>().unwrap() - std::f64::consts::PI).abs() < 1e-12);
    assert_eq!(cells[4], "true");
}

#[test]
fn dashpot_capture_has_infinite_duration() {
    let args = [
        "cor",
        "dashpot",
        "--damping-ratio",
        "0.5,1,2",
        "--criterion",
        "naive",
    ];
    let stdout = stdout_of(&args);
    let last: Vec<&str> = stdout.lines().last().expect("rows").split(',').collect();
    assert_eq!(last, ["2", "naive", "0", "inf", "false"]);
    let json = json_of(&[&args[..], &["--format", "json"]].concat());
    let rows = json["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), 3);
    assert!(rows[2]["omega0_tc"].is_null());
}

#[test]
fn bench_json_lists_every_law() {
    let json = json_of(&[
        "bench",
        "cor",
        "--format",
        "json",
        "--repeats",
        "1",
        "--evaluations",
        "100",
    ]);
    assert_eq!(json["unit"], "ns_per_eval");
    let results = json["results"].as_array().expect("results");
    let laws: Vec<&str> = results
        .iter()
        .map(|r| r["law"].as_str().expect("law"))
        .collect();
    let expected = [
        "exact",
        "exact-naive",
        "fast",
        "pade:1/4",
        "pade:3/6",
        "series:20",
        "fast(v)",
        "pade:3/6(v)",
    ];
    assert_eq!(laws, expected);
    for result in results {
        let [median, min, max] = ["median_ns", "min_ns", "max_ns"].map(|k| number(&result[k]));
        assert!(min > 0.0 && min <= median && median <= max, "{result}");
        assert!(number(&result["ratio_to_pade36"]) > 0.0);
    }
}

#[test]
fn demo_shows_every_law() {
    let stdout = stdout_of(&["demo"]);
    let header = stdout.lines().nth(1).expect("a table header");
    for column in [
        "v [cm/s]",
        "v*",
        "exact",
        "exact-naive",
        "fast",
        "pade:1/4",
        "pade:3/6",
        "series:10",
        "series:20",
    ] {
        assert!(header.contains(column), "{column} missing from {header}");
    }
}

/// Bad input: exit code 2 and one line on stderr naming the argument, no panic.
fn assert_rejected(args: &[&str], argument: &str) {
    let output = haff(args);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "haff {args:?}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "haff {args:?}: {stderr}");
    assert!(
        stderr.starts_with("haff: error: "),
        "haff {args:?}: {stderr}"
    );
    assert!(
        stderr.contains(argument),
        "haff {args:?} does not name {argument}: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "haff {args:?}: {stderr}");
    assert!(output.stdout.is_empty(), "haff {args:?} wrote output");
}

#[test]
fn bad_speeds_are_rejected() {
    let eps = ["cor", "eps", "--law", "exact"];
    for vstar in ["-1", "nan", "inf", "", "1,,2", "1,", "abc", "2e6"] {
        assert_rejected(&[&eps[..], &["--vstar", vstar]].concat(), "--vstar");
    }
    for v in ["-1", "inf", "", "1,,2"] {
        assert_rejected(&[&eps[..], &["--v", v, "--beta", "1"]].concat(), "--v");
    }
    assert_rejected(&[&eps[..], &["--v", "1e70", "--beta", "1"]].concat(), "--v");
}

#[test]
fn bad_laws_criteria_and_parameters_are_rejected() {
    // pade:1/1 does not exist (its linear system is singular): an input error too.
    for law in [
        "foo",
        "pade:99/1",
        "pade-paper:2/2",
        "series:999",
        "pade:x",
        "pade:1/1",
    ] {
        assert_rejected(&["cor", "eps", "--law", law, "--vstar", "1"], "--law");
    }
    for beta in ["0", "-1", "nan", "x"] {
        assert_rejected(
            &["cor", "eps", "--law", "exact", "--v", "1", "--beta", beta],
            "--beta",
        );
    }
    let units = [
        "cor", "eps", "--law", "exact", "--v", "1", "--beta", "1", "--units", "furlong",
    ];
    assert_rejected(&units, "--units");
    assert_rejected(
        &["cor", "collision", "--vstar", "1", "--criterion", "x"],
        "--criterion",
    );
    assert_rejected(
        &["cor", "dashpot", "--damping-ratio", "1", "--criterion", "x"],
        "--criterion",
    );
    for points in ["1", "0", "-3", "2.5"] {
        assert_rejected(
            &["cor", "collision", "--vstar", "1", "--points", points],
            "--points",
        );
    }
    assert_rejected(&["cor", "collision", "--vstar", "-1"], "--vstar");
    assert_rejected(&["cor", "collision", "--vstar", "1e7"], "--vstar");
    for ratio in ["-0.5", "nan", "", "0,,1"] {
        assert_rejected(
            &["cor", "dashpot", "--damping-ratio", ratio],
            "--damping-ratio",
        );
    }
    assert_rejected(&["bench", "cor", "--repeats", "0"], "--repeats");
    assert_rejected(&["bench", "cor", "--evaluations", "x"], "--evaluations");
}

#[test]
fn bad_option_combinations_are_rejected() {
    assert_rejected(&["cor", "eps", "--vstar", "1"], "--law");
    assert_rejected(&["cor", "eps", "--law", "exact"], "--vstar");
    assert_rejected(&["cor", "collision"], "--vstar");
    assert_rejected(&["cor", "dashpot"], "--damping-ratio");
    let both = [
        "cor", "eps", "--law", "exact", "--vstar", "1", "--v", "1", "--beta", "1",
    ];
    assert_rejected(&both, "--v");
    assert_rejected(&["cor", "eps", "--law", "exact", "--v", "1"], "--beta");
    assert_rejected(
        &[
            "cor", "eps", "--law", "exact", "--vstar", "1", "--beta", "1",
        ],
        "--beta",
    );
    assert_rejected(
        &[
            "cor", "eps", "--law", "exact", "--vstar", "1", "--format", "xml",
        ],
        "--format",
    );
}

/// beta from material data (Eq. 8 of MP2011): glass spheres of 1 mm, A = 1 ns.
#[test]
fn eps_from_a_material() {
    let base = [
        "cor",
        "eps",
        "--law",
        "exact",
        "--v",
        "1",
        "--radius",
        "1e-3",
        "--dissipative-constant",
        "1e-9",
    ];
    let named = stdout_of(&[&base[..], &["--material", "soda-lime-glass"]].concat());
    let explicit = stdout_of(
        &[
            &base[..],
            &["--young", "72e9", "--poisson", "0.23", "--density", "2500"],
        ]
        .concat(),
    );
    assert_eq!(named, explicit);
    let (header, rows) = parse_csv(&named);
    assert_eq!(header, "v,vstar,eps");
    // v* = sqrt(beta) v^(1/10) with beta = (3/2) A (rho/m_eff)^(2/5), computed by hand.
    let (young, nu, density, radius, a) = (72e9f64, 0.23f64, 2500f64, 1e-3f64, 1e-9f64);
    let mass = density * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3);
    let rho = 2.0 * young * (radius / 2.0).sqrt() / (3.0 * (1.0 - nu * nu));
    let beta = 1.5 * a * (rho / (mass / 2.0)).powf(0.4);
    assert!((rows[0][1] - beta.sqrt()).abs() < 1e-12 * beta.sqrt());
    for (flag, value) in [("--poisson", "0.5"), ("--young", "-1"), ("--radius", "0")] {
        let mut args = base.to_vec();
        args.extend(["--material", "soda-lime-glass", flag, value]);
        assert_rejected(&args, flag);
    }
    assert_rejected(
        &[&base[..], &["--material", "cheese"]].concat(),
        "--material",
    );
    assert_rejected(&[&base[..], &["--young", "7e10"]].concat(), "--poisson");
}

#[test]
fn coefficients_and_pade() {
    let text = stdout_of(&[
        "cor",
        "coefficients",
        "--kind",
        "h",
        "--order",
        "6",
        "--digits",
        "12",
    ]);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "k,value");
    assert_eq!(lines.len(), 8);
    assert_eq!(lines[3], "2,-1.15344885810");
    assert_eq!(lines[6], "5,0.266666666667");
    let a = stdout_of(&["cor", "coefficients", "--kind", "a", "--order", "1"]);
    assert!(a.contains("0,1.6090327298595215423"), "{a}");
    let out = haff(&["cor", "pade", "--m", "4", "--n", "7", "--digits", "10"]);
    assert!(out.status.success());
    let csv = String::from_utf8_lossy(&out.stdout);
    assert!(
        csv.starts_with("i,a,b\n0,1.000000000,1.000000000\n"),
        "{csv}"
    );
    assert_eq!(csv.lines().count(), 9);
    // i > 4: no numerator coefficient.
    assert!(csv.lines().nth(6).unwrap().starts_with("5,,"));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("pole on the positive real axis at v* = 3.687"),
        "{stderr}"
    );
    assert_rejected(
        &["cor", "coefficients", "--kind", "z", "--order", "3"],
        "--kind",
    );
    assert_rejected(
        &["cor", "coefficients", "--kind", "h", "--order", "500"],
        "--order",
    );
    assert_rejected(&["cor", "pade", "--m", "-1", "--n", "3"], "--m");
    assert_rejected(&["cor", "pade", "--m", "1", "--n", "1"], "--m/--n");
}

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
        ("packing_fraction = 0.05", "packing_fraction = 0.6"),
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

#[test]
fn bench_emd_reports_rates_and_memory() {
    let report = json_of(&[
        "bench",
        "emd",
        "--particles",
        "2000",
        "--packing-fraction",
        "0.1",
        "--events",
        "20000",
        "--repeats",
        "1",
        "--format",
        "json",
    ]);
    assert!(number(&report["collisions_per_second"]) > 0.0);
    assert!(number(&report["events_per_second"]) >= number(&report["collisions_per_second"]));
    let bytes = number(&report["bytes_per_particle"]);
    assert!(bytes > 50.0 && bytes < 400.0, "{bytes}");
    assert_rejected(
        &["bench", "emd", "--packing-fraction", "0.9"],
        "--packing-fraction",
    );
}

/// Runs `haff run` with `args` and checks that it succeeded.
fn run_ok(args: &[&str]) {
    let mut all = vec!["run"];
    all.extend_from_slice(args);
    let out = haff(&all);
    assert!(
        out.status.success(),
        "haff {all:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Runs `toml` uninterrupted and in two chunks (stopped after 6 of 12 samples, resumed),
/// both with check-points every 3 samples, and returns both output directories.
fn run_full_and_chunked(dir: &std::path::Path, toml: &str) -> (PathBuf, PathBuf) {
    std::fs::create_dir_all(dir).unwrap();
    let file = dir.join("ck.toml");
    std::fs::write(&file, toml).unwrap();
    let (full, chunked) = (dir.join("full"), dir.join("chunked"));
    let f = file.to_str().unwrap();
    run_ok(&[
        f,
        "--out",
        full.to_str().unwrap(),
        "--checkpoint-every",
        "3",
    ]);
    run_ok(&[
        f,
        "--out",
        chunked.to_str().unwrap(),
        "--checkpoint-every",
        "3",
        "--stop-after-samples",
        "6",
    ]);
    let partial = std::fs::read_to_string(chunked.join("timeseries.csv")).unwrap();
    assert_eq!(partial.lines().count(), 7);
    run_ok(&["--resume", chunked.to_str().unwrap()]);
    (full, chunked)
}

fn read(dir: &std::path::Path, name: &str) -> String {
    std::fs::read_to_string(dir.join(name)).unwrap()
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

/// `haff run` with a bad file: exit code 2, one line naming `key`.
fn assert_run_rejected(toml: &str, key: &str) {
    // Tests run in parallel threads of one process: one directory per call.
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("haff-bad-run-{}-{call}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("bad.toml");
    std::fs::write(&file, toml).unwrap();
    let out = dir.join("out");
    assert_rejected(
        &[
            "run",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        key,
    );
    assert!(!out.join("timeseries.csv").exists(), "{toml}");
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
            "packing_fraction = 0.4",
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

#[test]
fn bench_dsmc_reports_rates_and_memory() {
    let report = json_of(&[
        "bench",
        "dsmc",
        "--particles",
        "20000",
        "--collisions",
        "0.5",
        "--repeats",
        "1",
        "--threads",
        "2",
        "--format",
        "json",
    ]);
    let total = number(&report["collisions_per_second"]);
    assert!(total > 0.0);
    assert_eq!(number(&report["threads"]), 2.0);
    assert_eq!(
        number(&report["collisions_per_second_per_core"]),
        total / 2.0
    );
    let bytes = number(&report["bytes_per_particle"]);
    assert!((24.0..200.0).contains(&bytes), "{bytes}");
    assert_rejected(&["bench", "dsmc", "--law", "1.5"], "--law");
    assert_rejected(&["bench", "dsmc", "--scheme", "fast"], "--scheme");
    assert_rejected(&["bench", "emd", "--calendar", "tree"], "--calendar");
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

/// `haff rods deterministic`: the solved eps of Eq. (3) last, beside the paper's closed
/// form (right for 1/2 < gamma < 2) and the generalized one (right below 1/2 too);
/// equal rods collide elastically.
#[test]
fn rods_deterministic_solves_eq3() {
    let text = stdout_of(&[
        "rods",
        "deterministic",
        "--gamma",
        "0.3,0.6173,1",
        "--kappa",
        "100",
    ]);
    let (header, rows) = parse_csv(&text);
    assert_eq!(header, "gamma,kappa,closed_form,closed_form_general,eps");
    let (low, mid, equal) = (&rows[0], &rows[1], &rows[2]);
    assert!((mid[4] - mid[2]).abs() < 1e-6, "{mid:?}");
    assert!(
        (low[4] - low[3]).abs() < 1e-3 && (low[4] - low[2]).abs() > 5e-3,
        "{low:?}"
    );
    assert!((equal[4] - 1.0).abs() < 1e-6, "{equal:?}");
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
/// cargo test --release -p haff-cli --test cli -- --ignored ed_mc_against_rod_chain
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
        let v: Value = serde_json::from_str(&read(&chunked, "checkpoint.json")).unwrap();
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
