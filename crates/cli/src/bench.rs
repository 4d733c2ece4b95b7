//! `haff bench cor`: nanoseconds per evaluation of each coefficient-of-restitution law on
//! a fixed log-spaced set of scaled speeds, and through the physical-speed path
//! [`Viscoelastic::eps`] for the laws engines use.

use crate::error::{CliError, CliResult};
use crate::output::{parse_count, significant, stdout, write_json, write_table, ReportFormat};
use crate::BenchCorArgs;
use restitution::material::{speed_from_vstar, ICE_BRIDGES_BETA_CGS};
use restitution::{Restitution, ScaledForm, Viscoelastic};
use serde::Serialize;
use std::hint::black_box;
use std::io::Write;
use std::time::Instant;

/// Laws timed on scaled speeds v*.
const SCALED_LAWS: [&str; 6] = [
    "exact",
    "exact-naive",
    "fast",
    "pade:1/4",
    "pade:3/6",
    "series:20",
];
/// Laws timed on physical speeds through [`Viscoelastic::eps`].
const PHYSICAL_LAWS: [&str; 2] = ["fast", "pade:3/6"];
/// The law every median is compared with.
const REFERENCE_LAW: &str = "pade:3/6";
/// beta for the physical-speed path: ice, in (s/cm)^(1/5), so speeds are in cm/s.
const BETA: f64 = ICE_BRIDGES_BETA_CGS;
/// The scaled speeds: log-spaced in [VSTAR_LOW, VSTAR_HIGH].
const VSTAR_LOW: f64 = 1e-3;
const VSTAR_HIGH: f64 = 1e3;
/// At most this many distinct speeds; more evaluations repeat them.
const GRID_POINTS: usize = 1000;
/// The exact laws get this fraction of the evaluations (each one integrates an ODE) ...
const EXACT_DIVISOR: usize = 10_000;
/// ... but at least this many.
const EXACT_MIN_EVALUATIONS: usize = 10;
/// Largest accepted --repeats and --evaluations.
const MAX_REPEATS: usize = 1000;
const MAX_EVALUATIONS: usize = 1_000_000_000;

/// The timing of one law, in nanoseconds per evaluation.
#[derive(Debug, Serialize)]
struct LawTiming {
    law: String,
    median_ns: f64,
    min_ns: f64,
    max_ns: f64,
    ratio_to_pade36: f64,
}

/// The JSON document of `bench cor`.
#[derive(Debug, Serialize)]
struct BenchReport {
    unit: &'static str,
    results: Vec<LawTiming>,
}

/// What one timed repetition evaluates: `passes` passes over `inputs`.
struct Workload {
    inputs: Vec<f64>,
    passes: usize,
}

impl Workload {
    /// About `evaluations` evaluations at log-spaced scaled speeds.
    fn scaled(evaluations: usize) -> Self {
        let points = evaluations.clamp(1, GRID_POINTS);
        Workload {
            inputs: log_spaced(VSTAR_LOW, VSTAR_HIGH, points),
            passes: evaluations.div_ceil(points),
        }
    }

    /// As [`Workload::scaled`], converted to physical speeds with material constant `beta`.
    fn physical(evaluations: usize, beta: f64) -> CliResult<Self> {
        let mut work = Workload::scaled(evaluations);
        work.inputs = work
            .inputs
            .iter()
            .map(|&vstar| speed_from_vstar(beta, vstar))
            .collect::<Result<_, _>>()
            .map_err(|e| CliError::library("beta", e))?;
        Ok(work)
    }

    /// Evaluations per repetition.
    fn evaluations(&self) -> usize {
        self.inputs.len() * self.passes
    }
}

/// `n` numbers from `low` to `high` inclusive, equally spaced in the logarithm (the
/// geometric mean if `n` is 1).
pub fn log_spaced(low: f64, high: f64, n: usize) -> Vec<f64> {
    if n == 1 {
        return vec![(low * high).sqrt()];
    }
    let ratio = high / low;
    (0..n)
        .map(|i| low * ratio.powf(i as f64 / (n - 1) as f64))
        .collect()
}

