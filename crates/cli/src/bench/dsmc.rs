//! `haff bench dsmc`: throughput of DSMC (homogeneous schemes, or the spatial one with a
//! given number of particles per cell and steps of a fifth of the mean free time).

use super::{median_min_max, DsmcSchemeChoice};
use crate::error::{CliError, CliResult};
use crate::output::{parse_count, stdout, ReportFormat};
use restitution::Restitution;
use std::io::Write;
use std::time::Instant;

/// `haff bench dsmc`: accepted collisions per second of homogeneous DSMC in 3D (a cooling
/// gas, T0 = 1), on all cores or `--threads`, medians of repeats, and memory per particle.
pub fn dsmc(args: &crate::BenchDsmcArgs) -> CliResult {
    use gas::dsmc::{point_gas, Scheme, SpatialOptions, StepSize};
    use restitution::{Constant, ScaledForm, Viscoelastic};
    use sim::driver::{Driver, Until};
    use sim::engines::{EngineSpec, Setup};
    use sim::schedule::{Measure, Schedule};
    let spatial = matches!(args.scheme, DsmcSchemeChoice::Spatial);
    let particles =
        args.particles
            .as_deref()
            .unwrap_or(if spatial { "1000000" } else { "10000000" });
    let n = parse_count("--particles", particles, 2, 1_000_000_000)?;
    let law_name = args
        .law
        .as_deref()
        .unwrap_or(if spatial { "1" } else { "fast" });
    let phi = super::packing_fraction(&args.packing_fraction)?;
    let per_particle = crate::output::parse_number(
        "--collisions",
        &args.collisions,
        crate::output::Allowed::between("collisions per particle", 1e-3, 1e4),
    )?;
    let repeats = parse_count("--repeats", &args.repeats, 1, 1000)?;
    let per_cell = crate::output::parse_number(
        "--particles-per-cell",
        &args.particles_per_cell,
        crate::output::Allowed::between("particles per cell", 1.0, 1000.0),
    )?;
    let (scheme, scheme_name) = match args.scheme {
        DsmcSchemeChoice::Blocks => (Some(Scheme::default()), "blocks"),
        DsmcSchemeChoice::Exact => (Some(Scheme::Exact), "exact"),
        DsmcSchemeChoice::Spatial => (None, "spatial"),
    };
    let law: Box<dyn Restitution> = if law_name == "fast" {
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
            law_name,
            crate::output::Allowed::between("fast, or a constant eps", 0.0, 1.0),
        )?;
        Box::new(Constant::new(eps).map_err(|e| CliError::library("--law", e))?)
    };
    let (law, rough) = super::rough_law(law, &args.tangential_restitution)?;
    let threads = match &args.threads {
        Some(t) => parse_count("--threads", t, 1, 4096)?,
        // The exact scheme is serial: one thread unless asked otherwise.
        None if matches!(args.scheme, DsmcSchemeChoice::Exact) => 1,
        None => rayon::current_num_threads(),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| CliError::argument("--threads", e.to_string()))?;
    let length = gas::system::monodisperse_box_side::<3>(n, 1.0, phi);
    let collisions = (per_particle * n as f64 / 2.0).round().max(1.0) as u64;
    let (mut rates, mut bytes) = (Vec::new(), 0);
    // Candidates drawn and collisions accepted in the timed runs (the majorant's efficiency).
    let (mut candidates, mut accepted) = (0u64, 0u64);
    for repeat in 0..repeats {
        let system = point_gas::<3>(n, [length; 3], 1.0, 1.0, 1.0, 1 + repeat as u64)
            .map_err(|e| CliError::argument("--particles", e))?;
        let spec = match scheme {
            Some(scheme) => EngineSpec::HomogeneousDsmc(scheme),
            // Cells holding `per_cell` particles on average; steps of a fifth of the mean
            // free time (0.2 collisions per particle), SPARTA's dt = tau / 5.
            None => EngineSpec::SpatialDsmc(SpatialOptions {
                cell_width: Some(length * (per_cell / n as f64).cbrt()),
                step: StepSize::CollisionsPerParticle(0.2),
            }),
        };
        let setup = Setup {
            law: law.box_clone(),
            packing_fraction: phi,
            seed: 1,
            baths: None,
        };
        let mut engine = sim::engines::build(&spec, system, setup)
            .map_err(|e| CliError::argument("--particles", e))?;
        if rough {
            super::spin(engine.as_mut(), 1 + repeat as u64)?;
        }
        // A warm-up of one collision per particle, then the timed collisions, through the
        // run driver (as `haff run` advances an engine).
        let timed = 1.0 + 2.0 * collisions as f64 / n as f64;
        let schedule = Schedule::samples_at(&[1.0, timed], Measure::CollisionsPerParticle);
        let mut driver = Driver::new(engine, Vec::new(), schedule);
        let warm_up = Until {
            samples: Some(1),
            point: None,
        };
        pool.install(|| driver.go(&mut (), warm_up, None))?;
        let before = driver.engine().counters();
        let start = Instant::now();
        pool.install(|| driver.go(&mut (), Until::default(), None))?;
        let seconds = start.elapsed().as_secs_f64();
        let after = driver.engine().counters();
        rates.push((after.collisions - before.collisions) as f64 / seconds);
        candidates += after.events - before.events;
        accepted += after.collisions - before.collisions;
        bytes = driver.engine().memory_bytes();
    }
    let [median, min, max] = median_min_max(rates);
    let candidates_per_collision = candidates as f64 / accepted.max(1) as f64;
    let report = serde_json::json!({
        "particles": n,
        "packing_fraction": phi,
        "scheme": scheme_name,
        "law": law_name,
        "tangential_restitution": args.tangential_restitution,
        "threads": threads,
        "collisions_per_repeat": collisions,
        "repeats": repeats,
        "collisions_per_second": median,
        "collisions_per_second_min": min,
        "collisions_per_second_max": max,
        "collisions_per_second_per_thread": median / threads as f64,
        // One worker thread per core (the default uses all cores).
        "collisions_per_second_per_core": median / threads as f64,
        "particles_per_cell": if scheme.is_none() { Some(per_cell) } else { None },
        "bytes_per_particle": bytes as f64 / n as f64,
        "candidates_per_collision": candidates_per_collision,
        // The collisions the timed runs made (the steps end near the requested count):
        // the denominator of a cost per collision measured from outside (callgrind).
        "collisions_timed": accepted,
    });
    let mut out = stdout();
    match args.format {
        ReportFormat::Json => crate::output::write_json(&mut out, &report)?,
        ReportFormat::Table => writeln!(
            out,
            "N = {n}, phi = {phi}, {} scheme, law {}: {median:.3e} collisions/s (min {min:.3e}, max {max:.3e}) on {threads} threads, {:.3e} per thread, {:.0} bytes/particle, {candidates_per_collision:.3} candidates/collision (median of {repeats})",
            scheme_name,
            law_name,
            median / threads as f64,
            bytes as f64 / n as f64
        )?,
    }
    Ok(out.flush()?)
}
