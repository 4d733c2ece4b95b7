//! The kinds of particle in a DSMC gas and what a collision needs to know about a pair.

use crate::error::{Error, Result};
use crate::system::ball_volume;
use crate::theory::{contact_value, mixture_contact_value};

/// Distinct (radius, mass) pairs the engines accept (pair data is a table of this squared).
pub const MAX_SPECIES: usize = 256;

/// What the collision kernel needs about a pair of species.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PairData {
    /// W_ab / W_max with W = g_ab sigma_ab^(D-1): the pair's share of the majorant rate.
    pub ratio: f64,
    /// m_b / (m_a + m_b) and m_a / (m_a + m_b): velocity changes per unit of momentum
    /// transfer over the reduced mass.
    pub share_a: f64,
    pub share_b: f64,
    /// Reduced mass m_a m_b / (m_a + m_b).
    pub reduced: f64,
    /// Contact distance (sigma_a + sigma_b) / 2.
    pub sigma: f64,
}

/// The species of a gas (distinct (radius, mass) pairs, in order of first appearance).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Species {
    pub radii: Vec<f64>,
    pub masses: Vec<f64>,
    pairs: Vec<PairData>,
    /// The largest pair weight W_max = max g_ab sigma_ab^(D-1).
    pub max_weight: f64,
    /// The smallest mass (for an upper estimate of the collision frequency).
    pub min_mass: f64,
    /// Total volume of all spheres.
    pub sphere_volume: f64,
}

impl Species {
    /// The species of particles with these radii and masses at packing fraction `phi`, and
    /// the species index of each particle. Fails for a non-positive radius or mass or too
    /// many species.
    pub fn of<const D: usize>(
        radii: &[f64],
        masses: &[f64],
        phi: f64,
    ) -> Result<(Species, Vec<u32>)> {
        let mut kinds: Vec<(f64, f64)> = Vec::new();
        let mut counts: Vec<usize> = Vec::new();
        let mut index = Vec::with_capacity(radii.len());
        let mut last = usize::MAX;
        for (i, (&r, &m)) in radii.iter().zip(masses).enumerate() {
            if !(r.is_finite() && r > 0.0) {
                return Err(Error::out_of_range(
                    format!("radii[{i}]"),
                    r,
                    "a finite number > 0",
                ));
            }
            if !(m.is_finite() && m > 0.0) {
                return Err(Error::out_of_range(
                    format!("masses[{i}]"),
                    m,
                    "a finite number > 0",
                ));
            }
            if last == usize::MAX || kinds[last] != (r, m) {
                last = match kinds.iter().position(|&k| k == (r, m)) {
                    Some(s) => s,
                    None if kinds.len() < MAX_SPECIES => {
                        kinds.push((r, m));
                        counts.push(0);
                        kinds.len() - 1
                    }
                    None => {
                        return Err(Error::out_of_range(
                            "species",
                            format!("more than {MAX_SPECIES} distinct (radius, mass) pairs"),
                            format!("at most {MAX_SPECIES}"),
                        ))
                    }
                };
            }
            counts[last] += 1;
            index.push(last as u32);
        }
        let radii: Vec<f64> = kinds.iter().map(|k| k.0).collect();
        let masses: Vec<f64> = kinds.iter().map(|k| k.1).collect();
        let weights = pair_weights::<D>(&radii, &counts, phi);
        let max_weight = weights.iter().cloned().fold(0.0, f64::max);
        let s = radii.len();
        let pairs = (0..s * s)
            .map(|ab| {
                let (a, b) = (ab / s, ab % s);
                let (ma, mb) = (masses[a], masses[b]);
                PairData {
                    ratio: weights[ab] / max_weight,
                    share_a: mb / (ma + mb),
                    share_b: ma / (ma + mb),
                    reduced: ma * mb / (ma + mb),
                    sigma: radii[a] + radii[b],
                }
            })
            .collect();
        let sphere_volume = counts
            .iter()
            .zip(&radii)
            .map(|(&c, &r)| c as f64 * ball_volume::<D>(r))
            .sum();
        let min_mass = masses.iter().cloned().fold(f64::INFINITY, f64::min);
        let species = Species {
            radii,
            masses,
            pairs,
            max_weight,
            min_mass,
            sphere_volume,
        };
        Ok((species, index))
    }

    pub fn len(&self) -> usize {
        self.radii.len()
    }

    #[inline]
    pub fn pair(&self, a: usize, b: usize) -> &PairData {
        &self.pairs[a * self.radii.len() + b]
    }

