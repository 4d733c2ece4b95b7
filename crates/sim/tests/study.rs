//! Studies (`sim::study`): the aggregates against the runs' own files, a study killed and
//! continued against one never interrupted, failing points, the study directory's
//! ownership.

use sim::study::{self, Study};
use std::path::{Path, PathBuf};

const BASE: &str = "[system]\nparticles = 60\npacking_fraction = 0.05\nseed = 3\n\
                    [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
                    [run]\ncollisions_per_particle = 4\nsamples = 5\n";

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("haff-study-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A study file beside `gas.toml` in `dir`.
fn study_in(dir: &Path, vary: &str, seeds: u64) -> Study {
    std::fs::write(dir.join("gas.toml"), BASE).unwrap();
    let text = format!("base = \"gas.toml\"\nseeds = {seeds}\n[vary]\n{vary}\n");
    std::fs::write(dir.join("study.toml"), &text).unwrap();
    Study::from_path(&dir.join("study.toml")).unwrap()
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Oracle: each ensemble row's mean and standard error recomputed here from the replicas'
/// `timeseries.csv` files (sample standard deviation over sqrt(n)), to 1e-12 relative
/// (the same sums in another order).
#[test]
fn the_aggregate_is_the_mean_and_standard_error_of_the_runs_files() {
    let dir = scratch("aggregate");
    let study = study_in(&dir, "\"collision.restitution\" = [0.6, 0.9]", 3);
    study.check_runs().unwrap();
    let out = dir.join("out");
    study::open_study_dir(&out, &study, false).unwrap();
    let outcomes = study::execute(&study, &out, 2, 1, None, &[], &());
    assert_eq!(outcomes.len(), 6);
    assert!(
        outcomes.iter().all(|o| o.state == "complete"),
        "{outcomes:?}"
    );
    let aggregates = study::aggregate(&study, &out, &outcomes, &[]).unwrap();
    let ensemble = read(&out.join("ensemble.csv"));
    let mut lines = ensemble.lines();
    assert_eq!(
        lines.next().unwrap(),
        "point,collision.restitution,sample,time,collisions_per_particle,quantity,mean,\
         standard_error,replicas"
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), aggregates.rows.len());
    let mut checked = 0;
    for (point, eps) in [(0, "0.6"), (1, "0.9")] {
        let series: Vec<(Vec<String>, Vec<Vec<f64>>)> = [3, 4, 5]
            .iter()
            .map(|seed| {
                let text = read(&study::run_dir(&out, point, *seed).join("timeseries.csv"));
                let mut lines = text.lines();
                let header = lines.next().unwrap().split(',').map(String::from).collect();
                let rows = lines
                    .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
                    .collect();
                (header, rows)
            })
            .collect();
        let header = &series[0].0;
        for row in rows.iter().filter(|r| r[0] == point.to_string()) {
            assert_eq!(row[1], eps);
            let sample: usize = row[2].parse().unwrap();
            let column = header.iter().position(|c| c == row[5]).unwrap();
            let values: Vec<f64> = series.iter().map(|(_, r)| r[sample][column]).collect();
            let mean = values.iter().sum::<f64>() / 3.0;
            let sd = (values.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / 2.0).sqrt();
            let error = sd / 3f64.sqrt();
            let (m, e): (f64, f64) = (row[6].parse().unwrap(), row[7].parse().unwrap());
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-300);
            assert!(close(m, mean), "{row:?}: mean {mean}");
            assert!(
                close(e, error) || (e == 0.0 && error == 0.0),
                "{row:?}: error {error}"
            );
            assert_eq!(row[8], "3");
            checked += 1;
        }
    }
    // Every column but time and collisions_per_particle, at every sample of the files.
    let first = read(&study::run_dir(&out, 0, 3).join("timeseries.csv"));
    let quantities = first.lines().next().unwrap().split(',').count() - 2;
    let samples = first.lines().count() - 1;
    assert_eq!(checked, 2 * samples * quantities);
    let json: serde_json::Value = serde_json::from_str(&read(&out.join("study.json"))).unwrap();
    assert_eq!(json["runs_complete"], 6);
    let t = &json["points"][1]["summary"]["final.temperature"];
    assert!(t["mean"].as_f64().unwrap() > 0.0 && t["standard_error"].as_f64().unwrap() > 0.0);
}

