//! A fuzzing harness that stays (issue 12): valid run files, check-points, study files and
//! particle files are mutated
//! (keys, values, types, truncation, byte flips; check-points also with the checksum
//! fixed after the edit) and fed to the run driver. For every input: no panic; a refusal is
//! an input error (exit 2 in the CLI) with a one-line message; an accepted run produces
//! only finite numbers. The suite runs a modest number of cases; the long run is
//! `cargo test --release -p haff-sim --test fuzz -- --ignored --nocapture` (FUZZ_CASES
//! cases per property, default 50000).

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use sim::{Error, RunDescription, Simulation};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

/// Valid run files of every engine and law (small, so that accepted mutants run fast).
const SEEDS: [&str; 19] = [
    "[system]\ndimension = 3\nparticles = 60\npacking_fraction = 0.1\nseed = 3\n\
     [collision]\nlaw = \"constant\"\nrestitution = 0.8\ntc = 1e-4\n\
     [run]\ncollisions_per_particle = 5\nsamples = 5\nhistogram_at = [0.0, 5.0]\nhistogram_bins = 8\n",
    "[system]\ndimension = 2\nparticles = 50\npacking_fraction = 0.2\n\
     species = [{ diameter = 1.0, mass = 1.0, fraction = 3 }, { diameter = 2.0, mass = 4.0, fraction = 1 }]\n\
     [collision]\nlaw = \"viscoelastic\"\nbeta = 0.3\nform = \"pade:3/6\"\n\
     [run]\nend_time = 2.0\nsamples = 4\nspacing = \"linear\"\n",
    "[system]\nparticles = 80\npacking_fraction = 0.05\n\
     [collision]\nlaw = \"dashpot\"\ndamping_ratio = 0.2\ncriterion = \"naive\"\n\
     [run]\nengine = \"dsmc\"\ndsmc_scheme = \"blocks\"\nblock_size = 16\ncollisions_per_particle = 4\nsamples = 4\n",
    "[system]\nparticles = 80\npacking_fraction = 0.05\n\
     [collision]\nlaw = \"constant\"\nrestitution = 0.5\n\
     [run]\nengine = \"dsmc\"\ndsmc_scheme = \"exact\"\ncollisions_per_particle = 4\nsamples = 4\n",
    "[system]\nparticles = 200\npacking_fraction = 0.05\n\
     [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
     [run]\nengine = \"dsmc\"\ndsmc_scheme = \"spatial\"\ncollisions_per_step = 0.5\ncollisions_per_particle = 3\nsamples = 3\n",
    "[system]\ndimension = 1\nparticles = 40\npacking_fraction = 0.3\n\
     [collision]\nlaw = \"stochastic\"\nmodes = 5\nbath_temperature = 0.5\n\
     [run]\ncollisions_per_particle = 5\nsamples = 4\n",
    "[system]\nparticles = 40\npacking_fraction = 0.1\n\
     [collision]\nlaw = \"viscoelastic\"\nyoung = 1e5\npoisson = 0.3\ndissipative_constant = 0.01\n\
     [run]\nengine = \"soft-sphere\"\nend_time = 0.5\nsamples = 3\nsteps_per_contact = 20\n",
    "[system]\nparticles = 40\npacking_fraction = 0.1\ndiameter = 2e-3\ntemperature = 1e-5\n\
     [collision]\nlaw = \"viscoelastic\"\nmaterial = \"ice\"\ndissipative_constant = 1e-9\n\
     [run]\nengine = \"soft-sphere\"\nend_time = 1e-4\nsamples = 3\ntime_step = 2e-7\n",
    "[system]\ndimension = 2\nparticles = 60\nbox = [20.0, 40.0]\n\
     [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
     [run]\ncollisions_per_particle = 5\nsamples = 4\n\
     [output]\nprofiles = { axis = \"y\", bins = 6 }\n\
     [field]\ngravity = [0.0, -0.5]\n\
     [[wall]]\naxis = \"y\"\nside = \"low\"\nkind = \"thermal\"\ntemperature = 1.5\n\
     [[wall]]\naxis = \"y\"\nside = \"high\"\nkind = \"restitution\"\nrestitution = 0.8\n",
    "[system]\ndimension = 2\nparticles = 50\npacking_fraction = 0.05\n\
     [collision]\nlaw = \"constant\"\nrestitution = 0.9\ntc = 1e-4\n\
     [run]\ncollisions_per_particle = 5\nsamples = 3\n\
     [field]\ngravity = [0.0, -1.0]\nrest_height = 1e-3\n\
     [[wall]]\naxis = \"y\"\nside = \"low\"\nkind = \"vibrating\"\namplitude = 0.3\nfrequency = 1.0\nwaveform = \"triangle\"\n\
     [[wall]]\naxis = \"y\"\nside = \"high\"\nkind = \"elastic\"\n",
    "[system]\ndimension = 2\nparticles = 200\nbox = [40.0, 80.0]\n\
     [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
     [run]\nengine = \"dsmc\"\ndsmc_scheme = \"spatial\"\ncollisions_per_particle = 3\nsamples = 3\n\
     [field]\ngravity = [0.0, -0.1]\n\
     [[wall]]\naxis = \"y\"\nside = \"low\"\nkind = \"restitution\"\nrestitution = 0.5\n\
     [[wall]]\naxis = \"y\"\nside = \"high\"\nkind = \"thermal\"\ntemperature = 1.0\n\
     [output]\nmsd = true\n",
    "[system]\nparticles = 40\npacking_fraction = 0.1\ntemperature = 0.1\n\
     [collision]\nlaw = \"viscoelastic\"\nyoung = 1e5\npoisson = 0.3\ndissipative_constant = 0.01\n\
     [run]\nengine = \"soft-sphere\"\nend_time = 0.5\nsamples = 3\nsteps_per_contact = 20\n\
     [field]\ngravity = [0.0, 0.0, -1.0]\n\
     [[wall]]\naxis = \"z\"\nside = \"low\"\nkind = \"restitution\"\n\
     [[wall]]\naxis = \"z\"\nside = \"high\"\nkind = \"vibrating\"\namplitude = 0.1\nfrequency = 1.0\n\
     [output]\nmsd = true\n",
    "[system]\ndimension = 2\nparticles = 60\npacking_fraction = 0.1\n\
     [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
     [run]\ncollisions_per_particle = 5\nsamples = 4\n\
     [driving]\nkind = \"gaussian-thermostat\"\n\
     [output]\npressure = true\n\
     [shear]\nrate = 0.3\n",
    "[system]\nparticles = 80\npacking_fraction = 0.05\n\
     [collision]\nlaw = \"constant\"\nrestitution = 0.8\n\
     [run]\nengine = \"dsmc\"\ndsmc_scheme = \"blocks\"\nblock_size = 16\ncollisions_per_particle = 4\nsamples = 4\n\
     [shear]\nrate = 0.5\n",
    "[system]\ndimension = 2\nparticles = 40\npacking_fraction = 0.1\n\
     [collision]\nlaw = \"viscoelastic\"\nyoung = 1e5\npoisson = 0.3\ndissipative_constant = 0.01\n\
     [run]\nengine = \"soft-sphere\"\nend_time = 0.5\nsamples = 3\nsteps_per_contact = 20\n\
     [shear]\nrate = 0.4\n",
    "[system]\ndimension = 2\nparticles = 60\npacking_fraction = 0.1\ninertia = 0.3\n\
     rotational_temperature = 0.5\n\
     [collision]\nlaw = \"constant\"\nrestitution = 0.8\ntangential_restitution = 0.4\nfriction = 0.3\n\
     [run]\ncollisions_per_particle = 5\nsamples = 4\n",
    "[system]\nparticles = 80\npacking_fraction = 0.05\n\
     species = [{ diameter = 1.0, mass = 1.0, fraction = 1, inertia = 0.2 }, { diameter = 1.5, mass = 2.0, fraction = 1 }]\n\
     [collision]\nlaw = \"viscoelastic\"\nbeta = 0.3\ntangential_restitution = -0.5\n\
     [run]\nengine = \"dsmc\"\ndsmc_scheme = \"exact\"\ncollisions_per_particle = 4\nsamples = 4\n",
    "[system]\ndimension = 2\nparticles = 40\npacking_fraction = 0.1\ninertia = 0.4\n\
     rotational_temperature = 0.5\n\
     [collision]\nlaw = \"viscoelastic\"\nyoung = 1e5\npoisson = 0.3\ndissipative_constant = 0.01\n\
     friction = 0.5\n\
     [run]\nengine = \"soft-sphere\"\nend_time = 0.5\nsamples = 3\nsteps_per_contact = 20\n",
    "[system]\ndimension = 2\nparticles = 120\nbox = [30.0, 40.0]\ninertia = 0.4\nrotational_temperature = 0.5\n\
     [collision]\nlaw = \"constant\"\nrestitution = 0.8\ntangential_restitution = 0.3\nfriction = 0.4\n\
     [run]\nengine = \"dsmc\"\ndsmc_scheme = \"spatial\"\ncollisions_per_particle = 3\nsamples = 3\n\
     [field]\ngravity = [0.0, -0.1]\n\
     [[wall]]\naxis = \"y\"\nside = \"low\"\nkind = \"restitution\"\nrestitution = 0.7\n\
     [[wall]]\naxis = \"y\"\nside = \"high\"\nkind = \"thermal\"\ntemperature = 1.0\n\
     [output]\nmsd = true\n",
];

/// Keys, in and out of the schema, that mutations insert.
const KEYS: [&str; 60] = [
    "dimension",
    "particles",
    "packing_fraction",
    "diameter",
    "mass",
    "species",
    "temperature",
    "seed",
    "law",
    "restitution",
    "damping_ratio",
    "criterion",
    "beta",
    "form",
    "tc",
    "engine",
    "collisions_per_particle",
    "end_time",
    "samples",
    "spacing",
    "histogram_at",
    "dsmc_scheme",
    "modes",
    "young",
    "poisson",
    "dissipative_constant",
    "material",
    "steps_per_contact",
    "time_step",
    "ranks",
    "colour",
    "axis",
    "side",
    "kind",
    "amplitude",
    "frequency",
    "waveform",
    "profiles",
    "bins",
    "field",
    "gravity",
    "rest_height",
    "box",
    "shear",
    "rate",
    "pressure",
    "msd",
    "inertia",
    "rotational_temperature",
    "tangential_restitution",
    "friction",
    "initial",
    "file",
    "format",
    "frame",
    "run",
    "momentum",
    "density",
    "snapshots",
    "every",
];

/// Values of every TOML type, in and out of range.
const VALUES: [&str; 52] = [
    "0",
    "1",
    "-1",
    "2",
    "3",
    "4",
    "1e300",
    "-1e300",
    "1e-300",
    "nan",
    "inf",
    "-inf",
    "0.5",
    // Dense starts: grown spheres (3D 0.55, 2D 0.75) or refused (box too small for N).
    "0.55",
    "0.75",
    "1.5",
    "1e9",
    "100000000000",
    "\"\"",
    "\"constant\"",
    "\"dsmc\"",
    "\"spatial\"",
    "\"pade:50/1\"",
    "\"series:20\"",
    "\"x\"",
    "true",
    "[]",
    "[1.0, 2.0]",
    "[-1.0]",
    "{ a = 1 }",
    "[{ diameter = 1.0, mass = 1.0, fraction = 0 }]",
    "18446744073709551615",
    "\"z\"",
    "\"low\"",
    "\"high\"",
    "\"elastic\"",
    "\"vibrating\"",
    "\"sawtooth\"",
    "{ axis = \"y\", bins = 8 }",
    "{ axis = \"z\", bins = 0 }",
    "[0.0, -1.0]",
    "{ run = \"/nonexistent/haff\" }",
    "{ file = \"missing.csv\" }",
    "{ file = \"fuzz.toml\", format = \"xyz\", frame = 3 }",
    "\"remove\"",
    "\"lammps-dump\"",
    // output.snapshots and its formats (issue 38), good and bad.
    "\"vtk\"",
    "\"h5md\"",
    "[\"vtk\", \"xyz\"]",
    "[\"xyz\", \"xyz\"]",
    "{ every = 1, format = [\"lammps-dump\", \"xyz\"] }",
    "{ every = 2, format = [] }",
];

/// One mutation of a run file's text.
#[derive(Debug, Clone)]
enum Mutation {
    ReplaceValue {
        line: usize,
        value: usize,
    },
    DeleteLine {
        line: usize,
    },
    InsertKey {
        line: usize,
        key: usize,
        value: usize,
    },
    Truncate {
        at: usize,
    },
    FlipByte {
        at: usize,
        to: u8,
    },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 0..VALUES.len())
            .prop_map(|(line, value)| Mutation::ReplaceValue { line, value }),
        any::<usize>().prop_map(|line| Mutation::DeleteLine { line }),
        (any::<usize>(), 0..KEYS.len(), 0..VALUES.len())
            .prop_map(|(line, key, value)| Mutation::InsertKey { line, key, value }),
        any::<usize>().prop_map(|at| Mutation::Truncate { at }),
        (any::<usize>(), 32u8..127).prop_map(|(at, to)| Mutation::FlipByte { at, to }),
    ]
}

