//! Driving a granular gas into a steady state: energy fed in to balance the collisional
//! loss (Williams & MacKintosh, Phys. Rev. E 54, R9 (1996); van Noije & Ernst, Granular
//! Matter 1, 57 (1998)).
//!
//! White noise: in a time dt every particle's velocity receives an independent Gaussian
//! kick of variance `strength` dt per component (a random acceleration, the same for every
//! species), less the mass-weighted mean kick of its group (a DSMC block), so that momentum
//! is conserved exactly. For a group of B equal masses the mean removal leaves (1 - 1/B) of
//! the variance: the energy fed in per particle and unit time is (1 - 1/B) D m xi^2 / 2.
//! The DSMC block scheme kicks half a step before and half after each step's collisions
//! (symmetric splitting); the event-driven engine kicks every particle at the discrete
//! times k dt of its `interval` and renews every prediction (`emd::driving`).
//!
//! Gaussian thermostat (anti-drag): every velocity is scaled about the mean velocity by
//! one factor, so that the temperature stays at its target. It is the force m_i gamma
//! (v - u) with a common gamma that balances the collisional cooling at every instant; it
//! maps the homogeneous cooling state onto a steady one in which the shape of the velocity
//! distributions (a2, the temperature ratios of a mixture) is the HCS's (Montanero & Garzó,
//! Granular Matter 4, 17 (2002)). Scaled after every step (DSMC) or at the discrete times of
//! an interval (event-driven).

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

/// The Gaussian thermostat holding the temperature at `temperature`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Thermostat {
    pub temperature: f64,
}

impl Thermostat {
    /// Fails, naming `temperature`, unless 0 < temperature < inf.
    pub fn new(temperature: f64) -> Result<Self> {
        if !(temperature.is_finite() && temperature > 0.0) {
            return Err(Error::out_of_range(
                "temperature",
                temperature,
                "finite and > 0",
            ));
        }
        Ok(Thermostat { temperature })
    }

    /// The factor that scales velocities about the mean from `temperature` to the target
    /// (1 for a gas at rest: nothing to scale).
    pub fn factor(&self, temperature: f64) -> f64 {
        if temperature > 0.0 && temperature.is_finite() {
            (self.temperature / temperature).sqrt()
        } else {
            1.0
        }
    }
}

/// Energy fed into a gas for a steady state.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Driving {
    WhiteNoise(WhiteNoise),
    Thermostat(Thermostat),
}

/// Driving as an engine is asked to apply it ([`crate::Engine::set_driving`]): the driving,
/// and when it is applied. A stepped engine (DSMC blocks) applies it at every step of its
/// own and refuses an `interval`; the event-driven engine applies it at the times
/// k `interval` (required), its white-noise kicks drawn from streams of `seed`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drive {
    pub driving: Driving,
    pub interval: Option<f64>,
    pub seed: u64,
}

impl WhiteNoise {
    /// Fails, naming `strength`, unless 0 < strength < inf.
    pub fn new(strength: f64) -> Result<Self> {
        if !(strength.is_finite() && strength > 0.0) {
            return Err(Error::out_of_range("strength", strength, "finite and > 0"));
        }
        Ok(WhiteNoise { strength })
    }

    /// The kicks of a group of particles of `masses` for a time `dt` (D normals per
    /// particle from `rng`, particle by particle), less their mass-weighted mean.
    pub(crate) fn kicks<const D: usize>(
        &self,
        masses: impl Iterator<Item = f64>,
        dt: f64,
        rng: &mut Stream,
    ) -> Vec<Vector<D>> {
        let width = (self.strength * dt).sqrt();
        let mut mass = 0.0;
        let mut momentum: Vector<D> = [0.0; D];
        let mut kicks: Vec<Vector<D>> = masses
            .map(|m| {
                let dv: Vector<D> = std::array::from_fn(|_| {
                    width * <StandardNormal as Distribution<f64>>::sample(&StandardNormal, rng)
                });
                for k in 0..D {
                    momentum[k] += m * dv[k];
                }
                mass += m;
                dv
            })
            .collect();
        if mass > 0.0 {
            let mean: Vector<D> = std::array::from_fn(|k| momentum[k] / mass);
            for dv in &mut kicks {
                for k in 0..D {
                    dv[k] -= mean[k];
                }
            }
        }
        kicks
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
        let masses = group.iter().map(|r| species.masses[r.species()]);
        let kicks = self.kicks::<D>(masses.collect::<Vec<_>>().into_iter(), dt, rng);
        for (r, dv) in group.iter_mut().zip(kicks) {
            let v = r.velocity_mut();
            for k in 0..D {
                v[k] += dv[k];
            }
        }
    }
}
