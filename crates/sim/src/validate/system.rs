//! `[system]`: the dimension, the particles and their species, the packing fraction and the
//! initial temperature, in range; the species with every default resolved.

use super::{in_scale, Species, MIN_PACKING};
use crate::description::{species, RunDescription};
use crate::error::{positive, Error, Result};

/// `[system]`.
pub(super) fn check_system(description: &RunDescription) -> Result<Vec<Species>> {
    let s = &description.system;
    if !(1..=3).contains(&s.dimension) {
        return Err(Error::out_of_range(
            "system.dimension",
            s.dimension,
            "1, 2 or 3",
        ));
    }
    if s.particles == 0 && s.initial.is_none() {
        return Err(Error::input(
            "system.particles",
            "missing: give system.particles (or system.initial, particles from a file)",
        ));
    }
    if s.particles < 2 || s.particles > 100_000_000 {
        return Err(Error::out_of_range(
            "system.particles",
            s.particles,
            "2 <= N <= 1e8",
        ));
    }
    check_box(description)?;
    match &s.species {
        None => {
            in_scale("system.diameter", s.diameter.unwrap_or(1.0))?;
            in_scale("system.mass", s.mass.unwrap_or(1.0))?;
        }
        Some(_) if s.diameter.is_some() || s.mass.is_some() => {
            return Err(Error::input(
                "system.species",
                "give either system.species or system.diameter/system.mass, not both",
            ));
        }
        Some(entries) => {
            if entries.is_empty() {
                return Err(Error::input("system.species", "give at least one species"));
            }
            for (k, x) in entries.iter().enumerate() {
                in_scale(&format!("system.species[{k}].diameter"), x.diameter)?;
                in_scale(&format!("system.species[{k}].mass"), x.mass)?;
                positive(&format!("system.species[{k}].fraction"), x.fraction)?;
                // Particles are told apart by diameter and mass (species.csv, the DSMC
                // tables): two entries alike would be one species counted twice.
                if let Some(j) = entries[..k]
                    .iter()
                    .position(|y| y.diameter == x.diameter && y.mass == x.mass)
                {
                    return Err(Error::input(
                        format!("system.species[{k}]"),
                        format!(
                            "the diameter and mass of system.species[{j}]: species must differ \
                             in diameter or mass (merge the two entries)"
                        ),
                    ));
                }
            }
        }
    }
    in_scale("system.temperature", s.temperature)?;
    let species = species_of(description)?;
    check_packing(description)?;
    Ok(species)
}

/// `system.packing_fraction` or `system.box`, one of them: the box one side per dimension,
/// each in scale.
fn check_box(description: &RunDescription) -> Result<()> {
    let s = &description.system;
    match (&s.packing_fraction, &s.sides) {
        (Some(_), Some(_)) => Err(Error::input(
            "system.box",
            "give either system.packing_fraction (a cube) or system.box (its sides), not both",
        )),
        (None, None) => Err(Error::input(
            "system.packing_fraction",
            "missing: give system.packing_fraction (a cube) or system.box (its sides)",
        )),
        (Some(_), None) => Ok(()),
        (None, Some(sides)) => {
            if sides.len() != s.dimension as usize {
                return Err(Error::out_of_range(
                    "system.box",
                    format!("{} sides", sides.len()),
                    &format!("one side per dimension: {}", s.dimension),
                ));
            }
            for (k, &side) in sides.iter().enumerate() {
                in_scale(&format!("system.box[{k}]"), side)?;
            }
            Ok(())
        }
    }
}

/// `system.box` needs an engine with space (the spatial ones, which have walls too), and,
/// for spheres with extent, sides of at least [`MIN_SIDE_IN_DIAMETERS`] largest diameters
/// (the event-driven engine's cells; the soft-sphere engine's neighbour cells need 2.6).
pub(super) fn check_box_engine(
    description: &RunDescription,
    engine: &crate::engines::Abilities,
    species: &[Species],
) -> Result<()> {
    let Some(sides) = &description.system.sides else {
        return Ok(());
    };
    if !engine.walls {
        return Err(Error::input(
            "system.box",
            format!(
                "this engine has no space (homogeneous DSMC: only the volume counts); give \
                 system.packing_fraction, or run.engine = {} for a box with sides of its own",
                crate::engines::kinds_that(|a| a.walls)
            ),
        ));
    }
    if engine.point_particles {
        return Ok(());
    }
    let largest = species.iter().map(|s| s.diameter).fold(0.0, f64::max);
    let least = MIN_SIDE_IN_DIAMETERS * largest;
    if let Some(k) = sides.iter().position(|&l| l < least) {
        return Err(Error::out_of_range(
            &format!("system.box[{k}]"),
            crate::output::number(sides[k]),
            &format!(
                "at least {MIN_SIDE_IN_DIAMETERS} largest diameters, {}",
                crate::output::number(least)
            ),
        ));
    }
    Ok(())
}

/// The shortest side of a box of spheres, in largest diameters.
const MIN_SIDE_IN_DIAMETERS: f64 = 4.0;

/// The packing fraction, given or of the spheres in the box, within what the initializer
/// places.
fn check_packing(description: &RunDescription) -> Result<()> {
    let s = &description.system;
    let max_phi = gas::init::packing_limit(s.dimension as usize);
    let phi = description.packing_fraction();
    // Particles of a file are checked for overlaps instead: a packing may be denser than
    // the placements reach.
    let max_phi = match s.initial {
        Some(_) => 1.0,
        None => max_phi,
    };
    if phi >= MIN_PACKING && phi <= max_phi {
        return Ok(());
    }
    let allowed = format!(
        "{MIN_PACKING:e} <= phi <= {max_phi} in {} dimensions",
        s.dimension
    );
    match s.packing_fraction {
        Some(phi) => Err(Error::out_of_range(
            "system.packing_fraction",
            phi,
            &allowed,
        )),
        None => Err(Error::out_of_range(
            "system.box",
            format!("a box the spheres fill to phi = {phi}"),
            &allowed,
        )),
    }
}

/// The particles of `[system]` with every default resolved: `system.species` (fractions
/// normalized, counts as the initializer splits `system.particles`), or the one kind of
/// `system.diameter` and `system.mass` (1 unless given).
fn species_of(description: &RunDescription) -> Result<Vec<Species>> {
    let s = &description.system;
    let Some(entries) = &s.species else {
        return Ok(vec![Species {
            diameter: s.diameter.unwrap_or(1.0),
            mass: s.mass.unwrap_or(1.0),
            fraction: 1.0,
            count: s.particles,
        }]);
    };
    let counts = gas::init::species_counts(s.particles, &species(entries))
        .map_err(|e| Error::input("system.species", e))?;
    let total: f64 = entries.iter().map(|x| x.fraction).sum();
    Ok(entries
        .iter()
        .zip(counts)
        .map(|(x, count)| Species {
            diameter: x.diameter,
            mass: x.mass,
            fraction: x.fraction / total,
            count,
        })
        .collect())
}
