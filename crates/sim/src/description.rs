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
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::path::Path;

mod snapshot_format;
pub use snapshot_format::{SnapshotFormat, SnapshotFormats};

/// A whole run file.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RunDescription {
    pub system: SystemSection,
    pub collision: CollisionSection,
    pub run: RunSection,
    /// `[output]`: the observers of space (spatial engines only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub output: Option<OutputSection>,
    /// `[driving]`: energy fed in, for a steady state instead of free cooling.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub driving: Option<DrivingSection>,
    /// `[[wall]]`: the walls of a container (none: the periodic box).
    #[serde(default, rename = "wall", skip_serializing_if = "Vec::is_empty")]
    pub walls: Vec<WallSection>,
    /// `[field]`: forces on every sphere (gravity).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub field: Option<FieldSection>,
    /// `[shear]`: uniform shear flow (Lees–Edwards boundaries).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear: Option<ShearSection>,
}

/// `[shear]`: the uniform shear flow u = rate · y e_x (flow along x, gradient along y):
/// Lees–Edwards boundaries in the event-driven engine, soft-sphere MD and the spatial DSMC,
/// the frame moving with the flow in the homogeneous DSMC (`gas::shear`). `pressure.csv` and `summary.json`'s `rheology`
/// come with it; `timeseries.csv`'s temperature is that of the velocities relative to the
/// flow.
///
/// ```toml
/// [shear]
/// rate = 0.5
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ShearSection {
    pub rate: f64,
}

/// `[field]`: a uniform acceleration of every sphere, along axes closed by walls.
///
/// ```toml
/// [field]
/// gravity = [0.0, 0.0, -1.0]   # one component per dimension
/// rest_height = 1e-4           # a floor sends spheres at least this high (default
///                              # 1e-4 of the smallest diameter; the resting rule)
/// ```
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FieldSection {
    pub gravity: Vec<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rest_height: Option<f64>,
}

/// One `[[wall]]`: a flat wall on one side of one axis (`gas::walls`); an axis is periodic
/// unless both its sides have a wall.
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
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct WallSection {
    pub axis: AxisName,
    pub side: WallSide,
    pub kind: WallKindName,
    /// Restitution and vibrating walls: the coefficient of restitution (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restitution: Option<f64>,
    /// Restitution and vibrating walls: the law of their contacts, with the keys of
    /// `[collision]`'s law of that name (default `constant`, with `restitution`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub law: Option<LawKind>,
    /// `law = "dashpot"`: the damping ratio.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping_ratio: Option<f64>,
    /// `law = "dashpot"`: the end-of-contact criterion.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub criterion: Option<Criterion>,
    /// `law = "viscoelastic"`: β of the sphere–wall contact.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beta: Option<f64>,
    /// `law = "viscoelastic"`: the form of eps(v) (default as in `[collision]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub form: Option<FormName>,
    /// `law = "viscoelastic"` without `beta`: the wall's material, Young modulus (a key
    /// left out is the particles' of `[collision]`; none: a wall of the particles' material).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub young: Option<f64>,
    /// The wall's material: Poisson ratio.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub poisson: Option<f64>,
    /// The wall's material: dissipative constant A (a time).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dissipative_constant: Option<f64>,
    /// Thermal walls: the wall's temperature.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature: Option<f64>,
    /// Vibrating walls: the amplitude of the wall's motion.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub amplitude: Option<f64>,
    /// Vibrating walls: the frequency of the wall's motion.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frequency: Option<f64>,
    /// Vibrating walls: the waveform of the wall's motion.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub waveform: Option<Waveform>,
}

/// `wall.axis`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
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

/// `wall.side`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum WallSide {
    Low,
    High,
}

/// `wall.kind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum WallKindName {
    Elastic,
    Restitution,
    Thermal,
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

/// `wall.waveform`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Waveform {
    Sine,
    Triangle,
    Sawtooth,
}

/// `[driving]`: energy fed in for a steady state (`gas::driving`). White noise
/// (`kind = "white-noise"`): every particle's velocity receives Gaussian kicks of variance
/// `strength` per component and unit time (a random acceleration, the same for every
/// species). The Gaussian thermostat (`kind = "gaussian-thermostat"`): every velocity is
/// scaled about the mean by one factor that holds the temperature at `temperature`
/// (default: `system.temperature`); the steady state has the HCS's shape. DSMC (blocks)
/// applies either at every step; the event-driven engine at the times k `interval`
/// (default: a tenth of the mean free time at the larger of the initial and the expected
/// steady temperature), renewing every prediction.
///
/// ```toml
/// [driving]
/// kind = "white-noise"
/// strength = 1.0
/// # interval = 0.01   (event-driven only)
/// ```
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DrivingSection {
    pub kind: DrivingKind,
    /// White noise: xi^2, the velocity variance per component and unit time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub strength: Option<f64>,
    /// Gaussian thermostat: the temperature held.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature: Option<f64>,
    /// Event-driven: the time between applications.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub interval: Option<f64>,
}

