//! Helpers shared by the restitution tests.
#![allow(dead_code)] // each test binary uses a subset

/// The relative difference |a - b| / |b| (0 if a == b, so that equal zeros compare).
pub fn rel(a: f64, b: f64) -> f64 {
    if a == b {
        0.0
    } else {
        (a - b).abs() / b.abs()
    }
}
