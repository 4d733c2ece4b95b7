//! The `.vtu` of haff's snapshots (VTK XML unstructured grid, `crate::vtk`): the points
//! are the centres; point data `radius` (or `diameter`), `mass`, `velocity`, `species`
//! (from 0), `angular_velocity`; other arrays (`collisions`, `bath_temperature`) are
//! skipped. The box is the field data array `box` (ascii), which `vtkio` does not read:
//! it is taken from the text, and the file is parsed by `vtkio` without it. A file without
//! it (or with it not in ascii) gives a configuration without sides (`read_with_box` asks
//! for them). Arrays inline (base64 or ascii), not appended raw data. One frame.

use super::{Configuration, Fault, Vec3};
use crate::vtk::{write_vtu, VtuParticles, BOX_ARRAY};
use std::path::Path;
use vtkio::model::{Attribute, DataSet, Piece, Vtk};

/// The box of the field data (empty if there is none) and the text without the field data.
fn take_box(text: &str) -> Result<(Vec<f64>, String), Fault> {
    let (Some(start), Some(end)) = (text.find("<FieldData>"), text.find("</FieldData>")) else {
        return Ok((Vec::new(), text.to_string()));
    };
    let end = end + "</FieldData>".len();
    if end < start {
        return Err(("box".into(), "a `</FieldData>` before `<FieldData>`".into()));
    }
    let field = &text[start..end];
    let rest = format!("{}{}", &text[..start], &text[end..]);
    let name = format!("Name=\"{BOX_ARRAY}\"");
    let Some(at) = field.find(&name) else {
        return Ok((Vec::new(), rest));
    };
    let element = &field[field[..at].rfind('<').unwrap_or(0)..];
    let open_end = element.find('>').unwrap_or(element.len());
    // A box re-encoded by another writer (binary) is not read: the sides must be given.
    if !element[..open_end].contains("format=\"ascii\"") {
        return Ok((Vec::new(), rest));
    }
    let body = &element[(open_end + 1).min(element.len())..];
    let body = &body[..body.find("</DataArray>").unwrap_or(body.len())];
    let sides = body
        .split_whitespace()
        .map(|x| {
            x.parse::<f64>()
                .map_err(|_| ("box".to_string(), format!("`{x}` is not a number")))
        })
        .collect::<Result<Vec<f64>, Fault>>()?;
    Ok((sides, rest))
}

pub(super) fn parse(text: &str, dimension: usize, frame: i64) -> Result<Configuration, Fault> {
    super::frame_index(frame, 1)?;
    let (mut sides, rest) = take_box(text)?;
    if !sides.is_empty() {
        if sides.len() < dimension {
            return Err((
                "box".into(),
                format!("{} sides for dimension {dimension}", sides.len()),
            ));
        }
        sides.truncate(dimension);
    }
    let file = |m: String| ("file".to_string(), m);
    let vtk = Vtk::parse_xml(rest.as_bytes()).map_err(|e| {
        file(format!(
            "not a VTK XML file: {}",
            crate::description::one_line(&e.to_string())
        ))
    })?;
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        return Err(file("not an unstructured grid (.vtu)".into()));
    };
    let [Piece::Inline(piece)] = pieces.as_slice() else {
        return Err(file(format!(
            "{} pieces; allowed: one inline piece",
            pieces.len()
        )));
    };
    let points: Vec<f64> = piece
        .points
        .clone()
        .cast_into()
        .ok_or_else(|| file("the points are not numbers".into()))?;
    if !points.len().is_multiple_of(3) {
        return Err(file(format!(
            "{} point coordinates, not 3 per point",
            points.len()
        )));
    }
    let n = points.len() / 3;
    // The point data array `name` as f64, `width` values per point, if the file has it.
    let array = |name: &str, width: usize| -> Result<Option<Vec<f64>>, Fault> {
        let found = piece.data.point.iter().find_map(|a| match a {
            Attribute::DataArray(d) if d.name == name => Some(d),
            _ => None,
        });
        let Some(d) = found else { return Ok(None) };
        let values: Vec<f64> = d
            .data
            .clone()
            .cast_into()
            .ok_or_else(|| (format!("array `{name}`"), "not numbers".to_string()))?;
        if values.len() != n * width {
            return Err((
                format!("array `{name}`"),
                format!("{} values for {n} points of {width}", values.len()),
            ));
        }
        Ok(Some(values))
    };
    let vectors = |flat: Vec<f64>, keep: usize| -> Vec<Vec3> {
        flat.chunks_exact(3)
            .map(|v| std::array::from_fn(|k| if k < keep { v[k] } else { 0.0 }))
            .collect()
    };
    let diameters = match array("radius", 1)? {
        Some(r) => Some(r.iter().map(|r| 2.0 * r).collect()),
        None => array("diameter", 1)?,
    };
    let species = match array("species", 1)? {
        Some(s) => Some(
            s.iter()
                .enumerate()
                .map(|(i, &k)| {
                    if k >= 0.0 && k.fract() == 0.0 && k < 2f64.powi(32) {
                        Ok(k as usize)
                    } else {
                        Err((
                            format!("record {i}"),
                            format!("species `{k}` is not an index (0, 1, ...)"),
                        ))
                    }
                })
                .collect::<Result<Vec<usize>, Fault>>()?,
        ),
        None => None,
    };
    Ok(Configuration {
        dimension,
        sides,
        positions: vectors(points, dimension),
        velocities: array("velocity", 3)?.map(|v| vectors(v, dimension)),
        diameters,
        masses: array("mass", 1)?,
        species,
        spins: array("angular_velocity", 3)?.map(|w| vectors(w, 3)),
        time: None,
    })
}

/// Writes `c` as a `.vtu` as haff's snapshots are written (the time is not kept; the
/// radius is written, as 1/2 where `c` has no diameters).
pub(super) fn write(path: &Path, c: &Configuration) -> crate::error::Result<()> {
    let flat = |list: &[Vec3]| -> Vec<f64> { list.iter().flatten().copied().collect() };
    let species = c
        .species
        .as_ref()
        .map(|s| {
            s.iter()
                .enumerate()
                .map(|(i, &k)| {
                    u32::try_from(k).map_err(|_| crate::error::Error::ParticleFile {
                        path: path.to_path_buf(),
                        at: format!("record {i}"),
                        message: format!("species {k}; allowed: 0 ..= {}", u32::MAX),
                    })
                })
                .collect::<crate::error::Result<Vec<u32>>>()
        })
        .transpose()?;
    write_vtu(
        path,
        VtuParticles {
            sides: c.sides.clone(),
            points: flat(&c.positions),
            radii: (0..c.len()).map(|i| 0.5 * c.diameter(i)).collect(),
            masses: c.masses.clone(),
            velocities: c.velocities.as_deref().map(flat),
            species,
            collisions: None,
            bath_temperatures: None,
            angular_velocities: c.spins.as_deref().map(flat),
        },
    )
}
