//! `haff bench observers`: the cost of the observers of space (`[output]` of a run) against
//! the engine they observe, for the budget of issue 16: each observer at most 10 % of the
//! run time at one sample per collision per particle.

use super::median_min_max;
use crate::error::{CliError, CliResult};
use crate::output::{parse_count, significant, stdout, write_json, write_table, ReportFormat};
use gas::structure::{
    coarse_grained_fields, hydrodynamic_modes, pair_correlation, structure_factor,
};
use gas::{init, System};
use serde::Serialize;
use sim::driver::{Driver, Until};
use sim::schedule::{Measure, Schedule};
use sim::space::{structure_resolution, StructureResolution, MODE_SHELLS};
use std::io::Write;
use std::time::Instant;

/// The timings of one task in `bench observers`.
#[derive(Debug, Serialize)]
struct ObserverTiming {
    task: &'static str,
    seconds: f64,
    seconds_min: f64,
    seconds_max: f64,
    /// Median seconds over the engine's median seconds for one collision per particle.
    percent_of_engine: f64,
}

/// What one repeat times, in the order of the report: the engine first, the observers after.
const TASKS: [&str; 6] = [
    "engine (1 collision/particle)",
    "state snapshot",
    "modes",
    "structure factor S(k)",
    "pair correlation g(r)",
    "fields",
];

/// `haff bench observers`: the median time of one call of each observer of space on an
/// elastic gas from [`init::monodisperse`], with the resolution `haff run` chooses
/// ([`structure_resolution`], [`MODE_SHELLS`]), and the engine's time for one collision per
/// particle of event-driven MD of the same gas. Each repeat runs the engine for one
/// collision per particle and then times every observer once on the state it reached, so
/// that drifts of the machine hit all alike.
pub fn observers(args: &crate::BenchObserversArgs) -> CliResult {
    let n = parse_count("--particles", &args.particles, 2, 100_000_000)?;
    let phi = super::packing_fraction(&args.packing_fraction)?;
    let dimension = parse_count("--dimension", &args.dimension, 2, 3)?;
    let repeats = parse_count("--repeats", &args.repeats, 1, 1000)?;
    let field_grid = match &args.field_grid {
        Some(text) => Some(parse_count("--field-grid", text, 3, 4096)?),
        None => None,
    };
    let mode_shells = match &args.mode_shells {
        Some(text) => parse_count("--mode-shells", text, 1, 100)?,
        None => MODE_SHELLS,
    };
    let settings = Settings {
        n,
        phi,
        repeats,
        field_grid,
        mode_shells,
    };
    let (samples, resolution, field_grid) = match dimension {
        2 => measure::<2>(&settings)?,
        _ => measure::<3>(&settings)?,
    };
    let engine = median_min_max(samples[0].clone())[0];
    let timings: Vec<ObserverTiming> = TASKS
        .iter()
        .zip(samples)
        .map(|(&task, sample)| {
            let [seconds, seconds_min, seconds_max] = median_min_max(sample);
            ObserverTiming {
                task,
                seconds,
                seconds_min,
                seconds_max,
                percent_of_engine: 100.0 * seconds / engine,
            }
        })
        .collect();
    let mut out = stdout();
    match args.format {
        ReportFormat::Json => write_json(
            &mut out,
            &serde_json::json!({
                "particles": n,
                "packing_fraction": phi,
                "dimension": dimension,
                "repeats": repeats,
                "threads": rayon::current_num_threads(),
                "mode_shells": mode_shells,
                "fft_grid": resolution.grid,
                "r_max": resolution.r_max,
                "bins": resolution.bins,
                "field_grid": field_grid,
                "timings": timings,
            }),
        )?,
        ReportFormat::Table => {
            writeln!(
                out,
                "{dimension}D, N = {n}, phi = {phi}, {} threads; modes |n|^2 <= {mode_shells}, \
                 S(k) grid {}^{dimension}, g(r) to {} in {} bins, fields grid {field_grid}^{dimension} \
                 (medians of {repeats})",
                rayon::current_num_threads(),
                resolution.grid,
                significant(resolution.r_max, 4),
                resolution.bins,
            )?;
            let header = ["task", "seconds", "min", "max", "% of engine"].map(String::from);
            let rows: Vec<Vec<String>> = timings
                .iter()
                .map(|t| {
                    vec![
                        t.task.to_string(),
                        significant(t.seconds, 3),
                        significant(t.seconds_min, 3),
                        significant(t.seconds_max, 3),
                        format!("{:.1}", t.percent_of_engine),
                    ]
                })
                .collect();
            write_table(&mut out, &header, &rows)?;
        }
    }
    Ok(out.flush()?)
}