fn mutate(text: &str, mutations: &[Mutation]) -> String {
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let mut text;
    for m in mutations {
        let n = lines.len().max(1);
        match *m {
            Mutation::ReplaceValue { line, value } => {
                if let Some(l) = lines.get_mut(line % n) {
                    if let Some((key, _)) = l.split_once('=') {
                        *l = format!("{key}= {}", VALUES[value]);
                    }
                }
            }
            Mutation::DeleteLine { line } => {
                if !lines.is_empty() {
                    lines.remove(line % n);
                }
            }
            Mutation::InsertKey { line, key, value } => {
                let at = line % (lines.len() + 1);
                lines.insert(at, format!("{} = {}", KEYS[key], VALUES[value]));
            }
            Mutation::Truncate { at } => {
                text = lines.join("\n");
                let cut = at % (text.len() + 1);
                let cut = (0..=cut)
                    .rev()
                    .find(|&c| text.is_char_boundary(c))
                    .unwrap_or(0);
                lines = text[..cut].lines().map(String::from).collect();
            }
            Mutation::FlipByte { at, to } => {
                text = lines.join("\n");
                let mut bytes = text.into_bytes();
                if !bytes.is_empty() {
                    let at = at % bytes.len();
                    bytes[at] = to;
                }
                text = String::from_utf8_lossy(&bytes).into_owned();
                lines = text.lines().map(String::from).collect();
            }
        }
    }
    lines.join("\n") + "\n"
}

