//! Observables of space: what the homogeneous cooling state does when it breaks up. The
//! Fourier modes of the momentum and number densities at the smallest wave vectors
//! ([`modes`]), the static structure factor S(k) ([`mod@structure_factor`]) and the pair
//! correlation g(r) ([`pair`]), and coarse-grained fields on a grid ([`fields`]). They read
//! a [`crate::system::System`] only, so every spatial engine has them; none is computed
//! unless asked for.

pub mod fields;
pub mod fourier;
pub mod modes;
pub mod pair;
#[cfg(target_arch = "x86_64")]
mod pair_avx2;
pub mod structure_factor;

pub use fields::{coarse_grained_fields, Fields};
pub use fourier::{half_space_shells, Shell};
pub use modes::{hydrodynamic_modes, ModeShell};
pub use pair::{pair_correlation, StructurePoint};
pub use structure_factor::structure_factor;
