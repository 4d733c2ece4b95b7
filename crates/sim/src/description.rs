//! The run description: what a TOML run file (or a Python dict) says, typed. Every closed
//! set of choices is an enum; values are checked by [`crate::validate`]. The serde form is
//! the file's: the same keys, and the same JSON under `parameters` in `summary.json`.
//!
//! ```toml
//! [system]
//! dimension = 3            # 1, 2 or 3
//! particles = 4000         # >= 2
//! packing_fraction = 0.05  # 0 < phi <= 0.6 (3D), 0.8 (2D), 0.9 (1D); above 0.45 (3D),
//!                          # 0.7 (2D) the spheres are grown (Lubachevsky-Stillinger)
//! # or, instead of packing_fraction, a box with sides of its own (one per dimension):
//! # box = [40.0, 20.0, 20.0]
//! diameter = 1.0
//! mass = 1.0
//! # or, instead of diameter and mass, a mixture (number fractions, normalized):
//! # species = [{ diameter = 1.0, mass = 1.0, fraction = 0.5 },
//! #            { diameter = 1.4, mass = 2.744, fraction = 0.5 }]
//! # (law = "viscoelastic": a species may name its own young, poisson,
//! #  dissipative_constant; beta per pair from the pair's effective radius, mass, moduli)
//! temperature = 1.0        # initial T = m <v^2> / d
//! seed = 1
//! [collision]
//! law = "constant"         # constant | dashpot | viscoelastic | stochastic
//! restitution = 0.9        # constant: 0 <= eps <= 1
//! # dashpot: damping_ratio = R, criterion = "improved" | "naive"
//! # viscoelastic: beta = 0.1, form = "exact" | "fast" | "pade:M/N" | "series:K";
//! #   or the material: young = Y, poisson = nu, dissipative_constant = A (the units of
//! #   the system; beta = (3/2) A (rho / m_eff)^(2/5), rho = 2 Y sqrt(R_eff) / (3 (1 - nu^2)));
//! #   or material = "ice" (a built-in one; SI, masses from its density) with
//! #   dissipative_constant
//! # stochastic: modes = M, distribution = "glauber" | "tabulated", table = PATH,
//! #             bath_temperature = 0.0
//! tc = 0.0                 # TC model: elastic if either partner collided < tc ago (0: off)
//! [run]
//! engine = "event-driven"  # event-driven | dsmc | soft-sphere
//! # soft-sphere: the material keys of law = "viscoelastic"; steps_per_contact = 50 or
//! #   time_step = DT
//! # dsmc: dsmc_scheme = "blocks" | "exact" | "spatial", block_size = 4096 (blocks),
//! #       collisions_per_step = 1 (blocks; spatial: 0.2) or time_step = DT,
//! #       collision_cell_width = W (spatial)
//! #       ranks = 4 (spatial: must be launched by mpirun -n 4; see docs/scaling.md)
//! collisions_per_particle = 500   # or end_time = ...
//! samples = 200
//! spacing = "log"          # log | linear
//! histogram_at = [0.0, 50.0, 500.0]  # velocity histograms (unit of the stop criterion)
//! histogram_bins = 60      # 4 ..= 10000
//! ```

use crate::error::{Error, Result};
use restitution::{Criterion, FormName};
use schemars::JsonSchema;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::path::Path;

mod json_schema;
mod snapshot_format;
pub use snapshot_format::{SnapshotFormat, SnapshotFormats};

/// A whole run file: `[system]`, `[collision]` and `[run]`, and the optional sections.
// The doc comments of these types are the descriptions of the JSON Schema of the run file
// (`crate::schema`, `haff schema`, docs/run-file.schema.json, docs/guide/reference.md):
// they are written for users. The `schemars` ranges are those validation enforces.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RunDescription {
    /// The particles, their box and their initial state.
    pub system: SystemSection,
    /// The collision law and its parameters.
    pub collision: CollisionSection,
    /// The engine, how far the run goes and what it samples.
    pub run: RunSection,
    /// What a run records of space: modes, structure, fields, snapshots, profiles.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub output: Option<OutputSection>,
    /// Energy fed in, for a steady state instead of free cooling.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub driving: Option<DrivingSection>,
    /// The walls of a container (none: the periodic box).
    #[serde(default, rename = "wall", skip_serializing_if = "Vec::is_empty")]
    pub walls: Vec<WallSection>,
    /// Forces on every sphere: gravity.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field: Option<FieldSection>,
    /// Uniform shear flow (Lees–Edwards boundaries).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear: Option<ShearSection>,
}

/// `[shear]`: the uniform shear flow u = rate · y e_x (flow along x, gradient along y):
/// Lees–Edwards boundaries in the event-driven engine, soft-sphere MD and the spatial DSMC,
/// the frame moving with the flow in the homogeneous DSMC. `pressure.csv` and the
/// `rheology` of `summary.json` come with it; the temperature of `timeseries.csv` is that
/// of the velocities relative to the flow. Needs 2 or 3 dimensions and no walls, gravity,
/// `output.modes` or `output.structure`.
///
/// ```toml
/// [shear]
/// rate = 0.5
/// ```
// The homogeneous DSMC shears in the co-moving frame (`gas::shear`).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ShearSection {
    /// The shear rate du_x/dy (1/time), positive or negative: 1e-30 <= |rate| <= 1e30.
    /// A rate at which the images slide past the whole box within a collision time is
    /// refused (the flow would no longer be resolved by collisions).
    #[schemars(range(min = -1e30, max = 1e30))]
    pub rate: f64,
}