/// A refusal is an input error (exit 2 in the CLI) with a one-line message.
fn refused_properly(error: &Error) -> Result<(), String> {
    let message = error.to_string();
    // A numerical failure on accepted input (exit 1) is a finding too.
    if !error.is_input() {
        return Err(format!("not an input error: {message}"));
    }
    if message.contains('\n') || message.is_empty() {
        return Err(format!("not one line: {message:?}"));
    }
    Ok(())
}

/// Whether a valid description is small enough to run in the harness: at most 500
/// particles, 50 samples and (for a stop by time, from the Enskog collision frequency at
/// the initial temperature, an upper estimate for a cooling gas; the smallest mass and
/// largest diameter of a mixture) 20 collisions per particle.
fn small(description: &RunDescription) -> bool {
    let (s, r) = (&description.system, &description.run);
    let (diameter, mass) = match &s.species {
        None => (s.diameter.unwrap_or(1.0), s.mass.unwrap_or(1.0)),
        Some(species) => (
            species.iter().map(|x| x.diameter).fold(0.0, f64::max),
            species.iter().map(|x| x.mass).fold(f64::INFINITY, f64::min),
        ),
    };
    let phi = description.packing_fraction();
    let rate = |d: usize| {
        let volume = match d {
            1 => gas::system::ball_volume::<1>(0.5 * diameter),
            2 => gas::system::ball_volume::<2>(0.5 * diameter),
            _ => gas::system::ball_volume::<3>(0.5 * diameter),
        };
        let density = phi / volume;
        match d {
            1 => gas::theory::collision_frequency::<1>(density, diameter, mass, s.temperature, phi),
            2 => gas::theory::collision_frequency::<2>(density, diameter, mass, s.temperature, phi),
            _ => gas::theory::collision_frequency::<3>(density, diameter, mass, s.temperature, phi),
        }
    };
    let per_particle = match (r.collisions_per_particle, r.end_time) {
        (Some(c), _) => c,
        (_, Some(t)) => t * rate(s.dimension as usize),
        _ => f64::INFINITY,
    };
    s.particles <= 500 && r.samples <= 50 && per_particle <= 20.0
}

