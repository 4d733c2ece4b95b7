//! `summary.json`'s `rough_theory`: the Maxwellian theory of rough particles
//! (`gas::theory::rough`) for a run it applies to — one kind of particle, a constant
//! normal restitution and a constant tangential one (no friction) — beside the run's last
//! sample, and under `sonine` the cooling state in the first Sonine approximation
//! (`gas::theory::rough_sonine`; spheres and disks).

use crate::observer::Sample;
use crate::validate::{LawSpec, Plan};
use gas::theory::rough::RoughMaxwellian;
use gas::theory::rough_sonine;
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
    out["sonine"] = sonine(&theory, hcs.ratio);
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

/// The `sonine` section: the cooling state of the first Sonine approximation beside the
/// Maxwellian one, or the reason it has none (the linear approximation's breakdown near
/// smooth particles, `gas::theory::rough_sonine`).
fn sonine(theory: &RoughMaxwellian, maxwellian_ratio: f64) -> Value {
    let approximation = "first Sonine approximation, linear in the cumulants a20, a02, a11 \
        of f = phi(c) phi(w) [1 + a20 S2(c^2) + a02 S2(w^2) + a11 S1(c^2) S1(w^2)] \
        (Santos, Kremer & dos Santos 2011; Megias & Santos 2023), derived and checked in \
        gas::theory::rough_sonine";
    match rough_sonine::hcs(theory) {
        Some(h) => json!({
            "approximation": approximation,
            "hcs_ratio": h.ratio,
            "ratio_over_maxwellian": h.ratio / maxwellian_ratio,
            "a20": h.a20,
            "a02": h.a02,
            "a11": h.a11,
            "hcs_cooling_per_collision": h.cooling_per_collision,
            "cooling_rate_over_maxwellian_collision_frequency": h.cooling_rate,
            "collision_frequency_over_maxwellian": h.collision_frequency,
        }),
        None => json!({
            "approximation": approximation,
            "breakdown": "the linear equations have no cooling state connected with the \
                Maxwellian one (the rotational cumulant a02 diverges)",
        }),
    }
}
