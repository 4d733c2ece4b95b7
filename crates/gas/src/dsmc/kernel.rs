//! The collision kernel shared by all schemes: the exact majorant (thinning) process among a
//! group of particles — all of them, a block or a cell — over a window of time.
//!
//! A pair (i, j) with relative velocity g = v_i - v_j collides at rate
//! W_ij c_D |g| / V_group (see [`super::theory`]); W_ij = g2 sigma_ij^(D-1). With a bound s on
//! |v_k - c| for every particle k of the group and any fixed velocity c, |g| <= 2 s, so the
//! pairs' rates sum to at most Lambda = n (n - 1) / 2 * c_D W_max 2 s / V_group. Candidates
//! form a Poisson process of rate Lambda (exponential waiting times); each is a uniformly
//! random pair, accepted with probability W_ij |g| / (W_max 2 s). By the thinning theorem
//! (Lewis & Shedler 1979) the accepted candidates are exactly the collisions of the master
//! equation — no time-step error — as long as s stays a bound, which the kernel ensures by
//! raising s whenever a collision produces a faster particle (rates change only at candidate
//! times, so the process stays exact). This is Bird's majorant frequency scheme (Bird 1994,
//! *Molecular Gas Dynamics and the Direct Simulation of Gas Flows*, Sec. 11.1) with a true
//! majorant instead of a running estimate of max |g|.
//!
//! The impact direction e of an accepted pair is drawn with density proportional to
//! (e.g/|g|)^+ over the unit sphere: the rate of the pair at fixed e is (g.e)^+, and
//! integrating e out leaves c_D |g|. This is the same process as drawing e uniformly and
//! accepting with (g.e)^+ / u_max (a further thinning), with S_D / c_D = 2, pi, 4 times
//! fewer rejected candidates. The collision then follows the inelastic hard-sphere rule
//! with eps from the law at the normal impact speed g.e (Brilliantov & Pöschel 2004, Ch. 1).

use super::positive;
use super::species::Species;
use crate::engine::Counters;
use crate::rng::Stream;
use crate::shear::Virial;
use crate::system::{dot, Vector};
use rand_distr::{Beta, Distribution, Poisson};
use restitution::Restitution;

/// A particle record as the kernel sees it.
pub(crate) trait Record<const D: usize>: Copy + Send + Sync {
    /// Whether records carry a species (false: one species, index 0).
    const MIXED: bool;
    fn velocity(&self) -> &Vector<D>;
    fn velocity_mut(&mut self) -> &mut Vector<D>;
    fn species(&self) -> usize;
    /// Whether records carry an angular velocity (rough particles: [`Spun`]).
    const ROUGH: bool = false;
    /// The velocity and angular velocity, for the tangential half of a rough collision.
    #[inline(always)]
    fn spin_parts(&mut self) -> Option<(&mut Vector<D>, &mut [f64; 3])> {
        None
    }
}

/// The record of a monodisperse homogeneous gas: the velocity alone.
impl<const D: usize> Record<D> for Vector<D> {
    const MIXED: bool = false;
    #[inline]
    fn velocity(&self) -> &Vector<D> {
        self
    }
    #[inline]
    fn velocity_mut(&mut self) -> &mut Vector<D> {
        self
    }
    #[inline]
    fn species(&self) -> usize {
        0
    }
}

/// The record of a homogeneous mixture: velocity and species.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Tagged<const D: usize> {
    pub velocity: Vector<D>,
    pub species: u32,
}

/// The records that carry a species tag (`velocity` and `species` fields).
macro_rules! tagged_record {
    ($record:ident) => {
        impl<const D: usize> Record<D> for $record<D> {
            const MIXED: bool = true;
            #[inline]
            fn velocity(&self) -> &Vector<D> {
                &self.velocity
            }
            #[inline]
            fn velocity_mut(&mut self) -> &mut Vector<D> {
                &mut self.velocity
            }
            #[inline]
            fn species(&self) -> usize {
                self.species as usize
            }
        }
    };
}

tagged_record!(Tagged);

/// The species of a rough record: a tag (mixtures) or nothing ([`OneSpecies`]: a gas of
/// one species, whose records are 8 bytes smaller and need no lookup by species).
pub(crate) trait SpeciesTag: Copy + Send + Sync + PartialEq + std::fmt::Debug {
    const MIXED: bool;
    fn of(species: u32) -> Self;
    fn index(&self) -> usize;
}

