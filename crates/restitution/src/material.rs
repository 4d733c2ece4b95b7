//! Materials, spheres, contact pairs and units.
//!
//! Everything is stored and computed in SI units (m, kg, s, Pa). The unit system only
//! matters at the boundary: [`UnitSystem`] converts speeds and the viscoelastic
//! material parameter β between SI and cgs.
//!
//! The physics is the viscoelastic (Hertz + dissipative) contact of two smooth spheres,
//! Eqs. (1)–(3) and (8)–(9) of MP2011 and Eqs. (13)–(23) of SP2008.

use std::f64::consts::PI;
use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::error::{require_non_negative, require_positive, Error, Result};

/// Centimetres per metre, the only length factor between SI and cgs.
pub const CENTIMETERS_PER_METER: f64 = 100.0;

/// β of the ice spheres of Bridges, Hatzes and Lin, Nature 309, 333 (1984), in (s/cm)^(1/5),
/// as quoted in MP2011 (text around Fig. 1 and caption of Fig. 4).
///
/// This is a calibration fitted to the measured coefficient of restitution, not a value
/// derived from the material table of this module.
pub const ICE_BRIDGES_BETA_CGS: f64 = 1.307;

/// The system of units used for input and output (the library itself computes in SI).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum UnitSystem {
    /// Metre, kilogram, second.
    #[default]
    Si,
    /// Centimetre, gram, second.
    Cgs,
}

impl UnitSystem {
    /// All unit systems, in the order of their names in error messages.
    pub const ALL: [UnitSystem; 2] = [UnitSystem::Si, UnitSystem::Cgs];

    /// The lowercase name accepted by [`FromStr`].
    pub fn name(self) -> &'static str {
        match self {
            UnitSystem::Si => "si",
            UnitSystem::Cgs => "cgs",
        }
    }

    /// Length units of this system per metre (1 for SI, 100 for cgs).
    pub fn length_units_per_meter(self) -> f64 {
        match self {
            UnitSystem::Si => 1.0,
            UnitSystem::Cgs => CENTIMETERS_PER_METER,
        }
    }

    /// Converts a length from metres into this system.
    pub fn length_from_si(self, meters: f64) -> f64 {
        meters * self.length_units_per_meter()
    }

    /// Converts a length from this system into metres.
    pub fn length_to_si(self, length: f64) -> f64 {
        length / self.length_units_per_meter()
    }

    /// Converts a speed from m/s into this system (time is the second in both).
    pub fn speed_from_si(self, meters_per_second: f64) -> f64 {
        self.length_from_si(meters_per_second)
    }

    /// Converts a speed from this system into m/s.
    pub fn speed_to_si(self, speed: f64) -> f64 {
        self.length_to_si(speed)
    }

    /// Converts β, Eq. (8) of MP2011, from (s/m)^(1/5) into this system.
    ///
    /// β v^(1/5) is dimensionless, so β scales as (length)^(-1/5):
    /// β_cgs = β_SI · 100^(-1/5).
    pub fn beta_from_si(self, beta_si: f64) -> f64 {
        beta_si * self.length_units_per_meter().powf(-0.2)
    }

    /// Converts β from this system into (s/m)^(1/5); inverse of [`Self::beta_from_si`].
    pub fn beta_to_si(self, beta: f64) -> f64 {
        beta * self.length_units_per_meter().powf(0.2)
    }

    /// Unit of speed in this system, for display.
    pub fn speed_unit(self) -> &'static str {
        match self {
            UnitSystem::Si => "m/s",
            UnitSystem::Cgs => "cm/s",
        }
    }

    /// Unit of β in this system, for display.
    pub fn beta_unit(self) -> &'static str {
        match self {
            UnitSystem::Si => "(s/m)^(1/5)",
            UnitSystem::Cgs => "(s/cm)^(1/5)",
        }
    }
}

impl fmt::Display for UnitSystem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for UnitSystem {
    type Err = Error;

    /// Parses `si` or `cgs` (case-insensitive, surrounding blanks ignored).
    fn from_str(s: &str) -> Result<Self> {
        let wanted = s.trim();
        UnitSystem::ALL
            .into_iter()
            .find(|units| units.name().eq_ignore_ascii_case(wanted))
            .ok_or_else(|| Error::parse("unit system", format!("`{s}` is not one of: si, cgs")))
    }
}

