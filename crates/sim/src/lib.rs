//! # haff-sim — the run driver
//!
//! A run as a library: what the `haff` command runs (and what the Python package will
//! call):
//!
//! TOML (or, later, a Python dict) -> [`RunDescription`] -> [`validate`] -> [`Plan`] -> system + law +
//! engine ([`engines`], [`law`]) -> [`observer`]s -> writers ([`output`], [`plot`], [`maps`]),
//! with [`checkpoint`]s to continue a run bit for bit.
//!
//! ```no_run
//! # fn main() -> sim::Result<()> {
//! let toml = "[system]\nparticles = 1000\npacking_fraction = 0.1\n\
//!             [collision]\nlaw = \"constant\"\nrestitution = 0.9\n\
//!             [run]\ncollisions_per_particle = 20\nsamples = 10\n";
//! let mut run = sim::Simulation::from_toml(toml, "example.toml".as_ref())?;
//! run.run(&mut (), None)?;
//! println!("T = {}", run.samples().last().unwrap().temperature);
//! # Ok(())
//! # }
//! ```

pub mod checkpoint;
pub mod demo;
pub mod description;
pub mod diffusion;
pub mod driver;
pub mod engines;
pub mod error;
mod figures;
pub mod green_kubo;
pub mod law;
pub mod maps;
pub mod observer;
pub mod outdir;
pub mod output;
pub mod parallel;
pub mod particles;
pub mod plot;
pub mod probe;
pub mod profiles;
pub mod rheology;
pub mod rod_ring;
pub mod rough;
pub mod schedule;
pub mod schema;
pub mod simulation;
pub mod snapshots;
pub mod space;
pub mod species;
pub mod study;
pub mod validate;
pub mod vtk;
pub mod walls;

pub use description::RunDescription;
pub use driver::{Point, Progress, PIECE_COLLISIONS};
pub use error::{Error, Result};
pub use simulation::{InitialMethod, InitialState, Outcome, Particles, Simulation};
pub use validate::{validate, Plan};