/// Every number a run produced is finite.
fn outputs_finite(run: &Simulation) -> Result<(), String> {
    for s in run.samples() {
        let numbers = [
            s.time,
            s.collisions_per_particle,
            s.temperature,
            s.a2,
            s.energy_lost,
            s.pressure,
        ];
        if numbers
            .iter()
            .chain(&s.bath_temperature)
            .any(|x| !x.is_finite())
        {
            return Err(format!("non-finite output: {s:?}"));
        }
    }
    for h in run.histograms() {
        if h.bins
            .iter()
            .any(|(c, d)| !(c.is_finite() && d.is_finite()))
        {
            return Err("non-finite histogram".into());
        }
    }
    Ok(())
}

/// Feeds one run file to the driver: refused properly, or run with finite outputs.
fn check_run_file(text: &str) -> Result<(), String> {
    let description = match RunDescription::from_toml(text, "fuzz.toml".as_ref()) {
        Ok(d) => d,
        Err(e) => return refused_properly(&e),
    };
    if let Err(e) = sim::validate(&description) {
        return refused_properly(&e);
    }
    if !small(&description) {
        return Ok(());
    }
    let mut run = match Simulation::new(&description) {
        Ok(run) => run,
        Err(e) => return refused_properly(&e),
    };
    match run.run(&mut (), None) {
        Ok(_) => outputs_finite(&run),
        Err(e) => refused_properly(&e),
    }
}