/// `[field]`: a uniform acceleration of every sphere, along axes closed by walls (along a
/// periodic axis the gas would fall forever). Not with `[driving]` or `[shear]`.
///
/// ```toml
/// [field]
/// gravity = [0.0, 0.0, -1.0]   # one component per dimension
/// rest_height = 1e-4           # a floor sends spheres at least this high (default
///                              # 1e-4 of the smallest diameter; the resting rule)
/// ```
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FieldSection {
    /// The acceleration g, one component per dimension (length/time^2): each 0 or
    /// 1e-30 <= |g| <= 1e30, non-zero only along axes with walls on both sides.
    #[schemars(length(min = 1, max = 3), inner(range(min = -1e30, max = 1e30)))]
    pub gravity: Vec<f64>,
    /// The resting rule of the event-driven engine: a floor sends a sphere off at least as
    /// fast as a bounce this high needs, so that spheres coming to rest do not collide
    /// infinitely often (a length, 0 up to the smallest diameter; default 1e-4 of the
    /// smallest diameter). Not for soft-sphere MD, whose contacts come to rest by themselves.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0))]
    pub rest_height: Option<f64>,
}

/// `[[wall]]`: a flat wall on one side of one axis. An axis is periodic unless both its
/// sides have a wall; one wall per side. Walls run in the event-driven engine, soft-sphere
/// MD (where they are contacts of the particles' material: no thermal walls, no law of
/// their own) and the spatial DSMC.
///
/// ```toml
/// [[wall]]
/// axis = "z"           # x | y | z
/// side = "low"         # low | high
/// kind = "restitution" # elastic | restitution | thermal | vibrating
/// restitution = 0.9    # restitution walls (default 1)
/// # law = "viscoelastic", beta = 0.1   # or another law of [collision] with its keys
/// # temperature = 2.0  # thermal: diffuse re-emission from the wall's Maxwellian
/// ```
// The walls themselves: `gas::walls`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WallSection {
    /// The axis the wall closes: `x`, `y` (2D and 3D) or `z` (3D).
    pub axis: AxisName,
    /// The side of the axis: `low` (at 0) or `high` (at the box side).
    pub side: WallSide,
    /// What the wall does to a sphere hitting it.
    pub kind: WallKindName,
    /// Restitution and vibrating walls with `law = "constant"`: the coefficient of
    /// restitution of the sphere–wall contact, 0 <= e <= 1 (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0, max = 1), extend("default" = 1.0))]
    pub restitution: Option<f64>,
    /// Restitution and vibrating walls: the law of their contacts, with the keys of
    /// `[collision]`'s law of that name (default `constant`, with `restitution`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "Option<json_schema::WallLaw>", extend("default" = "constant"))]
    pub law: Option<LawKind>,
    /// `law = "dashpot"`: the damping ratio R >= 0 of the linear dash-pot.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0))]
    pub damping_ratio: Option<f64>,
    /// `law = "dashpot"`: when a contact ends (default `improved`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(
        with = "Option<json_schema::CriterionName>",
        extend("default" = "improved")
    )]
    pub criterion: Option<Criterion>,
    /// `law = "viscoelastic"`: the material constant β > 0 of the sphere–wall contact, in
    /// (time/length)^(1/5) (or the wall's material: `young`, `poisson`,
    /// `dissipative_constant`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub beta: Option<f64>,
    /// `law = "viscoelastic"`: how eps(v) is evaluated (default `fast`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "Option<json_schema::FormText>", extend("default" = "fast"))]
    pub form: Option<FormName>,
    /// `law = "viscoelastic"` without `beta`: the wall's Young modulus Y > 0, in the units
    /// of the system. Each of `young`, `poisson`, `dissipative_constant` left out is the
    /// particles' of `[collision]` (all left out: a wall of the particles' material).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub young: Option<f64>,
    /// `law = "viscoelastic"` without `beta`: the wall's Poisson ratio, -1 < nu < 0.5.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = -1, "exclusiveMaximum" = 0.5))]
    pub poisson: Option<f64>,
    /// `law = "viscoelastic"` without `beta`: the wall's dissipative constant A >= 0 (a
    /// time).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0))]
    pub dissipative_constant: Option<f64>,
    /// Thermal walls: the wall's temperature, which re-emits spheres from its Maxwellian
    /// (required; 1e-12 to 1e12 times `system.temperature`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub temperature: Option<f64>,
    /// Vibrating walls: the amplitude A of the wall's motion, a length: the wall sweeps the
    /// layer 2A inside the box from its face (required; 1e-30 <= A <= 1e30, the sweeps of an
    /// axis' walls below its side minus the largest diameter).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 1e-30, max = 1e30))]
    pub amplitude: Option<f64>,
    /// Vibrating walls: the frequency f of the wall's motion, cycles per unit time
    /// (required; 1e-30 <= f <= 1e30, the top speed 2π A f at most 1e6 thermal speeds).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 1e-30, max = 1e30))]
    pub frequency: Option<f64>,
    /// Vibrating walls: the waveform of the wall's motion (default `sine`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("default" = "sine"))]
    pub waveform: Option<Waveform>,
}

/// An axis of the box.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum AxisName {
    X,
    Y,
    Z,
}

