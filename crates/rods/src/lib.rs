//! Giese's one-dimensional elastic rods with internal vibration modes.
pub mod chain;
pub mod deterministic;
pub mod stochastic;