impl SpeciesTag for u32 {
    const MIXED: bool = true;
    #[inline(always)]
    fn of(species: u32) -> Self {
        species
    }
    #[inline(always)]
    fn index(&self) -> usize {
        *self as usize
    }
}

/// The species of a record of a gas of one species: always the first.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct OneSpecies;

impl SpeciesTag for OneSpecies {
    const MIXED: bool = false;
    #[inline(always)]
    fn of(_species: u32) -> Self {
        OneSpecies
    }
    #[inline(always)]
    fn index(&self) -> usize {
        0
    }
}

/// The record of a homogeneous gas of rough particles: velocity, species (a tag for
/// mixtures, nothing for one species) and angular velocity (disks about z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Spun<const D: usize, S = u32> {
    pub velocity: Vector<D>,
    pub species: S,
    pub angular: [f64; 3],
}

impl<const D: usize, S: SpeciesTag> Record<D> for Spun<D, S> {
    const MIXED: bool = S::MIXED;
    const ROUGH: bool = true;
    #[inline]
    fn velocity(&self) -> &Vector<D> {
        &self.velocity
    }
    #[inline]
    fn velocity_mut(&mut self) -> &mut Vector<D> {
        &mut self.velocity
    }
    #[inline]
    fn species(&self) -> usize {
        self.species.index()
    }
    #[inline(always)]
    fn spin_parts(&mut self) -> Option<(&mut Vector<D>, &mut [f64; 3])> {
        Some((&mut self.velocity, &mut self.angular))
    }
}

/// The record of the spatial engine: position, velocity, species, and the particle's
/// place in the order it had when the engine was made or restored (its identity through
/// the sorts into cells, for the tracks of the mean-square displacement; it fills the
/// record's padding: 56 bytes in 3D with it or without).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Simulator<const D: usize> {
    pub position: Vector<D>,
    pub velocity: Vector<D>,
    pub species: u32,
    pub id: u32,
}

tagged_record!(Simulator);

/// Where the kernel counts what the collisions did.
pub(crate) trait Tally {
    fn counters(&mut self) -> &mut Counters;
    /// A collision of a particle of species `a` with one of species `b` (mixtures).
    #[inline(always)]
    fn pair(&mut self, _a: usize, _b: usize) {}
    /// The tensor virial, if summed.
    #[inline(always)]
    fn virial(&mut self) -> Option<&mut Virial> {
        None
    }
    /// A rough contact that slid (Walton's friction).
    #[inline(always)]
    fn slid(&mut self) {}
}

impl Tally for Counters {
    #[inline(always)]
    fn counters(&mut self) -> &mut Counters {
        self
    }
}

/// [`Counters`] and the collisions suffered by the particles of each species (a collision
/// counts once for each of its two particles), allocated at the first collision of a
/// mixture.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct SpeciesTally {
    pub counters: Counters,
    pub collisions: Vec<u64>,
    species: usize,
    /// The tensor virial of the collisions, if summed.
    pub virial: Option<Virial>,
    /// Rough contacts that slid.
    pub sliding: u64,
}

impl SpeciesTally {
    pub fn new(species: usize) -> Self {
        SpeciesTally {
            species,
            ..Default::default()
        }
    }
}

impl Tally for SpeciesTally {
    #[inline(always)]
    fn counters(&mut self) -> &mut Counters {
        &mut self.counters
    }
    #[inline(always)]
    fn pair(&mut self, a: usize, b: usize) {
        if self.collisions.is_empty() {
            self.collisions.resize(self.species, 0);
        }
        self.collisions[a] += 1;
        self.collisions[b] += 1;
    }
    #[inline(always)]
    fn virial(&mut self) -> Option<&mut Virial> {
        self.virial.as_mut()
    }
    #[inline(always)]
    fn slid(&mut self) {
        self.sliding += 1;
    }
}

/// Adds the per-species counts `more` to `total` (grown to their length).
pub(crate) fn add_counts(total: &mut Vec<u64>, more: &[u64]) {
    if total.len() < more.len() {
        total.resize(more.len(), 0);
    }
    total.iter_mut().zip(more).for_each(|(t, m)| *t += m);
}

