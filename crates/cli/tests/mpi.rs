//! `mpirun -n R haff run FILE`: the spatial DSMC run (smooth, in a container, rough), and
//! the homogeneous one of the block scheme, on 1, 2 and 4 MPI ranks write the same files,
//! byte for byte, as the run in one process (4 ranks oversubscribe a 2-core
//! machine, which only slows them). Built with the feature `mpi` (`scripts/test` builds and
//! runs it: `cargo test --release -p haff-cli --features mpi --test mpi`); without it, the
//! binary refuses a launch on several ranks and a run file asking for ranks.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const GAS: &str = "[system]\ndimension = 3\nparticles = 6000\npacking_fraction = 0.1\nseed = 5\n\
                   [collision]\nlaw = \"viscoelastic\"\nbeta = 0.2\n\
                   [run]\nengine = \"dsmc\"\ndsmc_scheme = \"spatial\"\n\
                   collisions_per_particle = 30\nsamples = 10\nhistogram_at = [0.0, 30.0]\n";

/// A homogeneous mixture in blocks of 200 (20 blocks).
#[cfg(feature = "mpi")]
const BLOCKS: &str = "[system]\ndimension = 3\nparticles = 4000\npacking_fraction = 0.1\n\
                      seed = 5\nspecies = [{ diameter = 1.0, mass = 1.0, fraction = 0.5 }, \
                      { diameter = 1.4, mass = 2.0, fraction = 0.5 }]\n\
                      [collision]\nlaw = \"viscoelastic\"\nbeta = 0.2\n\
                      [run]\nengine = \"dsmc\"\ndsmc_scheme = \"blocks\"\nblock_size = 200\n\
                      collisions_per_particle = 30\nsamples = 10\nhistogram_at = [0.0, 30.0]\n";

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("haff-mpi-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `haff args` under `mpirun -n ranks` (0: without mpirun).
fn launch(ranks: usize, args: &[&str]) -> Output {
    let haff = env!("CARGO_BIN_EXE_haff");
    let mut command = if ranks == 0 {
        Command::new(haff)
    } else {
        let mut c = Command::new("mpirun");
        c.args(["--oversubscribe", "-n", &ranks.to_string(), haff]);
        // Tests run as root in CI containers; shared-memory transport only (one machine).
        c.env("OMPI_ALLOW_RUN_AS_ROOT", "1")
            .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
            .env("OMPI_MCA_btl", "self,vader")
            .env("OMPI_MCA_btl_vader_single_copy_mechanism", "none");
        c
    };
    command.args(args).output().expect("mpirun (or haff) runs")
}

fn run(ranks: usize, file: &Path, out: &Path) -> Output {
    launch(
        ranks,
        &[
            "run",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
    )
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A scratch directory with the run file `gas` and its run in one process (in
/// `single`): (directory, file, single).
#[cfg(feature = "mpi")]
fn with_single_run(name: &str, gas: &str) -> (PathBuf, PathBuf, PathBuf) {
    let dir = scratch(name);
    let file = dir.join("gas.toml");
    std::fs::write(&file, gas).unwrap();
    let single = dir.join("single");
    let o = run(0, &file, &single);
    assert!(o.status.success(), "{}", stderr(&o));
    (dir, file, single)
}

/// A 2D column in a box with sides (slabs across the walls' axis): a vibrating floor, a
/// thermal ceiling, gravity, profiles.
#[cfg(feature = "mpi")]
const CONTAINER: &str = "[system]\ndimension = 2\nparticles = 4000\nbox = [60.0, 120.0]\nseed = 3\n\
                         [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
                         [run]\nengine = \"dsmc\"\ndsmc_scheme = \"spatial\"\n\
                         collisions_per_particle = 20\nsamples = 6\n\
                         [output]\nprofiles = { axis = \"y\", bins = 12 }\n\
                         [field]\ngravity = [0.0, -0.02]\n\
                         [[wall]]\naxis = \"y\"\nside = \"low\"\nkind = \"vibrating\"\n\
                         amplitude = 0.5\nfrequency = 0.2\n\
                         [[wall]]\naxis = \"y\"\nside = \"high\"\nkind = \"thermal\"\ntemperature = 1.0\n";

#[cfg(feature = "mpi")]
#[test]
fn one_two_and_four_ranks_write_the_same_files() {
    let files = ["timeseries.csv", "velocity_histograms.csv"];
    assert_same_files("same", GAS, 6000, &files);
}

#[cfg(feature = "mpi")]
#[test]
fn blocks_on_one_two_and_four_ranks_write_the_same_files() {
    let files = ["timeseries.csv", "velocity_histograms.csv"];
    assert_same_files("blocks", BLOCKS, 4000, &files);
}

/// Walls and gravity on ranks: each rank streams its particles in the container, the
/// walls' tallies are summed exactly over the ranks.
#[cfg(feature = "mpi")]
#[test]
fn a_container_on_one_two_and_four_ranks_writes_the_same_files() {
    let files = ["timeseries.csv", "walls.csv", "profiles.csv"];
    assert_same_files("container", CONTAINER, 4000, &files);
}

/// Rough particles of the spatial scheme: a mixture with Walton's friction, each
/// species its inertia.
#[cfg(feature = "mpi")]
const ROUGH: &str = "[system]\ndimension = 3\nparticles = 4000\npacking_fraction = 0.1\nseed = 5\n\
                     species = [{ diameter = 1.0, mass = 1.0, fraction = 0.5 }, \
                     { diameter = 1.4, mass = 2.0, fraction = 0.5, inertia = 0.25 }]\n\
                     [collision]\nlaw = \"viscoelastic\"\nbeta = 0.2\n\
                     tangential_restitution = 0.4\nfriction = 0.3\n\
                     [run]\nengine = \"dsmc\"\ndsmc_scheme = \"spatial\"\n\
                     collisions_per_particle = 20\nsamples = 8\n";

/// Rough particles on ranks: the spins travel with their records between the ranks'
/// slabs, the sliding contacts are summed over them; the time series (with
/// `rotational_temperature`) and the species' (theirs per species) are the single
/// process's, byte for byte.
#[cfg(feature = "mpi")]
#[test]
fn rough_particles_on_one_two_and_four_ranks_write_the_same_files() {
    let files = ["timeseries.csv", "species.csv"];
    assert_same_files("rough", ROUGH, 4000, &files);
}

#[cfg(feature = "mpi")]
fn assert_same_files(name: &str, gas: &str, particles: u64, files: &[&str]) {
    let (dir, file, single) = with_single_run(name, gas);
    for ranks in [1, 2, 4] {
        let out = dir.join(format!("ranks{ranks}"));
        let o = run(ranks, &file, &out);
        assert!(o.status.success(), "{ranks} ranks: {}", stderr(&o));
        for &name in files {
            let (a, b) = (
                std::fs::read_to_string(single.join(name)).unwrap(),
                std::fs::read_to_string(out.join(name)).unwrap(),
            );
            assert!(a == b, "{name} differs on {ranks} ranks");
        }
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        if ranks > 1 {
            let p = &summary["parallel"];
            assert_eq!(p["ranks"], ranks);
            let total: u64 = p["per_rank"]
                .as_array()
                .unwrap()
                .iter()
                .map(|r| r["particles"].as_u64().unwrap())
                .sum();
            assert_eq!(total, particles);
            assert!(
                stderr(&o).contains(&format!("{ranks} ranks")),
                "{}",
                stderr(&o)
            );
        } else {
            assert!(summary.get("parallel").is_none());
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A check-point written on 4 ranks resumes on 2, and the run ends as the one in a single
/// process.
#[cfg(feature = "mpi")]
#[test]
fn a_checkpoint_from_4_ranks_resumes_on_2() {
    let (dir, file, single) = with_single_run("resume", GAS);
    let out = dir.join("cut");
    let o = launch(
        4,
        &[
            "run",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--checkpoint-every",
            "3",
            "--stop-after-samples",
            "4",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = launch(2, &["run", "--resume", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (a, b) = (
        std::fs::read_to_string(single.join("timeseries.csv")).unwrap(),
        std::fs::read_to_string(out.join("timeseries.csv")).unwrap(),
    );
    assert!(a == b, "the resumed run differs");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// More ranks than planes of cells, a run file asking for other ranks, an engine that does
/// not spread: exit 2 with the key named, on every rank, no hang.
#[cfg(feature = "mpi")]
#[test]
fn launches_that_cannot_work_exit_2() {
    let dir = scratch("refused");
    let wide = dir.join("wide.toml");
    std::fs::write(&wide, format!("{GAS}collision_cell_width = 10.0\n")).unwrap();
    let o = run(4, &wide, &dir.join("wide"));
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("run.ranks") && stderr(&o).contains("at most"),
        "{}",
        stderr(&o)
    );
    let asks = dir.join("asks.toml");
    std::fs::write(&asks, format!("{GAS}ranks = 3\n")).unwrap();
    let o = run(2, &asks, &dir.join("asks"));
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("mpirun -n 3"), "{}", stderr(&o));
    let emd = dir.join("emd.toml");
    std::fs::write(
        &emd,
        "[system]\nparticles = 100\npacking_fraction = 0.1\n[collision]\nlaw = \"constant\"\n\
         restitution = 0.9\n[run]\ncollisions_per_particle = 1\nsamples = 2\n",
    )
    .unwrap();
    let o = run(2, &emd, &dir.join("emd"));
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("run.engine"), "{}", stderr(&o));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Without the feature: a launch on several ranks (as mpirun announces it) and a run file
/// asking for ranks are refused, exit 2, saying how to build with MPI.
#[cfg(not(feature = "mpi"))]
#[test]
fn without_mpi_ranks_are_refused() {
    let dir = scratch("nompi");
    let file = dir.join("gas.toml");
    std::fs::write(&file, GAS).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_haff"))
        .args(["run", file.to_str().unwrap(), "--out"])
        .arg(dir.join("a"))
        .env("OMPI_COMM_WORLD_SIZE", "2")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--features mpi"), "{}", stderr(&o));
    let asks = dir.join("asks.toml");
    std::fs::write(&asks, format!("{GAS}ranks = 2\n")).unwrap();
    let o = run(0, &asks, &dir.join("b"));
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("run.ranks") && stderr(&o).contains("--features mpi"),
        "{}",
        stderr(&o)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