/// `driving.kind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DrivingKind {
    WhiteNoise,
    GaussianThermostat,
}

/// `[output]`: what a run records of space, at the samples of its schedule. Checked by
/// `crate::space::check_output`.
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
#[derive(Debug, Clone, PartialEq, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSection {
    #[serde(default)]
    pub modes: bool,
    /// Largest |n|² of the mode shells (default 3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode_shells: Option<usize>,
    #[serde(default)]
    pub structure: bool,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fields: Option<FieldsOutput>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snapshots: Option<SnapshotsOutput>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profiles: Option<ProfilesOutput>,
    /// The pressure tensor at every sample (`pressure.csv`; always under `[shear]`).
    #[serde(default, skip_serializing_if = "is_false")]
    pub pressure: bool,
    /// The mean-square displacement at every sample (`msd.csv`; the event-driven engine,
    /// soft-sphere MD and spatial DSMC on one process; not under `[shear]`).
    #[serde(default, skip_serializing_if = "is_false")]
    pub msd: bool,
}

fn is_false(x: &bool) -> bool {
    !*x
}

/// `output.profiles`: slabs along `axis`, `bins` of them, at every sample
/// (`profiles.csv`).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ProfilesOutput {
    pub axis: AxisName,
    pub bins: usize,
}

/// `output.fields`: coarse-grained fields every `every` samples on a `grid`^D grid.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FieldsOutput {
    pub every: usize,
    pub grid: usize,
}

/// `output.snapshots`: the particles every `every` samples, in one or more formats.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SnapshotsOutput {
    pub every: usize,
    #[serde(default)]
    pub format: SnapshotFormats,
}

/// `[system]`: the particles and their initial state.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SystemSection {
    #[serde(default = "three")]
    pub dimension: u32,
    /// The number of particles (with `initial`: the file's, filled in by validation).
    #[serde(default)]
    pub particles: usize,
    /// The spheres' volume over the (cubic) box's; or `box`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub packing_fraction: Option<f64>,
    /// The sides of the box, one per dimension (instead of `packing_fraction`).
    #[serde(default, rename = "box", skip_serializing_if = "Option::is_none")]
    pub sides: Option<Vec<f64>>,
    /// 1.0 unless `species` is given (filled in by [`RunDescription::normalize`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diameter: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mass: Option<f64>,
    /// A mixture instead of `diameter` and `mass`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub species: Option<Vec<SpeciesEntry>>,
    #[serde(default = "one")]
    pub temperature: f64,
    #[serde(default = "first_seed")]
    pub seed: u64,
    /// Rough particles: the inertia factor q, I = q m d^2 / 4 (0.4 a solid sphere, the
    /// default; 2/3 a hollow one; disks: 0.5 a solid disk, the default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia: Option<f64>,
    /// Rough particles: the rotational temperature of the start, I <w^2> / d_rot
    /// (default: `temperature`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotational_temperature: Option<f64>,
    /// The particles from a file or from another run instead of a placement: their number,
    /// box, diameters, masses and velocities (the normal form holds them resolved:
    /// `crate::validate` fills in `particles`, `box`, the species and the temperature).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial: Option<InitialSection>,
    /// Whether the run file gave `temperature` (not serialized: a file's velocities and a
    /// temperature to draw them at are refused together).
    #[serde(skip)]
    pub temperature_given: bool,
}

/// `system.initial`: where the particles come from.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct InitialSection {
    /// A particle file (`sim::particles`), relative to the working directory.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// Its format (`csv`, `lammps-dump`, `xyz`, ...; by default from the file's extension).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub format: Option<String>,
    /// The frame of a file of several (0 the first, -1 the last: the default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frame: Option<i64>,
    /// The output directory of another haff run: its last check-point.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub run: Option<String>,
    /// The total momentum of the file's velocities: reported and kept (`keep`, the
    /// default) or removed (`remove`: the mass-weighted mean velocity subtracted).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub momentum: Option<MomentumPolicy>,
    /// The particles' mass density, for files without masses: m = density x the ball's
    /// volume (pi/6 d^3, pi/4 d^2 in 2D, d in 1D).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<f64>,
}

/// `system.initial.momentum`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MomentumPolicy {
    Keep,
    Remove,
}

/// One entry of `system.species`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SpeciesEntry {
    pub diameter: f64,
    pub mass: f64,
    /// Number fraction (normalized over the species).
    pub fraction: f64,
    /// Viscoelastic material of this species (law = "viscoelastic"): Young modulus; a key
    /// left out is taken from `[collision]`. Unlike species collide with the pair's beta
    /// (`restitution::material::MaterialPair`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub young: Option<f64>,
    /// Viscoelastic material of this species: Poisson ratio.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub poisson: Option<f64>,
    /// Viscoelastic material of this species: dissipative constant A (a time).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dissipative_constant: Option<f64>,
    /// Rough particles: this species' inertia factor (default `system.inertia`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
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