/// The longest a case may take (a small run takes milliseconds): beyond it the case hangs.
const HANG: Duration = Duration::from_secs(60);

/// Names the case now running for a watchdog that aborts the process, printing the case,
/// if one case runs longer than [`HANG`] (a hang is a failure, and must not stall the suite).
fn watch(case: String) {
    static CURRENT: Mutex<Option<(Instant, String)>> = Mutex::new(None);
    static WATCHDOG: OnceLock<()> = OnceLock::new();
    *CURRENT.lock().unwrap() = Some((Instant::now(), case));
    WATCHDOG.get_or_init(|| {
        std::thread::spawn(|| loop {
            std::thread::sleep(Duration::from_secs(1));
            if let Some((start, case)) = &*CURRENT.lock().unwrap() {
                if start.elapsed() > HANG {
                    eprintln!("hang: a case ran longer than {HANG:?}: {case}");
                    std::process::abort();
                }
            }
        });
    });
}

/// Every 10000 cases of a long run, a line on stderr (the long run takes minutes).
fn report_progress(what: &str) {
    static CASES: AtomicUsize = AtomicUsize::new(0);
    let n = CASES.fetch_add(1, Ordering::Relaxed) + 1;
    if n.is_multiple_of(10_000) {
        eprintln!("{n} cases ({what})");
    }
}

/// Runs `check` without letting a panic escape: a panic is a failure.
fn no_panic(check: impl FnOnce() -> Result<(), String>) -> Result<(), String> {
    catch_unwind(AssertUnwindSafe(check)).unwrap_or_else(|p| {
        let what = p
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        Err(format!("panic: {what}"))
    })
}

fn run_files(cases: u32) {
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    });
    let seeds = run_seeds();
    let strategy = (0..seeds.len(), prop::collection::vec(mutation(), 1..4));
    runner
        .run(&strategy, |(seed, mutations)| {
            let text = mutate(&seeds[seed], &mutations);
            watch(format!("run file:\n{text}"));
            report_progress("run files");
            no_panic(|| check_run_file(&text))
                .map_err(|e| TestCaseError::fail(format!("{e}\n--- input:\n{text}")))
        })
        .unwrap();
}

/// The seed run files: [`SEEDS`] and runs from a particle file (`system.initial`, a 2D
/// lattice of 36 spheres written once per process in every text format).
fn run_seeds() -> Vec<String> {
    static FILES: OnceLock<Vec<String>> = OnceLock::new();
    let from_files = FILES.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("haff-fuzz-initial-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let c = sim::particles::Configuration {
            dimension: 2,
            sides: vec![12.0, 12.0],
            positions: (0..36).map(|i| [1.0 + 2.0 * (i % 6) as f64, 1.0 + 2.0 * (i / 6) as f64, 0.0]).collect(),
            velocities: Some((0..36).map(|i| [(i as f64).sin(), (i as f64).cos(), 0.0]).collect()),
            diameters: Some(vec![1.2; 36]),
            masses: None,
            species: None,
            spins: None,
            time: None,
        };
        [("csv", "lattice.csv"), ("lammps-dump", "lattice.dump"), ("xyz", "lattice.xyz")]
            .iter()
            .map(|(format, name)| {
                let path = dir.join(name);
                let format = sim::particles::Format::parse("format", format).unwrap();
                sim::particles::write(&path, format, &c).unwrap();
                format!(
                    "[system]\ndimension = 2\ninitial = {{ file = {:?}, format = \"{}\", momentum = \"remove\" }}\n\
                     [collision]\nlaw = \"constant\"\nrestitution = 0.8\n\
                     [run]\ncollisions_per_particle = 3\nsamples = 3\n",
                    path.display().to_string(),
                    format.name()
                )
            })
            .collect()
    });
    SEEDS
        .iter()
        .map(|s| s.to_string())
        .chain(from_files.iter().cloned())
        .collect()
}

