//! `haff bench checkpoint`: the cost of a check-point of an event-driven run.

use super::median_min_max;
use crate::error::{CliError, CliResult};
use crate::output::{parse_count, significant, stdout, write_json, ReportFormat};
use std::io::Write;
use std::time::Instant;

/// `haff bench checkpoint`: bytes per particle on disk, seconds to save (synchronize,
/// encode, write) and to load (read, verify, decode, check, restore) the check-point of an
/// event-driven 3D gas at phi = 0.05 with the TC model on (medians of repeats).
pub fn checkpoint(args: &crate::BenchCheckpointArgs) -> CliResult {
    let n = parse_count("--particles", &args.particles, 2, 100_000_000)?;
    let repeats = parse_count("--repeats", &args.repeats, 1, 1000)?;
    let dir = std::env::temp_dir().join(format!("haff-bench-checkpoint-{}", std::process::id()));
    let toml = format!(
        "[system]\nparticles = {n}\npacking_fraction = 0.05\n\
         [collision]\nlaw = \"constant\"\nrestitution = 0.9\ntc = 1e-6\n\
         [run]\ncollisions_per_particle = 1\nsamples = 2\n"
    );
    let (mut saves, mut loads, mut bytes) = (Vec::new(), Vec::new(), 0);
    for _ in 0..repeats {
        std::fs::create_dir_all(&dir).map_err(|e| CliError::argument("--particles", e))?;
        let mut run = sim::Simulation::from_toml(&toml, "bench.toml".as_ref())?;
        run.set_checkpoints(&dir, Some(1));
        // The first sample (t = 0) is taken and saved; the run stops after it.
        let clock = Instant::now();
        run.run(&mut (), Some(1))?;
        saves.push(clock.elapsed().as_secs_f64());
        bytes = std::fs::metadata(dir.join(sim::checkpoint::FILE_NAME))?.len();
        let clock = Instant::now();
        sim::Simulation::resume(&dir)?;
        loads.push(clock.elapsed().as_secs_f64());
        std::fs::remove_dir_all(&dir)?;
    }
    let (save, load) = (median_min_max(saves)[0], median_min_max(loads)[0]);
    let per_particle = bytes as f64 / n as f64;
    let report = serde_json::json!({
        "particles": n,
        "repeats": repeats,
        "bytes_per_particle": per_particle,
        "save_seconds": save,
        "load_seconds": load,
    });
    let mut out = stdout();
    match args.format {
        ReportFormat::Json => write_json(&mut out, &report)?,
        ReportFormat::Table => writeln!(
            out,
            "N = {n}: {} bytes/particle, save {} s, load {} s (medians of {repeats})",
            significant(per_particle, 3),
            significant(save, 3),
            significant(load, 3)
        )?,
    }
    Ok(out.flush()?)
}
