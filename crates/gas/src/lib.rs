//! # haff-gas — engines over many particles
//!
//! The state of a gas of smooth hard spheres in a periodic box of dimension `D` (1, 2 or 3)
//! ([`system`]), initial conditions ([`init`]), cell lists ([`cells`]), the sorters of future
//! events ([`sorter`]), the engines behind one interface ([`Engine`], [`Checkpoint`]): the
//! event-driven engine ([`EventDriven`], docs/event-driven.md) and DSMC ([`dsmc`]), the
//! observables ([`observe`]) and the kinetic theory they are compared with ([`theory`]). The
//! engines take their coefficient of restitution through `restitution::Restitution` and
//! never read files; the run driver (crate `haff-sim`) builds and drives them.

pub mod cells;
pub mod driving;
pub mod dsmc;
pub mod emd;
pub mod engine;
pub mod error;
pub mod exact_sum;
pub mod init;
pub mod observe;
pub mod parallel;
mod prefetch;
pub mod profile;
pub(crate) mod rng;
pub mod rotation;
mod serde_util;
pub mod shear;
pub mod soft;
pub mod sorter;
pub mod structure;
pub mod system;
pub mod tail;
pub mod theory;
pub mod walls;

pub use dsmc::{HomogeneousDsmc, SpatialDsmc};
pub use emd::{BathState, EventDriven, EventDrivenState};
pub use engine::{Checkpoint, Counters, Engine};
pub use error::{Error, Result};
pub use soft::{SoftSphere, SoftSphereOptions, SoftSphereState};
pub use sorter::SorterKind;
pub use system::System;