/// `haff bench cor`.
pub fn cor(args: &BenchCorArgs) -> CliResult {
    let repeats = parse_count("--repeats", &args.repeats, 1, MAX_REPEATS)?;
    let evaluations = parse_count("--evaluations", &args.evaluations, 1, MAX_EVALUATIONS)?;
    let results = time_all_laws(repeats, evaluations)?;
    let mut out = stdout();
    match args.format {
        ReportFormat::Table => write_report_table(&mut out, &results, repeats, evaluations)?,
        ReportFormat::Json => write_json(
            &mut out,
            &BenchReport {
                unit: "ns_per_eval",
                results,
            },
        )?,
    }
    Ok(out.flush()?)
}

/// Evaluations per repetition for a law: fewer for the exact (integrating) laws.
fn evaluations_for(law: &str, evaluations: usize) -> usize {
    if law.starts_with("exact") {
        (evaluations / EXACT_DIVISOR).max(EXACT_MIN_EVALUATIONS)
    } else {
        evaluations
    }
}

/// Times every law and relates the medians to the reference law.
fn time_all_laws(repeats: usize, evaluations: usize) -> CliResult<Vec<LawTiming>> {
    let mut samples = Vec::new();
    for name in SCALED_LAWS {
        let form = builtin_law(name)?;
        let work = Workload::scaled(evaluations_for(name, evaluations));
        samples.push((name.to_string(), time_law(|v| form.eps(v), &work, repeats)));
    }
    for name in PHYSICAL_LAWS {
        let law = Viscoelastic::new(BETA, builtin_law(name)?)
            .map_err(|e| CliError::library("beta", e))?;
        let work = Workload::physical(evaluations, BETA)?;
        samples.push((
            format!("{name}(v)"),
            time_law(|v| law.eps(v), &work, repeats),
        ));
    }
    let summaries: Vec<(String, [f64; 3])> = samples
        .into_iter()
        .map(|(law, ns)| (law, median_min_max(ns)))
        .collect();
    let reference = summaries
        .iter()
        .find(|(law, _)| law == REFERENCE_LAW)
        .map_or(f64::NAN, |(_, [median, _, _])| *median);
    Ok(summaries
        .into_iter()
        .map(|(law, [median_ns, min_ns, max_ns])| LawTiming {
            law,
            median_ns,
            min_ns,
            max_ns,
            ratio_to_pade36: median_ns / reference,
        })
        .collect())
}

/// One of the laws named in this module.
fn builtin_law(name: &str) -> CliResult<ScaledForm> {
    name.parse().map_err(|e| CliError::library("law", e))
}

/// Nanoseconds per evaluation of `eps` over `work`, one sample per repetition. One call
/// before the timing builds any table the law needs (the fast law's), untimed.
fn time_law(eps: impl Fn(f64) -> f64, work: &Workload, repeats: usize) -> Vec<f64> {
    black_box(eps(black_box(work.inputs[0])));
    (0..repeats)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..work.passes {
                for &input in &work.inputs {
                    black_box(eps(black_box(input)));
                }
            }
            start.elapsed().as_nanos() as f64 / work.evaluations() as f64
        })
        .collect()
}

/// [median, min, max] of a non-empty sample.
fn median_min_max(mut sample: Vec<f64>) -> [f64; 3] {
    sample.sort_by(f64::total_cmp);
    let n = sample.len();
    let median = (sample[(n - 1) / 2] + sample[n / 2]) / 2.0;
    [median, sample[0], sample[n - 1]]
}

