//! `haff run RUN.toml [--out DIR]`: a granular-gas run described by a TOML file.
//!
//! Schema (unknown keys and out-of-range values are rejected before the run, naming the key):
//!
//! ```toml
//! [system]
//! dimension = 3            # 1, 2 or 3
//! particles = 4000         # >= 2
//! packing_fraction = 0.05  # 0 < phi <= 0.45 (3D), 0.7 (2D), 0.9 (1D)
//! diameter = 1.0
//! mass = 1.0
//! # or, instead of diameter and mass, a mixture (number fractions, normalized):
//! # species = [{ diameter = 1.0, mass = 1.0, fraction = 0.5 },
//! #            { diameter = 1.4, mass = 2.744, fraction = 0.5 }]
//! temperature = 1.0        # initial T = m <v^2> / d
//! seed = 1
//! [collision]
//! law = "constant"         # constant | dashpot | viscoelastic
//! restitution = 0.9        # constant: 0 <= eps <= 1
//! # dashpot: damping_ratio = R, criterion = "improved" | "naive"
//! # viscoelastic: beta = 0.1, form = "exact" | "fast" | "pade:M/N" | "series:K"
//! tc = 0.0                 # TC model: elastic if either partner collided < tc ago (0: off)
//! [run]
//! engine = "event-driven"  # event-driven | dsmc
//! # dsmc: dsmc_scheme = "blocks" | "exact" | "spatial", block_size = 4096 (blocks),
//! #       collisions_per_step = 1 (blocks; spatial: 0.2) or time_step = DT,
//! #       collision_cell_width = W (spatial)
//! collisions_per_particle = 500   # or end_time = ...
//! samples = 200
//! spacing = "log"          # log | linear
//! histogram_at = [0.0, 50.0, 500.0]  # velocity histograms (unit of the stop criterion)
//! histogram_bins = 60      # 4 ..= 10000
//! ```
//!
//! `system.species` replaces `diameter` and `mass` (giving both is an error): each species
//! has a diameter and a mass (finite, > 0) and a fraction (> 0) of the particles; the
//! counts are the normalized fractions times N, rounded so that they sum to N (every
//! species needs at least one particle). The box holds the total sphere volume at the
//! packing fraction; every species starts Maxwellian at `temperature` (the total exactly);
//! above phi = 0.3 the initial lattice needs a spacing of at least the largest diameter.
//! `collision.tc` (finite, >= 0) is the contact duration of the TC model of Luding &
//! McNamara against inelastic collapse. `run.histogram_at` lists values in [0, end] of
//! the stop criterion (collisions per particle or time); the run stops exactly there as at
//! a sample target.
//!
//! Writes `DIR/timeseries.csv` (header `time,collisions_per_particle,temperature,a2,...`;
//! for a mixture a2 weights c^2 by the mass), `DIR/summary.json` and
//! `DIR/temperature.png` (T(t), log-log, with Haff's law for a constant eps), with a
//! progress bar (events/s) on a terminal. With `run.histogram_at`, also
//! `DIR/velocity_histograms.csv` (header
//! `target,time,collisions_per_particle,c,density,maxwellian`, one row per bin): the
//! histogram of the scaled peculiar velocity components c = (v_k - <v>_k) / sqrt(2 T / m_i)
//! on [-5, 5], normalized by the number of components N d (so it integrates to the fraction
//! inside the range), next to the Maxwellian exp(-c^2) / sqrt(pi). With
//! `--checkpoint-every K` the state is saved every K samples to `DIR/checkpoint.json` (with
//! the TC model's last collision times and the histograms so far), and
//! `haff run --resume DIR` continues from it: the engine is synchronized at every check-point
//! (all particles brought to the same time, every event predicted afresh), so a resumed
//! run repeats the uninterrupted one with the same settings bit for bit.

