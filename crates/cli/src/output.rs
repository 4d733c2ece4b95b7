//! Reading numbers and lists from the command line, and writing aligned tables for people.
//! CSV and JSON go through the run driver's writers (`sim::output`: one number format for
//! every machine-readable output).

use crate::error::{CliError, CliResult};
use serde::Serialize;
pub use sim::output::{number, write_csv};
use std::io::{self, BufWriter, StdoutLock, Write};

/// Output format of the data commands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DataFormat {
    /// Comma-separated values with a header line.
    Csv,
    /// One JSON document.
    Json,
}

/// Output format of the benchmark.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ReportFormat {
    /// An aligned table for people.
    Table,
    /// One JSON document.
    Json,
}

/// The values a numeric argument accepts, with the quantity's name for messages.
/// Every accepted value is finite.
#[derive(Debug, Clone, Copy)]
pub struct Allowed {
    name: &'static str,
    low: f64,
    low_inclusive: bool,
    high: f64,
    high_inclusive: bool,
}

impl Allowed {
    /// Finite values >= 0.
    pub fn non_negative(name: &'static str) -> Self {
        Allowed::between(name, 0.0, f64::MAX)
    }

    /// Finite values > 0.
    pub fn positive(name: &'static str) -> Self {
        Allowed {
            low_inclusive: false,
            ..Allowed::non_negative(name)
        }
    }

    /// Values in the closed interval [low, high].
    pub fn between(name: &'static str, low: f64, high: f64) -> Self {
        Allowed {
            name,
            low,
            low_inclusive: true,
            high,
            high_inclusive: true,
        }
    }

    /// Values in the open interval (low, high).
    pub fn open(name: &'static str, low: f64, high: f64) -> Self {
        Allowed {
            low_inclusive: false,
            high_inclusive: false,
            ..Allowed::between(name, low, high)
        }
    }

    /// Whether `x` is accepted.
    pub fn admits(&self, x: f64) -> bool {
        let above_low = if self.low_inclusive {
            x >= self.low
        } else {
            x > self.low
        };
        let below_high = if self.high_inclusive {
            x <= self.high
        } else {
            x < self.high
        };
        x.is_finite() && above_low && below_high
    }

    /// The accepted range in words, e.g. `0 <= v* <= 1e6`.
    pub fn describe(&self) -> String {
        let low_sign = if self.low_inclusive { "<=" } else { "<" };
        if self.high == f64::MAX {
            let high_sign = if self.low_inclusive { ">=" } else { ">" };
            format!("a finite {} {high_sign} {}", self.name, bound(self.low))
        } else {
            let high_sign = if self.high_inclusive { "<=" } else { "<" };
            let (name, low, high) = (self.name, bound(self.low), bound(self.high));
            format!("{low} {low_sign} {name} {high_sign} {high}")
        }
    }
}

impl From<restitution::ranges::Range> for Allowed {
    /// The range of a library quantity (`restitution::ranges`, `rods::ranges`), with its
    /// name and wording.
    fn from(range: restitution::ranges::Range) -> Self {
        if range.open {
            Allowed::open(range.name, range.low, range.high)
        } else {
            Allowed::between(range.name, range.low, range.high)
        }
    }
}

/// A range bound for messages: `1e6` rather than `1000000`.
fn bound(x: f64) -> String {
    if x.abs() >= 1e4 {
        format!("{x:e}")
    } else {
        number(x)
    }
}

/// Reads one number and checks it; on failure, says what is wrong with it.
fn check_number(text: &str, allowed: &Allowed) -> Result<f64, String> {
    let text = text.trim();
    let value: f64 = text
        .parse()
        .map_err(|_| format!("'{text}' is not a number"))?;
    if allowed.admits(value) {
        Ok(value)
    } else {
        Err(format!("{} is out of range", number(value)))
    }
}

/// Parses one number given to `flag` and checks it against `allowed`.
pub fn parse_number(flag: &str, text: &str, allowed: Allowed) -> CliResult<f64> {
    check_number(text, &allowed).map_err(|problem| {
        CliError::argument(flag, format!("{problem}; allowed: {}", allowed.describe()))
    })
}

/// Parses a comma-separated, non-empty list of numbers given to `flag`, each checked
/// against `allowed`. Blanks around items are ignored; empty items are errors.
pub fn parse_list(flag: &str, text: &str, allowed: Allowed) -> CliResult<Vec<f64>> {
    let fail = |problem: String| {
        let expected = format!("comma-separated numbers, each {}", allowed.describe());
        CliError::argument(flag, format!("{problem}; allowed: {expected}"))
    };
    if text.trim().is_empty() {
        return Err(fail("empty list".to_string()));
    }
    text.split(',')
        .enumerate()
        .map(|(index, item)| {
            let position = index + 1;
            if item.trim().is_empty() {
                return Err(fail(format!("item {position} of '{text}' is empty")));
            }
            check_number(item, &allowed)
                .map_err(|problem| fail(format!("item {position}: {problem}")))
        })
        .collect()
}