/// Writes the aligned table and a note on what was measured.
fn write_report_table(
    out: &mut impl Write,
    results: &[LawTiming],
    repeats: usize,
    evaluations: usize,
) -> CliResult {
    let header = ["law", "median ns/eval", "min", "max", "ratio to pade:3/6"].map(String::from);
    let rows: Vec<Vec<String>> = results
        .iter()
        .map(|r| {
            vec![
                r.law.clone(),
                significant(r.median_ns, 4),
                significant(r.min_ns, 4),
                significant(r.max_ns, 4),
                significant(r.ratio_to_pade36, 3),
            ]
        })
        .collect();
    write_table(out, &header, &rows)?;
    writeln!(
        out,
        "note: median/min/max over {repeats} repeats; v* log-spaced in [{VSTAR_LOW:e}, {VSTAR_HIGH:e}]; \
         {evaluations} evaluations per repeat ({} for exact laws); \
         (v): physical speeds via Viscoelastic::eps with beta = {BETA} (s/cm)^(1/5)",
        evaluations_for("exact", evaluations)
    )?;
    Ok(())
}

/// The timings of one calendar in `bench emd`.
#[derive(Debug, Serialize)]
struct EmdTiming {
    calendar: &'static str,
    collisions_per_second: f64,
    collisions_per_second_min: f64,
    collisions_per_second_max: f64,
    events_per_second: f64,
    bytes_per_particle: f64,
}

/// `haff bench emd`: collisions and events per second of an elastic 3D gas (one core),
/// medians of repeats, and the engine's memory per particle. With `--calendar both` the
/// repeats of the two calendars alternate, so that drifts of the machine hit both alike.
pub fn emd(args: &crate::BenchEmdArgs) -> CliResult {
    use gas::{init, Calendar, EventDriven};
    let n = parse_count("--particles", &args.particles, 2, 100_000_000)?;
    let phi = crate::output::parse_number(
        "--packing-fraction",
        &args.packing_fraction,
        crate::output::Allowed::between("phi", 1e-6, 0.45),
    )?;
    let width = crate::output::parse_number(
        "--cell-width",
        &args.cell_width,
        crate::output::Allowed::between("width in diameters", 1.0, 1e6),
    )?;
    let events = parse_count("--events", &args.events, 1, 1_000_000_000_000)? as u64;
    let repeats = parse_count("--repeats", &args.repeats, 1, 1000)?;
    let calendars: Vec<(&'static str, Calendar)> = match args.calendar.as_str() {
        "heap" => vec![("heap", Calendar::Heap)],
        "buckets" => vec![("buckets", Calendar::Buckets)],
        "both" => vec![("heap", Calendar::Heap), ("buckets", Calendar::Buckets)],
        other => {
            return Err(CliError::argument(
                "--calendar",
                format!("'{other}': allowed: heap, buckets, both"),
            ))
        }
    };
    let mut rates = vec![(vec![], vec![], 0usize); calendars.len()];
    for repeat in 0..repeats {
        for (&(_, kind), (collision_rates, event_rates, bytes)) in calendars.iter().zip(&mut rates)
        {
            let system = init::monodisperse::<3>(n, phi, 1.0, 1.0, 1.0, 1 + repeat as u64)
                .map_err(|e| CliError::argument("--particles", e))?;
            let law =
                Box::new(restitution::Constant::new(1.0).map_err(|e| CliError::library("law", e))?);
            let mut engine = EventDriven::with_cell_width(system, law, width)
                .map_err(|e| CliError::argument("--particles", e))?;
            engine.set_calendar(kind);
            for _ in 0..events {
                engine.step();
            }
            let before = engine.tally();
            let start = std::time::Instant::now();
            for _ in 0..events {
                engine.step();
            }
            let seconds = start.elapsed().as_secs_f64();
            let after = engine.tally();
            collision_rates.push((after.collisions - before.collisions) as f64 / seconds);
            event_rates.push((after.events - before.events) as f64 / seconds);
            *bytes = engine.memory_bytes();
        }
    }
    let timings: Vec<EmdTiming> = calendars
        .iter()
        .zip(rates)
        .map(|(&(calendar, _), (collision_rates, event_rates, bytes))| {
            let [collisions, min, max] = median_min_max(collision_rates);
            EmdTiming {
                calendar,
                collisions_per_second: collisions,
                collisions_per_second_min: min,
                collisions_per_second_max: max,
                events_per_second: median_min_max(event_rates)[0],
                bytes_per_particle: bytes as f64 / n as f64,
            }
        })
        .collect();
    let first = &timings[0];
    let report = serde_json::json!({
        "particles": n,
        "packing_fraction": phi,
        "cell_width": width,
        "events_per_repeat": events,
        "repeats": repeats,
        "calendar": first.calendar,
        "collisions_per_second": first.collisions_per_second,
        "collisions_per_second_min": first.collisions_per_second_min,
        "collisions_per_second_max": first.collisions_per_second_max,
        "events_per_second": first.events_per_second,
        "bytes_per_particle": first.bytes_per_particle,
        "calendars": timings,
    });
    let mut out = stdout();
    match args.format {
        ReportFormat::Json => crate::output::write_json(&mut out, &report)?,
        ReportFormat::Table => {
            for t in &timings {
                writeln!(
                    out,
                    "N = {n}, phi = {phi}, calendar {}: {:.3e} collisions/s (min {:.3e}, max {:.3e}), {:.3e} events/s, {:.0} bytes/particle (median of {repeats})",
                    t.calendar,
                    t.collisions_per_second,
                    t.collisions_per_second_min,
                    t.collisions_per_second_max,
                    t.events_per_second,
                    t.bytes_per_particle
                )?;
            }
        }
    }
    Ok(out.flush()?)
}

