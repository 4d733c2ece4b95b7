//! Rough particles (`collision.tangential_restitution`, `collision.friction`,
//! `system.inertia`, `system.species[i].inertia`, `system.rotational_temperature`): the
//! tangential rule of `restitution::rough` and the rotation it couples to translation.
//! Refused: beta outside [-1, 1], a friction that is negative or not finite or given for
//! smooth spheres, an inertia factor outside (0, 2/3] (disks (0, 1/2]), rotation in 1D,
//! engines without rotation, a stochastic law (its baths take normal energy only).
//!
//! Soft-sphere MD has no tangential restitution to give: its contacts' tangential force
//! (`gas::soft::tangential`) yields one; `collision.friction` alone makes its spheres
//! rough, and `collision.tangential_restitution` is refused for it.

use super::Species;
use crate::description::{LawKind, RestitutionValue, RunDescription};
use crate::engines::{kind_name, kinds_that, Abilities};
use crate::error::{Error, Result};

/// The rough particles of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct RoughSpec {
    /// Tangential restitution beta of each pair of species (one row and column per
    /// species; some entry > -1); empty for soft-sphere MD, whose contact force yields it.
    pub betas: Vec<Vec<f64>>,
    /// Whether the run file gave a matrix (else one beta for all pairs).
    pub per_pair: bool,
    /// Walton's friction coefficient, if given.
    pub friction: Option<f64>,
    /// Inertia factor of each species.
    pub inertia: Vec<f64>,
    /// The rotational temperature of the start.
    pub temperature: f64,
}

impl RoughSpec {
    /// The tangential rule of species a and b.
    pub fn tangential(&self, a: usize, b: usize) -> restitution::rough::Tangential {
        // beta = -1 with friction is refused by the rule itself: a smooth pair of a rough
        // mixture takes no friction.
        let beta = self.betas[a][b];
        let friction = self.friction.filter(|_| beta > -1.0);
        restitution::rough::Tangential::new(beta, friction).expect("checked by validation")
    }

    /// The beta of one kind of particle with itself (`rough_theory`).
    pub fn beta(&self) -> f64 {
        self.betas[0][0]
    }
}

/// The checked rough particles of a run, if any (beta given and > -1).
pub(crate) fn rough_spec(
    description: &RunDescription,
    engine: &Abilities,
    species: &[Species],
) -> Result<Option<RoughSpec>> {
    let c = &description.collision;
    let s = &description.system;
    let dimension = s.dimension as usize;
    let betas = betas(description, species.len())?;
    if let Some(mu) = c.friction {
        if !(mu.is_finite() && (0.0..=1e30).contains(&mu)) {
            return Err(Error::out_of_range(
                "collision.friction",
                crate::output::number(mu),
                "a finite friction coefficient 0 <= mu <= 1e30",
            ));
        }
    }
    let largest = gas::rotation::largest_inertia(dimension);
    let inertia_keys = std::iter::once(("system.inertia".to_string(), s.inertia)).chain(
        s.species
            .iter()
            .flatten()
            .enumerate()
            .map(|(i, x)| (format!("system.species[{i}].inertia"), x.inertia)),
    );
    for (key, q) in inertia_keys {
        if let Some(q) = q {
            if dimension < 2 {
                return Err(Error::input(&key, "rods (1D) do not rotate"));
            }
            if !(q > 0.0 && q <= largest) {
                let what = if dimension == 2 { "disks" } else { "spheres" };
                return Err(Error::out_of_range(
                    &key,
                    crate::output::number(q),
                    &format!(
                        "0 < inertia <= {} for {what}",
                        if dimension == 2 { "1/2" } else { "2/3" }
                    ),
                ));
            }
        }
    }
    if engine.contacts {
        return soft_contacts(description, betas.is_some(), species.len());
    }
    let rough = betas
        .as_ref()
        .is_some_and(|m| m.iter().flatten().any(|&b| b > -1.0));
    let Some(betas) = betas.filter(|_| rough) else {
        if let Some(mu) = c.friction {
            return Err(Error::out_of_range(
                "collision.friction",
                crate::output::number(mu),
                "none for smooth spheres: give collision.tangential_restitution > -1, the \
                 restitution of sticking contacts",
            ));
        }
        if s.rotational_temperature.is_some() {
            return Err(Error::input(
                "system.rotational_temperature",
                "smooth spheres do not exchange rotation: give collision.tangential_restitution > -1",
            ));
        }
        return Ok(None);
    };
    if dimension < 2 {
        return Err(Error::input(
            "collision.tangential_restitution",
            "rods (1D) do not rotate: rough particles are disks (2D) or spheres (3D)",
        ));
    }
    if !engine.rotation {
        return Err(Error::input(
            "collision.tangential_restitution",
            format!(
                "run.engine = \"{}\" has no rough particles yet; they run with run.engine = {}",
                kind_name(description.run.engine),
                kinds_that(|a| a.rotation)
            ),
        ));
    }
    if c.law == LawKind::Stochastic {
        return Err(Error::input(
            "collision.tangential_restitution",
            "the stochastic law's baths take the normal energy only: rough particles take \
             another law",
        ));
    }
    Ok(Some(RoughSpec {
        per_pair: matches!(c.tangential_restitution, Some(RestitutionValue::PerPair(_))),
        betas,
        friction: c.friction,
        inertia: inertia(description, species.len()),
        temperature: rotational_temperature(description)?,
    }))
}

