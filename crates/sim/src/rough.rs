//! `summary.json`'s `rough_theory`: the Maxwellian theory of rough particles
//! (`gas::theory::rough`) for a run it applies to — one kind of particle, a constant
//! normal restitution and a constant tangential one (no friction) — beside the run's last
//! sample.

use crate::observer::Sample;
use crate::validate::{LawSpec, Plan};
use gas::theory::rough::RoughMaxwellian;
use serde_json::{json, Value};

/// The theory of the run of `plan`, with its prediction at the last of `samples`; None
/// where it does not apply.
pub fn theory(plan: &Plan, samples: &[Sample]) -> Option<Value> {
    let rough = plan.rough.as_ref()?;
    let LawSpec::Constant(alpha) = plan.law else {
        return None;
    };
    if rough.friction.is_some() || plan.species.len() != 1 {
        return None;
    }
    let s = &plan.description.system;
    let theory = RoughMaxwellian {
        dimension: s.dimension as usize,
        alpha,
        beta: rough.beta(),
        inertia: rough.inertia[0],
    };
    let hcs = theory.hcs()?;
    let mut out = json!({
        "approximation": "Maxwellian: Gaussian translational and angular velocities, \
            uncorrelated (Huthmann & Zippelius 1997; Luding, Huthmann, McNamara & Zippelius \
            1998); the first Sonine corrections are not included",
        "alpha": alpha,
        "beta": rough.beta(),
        "inertia": rough.inertia[0],
        "hcs_ratio": hcs.ratio,
        "hcs_cooling_per_collision": hcs.cooling_per_collision,
    });
    if let Some(last) = samples.last() {
        let [t, t_rot] = theory.evolve(
            [s.temperature, rough.temperature],
            last.collisions_per_particle,
        );
        out["at_last_sample"] = json!({
            "collisions_per_particle": last.collisions_per_particle,
            "temperature": t,
            "rotational_temperature": t_rot,
            "ratio": t_rot / t,
            "measured_ratio": last.rotational_temperature.map(|r| r / last.temperature),
        });
    }
    Some(out)
}