/// `haff bench dsmc`: accepted collisions per second of homogeneous DSMC in 3D (a cooling
/// gas, T0 = 1), on all cores or `--threads`, medians of repeats, and memory per particle.
pub fn dsmc(args: &crate::BenchDsmcArgs) -> CliResult {
    use gas::dsmc::{point_gas, Scheme};
    use gas::HomogeneousDsmc;
    use restitution::{Constant, ScaledForm, Viscoelastic};
    let n = parse_count("--particles", &args.particles, 2, 1_000_000_000)?;
    let phi = crate::output::parse_number(
        "--packing-fraction",
        &args.packing_fraction,
        crate::output::Allowed::between("phi", 1e-6, 0.45),
    )?;
    let per_particle = crate::output::parse_number(
        "--collisions",
        &args.collisions,
        crate::output::Allowed::between("collisions per particle", 1e-3, 1e4),
    )?;
    let repeats = parse_count("--repeats", &args.repeats, 1, 1000)?;
    let scheme = match args.scheme.as_str() {
        "blocks" => Scheme::default(),
        "exact" => Scheme::Exact,
        other => {
            return Err(CliError::argument(
                "--scheme",
                format!("'{other}': allowed: blocks, exact"),
            ))
        }
    };
    let law: Box<dyn Restitution> = if args.law == "fast" {
        let beta = crate::output::parse_number(
            "--beta",
            &args.beta,
            crate::output::Allowed::between("beta", 1e-12, 1e12),
        )?;
        let form: ScaledForm = "fast".parse().map_err(|e| CliError::library("--law", e))?;
        Box::new(Viscoelastic::new(beta, form).map_err(|e| CliError::library("--beta", e))?)
    } else {
        let eps = crate::output::parse_number(
            "--law",
            &args.law,
            crate::output::Allowed::between("fast, or a constant eps", 0.0, 1.0),
        )?;
        Box::new(Constant::new(eps).map_err(|e| CliError::library("--law", e))?)
    };
    let threads = match &args.threads {
        Some(t) => parse_count("--threads", t, 1, 4096)?,
        None => rayon::current_num_threads(),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| CliError::argument("--threads", e.to_string()))?;
    let length = (n as f64 * std::f64::consts::PI / 6.0 / phi).cbrt();
    let collisions = (per_particle * n as f64 / 2.0).round().max(1.0) as u64;
    let (mut rates, mut bytes) = (Vec::new(), 0);
    for repeat in 0..repeats {
        let system = point_gas::<3>(n, length, 1.0, 1.0, 1.0, 1 + repeat as u64)
            .map_err(|e| CliError::argument("--particles", e))?;
        let mut engine = HomogeneousDsmc::new(system, phi, law.box_clone(), 1, scheme)
            .map_err(|e| CliError::argument("--particles", e))?;
        pool.install(|| engine.run_collisions(n as u64 / 2));
        let before = engine.tally().collisions;
        let start = Instant::now();
        pool.install(|| engine.run_collisions(collisions));
        let seconds = start.elapsed().as_secs_f64();
        rates.push((engine.tally().collisions - before) as f64 / seconds);
        bytes = engine.memory_bytes();
    }
    let [median, min, max] = median_min_max(rates);
    let report = serde_json::json!({
        "particles": n,
        "packing_fraction": phi,
        "scheme": args.scheme,
        "law": args.law,
        "threads": threads,
        "collisions_per_repeat": collisions,
        "repeats": repeats,
        "collisions_per_second": median,
        "collisions_per_second_min": min,
        "collisions_per_second_max": max,
        "collisions_per_second_per_thread": median / threads as f64,
        // One worker thread per core (the default uses all cores).
        "collisions_per_second_per_core": median / threads as f64,
        "bytes_per_particle": bytes as f64 / n as f64,
    });
    let mut out = stdout();
    match args.format {
        ReportFormat::Json => crate::output::write_json(&mut out, &report)?,
        ReportFormat::Table => writeln!(
            out,
            "N = {n}, phi = {phi}, {} scheme, law {}: {median:.3e} collisions/s (min {min:.3e}, max {max:.3e}) on {threads} threads, {:.3e} per thread, {:.0} bytes/particle (median of {repeats})",
            args.scheme,
            args.law,
            median / threads as f64,
            bytes as f64 / n as f64
        )?,
    }
    Ok(out.flush()?)
}

