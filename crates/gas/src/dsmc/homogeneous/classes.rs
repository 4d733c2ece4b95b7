//! Speed classes: a tighter majorant for the exact process of [`crate::dsmc::kernel`], used by
//! [`crate::dsmc::Scheme::Exact`] over all particles. (Inside the blocks of
//! [`crate::dsmc::Scheme::Blocks`] it halves the candidates but doubles the time: each block
//! would be re-sorted every step; docs/performance.md.)
//!
//! The kernel bounds every pair's |g| by 2 s with s the largest |v - c| of the group, so a
//! Maxwellian group of a few thousand particles draws about 4 candidates per collision
//! (2 s / <|g|> = 2 x 4.5 / 2.26 in units of sqrt(T/m)). Here every particle gets its own
//! bound instead.
//!
//! **Classes.** The speeds s_i = |v_i - c| about a fixed velocity c are binned into
//! [`CLASSES`] = K classes of width w: class a < K - 1 holds the speeds below (a + 1) w that
//! `floor(s / w)` puts there (rounded up a class if round-off put s above (a + 1) w), the top
//! class K - 1 all faster ones. Particle i's bound is b_i = m_i w with the integer multiplier
//! m_i = a + 1 in class a < K - 1 and m_i = M in the top class, M >= K the smallest integer
//! with M w >= s_max (s_max the running bound of the kernel: the largest speed at the last
//! sort, raised whenever a collision produces a faster particle). So s_i <= b_i for every
//! particle at every moment: both partners of a collision are re-classified at once
//! ([`Classes::reclassify`]), and `tests::class_bounds_hold_after_every_collision` checks
//! it.
//!
//! **The process and its exactness.** About c the triangle inequality gives
//! |g_ij| = |(v_i - c) - (v_j - c)| <= s_i + s_j <= b_i + b_j. Give pair {i, j} the
//! candidate rate P (b_i + b_j) with P = c_D W_max / V (the kernel's `pair_rate`); the
//! total is Lambda = P sum_{i<j} (b_i + b_j) = P (n - 1) sum_i b_i = P (n - 1) w M_tot, with
//! M_tot = sum_i m_i an integer, because every particle is in n - 1 pairs. A candidate is
//! drawn as particle i with probability m_i / M_tot, then j uniform among the other n - 1:
//! P({i, j}) = (m_i + m_j) / ((n - 1) M_tot), so the candidate rate of {i, j} is
//! Lambda P({i, j}) = P (b_i + b_j) (the class-pair selection with probability
//! n_a n_b (b_a + b_b) collapses to this K-vector choice). Accepting with
//! W_ij |g| / (W_max (b_i + b_j)) <= 1 leaves pair {i, j} colliding at rate
//! c_D W_ij |g| / V: the master equation's rate. Between candidates the state, and with it
//! Lambda, is constant, so waiting times exponential with the current Lambda make the
//! candidates a Markov jump process whose accepted jumps have exactly the master equation's
//! rates and whose rejected jumps change nothing (thinning, Lewis & Shedler 1979; the
//! majorant may change after every candidate because it is a function of the state). The
//! process is therefore the one of [`crate::dsmc::kernel`] (the same Markov process, other random
//! numbers), with Lambda / (collision rate) -> 2 (<s> + w/2) / <|g|> = (2 x 1.596 + 0.2) /
//! 2.257 = 1.50 candidates per collision for a Maxwellian and w = 0.2 sqrt(T/m), against
//! the bound sqrt(2) of the triangle inequality itself (w -> 0).
//!
//! **Drawing i with probability m_i / M_tot.** The records are kept sorted by class (class
//! a in `start[a] .. start[a+1]`). Particle i lies in the "levels" l = 0 .. m_i - 1; level
//! l < K - 1 holds exactly the classes >= l, the contiguous range `start[l] .. n`, and the
//! levels K - 1 .. M - 1 hold the top class. A uniform integer r < M_tot = sum of the level
//! sizes is located by a scan over the levels and gives i = start[l] + (r - offset of l):
//! each particle is hit by m_i of the M_tot values.
//!
//! **Round-off.** Bounds are compared in floating point exactly as the kernel compares its
//! 2 s: an acceptance probability can exceed 1 only by round-off of |g| (~1e-16).

use crate::dsmc::kernel::{Collider, Record, Tally, Window};
use crate::dsmc::positive;
use crate::rng::Stream;
use crate::system::{dot, Vector};
use rand::RngCore;

/// Speed classes K (the top one open-ended): with [`CLASS_WIDTH`] they reach 6.2 thermal
/// speeds, beyond the fastest of 10^7 Maxwellian particles (about 6).
pub(crate) const CLASSES: usize = 32;

