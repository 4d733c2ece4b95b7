//! `haff reproduce ID|all [--out DIR] [--quick]`, `haff reproduce --list`: the figures and
//! tables of the papers, recomputed by the `reproduce` crate (this file holds only the
//! arguments, the progress bar and the report).

use crate::error::{CliError, CliResult};
use crate::progress::Steps;
use crate::ReproduceArgs;
use ::reproduce::{entries, find, id_list, Context, Entry};
use std::io::Write;
use std::time::Instant;

/// `haff reproduce`.
pub fn reproduce(args: &ReproduceArgs) -> CliResult {
    if args.list {
        let mut out = std::io::stdout().lock();
        for e in entries() {
            writeln!(
                out,
                "{:<16} {:<26} {:<16} {:>6.1} s  {}",
                e.id, e.paper, e.item, e.typical_seconds, e.shows
            )?;
        }
        return Ok(());
    }
    let Some(id) = args.id.as_deref() else {
        return Err(CliError::argument(
            "ID",
            format!("give an ID, `all` or --list; valid IDs: all, {}", id_list()),
        ));
    };
    let chosen: Vec<Entry> = if id == "all" {
        entries()
    } else {
        match find(id) {
            Some(entry) => vec![entry],
            None => {
                return Err(CliError::argument(
                    "ID",
                    format!("unknown ID '{id}'; valid IDs: all, {}", id_list()),
                ))
            }
        }
    };
    let ctx = Context::new(&args.out, args.quick);
    let mut bar = Steps::new(chosen.len(), "items");
    let start = Instant::now();
    let mut results = Vec::new();
    for entry in &chosen {
        bar.message(entry.id);
        let began = Instant::now();
        let outcome = (entry.run)(&ctx)?;
        let line = format!(
            "{:<16} {:>6.2} s  {}",
            entry.id,
            began.elapsed().as_secs_f64(),
            outcome.summary
        );
        bar.println(&line);
        bar.step();
        results.push((*entry, outcome));
    }
    bar.finish();
    if let Some(page) = &args.gallery {
        let command = format!(
            "haff reproduce {id} --out {}{}",
            args.out.display(),
            if args.quick { " --quick" } else { "" }
        );
        let command = format!("{command} --gallery {}", page.display());
        ::reproduce::gallery::write(page, &args.out, &results, &command)?;
    }
    eprintln!(
        "haff reproduce: {} item(s) in {:.1} s; output in {}",
        chosen.len(),
        start.elapsed().as_secs_f64(),
        args.out.display()
    );
    Ok(())
}
