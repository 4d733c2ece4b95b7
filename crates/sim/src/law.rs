//! Collision laws built from their checked description.

use crate::error::{Error, Result};
use crate::validate::{LawSpec, StochasticTable};
use restitution::{Constant, Dashpot, Glauber, Restitution, Viscoelastic};
use std::path::Path;

/// The law of `spec`. Errors name the key of the run file that set the failing value.
pub fn build(spec: &LawSpec) -> Result<Box<dyn Restitution>> {
    let input = |key: &'static str| move |e: restitution::Error| Error::law(key, e);
    Ok(match spec {
        LawSpec::Constant(eps) => {
            Box::new(Constant::new(*eps).map_err(input("collision.restitution"))?)
        }
        LawSpec::Dashpot {
            damping_ratio,
            criterion,
        } => Box::new(
            Dashpot::new(*damping_ratio, (*criterion).into(), None)
                .map_err(input("collision.damping_ratio"))?,
        ),
        LawSpec::Viscoelastic { beta, form } => {
            let form = form.build().map_err(input("collision.form"))?;
            Box::new(Viscoelastic::new(*beta, form).map_err(input("collision.beta"))?)
        }
        LawSpec::Stochastic {
            modes,
            distribution,
            ..
        } => match distribution {
            StochasticTable::Glauber => {
                Box::new(Glauber::new(*modes).map_err(input("collision.modes"))?)
            }
            StochasticTable::Tabulated(path) => tabulated(path, *modes, "collision.table")?,
        },
    })
}

/// The tabulated stochastic law from a table written by `haff rods table`, for particles
/// with `modes` internal modes; errors name `key`.
pub fn tabulated(path: &Path, modes: u32, key: &str) -> Result<Box<dyn Restitution>> {
    let fail = |e: String| Error::input(key, format!("{}: {e}", path.display()));
    let text = std::fs::read_to_string(path).map_err(|e| fail(e.to_string()))?;
    let table: rods::stochastic::Table =
        serde_json::from_str(&text).map_err(|e| fail(e.to_string()))?;
    Ok(Box::new(table.law(modes).map_err(|e| fail(e.to_string()))?))
}