use crate::engine::{Counters, DsmcSetup, DsmcState, Engine, EngineState};
use crate::error::{CliError, CliResult};
use crate::RunArgs;
use gas::observe::{sonine_a2, temperature, velocity_histogram};
use gas::{init, EventDriven};
use restitution::dashpot::DashpotCriterion;
use restitution::{Constant, Dashpot, Glauber, Restitution, ScaledForm, Viscoelastic};
use serde::{Deserialize, Serialize};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RunFile {
    system: SystemSection,
    collision: CollisionSection,
    run: RunSection,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct SystemSection {
    #[serde(default = "three")]
    dimension: u32,
    particles: usize,
    packing_fraction: f64,
    /// 1.0 unless `species` is given (filled in by [`normalize`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    diameter: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    mass: Option<f64>,
    /// A mixture instead of `diameter` and `mass`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    species: Option<Vec<SpeciesEntry>>,
    #[serde(default = "one")]
    temperature: f64,
    #[serde(default = "seed")]
    seed: u64,
}

/// One entry of `system.species`.
#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct SpeciesEntry {
    diameter: f64,
    mass: f64,
    /// Number fraction (normalized over the species).
    fraction: f64,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct CollisionSection {
    law: String,
    restitution: Option<f64>,
    damping_ratio: Option<f64>,
    criterion: Option<String>,
    beta: Option<f64>,
    form: Option<String>,
    /// Contact duration of the TC model (0 or absent: off).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    tc: Option<f64>,
    /// Stochastic law (Giese): "glauber" (Eq. 7, default) or "tabulated" (from Eq. 3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    distribution: Option<String>,
    /// Stochastic law: internal vibration modes per particle.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    modes: Option<u32>,
    /// Stochastic law: initial bath temperature of every particle (default 0: cold).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    bath_temperature: Option<f64>,
    /// Stochastic tabulated law: a table written by `haff rods table`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    table: Option<String>,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RunSection {
    #[serde(default = "event_driven")]
    engine: String,
    collisions_per_particle: Option<f64>,
    end_time: Option<f64>,
    #[serde(default = "samples")]
    samples: usize,
    #[serde(default = "log")]
    spacing: String,
    /// Where to write velocity histograms (unit of the stop criterion).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    histogram_at: Option<Vec<f64>>,
    /// Bins of the velocity histograms (default [`HISTOGRAM_BINS`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    histogram_bins: Option<usize>,
    /// DSMC: "blocks" (default), "exact" (homogeneous) or "spatial".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    dsmc_scheme: Option<String>,
    /// DSMC blocks: particles per block.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    block_size: Option<usize>,
    /// DSMC blocks / spatial: collisions per particle per step (or `time_step`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    collisions_per_step: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    time_step: Option<f64>,
    /// Spatial DSMC: width of the collision cells.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    collision_cell_width: Option<f64>,
}

/// Default number of bins of a velocity histogram.
const HISTOGRAM_BINS: usize = 60;
/// Velocity histograms cover the scaled components -C_MAX <= c < C_MAX.
const C_MAX: f64 = 5.0;

/// The defaults that depend on other keys: diameter = mass = 1 without species (so that the
/// parameters in summary.json name them as before).
fn normalize(file: &mut RunFile) {
    let s = &mut file.system;
    if s.species.is_none() {
        s.diameter.get_or_insert(1.0);
        s.mass.get_or_insert(1.0);
    }
}

fn three() -> u32 {
    3
}
fn one() -> f64 {
    1.0
}
fn seed() -> u64 {
    1
}
fn event_driven() -> String {
    "event-driven".into()
}
fn samples() -> usize {
    200
}
fn log() -> String {
    "log".into()
}

/// A bad key: `section.key = value: allowed ...`.
fn bad_key(key: &str, value: impl std::fmt::Display, allowed: &str) -> CliError {
    CliError::argument(key, format!("{value} is out of range; allowed: {allowed}"))
}

fn positive(key: &str, x: f64) -> CliResult<f64> {
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(bad_key(key, x, "a finite number > 0"))
    }
}

/// How far the run goes.
#[derive(Debug, Clone, Copy)]
enum Stop {
    Collisions(f64),
    Time(f64),
}

/// Checks every key before anything runs.
fn validate(file: &RunFile) -> CliResult<Stop> {
    let s = &file.system;
    if !(1..=3).contains(&s.dimension) {
        return Err(bad_key("system.dimension", s.dimension, "1, 2 or 3"));
    }
    if s.particles < 2 || s.particles > 100_000_000 {
        return Err(bad_key("system.particles", s.particles, "2 <= N <= 1e8"));
    }
    let max_phi = [0.9, 0.7, 0.45][s.dimension as usize - 1];
    if !(s.packing_fraction > 0.0 && s.packing_fraction <= max_phi) {
        let allowed = format!("0 < phi <= {max_phi} in {} dimensions", s.dimension);
        return Err(bad_key(
            "system.packing_fraction",
            s.packing_fraction,
            &allowed,
        ));
    }
    match &s.species {
        None => {
            positive("system.diameter", s.diameter.unwrap_or(1.0))?;
            positive("system.mass", s.mass.unwrap_or(1.0))?;
        }
        Some(_) if s.diameter.is_some() || s.mass.is_some() => {
            return Err(CliError::argument(
                "system.species",
                "give either system.species or system.diameter/system.mass, not both",
            ));
        }
        Some(species) => {
            if species.is_empty() {
                return Err(CliError::argument(
                    "system.species",
                    "give at least one species",
                ));
            }
            for (k, x) in species.iter().enumerate() {
                positive(&format!("system.species[{k}].diameter"), x.diameter)?;
                positive(&format!("system.species[{k}].mass"), x.mass)?;
                positive(&format!("system.species[{k}].fraction"), x.fraction)?;
            }
            init::species_counts(s.particles, &to_species(species))
                .map_err(|e| CliError::argument("system.species", e))?;
        }
    }
    positive("system.temperature", s.temperature)?;
    validate_stochastic(file)?;
    if let Some(tc) = file.collision.tc {
        if !(tc.is_finite() && tc >= 0.0) {
            return Err(bad_key("collision.tc", tc, "a finite number >= 0 (0: off)"));
        }
    }
    let r = &file.run;
    match r.engine.as_str() {
        "event-driven" => {
            for (key, given) in [
                ("run.dsmc_scheme", r.dsmc_scheme.is_some()),
                ("run.block_size", r.block_size.is_some()),
                ("run.collisions_per_step", r.collisions_per_step.is_some()),
                ("run.time_step", r.time_step.is_some()),
                ("run.collision_cell_width", r.collision_cell_width.is_some()),
            ] {
                if given {
                    return Err(CliError::argument(key, "only for run.engine = \"dsmc\""));
                }
            }
        }
        "dsmc" => {
            if file.collision.tc.is_some_and(|tc| tc > 0.0) {
                return Err(CliError::argument(
                    "collision.tc",
                    "the TC model is for run.engine = \"event-driven\" (DSMC has no collapse)",
                ));
            }
            dsmc_setup(r)?;
        }
        other => {
            return Err(CliError::argument(
                "run.engine",
                format!("'{other}': allowed: event-driven, dsmc"),
            ))
        }
    }
    if !(2..=1_000_000).contains(&r.samples) {
        return Err(bad_key("run.samples", r.samples, "2 <= samples <= 1e6"));
    }
    if r.spacing != "log" && r.spacing != "linear" {
        return Err(CliError::argument(
            "run.spacing",
            format!("'{}': allowed: log, linear", r.spacing),
        ));
    }
    let stop = match (r.collisions_per_particle, r.end_time) {
        (Some(c), None) => Stop::Collisions(positive("run.collisions_per_particle", c)?),
        (None, Some(t)) => Stop::Time(positive("run.end_time", t)?),
        _ => {
            return Err(CliError::argument(
                "run.collisions_per_particle",
                "give exactly one of run.collisions_per_particle and run.end_time",
            ))
        }
    };
    if let Some(bins) = r.histogram_bins {
        if !(4..=10_000).contains(&bins) {
            return Err(bad_key("run.histogram_bins", bins, "4 <= bins <= 10000"));
        }
    }
    if let Some(at) = &r.histogram_at {
        let (end, unit) = match stop {
            Stop::Collisions(c) => (c, "run.collisions_per_particle"),
            Stop::Time(t) => (t, "run.end_time"),
        };
        if at.len() > 10_000 {
            return Err(bad_key(
                "run.histogram_at",
                format!("a list of {}", at.len()),
                "at most 10000 values",
            ));
        }
        for &x in at {
            if !(0.0..=end).contains(&x) {
                let allowed = format!("0 <= value <= {end} (the end of the run, {unit})");
                return Err(bad_key("run.histogram_at", x, &allowed));
            }
        }
        let mut sorted = at.clone();
        sorted.sort_by(f64::total_cmp);
        if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
            return Err(CliError::argument(
                "run.histogram_at",
                format!("{} appears twice", w[0]),
            ));
        }
    }
    Ok(stop)
}

