//! Output directories owned by one run. A run writes a manifest (`haff-run.json`: which
//! command, a hash of its run description, the haff version, and its state: running,
//! stopped or complete) before anything else, so that outputs of two runs are never mixed:
//!
//! - a new run goes into a new or empty directory, or into one holding another haff run's
//!   outputs only with `force` (which removes those outputs first); a directory holding
//!   files of anything else is refused, `force` or not;
//! - a resumed run continues only in a directory whose manifest names the same run (same
//!   command and description hash), or in a new or empty one.

use crate::error::{Error, Result};
use crate::output::write_json_file;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The file name of the manifest.
pub const MANIFEST: &str = "haff-run.json";

/// The files a haff run may write into its directory (besides `ed_mc_<law>.csv` of
/// `haff rods chain` and the `.partial` files of interrupted writes).
const OUTPUTS: [&str; 8] = [
    "timeseries.csv",
    "species.csv",
    "velocity_histograms.csv",
    "temperature.png",
    "cooling.png",
    "summary.json",
    crate::checkpoint::FILE_NAME,
    crate::checkpoint::LEGACY_FILE_NAME,
];

/// Where a run stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RunState {
    /// Started (and still running, or killed).
    Running,
    /// Stopped after a number of samples, to be resumed.
    Stopped,
    /// Every sample taken, outputs final.
    Complete,
}

/// The manifest of an output directory.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// `run` or `rods chain`.
    pub command: String,
    /// CRC-32 of the run description's JSON (normalized), `crc32:xxxxxxxx`.
    pub run_hash: String,
    pub haff_version: String,
    pub state: RunState,
}

/// The hash that names a run: CRC-32 of its description as JSON.
pub fn run_hash<T: Serialize>(description: &T) -> String {
    let json = serde_json::to_vec(description).unwrap_or_default();
    format!("crc32:{:08x}", crc32fast::hash(&json))
}

/// An output directory claimed by a run.
#[derive(Debug, Clone)]
pub struct OutputDir {
    path: PathBuf,
    manifest: Manifest,
}

impl OutputDir {
    /// The output directory of a run of `command` with description hash `hash`: claimed
    /// for a new run ([`OutputDir::claim`]), or, for a run resumed from the check-point in
    /// `resumed_from`, checked for it ([`OutputDir::verify`], [`OutputDir::for_resume`]).
    pub fn open(
        path: &Path,
        resumed_from: Option<&Path>,
        command: &str,
        hash: &str,
        force: bool,
    ) -> Result<Self> {
        match resumed_from {
            None => Self::claim(path, command, hash, force),
            Some(from) => {
                Self::verify(from, command, hash)?;
                Self::for_resume(path, command, hash)
            }
        }
    }

    /// The directory of a new run of `command` with description hash `hash` (see the
    /// module documentation); writes the manifest with state running.
    pub fn claim(path: &Path, command: &str, hash: &str, force: bool) -> Result<Self> {
        let fail =
            |message: String| Error::input("--out", format!("{}: {message}", path.display()));
        match read_manifest(path)? {
            Contents::Missing | Contents::Empty => {}
            Contents::Run(_) if force => remove_outputs(path).map_err(|e| fail(e.to_string()))?,
            Contents::Run(old) => return Err(fail(occupied(path, &old, command, hash))),
            Contents::Foreign(file) => {
                return Err(fail(format!(
                    "holds files that are not a haff run's (e.g. {file}); choose a new or \
                     empty directory"
                )))
            }
        }
        Self::create(path, command, hash)
    }

    /// The directory a resumed run writes into: the manifest must name the same run (or the
    /// directory is new or empty).
    pub fn for_resume(path: &Path, command: &str, hash: &str) -> Result<Self> {
        let fail =
            |message: String| Error::input("--out", format!("{}: {message}", path.display()));
        match read_manifest(path)? {
            Contents::Missing | Contents::Empty => Self::create(path, command, hash),
            Contents::Run(old) if old.command == command && old.run_hash == hash => {
                let mut dir = OutputDir {
                    path: path.to_path_buf(),
                    manifest: old,
                };
                dir.set_state(RunState::Running)?;
                Ok(dir)
            }
            Contents::Run(old) => Err(fail(format!(
                "holds the outputs of another run (haff {}, {}) than the check-point's ({hash})",
                old.command, old.run_hash
            ))),
            Contents::Foreign(file) => Err(fail(format!(
                "holds files that are not a haff run's (e.g. {file})"
            ))),
        }
    }

