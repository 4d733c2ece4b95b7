//! `haff run RUN.toml [--out DIR]`, `haff run --resume DIR`: a granular-gas run described by
//! a TOML file (schema: `sim::description`), driven by the library run driver
//! (`sim::Simulation`); this file holds the arguments, the progress bar and the report.

use crate::error::{CliError, CliResult};
use crate::output::parse_count;
use crate::progress::Bar;
use crate::RunArgs;
use sim::outdir::{run_hash, OutputDir, RunState};
use sim::Simulation;
use std::path::PathBuf;

/// `haff run`.
pub fn run(args: &RunArgs) -> CliResult {
    let (mut simulation, out) = match (&args.file, &args.resume) {
        (Some(path), None) => {
            let in_file = CliError::in_file(path);
            let description = sim::RunDescription::from_path(path).map_err(&in_file)?;
            let out = args.out.clone().unwrap_or_else(|| default_out(path));
            (Simulation::new(&description).map_err(in_file)?, out)
        }
        (None, Some(dir)) => {
            let simulation = Simulation::resume(dir).map_err(CliError::resume)?;
            (simulation, args.out.clone().unwrap_or(dir.clone()))
        }
        _ => {
            return Err(CliError::argument(
                "haff run",
                "give a run file (haff run FILE.toml) or --resume DIR, exactly one",
            ))
        }
    };
    let every = match &args.checkpoint_every {
        Some(text) => Some(parse_count("--checkpoint-every", text, 1, 1_000_000)?),
        None => simulation.checkpoint_interval(),
    };
    let stop_after = args
        .stop_after_samples
        .as_ref()
        .map(|text| parse_count("--stop-after-samples", text, 1, 1_000_000))
        .transpose()?;
    let hash = run_hash(simulation.description());
    let mut dir = OutputDir::open(&out, args.resume.as_deref(), "run", &hash, args.force)?;
    simulation.set_checkpoints(&out, every);
    simulation.set_output_dir(&out);
    let outcome = simulation.run(&mut Bar::samples(), stop_after)?;
    simulation.write(&out)?;
    dir.set_state(if outcome.complete {
        RunState::Complete
    } else {
        RunState::Stopped
    })?;
    let (counters, wall) = (outcome.counters, simulation.wall_seconds());
    eprintln!(
        "haff run: {} collisions, {} events in {wall:.2} s ({:.3e} events/s); output in {}",
        counters.collisions,
        counters.events,
        counters.events as f64 / wall,
        out.display()
    );
    if let Some(c) = simulation.contact_report() {
        eprintln!(
            "haff run: soft-sphere time step {:.3e} ({} steps), eps of isolated contacts within \
             {:.1e} of the exact law, largest overlap {:.2} % of the contact distance, \
             {:.1} % of the time in contact spent in multi-particle contacts",
            c.time_step,
            c.steps,
            c.eps_error,
            100.0 * c.max_relative_overlap,
            100.0 * c.multi_contact_fraction
        );
    }
    Ok(())
}

/// RUN.toml -> ./RUN (next to the current directory).
fn default_out(file: &std::path::Path) -> PathBuf {
    PathBuf::from(
        file.file_stem()
            .map_or("haff-run".into(), |s| s.to_os_string()),
    )
}