/// The stochastic keys: only with law = "stochastic", which runs event-driven only.
fn validate_stochastic(file: &RunFile) -> CliResult {
    let c = &file.collision;
    if c.law != "stochastic" {
        for (key, given) in [
            ("collision.distribution", c.distribution.is_some()),
            ("collision.modes", c.modes.is_some()),
            ("collision.bath_temperature", c.bath_temperature.is_some()),
            ("collision.table", c.table.is_some()),
        ] {
            if given {
                return Err(CliError::argument(key, "only for law = \"stochastic\""));
            }
        }
        return Ok(());
    }
    if file.run.engine != "event-driven" {
        return Err(CliError::argument(
            "run.engine",
            "law = \"stochastic\" runs with engine = \"event-driven\" (Giese's ED + Monte Carlo)",
        ));
    }
    if let Some(t) = c.bath_temperature {
        if !(t.is_finite() && t >= 0.0) {
            return Err(bad_key(
                "collision.bath_temperature",
                t,
                "a finite number >= 0",
            ));
        }
    }
    Ok(())
}

fn to_species(entries: &[SpeciesEntry]) -> Vec<init::Species> {
    entries
        .iter()
        .map(|x| init::Species {
            diameter: x.diameter,
            mass: x.mass,
            fraction: x.fraction,
        })
        .collect()
}

/// The DSMC engine and options of the `[run]` section (checked).
fn dsmc_setup(r: &RunSection) -> CliResult<DsmcSetup> {
    use gas::dsmc::{Scheme, SpatialOptions, StepSize};
    let step = match (r.collisions_per_step, r.time_step) {
        (None, None) => StepSize::Auto,
        (Some(c), None) => {
            if !(c.is_finite() && c > 0.0 && c <= 100.0) {
                return Err(bad_key("run.collisions_per_step", c, "0 < value <= 100"));
            }
            StepSize::CollisionsPerParticle(c)
        }
        (None, Some(dt)) => StepSize::Fixed(positive("run.time_step", dt)?),
        (Some(_), Some(_)) => {
            return Err(CliError::argument(
                "run.time_step",
                "give at most one of run.collisions_per_step and run.time_step",
            ))
        }
    };
    let scheme = r.dsmc_scheme.as_deref().unwrap_or("blocks");
    let exclusive = |key: &str, given: bool| -> CliResult {
        if given {
            Err(CliError::argument(
                key,
                format!("not used by run.dsmc_scheme = \"{scheme}\""),
            ))
        } else {
            Ok(())
        }
    };
    match scheme {
        "blocks" => {
            exclusive("run.collision_cell_width", r.collision_cell_width.is_some())?;
            let block_size = r.block_size.unwrap_or(gas::dsmc::DEFAULT_BLOCK_SIZE);
            if !(2..=u32::MAX as usize).contains(&block_size) {
                return Err(bad_key(
                    "run.block_size",
                    block_size,
                    "2 <= block_size <= 2^32 - 1",
                ));
            }
            Ok(DsmcSetup::Homogeneous(Scheme::Blocks { block_size, step }))
        }
        "exact" => {
            exclusive("run.block_size", r.block_size.is_some())?;
            exclusive("run.collision_cell_width", r.collision_cell_width.is_some())?;
            exclusive("run.collisions_per_step", r.collisions_per_step.is_some())?;
            exclusive("run.time_step", r.time_step.is_some())?;
            Ok(DsmcSetup::Homogeneous(Scheme::Exact))
        }
        "spatial" => {
            exclusive("run.block_size", r.block_size.is_some())?;
            let cell_width = r
                .collision_cell_width
                .map(|w| positive("run.collision_cell_width", w))
                .transpose()?;
            Ok(DsmcSetup::Spatial(SpatialOptions { cell_width, step }))
        }
        other => Err(CliError::argument(
            "run.dsmc_scheme",
            format!("'{other}': allowed: blocks, exact, spatial"),
        )),
    }
}

