//! serde adapters for the engine states: JSON has no infinities, and serde derives no
//! impls for arrays of a generic length.

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A `[f64; D]` as a sequence of D numbers.
pub(crate) mod vector {
    use super::*;

    pub fn serialize<S: Serializer, const D: usize>(v: &[f64; D], s: S) -> Result<S::Ok, S::Error> {
        v.as_slice().serialize(s)
    }

    pub fn deserialize<'de, De: Deserializer<'de>, const D: usize>(
        d: De,
    ) -> Result<[f64; D], De::Error> {
        let v: Vec<f64> = Vec::deserialize(d)?;
        let n = v.len();
        v.try_into().map_err(|_| {
            serde::de::Error::custom(format!("a vector of {n} components in {D} dimensions"))
        })
    }
}

/// A list of times where -infinity ("never") is written as null.
pub(crate) mod never_as_null {
    use super::*;

    pub fn serialize<S: Serializer>(values: &[f64], s: S) -> Result<S::Ok, S::Error> {
        let v: Vec<Option<f64>> = values.iter().map(|x| x.is_finite().then_some(*x)).collect();
        v.serialize(s)
    }

    pub fn deserialize<'de, De: Deserializer<'de>>(d: De) -> Result<Vec<f64>, De::Error> {
        let v: Vec<Option<f64>> = Vec::deserialize(d)?;
        Ok(v.into_iter()
            .map(|x| x.unwrap_or(f64::NEG_INFINITY))
            .collect())
    }
}
