//! Rods on a ring: the start of a ring of N rods (lengths repeated around the ring, equal
//! free gaps, Maxwellian centre-of-mass velocities with zero total momentum, optionally
//! thermal modes) and the [`Chain`] of Eq. (2) of Giese built from it. The same start
//! serves the event-driven + Monte Carlo gas of hard rods it is compared with.

mod energy;

pub use energy::{equipartition_share, translational_energy};

use crate::chain::{Chain, ChainConfig};
use crate::error::{non_negative, positive, Error, Result};
use rand::{Rng, SeedableRng};
use rand_distr::StandardNormal;
use rand_pcg::Pcg64;

/// Mixed into [`RingSetup::seed`] for the generator of the thermal modes.
const MODE_SEED: u64 = 0x5eed;

/// A ring of rods. Field names are the keys of the `[chain]` table of `haff rods chain`,
/// and errors of [`RingSetup::validate`] name them.
#[derive(Clone, Debug, PartialEq)]
pub struct RingSetup {
    /// Number of rods N, 2 ≤ N ≤ 100000.
    pub rods: usize,
    /// Rod lengths (> 0), repeated around the ring (e.g. two lengths: alternating rods).
    pub lengths: Vec<f64>,
    /// Internal modes per rod, 1 ≤ M ≤ 10000.
    pub modes: usize,
    /// Ring perimeter P (default: twice the total length of the rods); must exceed the
    /// total length.
    pub perimeter: Option<f64>,
    /// Inverse range α of the contact potential B e^{−α r}.
    pub alpha: f64,
    /// B of the contact potential (default: [`RingSetup::strength`]).
    pub strength: Option<f64>,
    /// Speed of sound c.
    pub sound_speed: f64,
    /// Mass density ρ (m_i = ρ l_i).
    pub density: f64,
    /// Initial translational temperature T: velocities ~ N(0, T/m_i), then the centre-of-mass
    /// velocity is subtracted.
    pub temperature: f64,
    /// Initial temperature of the modes (0: cold rods).
    pub bath_temperature: f64,
    /// Seed of the velocities (and, mixed with 0x5eed, of the modes).
    pub seed: u64,
    /// Step constant c_h of the contact integrator, 0 < c_h ≤ 1 (see [`ChainConfig::c_h`]).
    pub step: f64,
}

/// Centres and centre-of-mass velocities of the rods at t = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct RingState {
    pub positions: Vec<f64>,
    pub velocities: Vec<f64>,
}

impl RingSetup {
    /// Checks every parameter; errors name the field (`rods`, `lengths`, `perimeter`, ...)
    /// and its allowed range.
    pub fn validate(&self) -> Result<()> {
        if !(2..=100_000).contains(&self.rods) {
            return Err(Error::out_of_range("rods", self.rods, "2 <= N <= 100000"));
        }
        if !(1..=10_000).contains(&self.modes) {
            return Err(Error::out_of_range(
                "modes",
                self.modes,
                "1 <= modes <= 10000",
            ));
        }
        if self.lengths.is_empty() {
            return Err(Error::out_of_range("lengths", "[]", "at least one length"));
        }
        for l in &self.lengths {
            positive("lengths", *l)?;
        }
        for (name, x) in [
            ("alpha", self.alpha),
            ("sound_speed", self.sound_speed),
            ("density", self.density),
            ("temperature", self.temperature),
            ("step", self.step),
        ] {
            positive(name, x)?;
        }
        if self.step > 1.0 {
            return Err(Error::out_of_range("step", self.step, "0 < step <= 1"));
        }
        non_negative("bath_temperature", self.bath_temperature)?;
        let total: f64 = self.rod_lengths().iter().sum();
        let perimeter = self.perimeter();
        if !(perimeter.is_finite() && perimeter > total) {
            let allowed = format!("a finite number > {total} (the total length of the rods)");
            return Err(Error::out_of_range("perimeter", perimeter, allowed));
        }
        positive("strength", self.strength())?;
        Ok(())
    }

    /// The N rod lengths around the ring: [`RingSetup::lengths`] repeated.
    pub fn rod_lengths(&self) -> Vec<f64> {
        self.lengths
            .iter()
            .cycle()
            .take(self.rods)
            .copied()
            .collect()
    }

    /// The perimeter: as given, or twice the total length of the rods.
    pub fn perimeter(&self) -> f64 {
        let total: f64 = self.rod_lengths().iter().sum();
        self.perimeter.unwrap_or(2.0 * total)
    }

