//! `haff rods chain RUN.toml`, `haff rods chain --resume DIR`: the rod-chain MD on a ring
//! and ED + Monte Carlo of the same rods (`sim::rod_ring`); this file holds the arguments
//! and the report.

use crate::error::{CliError, CliResult};
use crate::output::parse_count;
use crate::progress::Bar;
use crate::RunArgs;
use sim::rod_ring::{RingDescription, RingRun};

/// `haff rods chain`.
pub fn run(args: &RunArgs) -> CliResult {
    let (mut run, out) = match (&args.file, &args.resume) {
        (Some(path), None) => {
            let out = args.out.clone().unwrap_or_else(|| path.with_extension(""));
            (RingRun::new(&RingDescription::from_path(path)?)?, out)
        }
        (None, Some(dir)) => {
            let run = RingRun::resume(dir).map_err(CliError::resume)?;
            (run, args.out.clone().unwrap_or_else(|| dir.clone()))
        }
        _ => {
            return Err(CliError::argument(
                "RUN.toml",
                "give a run file or --resume DIR (exactly one)",
            ))
        }
    };
    let count = |flag: &str, text: &Option<String>| {
        text.as_ref()
            .map(|t| parse_count(flag, t, 1, 1_000_000))
            .transpose()
    };
    let every = count("--checkpoint-every", &args.checkpoint_every)?.or(run.checkpoint_interval());
    let stop_after = count("--stop-after-samples", &args.stop_after_samples)?;
    std::fs::create_dir_all(&out)
        .map_err(|e| CliError::argument("--out", format!("{}: {e}", out.display())))?;
    run.set_checkpoints(&out, every);
    if !run.run(&mut Bar::samples(), stop_after)? {
        eprintln!(
            "haff rods chain: stopped after {} samples; continue with --resume {}",
            stop_after.unwrap_or(0),
            out.display()
        );
        return Ok(());
    }
    run.write(&out)?;
    eprintln!(
        "haff rods chain: {} rods, {:.2} s; output in {}",
        run.ring().rods,
        run.chain_seconds(),
        out.display()
    );
    Ok(())
}
