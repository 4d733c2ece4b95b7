//! `haff bench rods`: throughput of the rod-chain MD.

use super::median_min_max;
use crate::error::{CliError, CliResult};
use crate::output::{parse_count, significant, stdout, write_json, ReportFormat};
use std::io::Write;
use std::time::Instant;

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