/// The collision law of the `[collision]` section.
fn build_law(c: &CollisionSection) -> CliResult<Box<dyn Restitution>> {
    fn lib(key: &'static str) -> impl Fn(restitution::Error) -> CliError {
        move |e| CliError::library(key, e)
    }
    let need = |key: &str, x: Option<f64>| {
        x.ok_or_else(|| CliError::argument(key, "missing for this law"))
    };
    let criterion = |text: &Option<String>| -> CliResult<DashpotCriterion> {
        let c: restitution::Criterion = text
            .as_deref()
            .unwrap_or("improved")
            .parse()
            .map_err(lib("collision.criterion"))?;
        Ok(c.into())
    };
    match c.law.as_str() {
        "constant" => {
            let eps = need("collision.restitution", c.restitution)?;
            Ok(Box::new(
                Constant::new(eps).map_err(lib("collision.restitution"))?,
            ))
        }
        "dashpot" => {
            let ratio = need("collision.damping_ratio", c.damping_ratio)?;
            let law = Dashpot::new(ratio, criterion(&c.criterion)?, None)
                .map_err(lib("collision.damping_ratio"))?;
            Ok(Box::new(law))
        }
        "viscoelastic" => {
            let beta = need("collision.beta", c.beta)?;
            let form: ScaledForm = c
                .form
                .as_deref()
                .unwrap_or("fast")
                .parse()
                .map_err(lib("collision.form"))?;
            Ok(Box::new(
                Viscoelastic::new(beta, form).map_err(lib("collision.beta"))?,
            ))
        }
        "stochastic" => stochastic_law(c),
        other => Err(CliError::argument(
            "collision.law",
            format!("'{other}': allowed: constant, dashpot, viscoelastic, stochastic"),
        )),
    }
}

/// Giese's stochastic law: `collision.distribution`, `modes` and, tabulated, `table`.
fn stochastic_law(c: &CollisionSection) -> CliResult<Box<dyn Restitution>> {
    let modes = c
        .modes
        .ok_or_else(|| CliError::argument("collision.modes", "missing for law = \"stochastic\""))?;
    let lib = |key: &'static str| move |e: restitution::Error| CliError::library(key, e);
    match c.distribution.as_deref().unwrap_or("glauber") {
        "glauber" => {
            if c.table.is_some() {
                return Err(CliError::argument(
                    "collision.table",
                    "only for distribution = \"tabulated\"",
                ));
            }
            Ok(Box::new(
                Glauber::new(modes).map_err(lib("collision.modes"))?,
            ))
        }
        "tabulated" => {
            let path = c.table.as_deref().ok_or_else(|| {
                CliError::argument("collision.table", "missing: a table from `haff rods table`")
            })?;
            tabulated_law(Path::new(path), modes, "collision.table")
        }
        other => Err(CliError::argument(
            "collision.distribution",
            format!("'{other}': allowed: glauber, tabulated"),
        )),
    }
}

/// The tabulated stochastic law from a table of `haff rods table` (errors name `key`).
pub fn tabulated_law(path: &Path, modes: u32, key: &str) -> CliResult<Box<dyn Restitution>> {
    let fail = |e: String| CliError::argument(key, format!("{}: {e}", path.display()));
    let text = std::fs::read_to_string(path).map_err(|e| fail(e.to_string()))?;
    let table: rods::stochastic::Table =
        serde_json::from_str(&text).map_err(|e| fail(e.to_string()))?;
    Ok(Box::new(table.law(modes).map_err(|e| fail(e.to_string()))?))
}

/// One row of timeseries.csv.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct Sample {
    time: f64,
    collisions_per_particle: f64,
    temperature: f64,
    a2: f64,
    energy_lost: f64,
    pressure: f64,
    events: u64,
    /// Stochastic law: mean bath temperature of the particles.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    bath_temperature: Option<f64>,
}

/// A velocity histogram taken at one of `run.histogram_at`.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct Histogram {
    target: f64,
    time: f64,
    collisions_per_particle: f64,
    /// (bin centre, density).
    bins: Vec<(f64, f64)>,
}