/// The law and the species: everything a collision needs besides the two particles.
pub(crate) struct Collider<'a> {
    pub law: &'a dyn Restitution,
    pub species: &'a Species,
    /// A law per pair of species (row-major, in the order of `species`) for a mixture with
    /// a pairwise law ([`super::species::engine_laws`]); else `law` for every pair.
    pub pairs: Option<&'a [Box<dyn Restitution>]>,
    /// Rough particles: the tangential rule and each species' inertia factor (records
    /// of [`Spun`] only; others collide smoothly).
    pub rough: Option<Rough<'a>>,
}

/// The tangential half of the collisions of rough particles: the kick's constants of
/// each pair of species (row-major; one entry for one species).
#[derive(Clone, Copy)]
pub(crate) struct Rough<'a> {
    pub contacts: &'a [crate::rotation::Contact],
}

/// A window of the exact process: from `start` to `end` (may be infinite), at most
/// `max_collisions` accepted collisions.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Window {
    pub start: f64,
    pub end: f64,
    pub max_collisions: u64,
}

impl Collider<'_> {
    /// Runs the exact process among `group` through `window`, drawing the exponential
    /// waiting time of every candidate, so that it can stop at a collision. `pair_rate`
    /// (= c_D W_max / V_group) is the candidate rate per pair and unit of the speed bound
    /// 2 s; `bound` is s on entry (|v - reference| <= s for every particle) and the raised
    /// bound on exit. Returns the time reached: `window.end`, or the time of the last
    /// collision if `max_collisions` were reached first. Nothing happens (and `window.end`
    /// is returned) if the group cannot collide (fewer than 2 particles, or all at
    /// `reference`). (The homogeneous engine runs the speed-class process instead; this
    /// single-majorant process is its reference in the tests.)
    #[allow(clippy::too_many_arguments)]
    #[cfg_attr(not(test), allow(dead_code))]
    pub fn run<const D: usize, R: Record<D>>(
        &self,
        group: &mut [R],
        reference: &Vector<D>,
        pair_rate: f64,
        window: Window,
        bound: &mut f64,
        rng: &mut Stream,
        tally: &mut impl Tally,
    ) -> f64 {
        let n = group.len();
        let pairs = n as f64 * (n as f64 - 1.0) / 2.0;
        let mut rate = pairs * pair_rate * 2.0 * *bound;
        if n < 2 || !positive(rate) || window.max_collisions == 0 {
            return window.end;
        }
        let mut time = window.start;
        let mut collisions = 0;
        let mut candidates = 0;
        let reached = loop {
            let next = time + rng.exponential() / rate;
            if next > window.end {
                break window.end;
            }
            time = next;
            candidates += 1;
            if let Some(fastest) = self.candidate(group, reference, *bound, rng, tally) {
                if fastest > *bound * *bound {
                    *bound = fastest.sqrt();
                    rate = pairs * pair_rate * 2.0 * *bound;
                }
                collisions += 1;
                if collisions == window.max_collisions {
                    break time;
                }
            }
        };
        tally.counters().events += candidates;
        reached
    }

    /// Runs the exact process among `group` from `start` to `end` (finite), as
    /// [`Collider::run`] but without waiting times: the number of candidates in the window
    /// is Poisson(Lambda (end - start)) and, given it, their times are independent uniform
    /// points, of which only the order matters. Only when a collision raises the bound (and
    /// Lambda) is the time of that candidate drawn, as the k-th smallest of the k + m
    /// points left in the window (start' + (end - start') Beta(k, m + 1)); the m points
    /// after it are joined by Poisson((Lambda' - Lambda)(end - t)) new ones (independent
    /// increments and superposition of Poisson processes).
    #[allow(clippy::too_many_arguments)]
    pub fn run_for<const D: usize, R: Record<D>>(
        &self,
        group: &mut [R],
        reference: &Vector<D>,
        pair_rate: f64,
        (start, end): (f64, f64),
        bound: &mut f64,
        rng: &mut Stream,
        tally: &mut impl Tally,
    ) {
        let n = group.len();
        let pairs = n as f64 * (n as f64 - 1.0) / 2.0;
        let mut rate = pairs * pair_rate * 2.0 * *bound;
        if n < 2 || !positive(rate) || !positive(end - start) {
            return;
        }
        let mut from = start;
        let mut left = poisson(rate * (end - from), rng);
        let mut since = 0u64;
        tally.counters().events += left;
        while left > 0 {
            left -= 1;
            since += 1;
            let Some(fastest) = self.candidate(group, reference, *bound, rng, tally) else {
                continue;
            };
            if fastest > *bound * *bound {
                let at = from + (end - from) * order_statistic(since, left, rng);
                *bound = fastest.sqrt();
                let raised = pairs * pair_rate * 2.0 * *bound;
                let extra = poisson((raised - rate) * (end - at), rng);
                tally.counters().events += extra;
                left += extra;
                (from, since, rate) = (at, 0, raised);
            }
        }
    }

    /// One candidate: a uniformly random pair, accepted with probability
    /// ratio |g| / (2 s); if accepted, the collision. Returns the larger |v - reference|^2 of
    /// the pair after a collision, None for a rejected candidate.
    #[inline(always)]
    fn candidate<const D: usize, R: Record<D>>(
        &self,
        group: &mut [R],
        reference: &Vector<D>,
        bound: f64,
        rng: &mut Stream,
        tally: &mut impl Tally,
    ) -> Option<f64> {
        let (i, j) = rng.pair(group.len() as u32);
        // Only what the test needs of a candidate: the whole records (larger for rough
        // particles) are copied for a collision only.
        let g: Vector<D> = std::array::from_fn(|k| group[i].velocity()[k] - group[j].velocity()[k]);
        let g2 = dot(&g, &g);
        let u = rng.uniform() * 2.0 * bound;
        let ratio = if R::MIXED && self.species.len() > 1 {
            self.species
                .pair(group[i].species(), group[j].species())
                .ratio
        } else {
            1.0
        };
        if ratio * ratio * g2 <= u * u {
            return None;
        }
        let (mut a, mut b) = (group[i], group[j]);
        let fastest = self.collide(&mut a, &mut b, &g, g2, reference, rng, tally);
        (group[i], group[j]) = (a, b);
        Some(fastest)
    }

    /// The collision of a and b (relative velocity g = v_a - v_b, |g|^2 = g2 > 0) with a random
    /// impact direction. Returns the larger |v - reference|^2 of the two afterwards. (Also
    /// the collision of the speed-class process of the homogeneous engine.)
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn collide<const D: usize, R: Record<D>>(
        &self,
        a: &mut R,
        b: &mut R,
        g: &Vector<D>,
        g2: f64,
        reference: &Vector<D>,
        rng: &mut Stream,
        tally: &mut impl Tally,
    ) -> f64 {
        let e = impact_direction(g, g2.sqrt(), rng);
        let approach = dot(g, &e).max(0.0);
        let eps = match self.pairs {
            Some(laws) => laws[a.species() * self.species.len() + b.species()].eps(approach),
            None => self.law.eps(approach),
        };
        let pair = self.species.pair(a.species(), b.species());
        let kick = (1.0 + eps) * approach;
        let (kick_a, kick_b) = (kick * pair.share_a, kick * pair.share_b);
        let va = a.velocity_mut();
        for k in 0..D {
            va[k] -= kick_a * e[k];
        }
        let vb = b.velocity_mut();
        for k in 0..D {
            vb[k] += kick_b * e[k];
        }
        let counters = tally.counters();
        counters.collisions += 1;
        counters.energy_lost += 0.5 * pair.reduced * (1.0 - eps * eps) * approach * approach;
        counters.virial += kick * pair.reduced * pair.sigma;
        if let Some(virial) = tally.virial() {
            virial.add(kick * pair.reduced, pair.sigma, &e);
        }
        // One species: its collisions are the gas's (`super::species::by_species`).
        if R::MIXED && self.species.len() > 1 {
            tally.pair(a.species(), b.species());
        }
        if R::ROUGH {
            if let Some(rough) = &self.rough {
                self.rough_kick(rough, a, b, &e, kick * pair.reduced, pair.sigma, tally);
            }
        }
        let da: Vector<D> = std::array::from_fn(|k| a.velocity()[k] - reference[k]);
        let db: Vector<D> = std::array::from_fn(|k| b.velocity()[k] - reference[k]);
        dot(&da, &da).max(dot(&db, &db))
    }
}

