//! `haff run RUN.toml [--out DIR]`, `haff run --resume DIR`: a granular-gas run described by
//! a TOML file (schema: `sim::description`), driven by the library run driver
//! (`sim::Simulation`); this file holds the arguments, the progress bar and the report.

use crate::error::{CliError, CliResult};
use crate::output::parse_count;
use crate::progress::Bar;
use crate::RunArgs;
use sim::outdir::{run_hash, OutputDir, RunState};
use sim::Simulation;
use std::io::Write;
use std::path::PathBuf;

/// `haff run`. Launched by `mpirun -n R` (a binary built with the feature `mpi`), every
/// rank runs it: the run is spread over the ranks, rank 0 writes and reports. Errors of the
/// run description happen on every rank alike (rank 0 reports them); a rank that fails
/// alone once the run goes (writing its files) ends all ranks (MPI_Abort).
pub fn run(args: &RunArgs) -> CliResult {
    if args.check {
        return check(args);
    }
    let _session = sim::parallel::start()?;
    let root = sim::parallel::world().rank() == 0;
    // Errors of the description are every rank's: rank 0 reports, then all leave together
    // (after rank 0 has written the message: mpirun ends the job at the first failed exit).
    let (simulation, out, every, stop_after) = prepare(args).map_err(|e| {
        if root {
            e.report();
        }
        sim::parallel::world().sum_i64(&mut [0]);
        e.silenced()
    })?;
    if root {
        for note in &simulation.plan().notes {
            eprintln!("haff run: note: {note}");
        }
        if let Some(g) = simulation.initial_state() {
            eprintln!(
                "haff run: dense start: spheres grown from packing fraction {} in {} \
                 collisions ({} events, {:.2} s; summary.json: initial_state)",
                g.start_fraction, g.collisions, g.events, g.seconds
            );
        }
    }
    // Rank 0 alone opens the output directory; all ranks learn whether it could.
    let opened = if root {
        let hash = run_hash(simulation.description());
        Some(OutputDir::open(
            &out,
            args.resume.as_deref(),
            "run",
            &hash,
            args.force,
        ))
    } else {
        None
    };
    let mut failed = [opened.as_ref().is_some_and(|o| o.is_err()) as i64];
    sim::parallel::world().sum_i64(&mut failed);
    let dir = match opened {
        Some(Ok(dir)) => Some(dir),
        Some(Err(e)) => return Err(e.into()),
        None if failed[0] > 0 => {
            return Err(CliError::argument("--out", "rank 0 could not open it").silenced())
        }
        None => None,
    };
    go(simulation, &out, dir, every, stop_after).map_err(|e| {
        e.report();
        sim::parallel::abort_others(e.code().into());
        e.silenced()
    })
}

/// A checked run of `args` on every rank, its output directory, its check-point interval
/// and its `--stop-after-samples`.
fn prepare(args: &RunArgs) -> CliResult<(Simulation, PathBuf, Option<usize>, Option<usize>)> {
    let (simulation, out) = match (&args.file, &args.resume) {
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
    Ok((simulation, out, every, stop_after))
}

/// `haff run --check FILE`: the validated description on stdout, the notes on stderr. The
/// run is set up as `haff run` sets it up before its first step (particles placed, laws
/// built, their ranges checked), so that a file it accepts starts; a run pinned to several
/// MPI ranks (`run.ranks`) is validated only, its engine being built under `mpirun` alone.
fn check(args: &RunArgs) -> CliResult {
    let Some(path) = &args.file else {
        return Err(CliError::argument("--check", "give the run file to check"));
    };
    let in_file = CliError::in_file(path);
    let description = sim::RunDescription::from_path(path).map_err(&in_file)?;
    let plan = sim::validate(&description).map_err(&in_file)?;
    for note in &plan.notes {
        eprintln!("haff run: note: {note}");
    }
    match plan.description.run.ranks {
        Some(ranks) if ranks != 1 => eprintln!(
            "haff run: note: validated only; the engine of a run on {ranks} ranks is set up \
             under mpirun"
        ),
        _ => drop(Simulation::new(&description).map_err(&in_file)?),
    }
    let text = plan.description.to_toml().map_err(in_file)?;
    let mut out = crate::output::stdout();
    write!(out, "{text}")?;
    Ok(out.flush()?)
}

/// Runs `simulation` into `out` (its directory `dir` open on rank 0 only) and reports.
fn go(
    mut simulation: Simulation,
    out: &std::path::Path,
    dir: Option<OutputDir>,
    every: Option<usize>,
    stop_after: Option<usize>,
) -> CliResult {
    simulation.set_checkpoints(out, every);
    simulation.set_output_dir(out);
    let outcome = match dir {
        Some(_) => simulation.run(&mut Bar::samples(), stop_after)?,
        None => simulation.run(&mut (), stop_after)?,
    };
    simulation.write(out)?;
    let reports = simulation.rank_reports();
    let Some(mut dir) = dir else {
        return Ok(());
    };
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
    if let Some(ranks) = reports {
        let p = sim::parallel::summary(&ranks, simulation.description().system.dimension as usize);
        eprintln!(
            "haff run: {} ranks, {} steps of {:.3e} s, {:.1} % of it communicating, {:.3e} \
             bytes migrating per rank and step (summary.json: parallel)",
            p["ranks"],
            p["steps"],
            p["step_seconds"].as_f64().unwrap_or(0.0),
            100.0 * p["communication_fraction"].as_f64().unwrap_or(0.0),
            p["bytes_sent_per_rank_per_step"].as_f64().unwrap_or(0.0)
        );
    }
    if let Some(c) = simulation.report().section("contacts") {
        eprintln!(
            "haff run: soft-sphere time step {:.3e} ({} steps), eps of isolated contacts within \
             {:.1e} of the exact law, largest overlap {:.2} % of the contact distance, \
             {:.1} % of the time in contact spent in multi-particle contacts",
            c.number("time_step"),
            c.number("steps"),
            c.number("eps_error"),
            100.0 * c.number("max_relative_overlap"),
            100.0 * c.number("multi_contact_fraction")
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
