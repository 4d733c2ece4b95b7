//! # haff — Python bindings
//!
//! The extension module `haff._haff` behind the Python package `haff` (python/haff): the
//! coefficient of restitution ([`cor`]), the series and Padé engine ([`algebra`]), Giese's
//! rods ([`rods`]), granular-gas runs on the library run driver ([`simulation`]) and studies
//! of many runs ([`study`]). Every
//! function calls the same library code as the `haff` command, with the same checks of its
//! input: a bad argument raises `haff.ConfigError` (a `ValueError`) naming it, never a
//! panic. Long loops run with the GIL released.

use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use restitution::ranges::Range;

mod algebra;
mod cor;
mod particles;
mod rods;
mod simulation;
mod study;
mod theory;

create_exception!(
    _haff,
    ConfigError,
    PyValueError,
    "Bad input: a run description, an argument or a check-point file. The message names the \
     key or argument (e.g. `system.packing_fraction`) and what is allowed, as the haff \
     command's does."
);

/// `key: message` as a [`ConfigError`].
pub(crate) fn config_error(key: &str, message: impl std::fmt::Display) -> PyErr {
    ConfigError::new_err(format!("{key}: {message}"))
}

/// `key: value is out of range; allowed: ...` as a [`ConfigError`].
pub(crate) fn out_of_range(key: &str, value: impl std::fmt::Display, allowed: &str) -> PyErr {
    config_error(key, format!("{value} is out of range; allowed: {allowed}"))
}

/// `low <= key <= high`: the bounds of a library range (`restitution::ranges`,
/// `rods::ranges`) in the wording of the bindings' messages (the argument's Python name,
/// the bounds written out).
pub(crate) fn bounds(key: &str, range: Range) -> String {
    format!("{} <= {key} <= {}", range.low, range.high)
}

/// `x` if `range` contains it, else an out-of-range error naming `key`.
pub(crate) fn within(key: &str, x: f64, range: Range) -> PyResult<f64> {
    if range.contains(x) {
        Ok(x)
    } else {
        Err(out_of_range(key, x, &bounds(key, range)))
    }
}

/// A run-driver error as the Python exception of its kind: input errors as
/// [`ConfigError`], write errors as `OSError`, the rest as `RuntimeError`.
pub(crate) fn sim_error(error: sim::Error) -> PyErr {
    match &error {
        sim::Error::Write { .. } => PyOSError::new_err(error.to_string()),
        e if e.is_input() => ConfigError::new_err(error.to_string()),
        _ => PyRuntimeError::new_err(error.to_string()),
    }
}

#[pymodule]
fn _haff(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("ConfigError", m.py().get_type::<ConfigError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    cor::register(m)?;
    algebra::register(m)?;
    rods::register(m)?;
    simulation::register(m)?;
    study::register(m)?;
    particles::register(m)?;
    theory::register(m)?;
    Ok(())
}
