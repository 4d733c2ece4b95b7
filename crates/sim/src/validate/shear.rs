//! `[shear]`: the uniform shear flow u = rate y e_x (`gas::shear`), and the pressure tensor
//! (`output.pressure`, always with `[shear]`). Refused: a rate that is not finite and
//! nonzero, 1D, engines without shear, walls on x or y (the Lees–Edwards boundaries), walls
//! on z and gravity (not built with shear), the observers whose wave vectors are a fixed
//! box's (modes, S(k)), and a rate at which the images slide past the whole box within a
//! collision time (the flow would no longer be resolved by collisions).

use super::{Species, WallSpec};
use crate::description::{RunDescription, AXIS_NAMES};
use crate::engines::{engine_named, kind_name, kinds_that, Abilities};
use crate::error::{Error, Result};
use gas::shear::Shear;

/// The checked shear of a run, if any.
pub(crate) fn shear_spec(
    description: &RunDescription,
    engine: &Abilities,
    walls: &[WallSpec],
    species: &[Species],
) -> Result<Option<Shear>> {
    check_pressure(description, engine)?;
    let Some(section) = &description.shear else {
        return Ok(None);
    };
    let rate = section.rate;
    let shear = Shear::new(rate)
        .map_err(|_| Error::out_of_range("shear.rate", rate, "finite and not 0"))?;
    if !(1e-30..=1e30).contains(&rate.abs()) {
        return Err(Error::out_of_range(
            "shear.rate",
            crate::output::number(rate),
            "1e-30 <= |rate| <= 1e30",
        ));
    }
    let dimension = description.system.dimension as usize;
    if dimension < 2 {
        return Err(Error::input(
            "shear.rate",
            "needs 2 or 3 dimensions (the flow along x, its gradient along y)",
        ));
    }
    if !engine.shear {
        return Err(Error::input(
            "shear",
            format!(
                "run.engine = \"{}\" has no shear yet; shear runs with run.engine = {}",
                kind_name(description.run.engine),
                kinds_that(|a| a.shear)
            ),
        ));
    }
    if let Some((i, w)) = walls.iter().enumerate().find(|(_, w)| w.axis < 2) {
        return Err(Error::input(
            format!("wall[{i}].axis"),
            format!(
                "{} is an axis of the Lees-Edwards boundaries of [shear] (x and y stay \
                 periodic)",
                AXIS_NAMES[w.axis]
            ),
        ));
    }
    if !walls.is_empty() {
        return Err(Error::input(
            "shear",
            "with walls (on z): not built yet; a sheared gas is periodic",
        ));
    }
    if description.field.is_some() {
        return Err(Error::input("field", "with [shear]: not built yet"));
    }
    if let Some(o) = &description.output {
        for (key, on) in [("output.modes", o.modes), ("output.structure", o.structure)] {
            if on {
                return Err(Error::input(
                    key,
                    "with [shear]: its wave vectors are those of a box at rest (the sheared \
                     box's are not built)",
                ));
            }
        }
    }
    if engine.positions {
        check_resolved(description, species, rate)?;
    }
    Ok(Some(shear))
}

/// `output.msd`: an engine that tracks displacements, no shear (the flow carries spheres).
pub(crate) fn msd_spec(description: &RunDescription, engine: &Abilities) -> Result<bool> {
    if !description.output.as_ref().is_some_and(|o| o.msd) {
        return Ok(false);
    }
    if !engine.displacements {
        return Err(Error::input(
            "output.msd",
            format!(
                "{} keeps no particle's identity through its steps; the mean-square \
                 displacement is measured with run.engine = {}",
                engine_named(description),
                kinds_that(|a| a.displacements)
            ),
        ));
    }
    if description.shear.is_some() {
        return Err(Error::input(
            "output.msd",
            "with [shear]: the flow carries the spheres along x (not built)",
        ));
    }
    Ok(true)
}

/// `output.pressure` needs an engine that sums the tensor virial.
fn check_pressure(description: &RunDescription, engine: &Abilities) -> Result<()> {
    let asked = description.output.as_ref().is_some_and(|o| o.pressure);
    if asked && !engine.stress {
        return Err(Error::input(
            "output.pressure",
            format!(
                "run.engine = \"{}\" has no pressure tensor yet; it is measured with run.engine \
                 = {}",
                kind_name(description.run.engine),
                kinds_that(|a| a.stress)
            ),
        ));
    }
    Ok(())
}

/// Refuses a rate at which the images above the box slide past its whole length along x
/// within a mean free time of the initial gas: |a| L_y / omega0 > L_x (omega0 Enskog's
/// collision frequency at `system.temperature`, for the largest spheres).
fn check_resolved(description: &RunDescription, species: &[Species], rate: f64) -> Result<()> {
    let s = &description.system;
    let sides = description.box_sides();
    let volume: f64 = sides.iter().product();
    let weight = description.run.particle_weight.unwrap_or(1.0);
    let density = weight * s.particles as f64 / volume;
    let largest = species
        .iter()
        .max_by(|a, b| a.diameter.total_cmp(&b.diameter))
        .expect("a species");
    let phi = description.packing_fraction();
    let omega = match s.dimension {
        2 => gas::theory::collision_frequency::<2>(
            density,
            largest.diameter,
            largest.mass,
            s.temperature,
            phi,
        ),
        _ => gas::theory::collision_frequency::<3>(
            density,
            largest.diameter,
            largest.mass,
            s.temperature,
            phi,
        ),
    };
    let slide = rate.abs() * sides[1] / omega;
    if slide > sides[0] {
        return Err(Error::out_of_range(
            "shear.rate",
            crate::output::number(rate),
            &format!(
                "|rate| <= {}: the images slide past the box's length along x ({}) in less \
                 than a mean free time (1 / omega0 = {})",
                crate::output::number(omega * sides[0] / sides[1]),
                crate::output::number(sides[0]),
                crate::output::number(1.0 / omega)
            ),
        ));
    }
    Ok(())
}