    pub fn memory_bytes(&self) -> usize {
        (self.radii.capacity() + self.masses.capacity()) * 8
            + self.pairs.capacity() * std::mem::size_of::<PairData>()
    }
}

/// W_ab = g_ab sigma_ab^(D-1) for all species pairs (row-major): the pure contact value for
/// one species, the mixture contact value of [`mixture_contact_value`] otherwise.
fn pair_weights<const D: usize>(radii: &[f64], counts: &[usize], phi: f64) -> Vec<f64> {
    let s = radii.len();
    let moment = |p: i32| -> f64 {
        counts
            .iter()
            .zip(radii)
            .map(|(&c, &r)| c as f64 * (2.0 * r).powi(p))
            .sum()
    };
    let ratio = moment(D as i32 - 1) / moment(D as i32);
    (0..s * s)
        .map(|ab| {
            let (da, db) = (2.0 * radii[ab / s], 2.0 * radii[ab % s]);
            let sigma = 0.5 * (da + db);
            let g = if s == 1 {
                contact_value::<D>(phi)
            } else {
                mixture_contact_value::<D>(phi, da * db / (da + db) * ratio)
            };
            g * sigma.powi(D as i32 - 1)
        })
        .collect()
}

/// The collisions of each species' particles: `counted` (mixtures) or, for one species,
/// twice the collisions of `tally`.
/// The collisions of each species `counted` (in the order of `species`) in the order a
/// restored engine will give its species: first appearance of (radius, mass) in the
/// saved system (`Species::of`). A snapshot writes them so: the records are permuted
/// (blocks, cells), and a restored engine whose first particle is of another species
/// than the engine's first would otherwise take one species' collisions for another's.
pub(crate) fn in_saved_order(
    species: &Species,
    counted: &[u64],
    radii: &[f64],
    masses: &[f64],
) -> Vec<u64> {
    if counted.is_empty() {
        return Vec::new();
    }
    let mut order: Vec<usize> = Vec::with_capacity(species.len());
    for (&r, &m) in radii.iter().zip(masses) {
        if order.len() == species.len() {
            break;
        }
        if let Some(s) = (0..species.len())
            .find(|&s| species.radii[s] == r && species.masses[s] == m)
            .filter(|s| !order.contains(s))
        {
            order.push(s);
        }
    }
    // Every species has a particle (`Species::of` makes species of particles only).
    order
        .iter()
        .map(|&s| counted.get(s).copied().unwrap_or(0))
        .collect()
}

pub(crate) fn by_species(
    species: &Species,
    counted: &[u64],
    tally: &crate::engine::Counters,
) -> Vec<crate::engine::SpeciesCollisions> {
    (0..species.len())
        .map(|s| crate::engine::SpeciesCollisions {
            radius: species.radii[s],
            mass: species.masses[s],
            collisions: if species.len() == 1 {
                2 * tally.collisions
            } else {
                counted.get(s).copied().unwrap_or(0)
            },
        })
        .collect()
}

/// The laws of an engine with `species`: for a pairwise law
/// ([`restitution::Restitution::pairwise`]), the law of each pair of species in their
/// order (or, for one species, its law with itself as the law); otherwise `law` alone.
/// Fails (`restitution`) if the pairwise law names no law for a species.
#[allow(clippy::type_complexity)]
pub(crate) fn engine_laws(
    law: Box<dyn restitution::Restitution>,
    species: &Species,
) -> crate::error::Result<(
    Box<dyn restitution::Restitution>,
    Option<Vec<Box<dyn restitution::Restitution>>>,
)> {
    let Some(pairwise) = law.pairwise() else {
        return Ok((law, None));
    };
    let kinds: Vec<usize> = (0..species.len())
        .map(|s| {
            pairwise
                .kind_of(species.radii[s], species.masses[s])
                .ok_or_else(|| {
                    crate::error::Error::out_of_range(
                        "restitution",
                        format!(
                            "no law for particles of radius {} and mass {}",
                            species.radii[s], species.masses[s]
                        ),
                        "a law for every pair of species",
                    )
                })
        })
        .collect::<crate::error::Result<_>>()?;
    if kinds.len() == 1 {
        return Ok((pairwise.boxed(kinds[0], kinds[0]), None));
    }
    let table = kinds
        .iter()
        .flat_map(|&a| kinds.iter().map(move |&b| (a, b)))
        .map(|(a, b)| pairwise.boxed(a, b))
        .collect();
    Ok((law, Some(table)))
}
