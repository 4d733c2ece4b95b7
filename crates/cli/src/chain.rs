//! `haff rods chain RUN.toml`: the rod-chain MD of Giese's Eq. (2) on a ring, and, on
//! request, Giese's event-driven + Monte Carlo gas of the same rods from the same start
//! (1D event-driven engine with a stochastic law and per-particle baths), so that the
//! cooling of the translational energy can be compared.

use crate::error::{CliError, CliResult};
use crate::RunArgs;
use gas::EventDriven;
use restitution::{Glauber, Restitution};
use rods::chain::{Chain, Impacts};
use rods::ring::{equipartition_share, translational_energy, RingSetup, RingState};
use serde::{Deserialize, Serialize};
use sim::plot::{self, Axes};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct ChainFile {
    chain: ChainSection,
    run: ChainRunSection,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct ChainSection {
    /// Number of rods N on the ring.
    rods: usize,
    /// Rod lengths, repeated along the ring (e.g. two lengths: alternating rods).
    #[serde(default = "unit_length")]
    lengths: Vec<f64>,
    /// Internal modes per rod.
    modes: usize,
    /// Ring perimeter (default: twice the total length of the rods).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    perimeter: Option<f64>,
    /// Inverse range alpha of the contact potential B exp(-alpha r).
    alpha: f64,
    /// B of the contact potential [default: m c^2 / (alpha l)^2 of the mean rod].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    strength: Option<f64>,
    #[serde(default = "one")]
    sound_speed: f64,
    #[serde(default = "one")]
    density: f64,
    /// Initial translational temperature: velocities ~ N(0, T/m), zero total momentum.
    temperature: f64,
    /// Initial temperature of the internal modes (default 0: cold rods).
    #[serde(default)]
    bath_temperature: f64,
    #[serde(default = "seed")]
    seed: u64,
    /// Step constant c_h of the contact integrator, h = c_h / (alpha v_ref).
    #[serde(default = "step")]
    step: f64,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct ChainRunSection {
    end_time: f64,
    #[serde(default = "samples")]
    samples: usize,
    /// ED + MC runs from the same start: "glauber" and/or "tabulated".
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    compare: Vec<String>,
    /// Runs from seeds seed, seed + 1, ...; the outputs are their means.
    #[serde(default = "one_repeat")]
    repeats: usize,
    /// Table of `haff rods table` for compare = "tabulated".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    table: Option<PathBuf>,
}

impl ChainSection {
    /// The ring of rods this table describes.
    fn ring(&self) -> RingSetup {
        RingSetup {
            rods: self.rods,
            lengths: self.lengths.clone(),
            modes: self.modes,
            perimeter: self.perimeter,
            alpha: self.alpha,
            strength: self.strength,
            sound_speed: self.sound_speed,
            density: self.density,
            temperature: self.temperature,
            bath_temperature: self.bath_temperature,
            seed: self.seed,
            step: self.step,
        }
    }
}

fn unit_length() -> Vec<f64> {
    vec![1.0]
}
fn one_repeat() -> usize {
    1
}
fn one() -> f64 {
    1.0
}
fn seed() -> u64 {
    1
}
fn step() -> f64 {
    0.05
}
fn samples() -> usize {
    100
}

/// One row of a timeseries: energies summed over the rods.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
struct Row {
    time: f64,
    collisions_per_particle: f64,
    translational_energy: f64,
    bath_energy: f64,
    total_energy: f64,
}

const HEADER: &str = "time,collisions_per_particle,translational_energy,bath_energy,total_energy";

fn bad(key: &str, detail: impl std::fmt::Display) -> CliError {
    CliError::argument(key, detail)
}

/// A rods error about the `[chain]` table: range errors name their key `chain.NAME`.
fn chain_error(error: rods::Error) -> CliError {
    match error {
        rods::Error::OutOfRange {
            name,
            value,
            allowed,
        } => bad(
            &format!("chain.{name}"),
            format!("{value} is out of range; allowed: {allowed}"),
        ),
        other => bad("chain", other),
    }
}

/// Checks the file; returns the ring of rods it describes.
fn validate(file: &ChainFile) -> CliResult<RingSetup> {
    let ring = file.chain.ring();
    ring.validate().map_err(chain_error)?;
    let end_time = file.run.end_time;
    if !(end_time.is_finite() && end_time > 0.0) {
        return Err(bad(
            "run.end_time",
            format!("{end_time} is out of range; allowed: a finite number > 0"),
        ));
    }
    if !(1..=10_000).contains(&file.run.repeats) {
        return Err(bad(
            "run.repeats",
            format!("{}; allowed: 1 <= repeats <= 10000", file.run.repeats),
        ));
    }
    if !(2..=100_000).contains(&file.run.samples) {
        return Err(bad("run.samples", "allowed: 2 <= samples <= 100000"));
    }
    for name in &file.run.compare {
        if name != "glauber" && name != "tabulated" {
            return Err(bad(
                "run.compare",
                format!("'{name}': allowed: glauber, tabulated"),
            ));
        }
    }
    let tabulated = file.run.compare.iter().any(|c| c == "tabulated");
    if tabulated != file.run.table.is_some() {
        return Err(bad(
            "run.table",
            "give a table exactly when compare holds \"tabulated\"",
        ));
    }
    Ok(ring)
}

/// Where a run stands: saved as `DIR/checkpoint.json` after a sample of the chain MD.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct Checkpoint {
    file: ChainFile,
    /// The repeat in progress (0-based).
    repeat: usize,
    /// Its chain MD rows so far, and the chain after the last one.
    rows: Vec<Row>,
    chain: Chain,
    impacts: Impacts,
    /// Sums of the completed repeats (curve 0: chain MD; then one per compared law).
    curves: Vec<(String, Vec<Row>)>,
    chain_seconds: f64,
    /// Check-point interval in samples (reused on resume).
    every: Option<usize>,
}

/// The chain MD of one repeat in progress.
struct ChainRun {
    rows: Vec<Row>,
    chain: Chain,
    impacts: Impacts,
}

/// What the sample loop needs besides the chain.
struct Saving<'a> {
    out: &'a Path,
    every: Option<usize>,
    /// Stop (after a check-point) once this many samples were taken in this process.
    stop_after: Option<usize>,
    taken: usize,
}

