//! `haff bench emd`: throughput of the event-driven engine.

use super::{median_min_max, CalendarChoice};
use crate::error::{CliError, CliResult};
use crate::output::{parse_count, stdout, ReportFormat};
use serde::Serialize;
use std::io::Write;

/// The timings of one calendar in `bench emd`.
#[derive(Debug, Serialize)]
struct EmdTiming {
    calendar: &'static str,
    collisions_per_second: f64,
    collisions_per_second_min: f64,
    collisions_per_second_max: f64,
    events_per_second: f64,
    /// Events per collision in the timed events (collisions, cell crossings, stale
    /// predictions).
    events_per_collision: f64,
    /// Median nanoseconds per event.
    ns_per_event: f64,
    bytes_per_particle: f64,
    /// Whether the neighbour scans prefetched (the engine's choice by density).
    neighbour_prefetch: bool,
    particles_per_cell: f64,
}

/// `haff bench emd`: collisions and events per second of an elastic 3D gas (one core),
/// medians of repeats, and the engine's memory per particle. With `--calendar both` the
/// repeats of the two calendars alternate, so that drifts of the machine hit both alike.
pub fn emd(args: &crate::BenchEmdArgs) -> CliResult {
    use gas::{init, Engine, SorterKind};
    let n = parse_count("--particles", &args.particles, 2, 100_000_000)?;
    let phi = super::packing_fraction(&args.packing_fraction)?;
    let width = crate::output::parse_number(
        "--cell-width",
        &args.cell_width,
        crate::output::Allowed::between("width in diameters", 1.0, 1e6),
    )?;
    let events = parse_count("--events", &args.events, 1, 1_000_000_000_000)? as u64;
    let repeats = parse_count("--repeats", &args.repeats, 1, 1000)?;
    let restitution = crate::output::parse_number(
        "--restitution",
        &args.restitution,
        crate::output::Allowed::between("coefficient", f64::MIN_POSITIVE, 1.0),
    )?;
    let shear = match &args.shear_rate {
        None => None,
        Some(text) => {
            let rate = crate::output::parse_number(
                "--shear-rate",
                text,
                crate::output::Allowed::between("rate", -1e3, 1e3),
            )?;
            Some(gas::shear::Shear::new(rate).map_err(|e| CliError::argument("--shear-rate", e))?)
        }
    };
    let calendars: Vec<(&'static str, SorterKind)> = match args.calendar {
        CalendarChoice::Heap => vec![("heap", SorterKind::Heap)],
        CalendarChoice::Buckets => vec![("buckets", SorterKind::Buckets)],
        CalendarChoice::Both => vec![("heap", SorterKind::Heap), ("buckets", SorterKind::Buckets)],
    };
    let mut rates = vec![(vec![], vec![], 0usize, 0.0f64, (false, 0.0)); calendars.len()];
    for repeat in 0..repeats {
        for (&(_, kind), (collision_rates, event_rates, bytes, per_collision, prefetch)) in
            calendars.iter().zip(&mut rates)
        {
            let system = init::monodisperse::<3>(n, phi, 1.0, 1.0, 1.0, 1 + repeat as u64)
                .map_err(|e| CliError::argument("--particles", e))?;
            let law = Box::new(
                restitution::Constant::new(restitution).map_err(|e| CliError::library("law", e))?,
            );
            let (law, rough) = super::rough_law(law, &args.tangential_restitution)?;
            let tuning = sim::engines::Tuning {
                cell_width: width,
                sorter: kind,
            };
            let mut engine = sim::engines::event_driven(system, law, tuning)
                .map_err(|e| CliError::argument("--particles", e))?;
            if shear.is_some() {
                engine
                    .set_shear(shear)
                    .map_err(|e| CliError::argument("--shear-rate", e))?;
            }
            if rough {
                super::spin(&mut engine, 1 + repeat as u64)?;
            }
            for _ in 0..events {
                engine.step();
            }
            let before = engine.counters();
            let start = std::time::Instant::now();
            for _ in 0..events {
                engine.step();
            }
            let seconds = start.elapsed().as_secs_f64();
            let after = engine.counters();
            collision_rates.push((after.collisions - before.collisions) as f64 / seconds);
            event_rates.push((after.events - before.events) as f64 / seconds);
            *bytes = engine.memory_bytes();
            *prefetch = engine.neighbour_prefetch();
            *per_collision = (after.events - before.events) as f64
                / (after.collisions - before.collisions).max(1) as f64;
        }
    }
    let timings: Vec<EmdTiming> = calendars
        .iter()
        .zip(rates)
        .map(
            |(&(calendar, _), (collision_rates, event_rates, bytes, per_collision, prefetch))| {
                let [collisions, min, max] = median_min_max(collision_rates);
                let events_per_second = median_min_max(event_rates)[0];
                EmdTiming {
                    calendar,
                    collisions_per_second: collisions,
                    collisions_per_second_min: min,
                    collisions_per_second_max: max,
                    events_per_second,
                    events_per_collision: per_collision,
                    ns_per_event: 1e9 / events_per_second,
                    bytes_per_particle: bytes as f64 / n as f64,
                    neighbour_prefetch: prefetch.0,
                    particles_per_cell: prefetch.1,
                }
            },
        )
        .collect();
    let first = &timings[0];
    let report = serde_json::json!({
        "particles": n,
        "packing_fraction": phi,
        "cell_width": width,
        "restitution": restitution,
        "shear_rate": shear.map(|s| s.rate),
        "tangential_restitution": args.tangential_restitution,
        "events_per_repeat": events,
        "repeats": repeats,
        "calendar": first.calendar,
        "collisions_per_second": first.collisions_per_second,
        "collisions_per_second_min": first.collisions_per_second_min,
        "collisions_per_second_max": first.collisions_per_second_max,
        "events_per_second": first.events_per_second,
        "events_per_collision": first.events_per_collision,
        "ns_per_event": first.ns_per_event,
        "bytes_per_particle": first.bytes_per_particle,
        "neighbour_prefetch": first.neighbour_prefetch,
        "particles_per_cell": first.particles_per_cell,
        "calendars": timings,
    });
    let mut out = stdout();
    match args.format {
        ReportFormat::Json => crate::output::write_json(&mut out, &report)?,
        ReportFormat::Table => {
            for t in &timings {
                writeln!(
                    out,
                    "N = {n}, phi = {phi}, calendar {}: {:.3e} collisions/s (min {:.3e}, max {:.3e}), {:.3e} events/s ({:.1} ns/event, {:.2} events/collision), {:.0} bytes/particle, {:.2} particles per cell, neighbour prefetch {} (median of {repeats})",
                    t.calendar,
                    t.collisions_per_second,
                    t.collisions_per_second_min,
                    t.collisions_per_second_max,
                    t.events_per_second,
                    t.ns_per_event,
                    t.events_per_collision,
                    t.bytes_per_particle,
                    t.particles_per_cell,
                    if t.neighbour_prefetch { "on" } else { "off" }
                )?;
            }
        }
    }
    Ok(out.flush()?)
}