    /// Rod masses m_i = ρ l_i.
    pub fn masses(&self) -> Vec<f64> {
        self.rod_lengths()
            .iter()
            .map(|l| self.density * l)
            .collect()
    }

    /// B of the contact potential: as given, or m c²/(α l)² of the rod of mean length l
    /// and mass m = ρ l.
    pub fn strength(&self) -> f64 {
        let lengths = self.rod_lengths();
        let mean_length = lengths.iter().sum::<f64>() / lengths.len() as f64;
        let mass = self.density * mean_length;
        self.strength
            .unwrap_or(mass * self.sound_speed.powi(2) / (self.alpha * mean_length).powi(2))
    }

    /// The start: centres evenly spaced with equal free gaps (rod 0 at 0), velocities
    /// √(T/m_i) N(0, 1) from a PCG64 seeded with [`RingSetup::seed`], minus the
    /// centre-of-mass velocity (zero total momentum up to rounding).
    pub fn initial_state(&self) -> RingState {
        let lengths = self.rod_lengths();
        let gap = (self.perimeter() - lengths.iter().sum::<f64>()) / lengths.len() as f64;
        let mut x = 0.0;
        let positions = lengths
            .iter()
            .enumerate()
            .map(|(i, l)| {
                if i > 0 {
                    x += 0.5 * (lengths[i - 1] + l) + gap;
                }
                x
            })
            .collect();
        let mut rng = Pcg64::seed_from_u64(self.seed);
        let masses = self.masses();
        let mut velocities: Vec<f64> = masses
            .iter()
            .map(|m| (self.temperature / m).sqrt() * rng.sample::<f64, _>(StandardNormal))
            .collect();
        let momentum: f64 = velocities.iter().zip(&masses).map(|(v, m)| v * m).sum();
        let drift = momentum / masses.iter().sum::<f64>();
        velocities.iter_mut().for_each(|v| *v -= drift);
        RingState {
            positions,
            velocities,
        }
    }

    /// The chain of Eq. (2) of Giese from `start` (normally [`RingSetup::initial_state`]):
    /// one integration step for the whole chain (`global_step`), and, if
    /// `bath_temperature` > 0, Boltzmann modes from a PCG64 seeded with `seed ^ 0x5eed`.
    pub fn chain(&self, start: &RingState) -> Result<Chain> {
        self.validate()?;
        let mut chain = Chain::new(ChainConfig {
            lengths: self.rod_lengths(),
            modes: self.modes,
            alpha: self.alpha,
            b: self.strength(),
            c: self.sound_speed,
            rho: self.density,
            perimeter: self.perimeter(),
            positions: start.positions.clone(),
            velocities: start.velocities.clone(),
            c_h: self.step,
            global_step: true,
        })?;
        if self.bath_temperature > 0.0 {
            let mut rng = Pcg64::seed_from_u64(self.seed ^ MODE_SEED);
            chain.thermalize_modes(self.bath_temperature, &mut rng)?;
        }
        Ok(chain)
    }

