//! Check-points: one file, `DIR/checkpoint.bin`, from which a run continues bit for bit.
//!
//! Layout (of a [`Format`] and its version; `haff run`'s is [`RUN`], version 5: 4 added
//! the DSMC engines' per-species collision counts to the engine state, 5 the driver's
//! position and the records keyed by observer):
//!
//! ```text
//! {"format":"haff-run-checkpoint","version":5,"haff_version":"0.1.0","records_bytes":R,"engine_bytes":E,"crc32":C}\n
//! <R bytes: the records as one JSON object: the caller's (run description, interval), the
//!  driver's position ("driver"), then each observer's under its name>\n
//! <E bytes: the engine's complete state (gas::Checkpoint::State), postcard-encoded>
//! ```
//!
//! The first line says what the file is and which haff wrote it; C is the CRC-32 of the
//! records and engine bytes, so an edited, truncated or damaged file is refused before it is
//! read. The records stay readable JSON; the engine state, O(N), is binary (f64 as 8
//! bytes, lengths as varints: about 70 bytes per particle for the event-driven engine in
//! 3D). After the checksum, the driver checks the content for meaning (the run description
//! like a fresh run, the engine state against it: see `engines`).

use crate::error::{Error, Result};
use crate::output::write_file;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use std::collections::BTreeMap;
use std::path::Path;

/// The file name of a check-point in its directory.
pub const FILE_NAME: &str = "checkpoint.bin";
/// The file name older versions (1, 2: all JSON) wrote.
pub const LEGACY_FILE_NAME: &str = "checkpoint.json";

/// What a check-point holds, and the version of its content: a check-point of another
/// format or version is refused, naming both.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Format {
    pub name: &'static str,
    pub version: u32,
}

/// The check-points of `haff run` (`crate::Simulation`).
pub const RUN: Format = Format {
    name: "haff-run-checkpoint",
    version: 5,
};
/// The version of haff that writes.
pub const HAFF_VERSION: &str = env!("CARGO_PKG_VERSION");
/// The longest first line read before a file is declared foreign.
const MAX_HEADER: usize = 4096;

/// The first line of a check-point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Header {
    format: String,
    version: u32,
    haff_version: String,
    records_bytes: u64,
    engine_bytes: u64,
    crc32: u32,
}

/// A check-point read and verified (format, version, lengths, checksum), not yet decoded.
#[derive(Debug)]
pub struct Sections {
    path: std::path::PathBuf,
    records: Vec<u8>,
    engine: Vec<u8>,
}

impl Sections {
    /// The records, as `R`.
    pub fn records<R: DeserializeOwned>(&self) -> Result<R> {
        serde_json::from_slice(&self.records).map_err(|e| self.error(format!("records: {e}")))
    }

    /// The engine state, as `S`. A state may end with optional parts written only when
    /// present (`gas::tail::Tail`: walls, shear, tensor virial; postcard cannot tell their
    /// absence from the end of the data); zero bytes after the end read as their absence. Bytes after a state are never read otherwise,
    /// and the file's lengths and checksum are verified before.
    pub fn engine<S: DeserializeOwned>(&self) -> Result<S> {
        let mut bytes = Vec::with_capacity(self.engine.len() + gas::tail::TAIL_PADDING);
        bytes.extend_from_slice(&self.engine);
        bytes.extend([0; gas::tail::TAIL_PADDING]);
        postcard::from_bytes(&bytes).map_err(|e| self.error(format!("engine state: {e}")))
    }

    /// An error about this check-point.
    pub fn error(&self, message: impl std::fmt::Display) -> Error {
        Error::Checkpoint {
            path: self.path.clone(),
            message: message.to_string(),
        }
    }
}

/// `state` encoded as the engine section of a check-point (postcard).
pub fn encode_state<S: Serialize>(state: &S) -> Result<Vec<u8>> {
    postcard::to_stdvec(state).map_err(|e| Error::Numerical {
        key: "check-point".into(),
        message: format!("encoding the engine state: {e}"),
    })
}

/// Writes the check-point of `format` with `records` and the encoded engine `state` as the
/// file `path` atomically (a partial file, then renamed), so that an interrupted write
/// never destroys the last one.
pub fn write_to<R: Serialize>(
    path: &Path,
    format: Format,
    records: &R,
    state: &[u8],
) -> Result<()> {
    let path = path.to_path_buf();
    let records = serde_json::to_vec(records).map_err(|e| Error::write(&path, e.into()))?;
    let mut crc = crc32fast::Hasher::new();
    crc.update(&records);
    crc.update(state);
    let header = Header {
        format: format.name.to_string(),
        version: format.version,
        haff_version: HAFF_VERSION.to_string(),
        records_bytes: records.len() as u64,
        engine_bytes: state.len() as u64,
        crc32: crc.finalize(),
    };
    write_file(&path, |out| {
        serde_json::to_writer(&mut *out, &header).map_err(std::io::Error::from)?;
        out.write_all(b"\n")?;
        out.write_all(&records)?;
        out.write_all(b"\n")?;
        out.write_all(state)
    })
}

