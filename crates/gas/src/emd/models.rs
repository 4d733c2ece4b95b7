//! The two models the event-driven engine adds to hard spheres: the TC model against
//! inelastic collapse, and the per-particle baths of Giese's stochastic coefficient of
//! restitution (event-driven + Monte Carlo).

use super::EventDriven;
use crate::error::{Error, Result};
use crate::rng::{Purpose, Stream};
use restitution::stochastic::collide_with_baths;
use serde::{Deserialize, Serialize};

/// The internal state of Giese's event-driven + Monte Carlo algorithm: each particle's bath
/// temperature, and one counted random stream (restored by jumping ahead) for eps.
#[derive(Debug, Clone)]
pub(super) struct Baths {
    pub(super) temperatures: Vec<f64>,
    pub(super) seed: u64,
    pub(super) stream: Stream,
}

impl Baths {
    pub(super) fn new(temperatures: Vec<f64>, seed: u64) -> Self {
        Baths {
            temperatures,
            seed,
            stream: Stream::new(seed, Purpose::Baths, 0, 0),
        }
    }
}

/// A snapshot of the baths of a stochastic law (see [`EventDriven::bath_state`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BathState {
    /// Bath temperature of each particle (energy per internal mode).
    pub temperatures: Vec<f64>,
    /// Seed of the stream that draws eps.
    pub seed: u64,
    /// Numbers drawn from it so far.
    pub draws: u64,
}

/// The TC model of Luding & McNamara (Granular Matter 1, 113 (1998)) against inelastic
/// collapse: a collision is elastic if either partner has collided less than `duration`
/// ago (a contact still "in progress"), so that no finite-time singularity of infinitely
/// many collisions can form.
#[derive(Debug, Clone)]
pub(super) struct TcModel {
    pub(super) duration: f64,
    /// Time of each particle's last collision (-inf before the first).
    pub(super) last: Vec<f64>,
}

impl<const D: usize> EventDriven<D> {
    /// Switches on the TC model with contact duration `duration` (0 switches it off).
    /// `last_collisions` restores each particle's last collision time from a snapshot;
    /// None starts with no recent collision.
    pub fn set_tc_model(&mut self, duration: f64, last_collisions: Option<Vec<f64>>) -> Result<()> {
        if !(duration.is_finite() && duration >= 0.0) {
            return Err(Error::out_of_range("tc", duration, "a finite number >= 0"));
        }
        let n = self.particles.len();
        let last = last_collisions.unwrap_or_else(|| vec![f64::NEG_INFINITY; n]);
        if last.len() != n {
            return Err(Error::LengthMismatch {
                what: "last collision times of the TC model and particles".into(),
            });
        }
        self.tc = (duration > 0.0).then_some(TcModel { duration, last });
        Ok(())
    }

    /// The TC model's contact duration and last collision times, if it is on.
    pub fn tc_model(&self) -> Option<(f64, &[f64])> {
        self.tc.as_ref().map(|tc| (tc.duration, tc.last.as_slice()))
    }

    /// Sets the bath temperatures of a stochastic law (one per particle, >= 0) and the
    /// seed of its random stream; fails if the law is deterministic.
    pub fn set_baths(&mut self, temperatures: Vec<f64>, seed: u64) -> Result<()> {
        self.set_bath_state(BathState {
            temperatures,
            seed,
            draws: 0,
        })
    }

    /// Restores baths saved by [`EventDriven::bath_state`].
    pub fn set_bath_state(&mut self, state: BathState) -> Result<()> {
        if self.baths.is_none() {
            return Err(Error::NoBaths {
                law: self.law.describe(),
            });
        }
        if state.temperatures.len() != self.particles.len() {
            return Err(Error::LengthMismatch {
                what: format!(
                    "bath temperatures ({}) and particles ({})",
                    state.temperatures.len(),
                    self.particles.len()
                ),
            });
        }
        if let Some(k) = state
            .temperatures
            .iter()
            .position(|t| !(t.is_finite() && *t >= 0.0))
        {
            return Err(Error::out_of_range(
                format!("bath temperature of particle {k}"),
                state.temperatures[k],
                "a finite number >= 0",
            ));
        }
        let mut baths = Baths::new(state.temperatures, state.seed);
        baths.stream = Stream::at(state.seed, Purpose::Baths, 0, 0, state.draws);
        self.baths = Some(baths);
        Ok(())
    }

    /// The baths and the position of their random stream (for check-points).
    pub fn bath_state(&self) -> Option<BathState> {
        self.baths.as_ref().map(|b| BathState {
            temperatures: b.temperatures.clone(),
            seed: b.seed,
            draws: b.stream.draws(),
        })
    }

    /// The normal impulse on j (minus that on i) and the translational energy lost: from
    /// eps of the law, or, for a stochastic law, from the energy E' drawn at the pair's
    /// bath temperature, the bath taking up the difference (Giese's steps (2)-(4)).
    pub(super) fn impulse(
        &mut self,
        i: usize,
        j: usize,
        reduced: f64,
        approach: f64,
    ) -> (f64, f64) {
        let e_tr = 0.5 * reduced * approach * approach;
        // Baths exist iff the law is stochastic: test the field first, so that
        // deterministic laws pay no extra virtual call per collision.
        let law = &self.law;
        let stochastic = self
            .baths
            .as_mut()
            .and_then(|b| Some((b, law.stochastic()?)));
        match stochastic {
            Some((baths, law)) => {
                let approach = approach.max(0.0);
                let t = &mut baths.temperatures;
                let (mut ti, mut tj) = (t[i], t[j]);
                let u = baths.stream.uniform();
                let e_after = collide_with_baths(law, e_tr, (&mut ti, &mut tj), u);
                (t[i], t[j]) = (ti, tj);
                let separation = (2.0 * e_after / reduced).sqrt();
                (reduced * (approach + separation), e_tr - e_after)
            }
            None => {
                let speed = approach.max(0.0);
                let eps = match &self.pairs {
                    Some((table, kinds)) => {
                        table.law(kinds[i] as usize, kinds[j] as usize).eps(speed)
                    }
                    None => self.law.eps(speed),
                };
                ((1.0 + eps) * reduced * approach, (1.0 - eps * eps) * e_tr)
            }
        }
    }
}