/// The names of the axes, by index.
pub const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];

impl AxisName {
    pub fn index(self) -> usize {
        self as usize
    }

    pub fn name(self) -> &'static str {
        AXIS_NAMES[self as usize]
    }
}

/// The side of an axis a wall stands on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum WallSide {
    /// At coordinate 0.
    Low,
    /// At the box side L.
    High,
}

/// What a wall does to a sphere hitting it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum WallKindName {
    /// Specular reflection, no energy lost.
    Elastic,
    /// Reflection with a law of restitution (`restitution`, or `law` and its keys).
    Restitution,
    /// Diffuse re-emission from the wall's Maxwellian at `temperature`.
    Thermal,
    /// A wall moving along its axis (`amplitude`, `frequency`, `waveform`), bouncing
    /// spheres with a law of restitution in its frame.
    Vibrating,
}

impl WallKindName {
    /// The name in the run file.
    pub fn name(self) -> &'static str {
        match self {
            WallKindName::Elastic => "elastic",
            WallKindName::Restitution => "restitution",
            WallKindName::Thermal => "thermal",
            WallKindName::Vibrating => "vibrating",
        }
    }
}

/// The motion of a vibrating wall.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Waveform {
    /// Displaced A (1 - cos 2π f t) into the box.
    Sine,
    /// Into the box and back at the speed 4 A f, once a period.
    Triangle,
    /// Into the box at the speed 2 A f over a period, then back to the face at once.
    Sawtooth,
}

/// `[driving]`: energy fed in for a steady state. White noise (`kind = "white-noise"`):
/// every particle's velocity receives Gaussian kicks of variance `strength` per component
/// and unit time (a random acceleration, the same for every species). The Gaussian
/// thermostat (`kind = "gaussian-thermostat"`): every velocity is scaled about the mean by
/// one factor that holds the temperature at `temperature` (default: `system.temperature`);
/// the steady state has the HCS's shape. DSMC (blocks) applies either at every step; the
/// event-driven engine at the times k `interval` (default: a tenth of the mean free time at
/// the larger of the initial and the expected steady temperature), renewing every
/// prediction. Not with the stochastic law nor with gravity.
///
/// ```toml
/// [driving]
/// kind = "white-noise"
/// strength = 1.0
/// # interval = 0.01   (event-driven only)
/// ```
// The driving itself: `gas::driving`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DrivingSection {
    /// The kind of driving.
    pub kind: DrivingKind,
    /// White noise (required): xi^2 > 0, the velocity variance per component and unit time
    /// (length^2/time^3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub strength: Option<f64>,
    /// Gaussian thermostat: the temperature held, > 0 (default `system.temperature`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub temperature: Option<f64>,
    /// Event-driven engine: the time between applications, > 0 (default a tenth of the
    /// mean free time at the larger of the initial and the expected steady temperature).
    /// DSMC drives at every step: leave it out.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub interval: Option<f64>,
}

/// The kind of driving.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum DrivingKind {
    /// Gaussian kicks of variance `strength` per component and unit time.
    WhiteNoise,
    /// Every velocity scaled about the mean to hold `temperature`.
    GaussianThermostat,
}

/// `[output]`: what a run records of space, at the samples of its schedule: the engines
/// with positions (event-driven, soft-sphere, `dsmc_scheme = "spatial"`).
///
/// ```toml
/// [output]
/// modes = true                             # modes.csv: hydrodynamic modes at small k
/// structure = true                         # structure.csv: S(k) and g(r)
/// fields = { every = 10, grid = 64 }       # fields_NNNNNN.vti + fields.pvd
/// snapshots = { every = 10, format = "vtk" }  # snapshot_NNNNNN.vtu + snapshots.pvd
/// # format = "lammps-dump": snapshots.lammpstrj, "xyz": snapshots.xyz (one frame per
/// # snapshot), or a list: format = ["vtk", "xyz"]
/// ```
// Checked by `crate::space::check_output`.
#[derive(Debug, Clone, PartialEq, Default, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OutputSection {
    /// `modes.csv`: the hydrodynamic modes at the smallest wave vectors (the shells of
    /// `mode_shells`), at every sample. Needs a cubic box.
    #[serde(default)]
    pub modes: bool,
    /// The shells of wave vectors of `modes`: k = 2π n / L with |n|^2 up to this,
    /// 1 ..= 100 (default 3). Only with `modes = true`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 1, max = 100), extend("default" = 3))]
    pub mode_shells: Option<usize>,
    /// `structure.csv`: the static structure factor S(k) and the pair correlation g(r).
    /// Needs a cubic box.
    #[serde(default)]
    pub structure: bool,
    /// Coarse-grained fields (density, velocity, temperature, vorticity) on a grid:
    /// `fields_NNNNNN.vti` and `fields.pvd` (ParaView).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fields: Option<FieldsOutput>,
    /// The particles: snapshots in one or more formats.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snapshots: Option<SnapshotsOutput>,
    /// Profiles across slabs normal to an axis (`profiles.csv`): density, packing
    /// fraction, temperature and its components, mean velocity.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profiles: Option<ProfilesOutput>,
    /// The pressure tensor at every sample (`pressure.csv`; always on under `[shear]`).
    #[serde(default, skip_serializing_if = "is_false")]
    #[schemars(extend("default" = false))]
    pub pressure: bool,
    /// The mean-square displacement at every sample (`msd.csv`; the event-driven engine,
    /// soft-sphere MD and spatial DSMC on one process; not under `[shear]`).
    #[serde(default, skip_serializing_if = "is_false")]
    #[schemars(extend("default" = false))]
    pub msd: bool,
}

