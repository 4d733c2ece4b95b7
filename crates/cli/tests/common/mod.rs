//! Helpers shared by the tests of the `haff` binary.
#![allow(dead_code)] // each test binary uses a subset

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs `haff` with `args`.
pub fn haff(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_haff"))
        .args(args)
        .output()
        .expect("the haff binary runs")
}

/// Runs `haff`, checks that it succeeded and returns its stdout.
pub fn stdout_of(args: &[&str]) -> String {
    let output = haff(args);
    assert!(
        output.status.success(),
        "haff {args:?} failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).expect("stdout is UTF-8")
}

/// A CSV document: its header line and its numeric rows.
pub fn parse_csv(text: &str) -> (String, Vec<Vec<f64>>) {
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

pub fn json_of(args: &[&str]) -> Value {
    serde_json::from_str(&stdout_of(args)).expect("valid JSON")
}

pub fn number(value: &Value) -> f64 {
    value.as_f64().expect("a JSON number")
}

/// Bad input: exit code 2 and one line on stderr naming the argument, no panic.
pub fn assert_rejected(args: &[&str], argument: &str) {
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

/// Runs `haff run` with `args` and checks that it succeeded.
pub fn run_ok(args: &[&str]) {
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
pub fn run_full_and_chunked(dir: &std::path::Path, toml: &str) -> (PathBuf, PathBuf) {
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

pub fn read(dir: &std::path::Path, name: &str) -> String {
    std::fs::read_to_string(dir.join(name)).unwrap()
}

/// `haff run` with a bad file: exit code 2, one line naming `key`.
pub fn assert_run_rejected(toml: &str, key: &str) {
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