/// Class width w in units of the thermal speed sqrt(T / m_min): about 1.50 candidates per
/// collision in a Maxwellian gas (see the [module](self) documentation); 0.1 would give
/// 1.46 for twice the class moves per collision.
pub(crate) const CLASS_WIDTH: f64 = 0.2;

/// The smallest width relative to the bound: w >= s_max / 2^20, so that a wrong
/// temperature (a forged check-point) cannot make the multipliers overflow; it then only
/// costs candidates.
const MIN_WIDTH_OF_BOUND: f64 = 1.0 / (1u64 << 20) as f64;

/// The class width for a gas at `temperature` whose lightest mass is `min_mass` and whose
/// speeds about the reference are at most `bound` (> 0).
pub(crate) fn class_width(temperature: f64, min_mass: f64, bound: f64) -> f64 {
    let thermal = CLASS_WIDTH * (temperature / min_mass).sqrt();
    if thermal.is_finite() {
        thermal.max(bound * MIN_WIDTH_OF_BOUND)
    } else {
        bound * MIN_WIDTH_OF_BOUND
    }
}

/// The classes of a group of records sorted by class, with their multipliers.
#[derive(Debug, Clone)]
pub(crate) struct Classes {
    width: f64,
    inverse: f64,
    /// Class a holds the records `start[a] .. start[a + 1]`; `start[K]` = n.
    start: [usize; CLASSES + 1],
    /// The multiplier M of the top class.
    top: u64,
    /// M_tot, the sum of all multipliers.
    total: u64,
    /// The running bound s_max on |v - reference|.
    bound: f64,
}

impl Classes {
    /// Sorts `group` by class in place (an American-flag sort: deterministic, and the
    /// identity on a group already sorted by the same classes, which lets a restored run
    /// rebuild the classes of a saved one) and sets `class` to the class of each record.
    /// `bound` (> 0) bounds every |v - reference|, `width` (> 0) is the class width.
    pub fn sort<const D: usize, R: Record<D>>(
        group: &mut [R],
        class: &mut Vec<u8>,
        reference: &Vector<D>,
        width: f64,
        bound: f64,
    ) -> Classes {
        let (classes, counts) = Classes::count(group, class, reference, width, bound);
        let mut next = classes.start;
        for a in 0..CLASSES {
            while next[a] < classes.start[a + 1] {
                let p = next[a];
                let c = class[p] as usize;
                if c == a {
                    next[a] += 1;
                } else {
                    let q = next[c];
                    group.swap(p, q);
                    class.swap(p, q);
                    next[c] += 1;
                }
            }
        }
        debug_assert_eq!(counts.iter().sum::<usize>(), group.len());
        classes
    }

    /// The classes of the records of `group` (into `class`), their ranges once sorted,
    /// multipliers and M_tot, and the count of each class.
    fn count<const D: usize, R: Record<D>>(
        group: &[R],
        class: &mut Vec<u8>,
        reference: &Vector<D>,
        width: f64,
        bound: f64,
    ) -> (Classes, [usize; CLASSES]) {
        let mut classes = Classes {
            width,
            inverse: 1.0 / width,
            start: [0; CLASSES + 1],
            top: 0,
            total: 0,
            bound,
        };
        classes.top = classes.top_multiplier(bound);
        class.clear();
        let mut counts = [0usize; CLASSES];
        class.extend(group.iter().map(|r| {
            let a = classes.class_of(speed2(r, reference));
            counts[a] += 1;
            a as u8
        }));
        for (a, &count) in counts.iter().enumerate() {
            classes.start[a + 1] = classes.start[a] + count;
        }
        classes.total = counts
            .iter()
            .enumerate()
            .map(|(a, &count)| count as u64 * classes.multiplier(a))
            .sum();
        (classes, counts)
    }

    pub fn bound(&self) -> f64 {
        self.bound
    }

    /// The class of a speed s = sqrt(`s2`): floor(s / w), one more if round-off left
    /// s > (a + 1) w, the top class for all beyond.
    #[inline]
    fn class_of(&self, s2: f64) -> usize {
        let s = s2.sqrt();
        let a = (s * self.inverse) as usize;
        if a >= CLASSES - 1 {
            return CLASSES - 1;
        }
        if s > (a + 1) as f64 * self.width {
            (a + 1).min(CLASSES - 1)
        } else {
            a
        }
    }

    /// The multiplier m of class a: the class's bound is m w.
    #[inline]
    fn multiplier(&self, a: usize) -> u64 {
        if a == CLASSES - 1 {
            self.top
        } else {
            a as u64 + 1
        }
    }

    /// The bound m w of class a.
    #[cfg(test)]
    fn class_bound(&self, a: usize) -> f64 {
        self.multiplier(a) as f64 * self.width
    }