/// Checks that the Poisson ratio is finite and in the open interval (-1, 0.5).
fn require_poisson_ratio(poisson: f64) -> Result<f64> {
    if poisson.is_finite() && poisson > -1.0 && poisson < 0.5 {
        Ok(poisson)
    } else {
        Err(Error::out_of_range(
            "poisson_ratio",
            poisson,
            "a number in the open interval (-1, 0.5)",
        ))
    }
}

/// Checks that an optional dissipative constant A, if given, is finite and >= 0.
fn check_optional_dissipative_constant(a: Option<f64>) -> Result<Option<f64>> {
    match a {
        Some(value) => {
            require_non_negative("dissipative_constant", value)?;
            Ok(Some(value))
        }
        None => Ok(None),
    }
}

/// An isotropic viscoelastic material; all quantities in SI.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Short identifier, e.g. `steel`.
    pub name: String,
    /// Young modulus Y in Pa.
    pub young_modulus: f64,
    /// Poisson ratio ν, in (-1, 0.5).
    pub poisson_ratio: f64,
    /// Mass density in kg/m³.
    pub density: f64,
    /// Dissipative constant A in s, Eq. (2) of MP2011 / Eq. (15) of SP2008, if known.
    pub dissipative_constant: Option<f64>,
    /// Where the numbers come from.
    pub source: String,
}

impl Material {
    /// A validated material: Y > 0, ν in (-1, 0.5), density > 0, A >= 0 (all finite).
    pub fn new(
        name: impl Into<String>,
        young_modulus: f64,
        poisson_ratio: f64,
        density: f64,
        dissipative_constant: Option<f64>,
        source: impl Into<String>,
    ) -> Result<Self> {
        let material = Material {
            name: name.into(),
            young_modulus,
            poisson_ratio,
            density,
            dissipative_constant,
            source: source.into(),
        };
        material.validate()?;
        Ok(material)
    }

    /// Checks the ranges of all fields (useful after deserialisation or manual edits).
    pub fn validate(&self) -> Result<()> {
        require_positive("young_modulus", self.young_modulus)?;
        require_poisson_ratio(self.poisson_ratio)?;
        require_positive("density", self.density)?;
        check_optional_dissipative_constant(self.dissipative_constant)?;
        Ok(())
    }

    /// The same material with dissipative constant A (in s, must be >= 0).
    pub fn with_dissipative_constant(mut self, a: f64) -> Result<Self> {
        self.dissipative_constant = check_optional_dissipative_constant(Some(a))?;
        Ok(self)
    }

    /// The dissipative constant A in s, or an error naming `dissipative_constant` if unknown.
    pub fn required_dissipative_constant(&self) -> Result<f64> {
        self.dissipative_constant.ok_or_else(|| {
            Error::out_of_range(
                "dissipative_constant",
                format!("unset (material `{}`)", self.name),
                "a finite number >= 0 in s; this material has none, set it explicitly",
            )
        })
    }

    /// The effective elastic modulus Y / (1 - ν²) that enters Eq. (3) of MP2011.
    pub fn plane_strain_modulus(&self) -> f64 {
        self.young_modulus / (1.0 - self.poisson_ratio.powi(2))
    }
}

/// Dissipative constant A in s from the viscous constants η1, η2 (Pa·s), Eq. (15) of SP2008:
///
/// A = (1/3) (3η2 − η1)² / (3η2 + 2η1) · (1 − ν²)(1 − 2ν) / (Y ν²).
///
/// Requires η1, η2 >= 0 (not both zero), Y > 0, ν in (-1, 0.5) and ν ≠ 0
/// (the formula divides by ν²).
pub fn dissipative_constant_from_viscosities(
    eta1: f64,
    eta2: f64,
    young: f64,
    poisson: f64,
) -> Result<f64> {
    require_non_negative("eta1", eta1)?;
    require_non_negative("eta2", eta2)?;
    require_positive("3*eta2 + 2*eta1", 3.0 * eta2 + 2.0 * eta1)?;
    require_positive("young_modulus", young)?;
    require_poisson_ratio(poisson)?;
    if poisson == 0.0 {
        return Err(Error::out_of_range(
            "poisson_ratio",
            poisson,
            "a nonzero number in (-1, 0.5): Eq. (15) of SP2008 divides by nu^2",
        ));
    }
    let viscous = (3.0 * eta2 - eta1).powi(2) / (3.0 * eta2 + 2.0 * eta1);
    let elastic = (1.0 - poisson.powi(2)) * (1.0 - 2.0 * poisson) / (young * poisson.powi(2));
    Ok(viscous * elastic / 3.0)
}