/// The state of a run at a sample boundary (`DIR/checkpoint.json`).
#[derive(Debug, Clone, Serialize, Deserialize)]
struct Checkpoint {
    file: RunFile,
    /// Samples written so far (the next target is `samples.len()`).
    samples: Vec<Sample>,
    time: f64,
    /// Side of the periodic box.
    length: f64,
    positions: Vec<Vec<f64>>,
    velocities: Vec<Vec<f64>>,
    radii: Vec<f64>,
    masses: Vec<f64>,
    counts: Vec<u64>,
    collisions: u64,
    events: u64,
    energy_lost: f64,
    virial: f64,
    last_virial: (f64, f64),
    /// Check-point interval of the run (reused on resume).
    every: Option<usize>,
    /// TC model: each particle's last collision time (null before its first); absent
    /// without the TC model.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    tc_last: Option<Vec<Option<f64>>>,
    /// Velocity histograms taken so far.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    histograms: Vec<Histogram>,
    /// Collisions the TC model made elastic so far.
    #[serde(default)]
    tc_elastic: u64,
    /// DSMC: the engine's state beyond its particles (`events` then counts candidates).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    dsmc: Option<DsmcState>,
    /// Stochastic law: the particles' baths and the position of their random stream.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    baths: Option<BathRecord>,
}

/// [`gas::BathState`] in a check-point.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct BathRecord {
    temperatures: Vec<f64>,
    seed: u64,
    draws: u64,
}

/// `haff run`.
pub fn run(args: &RunArgs) -> CliResult {
    let (file, out, resume) = match (&args.file, &args.resume) {
        (Some(path), None) => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| CliError::argument("RUN.toml", format!("{}: {e}", path.display())))?;
            let file: RunFile = toml::from_str(&text).map_err(|e| {
                CliError::argument(&path.display().to_string(), one_line(&e.to_string()))
            })?;
            let out = args.out.clone().unwrap_or_else(|| default_out(path));
            (file, out, None)
        }
        (None, Some(dir)) => {
            let path = dir.join("checkpoint.json");
            let text = std::fs::read_to_string(&path)
                .map_err(|e| CliError::argument("--resume", format!("{}: {e}", path.display())))?;
            let checkpoint: Checkpoint = serde_json::from_str(&text)
                .map_err(|e| CliError::argument("--resume", format!("{}: {e}", path.display())))?;
            (
                checkpoint.file.clone(),
                args.out.clone().unwrap_or(dir.clone()),
                Some(checkpoint),
            )
        }
        _ => {
            return Err(CliError::argument(
                "RUN.toml",
                "give a run file or --resume DIR (exactly one)",
            ))
        }
    };
    let mut file = file;
    let stop = validate(&file)?;
    normalize(&mut file);
    let law = build_law(&file.collision)?;
    let every = match &args.checkpoint_every {
        Some(text) => Some(crate::output::parse_count(
            "--checkpoint-every",
            text,
            1,
            1_000_000,
        )?),
        None => resume.as_ref().and_then(|c| c.every),
    };
    let stop_after = match &args.stop_after_samples {
        Some(text) => Some(crate::output::parse_count(
            "--stop-after-samples",
            text,
            1,
            1_000_000,
        )?),
        None => None,
    };
    std::fs::create_dir_all(&out)
        .map_err(|e| CliError::argument("--out", format!("{}: {e}", out.display())))?;
    let start = Instant::now();
    let context = RunContext {
        file: &file,
        stop,
        every,
        stop_after,
        out: &out,
    };
    let (samples, histograms, tally) = match file.system.dimension {
        1 => simulate::<1>(&context, law, resume)?,
        2 => simulate::<2>(&context, law, resume)?,
        _ => simulate::<3>(&context, law, resume)?,
    };
    let wall = start.elapsed().as_secs_f64();
    write_timeseries(&out.join("timeseries.csv"), &samples)?;
    if file
        .run
        .histogram_at
        .as_ref()
        .is_some_and(|at| !at.is_empty())
    {
        write_histograms(&out.join("velocity_histograms.csv"), &histograms)?;
    }
    plot_temperature(&out.join("temperature.png"), &file, &samples)?;
    let summary = serde_json::json!({
        "parameters": file,
        "collisions": tally.collisions,
        "events": tally.events,
        "tc_elastic_collisions": tally.tc_elastic,
        "wall_seconds": wall,
        "events_per_second": tally.events as f64 / wall,
        "collisions_per_second": tally.collisions as f64 / wall,
        "final": samples.last(),
    });
    let mut f = std::fs::File::create(out.join("summary.json"))?;
    serde_json::to_writer_pretty(&mut f, &summary)?;
    writeln!(f)?;
    eprintln!(
        "haff run: {} collisions, {} events in {wall:.2} s ({:.3e} events/s); output in {}",
        tally.collisions,
        tally.events,
        tally.events as f64 / wall,
        out.display()
    );
    Ok(())
}

fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// RUN.toml -> ./RUN (next to the current directory).
fn default_out(file: &Path) -> PathBuf {
    PathBuf::from(
        file.file_stem()
            .map_or("haff-run".into(), |s| s.to_os_string()),
    )
}