/// The rods and their common start, shared by the chain MD and the ED + MC runs.
struct Start<'a> {
    ring: RingSetup,
    state: RingState,
    /// Sampling times.
    targets: &'a [f64],
}

fn parse_file(path: &Path) -> CliResult<ChainFile> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| bad("RUN.toml", format!("{}: {e}", path.display())))?;
    toml::from_str(&text).map_err(|e| {
        let one_line = e
            .to_string()
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ");
        bad("RUN.toml", one_line)
    })
}

fn read_checkpoint(dir: &Path) -> CliResult<Checkpoint> {
    let path = dir.join("checkpoint.json");
    let fail = |e: String| bad("--resume", format!("{}: {e}", path.display()));
    let text = std::fs::read_to_string(&path).map_err(|e| fail(e.to_string()))?;
    serde_json::from_str(&text).map_err(|e| fail(e.to_string()))
}

/// `haff rods chain`.
pub fn run(args: &RunArgs) -> CliResult {
    let count = |flag: &str, text: &Option<String>| {
        text.as_ref()
            .map(|t| crate::output::parse_count(flag, t, 1, 1_000_000))
            .transpose()
    };
    let (file, out, mut resume) = match (&args.file, &args.resume) {
        (Some(path), None) => {
            let out = args.out.clone().unwrap_or_else(|| path.with_extension(""));
            (parse_file(path)?, out, None)
        }
        (None, Some(dir)) => {
            let c = read_checkpoint(dir)?;
            let out = args.out.clone().unwrap_or_else(|| dir.clone());
            (c.file.clone(), out, Some(c))
        }
        _ => {
            return Err(bad(
                "RUN.toml",
                "give a run file or --resume DIR (exactly one)",
            ))
        }
    };
    let ring = validate(&file)?;
    std::fs::create_dir_all(&out).map_err(|e| bad("--out", format!("{}: {e}", out.display())))?;
    let every = count("--checkpoint-every", &args.checkpoint_every)?
        .or(resume.as_ref().and_then(|c| c.every));
    let mut saving = Saving {
        out: &out,
        every,
        stop_after: count("--stop-after-samples", &args.stop_after_samples)?,
        taken: 0,
    };
    let targets: Vec<f64> = (0..file.run.samples)
        .map(|k| file.run.end_time * k as f64 / (file.run.samples - 1) as f64)
        .collect();
    let started = Instant::now();
    let first = resume.as_ref().map_or(0, |c| c.repeat);
    let (mut curves, mut chain_seconds) = match &resume {
        Some(c) => (c.curves.clone(), c.chain_seconds),
        None => (Vec::new(), 0.0),
    };
    for repeat in first..file.run.repeats {
        let mut one = file.clone();
        one.chain.seed = file.chain.seed.wrapping_add(repeat as u64);
        let ring = one.chain.ring();
        let start = Start {
            state: ring.initial_state(),
            ring,
            targets: &targets,
        };
        let clock = Instant::now();
        let mut progress = match resume.take() {
            Some(c) => ChainRun {
                rows: c.rows,
                chain: c.chain,
                impacts: c.impacts,
            },
            None => new_chain_run(&start)?,
        };
        let finished = sample_chain(&mut progress, &start, &mut saving, |run| Checkpoint {
            file: file.clone(),
            repeat,
            rows: run.rows.clone(),
            chain: run.chain.clone(),
            impacts: run.impacts.clone(),
            curves: curves.clone(),
            chain_seconds: chain_seconds + clock.elapsed().as_secs_f64(),
            every,
        })?;
        chain_seconds += clock.elapsed().as_secs_f64();
        if !finished {
            eprintln!(
                "haff rods chain: stopped after {} samples; continue with --resume {}",
                saving.taken,
                out.display()
            );
            return Ok(());
        }
        let mut runs = vec![("rod-chain MD".to_string(), progress.rows)];
        for name in &file.run.compare {
            let law = stochastic_law(name, &one)?;
            let rows = run_ed_mc(law, &start)?;
            runs.push((format!("ED + MC, {name}"), rows));
        }
        accumulate(&mut curves, runs, file.run.repeats);
    }
    write_outputs(&file, &out, &ring, &curves, chain_seconds, started)
}