/// `collision.law`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LawKind {
    /// A constant coefficient of restitution (`restitution`).
    Constant,
    /// The linear dash-pot (`damping_ratio`, `criterion`).
    Dashpot,
    /// Viscoelastic spheres (`beta`, `form`).
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

/// `collision.distribution` of the stochastic law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Distribution {
    /// Eq. (7) of Giese.
    Glauber,
    /// p(eps^2) tabulated from Eq. (3) by `haff rods table`.
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

/// `[collision]`: the law and its parameters. The stochastic keys are refused for the
/// other laws by [`crate::validate`]; keys of another deterministic law are still accepted
/// and ignored (as they always were).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CollisionSection {
    pub law: LawKind,
    // The four keys below are written as null when absent (summary.json has always
    // listed them).
    #[serde(default)]
    pub restitution: Option<RestitutionValue>,
    #[serde(default)]
    pub damping_ratio: Option<f64>,
    #[serde(default)]
    pub criterion: Option<Criterion>,
    #[serde(default)]
    pub beta: Option<f64>,
    #[serde(default)]
    pub form: Option<FormName>,
    /// Viscoelastic material: a built-in one by name (`steel`, `soda-lime-glass`,
    /// `aluminium`, `ice`: Young modulus, Poisson ratio and density in SI; the masses follow
    /// from the density), with `dissipative_constant` in s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// Viscoelastic material: Young modulus (instead of beta, with `poisson` and
    /// `dissipative_constant`), in the units of the system.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub young: Option<f64>,
    /// Viscoelastic material: Poisson ratio.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub poisson: Option<f64>,
    /// Viscoelastic material: the dissipative constant A of Eq. (2) of MP2011 (a time).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dissipative_constant: Option<f64>,
    /// Contact duration of the TC model (0 or absent: off).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tc: Option<f64>,
    /// Stochastic law: Glauber (default) or tabulated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distribution: Option<Distribution>,
    /// Stochastic law: internal vibration modes per particle.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<u32>,
    /// Stochastic law: initial bath temperature of every particle (default 0: cold).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bath_temperature: Option<f64>,
    /// Stochastic tabulated law: a table written by `haff rods table` (a path relative to
    /// the working directory).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub table: Option<String>,
    /// Rough particles: the tangential restitution beta in [-1, 1] (-1: smooth, the
    /// default; `restitution::rough`), one for all pairs or a symmetric matrix with a row
    /// per species of `system.species`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangential_restitution: Option<RestitutionValue>,
    /// Rough particles: Coulomb's friction coefficient of Walton's model (the contact
    /// slides where sticking would need a tangential impulse beyond mu times the normal
    /// one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<f64>,
}

/// `run.engine`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum EngineKind {
    EventDriven,
    Dsmc,
    SoftSphere,
}

/// `run.dsmc_scheme`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
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

/// `run.spacing` of the samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Spacing {
    Log,
    Linear,
}

/// `[run]`: the engine, how far to go and what to record.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RunSection {
    #[serde(default = "event_driven")]
    pub engine: EngineKind,
    pub collisions_per_particle: Option<f64>,
    pub end_time: Option<f64>,
    #[serde(default = "two_hundred")]
    pub samples: usize,
    #[serde(default = "log")]
    pub spacing: Spacing,
    /// Where to take velocity histograms (unit of the stop criterion).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub histogram_at: Option<Vec<f64>>,
    /// Bins of the velocity histograms (default [`crate::observer::HISTOGRAM_BINS`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub histogram_bins: Option<usize>,
    /// DSMC: blocks (default), exact or spatial.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dsmc_scheme: Option<DsmcScheme>,
    /// DSMC blocks: particles per block.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub block_size: Option<usize>,
    /// DSMC blocks / spatial: collisions per particle per step (or `time_step`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collisions_per_step: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_step: Option<f64>,
    /// Spatial DSMC: width of the collision cells.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collision_cell_width: Option<f64>,
    /// Spatial DSMC: the physical particles each simulated particle stands for (SPARTA's
    /// `fnum`; default 1). The box holds `system.particles` x weight spheres at
    /// `system.packing_fraction`, so a weight below 1 puts more simulated particles into
    /// each mean free path.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub particle_weight: Option<f64>,
    /// Soft-sphere MD: time steps per Hertz contact duration (or `time_step`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps_per_contact: Option<f64>,
    /// Spatial DSMC: the MPI ranks the run must be launched on (`mpirun -n RANKS`; a binary
    /// built with the feature `mpi`). Without it, a run takes the ranks it is launched on.
    #[serde(default, skip_serializing_if = "Option::is_none")]
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
