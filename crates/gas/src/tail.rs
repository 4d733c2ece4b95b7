//! The optional parts that end an engine's saved state ([`Tail`]), and the particles'
//! tracks ([`Tracks`]: their displacements since tracking began, for the mean-square
//! displacement).

use crate::error::{Error, Result};
use crate::shear::{Shear, Virial};
use crate::system::Vector;
use serde::de::{SeqAccess, Visitor};
use serde::ser::SerializeTuple;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// Where each particle started and the periodic images it has crossed into along each
/// axis since (flattened, D per particle): its displacement is the unwrapped position now
/// less the origin.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tracks {
    pub origins: Vec<f64>,
    pub images: Vec<i32>,
}

/// Why a sheared gas is not tracked (every engine that tracks): the flow carries the
/// particles along x and the faces move them by the images' offset.
pub(crate) fn tracking_under_shear() -> Error {
    Error::out_of_range(
        "tracking",
        "a sheared gas",
        "a gas without shear (the flow carries particles along x)",
    )
}

/// Why a tracked gas is not sheared (the engines that check it when shear comes second).
pub(crate) fn shear_while_tracked() -> Error {
    Error::out_of_range(
        "shear",
        "a gas whose displacements are tracked",
        "a gas without tracking (the flow carries particles along x)",
    )
}

impl Tracks {
    /// Tracks from `positions` on.
    pub fn new<const D: usize>(positions: &[Vector<D>]) -> Self {
        Tracks {
            origins: positions.iter().flatten().copied().collect(),
            images: vec![0; D * positions.len()],
        }
    }

    /// Notes that particle i's coordinate k was wrapped from `unwrapped` to `wrapped` in a
    /// box of side `side` along k.
    #[inline]
    pub fn note_wrap<const D: usize>(
        &mut self,
        i: usize,
        k: usize,
        unwrapped: f64,
        wrapped: f64,
        side: f64,
    ) {
        self.images[D * i + k] += ((unwrapped - wrapped) / side).round() as i32;
    }

    /// Counts the images particle i crossed into in one step of an engine that wraps
    /// positions every step: `expected` its position the step would give without the wrap
    /// (the last position, or that plus its flight), `now` the wrapped one; along the
    /// `periodic` axes only (a wall's axis wraps nothing). Exact while a step moves a
    /// particle less than half a box from `expected`.
    #[inline]
    pub fn follow<const D: usize>(
        &mut self,
        i: usize,
        expected: &Vector<D>,
        now: &Vector<D>,
        sides: &Vector<D>,
        periodic: &[bool; D],
    ) {
        for k in (0..D).filter(|&k| periodic[k]) {
            self.note_wrap::<D>(i, k, expected[k], now[k], sides[k]);
        }
    }

    /// The displacements of particles now at `positions` (unwrapped since their last wrap)
    /// in a box of `sides`.
    pub fn displacements<const D: usize>(
        &self,
        positions: &[Vector<D>],
        sides: &Vector<D>,
    ) -> Vec<Vector<D>> {
        positions
            .iter()
            .enumerate()
            .map(|(i, x)| {
                std::array::from_fn(|k| {
                    x[k] + self.images[D * i + k] as f64 * sides[k] - self.origins[D * i + k]
                })
            })
            .collect()
    }

    /// Checks restored tracks: `entries` (D per particle) of each, finite origins.
    pub fn check(&self, entries: usize) -> Result<()> {
        if self.origins.len() != entries || self.images.len() != entries {
            return Err(Error::LengthMismatch {
                what: "tracks and particles".into(),
            });
        }
        if self.origins.iter().any(|x| !x.is_finite()) {
            return Err(Error::out_of_range(
                "tracks",
                "an origin not finite",
                "finite origins",
            ));
        }
        Ok(())
    }
}

/// The optional parts that end an engine's saved state: the walls of a container, the
/// shear, the tensor virial, the particles' tracks, their rotation, the history of an
/// engine's contacts (`H`: soft-sphere MD's tangential springs; [`Never`] for the engines
/// without). Written up to the last one present (nothing for a periodic
/// unsheared gas, whose states stay byte for byte as before they existed; only the walls
/// for a container, as the walls alone were written before), each as an option; a reader
/// takes the end of the data as absence (`sim::checkpoint::Sections::engine` pads the data
/// with zero bytes, which read as None).
#[derive(Debug, Clone, PartialEq)]
pub struct Tail<W, H = Never> {
    pub walls: Option<W>,
    pub shear: Option<Shear>,
    pub virial: Option<Virial>,
    /// The particles' displacements since tracking began.
    pub tracks: Option<Tracks>,
    /// The particles' rotation (rough spheres).
    pub rotation: Option<crate::rotation::Rotation>,
    /// The history of the contacts (soft-sphere MD's tangential springs).
    pub history: Option<H>,
}

/// The contact history of engines that have none: no value exists, so that such an
/// engine's tail cannot hold one (and a state that claims one does not read).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Never {}

impl<W, H> Default for Tail<W, H> {
    fn default() -> Self {
        Tail {
            walls: None,
            shear: None,
            virial: None,
            tracks: None,
            rotation: None,
            history: None,
        }
    }
}

impl<W, H> Tail<W, H> {
    pub fn is_empty(&self) -> bool {
        self.walls.is_none()
            && self.shear.is_none()
            && self.virial.is_none()
            && self.tracks.is_none()
            && self.rotation.is_none()
            && self.history.is_none()
    }

