//! `haff bench cor`: nanoseconds per evaluation of each coefficient-of-restitution law on
//! a fixed log-spaced set of scaled speeds, and through the physical-speed path
//! [`Viscoelastic::eps`] for the laws engines use.

use super::median_min_max;
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
/// Laws also timed over whole slices (`ScaledForm::eps_slice`, as Python's `haff.eps`).
const SLICE_LAWS: [&str; 2] = ["fast", "pade:3/6"];
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
    for name in SLICE_LAWS {
        let form = builtin_law(name)?;
        let work = Workload::scaled(evaluations_for(name, evaluations));
        samples.push((format!("{name}[]"), time_slice(&form, &work, repeats)));
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

/// Nanoseconds per evaluation of `form` over `work` a slice at a time
/// ([`ScaledForm::eps_slice`]), one sample per repetition.
fn time_slice(form: &ScaledForm, work: &Workload, repeats: usize) -> Vec<f64> {
    let mut out = vec![0.0; work.inputs.len()];
    form.eps_slice(&work.inputs, &mut out);
    (0..repeats)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..work.passes {
                form.eps_slice(black_box(&work.inputs), &mut out);
                black_box(&mut out);
            }
            start.elapsed().as_nanos() as f64 / work.evaluations() as f64
        })
        .collect()
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
         []: a slice at a time (ScaledForm::eps_slice, as Python haff.eps per core); (v): physical \
         speeds via Viscoelastic::eps with beta = {BETA} (s/cm)^(1/5)",
        evaluations_for("exact", evaluations)
    )?;
    Ok(())
}
