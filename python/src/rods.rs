//! Giese's vibrating rods: eps of the collision equation, Eq. (3), deterministic (a cold
//! bath) and stochastic (thermal noise, Eq. (5)), as `haff rods deterministic` and
//! `haff rods collide` compute them (same ranges, same bound on the work of one call).

use crate::{config_error, out_of_range, within};
use numpy::PyArray1;
use pyo3::prelude::*;
use rods::deterministic::{
    eps_closed_form, eps_closed_form_general, eps_numeric, estimated_work, WORK_LIMIT,
    WORK_PER_SECOND,
};
use rods::ranges::{BATH_RATIO, GAMMA, KAPPA, REALIZATIONS, STEP};
use rods::stochastic::{sample_eps, Resolution};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(rods_deterministic, m)?)?;
    m.add_function(wrap_pyfunction!(rods_closed_form, m)?)?;
    m.add_function(wrap_pyfunction!(rods_collide, m)?)?;
    Ok(())
}

/// Refuses work beyond [`WORK_LIMIT`], naming `key`.
fn bounded(key: &str, work: f64) -> PyResult<()> {
    if work > WORK_LIMIT {
        return Err(config_error(
            key,
            format!(
                "needs about {:.0} s; allowed: at most about {:.0} s per call (the work grows as \
                 kappa / step and as 1/gamma^2 or gamma^2 away from 1)",
                work / WORK_PER_SECOND,
                WORK_LIMIT / WORK_PER_SECOND
            ),
        ));
    }
    Ok(())
}

/// eps of Eq. (3) at T_bath = 0 (the solved value), step h = `step` / kappa.
#[pyfunction]
fn rods_deterministic(py: Python<'_>, gamma: f64, kappa: f64, step: f64) -> PyResult<f64> {
    let gamma = within("gamma", gamma, GAMMA)?;
    let kappa = within("kappa", kappa, KAPPA)?;
    if !STEP.contains(step) {
        let allowed = format!("{} < step < {} ({})", STEP.low, STEP.high, STEP.name);
        return Err(out_of_range("step", step, &allowed));
    }
    bounded("gamma", estimated_work(gamma, kappa, step / kappa))?;
    Ok(py.detach(|| eps_numeric(gamma, kappa, step / kappa)))
}

/// Giese's closed form of eps (the paper's, or the generalized one); NaN where undefined
/// (gamma = 1).
#[pyfunction]
fn rods_closed_form(gamma: f64, kappa: f64, general: bool) -> PyResult<f64> {
    let gamma = within("gamma", gamma, GAMMA)?;
    let kappa = within("kappa", kappa, KAPPA)?;
    let eps = if general {
        eps_closed_form_general(gamma, kappa)
    } else {
        eps_closed_form(gamma, kappa)
    };
    Ok(if eps.is_finite() { eps } else { f64::NAN })
}

/// eps of `realizations` collisions with thermal noise; `bath_ratio` = E_tr / T_bath
/// (infinite: a cold bath).
#[pyfunction]
fn rods_collide<'py>(
    py: Python<'py>,
    gamma: f64,
    kappa: f64,
    bath_ratio: f64,
    realizations: i64,
    seed: u64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let gamma = within("gamma", gamma, GAMMA)?;
    let kappa = within("kappa", kappa, KAPPA)?;
    if !(bath_ratio == f64::INFINITY || BATH_RATIO.contains(bath_ratio)) {
        let (low, name, high) = (BATH_RATIO.low, BATH_RATIO.name, BATH_RATIO.high);
        let allowed = format!("{low:e} <= {name} <= {high:e}, or None (a cold bath)");
        return Err(out_of_range("bath_ratio", bath_ratio, &allowed));
    }
    let realizations = usize::try_from(realizations)
        .ok()
        .filter(|&r| REALIZATIONS.contains(r as f64))
        .ok_or_else(|| out_of_range("realizations", realizations, &REALIZATIONS.describe()))?;
    let h = Resolution::default().h(kappa, bath_ratio);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get()) as f64;
    bounded(
        "realizations",
        realizations as f64 * estimated_work(gamma, kappa, h) / cores,
    )?;
    let eps = py
        .detach(|| sample_eps(gamma, kappa, bath_ratio, realizations, seed))
        .map_err(|e| config_error("gamma", e))?;
    Ok(PyArray1::from_vec(py, eps))
}
