//! `[field]`: gravity, a uniform acceleration of every sphere along axes closed by walls
//! (along a periodic axis a gas would fall forever: refused), and the resting rule's
//! height (docs/walls.md).

use super::{Species, WallSpec};
use crate::description::{EngineKind, RunDescription, AXIS_NAMES};
use crate::engines::{engine_named, kinds_that, Abilities};
use crate::error::{Error, Result};

/// Checked gravity.
#[derive(Debug, Clone, PartialEq)]
pub struct GravitySpec {
    /// One component per dimension, non-zero only along closed axes.
    pub acceleration: Vec<f64>,
    /// A floor sends spheres off at least as fast as a bounce this high needs.
    pub rest_height: f64,
}

/// The resting rule's height by default, in smallest diameters.
pub const REST_HEIGHT: f64 = 1e-4;

pub(crate) fn gravity_spec(
    description: &RunDescription,
    engine: &Abilities,
    walls: &[WallSpec],
    species: &[Species],
) -> Result<Option<GravitySpec>> {
    let Some(field) = &description.field else {
        return Ok(None);
    };
    if !engine.walls {
        return Err(Error::input(
            "field",
            format!(
                "{} has no gravity yet; gravity runs in run.engine = {}",
                engine_named(description),
                kinds_that(|a| a.walls)
            ),
        ));
    }
    let dimension = description.system.dimension as usize;
    let g = &field.gravity;
    if g.len() != dimension {
        return Err(Error::out_of_range(
            "field.gravity",
            format!("{} components", g.len()),
            &format!("{dimension} components (one per axis)"),
        ));
    }
    for (k, &x) in g.iter().enumerate() {
        if !(x == 0.0 || (x.is_finite() && (1e-30..=1e30).contains(&x.abs()))) {
            return Err(Error::out_of_range(
                &format!("field.gravity[{k}]"),
                crate::output::number(x),
                "0 or 1e-30 <= |g| <= 1e30",
            ));
        }
        if x != 0.0 && !walls.iter().any(|w| w.axis == k) {
            let closed: Vec<&str> = (0..dimension)
                .filter(|&j| walls.iter().any(|w| w.axis == j))
                .map(|j| AXIS_NAMES[j])
                .collect();
            return Err(Error::input(
                format!("field.gravity[{k}]"),
                format!(
                    "gravity along the periodic axis {} (a gas would fall forever); allowed: \
                     components along axes closed by [[wall]] ({})",
                    AXIS_NAMES[k],
                    if closed.is_empty() {
                        "none here".to_string()
                    } else {
                        closed.join(", ")
                    }
                ),
            ));
        }
    }
    let smallest = species
        .iter()
        .map(|s| s.diameter)
        .fold(f64::INFINITY, f64::min);
    if field.rest_height.is_some() && description.run.engine == EngineKind::SoftSphere {
        return Err(Error::input(
            "field.rest_height",
            "run.engine = \"soft-sphere\": soft contacts come to rest by themselves; leave \
             rest_height out",
        ));
    }
    let rest_height = field.rest_height.unwrap_or(REST_HEIGHT * smallest);
    if !(rest_height.is_finite() && (0.0..=smallest).contains(&rest_height)) {
        return Err(Error::out_of_range(
            "field.rest_height",
            crate::output::number(rest_height),
            &format!("0 ..= {} (the smallest diameter)", smallest),
        ));
    }
    if g.iter().all(|&x| x == 0.0) {
        return Ok(None);
    }
    if description.driving.is_some() {
        return Err(Error::input(
            "field.gravity",
            "gravity with [driving] is not built; allowed: one of them",
        ));
    }
    Ok(Some(GravitySpec {
        acceleration: g.clone(),
        rest_height,
    }))
}
