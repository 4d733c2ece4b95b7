//! The JSON Schema of the run-file values whose serde form is written by hand or whose type
//! lives in another crate: what their deserializers (and validation, for names) accept.
//! The description types name these with `#[schemars(with = "Option<...>")]`; the types
//! here only carry schemas.

use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use std::borrow::Cow;

/// Drops the `default` schemars writes for a `#[serde(default)]` field whose default is no
/// value a user may give (`system.particles`: 0, "left out").
pub(super) fn no_default(schema: &mut Schema) {
    schema.remove("default");
}

/// A number in `min ..= max` or a symmetric matrix of them with a row per species: the
/// serde form of [`super::RestitutionValue`].
fn number_or_matrix(min: f64, max: f64) -> Schema {
    let entry = json_schema!({ "type": "number", "minimum": min, "maximum": max });
    json_schema!({
        "anyOf": [
            {
                "description": "One value for every pair.",
                "type": "number",
                "minimum": min,
                "maximum": max,
            },
            {
                "description": "A symmetric matrix, one row and one column per species of \
                                `system.species`.",
                "type": "array",
                "minItems": 1,
                "items": { "type": "array", "minItems": 1, "items": entry },
            },
        ]
    })
}

/// `collision.restitution`.
pub(super) struct Restitution;

impl JsonSchema for Restitution {
    fn schema_name() -> Cow<'static, str> {
        "Restitution".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        number_or_matrix(0.0, 1.0)
    }
}

/// `collision.tangential_restitution`.
pub(super) struct TangentialRestitution;

impl JsonSchema for TangentialRestitution {
    fn schema_name() -> Cow<'static, str> {
        "TangentialRestitution".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        number_or_matrix(-1.0, 1.0)
    }
}

/// `restitution::Criterion` (`criterion` of the dash-pot).
pub(super) struct CriterionName;

impl JsonSchema for CriterionName {
    fn schema_name() -> Cow<'static, str> {
        "Criterion".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "When a contact ends.",
            "oneOf": [
                {
                    "description": "When the force vanishes (delayed recovery; Eq. (8) of \
                                    Schwager & Pöschel 2008).",
                    "type": "string",
                    "const": "improved",
                },
                {
                    "description": "When the overlap vanishes (Eq. (7) of Schwager & Pöschel \
                                    2008).",
                    "type": "string",
                    "const": "naive",
                },
            ]
        })
    }
}

/// `restitution::FormName` (`form` of the viscoelastic law): the names its `FromStr`
/// parses. `str::parse::<usize>` takes a leading `+`, so the pattern does too.
pub(super) struct FormText;

impl JsonSchema for FormText {
    fn schema_name() -> Cow<'static, str> {
        "ViscoelasticForm".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "The forms: `exact`, the collision equation integrated \
                            (`exact-naive`: with the naive criterion); `fast`, a table of the \
                            exact law, equal to it within ~1e-13 (`fast-naive`); `pade:M/N`, \
                            the Padé approximant [M/N] of the series computed by haff; \
                            `series:K`, the series to order K; `pade-paper:M/N`, \
                            `series-paper:K`, with the coefficients printed in Müller & Pöschel \
                            2011 and Schwager & Pöschel 2008. A Padé or series form that the \
                            run's impact speeds would take beyond its validity is refused.",
            "type": "string",
            "pattern": "^(exact|exact-naive|fast|fast-naive|pade(-paper)?:\\+?[0-9]+/\\+?[0-9]+|series(-paper)?:\\+?[0-9]+)$",
            "examples": ["fast", "exact", "pade:3/6", "series:10"],
        })
    }
}

/// `wall.law`: the laws of `[collision]` a wall can have.
pub(super) struct WallLaw;

impl JsonSchema for WallLaw {
    fn schema_name() -> Cow<'static, str> {
        "WallLaw".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "The law of a wall's contacts (a wall has no internal modes: not \
                            `stochastic`).",
            "oneOf": [
                {
                    "description": "A constant coefficient of restitution (`restitution`).",
                    "type": "string",
                    "const": "constant",
                },
                {
                    "description": "The linear dash-pot (`damping_ratio`, `criterion`).",
                    "type": "string",
                    "const": "dashpot",
                },
                {
                    "description": "A viscoelastic contact (`beta` or the wall's material, \
                                    `form`).",
                    "type": "string",
                    "const": "viscoelastic",
                },
            ]
        })
    }
}

/// `collision.material`: a built-in material's name, case-insensitive with `_` or blanks
/// for `-` (`restitution::material::material_by_name`), so any string as far as a schema
/// can tell; the names are listed.
pub(super) struct MaterialName;

impl JsonSchema for MaterialName {
    fn schema_name() -> Cow<'static, str> {
        "Material".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        let names = restitution::material::builtin_material_names();
        let list: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
        json_schema!({
            "description": format!(
                "A built-in material: {} (case-insensitive; `_` or a blank for `-`).",
                list.join(", ")
            ),
            "type": "string",
            "examples": names,
        })
    }
}

/// `system.initial.format`: the names of `crate::particles::Format`.
pub(super) struct ParticleFormat;

impl JsonSchema for ParticleFormat {
    fn schema_name() -> Cow<'static, str> {
        "ParticleFileFormat".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "A particle file format.",
            "type": "string",
            "enum": crate::particles::Format::NAMES,
        })
    }
}