/// Sample targets (collisions per particle or time) from 0 to `end`.
fn targets(end: f64, count: usize, log: bool) -> Vec<f64> {
    let first = end * 1e-3;
    (0..count)
        .map(|k| {
            let x = k as f64 / (count - 1) as f64;
            match (k, log) {
                (0, _) => 0.0,
                (_, true) if k == count - 1 => end,
                (_, true) => {
                    first * (end / first).powf((k as f64 - 1.0) / (count - 2).max(1) as f64)
                }
                (_, false) => end * x,
            }
        })
        .collect()
}

/// A point where the run stops to observe: a row of timeseries.csv, a velocity histogram
/// or both.
#[derive(Debug, Clone, Copy)]
struct Target {
    /// Collisions per particle or time.
    value: f64,
    /// Index of the sample taken here.
    sample: Option<usize>,
    /// Whether a velocity histogram is taken here.
    histogram: bool,
}

/// The sample targets and the histogram targets merged in order (a histogram at a sample
/// target is taken at that stop).
fn schedule(samples: &[f64], histograms: &[f64]) -> Vec<Target> {
    let mut histograms = histograms.to_vec();
    histograms.sort_by(f64::total_cmp);
    let mut h = histograms.into_iter().peekable();
    let mut out = Vec::with_capacity(samples.len() + h.len());
    for (k, &value) in samples.iter().enumerate() {
        while let Some(x) = h.next_if(|&x| x < value) {
            out.push(Target {
                value: x,
                sample: None,
                histogram: true,
            });
        }
        out.push(Target {
            value,
            sample: Some(k),
            histogram: h.next_if(|&x| x == value).is_some(),
        });
    }
    out.extend(h.map(|value| Target {
        value,
        sample: None,
        histogram: true,
    }));
    out
}

/// What the sampling loop needs besides the engine.
struct RunContext<'a> {
    file: &'a RunFile,
    stop: Stop,
    /// Write a check-point every this many samples.
    every: Option<usize>,
    /// End the run (after its check-point) once this many samples exist.
    stop_after: Option<usize>,
    out: &'a Path,
}

/// The initial particles of the `[system]` section.
fn initial_system<const D: usize>(file: &RunFile) -> CliResult<gas::System<D>> {
    let s = &file.system;
    let fail = |e: String| CliError::argument("system", e);
    match &s.species {
        // DSMC particles are points: no need to place them without overlaps.
        None if file.run.engine == "dsmc" => {
            let diameter = s.diameter.unwrap_or(1.0);
            let volume = s.particles as f64 * gas::system::ball_volume::<D>(0.5 * diameter)
                / s.packing_fraction;
            gas::dsmc::point_gas::<D>(
                s.particles,
                volume.powf(1.0 / D as f64),
                diameter,
                s.mass.unwrap_or(1.0),
                s.temperature,
                s.seed,
            )
        }
        None => init::monodisperse::<D>(
            s.particles,
            s.packing_fraction,
            s.diameter.unwrap_or(1.0),
            s.mass.unwrap_or(1.0),
            s.temperature,
            s.seed,
        ),
        Some(species) => init::polydisperse::<D>(
            s.particles,
            s.packing_fraction,
            &to_species(species),
            s.temperature,
            s.seed,
        ),
    }
    .map_err(fail)
}

/// The engine state stored in a check-point.
fn checkpoint_state<const D: usize>(c: &Checkpoint) -> CliResult<EngineState<D>> {
    let vector = |v: &Vec<f64>| -> CliResult<[f64; D]> {
        v.as_slice()
            .try_into()
            .map_err(|_| CliError::argument("--resume", "check-point of another dimension"))
    };
    Ok(EngineState {
        time: c.time,
        system: gas::System {
            length: c.length,
            positions: c.positions.iter().map(vector).collect::<CliResult<_>>()?,
            velocities: c.velocities.iter().map(vector).collect::<CliResult<_>>()?,
            radii: c.radii.clone(),
            masses: c.masses.clone(),
        },
        counts: c.counts.clone(),
        counters: Counters {
            collisions: c.collisions,
            events: c.events,
            energy_lost: c.energy_lost,
            virial: c.virial,
            tc_elastic: c.tc_elastic,
        },
        // -inf (no collision yet) is stored as null: JSON has no infinities.
        tc_last: c.tc_last.as_ref().map(|last| {
            last.iter()
                .map(|t| t.unwrap_or(f64::NEG_INFINITY))
                .collect()
        }),
        dsmc: c.dsmc.clone(),
    })
}

