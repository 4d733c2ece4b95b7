//! `[collision]`: the law and its keys, each key refused for the laws that do not read it;
//! the stochastic law only with an engine of per-particle baths.

use super::material::{species_betas, viscoelastic_beta};
use super::{Species, SCALE};
use crate::description::{Distribution, LawKind, RestitutionValue, RunDescription};
use crate::engines::Abilities;
use crate::error::{Error, Result};
use restitution::{Criterion, FormName};
use std::path::PathBuf;

/// The collision law, checked (built by [`crate::law::build`]).
#[derive(Debug, Clone, PartialEq)]
pub enum LawSpec {
    Constant(f64),
    /// A constant restitution per pair of species: kinds (radius, mass) in the order of
    /// `system.species` and the symmetric matrix.
    ConstantPairs {
        kinds: Vec<(f64, f64)>,
        matrix: Vec<Vec<f64>>,
    },
    Dashpot {
        damping_ratio: f64,
        criterion: Criterion,
    },
    Viscoelastic {
        beta: f64,
        form: FormName,
    },
    /// A viscoelastic mixture: kinds (radius, mass) in the order of `system.species` and
    /// beta per pair from the species' materials.
    ViscoelasticPairs {
        kinds: Vec<(f64, f64)>,
        betas: Vec<Vec<f64>>,
        form: FormName,
    },
    Stochastic {
        modes: u32,
        distribution: StochasticTable,
        bath_temperature: f64,
    },
}

/// Where a stochastic law draws eps^2 from.
#[derive(Debug, Clone, PartialEq)]
pub enum StochasticTable {
    Glauber,
    Tabulated(PathBuf),
}

/// `[collision]` without the TC model: the law and its keys.
pub(super) fn law_spec(
    description: &RunDescription,
    species: &[Species],
    engine: &Abilities,
) -> Result<LawSpec> {
    let c = &description.collision;
    let need =
        |key: &str, x: Option<f64>| x.ok_or_else(|| Error::input(key, "missing for this law"));
    // Every key belongs to one law: a key of another law would be recorded and ignored.
    let keys = [
        (
            "collision.restitution",
            c.restitution.is_some(),
            LawKind::Constant,
        ),
        (
            "collision.damping_ratio",
            c.damping_ratio.is_some(),
            LawKind::Dashpot,
        ),
        (
            "collision.criterion",
            c.criterion.is_some(),
            LawKind::Dashpot,
        ),
        ("collision.beta", c.beta.is_some(), LawKind::Viscoelastic),
        ("collision.form", c.form.is_some(), LawKind::Viscoelastic),
        ("collision.young", c.young.is_some(), LawKind::Viscoelastic),
        (
            "collision.poisson",
            c.poisson.is_some(),
            LawKind::Viscoelastic,
        ),
        (
            "collision.dissipative_constant",
            c.dissipative_constant.is_some(),
            LawKind::Viscoelastic,
        ),
        (
            "collision.distribution",
            c.distribution.is_some(),
            LawKind::Stochastic,
        ),
        ("collision.modes", c.modes.is_some(), LawKind::Stochastic),
        (
            "collision.bath_temperature",
            c.bath_temperature.is_some(),
            LawKind::Stochastic,
        ),
        ("collision.table", c.table.is_some(), LawKind::Stochastic),
    ];
    if let Some((key, _, owner)) = keys
        .iter()
        .find(|(_, given, owner)| *given && *owner != c.law)
    {
        return Err(Error::input(
            *key,
            format!(
                "only for law = \"{}\" (this run has law = \"{}\")",
                owner.name(),
                c.law.name()
            ),
        ));
    }
    if c.law != LawKind::Viscoelastic {
        for (i, x) in description.system.species.iter().flatten().enumerate() {
            if x.has_material() {
                return Err(Error::input(
                    format!("system.species[{i}].young"),
                    format!(
                        "a species' material (young, poisson, dissipative_constant) is for \
                         law = \"viscoelastic\" (this run has law = \"{}\")",
                        c.law.name()
                    ),
                ));
            }
        }
    }
    Ok(match c.law {
        LawKind::Constant => {
            let tc = c.tc.is_some_and(|t| t > 0.0);
            let sticking = |key: &str, eps: f64| {
                if eps == 0.0 && engine.collapse && !tc {
                    return Err(Error::out_of_range(
                        key,
                        eps,
                        "0 < restitution <= 1 in an event-driven run (at 0 the spheres stick: \
                         they collide again at once, forever, and time stops); or set \
                         collision.tc, the TC model, or use engine = \"dsmc\"",
                    ));
                }
                Ok(())
            };
            match &c.restitution {
                None => {
                    return Err(Error::input(
                        "collision.restitution",
                        "missing for this law",
                    ))
                }
                Some(RestitutionValue::One(eps)) => {
                    sticking("collision.restitution", *eps)?;
                    LawSpec::Constant(*eps)
                }
                Some(RestitutionValue::PerPair(matrix)) => {
                    let kinds = restitution_matrix(description, matrix)?;
                    for (i, row) in matrix.iter().enumerate() {
                        for (j, &eps) in row.iter().enumerate() {
                            sticking(&format!("collision.restitution[{i}][{j}]"), eps)?;
                        }
                    }
                    LawSpec::ConstantPairs {
                        kinds,
                        matrix: matrix.clone(),
                    }
                }
            }
        }
        LawKind::Dashpot => LawSpec::Dashpot {
            damping_ratio: need("collision.damping_ratio", c.damping_ratio)?,
            criterion: c.criterion.unwrap_or(Criterion::Improved),
        },
        LawKind::Viscoelastic => {
            let form = c.form.unwrap_or(FormName::Fast(Criterion::Improved));
            match species_betas(description)? {
                Some((kinds, betas)) => LawSpec::ViscoelasticPairs { kinds, betas, form },
                None => LawSpec::Viscoelastic {
                    beta: viscoelastic_beta(description, &species[0])?,
                    form,
                },
            }
        }
        LawKind::Stochastic => stochastic_spec(description, engine)?,
    })
}