fn write_outputs(
    file: &ChainFile,
    out: &Path,
    ring: &RingSetup,
    curves: &[(String, Vec<Row>)],
    chain_seconds: f64,
    started: Instant,
) -> CliResult {
    write_rows(&out.join("timeseries.csv"), &curves[0].1)?;
    for (name, (_, rows)) in file.run.compare.iter().zip(&curves[1..]) {
        write_rows(&out.join(format!("ed_mc_{name}.csv")), rows)?;
    }
    let chain_rows = &curves[0].1;
    let share = equipartition_share(ring.rods, ring.modes);
    let equilibrium: Vec<(f64, f64)> = chain_rows
        .iter()
        .map(|r| (r.time, share * r.total_energy))
        .collect();
    plot_cooling(&out.join("cooling.png"), curves, equilibrium)?;
    let last = chain_rows.last().copied();
    let summary = serde_json::json!({
        "parameters": file,
        "perimeter": ring.perimeter(),
        "wall_seconds_chain": chain_seconds,
        "wall_seconds": started.elapsed().as_secs_f64(),
        "equipartition_translational_energy": share * chain_rows[0].total_energy,
        "final": last,
        "energy_drift": last.map(|r| (r.total_energy - chain_rows[0].total_energy) / chain_rows[0].total_energy),
        "compare_final": curves[1..].iter().map(|(n, r)| (n.clone(), r.last().copied())).collect::<Vec<_>>(),
    });
    let mut f = std::fs::File::create(out.join("summary.json"))?;
    serde_json::to_writer_pretty(&mut f, &summary)?;
    writeln!(f)?;
    eprintln!(
        "haff rods chain: {} rods, {chain_seconds:.2} s; output in {}",
        ring.rods,
        out.display()
    );
    Ok(())
}

/// The chain of one repeat at t = 0 (modes thermalized if `chain.bath_temperature` > 0).
fn new_chain_run(start: &Start) -> CliResult<ChainRun> {
    Ok(ChainRun {
        rows: Vec::new(),
        chain: start.ring.chain(&start.state).map_err(chain_error)?,
        impacts: Impacts::new(start.ring.rods),
    })
}

/// Takes the remaining samples of `run`, writing check-points as `saving` says; false if
/// it stopped early (`--stop-after-samples`).
fn sample_chain(
    run: &mut ChainRun,
    start: &Start,
    saving: &mut Saving,
    checkpoint: impl Fn(&ChainRun) -> Checkpoint,
) -> CliResult<bool> {
    let masses = run.chain.masses();
    let n = run.chain.n_rods();
    let progress = indicatif::ProgressBar::new(start.targets.len() as u64);
    progress.set_position(run.rows.len() as u64);
    for &t in &start.targets[run.rows.len()..] {
        let chain = &mut run.chain;
        run.impacts.count(&chain.run_until(t));
        let bath: f64 = (0..n)
            .map(|i| chain.modal_energies(i).iter().sum::<f64>())
            .sum();
        run.rows.push(Row {
            time: chain.time(),
            collisions_per_particle: run.impacts.per_particle(),
            translational_energy: translational_energy(&chain.velocities(), &masses),
            bath_energy: bath,
            total_energy: chain.energy(),
        });
        progress.inc(1);
        saving.taken += 1;
        let stop = saving.stop_after.is_some_and(|k| saving.taken >= k);
        if stop || saving.every.is_some_and(|k| saving.taken.is_multiple_of(k)) {
            crate::output::write_checkpoint(saving.out, &checkpoint(run))?;
        }
        if stop {
            progress.finish_and_clear();
            return Ok(false);
        }
    }
    progress.finish_and_clear();
    Ok(true)
}