impl Collider<'_> {
    /// The tangential impulse of the collision of a and b after their normal impulse
    /// `normal` along `e` (`crate::rotation::tangential_kick`), at contact distance
    /// `sigma`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn rough_kick<const D: usize, R: Record<D>>(
        &self,
        rough: &Rough,
        a: &mut R,
        b: &mut R,
        e: &Vector<D>,
        normal: f64,
        sigma: f64,
        tally: &mut impl Tally,
    ) {
        let contact = match rough.contacts {
            [one] => one,
            all => &all[a.species() * self.species.len() + b.species()],
        };
        let (Some((va, wa)), Some((vb, wb))) = (a.spin_parts(), b.spin_parts()) else {
            return;
        };
        let relative: Vector<D> = std::array::from_fn(|k| va[k] - vb[k]);
        let kick =
            crate::rotation::tangential_kick(contact, e, &relative, normal, (va, wa), (vb, wb));
        tally.counters().energy_lost += kick.energy_lost;
        if kick.sliding {
            tally.slid();
        }
        if let Some(virial) = tally.virial() {
            virial.add_tangential(sigma, e, &kick.to_j);
        }
    }
}

/// A Poisson(mean) count (rand_distr: inversion below 12, PTRS of Hörmann 1993 above).
fn poisson(mean: f64, rng: &mut Stream) -> u64 {
    match Poisson::new(mean) {
        Ok(p) => p.sample(rng) as u64,
        // mean = 0, or beyond 1.8e19 candidates (not reachable in practice).
        Err(_) if mean > 0.0 => u64::MAX / 2,
        Err(_) => 0,
    }
}

