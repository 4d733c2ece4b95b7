//! Walls of a container: flat walls at the faces of the box, each on one side of one axis,
//! and what happens to a sphere that touches one. An axis with walls on both sides is
//! closed; the others stay periodic.
//!
//! A sphere of radius r touches the wall on the low side of axis k at x_k = r and the one on
//! the high side at x_k = L - r. The wall is infinitely massive; with u > 0 the normal
//! speed towards it and v_n' >= 0 the normal speed away from it after the contact:
//! - **elastic**: specular reflection, v_n' = u;
//! - **restitution**: v_n' = eps(u) u with eps from a law of [`restitution`] (the
//!   tangential velocity is kept: smooth spheres);
//! - **thermal** (Maxwell's diffuse wall at temperature T_w): the sphere leaves with a
//!   velocity drawn from the flux of a Maxwellian at rest at T_w through the wall: the
//!   tangential components Gaussian with variance T_w / m, the normal one with density
//!   (m v / T_w) exp(-m v^2 / (2 T_w)), drawn as sqrt(-2 (T_w / m) ln U) (Cercignani,
//!   *The Boltzmann Equation and Its Applications*, 1988, Sec. III.5).
//!
//! Each wall counts its contacts, the normal momentum the spheres gave it, m (u + v_n'),
//! and the energy it gave the gas, m (|v'|^2 - |v|^2) / 2 (negative where it takes energy).

mod motion;

pub use motion::{first_contact, Motion, Waveform};

use crate::error::{Error, Result};
use crate::rng::Stream;
use restitution::Restitution;
use serde::{Deserialize, Serialize};

/// Which face of an axis a wall closes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    Low,
    High,
}

impl Side {
    pub fn name(self) -> &'static str {
        match self {
            Side::Low => "low",
            Side::High => "high",
        }
    }
}

/// What a wall does to a sphere that touches it (see the [module](self) documentation).
pub enum WallKind {
    Elastic,
    Restitution(Box<dyn Restitution>),
    Thermal {
        temperature: f64,
    },
    /// A wall moving along its axis ([`Motion`]), bouncing spheres with the law's
    /// restitution in its own frame: with u > 0 the normal speed of approach relative to
    /// the wall and V its velocity into the box, v_n' = V + eps(u) u.
    Vibrating {
        law: Box<dyn Restitution>,
        motion: Motion,
    },
}

impl std::fmt::Debug for WallKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            WallKind::Elastic => write!(f, "Elastic"),
            WallKind::Restitution(_) => write!(f, "Restitution(law)"),
            WallKind::Thermal { temperature } => write!(f, "Thermal {{ {temperature} }}"),
            WallKind::Vibrating { motion, .. } => write!(f, "Vibrating {{ {motion:?} }}"),
        }
    }
}

/// A flat wall on one side of one axis.
#[derive(Debug)]
pub struct Wall {
    pub axis: usize,
    pub side: Side,
    pub kind: WallKind,
}

/// What a wall has done since the start of the run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WallTally {
    /// Contacts with spheres.
    pub collisions: u64,
    /// Normal momentum the spheres gave the wall.
    pub momentum: f64,
    /// Energy the wall gave the gas (negative where it took energy).
    pub energy: f64,
}

/// The lifts of a floor in gravity ([`Walls::set_min_speed`]): contacts that would have
/// left a sphere slower than the floor's least speed, and the energy the floor gave by
/// raising them to it (part of [`WallTally::energy`] too).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LiftTally {
    pub lifts: u64,
    pub energy: f64,
}

/// A wall and its tally, as an engine reports it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallRecord {
    pub axis: usize,
    pub side: Side,
    pub tally: WallTally,
    pub lift: LiftTally,
}

/// The walls' part of an engine's saved state: their tallies and the position of the
/// thermal walls' random stream.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WallsState {
    pub tallies: Vec<WallTally>,
    pub draws: u64,
    /// Per wall (empty before any lift; the last field: states without it read as empty).
    #[serde(default)]
    pub lifts: Vec<LiftTally>,
}

/// The walls of a container, with their tallies and the random stream of the thermal ones.
#[derive(Debug)]
pub struct Walls<const D: usize> {
    walls: Vec<Wall>,
    /// `at[k][side]`: the index in `walls` of the wall on that side of axis k.
    at: [[Option<usize>; 2]; D],
    tallies: Vec<WallTally>,
    /// The least normal speed each wall sends a sphere off with (0: none).
    min_speed: Vec<f64>,
    /// Whether any wall vibrates.
    vibrating: bool,
    lifts: Vec<LiftTally>,
    seed: u64,
    stream: Stream,
}

