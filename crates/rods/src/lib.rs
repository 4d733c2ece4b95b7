//! Giese's one-dimensional elastic rods with internal vibration modes.
pub mod chain;
pub mod deterministic;
pub mod engine;
mod error;
pub mod ranges;
pub mod ring;
pub mod stochastic;

pub use error::{Error, Result};