/// The k-th smallest of k + m independent uniform points on (0, 1): Beta(k, m + 1)
/// (1 - U^(1/(m+1)) for k = 1).
fn order_statistic(k: u64, m: u64, rng: &mut Stream) -> f64 {
    if k == 1 {
        return 1.0 - rng.uniform().powf(1.0 / (m as f64 + 1.0));
    }
    match Beta::new(k as f64, m as f64 + 1.0) {
        Ok(beta) => beta.sample(rng),
        Err(_) => k as f64 / (k + m) as f64,
    }
}

/// A unit vector e with density proportional to (e.g)^+ over the unit sphere, for g of norm
/// `speed` > 0: in 1D the direction of g; in 2D at angle theta to g with sin theta uniform
/// on [-1, 1] (density cos theta); in 3D the direction of g/|g| + s with s uniform on the
/// unit sphere (Marsaglia 1972), which has density proportional to cos theta: the point
/// g/|g| + s lies on a unit sphere through the origin, whose area element seen from the
/// origin is 4 cos theta dOmega.
#[inline]
fn impact_direction<const D: usize>(g: &Vector<D>, speed: f64, rng: &mut Stream) -> Vector<D> {
    let inverse = 1.0 / speed;
    let u: Vector<D> = std::array::from_fn(|k| g[k] * inverse);
    match D {
        1 => u,
        2 => {
            let s = 2.0 * rng.uniform() - 1.0;
            let c = (1.0 - s * s).sqrt();
            // u rotated by theta: (c u0 - s u1, c u1 + s u0).
            std::array::from_fn(|k| {
                if k == 0 {
                    c * u[0] - s * u[1]
                } else {
                    c * u[1] + s * u[0]
                }
            })
        }
        _ => loop {
            let (x, y) = (2.0 * rng.uniform() - 1.0, 2.0 * rng.uniform() - 1.0);
            let q = x * x + y * y;
            if q >= 1.0 {
                continue;
            }
            let r = 2.0 * (1.0 - q).sqrt();
            let s = [x * r, y * r, 1.0 - 2.0 * q];
            let h: Vector<D> = std::array::from_fn(|k| u[k] + s[k]);
            let h2 = dot(&h, &h);
            // h = 0 (s = -u) has probability zero; guard against round-off near it.
            if h2 > 1e-20 {
                let inverse = 1.0 / h2.sqrt();
                break std::array::from_fn(|k| h[k] * inverse);
            }
        },
    }
}

