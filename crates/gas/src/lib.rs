//! # haff-gas — engines over many particles
//!
//! The state of a gas of smooth hard spheres in a periodic box of dimension `D` (1, 2 or 3),
//! initial conditions, cell lists, the event calendar and the event-driven engine. The
//! engine takes its coefficient of restitution through `restitution::Restitution` and never
//! reads files.
//!
//! Status: the event-driven core (issue 4) — engine, cells, calendar, observables. The TOML
//! runs, outputs, check-points and benchmarks of that issue are still to come.

pub mod calendar;
pub mod cells;
pub mod emd;
pub mod init;
pub mod observe;
pub mod queue;
pub mod system;

pub use emd::{Calendar, EventDriven};
pub use system::System;
