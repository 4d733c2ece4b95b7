//! Writers: CSV, JSON and whole files written atomically. Every CSV of haff goes through
//! [`write_csv`] with numbers formatted by [`number`].
//!
//! Number format of the machine-readable outputs (CSV and JSON): every f64 is written with
//! the shortest digits that parse back to the same f64 (Rust's `{}`/`{:e}`; serde_json's
//! ryu for JSON). In CSV, magnitudes in [1e-5, 1e16) are written positionally (`0.25`), all
//! others in exponent form (`5.158381704267411e-30`), so no number is written with dozens
//! of zeros. Non-finite values are `inf`, `-inf` and `NaN` in CSV and `null` in JSON.

use crate::error::{Error, Result};
use serde::Serialize;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// A number for CSV: shortest round-trip digits (see the module documentation).
pub fn number(x: f64) -> String {
    let positional = (1e-5..1e16).contains(&x.abs());
    if positional || x == 0.0 || !x.is_finite() {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// Writes a CSV header line and one line per row (cells contain no commas).
pub fn write_csv<W: Write + ?Sized>(
    out: &mut W,
    header: &[&str],
    rows: impl IntoIterator<Item = Vec<String>>,
) -> io::Result<()> {
    writeln!(out, "{}", header.join(","))?;
    for row in rows {
        writeln!(out, "{}", row.join(","))?;
    }
    Ok(())
}

/// Writes `value` as pretty-printed JSON followed by a newline.
pub fn write_json<W: Write + ?Sized, T: Serialize + ?Sized>(
    out: &mut W,
    value: &T,
) -> io::Result<()> {
    serde_json::to_writer_pretty(&mut *out, value).map_err(io::Error::from)?;
    writeln!(out)
}

/// Writes the file `path` through `write`: first to `path.partial`, then renamed, so that
/// an interrupted write never leaves a half-written file under the final name.
pub fn write_file(path: &Path, write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<()> {
    let mut partial = path.as_os_str().to_owned();
    partial.push(".partial");
    let partial = std::path::PathBuf::from(partial);
    let fail = |e: io::Error| Error::write(path, e);
    let file = std::fs::File::create(&partial).map_err(fail)?;
    let mut out = BufWriter::new(file);
    write(&mut out).map_err(fail)?;
    out.flush().map_err(fail)?;
    drop(out);
    std::fs::rename(&partial, path).map_err(fail)
}

/// Writes a CSV file (see [`write_csv`]).
pub fn write_csv_file(
    path: &Path,
    header: &[&str],
    rows: impl IntoIterator<Item = Vec<String>>,
) -> Result<()> {
    write_file(path, |out| write_csv(out, header, rows))
}

/// Writes a pretty-printed JSON file.
pub fn write_json_file<T: Serialize + ?Sized>(path: &Path, value: &T) -> Result<()> {
    write_file(path, |out| write_json(out, value))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_trip() {
        for x in [
            0.0,
            1.0,
            0.27063202542608993,
            5.158381704267411e-30,
            1e300,
            3.5e-6,
        ] {
            assert_eq!(number(x).parse::<f64>().unwrap(), x);
        }
        assert_eq!(number(f64::INFINITY), "inf");
        assert_eq!(number(0.25), "0.25");
        assert_eq!(number(1e-30), "1e-30");
    }
}
