//! `haff reproduce`: the figures and tables of the papers, recomputed.
//!
//! Each [`Entry`] of the registry ([`entries`]) recomputes one figure or table of a paper
//! with the library crates only (the exact law, the computer-algebra coefficients, the Padé
//! approximants, the dash-pot) and writes into [`Context::out`]:
//!
//! - `ID.csv` (and, for some, `ID-NAME.csv`): the data, through [`sim::output`];
//! - `ID.png` and `ID.svg`: the figure, through [`sim::plot::Figure`] (the paper's printed
//!   values as markers, theory dashed);
//! - `ID.md`: what the paper shows, what we get, where and why they differ, with numbers.
//!
//! A printed constant of a paper appears only as "printed" (a marker or a CSV column beside
//! the computed value), never in place of a computation.
//!
//! Papers: [`mp2011`] (Müller & Pöschel 2011, Padé approximants), [`sp2008`] (Schwager &
//! Pöschel 2008, delayed recovery). Further papers add their module and their entries to
//! [`entries`].

pub mod conductivity;
pub mod diffusion;
pub mod gallery;
pub mod giese;
pub mod giese_ring;
pub mod green_kubo;
pub mod kinetic;
pub mod mp2011;
pub mod rough;
pub mod shear;
pub mod soft;
pub mod sp2008;
pub mod usf;

use restitution::exact::{self, Criterion};
use sim::error::{Error, Result};
use sim::output;
use sim::plot::Figure;
use std::path::{Path, PathBuf};

/// One reproducible item of a paper.
#[derive(Clone, Copy)]
pub struct Entry {
    /// `paper-item`, e.g. `mp2011-fig1`.
    pub id: &'static str,
    /// The paper, e.g. `Müller & Pöschel 2011`.
    pub paper: &'static str,
    /// The item, e.g. `Fig. 1`.
    pub item: &'static str,
    /// What it shows, one line.
    pub shows: &'static str,
    /// Typical wall time of the full (not quick) run on one core, in seconds.
    pub typical_seconds: f64,
    /// Computes the item and writes its files into the context's directory.
    pub run: fn(&Context) -> Result<Outcome>,
}

impl std::fmt::Debug for Entry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Entry").field("id", &self.id).finish()
    }
}

/// Every reproducible item, in the order `haff reproduce all` runs them.
pub fn entries() -> Vec<Entry> {
    let mut all = mp2011::entries();
    all.extend(sp2008::entries());
    all.extend(kinetic::entries());
    all.extend(shear::entries());
    all.extend(usf::entries());
    all.extend(green_kubo::entries());
    all.extend(diffusion::entries());
    all.extend(conductivity::entries());
    all.extend(rough::entries());
    all.extend(soft::entries());
    all.extend(giese::entries());
    all.extend(giese_ring::entries());
    all
}

/// The entry with this id.
pub fn find(id: &str) -> Option<Entry> {
    entries().into_iter().find(|e| e.id == id)
}

