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

/// A list of `[f64; D]` as a sequence of D-tuples: a JSON list of lists, and in binary
/// formats D numbers each without a length (no allocation per vector when read).
pub(crate) mod vectors {
    use super::*;
    use serde::de::{Error, SeqAccess, Visitor};
    use serde::ser::{SerializeSeq, SerializeTuple};
    use std::fmt;

    struct Tuple<'a, const D: usize>(&'a [f64; D]);

    impl<const D: usize> Serialize for Tuple<'_, D> {
        fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
            let mut t = s.serialize_tuple(D)?;
            for x in self.0 {
                t.serialize_element(x)?;
            }
            t.end()
        }
    }

    pub fn serialize<S: Serializer, const D: usize>(
        list: &[[f64; D]],
        s: S,
    ) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(list.len()))?;
        for v in list {
            seq.serialize_element(&Tuple(v))?;
        }
        seq.end()
    }

    struct VectorVisitor<const D: usize>;

    impl<'de, const D: usize> Visitor<'de> for VectorVisitor<D> {
        type Value = [f64; D];
        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            write!(f, "a vector of {D} components")
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<[f64; D], A::Error> {
            let mut v = [0.0; D];
            for (k, x) in v.iter_mut().enumerate() {
                *x = seq
                    .next_element()?
                    .ok_or_else(|| A::Error::invalid_length(k, &self))?;
            }
            Ok(v)
        }
    }

    struct Vector<const D: usize>([f64; D]);

    impl<'de, const D: usize> Deserialize<'de> for Vector<D> {
        fn deserialize<De: Deserializer<'de>>(d: De) -> Result<Self, De::Error> {
            d.deserialize_tuple(D, VectorVisitor::<D>).map(Vector)
        }
    }

    pub fn deserialize<'de, De: Deserializer<'de>, const D: usize>(
        d: De,
    ) -> Result<Vec<[f64; D]>, De::Error> {
        let list: Vec<Vector<D>> = Vec::deserialize(d)?;
        Ok(list.into_iter().map(|v| v.0).collect())
    }
}
