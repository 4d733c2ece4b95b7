//! The viscoelastic material of `[collision]`: a built-in one by name
//! (`material = "ice"`, SI, as `haff cor eps --material` takes it) or `young`, `poisson`
//! and `dissipative_constant` in the units of the system; beta per pair from it.

use super::Species;
use crate::description::RunDescription;
use crate::error::{Error, Result};
use gas::soft::contact::ViscoelasticMaterial;

/// Relative tolerance between a given mass and the one a material's density gives: the
/// masses of a run file are decimals, printed to about nine digits or more.
const MASS_TOLERANCE: f64 = 1e-6;

/// `description` with a built-in `collision.material` resolved: `young` and `poisson` from
/// the table unless given (explicit keys win, as in `haff cor eps`), and `system.mass`
/// from the density, m = density pi d^3 / 6 (SI: diameter in m, mass in kg). A given mass
/// (or species mass) must match the density. Spheres only: dimension 3.
pub(crate) fn resolve_named_material(description: &RunDescription) -> Result<RunDescription> {
    let mut resolved = description.clone();
    let Some(name) = description.collision.material.as_deref() else {
        return Ok(resolved);
    };
    let table = restitution::material::material_by_name(name)
        .map_err(|e| Error::input("collision.material", e))?;
    if description.collision.law != crate::description::LawKind::Viscoelastic {
        return Err(Error::input(
            "collision.material",
            "a material is for law = \"viscoelastic\"",
        ));
    }
    let s = &description.system;
    if s.dimension != 3 {
        return Err(Error::input(
            "collision.material",
            format!(
                "a material's density gives the masses of spheres: system.dimension = 3 \
                 (is {}); in {}D give young, poisson, dissipative_constant and system.mass",
                s.dimension, s.dimension
            ),
        ));
    }
    let c = &mut resolved.collision;
    c.young.get_or_insert(table.young_modulus);
    c.poisson.get_or_insert(table.poisson_ratio);
    let mass_of = |d: f64| table.density * std::f64::consts::PI * d * d * d / 6.0;
    let mismatch = |key: String, given: f64, d: f64| {
        Error::input(
            key,
            format!(
                "= {given}, but {} (density {} kg/m^3) gives {} for diameter {d} (SI units); \
                 leave the mass out or match it",
                table.name,
                table.density,
                mass_of(d)
            ),
        )
    };
    match &s.species {
        None => {
            let d = s.diameter.unwrap_or(1.0);
            match s.mass {
                None => resolved.system.mass = Some(mass_of(d)),
                Some(m) if (m / mass_of(d) - 1.0).abs() > MASS_TOLERANCE => {
                    return Err(mismatch("system.mass".into(), m, d))
                }
                Some(_) => {}
            }
        }
        Some(species) => {
            for (i, sp) in species.iter().enumerate() {
                if (sp.mass / mass_of(sp.diameter) - 1.0).abs() > MASS_TOLERANCE {
                    return Err(mismatch(
                        format!("system.species[{i}].mass"),
                        sp.mass,
                        sp.diameter,
                    ));
                }
            }
        }
    }
    Ok(resolved)
}

/// The material of `[collision]` (`young`, `poisson`, `dissipative_constant`), if any of
/// its keys is given: then all three, in range.
pub(crate) fn material(description: &RunDescription) -> Result<Option<ViscoelasticMaterial>> {
    let c = &description.collision;
    let keys = [
        ("collision.young", c.young),
        ("collision.poisson", c.poisson),
        ("collision.dissipative_constant", c.dissipative_constant),
    ];
    if keys.iter().all(|k| k.1.is_none()) {
        return Ok(None);
    }
    if let Some((key, _)) = keys.iter().find(|k| k.1.is_none()) {
        return Err(Error::input(
            *key,
            "missing: a material needs young, poisson and dissipative_constant",
        ));
    }
    let (young, poisson, a) = (keys[0].1.unwrap(), keys[1].1.unwrap(), keys[2].1.unwrap());
    ViscoelasticMaterial::new(young, poisson, a)
        .map(Some)
        .map_err(|e| Error::input(format!("collision.{}", parameter(&e)), e))
}

