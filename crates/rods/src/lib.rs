//! Giese's one-dimensional elastic rods with internal vibration modes.
pub mod deterministic;
