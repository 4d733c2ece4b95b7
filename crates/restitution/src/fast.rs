//! A fast law equal to the exact one to ~1e-13, at the cost of a Padé approximant.
//!
//! Two tables, both generated at first use from the exact solution of Eq. (9) of MP2011:
//! 1. the *generator*: ln eps as piecewise Chebyshev interpolants in u = ln v* on
//!    [2^-14, 2^14] (ln eps is smooth and slowly varying in ln v*: eps -> 1 - 1.1534 v*^2 for
//!    small v*, eps -> (3/2)^(2/3) v*^(-10/3) for large v* with the improved criterion, and
//!    an absolute error in ln eps is a relative error in eps);
//! 2. the *evaluator*: eps itself as piecewise polynomials on binary-exponent buckets of v*
//!    ([`crate::bucket`]), 8 (naive: 16) per octave on [2^-14, 2^14), sampled from the generator. It needs
//!    neither a logarithm nor an exponential: bit operations and one Horner scheme.
//!
//! Outside [2^-14, 2^14] the law uses the leading small-v* term 1 + h_2 v*^2 (error
//! h_4 v*^4 < 2e-16) and the large-v* power law with the exact asymptotic exponent (-10/3
//! improved, -10 naive) and its prefactor fitted at the end of the table.

use crate::bucket::{chebyshev_monomials, BucketTable, DEGREE};
use crate::exact::{solve, Criterion};
use std::sync::OnceLock;

/// Range of the generator table.
const GENERATOR_MIN: f64 = 1.0 / 16384.0;
const GENERATOR_MAX: f64 = 16384.0;
/// Range of the evaluator table: v* in [2^MIN_EXPONENT, 2^MAX_EXPONENT).
const MIN_EXPONENT: i32 = -14;
const MAX_EXPONENT: i32 = 14;
/// Buckets per octave of v*: 2^SUB_BITS (twice as many for the sharper naive knee).
const SUB_BITS_IMPROVED: u32 = 3;
const SUB_BITS_NAIVE: u32 = 4;
/// The evaluator's range.
pub const VSTAR_MIN: f64 = 1.0 / 16384.0;
pub const VSTAR_MAX: f64 = 16384.0;
/// Generator pieces (degree `bucket::DEGREE`) start this wide in u = ln v* and are halved
/// up to `MAX_REFINEMENT` times until their error is below `PIECE_TOLERANCE` (the naive
/// ln eps bends sharply near v* ~ 1.7 and needs short pieces there).
const INITIAL_PIECE_WIDTH: f64 = 1.0;
const MAX_REFINEMENT: u32 = 6;
const PIECE_TOLERANCE: f64 = 1e-13;

/// The generator: ln eps(u) as piecewise polynomials in u = ln v*, with pieces halved
/// until the interpolant matches the exact law between its nodes.
struct Generator {
    /// (left end, width, coefficients in t in [-1, 1]) sorted by left end.
    pieces: Vec<(f64, f64, [f64; DEGREE + 1])>,
}

impl Generator {
    fn new(criterion: Criterion) -> Self {
        let ln_eps = |u: f64| {
            solve(u.exp(), criterion)
                .expect("exact law inside its validated range")
                .eps
                .ln()
        };
        let (u_min, u_max) = (GENERATOR_MIN.ln(), GENERATOR_MAX.ln());
        let count = ((u_max - u_min) / INITIAL_PIECE_WIDTH).ceil() as usize;
        let width = (u_max - u_min) / count as f64;
        let mut pieces = Vec::new();
        for i in 0..count {
            Self::refine(&ln_eps, u_min + i as f64 * width, width, 0, &mut pieces);
        }
        Generator { pieces }
    }

    /// Appends the interpolant on [left, left + width], halving it while its error at three
    /// off-node points exceeds `PIECE_TOLERANCE` (absolute in ln eps = relative in eps).
    fn refine(
        ln_eps: &impl Fn(f64) -> f64,
        left: f64,
        width: f64,
        depth: u32,
        out: &mut Vec<(f64, f64, [f64; DEGREE + 1])>,
    ) {
        let at = |t: f64| left + 0.5 * (t + 1.0) * width;
        let c = chebyshev_monomials(|t| ln_eps(at(t)));
        let error = [-0.77, 0.13, 0.61]
            .iter()
            .map(|&t| (horner(&c, t) - ln_eps(at(t))).abs())
            .fold(0.0, f64::max);
        if error > PIECE_TOLERANCE && depth < MAX_REFINEMENT {
            Self::refine(ln_eps, left, 0.5 * width, depth + 1, out);
            Self::refine(ln_eps, left + 0.5 * width, 0.5 * width, depth + 1, out);
        } else {
            out.push((left, width, c));
        }
    }

