//! Nothing silently wrong (issue 12): check-points that are edited, truncated, foreign or
//! of another version are refused (exit 2, one line), even when whoever edited them fixed
//! the checksum; output directories are never shared by two runs. Studies (issue 37): a
//! `haff study` killed with SIGKILL continues to the bytes of one never interrupted; its
//! exit codes.

mod common;

use common::{assert_rejected, haff, read, run_ok};
use serde_json::Value;
use std::path::{Path, PathBuf};

const RUN: &str = "[system]\nparticles = 200\npacking_fraction = 0.05\nseed = 2\n\
                   [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
                   [run]\ncollisions_per_particle = 10\nsamples = 8\n\
                   histogram_at = [0.0, 10.0]\n";

/// A fresh directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("haff-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A run of `RUN` stopped after 4 of its 8 samples with a check-point: its directory.
fn stopped_run(dir: &Path) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let file = dir.join("gas.toml");
    std::fs::write(&file, RUN).unwrap();
    let out = dir.join("out");
    let (f, o) = (file.to_str().unwrap(), out.to_str().unwrap());
    run_ok(&[
        f,
        "--out",
        o,
        "--checkpoint-every",
        "2",
        "--stop-after-samples",
        "4",
    ]);
    out
}

/// The three parts of a check-point: header, records (JSON), engine bytes.
fn parts(out: &Path) -> (Value, Value, Vec<u8>) {
    let bytes = std::fs::read(out.join("checkpoint.bin")).unwrap();
    let first = bytes.iter().position(|&b| b == b'\n').unwrap();
    let header: Value = serde_json::from_slice(&bytes[..first]).unwrap();
    let r = header["records_bytes"].as_u64().unwrap() as usize;
    let records = serde_json::from_slice(&bytes[first + 1..first + 1 + r]).unwrap();
    (header, records, bytes[first + 2 + r..].to_vec())
}

/// Writes a check-point from its parts with a correct checksum and lengths (an edit that
/// only the meaning of the content can reveal).
fn forge(out: &Path, mut header: Value, records: &Value, engine: &[u8]) {
    let records = serde_json::to_vec(records).unwrap();
    let mut crc = crc32fast::Hasher::new();
    crc.update(&records);
    crc.update(engine);
    header["records_bytes"] = records.len().into();
    header["engine_bytes"] = engine.len().into();
    header["crc32"] = crc.finalize().into();
    let mut bytes = serde_json::to_vec(&header).unwrap();
    bytes.push(b'\n');
    bytes.extend(&records);
    bytes.push(b'\n');
    bytes.extend(engine);
    std::fs::write(out.join("checkpoint.bin"), bytes).unwrap();
}

