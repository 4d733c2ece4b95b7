//! The run file of `haff rods chain`, typed, and its checks.

use crate::description::read_toml;
use crate::error::{Error, Result};
use rods::ring::RingSetup;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// A `haff rods chain` run file.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RingDescription {
    pub chain: ChainSection,
    pub run: RingRunSection,
}

/// `[chain]`: the rods (see [`RingSetup`]).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ChainSection {
    /// Number of rods N on the ring.
    pub rods: usize,
    /// Rod lengths, repeated along the ring (e.g. two lengths: alternating rods).
    #[serde(default = "unit_length")]
    pub lengths: Vec<f64>,
    /// Internal modes per rod.
    pub modes: usize,
    /// Ring perimeter (default: twice the total length of the rods).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub perimeter: Option<f64>,
    /// Inverse range alpha of the contact potential B exp(-alpha r).
    pub alpha: f64,
    /// B of the contact potential [default: m c^2 / (alpha l)^2 of the mean rod].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub strength: Option<f64>,
    #[serde(default = "one")]
    pub sound_speed: f64,
    #[serde(default = "one")]
    pub density: f64,
    /// Initial translational temperature: velocities ~ N(0, T/m), zero total momentum.
    pub temperature: f64,
    /// Initial temperature of the internal modes (default 0: cold rods).
    #[serde(default)]
    pub bath_temperature: f64,
    #[serde(default = "first_seed")]
    pub seed: u64,
    /// Step constant c_h of the contact integrator, h = c_h / (alpha v_ref).
    #[serde(default = "step")]
    pub step: f64,
}

/// A law of the ED + MC comparison (`run.compare`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum CompareLaw {
    /// Eq. (7) of Giese.
    Glauber,
    /// p(eps^2) of `run.table`.
    Tabulated,
}

impl CompareLaw {
    pub(super) fn name(self) -> &'static str {
        match self {
            CompareLaw::Glauber => "glauber",
            CompareLaw::Tabulated => "tabulated",
        }
    }
}

/// `[run]` of a chain run.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RingRunSection {
    pub end_time: f64,
    #[serde(default = "hundred")]
    pub samples: usize,
    /// ED + MC runs from the same start.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub compare: Vec<CompareLaw>,
    /// Runs from seeds seed, seed + 1, ...; the outputs are their means.
    #[serde(default = "one_repeat")]
    pub repeats: usize,
    /// Table of `haff rods table` for compare = "tabulated".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub table: Option<PathBuf>,
}

fn unit_length() -> Vec<f64> {
    vec![1.0]
}
fn one_repeat() -> usize {
    1
}
fn one() -> f64 {
    1.0
}
fn first_seed() -> u64 {
    1
}
fn step() -> f64 {
    0.05
}
fn hundred() -> usize {
    100
}

impl ChainSection {
    /// The ring of rods this table describes.
    pub fn ring(&self) -> RingSetup {
        RingSetup {
            rods: self.rods,
            lengths: self.lengths.clone(),
            modes: self.modes,
            perimeter: self.perimeter,
            alpha: self.alpha,
            strength: self.strength,
            sound_speed: self.sound_speed,
            density: self.density,
            temperature: self.temperature,
            bath_temperature: self.bath_temperature,
            seed: self.seed,
            step: self.step,
        }
    }
}

impl RingDescription {
    /// Reads and parses a run file.
    pub fn from_path(path: &Path) -> Result<Self> {
        read_toml(path)
    }

    /// Checks every key; returns the ring of rods.
    pub fn validate(&self) -> Result<RingSetup> {
        let ring = self.chain.ring();
        ring.validate().map_err(chain_error)?;
        let run = &self.run;
        crate::error::positive("run.end_time", run.end_time)?;
        if !(1..=10_000).contains(&run.repeats) {
            return Err(Error::out_of_range(
                "run.repeats",
                run.repeats,
                "1 <= repeats <= 10000",
            ));
        }
        if !(2..=100_000).contains(&run.samples) {
            return Err(Error::out_of_range(
                "run.samples",
                run.samples,
                "2 <= samples <= 100000",
            ));
        }
        let tabulated = run.compare.contains(&CompareLaw::Tabulated);
        if tabulated != run.table.is_some() {
            return Err(Error::input(
                "run.table",
                "give a table exactly when compare holds \"tabulated\"",
            ));
        }
        if let Some(path) = &run.table {
            let table = crate::law::read_table(path, "run.table")?;
            self.check_table_gamma(table.gamma)
                .map_err(|e| Error::input("run.table", format!("{}: {e}", path.display())))?;
        }
        Ok(ring)
    }

    /// The table's length ratio is that of every pair of neighbouring rods on the ring,
    /// gamma or 1/gamma (the collision of two rods does not depend on which is called
    /// first), to 1e-3 (tables name gamma to four digits, 0.6173 for 0.80865/1.31001).
    fn check_table_gamma(&self, gamma: f64) -> std::result::Result<(), String> {
        let lengths = &self.chain.lengths;
        let n = self.chain.rods;
        let length = |i: usize| lengths[i % lengths.len()];
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-3 * b;
        // The pattern's pairs and the one that closes the ring.
        for i in (0..n.min(lengths.len())).chain([n - 1]) {
            let ratio = length(i) / length((i + 1) % n);
            if !(close(ratio, gamma) || close(1.0 / ratio, gamma)) {
                return Err(format!(
                    "built for gamma = {gamma}, but rods {i} and {} have l1/l2 = {ratio}; \
                     build a table for these rods with `haff rods table --gamma {ratio}`",
                    (i + 1) % n
                ));
            }
        }
        Ok(())
    }
}

/// A rods error about the `[chain]` table: range errors name their key `chain.NAME`.
pub(super) fn chain_error(error: rods::Error) -> Error {
    match error {
        rods::Error::OutOfRange {
            name,
            value,
            allowed,
        } => Error::out_of_range(&format!("chain.{name}"), value, &allowed),
        other => Error::input("chain", other),
    }
}
