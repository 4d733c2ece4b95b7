//! Errors of the restitution crate: every message names the offending quantity and its range.

use std::fmt;

/// An invalid argument or a failed computation, with a one-line human message.
#[derive(Debug, Clone, PartialEq)]
pub enum Error {
    /// A parameter outside its allowed range: (name, value as given, allowed range).
    OutOfRange {
        name: String,
        value: String,
        allowed: String,
    },
    /// A text that does not parse (law names, numbers).
    Parse { what: String, message: String },
    /// Something asked for that does not exist, e.g. the Padé approximant of an order
    /// whose linear system is singular (input the user can change, not a failure).
    Undefined(String),
    /// A numerical procedure that did not converge.
    Numerical(String),
}

impl Error {
    pub fn out_of_range(name: &str, value: impl fmt::Display, allowed: &str) -> Self {
        Error::OutOfRange {
            name: name.to_string(),
            value: value.to_string(),
            allowed: allowed.to_string(),
        }
    }
    pub fn parse(what: &str, message: impl Into<String>) -> Self {
        Error::Parse {
            what: what.to_string(),
            message: message.into(),
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::OutOfRange {
                name,
                value,
                allowed,
            } => write!(f, "{name} = {value} is out of range: allowed {allowed}"),
            Error::Parse { what, message } => write!(f, "invalid {what}: {message}"),
            Error::Undefined(m) => write!(f, "undefined: {m}"),
            Error::Numerical(m) => write!(f, "numerical failure: {m}"),
        }
    }
}

impl std::error::Error for Error {}

pub type Result<T> = std::result::Result<T, Error>;

/// Checks that `value` is finite and strictly positive.
pub fn require_positive(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::out_of_range(name, value, "a finite number > 0"))
    }
}

/// Checks that `value` is finite and non-negative.
pub fn require_non_negative(name: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::out_of_range(name, value, "a finite number >= 0"))
    }
}
