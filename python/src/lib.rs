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

// Declared in the module `haff`, which re-exports it: tracebacks and help() name it
// `haff.ConfigError`, and pickle (a process pool's or dask's worker raising it) finds it.
create_exception!(
    haff,
    ConfigError,
    PyValueError,
    "Bad input: a run description, an argument, a particle or check-point file.\n\n\
     A ``ValueError`` whose message names the key or argument (e.g. \
     ``system.packing_fraction``, ``vstar[0]``) and what is allowed, as the message of the \
     ``haff`` command does (which exits with status 2 there).\n\n\
     Examples\n\
     --------\n\
     >>> import haff\n\
     >>> try:\n\
     ...     haff.eps(-1.0)\n\
     ... except haff.ConfigError as error:\n\
     ...     print(error)\n\
     vstar[0]: -1 is out of range; allowed: 0 <= vstar <= 1000000\n\
     >>> issubclass(haff.ConfigError, ValueError)\n\
     True\n"
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
