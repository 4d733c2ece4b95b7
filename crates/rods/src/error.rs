//! Errors of the rods crate: every message names the offending parameter and, for values
//! out of range, the allowed range.

use std::fmt::Display;

/// Why a rods computation was refused or failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A parameter outside its allowed range: its name, the value as given and the
    /// allowed range (e.g. `gamma`, `0`, `a finite number > 0`).
    #[error("{name} = {value} is out of range: allowed {allowed}")]
    OutOfRange {
        name: String,
        value: String,
        allowed: String,
    },
    /// A per-rod list (`positions`, `velocities`) whose length is not the number of rods.
    #[error("{name} has {len} entries, must have one per rod ({rods})")]
    WrongLength {
        name: &'static str,
        len: usize,
        rods: usize,
    },
    /// The initial gap of contact `contact` (between rods `contact` and `contact + 1`) is
    /// too small: the rods overlap or start in contact.
    #[error(
        "positions: gap {contact} is {gap}, must exceed (z_cut+2)/alpha = {min} \
         (rods may not overlap or start in contact)"
    )]
    Overlap { contact: usize, gap: f64, min: f64 },
    /// A change of the chain's state (`operation`) while a contact episode is open.
    #[error("{operation}: not allowed while a contact episode is in progress")]
    ContactInProgress { operation: &'static str },
    /// The two-rod experiment ended before the requested number of collisions.
    #[error("two rods: no further collision after {collisions} collisions")]
    NoFurtherCollision { collisions: usize },
    /// An error of the restitution crate (e.g. building a collision law from a table).
    #[error(transparent)]
    Restitution(#[from] restitution::Error),
}

impl Error {
    /// [`Error::OutOfRange`] from any displayable value.
    pub fn out_of_range(
        name: impl Into<String>,
        value: impl Display,
        allowed: impl Into<String>,
    ) -> Self {
        Error::OutOfRange {
            name: name.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}

/// The result type of the rods crate.
pub type Result<T> = std::result::Result<T, Error>;

/// Checks that `value` is finite and > 0.
pub(crate) fn positive(name: impl Into<String>, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::out_of_range(name, value, "a finite number > 0"))
    }
}

/// Checks that `value` is finite and >= 0.
pub(crate) fn non_negative(name: impl Into<String>, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::out_of_range(name, value, "a finite number >= 0"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_parameter_value_and_range() {
        let e = positive("gamma", -1.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "gamma = -1 is out of range: allowed a finite number > 0"
        );
        assert!(non_negative("temperature", 0.0).is_ok());
        assert!(non_negative("temperature", f64::NAN).is_err());
        let r = restitution::Error::Numerical("no convergence".into());
        assert_eq!(Error::from(r.clone()).to_string(), r.to_string());
    }
}