fn is_false(x: &bool) -> bool {
    !*x
}

/// `output.profiles`: slabs along `axis`, `bins` of them, at every sample
/// (`profiles.csv`).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ProfilesOutput {
    /// The axis across the slabs (one of the box's: `x`, `y` in 2D and 3D, `z` in 3D).
    pub axis: AxisName,
    /// The number of slabs, 1 ..= 100000.
    #[schemars(range(min = 1, max = 100_000))]
    pub bins: usize,
}

/// `output.fields`: coarse-grained fields every `every` samples on a `grid`^D grid.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FieldsOutput {
    /// A field every this many samples, 1 ..= 1e6.
    #[schemars(range(min = 1, max = 1_000_000))]
    pub every: usize,
    /// Cells per side of the grid: 3 ..= 256 in 3D, 4096 in 2D, 2^20 in 1D.
    #[schemars(range(min = 3, max = 1_048_576))]
    pub grid: usize,
}

/// `output.snapshots`: the particles every `every` samples, in one or more formats.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SnapshotsOutput {
    /// A snapshot every this many samples, 1 ..= 1e6.
    #[schemars(range(min = 1, max = 1_000_000))]
    pub every: usize,
    /// A format or a list of distinct formats (default `vtk`).
    #[serde(default)]
    pub format: SnapshotFormats,
}

/// `[system]`: the particles, their box and their initial state: a placement
/// (`particles`, `packing_fraction` or `box`, one kind of sphere or `species`, velocities
/// drawn at `temperature`) or the particles of a file or another run (`initial`).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SystemSection {
    /// 1 (rods on a line), 2 (disks) or 3 (spheres).
    #[serde(default = "three")]
    #[schemars(range(min = 1, max = 3))]
    pub dimension: u32,
    /// The number of particles N, 2 <= N <= 1e8. Required unless `initial` gives the
    /// particles (then leave it out).
    // With `initial`: the file's, filled in by validation.
    #[serde(default)]
    #[schemars(range(min = 2, max = 100_000_000), transform = json_schema::no_default)]
    pub particles: usize,
    /// The spheres' volume over the (cubic) box's: 1e-12 <= phi <= 0.6 in 3D, 0.8 in 2D,
    /// 0.9 in 1D; above 0.45 (3D), 0.7 (2D) the spheres are grown (Lubachevsky–Stillinger).
    /// Give either this or `box`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 1e-12, max = 0.9))]
    pub packing_fraction: Option<f64>,
    /// The sides of the box, one per dimension, each 1e-30 ..= 1e30 and, for spheres with
    /// extent (not the spatial DSMC's points), at least 4 largest diameters (instead of
    /// `packing_fraction`; the engines with space only: event-driven, soft-sphere, spatial
    /// DSMC).
    #[serde(default, rename = "box", skip_serializing_if = "Option::is_none")]
    #[schemars(length(min = 1, max = 3), inner(range(min = 1e-30, max = 1e30)))]
    pub sides: Option<Vec<f64>>,
    /// The diameter of the spheres, 1e-30 ..= 1e30 (default 1; not with `species`).
    // Filled in by [`RunDescription::normalize`] unless `species` is given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 1e-30, max = 1e30), extend("default" = 1.0))]
    pub diameter: Option<f64>,
    /// The mass of the spheres, 1e-30 ..= 1e30 (default 1; not with `species`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 1e-30, max = 1e30), extend("default" = 1.0))]
    pub mass: Option<f64>,
    /// A mixture instead of `diameter` and `mass`: one entry per species, species differing
    /// in diameter or mass.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(length(min = 1))]
    pub species: Option<Vec<SpeciesEntry>>,
    /// The initial temperature T = m <v^2> / d (an energy, k_B = 1), 1e-30 ..= 1e30: the
    /// velocities are drawn from its Maxwellian. Not with the velocities of `initial`.
    #[serde(default = "one")]
    #[schemars(range(min = 1e-30, max = 1e30))]
    pub temperature: f64,
    /// The seed of the run's random numbers (placement, velocities, the engines' draws).
    #[serde(default = "first_seed")]
    pub seed: u64,
    /// Rough particles: the inertia factor q of I = q m d^2 / 4, 0 < q <= 2/3 for spheres
    /// (0.4 a solid sphere, the default; 2/3 a hollow one), 0 < q <= 1/2 for disks (0.5 a
    /// solid disk, the default). 2D and 3D.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 2.0 / 3.0))]
    pub inertia: Option<f64>,
    /// Rough particles: the rotational temperature of the start, I <w^2> / d_rot, 0 or
    /// 1e-30 ..= 1e30 (default `temperature`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0, max = 1e30))]
    pub rotational_temperature: Option<f64>,
    /// The particles from a file or from another run instead of a placement: their number,
    /// box, diameters, masses and (if the file has them) velocities.
    // The normal form holds them resolved: `crate::validate` fills in `particles`, `box`,
    // the species and the temperature.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial: Option<InitialSection>,
    /// Whether the run file gave `temperature` (not serialized: a file's velocities and a
    /// temperature to draw them at are refused together).
    #[serde(skip)]
    pub temperature_given: bool,
}