impl<const D: usize> Walls<D> {
    /// Walls of a box; fails if an axis beyond the dimension is named, a side is given
    /// twice, an axis has a wall on one side only, or a thermal wall's temperature is not
    /// positive and finite. `seed` draws the thermal walls' velocities.
    pub fn new(walls: Vec<Wall>, seed: u64) -> Result<Self> {
        let mut at = [[None; 2]; D];
        for (index, wall) in walls.iter().enumerate() {
            if wall.axis >= D {
                return Err(Error::out_of_range(
                    "wall.axis",
                    wall.axis,
                    format!("an axis of the {D}-dimensional box"),
                ));
            }
            let slot = &mut at[wall.axis][wall.side as usize];
            if slot.is_some() {
                return Err(Error::out_of_range(
                    "wall.side",
                    format!("{} twice on axis {}", wall.side.name(), wall.axis),
                    "one wall per side of an axis",
                ));
            }
            *slot = Some(index);
            if let WallKind::Thermal { temperature } = wall.kind {
                if !(temperature.is_finite() && temperature > 0.0) {
                    return Err(Error::out_of_range(
                        "wall.temperature",
                        temperature,
                        "a finite temperature > 0",
                    ));
                }
            }
            if let WallKind::Vibrating { motion, .. } = &wall.kind {
                for (name, x) in [
                    ("amplitude", motion.amplitude),
                    ("frequency", motion.frequency),
                ] {
                    if !(x.is_finite() && x > 0.0) {
                        return Err(Error::out_of_range(
                            format!("wall.{name}"),
                            x,
                            "a finite number > 0",
                        ));
                    }
                }
            }
        }
        if let Some(k) = (0..D).find(|&k| at[k][0].is_some() != at[k][1].is_some()) {
            return Err(Error::out_of_range(
                "wall.side",
                format!("one side of axis {k} only"),
                "walls on both sides of an axis (or none: periodic)",
            ));
        }
        let tallies = vec![WallTally::default(); walls.len()];
        Ok(Walls {
            vibrating: walls
                .iter()
                .any(|w| matches!(w.kind, WallKind::Vibrating { .. })),
            min_speed: vec![0.0; walls.len()],
            lifts: vec![LiftTally::default(); walls.len()],
            walls,
            at,
            tallies,
            seed,
            stream: Stream::new(seed, crate::rng::Purpose::Walls, 0, 0),
        })
    }

    /// Whether axis k is closed by walls.
    #[inline]
    pub fn closed(&self, k: usize) -> bool {
        self.at[k][0].is_some()
    }

    /// The wall on `side` of axis k, if any.
    #[inline]
    pub fn at(&self, k: usize, side: Side) -> Option<usize> {
        self.at[k][side as usize]
    }

    pub fn walls(&self) -> &[Wall] {
        &self.walls
    }

    pub fn tallies(&self) -> &[WallTally] {
        &self.tallies
    }

    /// Each wall with its tally, in the order they were given.
    pub fn records(&self) -> Vec<WallRecord> {
        self.walls
            .iter()
            .zip(self.tallies.iter().zip(&self.lifts))
            .map(|(w, (&tally, &lift))| WallRecord {
                axis: w.axis,
                side: w.side,
                tally,
                lift,
            })
            .collect()
    }

    /// The tallies and stream position, to be saved.
    pub fn state(&self) -> WallsState {
        WallsState {
            tallies: self.tallies.clone(),
            draws: self.stream.draws(),
            lifts: if self.lifts.iter().any(|l| l.lifts > 0) {
                self.lifts.clone()
            } else {
                Vec::new()
            },
        }
    }

    /// Sends spheres off wall `index` with a normal speed of at least `speed` (a floor in
    /// gravity: the resting rule, docs/walls.md).
    pub fn set_min_speed(&mut self, index: usize, speed: f64) {
        self.min_speed[index] = speed;
    }

    /// Takes up a saved state; fails if it holds another number of walls.
    pub fn set_state(&mut self, state: WallsState) -> Result<()> {
        if state.tallies.len() != self.walls.len() {
            return Err(Error::LengthMismatch {
                what: "saved wall tallies and walls".into(),
            });
        }
        if let Some(t) = state
            .tallies
            .iter()
            .find(|t| !(t.momentum.is_finite() && t.energy.is_finite()))
        {
            return Err(Error::out_of_range(
                "walls.tallies",
                format!("{t:?}"),
                "finite momentum and energy",
            ));
        }
        if !(state.lifts.is_empty() || state.lifts.len() == self.walls.len())
            || state
                .lifts
                .iter()
                .any(|l| !(l.energy.is_finite() && l.energy >= 0.0))
        {
            return Err(Error::out_of_range(
                "walls.lifts",
                format!("{:?}", state.lifts),
                "one finite energy >= 0 per wall",
            ));
        }
        self.tallies = state.tallies;
        self.lifts = if state.lifts.is_empty() {
            vec![LiftTally::default(); self.walls.len()]
        } else {
            state.lifts
        };
        self.stream = Stream::at(self.seed, crate::rng::Purpose::Walls, 0, 0, state.draws);
        Ok(())
    }

