//! A fast law equal to the exact one: piecewise Chebyshev interpolation of ln eps in
//! u = ln v*, generated at first use from the exact solution of Eq. (9) of MP2011.
//!
//! Why this form: ln eps is a smooth, slowly varying function of ln v* over the whole range
//! (eps -> 1 - 1.1534 v*^2 for small v*, eps -> (3/2)^(2/3) v*^(-10/3) for large v* with the
//! improved criterion), so short polynomial pieces reach round-off accuracy, and an absolute
//! error in ln eps is a relative error in eps. From a physical speed, ln v* = (ln beta)/2 +
//! (ln v)/10 costs one logarithm, where a Padé approximant needs a power v^(1/10).
//!
//! Outside the tabulated range [1e-4, 1e4] the law uses the leading small-v* term
//! 1 + h_2 v*^2 (error h_4 v*^4 < 1e-16) and the large-v* power law fitted at the end of the
//! table, whose exponent is the exact asymptotic one (-10/3 improved, -10 naive).

use crate::exact::{solve, Criterion};
use std::sync::OnceLock;

/// Tabulated range of v*.
pub const VSTAR_MIN: f64 = 1e-4;
pub const VSTAR_MAX: f64 = 1e4;
/// Polynomial degree and target width in u = ln v* of each piece.
const DEGREE: usize = 11;
/// ln eps of the naive criterion bends sharply near v* ~ 1.7 and needs shorter pieces.
const PIECE_WIDTH_IMPROVED: f64 = 0.25;
const PIECE_WIDTH_NAIVE: f64 = 0.0625;

/// Piecewise polynomial table of ln eps(u).
#[derive(Debug)]
pub struct Table {
    criterion: Criterion,
    u_min: f64,
    u_max: f64,
    inv_width: f64,
    /// Monomial coefficients in t in [-1, 1] for each piece, lowest power first.
    pieces: Vec<[f64; DEGREE + 1]>,
    /// eps ~ 1 + h2 v*^2 below the table.
    h2: f64,
    /// eps ~ tail_coefficient * v*^tail_exponent above the table.
    tail_coefficient: f64,
    tail_exponent: f64,
}

impl Table {
    fn generate(criterion: Criterion) -> Table {
        let u_min = VSTAR_MIN.ln();
        let u_max = VSTAR_MAX.ln();
        let target_width = match criterion {
            Criterion::Improved => PIECE_WIDTH_IMPROVED,
            Criterion::Naive => PIECE_WIDTH_NAIVE,
        };
        let count = ((u_max - u_min) / target_width).ceil() as usize;
        let width = (u_max - u_min) / count as f64;
        let ln_eps = |u: f64| {
            solve(u.exp(), criterion)
                .expect("exact law inside its validated range")
                .eps
                .ln()
        };
        let pieces = (0..count)
            .map(|i| {
                let centre = u_min + (i as f64 + 0.5) * width;
                chebyshev_monomials(|t| ln_eps(centre + 0.5 * width * t))
            })
            .collect();
        let h2 = ln_eps(u_min).exp_m1() / (VSTAR_MIN * VSTAR_MIN);
        let tail_exponent = match criterion {
            Criterion::Improved => -10.0 / 3.0,
            Criterion::Naive => -10.0,
        };
        let tail_coefficient = ln_eps(u_max).exp() / VSTAR_MAX.powf(tail_exponent);
        Table {
            criterion,
            u_min,
            u_max,
            inv_width: 1.0 / width,
            pieces,
            h2,
            tail_coefficient,
            tail_exponent,
        }
    }

    /// eps at ln v* = u (inside the table).
    #[inline]
    fn eval_log(&self, u: f64) -> f64 {
        let x = (u - self.u_min) * self.inv_width;
        let i = (x as usize).min(self.pieces.len() - 1);
        let t = 2.0 * (x - i as f64) - 1.0;
        let c = &self.pieces[i];
        let mut acc = c[DEGREE];
        for k in (0..DEGREE).rev() {
            acc = acc.mul_add(t, c[k]);
        }
        acc.exp()
    }

    pub fn criterion(&self) -> Criterion {
        self.criterion
    }
}

/// Chebyshev interpolant of f on [-1, 1] at DEGREE + 1 Chebyshev nodes, converted to
/// monomial coefficients (well conditioned for this low degree on [-1, 1]).
fn chebyshev_monomials(f: impl Fn(f64) -> f64) -> [f64; DEGREE + 1] {
    let n = DEGREE + 1;
    let angle = |j: usize| std::f64::consts::PI * (j as f64 + 0.5) / n as f64;
    let values: Vec<f64> = (0..n).map(|j| f(angle(j).cos())).collect();
    let cheb: Vec<f64> = (0..n)
        .map(|k| {
            let s: f64 = (0..n)
                .map(|j| values[j] * (k as f64 * angle(j)).cos())
                .sum();
            s * 2.0 / n as f64 * if k == 0 { 0.5 } else { 1.0 }
        })
        .collect();
    // T_0 = 1, T_1 = t, T_{k+1} = 2 t T_k - T_{k-1}, as monomial coefficient arrays.
    let mut out = [0.0; DEGREE + 1];
    let (mut prev, mut cur) = ([0.0; DEGREE + 1], [0.0; DEGREE + 1]);
    prev[0] = 1.0;
    cur[1] = 1.0;
    for (k, ck) in cheb.iter().enumerate() {
        let tk = if k == 0 { prev } else { cur };
        if k >= 1 {
            for (o, t) in out.iter_mut().zip(tk.iter()) {
                *o += ck * t;
            }
            let mut next = [0.0; DEGREE + 1];
            for p in 0..DEGREE {
                next[p + 1] += 2.0 * cur[p];
            }
            for p in 0..=DEGREE {
                next[p] -= prev[p];
            }
            prev = cur;
            cur = next;
        } else {
            out[0] += ck;
        }
    }
    out
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

/// The fast law: a handle to a process-wide table (built on first use: about 0.5 s for
/// the improved criterion, a few seconds for the naive one).
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

    /// eps at scaled speed v* >= 0.
    #[inline]
    pub fn eval(&self, vstar: f64) -> f64 {
        if vstar < VSTAR_MIN {
            1.0 + self.table.h2 * vstar * vstar
        } else if vstar > VSTAR_MAX {
            self.table.tail_coefficient * vstar.powf(self.table.tail_exponent)
        } else {
            self.table.eval_log(vstar.ln())
        }
    }

    /// eps at ln v* = u, without forming v* (for callers that hold logarithms).
    #[inline]
    pub fn eval_log(&self, u: f64) -> f64 {
        let t = self.table;
        if u >= t.u_min && u <= t.u_max {
            t.eval_log(u)
        } else {
            self.eval(u.exp())
        }
    }
}
