//! The truncated delayed-recovery series eps = sum_{k=0}^{K} h_k v*^k (Eq. 7 of MP2011,
//! Eq. C7 of SP2008; h_0 = 1 as in Table V, i.e. the "1 +" of Eq. 7 is already h_0).
//!
//! The series has a finite radius of convergence near v* ~ 1 and every truncation diverges
//! for large v* (Fig. 1 of MP2011): use it only for v* well below 1.

use crate::error::{Error, Result};
use std::sync::Arc;

/// h_0 .. h_20 as printed in Table V of SP2008 (ten significant digits). Their accuracy is
/// established in the tests against the exact law; they are replaced by coefficients
/// computed to any order in the computer-algebra issue.
pub const TABLE_V: [f64; 21] = [
    1.0,
    0.0,
    -1.153_448_856,
    0.0,
    0.798_266_558_1,
    0.266_666_666_7,
    -0.522_882_565_7,
    -0.461_379_542_4,
    0.348_742_673_7,
    0.452_351_049_6,
    -0.146_431_464_4,
    -0.367_728_299_2,
    -0.043_248_983_3,
    0.281_804_232_5,
    0.147_852_587_2,
    -0.179_442_059_0,
    -0.178_466_032_6,
    0.065_933_588_82,
    0.171_358_617_8,
    0.025_249_822_3,
    -0.137_923_498_6,
];

/// A truncated power series in v*.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    coefficients: Arc<[f64]>,
}

impl Series {
    /// The series from explicit coefficients h_0 .. h_K.
    pub fn new(coefficients: &[f64]) -> Result<Self> {
        if coefficients.is_empty() || coefficients.iter().any(|c| !c.is_finite()) {
            return Err(Error::parse(
                "series",
                "coefficients must be finite and non-empty",
            ));
        }
        Ok(Series {
            coefficients: coefficients.into(),
        })
    }

    /// Table V of SP2008 truncated after the term v*^K, K <= 20.
    pub fn table_v(order: usize) -> Result<Self> {
        if order >= TABLE_V.len() {
            return Err(Error::out_of_range(
                "series order K",
                order,
                "0..=20 (the orders printed in Table V of SP2008)",
            ));
        }
        Series::new(&TABLE_V[..=order])
    }

    /// The truncation order K (highest power).
    pub fn order(&self) -> usize {
        self.coefficients.len() - 1
    }

    pub fn coefficients(&self) -> &[f64] {
        &self.coefficients
    }

    /// Horner evaluation.
    #[inline]
    pub fn eval(&self, vstar: f64) -> f64 {
        self.coefficients
            .iter()
            .rev()
            .fold(0.0, |acc, &c| acc * vstar + c)
    }
}