/// The ids of the registry, comma-separated (for error messages).
pub fn id_list() -> String {
    entries()
        .iter()
        .map(|e| e.id)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Where and how an item is reproduced.
#[derive(Debug, Clone)]
pub struct Context {
    /// Output directory (created if missing).
    pub out: PathBuf,
    /// Fewer points and lower orders (for tests; the whole registry in seconds).
    pub quick: bool,
}

/// What an item found.
#[derive(Debug, Clone, Default)]
pub struct Outcome {
    /// One line for the command's report.
    pub summary: String,
    /// The key numbers (also printed in `ID.md`), by name, for tests.
    pub values: Vec<(&'static str, f64)>,
    /// The files written (paths).
    pub files: Vec<PathBuf>,
}

impl Outcome {
    /// The value called `name`.
    pub fn value(&self, name: &str) -> Option<f64> {
        self.values.iter().find(|(n, _)| *n == name).map(|v| v.1)
    }
}

impl Context {
    pub fn new(out: impl Into<PathBuf>, quick: bool) -> Self {
        Context {
            out: out.into(),
            quick,
        }
    }

    /// `out/NAME.EXT`.
    pub fn path(&self, name: &str, extension: &str) -> PathBuf {
        self.out.join(format!("{name}.{extension}"))
    }

    fn ensure_dir(&self) -> Result<()> {
        std::fs::create_dir_all(&self.out).map_err(|e| Error::write(&self.out, e))
    }

    /// Writes `NAME.csv` with numeric cells (see [`output::number`]).
    pub fn csv(&self, name: &str, header: &[&str], rows: &[Vec<f64>]) -> Result<PathBuf> {
        self.csv_cells(
            name,
            header,
            rows.iter()
                .map(|r| r.iter().map(|&x| output::number(x)).collect())
                .collect(),
        )
    }

    /// Writes `NAME.csv` with preformatted cells (no commas).
    pub fn csv_cells(
        &self,
        name: &str,
        header: &[&str],
        rows: Vec<Vec<String>>,
    ) -> Result<PathBuf> {
        self.ensure_dir()?;
        let path = self.path(name, "csv");
        output::write_csv_file(&path, header, rows)?;
        Ok(path)
    }

    /// Writes `NAME.png` and `NAME.svg`.
    pub fn figure(&self, name: &str, figure: &Figure) -> Result<PathBuf> {
        self.ensure_dir()?;
        let stem = self.out.join(name);
        figure.write_png_and_svg(&stem)?;
        Ok(self.path(name, "png"))
    }

    /// Writes `NAME.md`.
    pub fn markdown(&self, name: &str, text: &str) -> Result<PathBuf> {
        self.ensure_dir()?;
        let path = self.path(name, "md");
        output::write_file(&path, |out| out.write_all(text.as_bytes()))?;
        Ok(path)
    }
}

// ---------------------------------------------------------------------------------------
// Helpers shared by the papers' modules.

/// A numerical failure while computing `what`.
pub(crate) fn numerical(what: &str, message: impl std::fmt::Display) -> Error {
    Error::Numerical {
        key: what.to_string(),
        message: message.to_string(),
    }
}

/// eps of the exact law.
pub(crate) fn exact_eps(vstar: f64, criterion: Criterion) -> Result<f64> {
    exact::solve(vstar, criterion)
        .map(|c| c.eps)
        .map_err(|e| numerical("exact law", e))
}

/// d ln eps / d ln v* of the exact law (central difference, factor 1.001).
pub(crate) fn local_slope(vstar: f64, criterion: Criterion) -> Result<f64> {
    let f = 1.001f64;
    let up = exact_eps(vstar * f, criterion)?;
    let down = exact_eps(vstar / f, criterion)?;
    Ok((up / down).ln() / (f * f).ln())
}

/// The mean of `x` and its standard error (sample standard deviation / sqrt(n); NaN for
/// one value).
pub(crate) fn mean_and_error(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    if x.len() < 2 {
        return (mean, f64::NAN);
    }
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// `n` points from `a` to `b` inclusive.
/// The least-squares slope of y against x.
pub(crate) fn slope(points: &[(f64, f64)]) -> f64 {
    let m = points.len() as f64;
    let xm = points.iter().map(|p| p.0).sum::<f64>() / m;
    let ym = points.iter().map(|p| p.1).sum::<f64>() / m;
    let sxx: f64 = points.iter().map(|p| (p.0 - xm).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - xm) * (p.1 - ym)).sum();
    sxy / sxx
}

pub(crate) fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
        .collect()
}

/// `n` logarithmically spaced points from `a` to `b` inclusive.
pub(crate) fn logspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    let (la, lb) = (a.ln(), b.ln());
    (0..n)
        .map(|i| (la + (lb - la) * i as f64 / (n - 1) as f64).exp())
        .collect()
}

/// The points up to (not including) the first one with y outside [lo, hi]: a diverging
/// curve ends at the edge of the plot instead of stretching its axis.
pub(crate) fn until_outside(points: Vec<(f64, f64)>, lo: f64, hi: f64) -> Vec<(f64, f64)> {
    points
        .into_iter()
        .take_while(|p| p.1 >= lo && p.1 <= hi)
        .collect()
}

/// A number in an `ID.md`: 6 significant digits.
pub fn sig(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let a = x.abs();
    if (1e-3..1e5).contains(&a) {
        let decimals = (5 - a.log10().floor() as i32).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.5e}")
    }
}

/// Whether every file of `id` exists in `dir` (CSV, PNG, SVG, MD).
pub fn written(dir: &Path, id: &str) -> bool {
    ["csv", "png", "svg", "md"]
        .iter()
        .all(|ext| dir.join(format!("{id}.{ext}")).is_file())
}