/// `system.initial`: the particles of a file (`file`) or of another run (`run`), one of
/// them. The file gives the box and positions, and whatever it has of diameters, masses
/// and velocities; what it lacks comes from `system.diameter`, `system.mass` (or
/// `density`) and `system.temperature`. Leave out `system.particles`,
/// `system.packing_fraction`, `system.box` and `system.species`.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct InitialSection {
    /// A particle file, relative to the working directory.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// The format of `file` (default: from its extension).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "Option<json_schema::ParticleFormat>")]
    pub format: Option<String>,
    /// The frame of a file of several: from 0 the first, negative from the end (-1 the
    /// last, the default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("default" = -1))]
    pub frame: Option<i64>,
    /// The output directory of another haff run: the particles of its check-point, else of
    /// its last snapshot.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub run: Option<String>,
    /// The total momentum of the file's velocities: reported and kept (`keep`, the
    /// default) or removed (`remove`: the mass-weighted mean velocity subtracted).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("default" = "keep"))]
    pub momentum: Option<MomentumPolicy>,
    /// The particles' mass density, for files without masses: m = density × the ball's
    /// volume (π/6 d^3, π/4 d^2 in 2D, d in 1D), 1e-30 ..= 1e30. Not with `system.mass`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 1e-30, max = 1e30))]
    pub density: Option<f64>,
}

/// What becomes of the total momentum of a file's velocities.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum MomentumPolicy {
    /// Reported and kept.
    Keep,
    /// Removed: the mass-weighted mean velocity subtracted.
    Remove,
}

/// One entry of `system.species`: a kind of sphere and its share of the particles.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SpeciesEntry {
    /// The diameter of this species, 1e-30 ..= 1e30.
    #[schemars(range(min = 1e-30, max = 1e30))]
    pub diameter: f64,
    /// The mass of this species, 1e-30 ..= 1e30.
    #[schemars(range(min = 1e-30, max = 1e30))]
    pub mass: f64,
    /// The number fraction, > 0 (normalized over the species).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub fraction: f64,
    /// `law = "viscoelastic"`: this species' Young modulus Y > 0 (a key of the species'
    /// material left out is taken from `[collision]`; unlike species collide with the
    /// pair's β).
    // `restitution::material::MaterialPair`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub young: Option<f64>,
    /// `law = "viscoelastic"`: this species' Poisson ratio, -1 < nu < 0.5.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = -1, "exclusiveMaximum" = 0.5))]
    pub poisson: Option<f64>,
    /// `law = "viscoelastic"`: this species' dissipative constant A >= 0 (a time).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0))]
    pub dissipative_constant: Option<f64>,
    /// Rough particles: this species' inertia factor (default `system.inertia`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0, "maximum" = 2.0 / 3.0))]
    pub inertia: Option<f64>,
}

impl SystemSection {
    /// Whether the box is a cube (`packing_fraction`, or a `box` of equal sides).
    pub fn is_cubic(&self) -> bool {
        self.sides
            .as_ref()
            .is_none_or(|l| l.iter().all(|&x| x == l[0]))
    }
}

impl SpeciesEntry {
    /// Whether this species names any key of its own material.
    pub fn has_material(&self) -> bool {
        self.young.is_some() || self.poisson.is_some() || self.dissipative_constant.is_some()
    }
}

/// The collision law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum LawKind {
    /// A constant coefficient of restitution (`restitution`).
    Constant,
    /// The linear dash-pot (`damping_ratio`, `criterion`).
    Dashpot,
    /// Viscoelastic spheres (`beta` or the material, `form`).
    Viscoelastic,
    /// Giese's stochastic law with per-particle baths (`modes`, `distribution`, `table`,
    /// `bath_temperature`).
    Stochastic,
}

impl LawKind {
    /// The name in the run file.
    pub fn name(self) -> &'static str {
        match self {
            LawKind::Constant => "constant",
            LawKind::Dashpot => "dashpot",
            LawKind::Viscoelastic => "viscoelastic",
            LawKind::Stochastic => "stochastic",
        }
    }
}

/// Where the stochastic law draws eps^2 from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Distribution {
    /// Eq. (7) of Giese.
    Glauber,
    /// p(eps^2) tabulated from Eq. (3) by `haff rods table` (`table`).
    Tabulated,
}

/// `collision.restitution`: one coefficient for every pair, or a symmetric matrix with one
/// row per species of `system.species` (`[[a11, a12], [a12, a22]]`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum RestitutionValue {
    One(f64),
    PerPair(Vec<Vec<f64>>),
}