/// Giese's stochastic law: event-driven only, `modes`, `distribution` and, tabulated,
/// `table`.
fn stochastic_spec(description: &RunDescription, engine: &Abilities) -> Result<LawSpec> {
    let c = &description.collision;
    if !engine.baths {
        return Err(Error::input(
            "run.engine",
            format!(
                "law = \"stochastic\" runs with engine = {} (Giese's ED + Monte Carlo)",
                crate::engines::kinds_that(|a| a.baths)
            ),
        ));
    }
    let bath_temperature = c.bath_temperature.unwrap_or(0.0);
    // 0 (cold baths) or within the scale of a temperature (the baths feed their energy to
    // the translation: 1e300 would overflow v^2).
    if bath_temperature != 0.0 && !(SCALE.0..=SCALE.1).contains(&bath_temperature) {
        return Err(Error::out_of_range(
            "collision.bath_temperature",
            crate::output::number(bath_temperature),
            "0, or 1e-30 <= value <= 1e30",
        ));
    }
    let modes = c
        .modes
        .ok_or_else(|| Error::input("collision.modes", "missing for law = \"stochastic\""))?;
    let distribution = match c.distribution.unwrap_or(Distribution::Glauber) {
        Distribution::Glauber => {
            if c.table.is_some() {
                return Err(Error::input(
                    "collision.table",
                    "only for distribution = \"tabulated\"",
                ));
            }
            StochasticTable::Glauber
        }
        Distribution::Tabulated => {
            let path = c.table.as_deref().ok_or_else(|| {
                Error::input("collision.table", "missing: a table from `haff rods table`")
            })?;
            StochasticTable::Tabulated(PathBuf::from(path))
        }
    };
    Ok(LawSpec::Stochastic {
        modes,
        distribution,
        bath_temperature,
    })
}

/// Checks a matrix `collision.restitution` against `system.species`: one row and column
/// per species, values in [0, 1], symmetric; returns the kinds (radius, mass).
fn restitution_matrix(
    description: &RunDescription,
    matrix: &[Vec<f64>],
) -> Result<Vec<(f64, f64)>> {
    let Some(species) = &description.system.species else {
        return Err(Error::input(
            "collision.restitution",
            "a matrix needs system.species (one row per species); give one number otherwise",
        ));
    };
    let s = species.len();
    if matrix.len() != s || matrix.iter().any(|row| row.len() != s) {
        return Err(Error::input(
            "collision.restitution",
            format!("a {s} x {s} matrix: one row and column per species of system.species"),
        ));
    }
    for (i, row) in matrix.iter().enumerate() {
        for (j, &eps) in row.iter().enumerate() {
            let key = format!("collision.restitution[{i}][{j}]");
            if !(eps.is_finite() && (0.0..=1.0).contains(&eps)) {
                return Err(Error::out_of_range(&key, eps, "0 <= eps <= 1"));
            }
            if eps != matrix[j][i] {
                return Err(Error::out_of_range(
                    &key,
                    eps,
                    &format!(
                        "collision.restitution[{j}][{i}] = {} (symmetric)",
                        matrix[j][i]
                    ),
                ));
            }
        }
    }
    Ok(species.iter().map(|x| (0.5 * x.diameter, x.mass)).collect())
}
