//! # haff-series — computer algebra for the coefficient of restitution
//!
//! Schwager & Pöschel (2008, "SP2008") obtain the coefficient of restitution of viscoelastic
//! spheres with delayed recovery as eps = sum h_k v*^k by a chain of Maple programs (their
//! Appendices A–C, Tables I, II, IV). This crate does the same in Rust, exactly where the
//! algebra is exact (rational arithmetic for the trajectory and for the premature end of
//! contact) and in arbitrary-precision floating point where transcendental numbers enter
//! (the time of maximal compression of the elastic collision, Eq. 28).
//!
//! - [`trajectory`]: x(tau; A) as an exact series in sqrt(tau) with polynomial coefficients
//!   in A (Appendix A).
//! - [`power`]: truncated power series over rationals or floats.
//! - [`coefficients`]: the chain of Appendices B–C, from the trajectory to the coefficients
//!   a_n, b_n, c_n (Table III) and h_k (Table V) of SP2008.
//! - [`pade`]: Padé approximants of the series in high precision (MP2011, Eqs. 11–12).
//! - [`sturm`]: exact isolation of the real zeros of a polynomial (poles and zeros of an
//!   approximant).
//!
//! [`Error`] is the crate's error type: an unknown coefficient kind, or a
//! [`pade::PadeError`] when an approximant cannot be built.

pub mod coefficients;
mod error;
pub mod pade;
pub mod power;
pub mod sturm;
pub mod trajectory;

pub use error::Error;
