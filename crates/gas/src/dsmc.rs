//! Direct simulation Monte Carlo (DSMC) of a granular gas of smooth inelastic hard spheres:
//! the Enskog–Boltzmann equation sampled by N particles, with the coefficient of restitution
//! taken at each collision from a `restitution::Restitution` law at the normal impact speed
//! (as Müller & Pöschel 2011 propose for their Padé and fast laws).
//!
//! Two engines:
//!
//! - [`HomogeneousDsmc`]: a spatially homogeneous gas (velocities only). The collision rate
//!   carries the Enskog factor g2(phi), so that its time axis is that of the event-driven
//!   engine of the same system. [`Scheme::Exact`] runs one exact Poisson process over all
//!   pairs (serial, exponential waiting times, no time-step error); [`Scheme::Blocks`] runs
//!   the same exact process inside blocks of a fixed size, in parallel, re-mixing the blocks
//!   every step.
//! - [`SpatialDsmc`]: positions and velocities in a periodic box; free streaming over a
//!   step, then the exact process inside each collision cell (Bird's scheme with the
//!   majorant of [`kernel`]), cells in parallel. The collision rate is multiplied by g2 of the
//!   mean packing fraction but collision partners are not displaced by sigma (Enskog's
//!   offset): the "Enskog-factor DSMC" approximation, exact only for a homogeneous gas.
//!
//! Both engines give results independent of the number of threads: every block or cell in
//! every step draws from its own random stream, a hash of (seed, step, block or cell), and
//! sums are reduced in a fixed order. See [`kernel`] for the collision scheme and its
//! exactness, [`crate::theory`] for the kinetic theory the tests compare with.

mod cell_sort;
mod domain;
mod homogeneous;
pub mod kernel;
mod reduce;
mod rough;
mod spatial;
pub(crate) mod species;

pub use homogeneous::HomogeneousDsmc;
pub use spatial::{
    SpatialDsmc, SpatialOptions, DEFAULT_CELL_WIDTH_IN_MEAN_FREE_PATHS,
    DEFAULT_MIN_PARTICLES_PER_CELL,
};
pub use species::MAX_SPECIES;

use crate::engine::Counters;
use crate::error::{require_positive, Error, Result};
use crate::serde_util;
use crate::system::{System, Vector};
use crate::theory;
use rand::{Rng, SeedableRng};
use rand_distr::StandardNormal;
use serde::{Deserialize, Serialize};

/// How long a step of a stepped scheme is.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StepSize {
    /// The engine's default (see [`Scheme::Blocks`] and [`SpatialOptions`]).
    #[default]
    Auto,
    /// This many collisions per particle per step at the current temperature (Maxwellian
    /// estimate; for a mixture an upper estimate with the largest pair weight and the
    /// smallest mass).
    CollisionsPerParticle(f64),
    /// A fixed time.
    Fixed(f64),
}

/// The fewest collisions per particle in a step: 1e4 steps per collision time, far below
/// where the O(dt) splitting error of a step matters (and a step of 1e-300 collisions would
/// never end).
pub const MIN_COLLISIONS_PER_STEP: f64 = 1e-4;

impl StepSize {
    fn check(&self) -> Result<()> {
        match *self {
            StepSize::Auto => Ok(()),
            StepSize::CollisionsPerParticle(x)
                if (MIN_COLLISIONS_PER_STEP..=100.0).contains(&x) =>
            {
                Ok(())
            }
            StepSize::CollisionsPerParticle(x) => Err(Error::out_of_range(
                "collisions_per_step",
                x,
                "1e-4 <= collisions per particle per step <= 100",
            )),
            StepSize::Fixed(dt) => require_positive("time_step", dt).map(|_| ()),
        }
    }
}

/// Default number of particles in a block of [`Scheme::Blocks`]: 4096 velocities (96 KB in
/// 3D) stay in the second-level cache.
pub const DEFAULT_BLOCK_SIZE: usize = 4096;

