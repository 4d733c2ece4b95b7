//! The figures of a run, drawn with [`crate::plot`].

use crate::error::Result;
use crate::observer::Sample;
use crate::species::SpeciesSample;
use crate::validate::{LawSpec, Plan};
use gas::system::ball_volume;
use gas::theory::{collision_frequency, haff_temperature, haff_time, van_noije_ernst_a2};

/// `temperature.png`: T(t) (for a mixture, each species' T_i(t) too) and, for a monodisperse gas with a constant eps < 1, Haff's law
/// T0 / (1 + t/tau)^2 with the Enskog collision frequency at T0 and (2D, 3D) the cooling
/// rate of the homogeneous cooling state, (1 + 3 a2/16) times the Maxwellian one (Haff 1983;
/// Brilliantov & Pöschel, *Kinetic Theory of Granular Gases*, Ch. 7; see [`gas::theory`]).
pub fn temperature(
    path: &std::path::Path,
    plan: &Plan,
    samples: &[Sample],
    species: Option<&[SpeciesSample]>,
) -> Result<()> {
    let points: Vec<(f64, f64)> = samples.iter().map(|s| (s.time, s.temperature)).collect();
    let list = plan.description.system.species.as_deref().unwrap_or(&[]);
    let lines: Vec<(String, Vec<(f64, f64)>)> = list
        .iter()
        .enumerate()
        .map(|(k, x)| {
            let rows = species.unwrap_or(&[]).iter().filter(|r| r.species == k);
            (
                format!("species {k} (d = {}, m = {})", x.diameter, x.mass),
                rows.map(|r| (r.time, r.temperature)).collect(),
            )
        })
        .collect();
    let tau = samples
        .first()
        .and_then(|first| haff_law(plan, first.temperature).map(|tau| (first.temperature, tau)));
    match tau {
        Some((t0, tau)) => {
            let haff = move |t: f64| haff_temperature(t0, tau, t);
            crate::plot::temperature(
                path,
                &points,
                &lines,
                Some(("Haff's law (Enskog rate, HCS a2)", &haff)),
            )
        }
        None => crate::plot::temperature(path, &points, &lines, None),
    }
}

/// Haff's time tau of T(t) = T0 / (1 + t/tau)^2 for the run of `plan` starting at T0: a
/// monodisperse, undriven gas with a constant eps < 1, the Enskog collision frequency at T0
/// and (2D, 3D) the cooling rate of the homogeneous cooling state, (1 + 3 a2/16) times the
/// Maxwellian one, a2 of van Noije & Ernst (Brilliantov & Pöschel 2004, Ch. 7). None for
/// other runs.
pub fn haff_law(plan: &Plan, t0: f64) -> Option<f64> {
    let s = &plan.description.system;
    match (&plan.law, &s.species) {
        (LawSpec::Constant(eps), None) if *eps < 1.0 && plan.driving.is_none() => {
            let (diameter, mass) = (plan.species[0].diameter, plan.species[0].mass);
            let phi = plan.description.packing_fraction();
            let omega0 = match s.dimension {
                1 => enskog::<1>(phi, diameter, mass, t0),
                2 => enskog::<2>(phi, diameter, mass, t0),
                _ => enskog::<3>(phi, diameter, mass, t0),
            };
            Some(match s.dimension {
                1 => haff_time::<1>(*eps, omega0),
                2 => {
                    haff_time::<2>(*eps, omega0)
                        / (1.0 + 3.0 * van_noije_ernst_a2::<2>(*eps) / 16.0)
                }
                _ => {
                    haff_time::<3>(*eps, omega0)
                        / (1.0 + 3.0 * van_noije_ernst_a2::<3>(*eps) / 16.0)
                }
            })
        }
        _ => None,
    }
}

/// The Enskog collision frequency at packing fraction phi (number density phi over the
/// sphere volume).
fn enskog<const D: usize>(phi: f64, diameter: f64, mass: f64, temperature: f64) -> f64 {
    let density = phi / ball_volume::<D>(0.5 * diameter);
    collision_frequency::<D>(density, diameter, mass, temperature, phi)
}
