//! Errors of the run driver. Whether the user's input caused one ([`Error::is_input`]) decides
//! the exit code of the `haff` command (2, else 1) and the exception class in Python.

use std::path::PathBuf;

/// Why a run could not be described, started, continued or written.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A key of the run description (`section.key`) with a bad value, or a key the run
    /// does not allow; the message says what is allowed.
    #[error("{key}: {message}")]
    Input { key: String, message: String },
    /// A run file that cannot be read or is not TOML.
    #[error("{}: {message}", path.display())]
    RunFile { path: PathBuf, message: String },
    /// A particle file that cannot be read, or whose particles a run cannot start from:
    /// `at` names the line or record (or `box`, `frame`), the message the field.
    #[error("{}: {at}: {message}", path.display())]
    ParticleFile {
        path: PathBuf,
        at: String,
        message: String,
    },
    /// A check-point that cannot be read or does not belong to a run of this kind.
    #[error("{}: {message}", path.display())]
    Checkpoint { path: PathBuf, message: String },
    /// The event-driven engine stopped at inelastic collapse (the input asks for a run that
    /// cannot go on without the TC model).
    #[error(
        "collision.tc: inelastic collapse at t = {time}: {} collisions per particle without \
         time advancing; switch on the TC model (collision.tc > 0)",
        gas::emd::COLLAPSE_COLLISIONS_PER_PARTICLE
    )]
    Collapse { time: f64 },
    /// A numerical procedure that failed on valid input (an internal failure, not the
    /// user's): `key` names what was being computed.
    #[error("{key}: {message}")]
    Numerical { key: String, message: String },
    /// An output file that could not be written.
    #[error("writing {}: {source}", path.display())]
    Write {
        path: PathBuf,
        source: std::io::Error,
    },
    /// The run was interrupted between two pieces (Ctrl-C in Python): it stands where it
    /// stopped and can go on.
    #[error("interrupted at t = {time}")]
    Interrupted { time: f64 },
    /// A figure that could not be drawn.
    #[error("writing {}: {message}", path.display())]
    Plot { path: PathBuf, message: String },
}

impl Error {
    /// `key: message`.
    pub fn input(key: impl Into<String>, message: impl std::fmt::Display) -> Self {
        Error::Input {
            key: key.into(),
            message: message.to_string(),
        }
    }

    /// `key: value is out of range; allowed: ...`.
    pub fn out_of_range(key: &str, value: impl std::fmt::Display, allowed: &str) -> Self {
        Error::input(key, format!("{value} is out of range; allowed: {allowed}"))
    }

    /// Whether the user's input caused the error (exit code 2), rather than the machine.
    pub fn is_input(&self) -> bool {
        !matches!(
            self,
            Error::Write { .. }
                | Error::Plot { .. }
                | Error::Numerical { .. }
                | Error::Interrupted { .. }
        )
    }

    /// A restitution error about `key`: numerical failures are internal, all else input.
    pub fn law(key: &str, error: restitution::Error) -> Self {
        match error {
            restitution::Error::Numerical(message) => Error::Numerical {
                key: key.to_string(),
                message,
            },
            other => Error::input(key, other),
        }
    }

    /// The error of writing `path`.
    pub fn write(path: &std::path::Path, source: std::io::Error) -> Self {
        Error::Write {
            path: path.to_path_buf(),
            source,
        }
    }
}

/// The result type of the run driver.
pub type Result<T> = std::result::Result<T, Error>;

/// `x`, if finite and > 0, else an error naming `key`.
pub(crate) fn positive(key: &str, x: f64) -> Result<f64> {
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(Error::out_of_range(key, x, "a finite number > 0"))
    }
}