/// A valid check-point of each seed file (written once per process).
fn checkpoints() -> &'static Vec<(PathBuf, Vec<u8>)> {
    static DIRS: OnceLock<Vec<(PathBuf, Vec<u8>)>> = OnceLock::new();
    DIRS.get_or_init(|| {
        SEEDS
            .iter()
            .enumerate()
            .map(|(k, text)| {
                let dir =
                    std::env::temp_dir().join(format!("haff-fuzz-{}-seed{k}", std::process::id()));
                std::fs::create_dir_all(&dir).unwrap();
                let mut run = Simulation::from_toml(text, "seed.toml".as_ref()).unwrap();
                run.set_checkpoints(&dir, Some(1));
                run.run(&mut (), Some(2)).unwrap();
                let bytes = std::fs::read(dir.join(sim::checkpoint::FILE_NAME)).unwrap();
                (dir, bytes)
            })
            .collect()
    })
}

/// One mutation of a check-point's bytes.
#[derive(Debug, Clone)]
enum Damage {
    Flip {
        at: usize,
        bit: u8,
    },
    Truncate {
        at: usize,
    },
    /// Replace a number in the records JSON, fixing the checksum.
    ForgeRecords {
        at: usize,
        value: usize,
    },
    /// Overwrite 8 bytes of the engine state, fixing the checksum.
    ForgeEngine {
        at: usize,
        with: f64,
    },
}

fn damage() -> impl Strategy<Value = Damage> {
    prop_oneof![
        (any::<usize>(), 0u8..8).prop_map(|(at, bit)| Damage::Flip { at, bit }),
        any::<usize>().prop_map(|at| Damage::Truncate { at }),
        (any::<usize>(), 0..VALUES.len())
            .prop_map(|(at, value)| Damage::ForgeRecords { at, value }),
        (
            any::<usize>(),
            prop_oneof![
                Just(0.0),
                Just(-1.0),
                Just(1e300),
                Just(f64::NAN),
                Just(f64::INFINITY),
                Just(0.5),
                Just(1e-300),
                any::<f64>()
            ]
        )
            .prop_map(|(at, with)| Damage::ForgeEngine { at, with }),
    ]
}

/// Splits a check-point into header, records and engine bytes.
fn split(bytes: &[u8]) -> (serde_json::Value, Vec<u8>, Vec<u8>) {
    let first = bytes.iter().position(|&b| b == b'\n').unwrap();
    let header: serde_json::Value = serde_json::from_slice(&bytes[..first]).unwrap();
    let r = header["records_bytes"].as_u64().unwrap() as usize;
    (
        header,
        bytes[first + 1..first + 1 + r].to_vec(),
        bytes[first + 2 + r..].to_vec(),
    )
}

fn join(mut header: serde_json::Value, records: &[u8], engine: &[u8]) -> Vec<u8> {
    let mut crc = crc32fast::Hasher::new();
    crc.update(records);
    crc.update(engine);
    header["records_bytes"] = records.len().into();
    header["engine_bytes"] = engine.len().into();
    header["crc32"] = crc.finalize().into();
    let mut bytes = serde_json::to_vec(&header).unwrap();
    bytes.push(b'\n');
    bytes.extend(records);
    bytes.push(b'\n');
    bytes.extend(engine);
    bytes
}

fn damaged(good: &[u8], damage: &Damage) -> Vec<u8> {
    match *damage {
        Damage::Flip { at, bit } => {
            let mut b = good.to_vec();
            let at = at % b.len();
            b[at] ^= 1 << bit;
            b
        }
        Damage::Truncate { at } => good[..at % good.len()].to_vec(),
        Damage::ForgeRecords { at, value } => {
            let (header, records, engine) = split(good);
            let text = String::from_utf8(records).unwrap();
            // Replace the digits of one number (found from a random place on).
            let start = at % text.len();
            let Some(i) = text[start..]
                .find(|c: char| c.is_ascii_digit())
                .map(|i| i + start)
            else {
                return good.to_vec();
            };
            let end = text[i..]
                .find(|c: char| !(c.is_ascii_digit() || "+-.eE".contains(c)))
                .map_or(text.len(), |e| e + i);
            let forged = format!("{}{}{}", &text[..i], VALUES[value], &text[end..]);
            join(header, forged.as_bytes(), &engine)
        }
        Damage::ForgeEngine { at, with } => {
            let (header, records, mut engine) = split(good);
            if engine.len() >= 8 {
                let at = at % (engine.len() - 7);
                engine[at..at + 8].copy_from_slice(&with.to_le_bytes());
            }
            join(header, &records, &engine)
        }
    }
}