    /// The smallest M >= K with M w >= s.
    fn top_multiplier(&self, s: f64) -> u64 {
        let mut m = (s * self.inverse).ceil() as u64;
        if s > m as f64 * self.width {
            m += 1;
        }
        m.max(CLASSES as u64)
    }

    /// A candidate pair: i with probability m_i / M_tot, j uniform among the others.
    #[inline]
    fn pick(&self, n: usize, rng: &mut Stream) -> (usize, usize) {
        let x = rng.next_u64();
        let (r, j) = if self.total <= u32::MAX as u64 {
            (
                rng.below_u32(x as u32, self.total as u32) as usize,
                rng.below_u32((x >> 32) as u32, (n - 1) as u32) as usize,
            )
        } else {
            (
                rng.below(self.total) as usize,
                rng.below_u32((x >> 32) as u32, (n - 1) as u32) as usize,
            )
        };
        let i = self.locate(n, r);
        (i, j + (j >= i) as usize)
    }

    /// The record hit by r < M_tot in the levels (see the [module](self) documentation).
    #[inline]
    fn locate(&self, n: usize, mut r: usize) -> usize {
        for &first in &self.start[..CLASSES - 1] {
            let size = n - first;
            if r < size {
                return first + r;
            }
            r -= size;
        }
        let first = self.start[CLASSES - 1];
        first + r % (n - first)
    }

    /// Re-classifies the records at `i` and `j` after their collision, raising the bound
    /// (and M) if one of them is faster than it. The records move to their classes'
    /// ranges (swaps with the records at class boundaries).
    #[inline(always)]
    fn reclassify<const D: usize, R: Record<D>>(
        &mut self,
        group: &mut [R],
        class: &mut [u8],
        reference: &Vector<D>,
        i: usize,
        j: usize,
    ) {
        let (mut i, mut j) = (i, j);
        let to = self.class_after(&group[i], reference);
        i = self.relocate(group, class, i, to, &mut j);
        let to = self.class_after(&group[j], reference);
        self.relocate(group, class, j, to, &mut i);
    }

    /// The class of a record whose velocity has just changed, raising the bound (and M,
    /// and M_tot with it) first if it is faster than the bound.
    #[inline]
    fn class_after<const D: usize, R: Record<D>>(&mut self, r: &R, reference: &Vector<D>) -> usize {
        let s2 = speed2(r, reference);
        if s2 > self.bound * self.bound {
            self.bound = s2.sqrt();
            let top = self.top_multiplier(self.bound);
            if top > self.top {
                let members = (self.start[CLASSES] - self.start[CLASSES - 1]) as u64;
                self.total += (top - self.top) * members;
                self.top = top;
            }
        }
        self.class_of(s2)
    }

    /// Moves the record at p to class `to`, one class boundary at a time, and returns its
    /// new place; `watch` follows the other partner of the collision if a swap moves it.
    fn relocate<R>(
        &mut self,
        group: &mut [R],
        class: &mut [u8],
        p: usize,
        to: usize,
        watch: &mut usize,
    ) -> usize {
        let from = class[p] as usize;
        if from == to {
            return p;
        }
        self.total = self.total + self.multiplier(to) - self.multiplier(from);
        let mut p = p;
        let mut swap = |p: usize, q: usize| {
            group.swap(p, q);
            class.swap(p, q);
            if *watch == p {
                *watch = q;
            } else if *watch == q {
                *watch = p;
            }
        };
        if to > from {
            for c in from..to {
                // The last record of class c changes places with ours, which becomes the
                // first of class c + 1.
                let last = self.start[c + 1] - 1;
                swap(p, last);
                self.start[c + 1] -= 1;
                p = last;
            }
        } else {
            for c in (to + 1..=from).rev() {
                let first = self.start[c];
                swap(p, first);
                self.start[c] += 1;
                p = first;
            }
        }
        class[p] = to as u8;
        p
    }
}

/// |v - reference|^2 of a record.
#[inline(always)]
fn speed2<const D: usize, R: Record<D>>(r: &R, reference: &Vector<D>) -> f64 {
    let d: Vector<D> = std::array::from_fn(|k| r.velocity()[k] - reference[k]);
    dot(&d, &d)
}

/// The frame of a uniform shear flow for the exact process (`run_classes_sheared`): the
/// records hold the peculiar velocities W at the time `anchor`; at time t they are
/// V = S(t - anchor) W, V_x = W_x - a (t - anchor) W_y, the rest unchanged (the solution of
/// dV_x/dt = -a V_y between collisions).
#[derive(Debug, Clone, Copy)]
pub struct ShearFrame {
    pub rate: f64,
    pub anchor: f64,
}