/// The largest |v - reference| in `group` (0 if empty).
pub(crate) fn speed_bound<const D: usize, R: Record<D>>(group: &[R], reference: &Vector<D>) -> f64 {
    group
        .iter()
        .map(|r| {
            let d: Vector<D> = std::array::from_fn(|k| r.velocity()[k] - reference[k]);
            dot(&d, &d)
        })
        .fold(0.0, f64::max)
        .sqrt()
}

/// Mass, momentum and spread (sum of m |v - mean|^2, about the group's own mean) of a
/// group of particles: what the temperature of a union of groups is made of.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Moments<const D: usize> {
    pub mass: f64,
    pub momentum: Vector<D>,
    pub spread: f64,
}

impl<const D: usize> Moments<D> {
    pub fn of<R: Record<D>>(group: &[R], species: &Species) -> Self {
        let mass: f64 = group.iter().map(|r| species.masses[r.species()]).sum();
        let momentum: Vector<D> = std::array::from_fn(|k| {
            group
                .iter()
                .map(|r| species.masses[r.species()] * r.velocity()[k])
                .sum()
        });
        let mean = scaled(&momentum, mass);
        let spread = group
            .iter()
            .map(|r| {
                let d: Vector<D> = std::array::from_fn(|k| r.velocity()[k] - mean[k]);
                species.masses[r.species()] * dot(&d, &d)
            })
            .sum();
        Moments {
            mass,
            momentum,
            spread,
        }
    }

    /// The mass-weighted mean velocity (zero for an empty group).
    pub fn mean(&self) -> Vector<D> {
        scaled(&self.momentum, self.mass)
    }
}

/// Mass, momentum and sum of m |v - center|^2 of a group, in one pass.
pub(crate) fn sums_about<const D: usize, R: Record<D>>(
    group: &[R],
    species: &Species,
    center: &Vector<D>,
) -> Moments<D> {
    let mut sums = Moments {
        mass: 0.0,
        momentum: [0.0; D],
        spread: 0.0,
    };
    for r in group {
        let m = species.masses[r.species()];
        let v = r.velocity();
        let d: Vector<D> = std::array::from_fn(|k| v[k] - center[k]);
        sums.mass += m;
        (0..D).for_each(|k| sums.momentum[k] += m * v[k]);
        sums.spread += m * dot(&d, &d);
    }
    sums
}

/// x / mass (zero for no mass).
pub(crate) fn scaled<const D: usize>(x: &Vector<D>, mass: f64) -> Vector<D> {
    if mass > 0.0 {
        std::array::from_fn(|k| x[k] / mass)
    } else {
        [0.0; D]
    }
}

/// Fisher–Yates shuffle with the group's own stream.
pub(crate) fn shuffle<T>(group: &mut [T], rng: &mut Stream) {
    for i in (1..group.len()).rev() {
        let j = rng.below(i as u64 + 1) as usize;
        group.swap(i, j);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Purpose;

    /// The impact directions have density proportional to cos theta on the hemisphere
    /// around g: <cos theta> = 2/3 in 3D, pi/4 in 2D.
    #[test]
    fn impact_directions_are_cosine_weighted() {
        let mut rng = Stream::new(9, Purpose::Exact, 0, 0);
        let g3 = [0.3, -1.2, 0.5];
        let speed3 = dot(&g3, &g3).sqrt();
        let (mut sum, n) = (0.0, 200_000);
        for _ in 0..n {
            let e = impact_direction(&g3, speed3, &mut rng);
            assert!((dot(&e, &e) - 1.0).abs() < 1e-12);
            let c = dot(&e, &g3) / speed3;
            assert!(c >= -1e-12);
            sum += c;
        }
        assert!(
            (sum / n as f64 - 2.0 / 3.0).abs() < 0.003,
            "{}",
            sum / n as f64
        );
        let g2 = [0.7, 0.2];
        let speed2 = dot(&g2, &g2).sqrt();
        let mut sum = 0.0;
        for _ in 0..n {
            let e = impact_direction(&g2, speed2, &mut rng);
            sum += dot(&e, &g2) / speed2;
        }
        let mean = sum / n as f64;
        assert!((mean - std::f64::consts::PI / 4.0).abs() < 0.003, "{mean}");
    }
}