    /// The directory a run's outputs are written into again and again (Python's
    /// `Simulation.write`): new, empty, or holding the outputs of the same run (updated);
    /// another run's outputs are replaced only with `force`; other files never.
    pub fn for_writing(path: &Path, command: &str, hash: &str, force: bool) -> Result<Self> {
        match read_manifest(path)? {
            Contents::Run(old) if old.command == command && old.run_hash == hash => {
                Self::for_resume(path, command, hash)
            }
            Contents::Run(old) if !force => Err(Error::input(
                "--out",
                format!(
                    "{}: holds the outputs of another {} (description {}); write with force \
                     to replace them",
                    path.display(),
                    command_name(&old.command),
                    old.run_hash
                ),
            )),
            _ => Self::claim(path, command, hash, force),
        }
    }

    /// Checks that `path`, where a check-point is read, holds the outputs of the run with
    /// description hash `hash` (the check-point's).
    pub fn verify(path: &Path, command: &str, hash: &str) -> Result<()> {
        match read_manifest(path)? {
            Contents::Run(old) if old.command == command && old.run_hash == hash => Ok(()),
            Contents::Run(old) => Err(Error::input(
                "--resume",
                format!(
                    "{}: its manifest names another run (haff {}, {}) than its check-point ({hash})",
                    path.display(),
                    old.command,
                    old.run_hash
                ),
            )),
            _ => Err(Error::input(
                "--resume",
                format!("{}: no {MANIFEST}: not the directory of a haff run", path.display()),
            )),
        }
    }