impl<'de> Deserialize<'de> for RestitutionValue {
    fn deserialize<D: serde::Deserializer<'de>>(
        deserializer: D,
    ) -> std::result::Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = RestitutionValue;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(
                    "a number 0 <= eps <= 1, or a symmetric matrix of them with one row per \
                     species, [[a11, a12], [a12, a22]]",
                )
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> std::result::Result<Self::Value, E> {
                Ok(RestitutionValue::One(v))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> std::result::Result<Self::Value, E> {
                Ok(RestitutionValue::One(v as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> std::result::Result<Self::Value, E> {
                Ok(RestitutionValue::One(v as f64))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> std::result::Result<Self::Value, A::Error> {
                let mut rows = Vec::new();
                while let Some(row) = seq.next_element::<Vec<f64>>()? {
                    rows.push(row);
                }
                Ok(RestitutionValue::PerPair(rows))
            }
        }
        deserializer.deserialize_any(Visitor)
    }
}

/// `[collision]`: the law and its parameters. Each key belongs to one law (the stochastic
/// keys, and every key of a law other than the run's, are refused).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CollisionSection {
    /// The collision law.
    pub law: LawKind,
    // The five keys below are written as null when absent (summary.json has always
    // listed them).
    /// `law = "constant"` (required): the coefficient of restitution 0 <= eps <= 1, one for
    /// every pair, or a symmetric matrix with one row per species of `system.species`
    /// (`[[e11, e12], [e12, e22]]`). The event-driven engine refuses 0 (sticking spheres)
    /// unless `tc` is set.
    #[serde(default)]
    #[schemars(with = "Option<json_schema::Restitution>")]
    pub restitution: Option<RestitutionValue>,
    /// `law = "dashpot"` (required): the damping ratio R >= 0 of the linear dash-pot.
    #[serde(default)]
    #[schemars(range(min = 0))]
    pub damping_ratio: Option<f64>,
    /// `law = "dashpot"`: when a contact ends (default `improved`).
    #[serde(default)]
    #[schemars(
        with = "Option<json_schema::CriterionName>",
        extend("default" = "improved")
    )]
    pub criterion: Option<Criterion>,
    /// `law = "viscoelastic"`: the material constant β > 0 of Müller & Pöschel (2011), in
    /// (time/length)^(1/5): eps depends on v* = β^(1/2) v^(1/10). Or, instead, the
    /// material: `young`, `poisson`, `dissipative_constant` (or `material`).
    #[serde(default)]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub beta: Option<f64>,
    /// `law = "viscoelastic"`: how eps(v*) is evaluated (default `fast`).
    #[serde(default)]
    #[schemars(with = "Option<json_schema::FormText>", extend("default" = "fast"))]
    pub form: Option<FormName>,
    /// `law = "viscoelastic"`, 3D: a built-in material by name, its Young modulus, Poisson
    /// ratio and density in SI units (the masses follow from the density: give diameters in
    /// m), with `dissipative_constant` in s. A `young` or `poisson` given overrides the
    /// table's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(with = "Option<json_schema::MaterialName>")]
    pub material: Option<String>,
    /// `law = "viscoelastic"`: the Young modulus Y > 0 of the particles' material, in the
    /// units of the system (with `poisson` and `dissipative_constant`, instead of `beta`;
    /// β = (3/2) A (ρ / m_eff)^(2/5), ρ = 2 Y sqrt(R_eff) / (3 (1 - nu^2))).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub young: Option<f64>,
    /// `law = "viscoelastic"`: the Poisson ratio of the particles' material, -1 < nu < 0.5.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = -1, "exclusiveMaximum" = 0.5))]
    pub poisson: Option<f64>,
    /// `law = "viscoelastic"`: the dissipative constant A >= 0 of the particles' material
    /// (a time; Eq. (2) of Müller & Pöschel 2011).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0))]
    pub dissipative_constant: Option<f64>,
    /// The contact duration of the TC model, a time >= 0: a collision is elastic if either
    /// partner collided less than `tc` ago, which stops the inelastic collapse of the
    /// event-driven engine (0 or absent: off).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0))]
    pub tc: Option<f64>,
    /// `law = "stochastic"`: where eps^2 is drawn from (default `glauber`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("default" = "glauber"))]
    pub distribution: Option<Distribution>,
    /// `law = "stochastic"` (required): the internal vibration modes per particle, >= 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 1))]
    pub modes: Option<u32>,
    /// `law = "stochastic"`: the initial bath temperature of every particle, 0 (cold, the
    /// default) or 1e-30 ..= 1e30.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0, max = 1e30), extend("default" = 0.0))]
    pub bath_temperature: Option<f64>,
    /// `law = "stochastic"`, `distribution = "tabulated"` (required): a table written by
    /// `haff rods table`, a path relative to the working directory.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub table: Option<String>,
    /// Rough particles (2D and 3D): the tangential restitution -1 <= β <= 1 (-1: smooth,
    /// the default; 1: perfectly rough), one for all pairs or a symmetric matrix with a row
    /// per species of `system.species`. Soft-sphere MD takes `friction` alone instead.
    // The tangential rule: `restitution::rough`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(
        with = "Option<json_schema::TangentialRestitution>",
        extend("default" = -1.0)
    )]
    pub tangential_restitution: Option<RestitutionValue>,
    /// Rough particles: Coulomb's friction coefficient 0 <= mu <= 1e30 of Walton's model
    /// (the contact slides where sticking would need a tangential impulse beyond mu times
    /// the normal one; soft-sphere MD: the cut of the tangential force).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0, max = 1e30))]
    pub friction: Option<f64>,
}

/// The engine of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum EngineKind {
    /// Event-driven molecular dynamics of hard spheres: exact collisions in order.
    EventDriven,
    /// Direct simulation Monte Carlo (`dsmc_scheme`).
    Dsmc,
    /// Soft-sphere molecular dynamics of the viscoelastic (Hertz) contact force.
    SoftSphere,
}

/// The scheme of the DSMC.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum DsmcScheme {
    /// Homogeneous, the exact process in parallel blocks.
    Blocks,
    /// Homogeneous, the exact process over all pairs (serial).
    Exact,
    /// Collision cells and free streaming in the periodic box.
    Spatial,
}

