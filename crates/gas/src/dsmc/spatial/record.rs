//! The spatial engine's records: smooth ([`Simulator`]: position, velocity, species,
//! identity) and rough ([`Rolling`]: that record and the angular velocity), and what
//! streaming, the sort into cells and the migration between ranks need of them
//! ([`Particle`]). The engine's code is generic over the two kinds and holds one of them
//! ([`Records`]): smooth spheres keep the record and the instructions they had before
//! rough ones existed (the body of a [`Simulator`] is itself), and a rough record's spin
//! travels wherever its record goes — through the sort, the walls (which leave it alone:
//! smooth walls, no torque) and to other ranks.

use super::super::kernel::{Record, Simulator};
use crate::system::Vector;

/// `$body` with `$r` bound to the records of either kind (a reference to the `Vec`, as
/// `$records` is one; the body is compiled for each kind).
macro_rules! each {
    ($records:expr, $r:ident => $body:expr) => {
        match $records {
            $crate::dsmc::spatial::record::Records::Smooth($r) => $body,
            $crate::dsmc::spatial::record::Records::Rough($r) => $body,
        }
    };
}
pub(crate) use each;

/// `$body` with `$r` the engine's records of either kind, moved out of `$engine.records`
/// (so that the body may borrow the rest of the engine mutably) and put back after it
/// (the body is compiled for each kind).
macro_rules! with_records {
    ($engine:expr, $r:ident => $body:expr) => {
        match std::mem::take(&mut $engine.records) {
            $crate::dsmc::spatial::record::Records::Smooth($r) => {
                #[allow(unused_mut)]
                let mut $r = $r;
                let out = $body;
                $engine.records = $crate::dsmc::spatial::record::Records::Smooth($r);
                out
            }
            $crate::dsmc::spatial::record::Records::Rough($r) => {
                #[allow(unused_mut)]
                let mut $r = $r;
                let out = $body;
                $engine.records = $crate::dsmc::spatial::record::Records::Rough($r);
                out
            }
        }
    };
}
pub(crate) use with_records;

/// A record of the spatial engine.
pub(crate) trait Particle<const D: usize>: Record<D> {
    /// f64 values of a message row: position, velocity, species, the place in the global
    /// order, then what else the record holds.
    const VALUES: usize;
    /// The position, velocity, species and identity.
    fn body(&self) -> &Simulator<D>;
    fn body_mut(&mut self) -> &mut Simulator<D>;
    /// Appends the record and its place in the global order to a message.
    fn encode(&self, out: &mut Vec<f64>, place: u64);
    /// The record of a message row written by [`Particle::encode`].
    fn decode(row: &[f64]) -> Self;
}

/// Appends the smooth part of a record and its place ([`Simulator`]'s row).
#[inline]
fn encode_body<const D: usize>(out: &mut Vec<f64>, p: &Simulator<D>, place: u64) {
    out.extend_from_slice(&p.position);
    out.extend_from_slice(&p.velocity);
    out.push(p.species as f64);
    out.push(f64::from_bits(place));
}

#[inline]
fn decode_body<const D: usize>(v: &[f64]) -> Simulator<D> {
    Simulator {
        position: std::array::from_fn(|k| v[k]),
        velocity: std::array::from_fn(|k| v[D + k]),
        species: v[2 * D] as u32,
        // Identities are not carried between ranks (no tracks over ranks).
        id: 0,
    }
}

impl<const D: usize> Particle<D> for Simulator<D> {
    const VALUES: usize = 2 * D + 2;
    #[inline(always)]
    fn body(&self) -> &Simulator<D> {
        self
    }
    #[inline(always)]
    fn body_mut(&mut self) -> &mut Simulator<D> {
        self
    }
    fn encode(&self, out: &mut Vec<f64>, place: u64) {
        encode_body(out, self, place);
    }
    fn decode(row: &[f64]) -> Self {
        decode_body(row)
    }
}

/// The record of a rough particle in the spatial engine: the smooth record and the
/// angular velocity (disks about z): 80 bytes in 3D, 64 in 2D.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rolling<const D: usize> {
    pub body: Simulator<D>,
    pub angular: [f64; 3],
}

impl<const D: usize> Record<D> for Rolling<D> {
    const MIXED: bool = true;
    const ROUGH: bool = true;
    #[inline]
    fn velocity(&self) -> &Vector<D> {
        &self.body.velocity
    }
    #[inline]
    fn velocity_mut(&mut self) -> &mut Vector<D> {
        &mut self.body.velocity
    }
    #[inline]
    fn species(&self) -> usize {
        self.body.species as usize
    }
    #[inline(always)]
    fn spin_parts(&mut self) -> Option<(&mut Vector<D>, &mut [f64; 3])> {
        Some((&mut self.body.velocity, &mut self.angular))
    }
}

/// A rough record's row: the smooth row, then the angular velocity.
impl<const D: usize> Particle<D> for Rolling<D> {
    const VALUES: usize = 2 * D + 5;
    #[inline(always)]
    fn body(&self) -> &Simulator<D> {
        &self.body
    }
    #[inline(always)]
    fn body_mut(&mut self) -> &mut Simulator<D> {
        &mut self.body
    }
    fn encode(&self, out: &mut Vec<f64>, place: u64) {
        encode_body(out, &self.body, place);
        out.extend_from_slice(&self.angular);
    }
    fn decode(row: &[f64]) -> Self {
        let at = 2 * D + 2;
        Rolling {
            body: decode_body(row),
            angular: [row[at], row[at + 1], row[at + 2]],
        }
    }
}

/// The engine's records: smooth, or rough once the particles are given a rotation.
#[derive(Debug, Clone)]
pub(crate) enum Records<const D: usize> {
    Smooth(Vec<Simulator<D>>),
    Rough(Vec<Rolling<D>>),
}

impl<const D: usize> Default for Records<D> {
    fn default() -> Self {
        Records::Smooth(Vec::new())
    }
}

impl<const D: usize> Records<D> {
    /// The records on this rank.
    pub fn len(&self) -> usize {
        each!(self, r => r.len())
    }

    /// Bytes held by the records.
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        match self {
            Records::Smooth(r) => r.capacity() * size_of::<Simulator<D>>(),
            Records::Rough(r) => r.capacity() * size_of::<Rolling<D>>(),
        }
    }
}