/// Two viscoelastic materials in contact: the constants of the force of Eq. (2) of MP2011,
/// F = ρ ξ^(3/2) + (3/2) A ρ √ξ ξ̇, for spheres of unlike materials (any consistent units).
///
/// Derivation (the papers treat one material). Hertz: ρ = (4/3) E* √R_eff with the
/// combined plane-strain compliance 1/E* = D_1 + D_2, D_i = (1 − ν_i²)/Y_i; for one material
/// E* = Y / (2 (1 − ν²)) gives Eq. (3) of MP2011. The dissipative force of one material,
/// (3/2) A ρ √ξ ξ̇ = A d/dt (ρ ξ^(3/2)), is the quasi-static (first order in A over the
/// contact duration) response of a Kelvin–Voigt modulus E(s) = E (1 + A s) in the Laplace
/// variable s. By the correspondence principle for a Hertz contact of growing area (Lee &
/// Radok 1960) the two bodies' compliances add: 1/E*(s) = D_1 / (1 + A_1 s) + D_2 / (1 +
/// A_2 s) = (D_1 + D_2) (1 − s (A_1 D_1 + A_2 D_2) / (D_1 + D_2) + O(s²)), so to the order the
/// viscoelastic law itself is derived at, the pair acts as one material of compliance
/// D_1 + D_2 and dissipative constant
///
///   A_12 = (A_1 D_1 + A_2 D_2) / (D_1 + D_2),
///
/// the compliance-weighted mean (the softer body dissipates more). One material: A_12 = A.
/// Checked in `tests/material.rs` against the collision of the two-body Kelvin–Voigt
/// contact integrated without the expansion: eps differs beyond O(A) (by O(A^2.5) there),
/// the order the single-material law itself neglects.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaterialPair {
    /// E* = 1 / (D_1 + D_2).
    pub combined_modulus: f64,
    /// A_12, the compliance-weighted mean of the dissipative constants.
    pub dissipative_constant: f64,
}

impl MaterialPair {
    /// The pair of materials (Young modulus, Poisson ratio, dissipative constant) each:
    /// Y > 0, ν in (−1, 0.5), A >= 0, all finite.
    pub fn new(first: (f64, f64, f64), second: (f64, f64, f64)) -> Result<Self> {
        let mut compliance = [0.0; 2];
        for (d, &(young, poisson, a)) in compliance.iter_mut().zip([&first, &second]) {
            require_positive("young_modulus", young)?;
            require_poisson_ratio(poisson)?;
            require_non_negative("dissipative_constant", a)?;
            *d = (1.0 - poisson * poisson) / young;
        }
        let [d1, d2] = compliance;
        Ok(MaterialPair {
            combined_modulus: 1.0 / (d1 + d2),
            dissipative_constant: (first.2 * d1 + second.2 * d2) / (d1 + d2),
        })
    }

    /// ρ = (4/3) E* √R_eff of spheres of radii r1, r2 (Eq. (3) of MP2011 for one material).
    pub fn elastic_constant(&self, r1: f64, r2: f64) -> f64 {
        4.0 / 3.0 * self.combined_modulus * (r1 * r2 / (r1 + r2)).sqrt()
    }

    /// ρ_w = (4/3) E* √r of a sphere of radius r (this pair's first material) against a
    /// half-space (the second): Eq. (3) of MP2011 with the second radius infinite
    /// (R_eff = r); for one material 2 Y √r / (3 (1 − ν²)).
    pub fn wall_elastic_constant(&self, r: f64) -> f64 {
        4.0 / 3.0 * self.combined_modulus * r.sqrt()
    }

    /// β = (3/2) A_12 (ρ_w / m)^(2/5) of a sphere (r, m) against an immovable half-space
    /// (m_eff = m): Eq. (8) of MP2011 with the second mass and radius infinite. For one
    /// material it is 2^(-1/5) times the β of two such spheres (ρ_w / ρ = √2, m / m_eff = 2).
    pub fn wall_beta(&self, r: f64, m: f64) -> f64 {
        1.5 * self.dissipative_constant * (self.wall_elastic_constant(r) / m).powf(0.4)
    }