fn resume_rejected(out: &Path, says: &str) {
    let output = haff(&["run", "--resume", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{says}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("--resume") && stderr.contains(says) && !stderr.contains("panicked"),
        "expected '{says}': {stderr}"
    );
}

#[test]
fn damaged_check_points_are_refused() {
    let dir = scratch("damaged");
    let out = stopped_run(&dir);
    let path = out.join("checkpoint.bin");
    let good = std::fs::read(&path).unwrap();
    let (header, records, engine) = parts(&out);
    assert_eq!(header["format"], "haff-run-checkpoint");
    assert_eq!(header["version"], sim::checkpoint::RUN.version);
    // One flipped bit in the engine state, in the records, a truncated or extended file.
    let mut flipped = good.clone();
    let last = flipped.len() - 9;
    flipped[last] ^= 1;
    std::fs::write(&path, &flipped).unwrap();
    resume_rejected(&out, "checksum mismatch");
    let mut edited = good.clone();
    let at = good.len() - engine.len() - 10;
    edited[at] ^= 4;
    std::fs::write(&path, &edited).unwrap();
    resume_rejected(&out, "checksum");
    std::fs::write(&path, &good[..good.len() / 2]).unwrap();
    resume_rejected(&out, "truncated");
    std::fs::write(&path, [&good[..], b"x"].concat()).unwrap();
    resume_rejected(&out, "truncated or was changed");
    std::fs::write(&path, b"{\"not\": \"a check-point\"}").unwrap();
    resume_rejected(&out, "not a haff check-point");
    // Another version names both.
    let mut old = header.clone();
    old["version"] = 2.into();
    forge(&out, old, &records, &engine);
    resume_rejected(&out, "version 2");
    // A check-point of the layout before version 3 (all JSON).
    std::fs::remove_file(&path).unwrap();
    std::fs::write(out.join("checkpoint.json"), "{}").unwrap();
    resume_rejected(&out, "older haff");
    std::fs::remove_file(out.join("checkpoint.json")).unwrap();
    // The intact file still resumes and completes the run.
    std::fs::write(&path, &good).unwrap();
    run_ok(&["--resume", out.to_str().unwrap()]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn check_points_edited_with_a_fixed_checksum_are_refused() {
    let dir = scratch("forged");
    let out = stopped_run(&dir);
    let (header, records, engine) = parts(&out);
    // (what, the edit of the records, what the refusal says)
    type Edit = Box<dyn Fn(&mut Value)>;
    let cases: [(&str, Edit, &str); 6] = [
        (
            "particles",
            Box::new(|r| r["description"]["system"]["particles"] = 300.into()),
            "particles",
        ),
        ("every", Box::new(|r| r["every"] = 0.into()), "every"),
        (
            "samples",
            Box::new(|r| r["description"]["run"]["samples"] = 3.into()),
            "samples",
        ),
        (
            "sample time",
            Box::new(|r| r["timeseries"]["samples"][3]["time"] = (-1.0).into()),
            "sample 3",
        ),
        (
            "phi",
            Box::new(|r| r["description"]["system"]["packing_fraction"] = 0.06.into()),
            "box side",
        ),
        (
            "histograms",
            Box::new(|r| r["histograms"]["histograms"] = Value::Array(vec![])),
            "histograms",
        ),
    ];
    for (what, edit, says) in cases {
        let mut edited = records.clone();
        edit(&mut edited);
        forge(&out, header.clone(), &edited, &engine);
        eprintln!("{what}");
        resume_rejected(&out, says);
    }
    // A position moved out of the box (the engine bytes edited, the checksum fixed): the
    // state starts with the time and the box side (8 bytes each), then the number of
    // positions (200: a 2-byte varint), then the first position's x.
    let mut far = engine.clone();
    let x = 8 + 8 + 2;
    far[x..x + 8].copy_from_slice(&1e300f64.to_le_bytes());
    forge(&out, header.clone(), &records, &far);
    resume_rejected(&out, "positions");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_output_directory_belongs_to_one_run() {
    let dir = scratch("outdir");
    let file = dir.join("gas.toml");
    std::fs::write(&file, RUN).unwrap();
    let (f, out) = (file.to_str().unwrap(), dir.join("out"));
    let o = out.to_str().unwrap();
    run_ok(&[f, "--out", o, "--checkpoint-every", "4"]);
    let manifest: Value = serde_json::from_str(&read(&out, "haff-run.json")).unwrap();
    assert_eq!(manifest["state"], "complete");
    let summary: Value = serde_json::from_str(&read(&out, "summary.json")).unwrap();
    assert_eq!(summary["complete"], true);
    // A second run into it is refused; --force replaces the first run's files, and the
    // second run (without histograms) leaves none of them behind.
    let other = dir.join("other.toml");
    std::fs::write(&other, RUN.replace("histogram_at = [0.0, 10.0]\n", "")).unwrap();
    let g = other.to_str().unwrap();
    assert_rejected(&["run", g, "--out", o], "--out");
    assert!(out.join("velocity_histograms.csv").exists());
    run_ok(&[g, "--out", o, "--force"]);
    assert!(!out.join("velocity_histograms.csv").exists());
    assert!(!out.join("checkpoint.bin").exists());
    // Resuming a check-point whose directory holds another run's outputs is refused.
    let stopped = stopped_run(&dir.join("s"));
    let manifest = read(&out, "haff-run.json");
    std::fs::write(stopped.join("haff-run.json"), manifest).unwrap();
    assert_rejected(&["run", "--resume", stopped.to_str().unwrap()], "--resume");
    // Directories holding anything else are refused, --force or not.
    let foreign = dir.join("foreign");
    std::fs::create_dir_all(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "mine").unwrap();
    for force in [false, true] {
        let mut args = vec!["run", f, "--out", foreign.to_str().unwrap()];
        if force {
            args.push("--force");
        }
        assert_rejected(&args, "--out");
    }
    assert_eq!(read(&foreign, "notes.txt"), "mine");
    assert_rejected(&["run", f, "--out", "/"], "--out");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_stopped_run_says_so() {
    let dir = scratch("stopped");
    let out = stopped_run(&dir);
    let manifest: Value = serde_json::from_str(&read(&out, "haff-run.json")).unwrap();
    assert_eq!(manifest["state"], "stopped");
    let summary: Value = serde_json::from_str(&read(&out, "summary.json")).unwrap();
    assert_eq!(summary["complete"], false);
    run_ok(&["--resume", out.to_str().unwrap()]);
    let summary: Value = serde_json::from_str(&read(&out, "summary.json")).unwrap();
    assert_eq!(summary["complete"], true);
    std::fs::remove_dir_all(&dir).ok();
}

/// A study of three runs long enough (about 0.2 s each) to be killed part-way.
const STUDY_BASE: &str = "[system]\nparticles = 1000\npacking_fraction = 0.05\nseed = 5\n\
                          [collision]\nlaw = \"constant\"\nrestitution = 0.98\n\
                          [run]\ncollisions_per_particle = 400\nsamples = 40\n";

fn study_files(dir: &Path, vary: &str, seeds: u64) -> PathBuf {
    std::fs::write(dir.join("gas.toml"), STUDY_BASE).unwrap();
    let study = dir.join("study.toml");
    std::fs::write(
        &study,
        format!("base = \"gas.toml\"\nseeds = {seeds}\n[vary]\n{vary}\n"),
    )
    .unwrap();
    study
}

/// Every file of a study's runs but their summaries (which hold wall-clock times), and its
/// ensemble, as (relative path, bytes).
fn study_bytes(out: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files = vec![(
        "ensemble.csv".to_string(),
        std::fs::read(out.join("ensemble.csv")).unwrap(),
    )];
    let mut points: Vec<_> = std::fs::read_dir(out.join("runs"))
        .unwrap()
        .flatten()
        .collect();
    points.sort_by_key(|e| e.file_name());
    for point in points {
        let mut seeds: Vec<_> = std::fs::read_dir(point.path()).unwrap().flatten().collect();
        seeds.sort_by_key(|e| e.file_name());
        for seed in seeds {
            let mut names: Vec<_> = std::fs::read_dir(seed.path()).unwrap().flatten().collect();
            names.sort_by_key(|e| e.file_name());
            for file in names {
                let name = file.file_name().to_string_lossy().to_string();
                if name != "summary.json" {
                    let path = file.path();
                    let key = path.strip_prefix(out).unwrap().display().to_string();
                    files.push((key, std::fs::read(&path).unwrap()));
                }
            }
        }
    }
    files
}

/// A study killed with SIGKILL (no chance to clean up) while its second run is part-way
/// and restarted with the same command gives the run files and ensemble of a study never
/// interrupted, byte for byte; the finished run is kept, the interrupted one resumed from
/// its check-point. Oracle: the uninterrupted study.
#[test]
fn a_study_killed_with_sigkill_continues_to_the_same_bytes() {
    let dir = scratch("study-kill");
    let study = study_files(&dir, "\"collision.restitution\" = [0.98]", 3);
    let s = study.to_str().unwrap();
    let whole = dir.join("whole");
    // Check-points at every sample (the default, once a minute, would write none here).
    let w = whole.to_str().unwrap();
    let output = haff(&["study", s, "--out", w, "--checkpoint-every", "1"]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );

    let killed = dir.join("killed");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_haff"))
        .args(["study", s, "--out", killed.to_str().unwrap()])
        .args(["--jobs", "1", "--checkpoint-every", "1"])
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // Killed as soon as the second run (seed 6) has a check-point.
    let second = killed.join("runs/000/6");
    let clock = std::time::Instant::now();
    while !second.join("checkpoint.bin").exists() {
        assert!(
            clock.elapsed().as_secs() < 60,
            "the second run never check-pointed"
        );
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    let manifest: Value = serde_json::from_str(&read(&second, "haff-run.json")).unwrap();
    // The kill lands within milliseconds of the run's first check-point, a third of a
    // second before its end.
    assert_eq!(
        manifest["state"], "running",
        "the second run was not interrupted"
    );

    let k = killed.to_str().unwrap();
    let output = haff(&["study", s, "--out", k, "--checkpoint-every", "1"]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let report: Value = serde_json::from_str(&read(&killed, "study.json")).unwrap();
    let runs = report["runs"].as_array().unwrap();
    assert_eq!(runs[0]["kept"], true, "{runs:?}");
    assert_eq!(runs[1]["resumed"], true, "{runs:?}");
    assert_eq!(runs[2]["kept"], false, "{runs:?}");
    let (a, b) = (study_bytes(&whole), study_bytes(&killed));
    let names = |files: &[(String, Vec<u8>)]| -> Vec<String> {
        files.iter().map(|(name, _)| name.clone()).collect()
    };
    assert_eq!(names(&a), names(&b));
    for ((name, x), (_, y)) in a.iter().zip(&b) {
        assert!(x == y, "{name} differs after the restart");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Exit codes of `haff study`: 2 for bad input, naming the key (and the point), before any
/// run starts; with --keep-going the valid points run, the invalid one is reported and the
/// exit code is still 2; another study's directory needs --force.
#[test]
fn a_study_refuses_bad_input_naming_the_point_and_key() {
    let dir = scratch("study-input");
    let short = STUDY_BASE.replace("400", "4").replace("40\n", "4\n");
    let bad = study_files(&dir, "\"collision.restitution\" = [0.7, 1.5, 0.9]", 1);
    std::fs::write(dir.join("gas.toml"), &short).unwrap();
    let (b, out) = (bad.to_str().unwrap(), dir.join("out"));
    let o = out.to_str().unwrap();
    assert_rejected(&["study", b, "--out", o], "point 1");
    assert_rejected(&["study", b, "--out", o], "collision.restitution");
    assert!(!out.exists(), "a refused study wrote files");
    assert_rejected(&["study", b, "--out", o, "--jobs", "0"], "--jobs");

    let output = haff(&["study", b, "--out", o, "--keep-going"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("point 1") && !stderr.contains("panicked"),
        "{stderr}"
    );
    let report: Value = serde_json::from_str(&read(&out, "study.json")).unwrap();
    assert_eq!(report["invalid_points"][0]["point"], 1);
    assert_eq!(report["runs_complete"], 2);
    let ensemble = read(&out, "ensemble.csv");
    let points: std::collections::BTreeSet<&str> = ensemble
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(points.into_iter().collect::<Vec<_>>(), ["0", "2"]);
    assert!(out.join("figures/temperature.png").exists());

    let good = dir.join("good.toml");
    std::fs::write(
        &good,
        "base = \"gas.toml\"\n[vary]\n\"collision.restitution\" = [0.5]\n",
    )
    .unwrap();
    let g = good.to_str().unwrap();
    assert_rejected(&["study", g, "--out", o], "--force");
    let output = haff(&["study", g, "--out", o, "--force"]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    std::fs::write(&good, "base = \"gas.toml\"\nseeds = 0\n").unwrap();
    assert_rejected(&["study", g, "--out", o], "seeds");
    std::fs::remove_dir_all(&dir).ok();
}