fn stochastic_law(name: &str, file: &ChainFile) -> CliResult<Box<dyn Restitution>> {
    let modes = u32::try_from(file.chain.modes).map_err(|_| bad("chain.modes", "too many"))?;
    if name == "glauber" {
        return Ok(Box::new(
            Glauber::new(modes).map_err(|e| CliError::library("chain.modes", e))?,
        ));
    }
    let path = file
        .run
        .table
        .as_ref()
        .ok_or_else(|| bad("run.table", "missing"))?;
    Ok(sim::law::tabulated(path, modes, "run.table")?)
}

/// Giese's ED + MC: the same rods as hard rods on the ring, each with a bath of `modes`
/// modes at the chain's initial mode temperature.
fn run_ed_mc(law: Box<dyn Restitution>, start: &Start) -> CliResult<Vec<Row>> {
    let (c, targets) = (&start.ring, start.targets);
    let masses = c.masses();
    let lengths = c.rod_lengths();
    let system = gas::System::<1> {
        length: c.perimeter(),
        positions: start.state.positions.iter().map(|x| [*x]).collect(),
        velocities: start.state.velocities.iter().map(|v| [*v]).collect(),
        radii: lengths.iter().map(|l| 0.5 * l).collect(),
        masses: masses.clone(),
    };
    let mut engine = EventDriven::new(system, law).map_err(|e| bad("chain", e))?;
    let n = lengths.len();
    engine
        .set_baths(vec![c.bath_temperature; n], c.seed)
        .map_err(|e| bad("chain.bath_temperature", e))?;
    let mut rows = Vec::with_capacity(targets.len());
    for &t in targets {
        engine.run_until(t);
        let baths: f64 = engine
            .bath_temperatures()
            .unwrap_or(&[])
            .iter()
            .sum::<f64>()
            * c.modes as f64;
        let time = engine.time();
        let cpp = engine.collisions_per_particle();
        let s = engine.system();
        let v: Vec<f64> = s.velocities.iter().map(|v| v[0]).collect();
        let kinetic = translational_energy(&v, &masses);
        rows.push(Row {
            time: t.max(time),
            collisions_per_particle: cpp,
            translational_energy: kinetic,
            bath_energy: baths,
            total_energy: kinetic + baths,
        });
    }
    Ok(rows)
}

/// Adds `runs` (one row list per curve) into `sums` with weight 1/`repeats`.
fn accumulate(sums: &mut Vec<(String, Vec<Row>)>, runs: Vec<(String, Vec<Row>)>, repeats: usize) {
    let w = 1.0 / repeats as f64;
    if sums.is_empty() {
        for (name, rows) in &runs {
            let zero = rows
                .iter()
                .map(|r| Row {
                    time: r.time,
                    ..Row::default()
                })
                .collect();
            sums.push((name.clone(), zero));
        }
    }
    for ((_, sum), (_, rows)) in sums.iter_mut().zip(runs) {
        for (s, r) in sum.iter_mut().zip(rows) {
            s.collisions_per_particle += w * r.collisions_per_particle;
            s.translational_energy += w * r.translational_energy;
            s.bath_energy += w * r.bath_energy;
            s.total_energy += w * r.total_energy;
        }
    }
}

fn write_rows(path: &Path, rows: &[Row]) -> CliResult {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(f, "{HEADER}")?;
    for r in rows {
        writeln!(
            f,
            "{},{},{},{},{}",
            r.time,
            r.collisions_per_particle,
            r.translational_energy,
            r.bath_energy,
            r.total_energy
        )?;
    }
    Ok(f.flush()?)
}

fn plot_cooling(
    path: &Path,
    curves: &[(String, Vec<Row>)],
    equilibrium: Vec<(f64, f64)>,
) -> CliResult {
    let mut series: Vec<(String, Vec<(f64, f64)>)> = curves
        .iter()
        .map(|(name, rows)| {
            (
                name.clone(),
                rows.iter()
                    .map(|r| (r.time, r.translational_energy))
                    .collect(),
            )
        })
        .collect();
    series.push((
        "equilibrium (equipartition with the modes)".into(),
        equilibrium,
    ));
    let axes = Axes {
        title: "translational energy of the rods",
        x: "time",
        y: "E_tr (centre-of-mass frame)",
        log_x: false,
        log_y: true,
    };
    Ok(plot::lines(path, axes, &series)?)
}