    /// β = (3/2) A_12 (ρ / m_eff)^(2/5) of spheres (r1, m1) and (r2, m2), Eq. (8) of MP2011.
    pub fn beta(&self, r1: f64, r2: f64, m1: f64, m2: f64) -> f64 {
        let effective_mass = m1 * m2 / (m1 + m2);
        1.5 * self.dissipative_constant * (self.elastic_constant(r1, r2) / effective_mass).powf(0.4)
    }
}

/// A smooth sphere: radius in m, mass in kg.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Sphere {
    /// Radius R in m.
    pub radius: f64,
    /// Mass m in kg.
    pub mass: f64,
}

impl Sphere {
    /// A sphere of the given radius (m) and mass (kg), both finite and > 0.
    pub fn new(radius: f64, mass: f64) -> Result<Self> {
        Ok(Sphere {
            radius: require_positive("radius", radius)?,
            mass: require_positive("mass", mass)?,
        })
    }

    /// A homogeneous sphere of the given radius (m) and density (kg/m³): m = (4/3) π R³ density.
    pub fn from_density(radius: f64, density: f64) -> Result<Self> {
        let radius = require_positive("radius", radius)?;
        let density = require_positive("density", density)?;
        Sphere::new(radius, 4.0 / 3.0 * PI * radius.powi(3) * density)
    }

    /// A homogeneous sphere of the given radius (m) made of `material`.
    pub fn of_material(radius: f64, material: &Material) -> Result<Self> {
        Sphere::from_density(radius, material.density)
    }

    /// Checks that radius and mass are finite and > 0.
    pub fn validate(&self) -> Result<()> {
        Sphere::new(self.radius, self.mass).map(|_| ())
    }
}

/// Two spheres of one material in contact: the parameters of Eq. (1)–(3) of MP2011
/// and Eqs. (16)–(18) of SP2008, all in SI.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactPair {
    material: Material,
    spheres: [Sphere; 2],
}

impl ContactPair {
    /// A pair of (validated) spheres of the (validated) `material`.
    pub fn new(material: &Material, first: Sphere, second: Sphere) -> Result<Self> {
        material.validate()?;
        first.validate()?;
        second.validate()?;
        Ok(ContactPair {
            material: material.clone(),
            spheres: [first, second],
        })
    }

    /// The material of both spheres.
    pub fn material(&self) -> &Material {
        &self.material
    }

    /// The two spheres.
    pub fn spheres(&self) -> [Sphere; 2] {
        self.spheres
    }

    /// Effective mass m_eff = m1 m2 / (m1 + m2) in kg, below Eq. (1) of MP2011.
    pub fn effective_mass(&self) -> f64 {
        let [a, b] = self.spheres;
        a.mass * b.mass / (a.mass + b.mass)
    }

    /// Effective radius R_eff = R1 R2 / (R1 + R2) in m, below Eq. (3) of MP2011.
    pub fn effective_radius(&self) -> f64 {
        let [a, b] = self.spheres;
        a.radius * b.radius / (a.radius + b.radius)
    }

    /// Elastic constant ρ = 2 Y √R_eff / (3 (1 − ν²)) in N/m^(3/2),
    /// Eq. (3) of MP2011 / Eq. (14) of SP2008.
    pub fn elastic_constant(&self) -> f64 {
        2.0 * self.material.plane_strain_modulus() * self.effective_radius().sqrt() / 3.0
    }

    /// k = ρ / m_eff in m^(-1/2) s^(-2), Eq. (18) of SP2008.
    pub fn k(&self) -> f64 {
        self.elastic_constant() / self.effective_mass()
    }

    /// The dissipative constant A in s, or an error naming `dissipative_constant`.
    pub fn dissipative_constant(&self) -> Result<f64> {
        self.material.required_dissipative_constant()
    }

    /// γ = (3/2) ρ A / m_eff in m^(-1/2) s^(-1), Eq. (18) of SP2008.
    pub fn gamma(&self) -> Result<f64> {
        Ok(1.5 * self.dissipative_constant()? * self.k())
    }

    /// β = (3/2) A (ρ/m_eff)^(2/5) in (s/m)^(1/5), Eq. (8) of MP2011
    /// (equal to γ k^(-3/5), SP2008 below Eq. (23)).
    pub fn beta(&self) -> Result<f64> {
        Ok(1.5 * self.dissipative_constant()? * self.k().powf(0.4))
    }

    /// β of Eq. (8) of MP2011 expressed in `units`.
    pub fn beta_in(&self, units: UnitSystem) -> Result<f64> {
        Ok(units.beta_from_si(self.beta()?))
    }