/// The material parameter (`young`, `poisson`, `dissipative_constant`) a material's error
/// names.
fn parameter(error: &gas::Error) -> &str {
    match error {
        gas::Error::OutOfRange { name, .. } => name,
        _ => "young",
    }
}

/// beta of the viscoelastic law of one kind of spheres (a mixture with a material takes
/// [`species_betas`]): `collision.beta`, or from the material and the spheres, beta = (3/2) A (rho / m_eff)^(2/5) (Eq. (8) of Müller & Pöschel 2011).
pub(crate) fn viscoelastic_beta(description: &RunDescription, kind: &Species) -> Result<f64> {
    let c = &description.collision;
    match (c.beta, material(description)?) {
        (Some(beta), None) => Ok(beta),
        (None, Some(m)) => {
            let (r, mass) = (kind.radius(), kind.mass);
            Ok(m.beta(r, r, mass, mass))
        }
        (Some(_), Some(_)) => Err(Error::input(
            "collision.beta",
            "give beta or the material (young, poisson, dissipative_constant), not both",
        )),
        (None, None) => Err(Error::input(
            "collision.beta",
            "missing: give beta, or young, poisson and dissipative_constant",
        )),
    }
}

/// Kinds (radius, mass) in the order of `system.species`, and beta per pair of them.
pub(crate) type PairBetas = (Vec<(f64, f64)>, Vec<Vec<f64>>);

/// A viscoelastic mixture with materials: each species' material (its own `young`,
/// `poisson`, `dissipative_constant`, a key left out taken from `[collision]`) and beta
/// per pair of species, from the pair's effective radius and mass and, for unlike
/// materials, the combined modulus and compliance-weighted dissipative constant
/// ([`ViscoelasticMaterial::pair_beta`]). `None` without species, or with one
/// `collision.beta` for every pair and no species material.
pub(crate) fn species_betas(description: &RunDescription) -> Result<Option<PairBetas>> {
    let c = &description.collision;
    let Some(species) = &description.system.species else {
        return Ok(None);
    };
    let materials = match species_materials(description)? {
        Some(m) => m,
        None => match material(description)? {
            Some(m) if c.beta.is_none() => vec![m; species.len()],
            _ => return Ok(None),
        },
    };
    let kinds: Vec<(f64, f64)> = species.iter().map(|x| (0.5 * x.diameter, x.mass)).collect();
    let betas = kinds
        .iter()
        .zip(&materials)
        .map(|(&(r1, m1), a)| {
            kinds
                .iter()
                .zip(&materials)
                .map(|(&(r2, m2), b)| a.pair_beta(b, r1, r2, m1, m2))
                .collect()
        })
        .collect();
    Ok(Some((kinds, betas)))
}

/// The material of each species if any species names a key of its own: a key left out is
/// taken from `[collision]`; every species must end with all three. Errors name
/// `system.species[i].<key>`.
pub(crate) fn species_materials(
    description: &RunDescription,
) -> Result<Option<Vec<ViscoelasticMaterial>>> {
    let c = &description.collision;
    let Some(species) = &description.system.species else {
        return Ok(None);
    };
    if !species.iter().any(|x| x.has_material()) {
        return Ok(None);
    }
    if c.beta.is_some() {
        return Err(Error::input(
            "collision.beta",
            "give beta or the species' materials (system.species[i].young, poisson, \
             dissipative_constant), not both",
        ));
    }
    species
        .iter()
        .enumerate()
        .map(|(i, x)| {
            let keys = [
                ("young", x.young.or(c.young)),
                ("poisson", x.poisson.or(c.poisson)),
                (
                    "dissipative_constant",
                    x.dissipative_constant.or(c.dissipative_constant),
                ),
            ];
            if let Some((key, _)) = keys.iter().find(|k| k.1.is_none()) {
                return Err(Error::input(
                    format!("system.species[{i}].{key}"),
                    format!(
                        "missing: a species' material needs young, poisson and \
                         dissipative_constant (its own or collision.{key} for every species)"
                    ),
                ));
            }
            let [y, nu, a] = keys.map(|k| k.1.unwrap());
            ViscoelasticMaterial::new(y, nu, a)
                .map_err(|e| Error::input(format!("system.species[{i}].{}", parameter(&e)), e))
        })
        .collect::<Result<Vec<_>>>()
        .map(Some)
}