impl Collider<'_> {
    /// Runs the exact process among `group` (sorted by `classes`, `class` its records'
    /// classes) through `window` with the class majorants, drawing the exponential waiting
    /// time of every candidate. `pair_rate` = c_D W_max / V_group, as for
    /// [`Collider::run`]. Returns the time reached: `window.end`, or the time of the last
    /// collision if `max_collisions` were reached first. The group stays sorted and
    /// `classes` bounds every speed on return.
    #[allow(clippy::too_many_arguments)]
    pub fn run_classes<const D: usize, R: Record<D>>(
        &self,
        group: &mut [R],
        class: &mut [u8],
        classes: &mut Classes,
        reference: &Vector<D>,
        pair_rate: f64,
        window: Window,
        rng: &mut Stream,
        tally: &mut impl Tally,
    ) -> f64 {
        let frame = ShearFrame {
            rate: 0.0,
            anchor: window.start,
        };
        self.run_classes_in::<false, D, R>(
            group, class, classes, reference, pair_rate, window, rng, tally, frame,
        )
    }

    /// [`Self::run_classes`] in the frame of a uniform shear flow (the records hold W at
    /// `frame.anchor`, D >= 2). |g(t)| = |S(τ) g_W| <= (1 + |a| τ) |g_W|: the class
    /// majorants of the W's times 1 + |a| (window.end - anchor) bound every pair's rate
    /// through the window, and a candidate is kept with probability |g(t)| over that bound
    /// (thinning: exact). A kept pair collides with its velocities at t, mapped back to W.
    #[allow(clippy::too_many_arguments)]
    pub fn run_classes_sheared<const D: usize, R: Record<D>>(
        &self,
        group: &mut [R],
        class: &mut [u8],
        classes: &mut Classes,
        reference: &Vector<D>,
        pair_rate: f64,
        window: Window,
        rng: &mut Stream,
        tally: &mut impl Tally,
        frame: ShearFrame,
    ) -> f64 {
        self.run_classes_in::<true, D, R>(
            group, class, classes, reference, pair_rate, window, rng, tally, frame,
        )
    }

    /// The process of [`Self::run_classes`]; `SHEARED`: in `frame` (compiled apart, so the
    /// unsheared loop is the one it always was).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn run_classes_in<const SHEARED: bool, const D: usize, R: Record<D>>(
        &self,
        group: &mut [R],
        class: &mut [u8],
        classes: &mut Classes,
        reference: &Vector<D>,
        pair_rate: f64,
        window: Window,
        rng: &mut Stream,
        tally: &mut impl Tally,
        frame: ShearFrame,
    ) -> f64 {
        let n = group.len();
        let mut unit = pair_rate * (n as f64 - 1.0) * classes.width;
        let inflation = 1.0 + frame.rate.abs() * (window.end - frame.anchor);
        if SHEARED {
            unit *= inflation;
        }
        if n < 2 || !positive(unit) || window.max_collisions == 0 {
            return window.end;
        }
        let mixed = R::MIXED && self.species.len() > 1;
        let mut time = window.start;
        let mut collisions = 0;
        let mut candidates = 0;
        let reached = loop {
            let next = time + rng.exponential() / (unit * classes.total as f64);
            if next > window.end {
                break window.end;
            }
            time = next;
            candidates += 1;
            let (i, j) = classes.pick(n, rng);
            // The whole records (larger for rough particles) are copied for a collision only.
            let mut g: Vector<D> =
                std::array::from_fn(|k| group[i].velocity()[k] - group[j].velocity()[k]);
            let shift = frame.rate * (time - frame.anchor);
            if SHEARED {
                g[0] -= shift * g[1];
            }
            let g2 = dot(&g, &g);
            let reach =
                classes.multiplier(class[i] as usize) + classes.multiplier(class[j] as usize);
            let mut u = rng.uniform() * classes.width * reach as f64;
            if SHEARED {
                u *= inflation;
            }
            let ratio = if mixed {
                self.species
                    .pair(group[i].species(), group[j].species())
                    .ratio
            } else {
                1.0
            };
            if ratio * ratio * g2 <= u * u {
                continue;
            }
            let (mut a, mut b) = (group[i], group[j]);
            if SHEARED {
                for r in [&mut a, &mut b] {
                    let v = r.velocity_mut();
                    v[0] -= shift * v[1];
                }
            }
            self.collide(&mut a, &mut b, &g, g2, reference, rng, tally);
            if SHEARED {
                for r in [&mut a, &mut b] {
                    let v = r.velocity_mut();
                    v[0] += shift * v[1];
                }
            }
            (group[i], group[j]) = (a, b);
            classes.reclassify(group, class, reference, i, j);
            collisions += 1;
            if collisions == window.max_collisions {
                break time;
            }
        };
        tally.counters().events += candidates;
        reached
    }
}

#[cfg(test)]
#[path = "classes_tests.rs"]
mod tests;