/// Default collisions per particle per step of [`Scheme::Blocks`] (`StepSize::Auto`): with
/// [`DEFAULT_BLOCK_SIZE`] a bias of about 1e-4 in the cooling rate (see [`Scheme::Blocks`]).
pub const DEFAULT_BLOCK_COLLISIONS_PER_STEP: f64 = 1.0;

/// Default collisions per particle per step of [`Scheme::Blocks`] under shear: the
/// splitting of streaming and collisions errs by O((omega dt)^2) in the stress (measured:
/// the viscosity of elastic spheres 5 % high at 1 collision per step, within 0.5 % from
/// 0.25 down; docs/shear.md).
pub const SHEARED_BLOCK_COLLISIONS_PER_STEP: f64 = 0.2;

/// How the homogeneous engine samples collisions.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Scheme {
    /// One exact Poisson process over all N(N-1)/2 pairs, serial. Time advances by the
    /// exponential waiting times: no time-step error. Reference for the other scheme.
    Exact,
    /// Particles in blocks of `block_size` (all blocks of N / round(N / block_size)
    /// particles, give or take one; fixed, whatever the number of threads). Each step of
    /// time dt runs the exact process inside every block, in parallel, with the block's
    /// pair rate scaled by (N - 1)/(B - 1) so that every particle's collision frequency is
    /// that of the whole gas; then the blocks are shuffled and re-mixed (lanes of 16
    /// particles rotated by a random number of blocks each, so that block-mates are
    /// scattered over different blocks).
    ///
    /// Error: no time-step error in the usual sense (there is no free flight to split
    /// from collisions, and within a block the process is exact). Within a step a particle
    /// meets only its block, whose temperature fluctuates by O(B^(-1/2)) and drifts
    /// independently of the others; faster cooling of hotter blocks biases the cooling rate
    /// by about 0.5 nu dt / B (nu dt the collisions per particle per step). Measured at
    /// eps = 0.7 (T after 30 collision times of the initial state, N = 10^4, 24 seeds,
    /// +-0.15 %): B = 64: +0.6 %, +1.5 %, +4.2 % at nu dt = 0.5, 2, 8; B = 512: +0.2 % at
    /// nu dt = 2. The defaults ([`DEFAULT_BLOCK_SIZE`], `StepSize::Auto` =
    /// [`DEFAULT_BLOCK_COLLISIONS_PER_STEP`]) keep it near 1e-4. dt sets how often the blocks
    /// are re-mixed; shorter steps cost a pass over memory each.
    Blocks { block_size: usize, step: StepSize },
}

impl Default for Scheme {
    fn default() -> Self {
        Scheme::Blocks {
            block_size: DEFAULT_BLOCK_SIZE,
            step: StepSize::Auto,
        }
    }
}

/// Everything needed to continue a run bit for bit (together with the law): the state, the
/// position of the random streams and the options. Fields are plain data for check-points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Snapshot<const D: usize, O> {
    /// Particles in the engine's current order (positions zero for the homogeneous engine).
    pub system: System<D>,
    pub packing_fraction: f64,
    pub seed: u64,
    pub options: O,
    pub time: f64,
    /// Steps of a stepped scheme so far (each step's streams derive from its number).
    pub steps: u64,
    pub counters: Counters,
    /// The velocity speed bounds are measured from (the mean velocity when the exact scheme
    /// last recomputed its bound, or at the end of the last block step; unused by the
    /// spatial engine, whose cells use their own mean).
    #[serde(with = "serde_util::vector")]
    pub reference_velocity: Vector<D>,
    /// [`Scheme::Exact`]: the running bound on |v - reference_velocity|.
    pub speed_bound: f64,
    /// [`Scheme::Exact`]: 64-bit draws taken from the random stream.
    pub draws: u64,
    /// The temperature that sets the next step of a stepped scheme; for
    /// [`Scheme::Exact`], the temperature at the last recompute of the speed bound, which
    /// sets the width of the speed classes.
    pub temperature: f64,
    /// Collisions suffered by the particles of each species (a collision counts for both
    /// of its particles), in the engine's species order (that of its
    /// `species_collisions`); empty for one species.
    pub species_collisions: Vec<u64>,
    /// The walls' tallies of a spatial engine in a container, the shear, the tensor
    /// virial (absent otherwise: the other states stay byte for byte as before; the last
    /// field, read as None where missing: [`crate::tail::Tail`]).
    #[serde(default, skip_serializing_if = "crate::tail::Tail::is_empty")]
    pub tail: crate::tail::Tail<crate::walls::WallsState>,
}