/// Feeds one damaged check-point to the driver: refused properly, or (a harmless edit)
/// continued with finite outputs.
fn check_checkpoint(dir: &Path, bytes: &[u8]) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
    std::fs::write(dir.join(sim::checkpoint::FILE_NAME), bytes).map_err(|e| e.to_string())?;
    let mut run = match Simulation::resume(dir) {
        Ok(run) => run,
        Err(e) => return refused_properly(&e),
    };
    if !small(run.description()) {
        return Ok(());
    }
    match run.run(&mut (), None) {
        Ok(_) => outputs_finite(&run),
        Err(e) => refused_properly(&e),
    }
}

fn check_points(cases: u32) {
    let seeds = checkpoints();
    static CASE: AtomicUsize = AtomicUsize::new(0);
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    });
    let strategy = (0..SEEDS.len(), damage());
    runner
        .run(&strategy, |(seed, damage)| {
            let bytes = damaged(&seeds[seed].1, &damage);
            watch(format!("check-point of seed {seed}, {damage:?}"));
            report_progress("check-points");
            let case = CASE.fetch_add(1, Ordering::Relaxed);
            let dir =
                std::env::temp_dir().join(format!("haff-fuzz-{}-case{case}", std::process::id()));
            let result = no_panic(|| check_checkpoint(&dir, &bytes));
            std::fs::remove_dir_all(&dir).ok();
            result.map_err(|e| TestCaseError::fail(format!("{e}\n--- damage: {damage:?}")))
        })
        .unwrap();
}

fn cases_from_env(default: u32) -> u32 {
    std::env::var("FUZZ_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(default)
}

/// Study files (`sim::study`): the seed study, its keys (`base`, `seeds`, `[vary]`,
/// `[[zip]]`) and their values mutated; reading and checking every point must refuse
/// properly or succeed, never panic.
const STUDY: &str = "seeds = 3\n[vary]\n\"collision.restitution\" = [0.5, 0.9]\n\
                     [[zip]]\n\"run.samples\" = [3, 4]\n\"run.collisions_per_particle\" = [2, 3]\n\
                     [base.system]\nparticles = 50\npacking_fraction = 0.05\nseed = 4\n\
                     [base.collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
                     [base.run]\ncollisions_per_particle = 2\nsamples = 3\n";

fn check_study(text: &str) -> Result<(), String> {
    let refused = |e: Error| refused_properly(&e);
    let study = match sim::study::Study::from_toml(text, Path::new("study.toml")) {
        Ok(study) => study,
        Err(e) => return refused(e),
    };
    if study.runs() > 10_000 {
        return Ok(());
    }
    study.check_runs().or_else(refused)?;
    for (_, message) in study.invalid_points() {
        if message.contains('\n') {
            return Err(format!("not one line: {message:?}"));
        }
    }
    Ok(())
}

#[test]
fn mutated_study_files_never_panic() {
    let mut runner = TestRunner::new(Config {
        cases: 200,
        failure_persistence: None,
        ..Config::default()
    });
    let strategy = prop::collection::vec(mutation(), 1..4);
    runner
        .run(&strategy, |mutations| {
            let text = mutate(STUDY, &mutations);
            no_panic(|| check_study(&text))
                .map_err(|e| TestCaseError::fail(format!("{e}\n--- input:\n{text}")))
        })
        .unwrap();
}

/// Particle files (`sim::particles`, issue 38): a small configuration written in every
/// format, its lines mutated (values replaced, lines deleted or inserted, the file cut,
/// bytes flipped); reading (2D and 3D, first and last frame) and checking must succeed or
/// refuse properly naming the file, never panic or hang.
fn particle_seeds() -> Vec<(sim::particles::Format, String)> {
    use sim::particles::{self, Configuration, Format};
    let n = 27;
    let positions: Vec<[f64; 3]> = (0..n)
        .map(|i| {
            [
                1.0 + 2.0 * (i % 3) as f64,
                1.0 + 2.0 * ((i / 3) % 3) as f64,
                1.0 + 2.0 * (i / 9) as f64,
            ]
        })
        .collect();
    let c = Configuration {
        dimension: 3,
        sides: vec![6.0; 3],
        positions,
        velocities: Some((0..n).map(|i| [i as f64, -0.5, 0.25]).collect()),
        diameters: Some(vec![0.9; n]),
        masses: Some(vec![1.5; n]),
        species: Some((0..n).map(|i| i % 2).collect()),
        spins: Some(vec![[0.1, 0.2, 0.3]; n]),
        time: None,
    };
    let dir = std::env::temp_dir().join(format!("haff-fuzz-particles-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let seeds = [
        Format::Csv,
        Format::LammpsDump,
        Format::Xyz,
        Format::LammpsData,
        Format::Vtk,
    ]
    .into_iter()
    .map(|format| {
        let path = dir.join("seed");
        particles::write(&path, format, &c).unwrap();
        (format, std::fs::read_to_string(&path).unwrap())
    })
    .collect();
    std::fs::remove_dir_all(&dir).ok();
    seeds
}

fn check_particle_file(
    path: &Path,
    format: sim::particles::Format,
    text: &str,
) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| e.to_string())?;
    for dimension in [2, 3] {
        for frame in [0, -1] {
            let read = sim::particles::read(path, format, dimension, frame)
                .and_then(|c| c.check(path, false));
            if let Err(e) = read {
                refused_properly(&e)?;
                let message = e.to_string();
                if !message.starts_with(&path.display().to_string()) {
                    return Err(format!("does not name the file: {message}"));
                }
            }
        }
    }
    Ok(())
}