    /// Fails, naming the amplitude, if the vibrating walls of an axis sweep (2 A each) the
    /// box side along it (of `sides`) less `clearance` (the largest diameter; 0 for points).
    pub fn check_sweeps(&self, sides: &[f64; D], clearance: f64) -> Result<()> {
        for k in (0..D).filter(|&k| self.closed(k)) {
            let length = sides[k];
            let sweep = |side| {
                self.at(k, side)
                    .and_then(|index| self.motion(index).map(|m| (index, 2.0 * m.amplitude)))
            };
            let (low, high) = (sweep(Side::Low), sweep(Side::High));
            let swept = low.map_or(0.0, |s| s.1) + high.map_or(0.0, |s| s.1);
            if let Some((index, _)) = low.or(high).filter(|_| swept + clearance >= length) {
                return Err(Error::out_of_range(
                    format!("wall[{index}].amplitude"),
                    format!("walls sweeping {swept} of axis {k}"),
                    format!(
                        "sweeps (2 A per vibrating wall) below the box side minus the \
                         largest diameter, {}",
                        length - clearance
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The displacement into the box of the wall on `side` of axis k at time t (0 unless it
    /// vibrates).
    pub fn displacement(&self, k: usize, side: Side, t: f64) -> f64 {
        self.at(k, side)
            .and_then(|index| self.motion(index))
            .map_or(0.0, |m| m.displacement(t))
    }

    /// Whether a wall vibrates.
    #[inline]
    pub fn vibrates(&self) -> bool {
        self.vibrating
    }

    /// The motion of wall `index`, if it vibrates.
    pub fn motion(&self, index: usize) -> Option<Motion> {
        match &self.walls[index].kind {
            WallKind::Vibrating { motion, .. } => Some(*motion),
            _ => None,
        }
    }

    /// The contact of a sphere of mass m and velocity v with wall `index` at time t: sets
    /// the velocity after it and tallies the wall. False (nothing done) if the sphere does
    /// not approach the wall (a vibrating wall's early check).
    pub fn bounce(&mut self, index: usize, mass: f64, v: &mut [f64; D], t: f64) -> bool {
        let contact = contact_with(
            &self.walls[index],
            self.min_speed[index],
            mass,
            v,
            t,
            &mut self.stream,
        );
        match contact {
            Some(c) => {
                self.add(index, &c);
                true
            }
            None => false,
        }
    }

    /// What the contact of a sphere of mass m and velocity v with wall `index` at time t
    /// does, the velocity set to the one after it, thermal walls drawing from `stream`;
    /// None (nothing done) if the sphere does not approach a vibrating wall. The walls are
    /// left as they were: [`Self::add`] tallies it (engines that handle contacts in
    /// parallel sum them first).
    pub(crate) fn contact(
        &self,
        index: usize,
        mass: f64,
        v: &mut [f64; D],
        t: f64,
        stream: &mut Stream,
    ) -> Option<Contact> {
        contact_with(
            &self.walls[index],
            self.min_speed[index],
            mass,
            v,
            t,
            stream,
        )
    }

    /// Tallies a contact with wall `index`.
    pub fn add(&mut self, index: usize, contact: &Contact) {
        if let Some(energy) = contact.lift {
            let lift = &mut self.lifts[index];
            lift.lifts += 1;
            lift.energy += energy;
        }
        let tally = &mut self.tallies[index];
        tally.collisions += 1;
        tally.momentum += contact.momentum;
        tally.energy += contact.energy;
    }

    /// Tallies what wall `index` did in a step of an engine with soft contacts: contacts
    /// begun, the normal momentum it took and the energy it gave.
    pub fn add_work(&mut self, index: usize, begun: u64, momentum: f64, energy: f64) {
        let tally = &mut self.tallies[index];
        tally.collisions += begun;
        tally.momentum += momentum;
        tally.energy += energy;
    }

    /// Tallies a sum of contacts with wall `index` (an engine's step).
    pub fn add_sums(&mut self, index: usize, sums: &ContactSums) {
        let lift = &mut self.lifts[index];
        lift.lifts += sums.lifts;
        lift.energy += sums.lift_energy.value();
        let tally = &mut self.tallies[index];
        tally.collisions += sums.collisions;
        tally.momentum += sums.momentum.value();
        tally.energy += sums.energy.value();
    }
}

/// What one contact did ([`Walls::contact`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Normal momentum given to the wall.
    pub momentum: f64,
    /// Energy the wall gave the sphere.
    pub energy: f64,
    /// The energy of a lift, if the resting rule lifted the sphere.
    pub lift: Option<f64>,
}

/// Contacts with one wall summed exactly (the same sums in any order: threads, ranks).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ContactSums {
    pub collisions: u64,
    pub momentum: crate::exact_sum::ExactSum,
    pub energy: crate::exact_sum::ExactSum,
    pub lifts: u64,
    pub lift_energy: crate::exact_sum::ExactSum,
}

impl ContactSums {
    pub fn add(&mut self, c: &Contact) {
        self.collisions += 1;
        self.momentum.add(c.momentum);
        self.energy.add(c.energy);
        if let Some(e) = c.lift {
            self.lifts += 1;
            self.lift_energy.add(e);
        }
    }

    pub fn merge(&mut self, other: &ContactSums) {
        self.collisions += other.collisions;
        self.momentum.merge(&other.momentum);
        self.energy.merge(&other.energy);
        self.lifts += other.lifts;
        self.lift_energy.merge(&other.lift_energy);
    }
}

/// Takes up an engine's walls state `saved` from a check-point into `walls` (the walls
/// being set): fails if the check-point had walls and the engine is set without, or their
/// numbers differ.
pub(crate) fn take_up<const D: usize>(
    walls: Option<&mut Walls<D>>,
    saved: Option<WallsState>,
) -> Result<()> {
    match (walls, saved) {
        (Some(w), Some(saved)) => w.set_state(saved),
        (None, Some(_)) => Err(Error::out_of_range(
            "walls",
            "none",
            "the walls the check-point was saved with",
        )),
        _ => Ok(()),
    }
}

/// Checks gravity `g` against `walls` (finite components, along closed axes only) and
/// sends spheres off each floor (the wall g pulls towards) at least as fast as a bounce
/// `rest_height` high needs, sqrt(2 |g_k| h): the resting rule (docs/walls.md).
pub(crate) fn fit_gravity<const D: usize>(
    walls: Option<&mut Walls<D>>,
    g: &[f64; D],
    rest_height: f64,
) -> Result<()> {
    if g.iter().any(|x| !x.is_finite()) || !(rest_height.is_finite() && rest_height >= 0.0) {
        return Err(Error::out_of_range(
            "gravity",
            format!("{g:?}, rest height {rest_height}"),
            "finite components and a finite rest height >= 0",
        ));
    }
    let closed_only = "components along axes closed by walls only";
    let Some(walls) = walls else {
        return Err(Error::out_of_range(
            "gravity",
            format!("{g:?}"),
            closed_only,
        ));
    };
    if let Some(k) = (0..D).find(|&k| g[k] != 0.0 && !walls.closed(k)) {
        return Err(Error::out_of_range(
            "gravity",
            format!("{} along the periodic axis {k}", g[k]),
            closed_only,
        ));
    }
    for k in (0..D).filter(|&k| g[k] != 0.0) {
        let floor = if g[k] < 0.0 { Side::Low } else { Side::High };
        if let Some(index) = walls.at(k, floor) {
            walls.set_min_speed(index, (2.0 * g[k].abs() * rest_height).sqrt());
        }
    }
    Ok(())
}

/// [`Walls::contact`] for one wall whose least speed is `least`.
fn contact_with<const D: usize>(
    wall: &Wall,
    least: f64,
    mass: f64,
    v: &mut [f64; D],
    t: f64,
    stream: &mut Stream,
) -> Option<Contact> {
    let Wall { axis, side, kind } = wall;
    let k = *axis;
    // +1: the gas lies above the wall (low side).
    let inward = match side {
        Side::Low => 1.0,
        Side::High => -1.0,
    };
    // The wall's velocity into the box; speeds are relative to it.
    let wall = match kind {
        WallKind::Vibrating { motion, .. } => motion.velocity(t),
        _ => 0.0,
    };
    let relative = inward * v[k] - wall;
    if matches!(kind, WallKind::Vibrating { .. }) && relative >= 0.0 {
        return None;
    }
    let u = (-relative).max(0.0);
    let before: f64 = v.iter().map(|x| x * x).sum();
    let away = match kind {
        WallKind::Elastic => u,
        WallKind::Restitution(law) | WallKind::Vibrating { law, .. } => law.eps(u) * u,
        WallKind::Thermal { temperature } => {
            let scale = (temperature / mass).sqrt();
            for (j, x) in v.iter_mut().enumerate() {
                if j != k {
                    *x = scale * gaussian(stream);
                }
            }
            // 1 - U lies in (0, 1]: the logarithm is finite.
            scale * (-2.0 * (1.0 - stream.uniform()).ln()).sqrt()
        }
    };
    let (away, lift) = if away < least {
        (least, Some(0.5 * mass * (least * least - away * away)))
    } else {
        (away, None)
    };
    v[k] = inward * (wall + away);
    let after: f64 = v.iter().map(|x| x * x).sum();
    Some(Contact {
        momentum: mass * (u + away),
        energy: 0.5 * mass * (after - before),
        lift,
    })
}

/// The first time s > 0 at which a sphere at x moving with v along an axis with
/// acceleration g (≠ 0) reaches `low` or `high` (low <= x <= high, up to rounding), and
/// whether that is `high`. Cancellation-free roots of g s²/2 + v s + x − b = 0: against
/// the pull (a distance d, upward speed u > 0) s = 2 d / (u + sqrt(u² − 2 a d)) when
/// u² >= 2 a d (a = |g|), else along it (a distance e): s = (u + S) / a for u >= 0 and
/// s = 2 e / (S − u) for u < 0, S = sqrt(u² + 2 a e) (always a root).
pub(crate) fn fall_exit(x: f64, v: f64, g: f64, low: f64, high: f64) -> (f64, bool) {
    let a = g.abs();
    // "Up" is against the pull.
    let (up_distance, down_distance, u) = if g < 0.0 {
        (high - x, x - low, v)
    } else {
        (x - low, high - x, -v)
    };
    let (d, e) = (up_distance.max(0.0), down_distance.max(0.0));
    let reach = u * u - 2.0 * a * d;
    if u > 0.0 && reach >= 0.0 {
        return (2.0 * d / (u + reach.sqrt()), g < 0.0);
    }
    let s = (u * u + 2.0 * a * e).sqrt();
    let time = if u >= 0.0 {
        (u + s) / a
    } else {
        2.0 * e / (s - u)
    };
    (time, g > 0.0)
}

/// A standard normal variate (Box–Muller's cosine branch: one per two uniforms, so that
/// the stream's position depends on the contacts alone).
fn gaussian(stream: &mut Stream) -> f64 {
    let u1 = 1.0 - stream.uniform();
    let u2 = stream.uniform();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

#[cfg(test)]
mod tests {
    use super::fall_exit;

    /// Oracle: the roots of the quadratic by the textbook formula, where it is accurate.
    #[test]
    fn fall_exits_are_the_quadratics_roots() {
        // Thrown up from 0.2 in [0, 1] at 1 with g = -1: reaches 1 if 1 >= 2 * 0.8? No:
        // falls back to 0 at s = 1 + sqrt(1 + 0.4).
        let (s, up) = fall_exit(0.2, 1.0, -1.0, 0.0, 1.0);
        assert!(!up && (s - (1.0 + 1.4f64.sqrt())).abs() < 1e-15, "{s}");
        // Fast enough: reaches 1 at the smaller root of s^2/2 - 2 s + 0.8 = 0.
        let (s, up) = fall_exit(0.2, 2.0, -1.0, 0.0, 1.0);
        assert!(
            up && (s - (2.0 - (4.0f64 - 1.6).sqrt())).abs() < 1e-15,
            "{s}"
        );
        // Falling: s^2/2 + 0.5 s - 0.2 = 0.
        let (s, up) = fall_exit(0.2, -0.5, -1.0, 0.0, 1.0);
        assert!(
            !up && (s - (-0.5 + (0.25f64 + 0.4).sqrt())).abs() < 1e-15,
            "{s}"
        );
        // Mirror: g > 0 pulls towards high.
        let (s, up) = fall_exit(0.8, -1.0, 1.0, 0.0, 1.0);
        assert!(up && (s - (1.0 + 1.4f64.sqrt())).abs() < 1e-15, "{s}");
        // Just crossed upwards at the face: back after 2 v / g.
        let (s, up) = fall_exit(0.0, 0.3, -2.0, 0.0, 1.0);
        assert!(!up && (s - 0.3).abs() < 1e-16, "{s}");
        // At rest on the low face: 0, downwards.
        assert_eq!(fall_exit(0.0, 0.0, -1.0, 0.0, 1.0), (0.0, false));
    }
}