impl<const D: usize, O> Snapshot<D, O> {
    /// Checks what a check-point could hold wrongly: time, step temperature, speed bound
    /// and reference velocity finite and in range, finite counters, the particles
    /// ([`System::check`], positions in the box if `in_box`). The engine's constructor
    /// checks the rest (packing fraction, options, radii and masses).
    pub fn check(&self, in_box: bool) -> Result<()> {
        let species = self.system.radii.len().min(MAX_SPECIES);
        if self.species_collisions.len() > species {
            return Err(Error::out_of_range(
                "species_collisions",
                self.species_collisions.len(),
                "one count per species",
            ));
        }
        for (name, x) in [
            ("time", self.time),
            ("temperature", self.temperature),
            ("speed_bound", self.speed_bound),
        ] {
            if !(x.is_finite() && x >= 0.0) {
                return Err(Error::out_of_range(name, x, "a finite number >= 0"));
            }
        }
        if self.reference_velocity.iter().any(|x| !x.is_finite()) {
            return Err(Error::NotFinite {
                what: "reference_velocity",
                index: 0,
            });
        }
        self.counters.check("candidates")?;
        self.tail.check()?;
        self.system.check(in_box)
    }

    /// The reference velocity is the mean velocity of the saved velocities (collisions
    /// conserve momentum: the mean when it was taken is the mean now), to 1e-6 of the rms
    /// speed (round-off of the sums). A forged one would make every speed bound huge.
    pub fn check_reference_velocity(&self) -> Result<()> {
        let s = &self.system;
        let (mean, _) = crate::observe::mean_velocity(s);
        let total: f64 = s.masses.iter().sum();
        let rms = (2.0 * crate::observe::kinetic_energy(s) / total).sqrt();
        let off: f64 = (0..D)
            .map(|k| (self.reference_velocity[k] - mean[k]).powi(2))
            .sum::<f64>()
            .sqrt();
        if off <= 1e-6 * rms {
            Ok(())
        } else {
            Err(Error::out_of_range(
                "reference_velocity",
                format!("{:?}", self.reference_velocity),
                format!("the mean velocity of the particles, {mean:?}"),
            ))
        }
    }

    /// For a stepped scheme: the step temperature is the kinetic temperature of the saved
    /// velocities, sum m |v - mean|^2 / (N D) (the engine sets it from them after every
    /// step; 1e-6 covers the round-off of summing in another order, ~N eps). A forged one
    /// would set a step of any number of collisions.
    pub fn check_step_temperature(&self) -> Result<()> {
        let kinetic = crate::observe::temperature(&self.system);
        if (self.temperature - kinetic).abs() <= 1e-6 * kinetic {
            Ok(())
        } else {
            Err(Error::out_of_range(
                "temperature",
                self.temperature,
                format!("the kinetic temperature of the velocities, {kinetic}"),
            ))
        }
    }
}

/// Snapshot of a [`HomogeneousDsmc`].
pub type HomogeneousSnapshot<const D: usize> = Snapshot<D, Scheme>;
/// Snapshot of a [`SpatialDsmc`].
pub type SpatialSnapshot<const D: usize> = Snapshot<D, SpatialOptions>;

