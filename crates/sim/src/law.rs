//! Collision laws built from their checked description.

use crate::error::{Error, Result};
use crate::validate::{LawSpec, StochasticTable};
use restitution::pairwise::Pairwise;
use restitution::{Constant, Dashpot, FormName, Glauber, Restitution, Viscoelastic};
use std::path::Path;

/// The law of the run of `plan`: [`build`] of its `[collision]`, rough if
/// `collision.tangential_restitution` says so (`restitution::rough::Rough`).
pub fn of_plan(plan: &crate::Plan) -> Result<Box<dyn Restitution>> {
    let law = build(&plan.law, plan.max_impact_speed())?;
    let fail = |e| Error::law("collision.tangential_restitution", e);
    Ok(match &plan.rough {
        None => law,
        // Soft-sphere MD: the contact force makes the tangential half.
        Some(rough) if rough.betas.is_empty() => law,
        Some(rough) if !rough.per_pair => {
            Box::new(restitution::rough::Rough::new(law, rough.tangential(0, 0)).map_err(fail)?)
        }
        Some(rough) => {
            let s = plan.species.len();
            let rules = (0..s)
                .map(|a| (0..s).map(|b| rough.tangential(a, b)).collect())
                .collect();
            let pairs =
                restitution::rough::TangentialPairs::new(plan.kinds(), rules).map_err(fail)?;
            Box::new(restitution::rough::Rough::with_pairs(law, pairs).map_err(fail)?)
        }
    })
}

/// The law of `spec` for a run whose impact speeds stay below `max_speed`
/// ([`crate::Plan::max_impact_speed`]). Errors name the key of the run file that set the
/// failing value; an approximate viscoelastic form that such a speed would evaluate
/// beyond its validity (a Padé past a pole or outside [0, 1], a series beyond its radius
/// of convergence) is refused.
pub fn build(spec: &LawSpec, max_speed: f64) -> Result<Box<dyn Restitution>> {
    let input = |key: &'static str| move |e: restitution::Error| Error::law(key, e);
    Ok(match spec {
        LawSpec::Constant(eps) => {
            Box::new(Constant::new(*eps).map_err(input("collision.restitution"))?)
        }
        LawSpec::ConstantPairs { kinds, matrix } => {
            let laws = matrix
                .iter()
                .map(|row| {
                    row.iter()
                        .map(|&eps| -> Result<Box<dyn Restitution>> {
                            Ok(Box::new(
                                Constant::new(eps).map_err(input("collision.restitution"))?,
                            ))
                        })
                        .collect::<Result<Vec<_>>>()
                })
                .collect::<Result<Vec<_>>>()?;
            Box::new(Pairwise::new(kinds.clone(), laws).map_err(input("collision.restitution"))?)
        }
        LawSpec::Dashpot {
            damping_ratio,
            criterion,
        } => Box::new(
            Dashpot::new(*damping_ratio, (*criterion).into(), None)
                .map_err(input("collision.damping_ratio"))?,
        ),
        LawSpec::Viscoelastic { beta, form } => {
            viscoelastic(*beta, form, max_speed, "collision.beta", "collision.form")?
        }
        LawSpec::ViscoelasticPairs { kinds, betas, form } => {
            let laws = betas
                .iter()
                .enumerate()
                .map(|(i, row)| {
                    row.iter()
                        .map(|&beta| {
                            let key = format!("system.species[{i}].dissipative_constant");
                            viscoelastic(beta, form, max_speed, &key, "collision.form")
                        })
                        .collect::<Result<Vec<_>>>()
                })
                .collect::<Result<Vec<_>>>()?;
            Box::new(Pairwise::new(kinds.clone(), laws).map_err(input("system.species"))?)
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

/// The viscoelastic law of `beta` (set by `key`) in `form`, refused if a collision of the
/// run could reach beyond the form's validity or the exact law's range.
fn viscoelastic(
    beta: f64,
    form: &FormName,
    max_speed: f64,
    key: &str,
    form_key: &str,
) -> Result<Box<dyn Restitution>> {
    let form = form.build().map_err(|e| Error::law(form_key, e))?;
    let law = Viscoelastic::new(beta, form).map_err(|e| Error::law(key, e))?;
    let (validity, reach) = (law.form().validity(), law.vstar(max_speed));
    // Beyond the exact law's range eps is ~1e-20 (sticking spheres), and the
    // polynomials of a Padé form overflow f64 from v* ~ 1e50 on.
    if reach > restitution::exact::VSTAR_MAX {
        return Err(Error::out_of_range(
            key,
            crate::output::number(beta),
            &format!(
                "a beta with which no collision of this run exceeds v* = 1e6 (the range \
                 of the exact law); here v* can reach {reach:e} (all the initial kinetic \
                 energy in one pair): beta <= {:e}",
                beta * (restitution::exact::VSTAR_MAX / reach).powi(2)
            ),
        ));
    }
    if !validity.contains(reach) {
        return Err(Error::input(
            form_key,
            format!(
                "{} is {validity}, but a collision of this run can reach v* = {reach:.6} \
                 ({key} gives beta = {beta} with all the initial kinetic energy in one \
                 pair); allowed: a form valid there (exact, fast, or a Padé \
                 approximant such as pade:3/6)",
                law.form()
            ),
        ));
    }
    Ok(Box::new(law))
}

/// The tabulated stochastic law from a table written by `haff rods table`, for particles
/// with `modes` internal modes; errors name `key`.
pub fn tabulated(path: &Path, modes: u32, key: &str) -> Result<Box<dyn Restitution>> {
    let table = read_table(path, key)?;
    let law = table
        .law(modes)
        .map_err(|e| Error::input(key, format!("{}: {e}", path.display())))?;
    Ok(Box::new(law))
}

/// A table written by `haff rods table`; errors name `key` and the file.
pub fn read_table(path: &Path, key: &str) -> Result<rods::stochastic::Table> {
    let fail = |e: String| Error::input(key, format!("{}: {e}", path.display()));
    let text = std::fs::read_to_string(path).map_err(|e| fail(e.to_string()))?;
    serde_json::from_str(&text).map_err(|e| fail(e.to_string()))
}

/// The law of wall `index` (`[[wall]]`; errors name the wall's keys), for impacts up to
/// `max_speed` relative to the wall.
pub fn wall_law(spec: &LawSpec, max_speed: f64, index: usize) -> Result<Box<dyn Restitution>> {
    let key = |name: &str| format!("wall[{index}].{name}");
    Ok(match spec {
        LawSpec::Constant(eps) => {
            Box::new(Constant::new(*eps).map_err(|e| Error::law(&key("restitution"), e))?)
        }
        LawSpec::Dashpot {
            damping_ratio,
            criterion,
        } => Box::new(
            Dashpot::new(*damping_ratio, (*criterion).into(), None)
                .map_err(|e| Error::law(&key("damping_ratio"), e))?,
        ),
        LawSpec::Viscoelastic { beta, form } => {
            viscoelastic(*beta, form, max_speed, &key("beta"), &key("form"))?
        }
        other => {
            return Err(Error::input(
                key("law"),
                format!("{other:?} is not a wall law; allowed: constant, dashpot, viscoelastic"),
            ))
        }
    })
}