/// The parsed arguments.
struct Settings {
    n: usize,
    phi: f64,
    repeats: usize,
    field_grid: Option<usize>,
    mode_shells: usize,
}

/// Seconds of each of [`TASKS`] per repeat, the structure resolution and the field grid.
fn measure<const D: usize>(
    settings: &Settings,
) -> CliResult<(Vec<Vec<f64>>, StructureResolution, usize)> {
    let &Settings {
        n,
        phi,
        repeats,
        field_grid,
        mode_shells,
    } = settings;
    let system: System<D> = init::monodisperse::<D>(n, phi, 1.0, 1.0, 1.0, 1)
        .map_err(|e| CliError::argument("--particles", e))?;
    let law = Box::new(restitution::Constant::new(1.0).map_err(|e| CliError::library("law", e))?);
    let setup = sim::engines::Setup {
        law,
        packing_fraction: phi,
        seed: 1,
        baths: None,
    };
    let engine = sim::engines::build(&sim::engines::EngineSpec::EventDriven, system, setup)
        .map_err(|e| CliError::argument("--particles", e))?;
    // One collision per particle of warm-up (the calendar and the cell lists reach their
    // steady state), then one per repeat, through the run driver.
    let targets: Vec<f64> = (1..=repeats + 1).map(|k| k as f64).collect();
    let schedule = Schedule::samples_at(&targets, Measure::CollisionsPerParticle);
    let mut driver = Driver::new(engine, Vec::new(), schedule);
    let until = |samples: usize| Until {
        samples: Some(samples),
        point: None,
    };
    driver.go(&mut (), until(1), None)?;
    let resolution = structure_resolution(driver.engine_mut().system());
    // the fields module's advice: about 10 particles per cell
    let field_grid =
        field_grid.unwrap_or_else(|| ((n as f64 / 10.0).powf(1.0 / D as f64) as usize).max(3));
    let structure_factor0 = gas::theory::long_wavelength_structure_factor::<D>(phi);
    let mut seconds = vec![Vec::with_capacity(repeats); TASKS.len()];
    let time = |seconds: &mut Vec<f64>, task: &mut dyn FnMut()| {
        let clock = Instant::now();
        task();
        seconds.push(clock.elapsed().as_secs_f64());
    };
    for repeat in 0..repeats {
        let mut advanced = Ok(());
        time(&mut seconds[0], &mut || {
            advanced = driver.go(&mut (), until(repeat + 2), None);
        });
        advanced?;
        // the engine synchronizes its state (what a run does per sample); the copy that the
        // observers read here is not timed
        time(&mut seconds[1], &mut || {
            std::hint::black_box(driver.engine_mut().system());
        });
        let system = driver.engine_mut().system().clone();
        time(&mut seconds[2], &mut || {
            std::hint::black_box(hydrodynamic_modes(&system, mode_shells, structure_factor0));
        });
        time(&mut seconds[3], &mut || {
            std::hint::black_box(structure_factor(&system, resolution.grid));
        });
        time(&mut seconds[4], &mut || {
            std::hint::black_box(pair_correlation(&system, resolution.r_max, resolution.bins));
        });
        time(&mut seconds[5], &mut || {
            std::hint::black_box(coarse_grained_fields(&system, field_grid));
        });
    }
    Ok((seconds, resolution, field_grid))
}