/// A gas of point-like simulated particles for DSMC: `n` particles of diameter `diameter`
/// and mass `mass` at uniformly random positions in the periodic box with `sides`
/// (overlaps allowed: DSMC particles have no extent), Gaussian velocities with zero total
/// momentum rescaled so that m <v^2> / D = `temperature` exactly.
pub fn point_gas<const D: usize>(
    n: usize,
    sides: impl crate::system::IntoSides<D>,
    diameter: f64,
    mass: f64,
    temperature: f64,
    seed: u64,
) -> Result<System<D>> {
    let sides = sides.into_sides();
    theory::check_dimension::<D>()?;
    if n < 2 {
        return Err(Error::out_of_range("particles", n, "at least 2"));
    }
    for &length in &sides {
        require_positive("length", length)?;
    }
    for (name, value) in [
        ("diameter", diameter),
        ("mass", mass),
        ("temperature", temperature),
    ] {
        require_positive(name, value)?;
    }
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    let positions = (0..n)
        .map(|_| std::array::from_fn(|k| rng.random::<f64>() * sides[k]))
        .collect();
    let mut velocities: Vec<Vector<D>> = (0..n)
        .map(|_| std::array::from_fn(|_| rng.sample::<f64, _>(StandardNormal)))
        .collect();
    let mean: Vector<D> =
        std::array::from_fn(|k| velocities.iter().map(|v| v[k]).sum::<f64>() / n as f64);
    let sum2: f64 = velocities
        .iter()
        .map(|v| (0..D).map(|k| (v[k] - mean[k]).powi(2)).sum::<f64>())
        .sum();
    let scale = (temperature / (mass * sum2 / (n * D) as f64)).sqrt();
    for v in &mut velocities {
        for k in 0..D {
            v[k] = (v[k] - mean[k]) * scale;
        }
    }
    Ok(System {
        sides,
        positions,
        velocities,
        radii: vec![0.5 * diameter; n],
        masses: vec![mass; n],
    })
}

/// Checks what both engines need of their input.
fn check_input<const D: usize>(system: &System<D>, phi: f64) -> Result<()> {
    theory::check_dimension::<D>()?;
    let n = system.velocities.len();
    if n < 2 {
        return Err(Error::out_of_range("particles", n, "at least 2"));
    }
    if n > u32::MAX as usize {
        return Err(Error::out_of_range(
            "particles",
            n,
            format!("at most {}", u32::MAX),
        ));
    }
    if system.radii.len() != n || system.masses.len() != n {
        return Err(Error::LengthMismatch {
            what: "velocities, radii and masses".into(),
        });
    }
    let max = theory::close_packing::<D>();
    if !(phi > 0.0 && phi < max) {
        return Err(Error::out_of_range(
            "packing_fraction",
            phi,
            format!("0 < phi < {max} (close packing)"),
        ));
    }
    if let Some(index) = system
        .velocities
        .iter()
        .position(|v| v.iter().any(|x| !x.is_finite()))
    {
        return Err(Error::NotFinite {
            what: "velocities",
            index,
        });
    }
    Ok(())
}

/// The mass-weighted mean velocity (conserved by collisions).
fn mean_velocity<const D: usize>(velocities: &[Vector<D>], masses: &[f64]) -> Vector<D> {
    crate::observe::mass_weighted_mean(velocities, masses)
}

/// The Maxwellian collision frequency (upper estimate for a mixture) of a particle among
/// `others` other particles in `volume` at `temperature`: others / V c_D W_max
/// sqrt(2 T / m_min) E|Z| (see [`theory`]).
fn frequency_estimate<const D: usize>(
    species: &species::Species,
    others: f64,
    volume: f64,
    temperature: f64,
) -> f64 {
    others / volume
        * theory::cross_section_factor::<D>()
        * species.max_weight
        * (2.0 * temperature / species.min_mass).sqrt()
        * theory::mean_norm_of_gaussian::<D>()
}

/// x > 0 (false for NaN).
#[inline]
fn positive(x: f64) -> bool {
    x > 0.0
}
