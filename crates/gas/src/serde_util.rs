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

/// The sides of a box: one number for a cube (exactly the bytes of the cubic boxes every
/// version before had, so their check-points stay readable and unchanged); otherwise a
/// list of D numbers in human-readable formats (JSON) and, in binary ones (postcard: no
/// optional fields in the middle of a state), a NaN marker followed by the D sides. An
/// older haff reads the marker as a side that is not a positive number and refuses it.
pub(crate) mod box_sides {
    use super::*;
    use serde::de::{Error, SeqAccess, Visitor};
    use serde::ser::SerializeTuple;
    use std::fmt;

    pub fn serialize<S: Serializer, const D: usize>(
        sides: &[f64; D],
        s: S,
    ) -> Result<S::Ok, S::Error> {
        if sides.iter().all(|&l| l == sides[0]) {
            return s.serialize_f64(sides[0]);
        }
        if s.is_human_readable() {
            return sides.as_slice().serialize(s);
        }
        let mut t = s.serialize_tuple(D + 1)?;
        t.serialize_element(&f64::NAN)?;
        for x in sides {
            t.serialize_element(x)?;
        }
        t.end()
    }

    /// JSON: one side, or a list of D.
    struct ReadableVisitor<const D: usize>;

    impl<'de, const D: usize> Visitor<'de> for ReadableVisitor<D> {
        type Value = [f64; D];
        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            write!(f, "a box side, or a list of {D} sides")
        }
        fn visit_f64<E: Error>(self, v: f64) -> Result<[f64; D], E> {
            Ok([v; D])
        }
        fn visit_i64<E: Error>(self, v: i64) -> Result<[f64; D], E> {
            Ok([v as f64; D])
        }
        fn visit_u64<E: Error>(self, v: u64) -> Result<[f64; D], E> {
            Ok([v as f64; D])
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<[f64; D], A::Error> {
            let mut sides = [0.0; D];
            for (k, side) in sides.iter_mut().enumerate() {
                *side = seq
                    .next_element()?
                    .ok_or_else(|| A::Error::invalid_length(k, &self))?;
            }
            if seq.next_element::<f64>()?.is_some() {
                return Err(A::Error::invalid_length(D + 1, &self));
            }
            Ok(sides)
        }
    }

    /// Binary: a side, or the NaN marker followed by D sides.
    struct BinaryVisitor<const D: usize>;

    impl<'de, const D: usize> Visitor<'de> for BinaryVisitor<D> {
        type Value = [f64; D];
        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            write!(f, "a box side, or NaN and {D} sides")
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<[f64; D], A::Error> {
            let first: f64 = seq
                .next_element()?
                .ok_or_else(|| A::Error::invalid_length(0, &self))?;
            if !first.is_nan() {
                return Ok([first; D]);
            }
            let mut sides = [0.0; D];
            for (k, side) in sides.iter_mut().enumerate() {
                *side = seq
                    .next_element()?
                    .ok_or_else(|| A::Error::invalid_length(k + 1, &self))?;
            }
            Ok(sides)
        }
    }

    pub fn deserialize<'de, De: Deserializer<'de>, const D: usize>(
        d: De,
    ) -> Result<[f64; D], De::Error> {
        if d.is_human_readable() {
            d.deserialize_any(ReadableVisitor::<D>)
        } else {
            d.deserialize_tuple(D + 1, BinaryVisitor::<D>)
        }
    }
}
