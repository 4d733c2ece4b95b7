//! `[run]` besides the engine's own keys: how far the run goes, its samples and
//! histograms, the ranks it asks for.

use super::Stop;
use crate::description::RunSection;
use crate::engines::Abilities;
use crate::error::{positive, Error, Result};

/// `run.samples` and the stop criterion: exactly one of `run.collisions_per_particle` and
/// `run.end_time`.
pub(super) fn stop(r: &RunSection) -> Result<Stop> {
    if !(2..=1_000_000).contains(&r.samples) {
        return Err(Error::out_of_range(
            "run.samples",
            r.samples,
            "2 <= samples <= 1e6",
        ));
    }
    match (r.collisions_per_particle, r.end_time) {
        (Some(c), None) => Ok(Stop::CollisionsPerParticle(positive(
            "run.collisions_per_particle",
            c,
        )?)),
        (None, Some(t)) => Ok(Stop::Time(positive("run.end_time", t)?)),
        _ => Err(Error::input(
            "run.collisions_per_particle",
            "give exactly one of run.collisions_per_particle and run.end_time",
        )),
    }
}

/// `run.ranks`: within 1 ..= 1e6, and several only for an engine that spreads over them.
pub(super) fn check_ranks(r: &RunSection, engine: &Abilities) -> Result<()> {
    if let Some(ranks) = r.ranks {
        if !(1..=1_000_000).contains(&ranks) {
            return Err(Error::out_of_range("run.ranks", ranks, "1 <= ranks <= 1e6"));
        }
        if ranks > 1 && !engine.ranks {
            return Err(Error::input(
                "run.ranks",
                format!("several ranks: {}", crate::parallel::spreading()),
            ));
        }
    }
    Ok(())
}

/// `run.histogram_at` and `run.histogram_bins`.
pub(super) fn check_histograms(r: &RunSection, stop: Stop) -> Result<()> {
    if let Some(bins) = r.histogram_bins {
        if !(4..=10_000).contains(&bins) {
            return Err(Error::out_of_range(
                "run.histogram_bins",
                bins,
                "4 <= bins <= 10000",
            ));
        }
    }
    let Some(at) = &r.histogram_at else {
        return Ok(());
    };
    let end = stop.end();
    if at.len() > 10_000 {
        return Err(Error::out_of_range(
            "run.histogram_at",
            format!("a list of {}", at.len()),
            "at most 10000 values",
        ));
    }
    for &x in at {
        if !(0.0..=end).contains(&x) {
            let allowed = format!("0 <= value <= {end} (the end of the run, {})", stop.key());
            return Err(Error::out_of_range("run.histogram_at", x, &allowed));
        }
    }
    let mut sorted = at.clone();
    sorted.sort_by(f64::total_cmp);
    if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
        return Err(Error::input(
            "run.histogram_at",
            format!("{} appears twice", w[0]),
        ));
    }
    Ok(())
}
