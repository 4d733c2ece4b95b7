//! # haff-gas — engines over many particles
//!
//! The state of a gas of smooth hard spheres in a periodic box of dimension `D` (1, 2 or 3),
//! initial conditions, cell lists, the event calendars, the event-driven engine
//! ([`EventDriven`], docs/event-driven.md) and DSMC ([`dsmc`]). The engines take their
//! coefficient of restitution through `restitution::Restitution` and never read files;
//! the `haff` binary (crates/cli) drives them from TOML.

pub mod calendar;
pub mod cells;
pub mod dsmc;
pub mod emd;
pub mod init;
pub mod observe;
pub mod queue;
pub mod system;

pub use dsmc::{HomogeneousDsmc, SpatialDsmc};
pub use emd::{BathState, Calendar, EventDriven};
pub use system::System;
