//! Errors of the gas crate: every message names the offending quantity and what is allowed.

use std::fmt::Display;

/// Why an engine, an initial state or a restored state could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A parameter outside its allowed range.
    #[error("{name} = {value}: allowed {allowed}")]
    OutOfRange {
        name: String,
        value: String,
        allowed: String,
    },
    /// Per-particle arrays of different lengths, e.g. "positions, velocities, radii and
    /// masses".
    #[error("{what} differ in number")]
    LengthMismatch { what: String },
    /// A non-finite entry of a per-particle array.
    #[error("{what}[{index}]: not finite")]
    NotFinite { what: &'static str, index: usize },
    /// Two spheres of an event-driven state overlap.
    #[error("particles {0} and {1} overlap")]
    Overlap(usize, usize),
    /// The periodic box is too small for the cell lists of the event-driven engine.
    #[error("the box (side {length}) must hold at least 4 cells of width {width} per side")]
    BoxTooSmall { length: f64, width: f64 },
    /// A dense initial state does not fit on the simple lattice it starts from.
    #[error(
        "packing_fraction = {phi} is too high for a simple lattice of the largest diameter \
         {diameter} (spacing {spacing}); lower it to at most {max_phi} or reduce the size ratio"
    )]
    LatticeTooDense {
        phi: f64,
        diameter: f64,
        spacing: f64,
        max_phi: f64,
    },
    /// Growing spheres (a dense start) jammed before they reached their size.
    #[error(
        "the spheres jammed at packing fraction {phi:.4} while growing (more than \
         {collisions_per_particle:e} collisions per particle); ask for a lower packing fraction"
    )]
    Jammed {
        phi: f64,
        collisions_per_particle: f64,
    },
    /// Random sequential addition found no free place.
    #[error("could not place particle {particle} by random addition")]
    Placement { particle: usize },
    /// Baths were set for a deterministic law.
    #[error("the law '{law}' has no baths")]
    NoBaths { law: String },
    /// More ranks than an engine spread over ranks can use.
    #[error("ranks = {ranks}: allowed {allowed}")]
    TooManyRanks { ranks: usize, allowed: String },
    /// A time step that does not resolve the contacts (soft-sphere MD): `name` is the
    /// option that set it (`time_step` or `steps_per_contact`).
    #[error("{name} = {value}: allowed {allowed}")]
    UnresolvedStep {
        name: &'static str,
        value: f64,
        allowed: String,
    },
    /// Something an engine cannot do (e.g. drive the gas).
    #[error("{what}: this engine cannot do it")]
    Unsupported { what: String },
    /// The collision law could not be built.
    #[error(transparent)]
    Law(#[from] restitution::Error),
}

impl Error {
    /// `name = value: allowed ...`.
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

/// The result type of the gas crate.
pub type Result<T> = std::result::Result<T, Error>;

/// `x`, if finite and > 0.
pub(crate) fn require_positive(name: &str, x: f64) -> Result<f64> {
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(Error::out_of_range(name, x, "a finite number > 0"))
    }
}
