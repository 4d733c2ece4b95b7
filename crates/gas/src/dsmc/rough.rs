//! What the DSMC engines keep of rough particles besides the spins in their records: the
//! tangential kick's constants per pair of species, each species' inertia factor (one per
//! species: the records carry their species only) and the contacts that slid. Shared by
//! the homogeneous engine (`homogeneous/spin.rs`) and the spatial one (`spatial/rough.rs`).

use super::kernel;
use super::species::Species;
use crate::error::{Error, Result};
use crate::rotation::{Contact, Rotation};
use restitution::rough::{Body, Tangential};
use restitution::Restitution;

/// Rough particles: the law's tangential kick per pair of species (none: the spins
/// rotate freely), each species' inertia factor, and the contacts that slid.
pub(crate) struct Spin {
    pub inertia: Vec<f64>,
    /// The kick's constants of each pair of species (row-major; one entry for one
    /// species), computed once; empty for a smooth law.
    pub contacts: Vec<Contact>,
    pub sliding: u64,
}

impl Spin {
    /// The spins' companion for `law` among `species` with each species' `inertia`
    /// factor, `sliding` contacts slid so far.
    pub fn new(law: &dyn Restitution, species: &Species, inertia: Vec<f64>, sliding: u64) -> Self {
        let tangential = rules_per_pair(law, species);
        let body = |s: usize| Body {
            mass: species.masses[s],
            radius: species.radii[s],
            inertia: inertia[s],
        };
        let kinds = species.len();
        let contacts = match tangential.as_slice() {
            [] => Vec::new(),
            [one] if kinds == 1 => vec![Contact::new(one, body(0), body(0))],
            rules => (0..kinds * kinds)
                .map(|k| {
                    let rule = if rules.len() == 1 {
                        &rules[0]
                    } else {
                        &rules[k]
                    };
                    Contact::new(rule, body(k / kinds), body(k % kinds))
                })
                .collect(),
        };
        Spin {
            inertia,
            contacts,
            sliding,
        }
    }

    /// What the kernel's tangential kick needs; None for a smooth law (no kick).
    pub fn kernel(&self) -> Option<kernel::Rough<'_>> {
        (!self.contacts.is_empty()).then_some(kernel::Rough {
            contacts: &self.contacts,
        })
    }

    /// The rotation of particles of the species `kinds` with the angular velocities
    /// `angular` (both in one order).
    pub fn rotation(&self, kinds: impl Iterator<Item = usize>, angular: Vec<[f64; 3]>) -> Rotation {
        Rotation {
            inertia: kinds.map(|s| self.inertia[s]).collect(),
            angular,
            sliding: self.sliding,
        }
    }
}

/// The law's tangential rules per pair of `species` (row-major), one rule for all, or
/// none for a smooth law. A species the law's table lacks takes the table's first rule
/// (the sim layer names a rule for every species).
pub(crate) fn rules_per_pair(law: &dyn Restitution, species: &Species) -> Vec<Tangential> {
    let Some(one) = law.tangential() else {
        return Vec::new();
    };
    let Some(table) = law.tangential_pairs() else {
        return vec![*one];
    };
    let kind = |s: usize| {
        table
            .kind_of(species.radii[s], species.masses[s])
            .unwrap_or(0)
    };
    let n = species.len();
    (0..n * n)
        .map(|k| *table.rule(kind(k / n), kind(k % n)))
        .collect()
}

/// The inertia factor of each of `count` species from `rotation`, given per particle
/// (`kinds`: each particle's species, in the rotation's order): one per species, refused
/// naming the particle whose factor differs from its species'. A species without
/// particles takes a solid sphere's, 0.4.
pub(crate) fn inertia_per_species(
    rotation: &Rotation,
    kinds: impl Iterator<Item = usize>,
    count: usize,
) -> Result<Vec<f64>> {
    let mut inertia: Vec<Option<f64>> = vec![None; count];
    for (i, s) in kinds.enumerate() {
        match inertia[s] {
            None => inertia[s] = Some(rotation.inertia[i]),
            Some(q) if q == rotation.inertia[i] => {}
            Some(q) => {
                return Err(Error::out_of_range(
                    format!("inertia[{i}]"),
                    rotation.inertia[i],
                    format!("{q}, the inertia factor of its species (one per species in DSMC)"),
                ))
            }
        }
    }
    Ok(inertia.into_iter().map(|q| q.unwrap_or(0.4)).collect())
}

/// Why a rough law's particles cannot lose their rotation.
pub(crate) fn rotation_needed() -> Error {
    Error::out_of_range(
        "rotation",
        "none",
        "a rotation for every particle: the law is rough",
    )
}