    /// Scaled impact speed v* = β^(1/2) v^(1/10) for an impact speed `v` in m/s,
    /// Eq. (7) of MP2011.
    pub fn vstar(&self, v: f64) -> Result<f64> {
        vstar(self.beta()?, v)
    }

    /// Impact speed in m/s for the scaled speed `vstar`: v = v*^10 / β^5 (MP2011, below Fig. 1).
    pub fn speed_from_vstar(&self, vstar: f64) -> Result<f64> {
        speed_from_vstar(self.beta()?, vstar)
    }

    /// Unit of time (s) at impact speed `v` (m/s): (ρ/m_eff)^(-2/5) v^(-1/5),
    /// so that t = τ · time_scale (MP2011 below Eq. (9)).
    pub fn time_scale(&self, v: f64) -> Result<f64> {
        let v = require_positive("v", v)?;
        Ok(self.k().powf(-0.4) * v.powf(-0.2))
    }

    /// Unit of compression (m) at impact speed `v` (m/s): (ρ/m_eff)^(-2/5) v^(4/5),
    /// so that ξ = x · length_scale (MP2011 below Eq. (9)).
    pub fn length_scale(&self, v: f64) -> Result<f64> {
        let v = require_non_negative("v", v)?;
        Ok(self.k().powf(-0.4) * v.powf(0.8))
    }
}

/// Scaled impact speed v* = β^(1/2) v^(1/10), Eq. (7) of MP2011.
///
/// `beta` and `v` must be in the same unit system; requires β > 0 and v >= 0, both finite.
pub fn vstar(beta: f64, v: f64) -> Result<f64> {
    let beta = require_positive("beta", beta)?;
    let v = require_non_negative("v", v)?;
    Ok(beta.sqrt() * v.powf(0.1))
}

/// Impact speed v = v*^10 / β^5, the inverse of [`vstar`] (MP2011, below Fig. 1).
///
/// Requires β > 0 and v* >= 0, both finite; the speed is in the unit system of β.
pub fn speed_from_vstar(beta: f64, vstar: f64) -> Result<f64> {
    let beta = require_positive("beta", beta)?;
    let vstar = require_non_negative("vstar", vstar)?;
    Ok(vstar.powi(10) / beta.powi(5))
}

/// Source text for values that are typical handbook numbers rather than one measurement.
const HANDBOOK: &str = "typical handbook value (e.g. CRC Handbook of Chemistry and Physics)";

/// One row of the built-in table: (name, Y in Pa, ν, density in kg/m³, source).
type TableRow = (&'static str, f64, f64, f64, &'static str);

/// The built-in table. No entry has a dissipative constant A: none is taken from a
/// published measurement here, so A must be supplied by the user.
const TABLE: [TableRow; 4] = [
    ("steel", 200e9, 0.30, 7850.0, HANDBOOK),
    ("soda-lime-glass", 72e9, 0.23, 2500.0, HANDBOOK),
    ("aluminium", 70e9, 0.33, 2700.0, HANDBOOK),
    (
        "ice",
        9.3e9,
        0.33,
        917.0,
        "polycrystalline ice Ih near 0 degC: typical literature value \
         (e.g. Petrenko & Whitworth, Physics of Ice, Oxford University Press, 1999)",
    ),
];

fn material_from_row(&(name, young, poisson, density, source): &TableRow) -> Material {
    Material {
        name: name.to_string(),
        young_modulus: young,
        poisson_ratio: poisson,
        density,
        dissipative_constant: None,
        source: source.to_string(),
    }
}

/// The built-in materials (SI, dissipative constant unknown for all of them).
pub fn builtin_materials() -> Vec<Material> {
    TABLE.iter().map(material_from_row).collect()
}

/// Names of the built-in materials, in table order.
pub fn builtin_material_names() -> Vec<&'static str> {
    TABLE.iter().map(|row| row.0).collect()
}

/// The built-in material called `name` (case-insensitive; `_` and blanks count as `-`).
pub fn material_by_name(name: &str) -> Result<Material> {
    let wanted = name.trim().to_ascii_lowercase().replace(['_', ' '], "-");
    builtin_materials()
        .into_iter()
        .find(|material| material.name == wanted)
        .ok_or_else(|| {
            Error::parse(
                "material",
                format!(
                    "unknown material `{name}`; known materials: {}",
                    builtin_material_names().join(", ")
                ),
            )
        })
}
