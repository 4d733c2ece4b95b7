//! Counted random streams of the engines (DSMC blocks and cells, the baths of the
//! event-driven engine).
//!
//! Every stream is a PCG-64 (128-bit multiplicative congruential generator with the XSL-RR
//! output, O'Neill 2014) whose state is a hash of (seed, purpose, step, index). A group of
//! particles (a block, a cell) in a step thus draws from its own stream whatever thread
//! runs it, which makes the parallel engines independent of the number of threads. A
//! stream counts its draws, so that the serial exact engine can restore its position by
//! jumping ahead (PCG's `advance`, Brown 1994) instead of storing the generator state.

use rand::RngCore;
use rand_distr::{Distribution, Exp1};
use rand_pcg::Pcg64Mcg;

/// What a stream is used for (part of its hash, so that streams never coincide).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Purpose {
    /// The one stream of the serial exact engine.
    Exact = 1,
    /// Collisions and the local shuffle of one block in one step.
    Block = 2,
    /// The lane offsets that re-mix the blocks in one step.
    Mixing = 3,
    /// Collisions in one cell of the spatial engine in one step.
    Cell = 4,
    /// The stochastic coefficient of restitution of the event-driven engine.
    Baths = 5,
    /// The white-noise kicks of the event-driven engine at one application.
    Driving = 6,
    /// The velocities thermal walls give the spheres that touch them.
    Walls = 7,
    /// The angular velocities of rough particles at the start.
    Spins = 8,
    /// The velocities of particles placed by a file without them.
    Velocities = 9,
}

/// A counted PCG-64 stream.
#[derive(Debug, Clone)]
pub(crate) struct Stream {
    rng: Pcg64Mcg,
    draws: u64,
}

/// The SplitMix64 finalizer (Steele, Lea & Flood 2014): a bijective 64-bit mixer.
#[inline]
fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl Stream {
    /// The stream of (seed, purpose, step, index), at its start.
    pub fn new(seed: u64, purpose: Purpose, step: u64, index: u64) -> Self {
        let h = splitmix(splitmix(splitmix(seed) ^ purpose as u64) ^ step);
        let high = splitmix(h ^ index);
        let low = splitmix(high ^ 0xD1B5_4A32_D192_ED03);
        Stream {
            rng: Pcg64Mcg::new(((high as u128) << 64) | low as u128),
            draws: 0,
        }
    }

    /// The stream of (seed, purpose, step, index) after `draws` draws.
    pub fn at(seed: u64, purpose: Purpose, step: u64, index: u64, draws: u64) -> Self {
        let mut s = Stream::new(seed, purpose, step, index);
        s.rng.advance(draws as u128);
        s.draws = draws;
        s
    }

    /// 64-bit outputs drawn so far.
    pub fn draws(&self) -> u64 {
        self.draws
    }

    /// Uniform in [0, 1) with 53 random bits.
    #[inline]
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A standard exponential variate (ziggurat of Marsaglia & Tsang 2000, `rand_distr`).
    #[inline]
    pub fn exponential(&mut self) -> f64 {
        Exp1.sample(self)
    }

    /// A standard normal variate (ziggurat, `rand_distr`).
    #[inline]
    pub fn normal(&mut self) -> f64 {
        rand_distr::StandardNormal.sample(self)
    }

    /// Uniform in [0, n) without bias (Lemire 2019, "Fast random integer generation in an
    /// interval", ACM TOMACS 29, 3).
    #[inline]
    pub fn below(&mut self, n: u64) -> u64 {
        let mut m = self.next_u64() as u128 * n as u128;
        if (m as u64) < n {
            let threshold = n.wrapping_neg() % n;
            while (m as u64) < threshold {
                m = self.next_u64() as u128 * n as u128;
            }
        }
        (m >> 64) as u64
    }

    /// Uniform in [0, n) from the 32-bit word `x` (Lemire), drawing anew only on rejection.
    #[inline]
    pub(crate) fn below_u32(&mut self, x: u32, n: u32) -> u32 {
        let mut m = x as u64 * n as u64;
        if (m as u32) < n {
            let threshold = n.wrapping_neg() % n;
            while (m as u32) < threshold {
                m = (self.next_u64() as u32) as u64 * n as u64;
            }
        }
        (m >> 32) as u32
    }

    /// A uniformly random unordered pair of distinct indices in [0, n), n >= 2, from one
    /// 64-bit draw (its two halves) in all but a fraction ~n/2^32 of the cases.
    #[inline]
    pub fn pair(&mut self, n: u32) -> (usize, usize) {
        let x = self.next_u64();
        let i = self.below_u32(x as u32, n);
        let j = self.below_u32((x >> 32) as u32, n - 1);
        (i as usize, (j + (j >= i) as u32) as usize)
    }
}

impl RngCore for Stream {
    #[inline]
    fn next_u32(&mut self) -> u32 {
        self.next_u64() as u32
    }

    #[inline]
    fn next_u64(&mut self) -> u64 {
        self.draws += 1;
        self.rng.next_u64()
    }

    fn fill_bytes(&mut self, dest: &mut [u8]) {
        rand_core_fill(self, dest)
    }
}

/// Fills bytes from whole 64-bit draws (each counted).
fn rand_core_fill(stream: &mut Stream, dest: &mut [u8]) {
    for chunk in dest.chunks_mut(8) {
        let bytes = stream.next_u64().to_le_bytes();
        chunk.copy_from_slice(&bytes[..chunk.len()]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn advance_restores_the_position() {
        let mut a = Stream::new(5, Purpose::Exact, 0, 0);
        for _ in 0..1000 {
            a.exponential();
            a.pair(7);
        }
        let mut b = Stream::at(5, Purpose::Exact, 0, 0, a.draws());
        assert_eq!(a.next_u64(), b.next_u64());
    }

    #[test]
    fn pairs_are_distinct_and_uniform() {
        let mut s = Stream::new(1, Purpose::Block, 3, 4);
        let n = 5;
        let mut counts = [[0u32; 5]; 5];
        for _ in 0..200_000 {
            let (i, j) = s.pair(n);
            assert_ne!(i, j);
            counts[i][j] += 1;
        }
        // 20 ordered pairs, 10 000 each in expectation (sd 100).
        for (i, row) in counts.iter().enumerate() {
            for (j, &c) in row.iter().enumerate() {
                if i != j {
                    assert!((c as f64 - 10_000.0).abs() < 500.0, "{i} {j}: {c}");
                }
            }
        }
    }

    #[test]
    fn streams_differ_by_every_key() {
        let first = |seed, step, index| Stream::new(seed, Purpose::Cell, step, index).next_u64();
        let base = first(1, 2, 3);
        assert_ne!(base, first(2, 2, 3));
        assert_ne!(base, first(1, 3, 3));
        assert_ne!(base, first(1, 2, 4));
        assert_ne!(base, Stream::new(1, Purpose::Block, 2, 3).next_u64());
    }
}
