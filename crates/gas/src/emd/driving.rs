//! Driving the event-driven engine ([`crate::driving`]): white-noise kicks or the
//! thermostat's scaling applied to every particle at the discrete times k dt of an
//! interval dt. A velocity change invalidates every prediction, so each application brings
//! every particle to the present and predicts every event afresh
//! ([`EventDriven::synchronize`]): the event calendar stays exact, and between two
//! applications the dynamics is the undriven one. Continuous driving is the limit dt -> 0;
//! the kicks of interval k draw from their own random stream (seed, k), so the run does not
//! depend on where it was paused or check-pointed.

use super::EventDriven;
use crate::driving::{Drive, Driving};
use crate::error::{Error, Result};
use crate::rng::{Purpose, Stream};
use crate::system::Vector;

/// The driving of an event-driven run and the index of its next application.
#[derive(Debug, Clone, Copy)]
pub(super) struct Kicks {
    driving: Driving,
    interval: f64,
    seed: u64,
    /// The next application is at `next * interval`.
    next: u64,
}

impl Kicks {
    pub(super) fn time_of_next(&self) -> f64 {
        self.next as f64 * self.interval
    }
}

impl<const D: usize> EventDriven<D> {
    /// Drives the gas from now on with `drive.driving` applied at the times k
    /// `drive.interval` (the first after the current time; None: freely cooling),
    /// white-noise kicks drawn from `drive.seed`. Fails (`interval`) unless
    /// 0 < interval < inf. Not part of the snapshot: set it again after a restore (the
    /// applications so far follow from the time). [`crate::Engine::set_driving`].
    pub(super) fn drive(&mut self, drive: Option<Drive>) -> Result<()> {
        let Some(Drive {
            driving,
            interval,
            seed,
        }) = drive
        else {
            self.kicks = None;
            return Ok(());
        };
        if self.field.is_some() {
            return Err(Error::out_of_range(
                "driving",
                "with gravity",
                "no driving in a gas with gravity",
            ));
        }
        let interval = match interval {
            Some(dt) if dt.is_finite() && dt > 0.0 => dt,
            other => {
                return Err(Error::out_of_range(
                    "interval",
                    other.map_or("none".to_string(), |dt| dt.to_string()),
                    "finite and > 0 (the event-driven engine drives at discrete times)",
                ))
            }
        };
        // The first k with k dt > now (an application at exactly now has been made).
        let mut next = (self.time / interval).floor().max(0.0) as u64;
        while next as f64 * interval <= self.time {
            next += 1;
        }
        self.kicks = Some(Kicks {
            driving,
            interval,
            seed,
            next,
        });
        Ok(())
    }

    /// The time of the next application of the driving, if driven.
    pub(super) fn next_kick(&self) -> Option<f64> {
        self.kicks.as_ref().map(Kicks::time_of_next)
    }

    /// Applies the driving at its next time (which must not be later than the next
    /// event) and predicts every event afresh.
    pub(super) fn kick(&mut self) {
        let Some(kicks) = self.kicks.as_mut() else {
            return;
        };
        let (driving, interval, seed, k) = (kicks.driving, kicks.interval, kicks.seed, kicks.next);
        kicks.next += 1;
        self.time = self.time.max(k as f64 * interval);
        match driving {
            Driving::WhiteNoise(noise) => {
                let mut rng = Stream::new(seed, Purpose::Driving, k, 0);
                let masses: Vec<f64> = self.particles.iter().map(|p| p.mass).collect();
                let kicks = noise.kicks::<D>(masses.into_iter(), interval, &mut rng);
                for (i, dv) in kicks.iter().enumerate() {
                    self.bring_to_now(i);
                    let v = &mut self.particles[i].velocity;
                    for k in 0..D {
                        v[k] += dv[k];
                    }
                }
            }
            Driving::Thermostat(thermostat) => {
                for i in 0..self.particles.len() {
                    self.bring_to_now(i);
                }
                // Under shear the peculiar velocities are scaled (about their mean).
                let (mean, temperature) = self.mean_and_temperature();
                let factor = thermostat.factor(temperature);
                for i in 0..self.particles.len() {
                    let p = &self.particles[i];
                    let flow = self.peculiar(&p.position, &p.velocity);
                    let v = &mut self.particles[i].velocity;
                    for k in 0..D {
                        // v = flow + V: the flow part v - V stays.
                        let u = flow[k];
                        v[k] = (v[k] - u) + mean[k] + factor * (u - mean[k]);
                    }
                }
            }
        }
        self.synchronize();
    }

    /// The mass-weighted mean velocity and the temperature about it (of the peculiar
    /// velocities under shear; every particle brought to now).
    fn mean_and_temperature(&self) -> (Vector<D>, f64) {
        if self.shear().is_some() {
            return self.peculiar_mean_and_temperature();
        }
        let mut mass = 0.0;
        let mut momentum: Vector<D> = [0.0; D];
        for p in &self.particles {
            mass += p.mass;
            for (m, v) in momentum.iter_mut().zip(&p.velocity) {
                *m += p.mass * v;
            }
        }
        let mean: Vector<D> = std::array::from_fn(|k| momentum[k] / mass);
        let spread: f64 = self
            .particles
            .iter()
            .map(|p| {
                p.mass
                    * (0..D)
                        .map(|k| (p.velocity[k] - mean[k]).powi(2))
                        .sum::<f64>()
            })
            .sum();
        (mean, spread / (self.particles.len() * D) as f64)
    }

    /// [`Self::mean_and_temperature`] of the peculiar velocities.
    #[cold]
    fn peculiar_mean_and_temperature(&self) -> (Vector<D>, f64) {
        let velocities: Vec<Vector<D>> = self
            .particles
            .iter()
            .map(|p| self.peculiar(&p.position, &p.velocity))
            .collect();
        let masses: Vec<f64> = self.particles.iter().map(|p| p.mass).collect();
        let mean = crate::observe::mass_weighted_mean(&velocities, &masses);
        let spread: f64 = velocities
            .iter()
            .zip(&masses)
            .map(|(v, m)| m * (0..D).map(|k| (v[k] - mean[k]).powi(2)).sum::<f64>())
            .sum();
        (mean, spread / (self.particles.len() * D) as f64)
    }
}
