//! Rough particles (`collision.tangential_restitution`, `collision.friction`,
//! `system.inertia`, `system.species[i].inertia`, `system.rotational_temperature`): the
//! tangential rule of `restitution::rough` and the rotation it couples to translation.
//! Refused: beta outside [-1, 1], a friction that is negative or not finite or given for
//! smooth spheres, an inertia factor outside (0, 2/3] (disks (0, 1/2]), rotation in 1D,
//! engines without rotation, a stochastic law (its baths take normal energy only).

use super::Species;
use crate::description::{LawKind, RunDescription};
use crate::engines::{kind_name, kinds_that, Abilities};
use crate::error::{Error, Result};

/// The rough particles of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct RoughSpec {
    /// Tangential restitution beta > -1.
    pub beta: f64,
    /// Walton's friction coefficient, if given.
    pub friction: Option<f64>,
    /// Inertia factor of each species.
    pub inertia: Vec<f64>,
    /// The rotational temperature of the start.
    pub temperature: f64,
}

impl RoughSpec {
    /// The tangential rule.
    pub fn tangential(&self) -> restitution::rough::Tangential {
        restitution::rough::Tangential::new(self.beta, self.friction)
            .expect("checked by validation")
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
    let beta = c.tangential_restitution;
    if let Some(b) = beta {
        if !(b.is_finite() && (-1.0..=1.0).contains(&b)) {
            return Err(Error::out_of_range(
                "collision.tangential_restitution",
                crate::output::number(b),
                "-1 <= beta <= 1 (-1: smooth)",
            ));
        }
    }
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
    let Some(beta) = beta.filter(|&b| b > -1.0) else {
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
    let temperature = s.rotational_temperature.unwrap_or(s.temperature);
    if !(temperature == 0.0 || (1e-30..=1e30).contains(&temperature)) {
        return Err(Error::out_of_range(
            "system.rotational_temperature",
            crate::output::number(temperature),
            "0 or 1e-30 <= value <= 1e30",
        ));
    }
    let default = s.inertia.unwrap_or(if dimension == 2 { 0.5 } else { 0.4 });
    let inertia = match &s.species {
        None => vec![default; species.len()],
        Some(list) => list.iter().map(|x| x.inertia.unwrap_or(default)).collect(),
    };
    Ok(Some(RoughSpec {
        beta,
        friction: c.friction,
        inertia,
        temperature,
    }))
}
