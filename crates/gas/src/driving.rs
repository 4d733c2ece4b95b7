//! Driving a granular gas into a steady state: energy fed in to balance the collisional
//! loss (Williams & MacKintosh, Phys. Rev. E 54, R9 (1996); van Noije & Ernst, Granular
//! Matter 1, 57 (1998)).
//!
//! White noise: in a time dt every particle's velocity receives an independent Gaussian
//! kick of variance `strength` dt per component (a random acceleration, the same for every
//! species), less the mass-weighted mean kick of its group (a DSMC block), so that momentum
//! is conserved exactly. For a group of B equal masses the mean removal leaves (1 - 1/B) of
//! the variance: the energy fed in per particle and unit time is (1 - 1/B) D m xi^2 / 2.
//! Kicks are applied at the end of each step (operator splitting, first order in the step).

use crate::dsmc::kernel::Record;
use crate::dsmc::species::Species;
use crate::error::{Error, Result};
use crate::rng::Stream;
use crate::system::Vector;
use rand_distr::{Distribution, StandardNormal};
use serde::{Deserialize, Serialize};

/// White-noise driving of strength xi^2 (velocity variance per component and unit time).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WhiteNoise {
    pub strength: f64,
}

impl WhiteNoise {
    /// Fails, naming `strength`, unless 0 < strength < inf.
    pub fn new(strength: f64) -> Result<Self> {
        if !(strength.is_finite() && strength > 0.0) {
            return Err(Error::out_of_range("strength", strength, "finite and > 0"));
        }
        Ok(WhiteNoise { strength })
    }

    /// Kicks every particle of `group` for a time `dt` (draws D normals per particle from
    /// `rng`), then removes the group's mass-weighted mean kick.
    pub(crate) fn kick<const D: usize, R: Record<D>>(
        &self,
        group: &mut [R],
        dt: f64,
        species: &Species,
        rng: &mut Stream,
    ) {
        if group.is_empty() {
            return;
        }
        let width = (self.strength * dt).sqrt();
        let mut mass = 0.0;
        let mut momentum: Vector<D> = [0.0; D];
        for r in group.iter_mut() {
            let m = species.masses[r.species()];
            let v = r.velocity_mut();
            for k in 0..D {
                let dv =
                    width * <StandardNormal as Distribution<f64>>::sample(&StandardNormal, rng);
                v[k] += dv;
                momentum[k] += m * dv;
            }
            mass += m;
        }
        let mean: Vector<D> = std::array::from_fn(|k| momentum[k] / mass);
        for r in group.iter_mut() {
            let v = r.velocity_mut();
            for k in 0..D {
                v[k] -= mean[k];
            }
        }
    }
}