/// Reads the check-point of `format` in `dir` and verifies it: a haff check-point of this
/// format and version, complete (nothing missing, nothing appended) and with the checksum
/// of its content.
pub fn read(dir: &Path, format: Format) -> Result<Sections> {
    let path = dir.join(FILE_NAME);
    if !path.exists() && dir.join(LEGACY_FILE_NAME).exists() {
        return Err(Error::Checkpoint {
            path: dir.join(LEGACY_FILE_NAME),
            message: format!(
                "a check-point of an older haff (format version 1 or 2, all JSON); this haff \
                 reads version {} ({FILE_NAME})",
                format.version
            ),
        });
    }
    read_from(&path, format)
}

/// Reads the check-point file `path` of `format` and verifies it, as [`read`] does.
pub fn read_from(path: &Path, format: Format) -> Result<Sections> {
    let path = path.to_path_buf();
    let fail = |message: String| Error::Checkpoint {
        path: path.clone(),
        message,
    };
    let bytes = std::fs::read(&path).map_err(|e| fail(e.to_string()))?;
    let end = bytes
        .iter()
        .take(MAX_HEADER)
        .position(|&b| b == b'\n')
        .ok_or_else(|| fail("not a haff check-point (no header line)".into()))?;
    let header: Header = serde_json::from_slice(&bytes[..end])
        .map_err(|e| fail(format!("not a haff check-point (header: {e})")))?;
    if header.format != format.name || header.version != format.version {
        return Err(fail(format!(
            "written as '{}' version {} by haff {}; this haff {HAFF_VERSION} reads '{}' \
             version {}",
            header.format, header.version, header.haff_version, format.name, format.version
        )));
    }
    let body = &bytes[end + 1..];
    let expected = header
        .records_bytes
        .checked_add(header.engine_bytes)
        .and_then(|n| n.checked_add(1))
        .ok_or_else(|| fail("header: impossible lengths".into()))?;
    if body.len() as u64 != expected {
        return Err(fail(format!(
            "{} bytes after the header where it announces {expected}: the file is truncated \
             or was changed",
            body.len()
        )));
    }
    let r = header.records_bytes as usize;
    if body[r] != b'\n' {
        return Err(fail("the records do not end where the header says".into()));
    }
    let (records, engine) = (&body[..r], &body[r + 1..]);
    let mut crc = crc32fast::Hasher::new();
    crc.update(records);
    crc.update(engine);
    if crc.finalize() != header.crc32 {
        return Err(fail(
            "checksum mismatch: the check-point was changed or damaged after it was written".into(),
        ));
    }
    Ok(Sections {
        path,
        records: records.to_vec(),
        engine: engine.to_vec(),
    })
}

/// The records of a check-point being written: one JSON object, its entries in the order
/// pushed (the caller's first, then the driver's, then each observer's under its name).
#[derive(Debug, Default)]
pub struct RecordsOut {
    entries: Vec<(String, Box<RawValue>)>,
}

impl RecordsOut {
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds `value` under `key`.
    pub fn push<T: Serialize + ?Sized>(&mut self, key: &str, value: &T) -> Result<()> {
        let raw = serde_json::value::to_raw_value(value).map_err(|e| Error::Numerical {
            key: "check-point".into(),
            message: format!("{key}: {e}"),
        })?;
        self.push_raw(key, raw);
        Ok(())
    }

    /// Adds JSON text already encoded under `key`.
    pub fn push_raw(&mut self, key: &str, value: Box<RawValue>) {
        self.entries.push((key.to_string(), value));
    }
}

impl Serialize for RecordsOut {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = s.serialize_map(Some(self.entries.len()))?;
        for (key, value) in &self.entries {
            map.serialize_entry(key, value)?;
        }
        map.end()
    }
}

/// The records of a check-point being read, by key: each reader takes its own
/// ([`Records::take`]); [`Records::finish`] refuses records nobody took.
#[derive(Debug, Deserialize)]
#[serde(transparent)]
pub struct Records {
    entries: BTreeMap<String, Box<RawValue>>,
}

impl Records {
    /// The JSON text under `key`, taken out.
    pub fn take_raw(&mut self, key: &str) -> std::result::Result<Box<RawValue>, String> {
        self.entries
            .remove(key)
            .ok_or_else(|| format!("records: no '{key}' (the check-point is not of this run)"))
    }

    /// The record under `key` as `T`, taken out.
    pub fn take<T: DeserializeOwned>(&mut self, key: &str) -> std::result::Result<T, String> {
        let raw = self.take_raw(key)?;
        serde_json::from_str(raw.get()).map_err(|e| format!("records: {key}: {e}"))
    }

    /// The record under `key` as `T`, taken out, if there is one.
    pub fn take_optional<T: DeserializeOwned>(
        &mut self,
        key: &str,
    ) -> std::result::Result<Option<T>, String> {
        match self.entries.contains_key(key) {
            true => self.take(key).map(Some),
            false => Ok(None),
        }
    }

    /// Fails if a record was not taken: the check-point holds what this run does not have.
    pub fn finish(self) -> std::result::Result<(), String> {
        match self.entries.keys().next() {
            None => Ok(()),
            Some(key) => Err(format!(
                "records: '{key}' does not belong to this run (its observers are set by the run \
                 description)"
            )),
        }
    }
}