impl DsmcScheme {
    /// The name in the run file.
    pub fn name(self) -> &'static str {
        match self {
            DsmcScheme::Blocks => "blocks",
            DsmcScheme::Exact => "exact",
            DsmcScheme::Spatial => "spatial",
        }
    }
}

/// How the samples are spread over the run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Spacing {
    /// The first at 0, the others log-spaced from a thousandth of the run to its end.
    Log,
    /// Evenly spaced from 0 to the end.
    Linear,
}

/// `[run]`: the engine, how far the run goes (`collisions_per_particle` or `end_time`,
/// exactly one) and what it samples; the keys of each engine are refused for the others.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RunSection {
    /// The engine.
    #[serde(default = "event_driven")]
    pub engine: EngineKind,
    /// Run until this many collisions per particle, > 0 (each collision counts for both
    /// partners); or `end_time`.
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub collisions_per_particle: Option<f64>,
    /// Run until this time, > 0; or `collisions_per_particle`.
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub end_time: Option<f64>,
    /// The number of samples (rows of `timeseries.csv`), 2 ..= 1e6.
    #[serde(default = "two_hundred")]
    #[schemars(range(min = 2, max = 1_000_000))]
    pub samples: usize,
    /// How the samples are spread over the run.
    #[serde(default = "log")]
    pub spacing: Spacing,
    /// Velocity histograms at these points of the run (in the unit of the stop criterion:
    /// collisions per particle or time), each in 0 ..= the end, distinct, at most 10000.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(length(max = 10_000), inner(range(min = 0)))]
    pub histogram_at: Option<Vec<f64>>,
    /// The bins of the velocity histograms, 4 ..= 10000 (default 60).
    // The default: [`crate::observer::HISTOGRAM_BINS`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(
        range(min = 4, max = 10_000),
        extend("default" = crate::observer::HISTOGRAM_BINS)
    )]
    pub histogram_bins: Option<usize>,
    /// `engine = "dsmc"`: the scheme (default `blocks`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("default" = "blocks"))]
    pub dsmc_scheme: Option<DsmcScheme>,
    /// `dsmc_scheme = "blocks"`: particles per block, 2 ..= 2^32 - 1 (default 4096).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(
        range(min = 2, max = 4_294_967_295_u64),
        extend("default" = gas::dsmc::DEFAULT_BLOCK_SIZE)
    )]
    pub block_size: Option<usize>,
    /// `dsmc_scheme = "blocks"` or `"spatial"`: the step size in collisions per particle per
    /// step, 1e-4 ..= 100 (default: the engine's); or `time_step`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 1e-4, max = 100))]
    pub collisions_per_step: Option<f64>,
    /// The time step, > 0: DSMC (`blocks`, `spatial`; with `end_time`, at most 1e8 steps),
    /// or soft-sphere MD (4 to 1e6 steps per contact duration); or `collisions_per_step`,
    /// `steps_per_contact`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub time_step: Option<f64>,
    /// `dsmc_scheme = "spatial"`: the width of the collision cells, > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub collision_cell_width: Option<f64>,
    /// `dsmc_scheme = "spatial"`: the physical particles each simulated particle stands for
    /// (SPARTA's `fnum`), 2 / `system.particles` ..= 1e6 (default 1). The box holds
    /// `system.particles` × weight spheres at `system.packing_fraction`, so a weight below 1
    /// puts more simulated particles into each mean free path.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(
        range(max = 1e6),
        extend("exclusiveMinimum" = 0, "default" = 1.0)
    )]
    pub particle_weight: Option<f64>,
    /// `engine = "soft-sphere"`: time steps per Hertz contact duration, 4 ..= 1e6 (default
    /// 50); or `time_step`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(
        range(min = 4, max = 1e6),
        extend("default" = gas::soft::DEFAULT_STEPS_PER_CONTACT)
    )]
    pub steps_per_contact: Option<f64>,
    /// The MPI ranks the run must be launched on (`mpirun -n RANKS`; a haff built with the
    /// feature `mpi`), 1 ..= 1e6; more than one for `dsmc_scheme = "spatial"` only. Without
    /// it, a run takes the ranks it is launched on.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 1, max = 1_000_000))]
    pub ranks: Option<usize>,
}

fn three() -> u32 {
    3
}
fn one() -> f64 {
    1.0
}
fn first_seed() -> u64 {
    1
}
fn event_driven() -> EngineKind {
    EngineKind::EventDriven
}
fn two_hundred() -> usize {
    200
}
fn log() -> Spacing {
    Spacing::Log
}

impl RunDescription {
    /// Parses TOML text (see [`parse_toml`]).
    pub fn from_toml(text: &str, origin: &Path) -> Result<Self> {
        let mut description: Self = parse_toml(text, origin)?;
        description.system.temperature_given = text
            .parse::<toml::Table>()
            .ok()
            .and_then(|t| t.get("system")?.as_table()?.get("temperature").cloned())
            .is_some();
        Ok(description)
    }