/// A fresh engine from the `[system]` section, or one restored from a check-point.
fn start_engine<const D: usize>(
    file: &RunFile,
    law: Box<dyn Restitution>,
    resume: &Option<Checkpoint>,
) -> CliResult<Engine<D>> {
    let s = &file.system;
    let fail = |e: String| CliError::argument("system", e);
    if file.run.engine == "dsmc" {
        let setup = dsmc_setup(&file.run)?;
        let (phi, seed) = (s.packing_fraction, s.seed);
        let resumed = |e: String| CliError::argument("--resume", e);
        return match resume {
            None => Engine::dsmc(initial_system::<D>(file)?, phi, law, seed, setup).map_err(fail),
            Some(c) => Engine::restore_dsmc(checkpoint_state::<D>(c)?, phi, law, seed, setup)
                .map_err(resumed),
        };
    }
    let (mut engine, tc_last) = match resume {
        None => (
            EventDriven::new(initial_system::<D>(file)?, law).map_err(fail)?,
            None,
        ),
        Some(c) => {
            let state = checkpoint_state::<D>(c)?;
            let tally = gas::emd::Tally {
                collisions: state.counters.collisions,
                events: state.counters.events,
                energy_lost: state.counters.energy_lost,
                virial: state.counters.virial,
                tc_elastic: state.counters.tc_elastic,
            };
            let engine = EventDriven::restore(state.system, law, state.time, state.counts, tally)
                .map_err(fail)?;
            (engine, state.tc_last)
        }
    };
    if file.collision.law == "stochastic" {
        let bath_state = match resume.as_ref().and_then(|c| c.baths.clone()) {
            Some(b) => gas::BathState {
                temperatures: b.temperatures,
                seed: b.seed,
                draws: b.draws,
            },
            None => gas::BathState {
                temperatures: vec![file.collision.bath_temperature.unwrap_or(0.0); s.particles],
                seed: s.seed,
                draws: 0,
            },
        };
        engine
            .set_bath_state(bath_state)
            .map_err(|e| CliError::argument("collision.bath_temperature", e))?;
    }
    if let Some(tc) = file.collision.tc {
        engine
            .set_tc_model(tc, tc_last)
            .map_err(|e| CliError::argument("collision.tc", e))?;
    }
    Ok(Engine::EventDriven(Box::new(engine)))
}

fn write_checkpoint<const D: usize>(
    context: &RunContext,
    engine: &mut Engine<D>,
    samples: &[Sample],
    histograms: &[Histogram],
    last_virial: (f64, f64),
) -> CliResult {
    let state = engine.state();
    let system = &state.system;
    let checkpoint = Checkpoint {
        file: context.file.clone(),
        samples: samples.to_vec(),
        time: state.time,
        length: system.length,
        positions: system.positions.iter().map(|p| p.to_vec()).collect(),
        velocities: system.velocities.iter().map(|v| v.to_vec()).collect(),
        radii: system.radii.clone(),
        masses: system.masses.clone(),
        counts: state.counts,
        collisions: state.counters.collisions,
        events: state.counters.events,
        energy_lost: state.counters.energy_lost,
        virial: state.counters.virial,
        tc_elastic: state.counters.tc_elastic,
        last_virial,
        every: context.every,
        tc_last: state
            .tc_last
            .map(|last| last.iter().map(|&t| t.is_finite().then_some(t)).collect()),
        histograms: histograms.to_vec(),
        dsmc: state.dsmc,
        baths: engine.bath_state().map(|b| BathRecord {
            temperatures: b.temperatures,
            seed: b.seed,
            draws: b.draws,
        }),
    };
    crate::output::write_checkpoint(context.out, &checkpoint)
}

fn simulate<const D: usize>(
    context: &RunContext,
    law: Box<dyn Restitution>,
    resume: Option<Checkpoint>,
) -> CliResult<(Vec<Sample>, Vec<Histogram>, Counters)> {
    let file = context.file;
    let mut engine = start_engine::<D>(file, law, &resume)?;
    let n = file.system.particles as f64;
    let log = file.run.spacing == "log";
    let (end, by_time) = match context.stop {
        Stop::Collisions(c) => (c, false),
        Stop::Time(t) => (t, true),
    };
    let bins = file.run.histogram_bins.unwrap_or(HISTOGRAM_BINS);
    let plan = schedule(
        &targets(end, file.run.samples, log),
        file.run.histogram_at.as_deref().unwrap_or(&[]),
    );
    let (mut samples, mut histograms, mut last) = match resume {
        Some(c) => (c.samples, c.histograms, c.last_virial),
        None => (Vec::new(), Vec::new(), (0.0, 0.0)),
    };
    // A check-point is written right after a sample: continue after that sample's stop.
    let done = match samples.len() {
        0 => 0,
        k => plan
            .iter()
            .position(|target| target.sample == Some(k - 1))
            .map_or(plan.len(), |i| i + 1),
    };
    if plan[..done].iter().filter(|t| t.histogram).count() != histograms.len() {
        return Err(CliError::argument(
            "--resume",
            "the check-point's histograms do not match run.histogram_at",
        ));
    }
    let progress = indicatif::ProgressBar::new(file.run.samples as u64);
    progress.set_style(
        indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} samples {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    progress.set_position(samples.len() as u64);
    let started = Instant::now();
    for target in &plan[done..] {
        if by_time {
            engine.run_until(target.value);
        } else {
            let want = (target.value * n / 2.0).round() as u64;
            let have = engine.counters().collisions;
            engine.run_collisions(want.saturating_sub(have));
        }
        if let Some(t) = engine.collapsed() {
            progress.finish_and_clear();
            return Err(CliError::argument(
                "collision.tc",
                format!(
                    "inelastic collapse at t = {t}: {} collisions per particle without time \
                     advancing; switch on the TC model (collision.tc > 0)",
                    gas::emd::COLLAPSE_COLLISIONS_PER_PARTICLE
                ),
            ));
        }
        let tally = engine.counters();
        let (time, cpp) = (engine.time(), engine.collisions_per_particle());
        if target.histogram {
            histograms.push(Histogram {
                target: target.value,
                time,
                collisions_per_particle: cpp,
                bins: velocity_histogram(engine.system(), bins, C_MAX),
            });
        }
        if target.sample.is_none() {
            continue;
        }
        let weight = engine.weight();
        let system = engine.system();
        let t = temperature(system);
        let volume = system.volume();
        let dt = time - last.0;
        let virial = if dt > 0.0 {
            weight * (tally.virial - last.1) / (D as f64 * volume * dt)
        } else {
            0.0
        };
        samples.push(Sample {
            time,
            collisions_per_particle: cpp,
            temperature: t,
            a2: sonine_a2(system),
            energy_lost: tally.energy_lost,
            pressure: weight * n / volume * t + virial,
            events: tally.events,
            bath_temperature: engine.bath_state().map(|b| mean(&b.temperatures)),
        });
        last = (time, tally.virial);
        if context.every.is_some_and(|k| samples.len() % k == 0) {
            write_checkpoint(context, &mut engine, &samples, &histograms, last)?;
        }
        let rate = tally.events as f64 / started.elapsed().as_secs_f64().max(1e-9);
        progress.set_message(format!("{rate:.3e} events/s, T = {t:.4e}"));
        progress.inc(1);
        if context.stop_after.is_some_and(|k| samples.len() >= k) {
            break;
        }
    }
    progress.finish_and_clear();
    Ok((samples, histograms, engine.counters()))
}

fn write_timeseries(path: &Path, samples: &[Sample]) -> CliResult {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    let baths = samples.iter().any(|s| s.bath_temperature.is_some());
    let extra = if baths { ",bath_temperature" } else { "" };
    writeln!(
        f,
        "time,collisions_per_particle,temperature,a2,energy_lost,pressure,events{extra}"
    )?;
    for s in samples {
        write!(
            f,
            "{},{},{},{},{},{},{}",
            s.time,
            s.collisions_per_particle,
            s.temperature,
            s.a2,
            s.energy_lost,
            s.pressure,
            s.events
        )?;
        match s.bath_temperature {
            Some(t) => writeln!(f, ",{t}")?,
            None => writeln!(f)?,
        }
    }
    Ok(f.flush()?)
}

fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len().max(1) as f64
}