/// A study stopped part-way (two runs complete, one interrupted after its first
/// check-point, one never started) and continued gives byte-identical run outputs and
/// ensemble to a study never interrupted. Oracle: the uninterrupted study.
#[test]
fn a_study_continued_equals_one_never_interrupted() {
    let dir = scratch("continued");
    let study = study_in(&dir, "\"collision.restitution\" = [0.7, 0.8]", 2);
    let whole = dir.join("whole");
    study::open_study_dir(&whole, &study, false).unwrap();
    let outcomes = study::execute(&study, &whole, 1, 1, None, &[], &());
    study::aggregate(&study, &whole, &outcomes, &[]).unwrap();

    let parts = dir.join("parts");
    study::open_study_dir(&parts, &study, false).unwrap();
    // Point 0 complete; point 1 seed 3 interrupted after 2 samples (as a killed run
    // leaves it: manifest running, a check-point); point 1 seed 4 never started.
    for replica in 0..2 {
        study::run_one(&study, &parts, 0, replica, 1, None);
    }
    let interrupted = study::run_dir(&parts, 1, 3);
    std::fs::create_dir_all(&interrupted).unwrap();
    let description = study.run_description(&study.points[1], 0).unwrap();
    let hash = sim::outdir::run_hash(&description);
    sim::outdir::OutputDir::claim(&interrupted, "run", &hash, false).unwrap();
    let mut run = sim::Simulation::new(&description).unwrap();
    run.set_checkpoints(&interrupted, Some(1));
    run.set_output_dir(&interrupted);
    run.run(&mut (), Some(2)).unwrap();
    drop(run);
    assert!(interrupted.join("checkpoint.bin").exists());

    study::open_study_dir(&parts, &study, false).unwrap();
    let again = study::execute(&study, &parts, 2, 1, None, &[], &());
    let kept: Vec<bool> = again.iter().map(|o| o.kept).collect();
    let resumed: Vec<bool> = again.iter().map(|o| o.resumed).collect();
    assert_eq!(kept, [true, true, false, false]);
    assert_eq!(resumed, [false, false, true, false]);
    study::aggregate(&study, &parts, &again, &[]).unwrap();
    for point in 0..2 {
        for seed in [3, 4] {
            for file in ["timeseries.csv", "haff-run.json"] {
                let a = read(&study::run_dir(&whole, point, seed).join(file));
                let b = read(&study::run_dir(&parts, point, seed).join(file));
                assert_eq!(a, b, "{point}/{seed}/{file}");
            }
        }
    }
    assert_eq!(
        read(&whole.join("ensemble.csv")),
        read(&parts.join("ensemble.csv"))
    );
}

/// A study directory belongs to one study: another study is refused without --force,
/// a directory of foreign files always; a failing point is reported and the others run.
#[test]
fn the_directory_is_one_studys_and_failures_stay_local() {
    let dir = scratch("owner");
    let study = study_in(&dir, "\"collision.restitution\" = [0.7, 1.5, 0.9]", 1);
    let e = study.check_runs().unwrap_err().to_string();
    assert!(e.contains("point 1") && e.contains("restitution"), "{e}");
    let invalid = study.invalid_points();
    assert_eq!(invalid.iter().map(|(p, _)| *p).collect::<Vec<_>>(), [1]);
    let out = dir.join("out");
    study::open_study_dir(&out, &study, false).unwrap();
    let outcomes = study::execute(&study, &out, 2, 1, None, &[1], &());
    assert_eq!(outcomes.len(), 2);
    assert!(outcomes.iter().all(|o| o.state == "complete"));
    let aggregates = study::aggregate(&study, &out, &outcomes, &invalid).unwrap();
    assert_eq!(aggregates.study["invalid_points"][0]["point"], 1);
    assert_eq!(aggregates.study["points"][1]["replicas"], 0);

    let other = study_in(&dir, "\"collision.restitution\" = [0.5]", 1);
    let e = study::open_study_dir(&out, &other, false)
        .unwrap_err()
        .to_string();
    assert!(e.contains("another study") && e.contains("--force"), "{e}");
    study::open_study_dir(&out, &other, true).unwrap();
    assert!(!out.join("runs/002").exists() && !out.join("ensemble.csv").exists());
    let foreign = dir.join("foreign");
    std::fs::create_dir_all(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "mine").unwrap();
    let e = study::open_study_dir(&foreign, &other, true)
        .unwrap_err()
        .to_string();
    assert!(e.contains("notes.txt"), "{e}");
}

/// By default a run of a study check-points once a minute of wall-clock time: a run of a
/// few milliseconds writes none; `checkpoint_every` = 1 writes one at every sample (the
/// last one kept). Oracle: the files present.
#[test]
fn a_short_run_of_a_study_writes_no_checkpoint_by_default() {
    let dir = scratch("spacing");
    let study = study_in(&dir, "\"collision.restitution\" = [0.8]", 2);
    let out = dir.join("out");
    study::open_study_dir(&out, &study, false).unwrap();
    let by_default = study::run_one(&study, &out, 0, 0, 1, None);
    let every = study::run_one(&study, &out, 0, 1, 1, Some(1));
    assert!(by_default.error.is_none() && every.error.is_none());
    assert!(!study::run_dir(&out, 0, 3).join("checkpoint.bin").exists());
    assert!(study::run_dir(&out, 0, 4).join("checkpoint.bin").exists());
}
