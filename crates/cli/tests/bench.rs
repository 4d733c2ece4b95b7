//! `haff bench ...`: the reports (JSON keys, rates, memory) and bad arguments.

mod common;

use common::{assert_rejected, json_of, number};

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
        "fast[]",
        "pade:3/6[]",
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
    // Every collision is an accepted candidate.
    assert!(number(&report["candidates_per_collision"]) >= 1.0);
    // The exact scheme's speed classes: about 1.5 candidates per collision in a
    // near-Maxwellian gas (the count over 5000 collisions is sharp to ~1 %; the blocks'
    // single majorant needs ~4).
    let exact = json_of(&[
        "bench",
        "dsmc",
        "--scheme",
        "exact",
        "--particles",
        "20000",
        "--collisions",
        "0.5",
        "--repeats",
        "1",
        "--format",
        "json",
    ]);
    let per_collision = number(&exact["candidates_per_collision"]);
    assert!((1.0..1.8).contains(&per_collision), "{per_collision}");
    assert_rejected(&["bench", "dsmc", "--law", "1.5"], "--law");
    assert_rejected(&["bench", "dsmc", "--scheme", "fast"], "--scheme");
    assert_rejected(&["bench", "emd", "--calendar", "tree"], "--calendar");
}

#[test]
fn bench_dsmc_runs_the_spatial_scheme() {
    let report = json_of(&[
        "bench",
        "dsmc",
        "--scheme",
        "spatial",
        "--particles",
        "20000",
        "--law",
        "1",
        "--collisions",
        "1",
        "--repeats",
        "1",
        "--format",
        "json",
    ]);
    assert_eq!(report["scheme"], "spatial");
    assert_eq!(number(&report["particles_per_cell"]), 15.6);
    assert!(number(&report["collisions_per_second"]) > 0.0);
    // Rough particles (solid spheres, spins at the temperature).
    let rough = json_of(&[
        "bench",
        "dsmc",
        "--scheme",
        "spatial",
        "--particles",
        "20000",
        "--law",
        "0.8",
        "--tangential-restitution",
        "0.0",
        "--collisions",
        "1",
        "--repeats",
        "1",
        "--format",
        "json",
    ]);
    assert_eq!(rough["tangential_restitution"], "0.0");
    assert!(number(&rough["collisions_per_second"]) > 0.0);
    assert_rejected(
        &[
            "bench",
            "dsmc",
            "--scheme",
            "spatial",
            "--particles-per-cell",
            "0.5",
        ],
        "--particles-per-cell",
    );
}

/// `haff bench soft-sphere`: the default gas and a run file; the time step is the Hertz
/// duration over 50 (gas::soft); a run file that is not a 3D viscoelastic material exits 2.
#[test]
fn bench_soft_sphere_reports_ns_per_particle_step() {
    let json = json_of(&[
        "bench",
        "soft-sphere",
        "--steps",
        "5",
        "--repeats",
        "1",
        "--format",
        "json",
    ]);
    assert_eq!(number(&json["particles"]), 10000.0);
    assert!(number(&json["ns_per_particle_step"]) > 0.0);
    assert!(number(&json["time_step"]) > 0.0);
    let dir = std::env::temp_dir().join(format!("haff-bench-soft-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("constant.toml");
    std::fs::write(
        &file,
        "[system]\nparticles = 100\npacking_fraction = 0.05\n[collision]\nlaw = \"constant\"\n\
         restitution = 0.9\n[run]\nend_time = 1.0\n",
    )
    .unwrap();
    assert_rejected(
        &[
            "bench",
            "soft-sphere",
            file.to_str().unwrap(),
            "--steps",
            "5",
        ],
        "RUN_FILE",
    );
    let _ = std::fs::remove_dir_all(&dir);
}