/// Soft-sphere MD's rough spheres: `collision.friction` alone (the tangential restitution
/// follows from the contact force), `given_beta` refused.
fn soft_contacts(
    description: &RunDescription,
    given_beta: bool,
    species: usize,
) -> Result<Option<RoughSpec>> {
    let s = &description.system;
    if given_beta {
        return Err(Error::input(
            "collision.tangential_restitution",
            "run.engine = \"soft-sphere\" takes no tangential restitution: its contacts' \
             tangential force (Mindlin's spring, damped by dissipative_constant, cut at \
             collision.friction) yields it (docs/rough.md); give collision.friction alone",
        ));
    }
    let Some(friction) = description.collision.friction else {
        if s.rotational_temperature.is_some() {
            return Err(Error::input(
                "system.rotational_temperature",
                "smooth spheres do not exchange rotation: give collision.friction for \
                 run.engine = \"soft-sphere\"",
            ));
        }
        return Ok(None);
    };
    if s.dimension < 2 {
        return Err(Error::input(
            "collision.friction",
            "rods (1D) do not rotate: rough particles are disks (2D) or spheres (3D)",
        ));
    }
    Ok(Some(RoughSpec {
        betas: Vec::new(),
        per_pair: false,
        friction: Some(friction),
        inertia: inertia(description, species),
        temperature: rotational_temperature(description)?,
    }))
}

/// `system.rotational_temperature`, by default the temperature, checked.
fn rotational_temperature(description: &RunDescription) -> Result<f64> {
    let s = &description.system;
    let temperature = s.rotational_temperature.unwrap_or(s.temperature);
    if !(temperature == 0.0 || (1e-30..=1e30).contains(&temperature)) {
        return Err(Error::out_of_range(
            "system.rotational_temperature",
            crate::output::number(temperature),
            "0 or 1e-30 <= value <= 1e30",
        ));
    }
    Ok(temperature)
}

/// The inertia factor of each of `species` species: `system.species[i].inertia`, else
/// `system.inertia`, else a solid sphere's 2/5 (a disk's 1/2).
fn inertia(description: &RunDescription, species: usize) -> Vec<f64> {
    let s = &description.system;
    let default = s
        .inertia
        .unwrap_or(if s.dimension == 2 { 0.5 } else { 0.4 });
    match &s.species {
        None => vec![default; species],
        Some(list) => list.iter().map(|x| x.inertia.unwrap_or(default)).collect(),
    }
}

/// `collision.tangential_restitution` as a matrix over the `species` (None if absent):
/// each entry in [-1, 1]; a matrix needs `system.species`, one row and column per species,
/// symmetric.
fn betas(description: &RunDescription, species: usize) -> Result<Option<Vec<Vec<f64>>>> {
    let key = "collision.tangential_restitution";
    let in_range = |key: &str, b: f64| {
        if b.is_finite() && (-1.0..=1.0).contains(&b) {
            Ok(())
        } else {
            Err(Error::out_of_range(
                key,
                crate::output::number(b),
                "-1 <= beta <= 1 (-1: smooth)",
            ))
        }
    };
    match &description.collision.tangential_restitution {
        None => Ok(None),
        Some(RestitutionValue::One(b)) => {
            in_range(key, *b)?;
            Ok(Some(vec![vec![*b; species]; species]))
        }
        Some(RestitutionValue::PerPair(matrix)) => {
            if description.system.species.is_none() {
                return Err(Error::input(
                    key,
                    "a matrix needs system.species (one row per species); give one number otherwise",
                ));
            }
            if matrix.len() != species || matrix.iter().any(|row| row.len() != species) {
                return Err(Error::input(
                    key,
                    format!(
                        "a {species} x {species} matrix: one row and column per species of \
                         system.species"
                    ),
                ));
            }
            for (i, row) in matrix.iter().enumerate() {
                for (j, &b) in row.iter().enumerate() {
                    let entry = format!("{key}[{i}][{j}]");
                    in_range(&entry, b)?;
                    if b != matrix[j][i] {
                        return Err(Error::out_of_range(
                            &entry,
                            crate::output::number(b),
                            &format!("{key}[{j}][{i}] = {} (symmetric)", matrix[j][i]),
                        ));
                    }
                }
            }
            Ok(Some(matrix.clone()))
        }
    }
}
