//! `output.snapshots.format`: the formats of particle snapshots, a name or a list of
//! names in the run file (`crate::snapshots` writes them).

use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use serde::{Deserialize, Serialize};
use std::borrow::Cow;

/// A format of particle snapshots.
// A new format is a variant here, its name in [`SnapshotFormat::name`] (the schema's
// `rename_all` spells the same names: tested) and its writer in `crate::snapshots`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, JsonSchema)]
#[schemars(rename_all = "kebab-case")]
pub enum SnapshotFormat {
    /// VTK XML: one `.vtu` per snapshot and a `.pvd` time series (ParaView).
    Vtk,
    /// A LAMMPS `dump custom` trajectory, `snapshots.lammpstrj` (OVITO, VMD).
    LammpsDump,
    /// An extended XYZ trajectory, `snapshots.xyz` (OVITO, ASE).
    Xyz,
    /// An H5MD trajectory, `snapshots.h5md` (h5py, MDAnalysis, OVITO), with the
    /// temperature and the energy lost as observables (a haff built with the feature
    /// `h5md`).
    H5md,
}

impl SnapshotFormat {
    /// Every format, in the order of the error message's list.
    pub const ALL: [SnapshotFormat; 4] = [
        SnapshotFormat::Vtk,
        SnapshotFormat::LammpsDump,
        SnapshotFormat::Xyz,
        SnapshotFormat::H5md,
    ];

    /// The name in the run file.
    pub fn name(self) -> &'static str {
        match self {
            SnapshotFormat::Vtk => "vtk",
            SnapshotFormat::LammpsDump => "lammps-dump",
            SnapshotFormat::Xyz => "xyz",
            SnapshotFormat::H5md => "h5md",
        }
    }

    /// The format named `name`, or a message listing the allowed names.
    pub fn parse(name: &str) -> std::result::Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|f| f.name() == name)
            .ok_or_else(|| {
                let names: Vec<&str> = Self::ALL.iter().map(|f| f.name()).collect();
                format!(
                    "`{name}` is not a snapshot format; allowed: {} (or a list of them)",
                    names.join(", ")
                )
            })
    }
}

/// `output.snapshots.format`: a name or a list of distinct names (default `"vtk"`). One
/// format is written back as a plain string, so that the `parameters` of `summary.json`
/// and the check-points of runs with one format keep their bytes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SnapshotFormats(Vec<SnapshotFormat>);

impl SnapshotFormats {
    /// The formats, in the order given (at least one, no two alike).
    pub fn list(&self) -> &[SnapshotFormat] {
        &self.0
    }

    /// Whether `format` is among them.
    pub fn has(&self, format: SnapshotFormat) -> bool {
        self.0.contains(&format)
    }

    /// `formats` (at least one, no two alike), or a message saying what is wrong.
    pub fn new(formats: Vec<SnapshotFormat>) -> std::result::Result<Self, String> {
        if formats.is_empty() {
            return Err("an empty list; allowed: one or more snapshot formats".into());
        }
        if let Some((i, f)) = formats
            .iter()
            .enumerate()
            .find(|(i, f)| formats[..*i].contains(f))
        {
            return Err(format!("`{}` given twice (entry {i})", f.name()));
        }
        Ok(SnapshotFormats(formats))
    }
}

impl Default for SnapshotFormats {
    fn default() -> Self {
        SnapshotFormats(vec![SnapshotFormat::Vtk])
    }
}

impl JsonSchema for SnapshotFormats {
    fn schema_name() -> Cow<'static, str> {
        "SnapshotFormats".into()
    }

    fn json_schema(generator: &mut SchemaGenerator) -> Schema {
        let one = generator.subschema_for::<SnapshotFormat>();
        json_schema!({
            "anyOf": [
                one,
                {
                    "description": "Several formats, each at most once.",
                    "type": "array",
                    "items": one,
                    "minItems": 1,
                    "uniqueItems": true,
                },
            ]
        })
    }
}

impl Serialize for SnapshotFormats {
    fn serialize<S: serde::Serializer>(
        &self,
        serializer: S,
    ) -> std::result::Result<S::Ok, S::Error> {
        match self.0.as_slice() {
            [one] => serializer.serialize_str(one.name()),
            many => serializer.collect_seq(many.iter().map(|f| f.name())),
        }
    }
}

impl<'de> Deserialize<'de> for SnapshotFormats {
    fn deserialize<D: serde::Deserializer<'de>>(
        deserializer: D,
    ) -> std::result::Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = SnapshotFormats;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a snapshot format (vtk, lammps-dump, xyz, h5md) or a list of them")
            }
            fn visit_str<E: serde::de::Error>(
                self,
                v: &str,
            ) -> std::result::Result<Self::Value, E> {
                SnapshotFormat::parse(v)
                    .map(|f| SnapshotFormats(vec![f]))
                    .map_err(E::custom)
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> std::result::Result<Self::Value, A::Error> {
                use serde::de::Error as _;
                let mut names = Vec::new();
                while let Some(name) = seq.next_element::<String>()? {
                    names.push(name);
                }
                let formats = names
                    .iter()
                    .map(|n| SnapshotFormat::parse(n))
                    .collect::<std::result::Result<Vec<_>, _>>()
                    .map_err(A::Error::custom)?;
                SnapshotFormats::new(formats).map_err(A::Error::custom)
            }
        }
        deserializer.deserialize_any(Visitor)
    }
}
