//! The truncated delayed-recovery series eps = sum_{k=0}^{K} h_k v*^k (Eq. 7 of MP2011,
//! Eq. C7 of SP2008; h_0 = 1 as in Table V, i.e. the "1 +" of Eq. 7 is already h_0).
//!
//! [`Series::computed`] takes the h_k from the computer-algebra chain of `haff-series`
//! (any order, ~20 correct digits); [`Series::table_v`] the ten-digit values printed in
//! Table V of SP2008 (whose h_2 is wrong in the ninth digit: docs/errata.md).
//!
//! The series has a finite radius of convergence near v* ~ 1 and every truncation diverges
//! for large v* (Fig. 1 of MP2011): use it only for v* well below 1.

use crate::error::{Error, Result};
use std::sync::{Arc, Mutex};

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

/// Largest truncation order `Series::computed` accepts (the chain takes ~30 s there).
pub const MAX_COMPUTED_ORDER: usize = 100;

/// A truncated power series in v*.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    coefficients: Arc<[f64]>,
    /// Whether the coefficients are the printed ones of Table V.
    from_paper: bool,
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
            from_paper: false,
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
        let mut series = Series::new(&TABLE_V[..=order])?;
        series.from_paper = true;
        Ok(series)
    }

    /// h_0 ..= h_K from the computer-algebra chain (`haff-series`), computed once per
    /// process for the largest K asked (about 0.3 s for K = 20, 1 s for 40, 5 s for 60).
    pub fn computed(order: usize) -> Result<Self> {
        if order > MAX_COMPUTED_ORDER {
            return Err(Error::out_of_range(
                "series order K",
                order,
                "0..=100 for computed coefficients",
            ));
        }
        let h: Vec<f64> = computed_chain(order)[..=order]
            .iter()
            .map(|x| x.to_f64().value())
            .collect();
        Series::new(&h)
    }

    /// Whether the coefficients are those printed in Table V of SP2008.
    pub fn is_from_paper(&self) -> bool {
        self.from_paper
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

/// The largest chain order whose coefficients the computer algebra computes within
/// [`series::coefficients::MAX_SECONDS`] by its estimate (112): the bound of M + N of
/// [`crate::pade::Pade::computed`] and of `haff cor pade`.
pub fn max_chain_order() -> usize {
    use series::coefficients::{Settings, MAX_SECONDS};
    (2..=1000)
        .take_while(|&k| Settings::for_order(k).estimated_seconds() <= MAX_SECONDS)
        .last()
        .unwrap_or(2)
}

/// The high-precision h_0 ..= h_K (at least) from the chain, cached for the largest order
/// computed so far (shared by the computed series and Padé approximants).
pub(crate) fn computed_chain(order: usize) -> Arc<[series::power::Real]> {
    static CACHE: Mutex<Option<Arc<[series::power::Real]>>> = Mutex::new(None);
    let mut cache = CACHE
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    match cache.as_ref() {
        Some(h) if h.len() > order => h.clone(),
        _ => {
            let settings = series::coefficients::Settings::for_order(order.max(2));
            let h: Arc<[series::power::Real]> = series::coefficients::compute(settings).h.into();
            *cache = Some(h.clone());
            h
        }
    }
}