    /// How many parts are written: up to the last one present.
    fn written(&self) -> usize {
        if self.history.is_some() {
            6
        } else if self.rotation.is_some() {
            5
        } else if self.tracks.is_some() {
            4
        } else if self.virial.is_some() {
            3
        } else if self.shear.is_some() {
            2
        } else {
            self.walls.is_some() as usize
        }
    }

    /// Checks the restored shear and virial (the walls are checked by their engine).
    pub fn check(&self) -> Result<()> {
        if let Some(shear) = &self.shear {
            Shear::new(shear.rate)?;
        }
        if let Some(virial) = &self.virial {
            virial.check()?;
        }
        Ok(())
    }
}

impl<W: Serialize, H: Serialize> Serialize for Tail<W, H> {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let len = self.written();
        let mut t = s.serialize_tuple(len)?;
        if len >= 1 {
            t.serialize_element(&self.walls)?;
        }
        if len >= 2 {
            t.serialize_element(&self.shear)?;
        }
        if len >= 3 {
            t.serialize_element(&self.virial)?;
        }
        if len >= 4 {
            t.serialize_element(&self.tracks)?;
        }
        if len >= 5 {
            t.serialize_element(&self.rotation)?;
        }
        if len >= 6 {
            t.serialize_element(&self.history)?;
        }
        t.end()
    }
}

impl<'de, W: Deserialize<'de>, H: Deserialize<'de>> Deserialize<'de> for Tail<W, H> {
    fn deserialize<De: Deserializer<'de>>(d: De) -> std::result::Result<Self, De::Error> {
        struct TailVisitor<W, H>(std::marker::PhantomData<(W, H)>);
        impl<'de, W: Deserialize<'de>, H: Deserialize<'de>> Visitor<'de> for TailVisitor<W, H> {
            type Value = Tail<W, H>;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("up to six options: walls, shear, virial, tracks, rotation, history")
            }
            fn visit_seq<A: SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> std::result::Result<Self::Value, A::Error> {
                let walls = seq.next_element::<Option<W>>()?.flatten();
                let shear = seq.next_element::<Option<Shear>>()?.flatten();
                let virial = seq.next_element::<Option<Virial>>()?.flatten();
                let tracks = seq.next_element::<Option<Tracks>>()?.flatten();
                let rotation = seq
                    .next_element::<Option<crate::rotation::Rotation>>()?
                    .flatten();
                let history = seq.next_element::<Option<H>>()?.flatten();
                Ok(Tail {
                    walls,
                    shear,
                    virial,
                    tracks,
                    rotation,
                    history,
                })
            }
        }
        d.deserialize_tuple(6, TailVisitor(std::marker::PhantomData))
    }
}

/// Zero bytes a reader of postcard appends to an engine's state so that the options of a
/// [`Tail`] missing at its end read as None.
pub const TAIL_PADDING: usize = 6;

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
    struct Old {
        a: u32,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        walls: Option<u64>,
    }

    #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
    struct New {
        a: u32,
        #[serde(default, skip_serializing_if = "Tail::is_empty")]
        tail: Tail<u64>,
    }

    fn padded(mut bytes: Vec<u8>) -> Vec<u8> {
        bytes.extend([0; TAIL_PADDING]);
        bytes
    }

    /// A state without a tail, or with walls only, is written as the older state with its
    /// optional walls was (byte for byte), and older states read back; every combination
    /// of parts reads back as written (postcard with the padding, and JSON).
    #[test]
    fn tails_keep_older_bytes_and_read_back() {
        let tracks = Some(Tracks {
            origins: vec![1.0, 2.0],
            images: vec![3, -1],
        });
        for walls in [None, Some(7u64)] {
            let old = postcard::to_stdvec(&Old { a: 3, walls }).unwrap();
            let tail = Tail {
                walls,
                ..Default::default()
            };
            let new = postcard::to_stdvec(&New { a: 3, tail }).unwrap();
            assert_eq!(old, new);
            let read: New = postcard::from_bytes(&padded(old)).unwrap();
            assert_eq!(read.tail.walls, walls);
        }
        let shear = Some(Shear { rate: -0.5 });
        let virial = Some(Virial([1.0, 2.0, 3.0, 4.0, 5.0, 6.0]));
        let mut rotation = crate::rotation::Rotation::at_rest(2, 0.4);
        rotation.angular[1] = [0.5, -1.0, 2.0];
        rotation.sliding = 3;
        for walls in [None, Some(9u64)] {
            for shear in [None, shear] {
                for virial in [None, virial] {
                    for tracks in [None, tracks.clone()] {
                        for rotation in [None, Some(rotation.clone())] {
                            let state = New {
                                a: 1,
                                tail: Tail {
                                    walls,
                                    shear,
                                    virial,
                                    tracks: tracks.clone(),
                                    rotation,
                                    history: None,
                                },
                            };
                            let bytes = padded(postcard::to_stdvec(&state).unwrap());
                            assert_eq!(postcard::from_bytes::<New>(&bytes).unwrap(), state);
                            let json = serde_json::to_string(&state).unwrap();
                            assert_eq!(serde_json::from_str::<New>(&json).unwrap(), state);
                        }
                    }
                }
            }
        }
    }
}
