//! The computer algebra of `haff-series`: the series coefficients of Schwager & Pöschel
//! 2008 to any order and the Padé approximants of Müller & Pöschel 2011, as
//! `haff cor coefficients` and `haff cor pade` compute them (same limits).

use crate::{config_error, out_of_range};
use pyo3::prelude::*;
use series::coefficients::{self, decimal, Kind, Settings};
use series::pade::MAX_DEGREE;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(coefficients_decimal, m)?)?;
    m.add_function(wrap_pyfunction!(pade_decimal, m)?)?;
    Ok(())
}

/// `value` within `low ..= high`, else an error naming `key`.
fn count(key: &str, value: i64, low: usize, high: usize) -> PyResult<usize> {
    usize::try_from(value)
        .ok()
        .filter(|v| (low..=high).contains(v))
        .ok_or_else(|| out_of_range(key, value, &format!("{low} <= {key} <= {high}")))
}

/// The chain settings for `order`, refused if it would take longer than allowed.
fn settings(order: usize, key: &str) -> PyResult<Settings> {
    let settings = Settings::for_order(order.max(2));
    let seconds = settings.estimated_seconds();
    if seconds > coefficients::MAX_SECONDS {
        return Err(config_error(
            key,
            format!(
                "needs about {seconds:.0} s; allowed: at most about {} s (the cost grows as \
                 the order^1.6 and faster with the trajectory order it needs)",
                coefficients::MAX_SECONDS
            ),
        ));
    }
    Ok(settings)
}

/// The coefficients k = 0..=order of `kind` (h, c, a or b) as decimal strings of `digits`
/// significant digits (GIL released while the chain computes).
#[pyfunction]
fn coefficients_decimal(
    py: Python<'_>,
    kind: &str,
    order: i64,
    digits: i64,
) -> PyResult<Vec<String>> {
    let kind: Kind = kind.trim().parse().map_err(|e| config_error("kind", e))?;
    let order = count("order", order, 0, coefficients::MAX_ORDER)?;
    let digits = count("digits", digits, 1, coefficients::MAX_DIGITS)?;
    let settings = settings(kind.chain_order(order), "order")?;
    let values = py
        .detach(|| coefficients::of_kind(kind, order, settings))
        .map_err(|e| config_error("order", e))?;
    Ok(values.iter().map(|x| decimal(x, digits)).collect())
}

/// The Padé approximant [m/n] of eps(v*) (b_0 = 1) as decimal strings of `digits`
/// significant digits, and its poles on the positive real axis below v* = 1e6.
#[pyfunction]
fn pade_decimal(
    py: Python<'_>,
    m: i64,
    n: i64,
    digits: i64,
) -> PyResult<(Vec<String>, Vec<String>, Vec<f64>)> {
    let m = count("m", m, 0, MAX_DEGREE)?;
    let n = count("n", n, 0, MAX_DEGREE)?;
    let digits = count("digits", digits, 1, coefficients::MAX_DIGITS)?;
    let settings = settings(m + n, "m + n")?;
    let approximant = py
        .detach(|| series::pade::pade(&coefficients::compute(settings).h, m, n))
        .map_err(|e| config_error("m/n", e))?;
    let text = |c: &[series::power::Real]| c.iter().map(|x| decimal(x, digits)).collect();
    Ok((
        text(&approximant.numerator),
        text(&approximant.denominator),
        approximant.positive_real_poles(1e6),
    ))
}