/// Parses a whole number given to `flag`, in the closed range [min, max].
pub fn parse_count(flag: &str, text: &str, min: usize, max: usize) -> CliResult<usize> {
    let name = flag.trim_start_matches('-');
    let allowed = format!("an integer with {min} <= {name} <= {max}");
    let value: usize = text.trim().parse().map_err(|_| {
        CliError::argument(
            flag,
            format!("'{text}' is not an integer; allowed: {allowed}"),
        )
    })?;
    if !(min..=max).contains(&value) {
        return Err(CliError::argument(
            flag,
            format!("{value} is out of range; allowed: {allowed}"),
        ));
    }
    Ok(value)
}

/// A number for tables read by people: `digits` significant digits, positional for
/// magnitudes in [1e-4, 1e6) (after rounding), exponent form otherwise.
pub fn significant(x: f64, digits: usize) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = digits.max(1);
    let scientific = format!("{:.*e}", digits - 1, x);
    let exponent = scientific
        .split_once('e')
        .and_then(|(_, exponent)| exponent.parse::<i64>().ok())
        .unwrap_or(0);
    if !(-4..6).contains(&exponent) {
        return scientific;
    }
    let decimals = (digits as i64 - 1 - exponent).max(0) as usize;
    format!("{x:.decimals$}")
}

/// Buffered, locked standard output.
pub fn stdout() -> BufWriter<StdoutLock<'static>> {
    BufWriter::new(io::stdout().lock())
}

/// Writes `value` as pretty-printed JSON followed by a newline.
pub fn write_json<W: Write, T: Serialize>(out: &mut W, value: &T) -> CliResult {
    Ok(sim::output::write_json(out, value)?)
}

/// Writes an aligned table: first column left-aligned, the others right-aligned, columns
/// separated by two blanks.
pub fn write_table<W: Write>(
    out: &mut W,
    header: &[String],
    rows: &[Vec<String>],
) -> io::Result<()> {
    let widths: Vec<usize> = (0..header.len())
        .map(|column| {
            let cells = rows.iter().map(|row| row[column].chars().count());
            cells.fold(header[column].chars().count(), usize::max)
        })
        .collect();
    for line in std::iter::once(header).chain(rows.iter().map(Vec::as_slice)) {
        let cells: Vec<String> = line
            .iter()
            .zip(&widths)
            .enumerate()
            .map(|(column, (cell, &width))| match column {
                0 => format!("{cell:<width$}"),
                _ => format!("{cell:>width$}"),
            })
            .collect();
        writeln!(out, "{}", cells.join("  ").trim_end())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_reject_empty_items_and_out_of_range_values() {
        let allowed = Allowed::between("v*", 0.0, 1e6);
        assert_eq!(
            parse_list("--vstar", "0, 1.25", allowed).unwrap(),
            vec![0.0, 1.25]
        );
        for bad in ["", " ", "1,,2", "1,", "-1", "nan", "inf", "2e6", "x"] {
            assert!(parse_list("--vstar", bad, allowed).is_err(), "{bad}");
        }
    }

    #[test]
    fn ranges_are_described() {
        assert_eq!(Allowed::positive("beta").describe(), "a finite beta > 0");
        assert_eq!(
            Allowed::between("v*", 0.0, 1e6).describe(),
            "0 <= v* <= 1e6"
        );
    }

    /// The library's ranges read and describe as the command's own (same values, same
    /// wording after `allowed:`).
    #[test]
    fn library_ranges_are_described_alike() {
        let all = restitution::ranges::ALL
            .into_iter()
            .chain(rods::ranges::ALL);
        for range in all {
            let allowed = Allowed::from(range);
            assert_eq!(allowed.describe(), range.describe());
            for x in [
                range.low,
                range.high,
                0.5 * (range.low + range.high),
                f64::NAN,
            ] {
                assert_eq!(allowed.admits(x), range.contains(x), "{range:?} {x}");
            }
        }
    }

    #[test]
    fn significant_digits() {
        assert_eq!(significant(0.270632, 4), "0.2706");
        assert_eq!(significant(12345.6, 4), "12346");
        assert_eq!(significant(1e-9, 3), "1.00e-9");
        assert_eq!(significant(9.99999, 4), "10.00");
        assert_eq!(significant(999999.9, 4), "1.000e6");
    }
}