    /// Reads and parses a TOML run file.
    pub fn from_path(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::RunFile {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        Self::from_toml(&text, path)
    }

    /// The description as a TOML run file (what `haff run --check` prints: the normal form
    /// after validation is the run `summary.json` records under `parameters`).
    pub fn to_toml(&self) -> Result<String> {
        toml::to_string(self).map_err(|e| Error::input("run file", e))
    }

    /// The packing fraction of the physical spheres: `system.packing_fraction`, or that of
    /// the spheres (each simulated one standing for `run.particle_weight`) in `system.box`.
    /// NaN if neither is given or the species do not split (validation refuses both first).
    pub fn packing_fraction(&self) -> f64 {
        let s = &self.system;
        match (s.packing_fraction, &s.sides) {
            (Some(phi), _) => phi,
            (None, Some(sides)) => self.physical_sphere_volume() / sides.iter().product::<f64>(),
            (None, None) => f64::NAN,
        }
    }

    /// The sides of the box: `system.box`, or those of the cube that the physical spheres
    /// fill to `system.packing_fraction` (the engines' sides up to rounding).
    pub fn box_sides(&self) -> Vec<f64> {
        let s = &self.system;
        match &s.sides {
            Some(sides) => sides.clone(),
            None => {
                let volume = self.physical_sphere_volume() / self.packing_fraction();
                vec![volume.powf(1.0 / s.dimension as f64); s.dimension as usize]
            }
        }
    }

    /// The volume of the physical spheres: the simulated ones' (species split as the
    /// initializer splits them) times `run.particle_weight`.
    fn physical_sphere_volume(&self) -> f64 {
        let s = &self.system;
        let ball = |d: f64| match s.dimension {
            1 => d,
            2 => std::f64::consts::PI * d * d / 4.0,
            _ => std::f64::consts::PI * d * d * d / 6.0,
        };
        let spheres = match &s.species {
            None => s.particles as f64 * ball(s.diameter.unwrap_or(1.0)),
            Some(entries) => {
                let kinds = species(entries);
                match gas::init::species_counts(s.particles, &kinds) {
                    Ok(counts) => kinds
                        .iter()
                        .zip(counts)
                        .map(|(x, c)| c as f64 * ball(x.diameter))
                        .sum(),
                    Err(_) => f64::NAN,
                }
            }
        };
        spheres * self.run.particle_weight.unwrap_or(1.0)
    }

    /// Fills in the defaults that depend on other keys: diameter = mass = 1 without species
    /// (so that summary.json names them).
    pub fn normalize(&mut self) {
        let s = &mut self.system;
        if s.species.is_none() {
            s.diameter.get_or_insert(1.0);
            s.mass.get_or_insert(1.0);
        }
    }
}

/// Parses TOML text into `T`. A value of the wrong type or a name outside its choices is an
/// [`Error::Input`] naming the key (`collision.law: unknown value `constnt`; did you mean
/// `constant`? ...`, [`did_you_mean`]); text that is not
/// TOML is an [`Error::RunFile`] of `origin`.
pub fn parse_toml<T: DeserializeOwned>(text: &str, origin: &Path) -> Result<T> {
    let syntax = |e: toml::de::Error| Error::RunFile {
        path: origin.to_path_buf(),
        message: one_line(&e.to_string()),
    };
    let deserializer = toml::de::Deserializer::parse(text).map_err(syntax)?;
    serde_path_to_error::deserialize(deserializer).map_err(|e| {
        let key = e.path().to_string();
        let message = did_you_mean(&key, &one_line(e.inner().message()));
        if key == "." {
            Error::RunFile {
                path: origin.to_path_buf(),
                message,
            }
        } else {
            Error::Input { key, message }
        }
    })
}

/// serde's refusal of an unknown key or value (`unknown field `restituton`, expected one of
/// `law`, `restitution`, ...`) said for a user: the closest allowed name suggested when it is
/// close (the Damerau–Levenshtein distance at most a third of the name's length, at least
/// 1), the allowed names listed. Other messages are returned as they are.
fn did_you_mean(key: &str, message: &str) -> String {
    let (what, rest) = if let Some(rest) = message.strip_prefix("unknown field ") {
        ("key", rest)
    } else if let Some(rest) = message.strip_prefix("unknown variant ") {
        ("value", rest)
    } else {
        return message.to_string();
    };
    let names: Vec<&str> = rest.split('`').skip(1).step_by(2).collect();
    let Some((given, allowed)) = names.split_first() else {
        return message.to_string();
    };
    let section = match (what, key.rsplit_once('.')) {
        ("key", Some((table, _))) => format!(" in [{table}]"),
        _ => String::new(),
    };
    let list = allowed
        .iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ");
    let closest = allowed
        .iter()
        .map(|n| (strsim::damerau_levenshtein(given, n), *n))
        .min()
        .filter(|&(d, _)| d <= (given.chars().count() / 3).max(1));
    match closest {
        Some((_, name)) => {
            format!("unknown {what} `{given}`{section}; did you mean `{name}`? (allowed: {list})")
        }
        None if allowed.is_empty() => format!("unknown {what} `{given}`{section}"),
        None => format!("unknown {what} `{given}`{section}; allowed: {list}"),
    }
}

/// Reads a TOML file and parses it into `T` (see [`parse_toml`]).
pub fn read_toml<T: DeserializeOwned>(path: &Path) -> Result<T> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::RunFile {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    parse_toml(&text, path)
}

/// The species of `system.species` as the initializer takes them.
pub(crate) fn species(entries: &[SpeciesEntry]) -> Vec<gas::init::Species> {
    entries
        .iter()
        .map(|x| gas::init::Species {
            diameter: x.diameter,
            mass: x.mass,
            fraction: x.fraction,
        })
        .collect()
}

/// A multi-line message on one line.
pub(crate) fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}