    fn create(path: &Path, command: &str, hash: &str) -> Result<Self> {
        std::fs::create_dir_all(path)
            .map_err(|e| Error::input("--out", format!("{}: {e}", path.display())))?;
        let mut dir = OutputDir {
            path: path.to_path_buf(),
            manifest: Manifest {
                command: command.to_string(),
                run_hash: hash.to_string(),
                haff_version: crate::checkpoint::HAFF_VERSION.to_string(),
                state: RunState::Running,
            },
        };
        dir.set_state(RunState::Running)?;
        Ok(dir)
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Records the run's state in the manifest.
    pub fn set_state(&mut self, state: RunState) -> Result<()> {
        self.manifest.state = state;
        write_json_file(&self.path.join(MANIFEST), &self.manifest)
    }
}

/// Why a new run of `command` with description hash `hash` does not go into `path`, which
/// holds the outputs of the run of `old`, and what the user can do. The same command and
/// hash are the same run (the same description: a re-run repeats it), not another one.
fn occupied(path: &Path, old: &Manifest, command: &str, hash: &str) -> String {
    let state = match old.state {
        RunState::Running => "running, or killed",
        RunState::Stopped => "stopped",
        RunState::Complete => "complete",
    };
    let saved = [
        crate::checkpoint::FILE_NAME,
        crate::checkpoint::LEGACY_FILE_NAME,
    ]
    .iter()
    .any(|name| path.join(name).exists());
    let resume = match old.state != RunState::Complete && saved {
        true => format!(", or --resume {} to continue it", path.display()),
        false => String::new(),
    };
    if old.command == command && old.run_hash == hash {
        format!("holds this run's outputs already ({state}); give --force to run it again from the start{resume}")
    } else {
        format!(
            "holds the outputs of another {} ({state}); give --force to replace them{resume}",
            command_name(&old.command)
        )
    }
}

/// `haff run`, `haff rods chain run`: the run of a manifest's command, for messages.
fn command_name(command: &str) -> String {
    match command {
        "run" => "haff run".to_string(),
        other => format!("haff {other} run"),
    }
}

/// What a directory holds.
enum Contents {
    Missing,
    Empty,
    Run(Manifest),
    /// Files, but no manifest: the name of one of them.
    Foreign(String),
}

fn read_manifest(path: &Path) -> Result<Contents> {
    let fail = |message: String| Error::input("--out", format!("{}: {message}", path.display()));
    if !path.exists() {
        return Ok(Contents::Missing);
    }
    if !path.is_dir() {
        return Err(fail("not a directory".into()));
    }
    let manifest = path.join(MANIFEST);
    if manifest.exists() {
        let text = std::fs::read_to_string(&manifest).map_err(|e| fail(e.to_string()))?;
        let manifest: Manifest = serde_json::from_str(&text)
            .map_err(|e| fail(format!("{MANIFEST} is not a haff manifest: {e}")))?;
        return Ok(Contents::Run(manifest));
    }
    let mut entries = std::fs::read_dir(path).map_err(|e| fail(e.to_string()))?;
    Ok(match entries.next() {
        None => Contents::Empty,
        Some(entry) => {
            let entry = entry.map_err(|e| fail(e.to_string()))?;
            Contents::Foreign(entry.file_name().to_string_lossy().into_owned())
        }
    })
}

/// Whether `name` is a file of the `[output]` observers (`crate::space`).
fn is_space_output(name: &str) -> bool {
    let numbered = |prefix: &str, extensions: &[&str]| {
        name.strip_prefix(prefix).is_some_and(|rest| {
            extensions.iter().any(|ext| {
                rest.strip_suffix(ext)
                    .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
            })
        })
    };
    [
        "modes.csv",
        "structure.csv",
        "fields.pvd",
        "snapshots.pvd",
        "snapshots.lammpstrj",
        "snapshots.xyz",
        "snapshots.h5md",
    ]
    .contains(&name)
        || numbered("fields_", &[".vti", ".png"])
        || numbered("snapshot_", &[".vtu"])
}

/// Removes the outputs of a haff run (and its manifest) from `path`; other files stay.
fn remove_outputs(path: &Path) -> std::io::Result<()> {
    for entry in std::fs::read_dir(path)? {
        let entry = entry?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let ours = OUTPUTS.contains(&name.as_str())
            || name == MANIFEST
            || name.ends_with(".partial")
            || (name.starts_with("ed_mc_") && name.ends_with(".csv"))
            || is_space_output(&name);
        if ours && entry.file_type()?.is_file() {
            std::fs::remove_file(entry.path())?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{is_space_output, OutputDir, RunState};

    /// `--force` removes the observers' files of the previous run, and only those.
    #[test]
    fn space_outputs_are_recognized() {
        for ours in [
            "modes.csv",
            "structure.csv",
            "fields.pvd",
            "snapshots.pvd",
            "fields_000010.vti",
            "fields_000010.png",
            "snapshot_000000.vtu",
            "snapshots.lammpstrj",
            "snapshots.xyz",
            "snapshots.h5md",
            "snapshots.h5md",
        ] {
            assert!(is_space_output(ours), "{ours}");
        }
        for theirs in [
            "fields_.vti",
            "fields_x1.vti",
            "snapshot_000001.vti",
            "notes.csv",
            "snapshot_1.vtu.bak",
        ] {
            assert!(!is_space_output(theirs), "{theirs}");
        }
    }

    /// A second run into a run's directory is told whose outputs are there (the same
    /// description is this run, not another) and what to give; --resume only where a
    /// stopped run saved a check-point.
    #[test]
    fn a_claimed_directory_says_whose_it_is() {
        let dir = std::env::temp_dir().join(format!("haff-outdir-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        let mut first = OutputDir::claim(&dir, "run", "crc32:00000001", false).unwrap();
        first.set_state(RunState::Complete).unwrap();
        let refused = |hash: &str| {
            OutputDir::claim(&dir, "run", hash, false)
                .unwrap_err()
                .to_string()
        };
        let same = refused("crc32:00000001");
        assert!(
            same.contains("this run's outputs already (complete)"),
            "{same}"
        );
        assert!(!same.contains("--resume"), "{same}");
        let other = refused("crc32:00000002");
        assert!(
            other.contains("another haff run (complete); give --force"),
            "{other}"
        );
        first.set_state(RunState::Stopped).unwrap();
        std::fs::write(dir.join(crate::checkpoint::FILE_NAME), b"").unwrap();
        let stopped = refused("crc32:00000002");
        assert!(
            stopped.contains("(stopped)") && stopped.contains("--resume"),
            "{stopped}"
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}