/// `haff bench rods`: impacts per second of the two-rod experiment (rod-chain MD of
/// Giese's Eq. (2)), nanoseconds per fine step of the contact integrator (medians).
pub fn rods(args: &crate::BenchRodsArgs) -> CliResult {
    use crate::output::{parse_number, Allowed};
    use rods::chain::{run_two_rods, TwoRodSetup};
    let modes = parse_count("--modes", &args.modes, 1, 2000)?;
    let kappa = parse_number("--kappa", &args.kappa, Allowed::between("kappa", 1.0, 1e6))?;
    let collisions = parse_count("--collisions", &args.collisions, 1, 10_000_000)?;
    let repeats = parse_count("--repeats", &args.repeats, 1, 1000)?;
    let setup = TwoRodSetup {
        gamma: 0.6173,
        kappa,
        modes,
        gap: 1.0,
        c_h: 0.125,
    };
    let (mut rates, mut step_ns, mut steps) = (Vec::new(), Vec::new(), 0);
    for _ in 0..repeats {
        let start = Instant::now();
        let run =
            run_two_rods(&setup, collisions, 0).map_err(|e| CliError::argument("--modes", e))?;
        rates.push(collisions as f64 / start.elapsed().as_secs_f64());
        step_ns.push(run.stats.step_seconds * 1e9 / run.stats.fine_steps as f64);
        steps = run.stats.fine_steps / collisions as u64;
    }
    let [median, min, max] = median_min_max(rates);
    let report = serde_json::json!({
        "modes": modes,
        "kappa": kappa,
        "gamma": setup.gamma,
        "c_h": setup.c_h,
        "collisions_per_repeat": collisions,
        "repeats": repeats,
        "collisions_per_second": median,
        "collisions_per_second_min": min,
        "collisions_per_second_max": max,
        "fine_steps_per_collision": steps,
        "ns_per_fine_step": median_min_max(step_ns)[0],
    });
    let mut out = stdout();
    match args.format {
        ReportFormat::Json => write_json(&mut out, &report)?,
        ReportFormat::Table => writeln!(
            out,
            "two rods, M = {modes}, kappa = {kappa}: {} collisions/s (median of {repeats}; min {}, max {}), {steps} fine steps per collision, {} ns per fine step",
            significant(median, 3),
            significant(min, 3),
            significant(max, 3),
            significant(report["ns_per_fine_step"].as_f64().unwrap_or(f64::NAN), 3)
        )?,
    }
    Ok(out.flush()?)
}
