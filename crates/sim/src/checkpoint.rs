//! The check-point of a run (`DIR/checkpoint.json`): the run description, the observers'
//! records and the engine's complete state ([`gas::Checkpoint::State`]), so that a resumed
//! run repeats the uninterrupted one bit for bit.

use crate::description::RunDescription;
use crate::error::{Error, Result};
use crate::observer::{TimeSeries, VelocityHistograms};
use crate::output::write_file;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The file name of a check-point in its directory.
pub const FILE_NAME: &str = "checkpoint.json";
/// What the `format` field of a run check-point says.
pub const FORMAT: &str = "haff-run-checkpoint";
/// The version of the layout below; a check-point of another version is refused.
pub const VERSION: u32 = 2;

/// A check-point with the engine state `S` (`serde::de::IgnoredAny` to read the rest
/// first, before the engine is known).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckpointFile<S> {
    pub format: String,
    pub version: u32,
    /// The run file (normalized).
    pub description: RunDescription,
    /// Check-point interval in samples (reused on resume).
    pub every: Option<usize>,
    pub timeseries: TimeSeries,
    pub histograms: VelocityHistograms,
    pub engine: S,
}

/// The serialized form of [`CheckpointFile`], borrowing its parts.
#[derive(Serialize)]
pub(crate) struct CheckpointRef<'a, S> {
    pub format: &'a str,
    pub version: u32,
    pub description: &'a RunDescription,
    pub every: Option<usize>,
    pub timeseries: &'a TimeSeries,
    pub histograms: &'a VelocityHistograms,
    pub engine: &'a S,
}

/// Reads the check-point in `dir` as text.
pub fn read_text(dir: &Path) -> Result<String> {
    let path = dir.join(FILE_NAME);
    std::fs::read_to_string(&path).map_err(|e| Error::Checkpoint {
        path,
        message: e.to_string(),
    })
}

/// Parses a check-point (of `dir`, for messages) with engine state `S`.
pub fn parse<S: DeserializeOwned>(text: &str, dir: &Path) -> Result<CheckpointFile<S>> {
    let fail = |message: String| Error::Checkpoint {
        path: dir.join(FILE_NAME),
        message,
    };
    let file: CheckpointFile<S> =
        serde_json::from_str(text).map_err(|e| fail(format!("not a run check-point: {e}")))?;
    check_format(dir, (&file.format, file.version), (FORMAT, VERSION))?;
    Ok(file)
}

/// Refuses a check-point of `dir` written as `found` (format, version) where `expected`
/// is read.
pub(crate) fn check_format(dir: &Path, found: (&str, u32), expected: (&str, u32)) -> Result<()> {
    if found == expected {
        return Ok(());
    }
    Err(Error::Checkpoint {
        path: dir.join(FILE_NAME),
        message: format!(
            "written as '{}' version {}; this haff reads '{}' version {}",
            found.0, found.1, expected.0, expected.1
        ),
    })
}

/// Writes `file` as `dir/checkpoint.json` atomically (a partial file, then renamed), so
/// that an interrupted write never destroys the last check-point.
pub(crate) fn write<T: Serialize>(dir: &Path, value: &T) -> Result<()> {
    write_file(&dir.join(FILE_NAME), |out| {
        serde_json::to_writer(out, value).map_err(std::io::Error::from)
    })
}