    /// The share of the energy in the translation at equipartition,
    /// [`equipartition_share`]`(rods, modes)`.
    pub fn equipartition_share(&self) -> f64 {
        equipartition_share(self.rods, self.modes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup() -> RingSetup {
        RingSetup {
            rods: 5,
            lengths: vec![0.8, 1.3],
            modes: 3,
            perimeter: None,
            alpha: 2000.0,
            strength: None,
            sound_speed: 1.0,
            density: 1.0,
            temperature: 1e-4,
            bath_temperature: 0.0,
            seed: 7,
            step: 0.05,
        }
    }

    #[test]
    fn lengths_repeat_and_perimeter_defaults_to_twice_the_rods() {
        let s = setup();
        assert_eq!(s.rod_lengths(), vec![0.8, 1.3, 0.8, 1.3, 0.8]);
        assert!((s.perimeter() - 10.0).abs() < 1e-14);
        let given = RingSetup {
            perimeter: Some(7.5),
            ..setup()
        };
        assert_eq!(given.perimeter(), 7.5);
        assert_eq!(s.masses()[1], 1.3);
        // B = m c²/(α l)² of the mean rod, l = 5/5 = 1
        assert!((s.strength() - 1.0 / 4e6).abs() < 1e-20);
        let given = RingSetup {
            strength: Some(2.0),
            ..setup()
        };
        assert_eq!(given.strength(), 2.0);
    }

    #[test]
    fn positions_have_equal_gaps() {
        let s = RingSetup {
            perimeter: Some(8.0),
            ..setup()
        };
        let state = s.initial_state();
        let lengths = s.rod_lengths();
        let gap = (8.0 - 5.0) / 5.0;
        assert_eq!(state.positions[0], 0.0);
        for i in 0..5 {
            let next = if i == 4 {
                state.positions[0] + 8.0
            } else {
                state.positions[i + 1]
            };
            let free = next - state.positions[i] - 0.5 * (lengths[i] + lengths[(i + 1) % 5]);
            assert!((free - gap).abs() < 1e-12, "gap {i}: {free}");
        }
    }

    #[test]
    fn velocities_have_zero_momentum_and_the_temperature() {
        let s = RingSetup {
            rods: 20_000,
            ..setup()
        };
        let state = s.initial_state();
        let masses = s.masses();
        let p: f64 = state
            .velocities
            .iter()
            .zip(&masses)
            .map(|(v, m)| v * m)
            .sum();
        let scale: f64 = state
            .velocities
            .iter()
            .zip(&masses)
            .map(|(v, m)| (v * m).abs())
            .sum();
        assert!(p.abs() < 1e-13 * scale, "momentum {p} of {scale}");
        // N − 1 translational degrees of freedom about the centre of mass:
        // E_tr = (N − 1) T/2 with relative standard deviation √(2/(N − 1)) = 1 %.
        let n = s.rods as f64;
        let t = 2.0 * translational_energy(&state.velocities, &masses) / (n - 1.0);
        assert!((t / s.temperature - 1.0).abs() < 0.03, "{t}");
        // the seed decides the start
        assert_eq!(s.initial_state(), state);
        let other = RingSetup { seed: 8, ..s };
        assert_ne!(other.initial_state().velocities, state.velocities);
    }

    #[test]
    fn chain_from_the_start() {
        let s = setup();
        let state = s.initial_state();
        let chain = s.chain(&state).unwrap();
        assert_eq!(chain.n_rods(), 5);
        assert_eq!(chain.positions(), state.positions);
        assert_eq!(chain.velocities(), state.velocities);
        assert!(chain.modal_energies(2).iter().all(|&e| e == 0.0));
        let warm = RingSetup {
            bath_temperature: 1e-5,
            ..setup()
        };
        let chain = warm.chain(&state).unwrap();
        let bath: f64 = (0..5)
            .map(|i| chain.modal_energies(i).iter().sum::<f64>())
            .sum();
        assert!(bath > 0.0 && bath < 5.0 * 15.0 * 1e-5, "{bath}");
        // rods in contact at the start
        let tight = RingSetup {
            perimeter: Some(5.01),
            ..setup()
        };
        let e = tight.chain(&tight.initial_state()).unwrap_err();
        assert!(matches!(e, Error::Overlap { .. }), "{e}");
    }

    #[test]
    fn validate_names_the_field() {
        let cases: Vec<(RingSetup, &str)> = vec![
            (RingSetup { rods: 1, ..setup() }, "rods"),
            (
                RingSetup {
                    modes: 0,
                    ..setup()
                },
                "modes",
            ),
            (
                RingSetup {
                    lengths: vec![],
                    ..setup()
                },
                "lengths",
            ),
            (
                RingSetup {
                    lengths: vec![1.0, -1.0],
                    ..setup()
                },
                "lengths",
            ),
            (
                RingSetup {
                    alpha: f64::NAN,
                    ..setup()
                },
                "alpha",
            ),
            (
                RingSetup {
                    sound_speed: 0.0,
                    ..setup()
                },
                "sound_speed",
            ),
            (
                RingSetup {
                    density: -1.0,
                    ..setup()
                },
                "density",
            ),
            (
                RingSetup {
                    temperature: 0.0,
                    ..setup()
                },
                "temperature",
            ),
            (
                RingSetup {
                    step: 1.5,
                    ..setup()
                },
                "step",
            ),
            (
                RingSetup {
                    bath_temperature: -1.0,
                    ..setup()
                },
                "bath_temperature",
            ),
            (
                RingSetup {
                    perimeter: Some(5.0),
                    ..setup()
                },
                "perimeter",
            ),
            (
                RingSetup {
                    strength: Some(0.0),
                    ..setup()
                },
                "strength",
            ),
        ];
        assert!(setup().validate().is_ok());
        for (s, field) in cases {
            match s.validate() {
                Err(Error::OutOfRange { name, .. }) => assert_eq!(name, field),
                other => panic!("{field}: {other:?}"),
            }
        }
        let e = RingSetup {
            perimeter: Some(5.0),
            ..setup()
        }
        .validate()
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "perimeter = 5 is out of range: allowed a finite number > 5 (the total length of the rods)"
        );
    }
}
