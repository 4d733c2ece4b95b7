//! A law per pair of particle kinds: a mixture whose species collide with different
//! restitutions (a constant per pair, or materials that differ between species). Kinds
//! are named by their radius and mass, the properties a collision partner has; engines
//! that know which kinds collide take the pair's law through [`Restitution::pairwise`].

use crate::error::{Error, Result};
use crate::law::Restitution;
use std::sync::Arc;

/// Laws for the pairs of `kinds` (symmetric: law(a, b) = law(b, a)).
#[derive(Debug, Clone)]
pub struct Pairwise {
    kinds: Vec<(f64, f64)>,
    /// Row-major, kinds x kinds.
    laws: Vec<Arc<dyn Restitution>>,
}

impl Pairwise {
    /// Kinds (radius, mass), distinct, and `laws[a][b]` for a <= b (the upper triangle is
    /// read; `laws` must be square with one row per kind).
    pub fn new(kinds: Vec<(f64, f64)>, laws: Vec<Vec<Box<dyn Restitution>>>) -> Result<Self> {
        let s = kinds.len();
        if s == 0 || laws.len() != s || laws.iter().any(|row| row.len() != s) {
            return Err(Error::out_of_range(
                "laws",
                laws.len(),
                &format!("a square matrix with one row per kind ({s})"),
            ));
        }
        for (a, ka) in kinds.iter().enumerate() {
            if kinds[..a].contains(ka) {
                return Err(Error::out_of_range(
                    "kinds",
                    format!("{ka:?}"),
                    "kinds that differ in radius or mass",
                ));
            }
        }
        let mut shared: Vec<Option<Arc<dyn Restitution>>> = vec![None; s * s];
        for (a, row) in laws.into_iter().enumerate() {
            for (b, law) in row.into_iter().enumerate().skip(a) {
                let law: Arc<dyn Restitution> = Arc::from(law);
                shared[a * s + b] = Some(law.clone());
                shared[b * s + a] = Some(law);
            }
        }
        Ok(Pairwise {
            kinds,
            laws: shared.into_iter().map(|l| l.expect("filled")).collect(),
        })
    }

    /// The kinds, (radius, mass) each.
    pub fn kinds(&self) -> &[(f64, f64)] {
        &self.kinds
    }

    /// The index of the kind of a particle of `radius` and `mass`.
    pub fn kind_of(&self, radius: f64, mass: f64) -> Option<usize> {
        self.kinds.iter().position(|&k| k == (radius, mass))
    }

    /// The law of a collision between kinds `a` and `b`.
    pub fn law(&self, a: usize, b: usize) -> &dyn Restitution {
        self.laws[a * self.kinds.len() + b].as_ref()
    }

    /// A copy of the law of kinds `a` and `b`.
    pub fn boxed(&self, a: usize, b: usize) -> Box<dyn Restitution> {
        self.law(a, b).box_clone()
    }
}

impl Restitution for Pairwise {
    /// The law of the first kind with itself: an engine must pick the pair's law through
    /// [`Restitution::pairwise`] (the engines of `gas` do, or refuse a pairwise law).
    fn eps(&self, speed: f64) -> f64 {
        self.law(0, 0).eps(speed)
    }
    fn describe(&self) -> String {
        let s = self.kinds.len();
        let pairs: Vec<String> = (0..s)
            .flat_map(|a| (a..s).map(move |b| (a, b)))
            .map(|(a, b)| format!("{a}-{b}: {}", self.law(a, b).describe()))
            .collect();
        format!("pairwise ({})", pairs.join("; "))
    }
    fn box_clone(&self) -> Box<dyn Restitution> {
        Box::new(self.clone())
    }
    fn pairwise(&self) -> Option<&Pairwise> {
        Some(self)
    }
}