    /// eps at v* in the generator's range.
    fn eps(&self, vstar: f64) -> f64 {
        let u = vstar.ln();
        let i = self.pieces.partition_point(|p| p.0 <= u).saturating_sub(1);
        let (left, width, c) = &self.pieces[i];
        horner(c, 2.0 * (u - left) / width - 1.0).exp()
    }
}

fn horner(c: &[f64], t: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ck| acc * t + ck)
}

/// The evaluator: eps on binary buckets of v*, and the two tails.
#[derive(Debug)]
pub struct Table {
    criterion: Criterion,
    buckets: BucketTable,
    /// eps ~ 1 + h2 v*^2 below the table.
    h2: f64,
    /// eps ~ tail_coefficient * v*^tail_exponent above the table.
    tail_coefficient: f64,
    tail_exponent: f64,
}

impl Table {
    fn generate(criterion: Criterion) -> Table {
        let generator = Generator::new(criterion);
        let sub_bits = match criterion {
            Criterion::Improved => SUB_BITS_IMPROVED,
            Criterion::Naive => SUB_BITS_NAIVE,
        };
        let buckets = BucketTable::new(MIN_EXPONENT, MAX_EXPONENT, sub_bits, |v| generator.eps(v));
        let h2 = (generator.eps(GENERATOR_MIN) - 1.0) / (GENERATOR_MIN * GENERATOR_MIN);
        let tail_exponent = match criterion {
            Criterion::Improved => -10.0 / 3.0,
            Criterion::Naive => -10.0,
        };
        let tail_coefficient = generator.eps(VSTAR_MAX) / VSTAR_MAX.powf(tail_exponent);
        Table {
            criterion,
            buckets,
            h2,
            tail_coefficient,
            tail_exponent,
        }
    }

    pub fn criterion(&self) -> Criterion {
        self.criterion
    }

    /// Memory of the evaluator table.
    pub fn bytes(&self) -> usize {
        self.buckets.bytes()
    }
}

fn table(criterion: Criterion) -> &'static Table {
    static IMPROVED: OnceLock<Table> = OnceLock::new();
    static NAIVE: OnceLock<Table> = OnceLock::new();
    let cell = match criterion {
        Criterion::Improved => &IMPROVED,
        Criterion::Naive => &NAIVE,
    };
    cell.get_or_init(|| Table::generate(criterion))
}

/// The fast law: a handle to a process-wide table (built on first use: about 0.2 s for
/// the improved criterion, about 2 s for the naive one).
#[derive(Clone, Copy)]
pub struct Fast {
    table: &'static Table,
}

impl std::fmt::Debug for Fast {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Fast({})", self.table.criterion)
    }
}

impl Fast {
    /// The fast law for a criterion; the first call per criterion builds the table.
    pub fn new(criterion: Criterion) -> Self {
        Fast {
            table: table(criterion),
        }
    }

    pub fn criterion(&self) -> Criterion {
        self.table.criterion
    }

    /// Memory of the evaluator table, in bytes.
    pub fn table_bytes(&self) -> usize {
        self.table.bytes()
    }

    /// eps at scaled speed v* >= 0.
    #[inline]
    pub fn eval(&self, vstar: f64) -> f64 {
        let t = self.table;
        if t.buckets.contains(vstar) {
            t.buckets.eval(vstar)
        } else {
            self.outside_table(vstar)
        }
    }

    /// eps at every v* of `vstar` into `out`, bit-identical to [`Fast::eval`], in one loop
    /// with the table's constants in registers (`haff bench cor`: `fast[]`).
    pub fn eval_slice(&self, vstar: &[f64], out: &mut [f64]) {
        self.table
            .buckets
            .eval_slice(vstar, out, |v| self.outside_table(v));
    }

    /// eps beyond the evaluator's range: the small-v* term or the large-v* power law.
    #[inline]
    fn outside_table(&self, vstar: f64) -> f64 {
        let t = self.table;
        if vstar < VSTAR_MIN {
            1.0 + t.h2 * vstar * vstar
        } else {
            t.tail_coefficient * vstar.powf(t.tail_exponent)
        }
    }
}
