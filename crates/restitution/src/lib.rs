//! # haff-restitution — the physics of one collision
//!
//! Everything about a single binary collision of smooth spheres: materials and units
//! ([`material`]), the scaled viscoelastic collision equation solved exactly ([`exact`]),
//! the linear dash-pot ([`dashpot`]), and the coefficient-of-restitution laws that engines
//! consume through the [`Restitution`] trait ([`law`]).
//!
//! References used throughout the documentation:
//! - **MP2011**: P. Müller and T. Pöschel, Phys. Rev. E 84, 021302 (2011) — Padé approximants.
//! - **Giese**: G. Giese, "Stochastic coefficient of restitution" — vibrating rods.
//! - **SP2008**: T. Schwager and T. Pöschel, Phys. Rev. E 78, 051304 (2008) — delayed recovery.

pub mod bucket;
pub mod dashpot;
pub mod error;
pub mod exact;
pub mod fast;
pub mod law;
mod manifold;
pub mod material;
pub mod ode;
pub mod pade;
pub mod pairwise;
pub mod ranges;
pub mod rough;
pub mod series;
pub mod stochastic;
mod taylor;
pub mod validity;

pub use error::{Error, Result};
pub use exact::Criterion;

pub use law::{Coefficients, Constant, Dashpot, FormName, Restitution, ScaledForm, Viscoelastic};
pub use stochastic::{Glauber, StochasticRestitution, Tabulated};
pub use validity::{Breakdown, Validity};