#[test]
fn mutated_particle_files_never_panic() {
    particle_files(300);
}

fn particle_files(cases: u32) {
    let seeds = particle_seeds();
    let path = std::env::temp_dir().join(format!("haff-fuzz-particle-{}", std::process::id()));
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    });
    let strategy = (0..seeds.len(), prop::collection::vec(mutation(), 1..4));
    runner
        .run(&strategy, |(seed, mutations)| {
            let (format, text) = &seeds[seed];
            let text = mutate(text, &mutations);
            watch(format!("particle file:\n{text}"));
            no_panic(|| check_particle_file(&path, *format, &text))
                .map_err(|e| TestCaseError::fail(format!("{e}\n--- input:\n{text}")))
        })
        .unwrap();
    std::fs::remove_file(&path).ok();
}

/// H5MD files (binary; the feature `h5md`): a written file cut short or with bytes
/// overwritten (anywhere: superblock, metadata, data); reading must succeed or refuse
/// properly naming the file, never panic.
#[cfg(feature = "h5md")]
#[test]
fn damaged_h5md_files_never_panic() {
    use sim::particles::Format;
    let (_, seed) = &particle_seeds()[0];
    let dir = std::env::temp_dir().join(format!("haff-fuzz-h5md-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let source = dir.join("seed.csv");
    std::fs::write(&source, seed).unwrap();
    let c = sim::particles::read(&source, Format::Csv, 3, -1).unwrap();
    let good = dir.join("seed.h5");
    sim::particles::write(&good, Format::H5md, &c).unwrap();
    let bytes = std::fs::read(&good).unwrap();
    let path = dir.join("damaged.h5");
    let mut runner = TestRunner::new(Config {
        cases: 200,
        failure_persistence: None,
        ..Config::default()
    });
    let strategy = (
        any::<bool>(),
        prop::collection::vec((any::<usize>(), any::<u8>()), 1..6),
    );
    runner
        .run(&strategy, |(cut, edits)| {
            let mut damaged = bytes.clone();
            if cut {
                damaged.truncate(edits[0].0 % bytes.len());
            } else {
                for (at, to) in &edits {
                    let n = damaged.len();
                    damaged[at % n] = *to;
                }
            }
            std::fs::write(&path, &damaged).unwrap();
            watch(format!("h5md file, cut {cut}, edits {edits:?}"));
            no_panic(|| {
                for dimension in [2, 3] {
                    for frame in [0, -1] {
                        let read = sim::particles::read(&path, Format::H5md, dimension, frame)
                            .and_then(|c| c.check(&path, false));
                        if let Err(e) = read {
                            refused_properly(&e)?;
                            if !e.to_string().starts_with(&path.display().to_string()) {
                                return Err(format!("does not name the file: {e}"));
                            }
                        }
                    }
                }
                Ok(())
            })
            .map_err(|e| TestCaseError::fail(format!("{e}\n--- cut {cut}, edits {edits:?}")))
        })
        .unwrap();
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn mutated_run_files_never_panic() {
    run_files(300);
}

#[test]
fn damaged_check_points_never_panic() {
    check_points(300);
}

#[test]
#[ignore]
fn mutated_inputs_at_length() {
    let cases = cases_from_env(50_000);
    run_files(cases);
    check_points(cases);
    particle_files(cases);
    eprintln!(
        "{cases} mutated run files, {cases} damaged check-points and {cases} mutated particle \
         files: no panic"
    );
}
