//! The error type of the `haff` command: a one-line message and the process exit code.

use std::fmt;
use std::io;
use std::process::ExitCode;

/// Exit code for invalid command-line input (the same code clap uses for usage errors).
pub const EXIT_BAD_INPUT: u8 = 2;
/// Exit code for failures that are not the user's fault (numerics, I/O).
pub const EXIT_FAILURE: u8 = 1;

/// Why a command failed: a one-line message and the exit code to report.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CliError {
    message: String,
    exit_code: u8,
    /// Whether the message should be suppressed (the reader of stdout went away).
    quiet: bool,
}

impl CliError {
    /// Invalid input in the command-line argument `flag`, e.g. `--vstar`.
    pub fn argument(flag: &str, detail: impl fmt::Display) -> Self {
        CliError {
            message: format!("{flag}: {detail}"),
            exit_code: EXIT_BAD_INPUT,
            quiet: false,
        }
    }

    /// An error reported by the restitution library while handling the argument `flag`.
    ///
    /// Range and parse errors are bad input (exit code 2); numerical failures are not.
    pub fn library(flag: &str, error: restitution::Error) -> Self {
        let exit_code = match error {
            restitution::Error::Numerical(_) => EXIT_FAILURE,
            _ => EXIT_BAD_INPUT,
        };
        CliError {
            message: format!("{flag}: {error}"),
            exit_code,
            quiet: false,
        }
    }

    /// A usage error detected by clap, already condensed to one line.
    pub fn usage(message: String) -> Self {
        CliError {
            message,
            exit_code: EXIT_BAD_INPUT,
            quiet: false,
        }
    }

    /// A failure that is not the input's (exit 1).
    pub fn failure(message: impl fmt::Display) -> Self {
        CliError {
            message: message.to_string(),
            exit_code: EXIT_FAILURE,
            quiet: false,
        }
    }

    /// The same error with another exit code.
    pub fn with_code(mut self, code: u8) -> Self {
        self.exit_code = code;
        self
    }

    /// The exit code for this error.
    pub fn exit_code(&self) -> ExitCode {
        ExitCode::from(self.exit_code)
    }

    /// The exit code as a number.
    pub fn code(&self) -> u8 {
        self.exit_code
    }

    /// Prints `haff: error: <message>` on stderr (nothing for a closed output pipe).
    pub fn report(&self) {
        if !self.quiet {
            eprintln!("haff: error: {}", self.message);
        }
    }
}

impl From<io::Error> for CliError {
    /// Failure to write the output. A closed pipe (`haff demo | head`) ends the command
    /// quietly and successfully, as for other Unix filters.
    fn from(error: io::Error) -> Self {
        let closed_pipe = error.kind() == io::ErrorKind::BrokenPipe;
        CliError {
            message: format!("writing output: {error}"),
            exit_code: if closed_pipe { 0 } else { EXIT_FAILURE },
            quiet: closed_pipe,
        }
    }
}

impl From<sim::Error> for CliError {
    /// Input errors (exit 2) name the key; failures to write outputs exit 1.
    fn from(error: sim::Error) -> Self {
        CliError {
            message: error.to_string(),
            exit_code: if error.is_input() {
                EXIT_BAD_INPUT
            } else {
                EXIT_FAILURE
            },
            quiet: false,
        }
    }
}

impl CliError {
    /// This error, reported by no one (another rank of the run reports it).
    pub fn silenced(mut self) -> Self {
        self.quiet = true;
        self
    }

    /// An error of the run file `path` (its reading, its keys, the run it describes before
    /// it starts): the message names the file first.
    pub fn in_file(path: &std::path::Path) -> impl Fn(sim::Error) -> Self + '_ {
        move |error| {
            let mut e = CliError::from(error);
            if !e.message.contains(&path.display().to_string()) {
                e.message = format!("{}: {}", path.display(), e.message);
            }
            e
        }
    }

    /// An error of `haff ... --resume DIR`: a check-point that cannot be read is named by
    /// the flag.
    pub fn resume(error: sim::Error) -> Self {
        match error {
            sim::Error::Checkpoint { .. } => CliError::argument("--resume", error),
            other => other.into(),
        }
    }
}

impl From<serde_json::Error> for CliError {
    fn from(error: serde_json::Error) -> Self {
        match error.io_error_kind() {
            Some(kind) => io::Error::from(kind).into(),
            None => CliError {
                message: format!("writing JSON: {error}"),
                exit_code: EXIT_FAILURE,
                quiet: false,
            },
        }
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

/// The result type of every command.
pub type CliResult<T = ()> = Result<T, CliError>;
