//! `summary.json`'s `green_kubo`: the shear viscosity of an elastic gas at equilibrium from
//! the fluctuations of its pressure tensor (`output.pressure` without `[shear]`), by the
//! Einstein–Helfand form of the Green–Kubo formula (`gas::observe::green_kubo`).
//!
//! Each row of `pressure.csv` past the first is taken as the pressure averaged over the
//! interval since the previous row: exact for the collisional part, the kinetic part
//! sampled at the row's end (its bias grows with the interval: +0.2 % from τ/10 to τ/5, +1 %
//! to 0.4 τ, τ the mean free time; docs/shear.md). The rows must be equally spaced in time
//! (`run.end_time` with `spacing = "linear"`), at most τ/4 apart; the slope of the Helfand moment's mean square is taken
//! between the lags 5 τ and 20 τ (the stress of a dilute gas decorrelates in about 1.25 τ,
//! so the bias of the window is below 0.2 %; denser gases: docs/shear.md), in up to 10
//! batches of at least 40 τ (at least 5, else `skipped` says why). τ = t / (collisions per
//! particle) of the last row. Only an elastic gas (constant restitution 1) without driving,
//! walls, gravity or shear is at equilibrium; any other run gets `skipped` with the reason.
//! The fluctuations are those of the simulated particles: the volume per simulated particle
//! enters (V / W with the particle weight W).
//!
//! Theory beside it, for one species in 2D and 3D: Enskog's viscosity of the elastic gas in
//! the first Sonine approximation at the run's packing fraction (`gas::theory::NavierStokes`)
//! and, in 3D, the dilute Chapman–Enskog value (converged Sonine series), both over
//! η0(T) = the dilute first Sonine viscosity at the measured temperature.

use crate::output::number;
use crate::rheology::PressureSeries;
use crate::validate::{LawSpec, Plan};
use gas::observe::green_kubo::helfand_viscosity;

/// Fit window of the Helfand moment's slope, in mean free times.
const FIT_FROM: f64 = 5.0;
const FIT_TO: f64 = 20.0;
/// Most rows apart, in mean free times.
const COARSEST_INTERVAL: f64 = 0.25;
const MOST_BATCHES: usize = 10;
const FEWEST_BATCHES: usize = 5;

fn skipped(reason: String) -> serde_json::Value {
    serde_json::json!({ "skipped": reason })
}

/// Why the run has no equilibrium viscosity to measure, if it has none.
fn not_at_equilibrium(plan: &Plan) -> Option<String> {
    if plan.shear.is_some() {
        return Some("a sheared gas: see rheology".into());
    }
    let has = match &plan.law {
        LawSpec::Constant(a) if *a == 1.0 => None,
        LawSpec::Constant(a) => Some(format!("collision.restitution = {}", number(*a))),
        LawSpec::ConstantPairs { .. } => Some("a restitution per pair of species".into()),
        LawSpec::Dashpot { .. } => Some("collision.law = \"dashpot\"".into()),
        LawSpec::Viscoelastic { .. } | LawSpec::ViscoelasticPairs { .. } => {
            Some("collision.law = \"viscoelastic\"".into())
        }
        LawSpec::Stochastic { .. } => Some("collision.law = \"stochastic\"".into()),
    };
    if let Some(has) = has {
        return Some(format!(
            "not elastic: this run has {has}; the equilibrium viscosity needs an elastic gas \
             (law = \"constant\", restitution = 1)"
        ));
    }
    if plan.driving.is_some() || !plan.walls.is_empty() || plan.gravity.is_some() {
        return Some("driving, walls or gravity: the gas is not at equilibrium".into());
    }
    None
}

/// `summary.json`'s `green_kubo` of an unsheared run measuring the pressure tensor.
pub fn summary<const D: usize>(plan: &Plan, series: &PressureSeries) -> serde_json::Value {
    if let Some(reason) = not_at_equilibrium(plan) {
        return skipped(reason);
    }
    let rows = &series.samples;
    let (Some(first), Some(last)) = (rows.first(), rows.last()) else {
        return skipped("no samples".into());
    };
    if rows.len() < 3 || last.collisions_per_particle <= 0.0 || D < 2 {
        return skipped("fewer than three samples, no collisions, or 1D".into());
    }
    let count = rows.len() - 1;
    let interval = (last.time - first.time) / count as f64;
    let uneven = rows
        .windows(2)
        .map(|w| (w[1].time - w[0].time - interval).abs())
        .fold(0.0, f64::max);
    if !(interval.is_finite() && interval > 0.0) || uneven > 1e-6 * interval {
        return skipped(
            "samples not equally spaced in time: give run.end_time with run.spacing = \"linear\""
                .into(),
        );
    }
    let free_time = last.time / last.collisions_per_particle;
    if interval > COARSEST_INTERVAL * free_time {
        return skipped(format!(
            "samples {} mean free times apart: at most {COARSEST_INTERVAL} (more run.samples)",
            interval / free_time
        ));
    }
    let fit = (
        (FIT_FROM * free_time / interval).ceil() as usize,
        (FIT_TO * free_time / interval).ceil() as usize,
    );
    let batches = (count / (2 * fit.1)).min(MOST_BATCHES);
    if batches < FEWEST_BATCHES {
        return skipped(format!(
            "the run is {} mean free times long: at least {} for {FEWEST_BATCHES} batches",
            last.time / free_time,
            2.0 * FIT_TO * FEWEST_BATCHES as f64
        ));
    }
    let pressures: Vec<[f64; 6]> = rows[1..].iter().map(|s| s.pressure).collect();
    let temperature = rows[1..].iter().map(|s| s.temperature).sum::<f64>() / count as f64;
    let simulated = plan.description.system.particles as f64;
    let volume = simulated / last.density;
    let Some(eta) = helfand_viscosity::<D>(&pressures, interval, volume, temperature, fit, batches)
    else {
        return skipped("the estimate failed (non-finite samples)".into());
    };
    let (diameter, mass) = (plan.species[0].diameter, plan.species[0].mass);
    let eta0 = gas::theory::dilute_elastic_viscosity::<D>(diameter, mass, temperature);
    let mut out = serde_json::json!({
        "method": "Einstein-Helfand (Green-Kubo) of the traceless pressure tensor, all components",
        "temperature": temperature,
        "mean_free_time": free_time,
        "sample_interval": interval,
        "fit_from": fit.0 as f64 * interval,
        "fit_to": fit.1 as f64 * interval,
        "batches": eta.batches,
        "viscosity": { "mean": eta.viscosity, "error": eta.error },
        "reduced_viscosity": { "mean": eta.viscosity / eta0, "error": eta.error / eta0 },
    });
    if plan.species.len() == 1 {
        let phi = plan.description.packing_fraction();
        let enskog = match D {
            2 => gas::theory::ReducedTransport::enskog::<2>(phi, 1.0),
            _ => gas::theory::ReducedTransport::enskog::<3>(phi, 1.0),
        };
        out["theory"] = serde_json::json!({ "enskog_first_sonine": enskog.shear_viscosity });
        if D == 3 {
            out["theory"]["chapman_enskog_dilute"] =
                serde_json::json!(gas::theory::transport::ELASTIC_VISCOSITY_SONINE_FACTOR);
        }
    }
    out
}