/// velocity_histograms.csv: one row per bin of every histogram, with the Maxwellian
/// exp(-c^2) / sqrt(pi) at the bin centre.
fn write_histograms(path: &Path, histograms: &[Histogram]) -> CliResult {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(
        f,
        "target,time,collisions_per_particle,c,density,maxwellian"
    )?;
    for h in histograms {
        for &(c, density) in &h.bins {
            let maxwellian = (-c * c).exp() / std::f64::consts::PI.sqrt();
            writeln!(
                f,
                "{},{},{},{c},{density},{maxwellian}",
                h.target, h.time, h.collisions_per_particle
            )?;
        }
    }
    Ok(f.flush()?)
}

/// temperature.png: T(t) and, for a constant eps, Haff's law T0 / (1 + zeta0 t / 2)^2 with
/// zeta0 = (1 - eps^2) omega0 / d from the collision frequency omega0 measured over the first
/// samples (Haff 1983; Brilliantov & Pöschel, Kinetic Theory of Granular Gases, Ch. 7).
fn plot_temperature(path: &Path, file: &RunFile, samples: &[Sample]) -> CliResult {
    let points: Vec<(f64, f64)> = samples.iter().map(|s| (s.time, s.temperature)).collect();
    let early = samples.iter().find(|s| s.collisions_per_particle > 0.0);
    let haff = match (
        file.collision.law.as_str(),
        file.collision.restitution,
        early,
    ) {
        ("constant", Some(eps), Some(first)) if eps < 1.0 => {
            let t0 = samples[0].temperature;
            let omega0 = first.collisions_per_particle / first.time;
            let zeta0 = (1.0 - eps * eps) * omega0 / file.system.dimension as f64;
            Some(move |t: f64| t0 / (1.0 + 0.5 * zeta0 * t).powi(2))
        }
        _ => None,
    };
    match &haff {
        Some(f) => crate::plot::temperature(path, &points, Some(("Haff's law", f))),
        None => crate::plot::temperature(path, &points, None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_targets_end_exactly_at_the_end() {
        for count in [2, 3, 12, 200] {
            for log in [true, false] {
                let t = targets(7.3, count, log);
                assert_eq!(t.len(), count);
                assert_eq!((t[0], t[count - 1]), (0.0, 7.3), "{count} {log}");
                assert!(t.windows(2).all(|w| w[0] < w[1]), "{t:?}");
            }
        }
    }

    #[test]
    fn histogram_targets_merge_into_the_samples() {
        let plan = schedule(&[0.0, 1.0, 2.0], &[2.0, 0.5, 0.0, 1.5]);
        let got: Vec<(f64, Option<usize>, bool)> = plan
            .iter()
            .map(|t| (t.value, t.sample, t.histogram))
            .collect();
        assert_eq!(
            got,
            [
                (0.0, Some(0), true),
                (0.5, None, true),
                (1.0, Some(1), false),
                (1.5, None, true),
                (2.0, Some(2), true),
            ]
        );
        assert_eq!(schedule(&[0.0, 1.0], &[]).len(), 2);
    }
}
