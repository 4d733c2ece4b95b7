//! Reading one frame of an H5MD file: the `h5md` group checked (version 1.x), the
//! particles group `particles/all` (or the only one), its periodic orthogonal box, and the
//! elements at the step of the chosen position frame. Every fault names the HDF5 object.

use super::super::{frame_index, Configuration, Fault, Vec3};
use super::line;
use crate::error::{Error, Result};
use hdf5::types::{VarLenAscii, VarLenUnicode};
use hdf5::{Dataset, File, Group};
use ndarray::s;
use std::path::Path;

/// At most this many values in one read (haff's 1e8 particles, three components): a
/// damaged file's shapes ask for no more memory than that.
const MOST_VALUES: usize = 300_000_000;

/// An H5MD element: a time-dependent group (step, time, value) or a dataset.
enum Element {
    Series {
        group: Group,
        value: Dataset,
        steps: Vec<i64>,
    },
    Fixed(Dataset),
}

pub(in super::super) fn read(path: &Path, dimension: usize, frame: i64) -> Result<Configuration> {
    parse(path, dimension, frame).map_err(|(at, message)| Error::ParticleFile {
        path: path.to_path_buf(),
        at,
        message,
    })
}

fn parse(path: &Path, dimension: usize, frame: i64) -> std::result::Result<Configuration, Fault> {
    let file = File::open(path).map_err(|e| {
        (
            "file".to_string(),
            format!("not an HDF5 file that can be read: {}", line(e)),
        )
    })?;
    let h5md = file.group("h5md").map_err(|_| {
        (
            "h5md".to_string(),
            "no group `h5md`: not an H5MD file".to_string(),
        )
    })?;
    let version: Vec<i64> = h5md
        .attr("version")
        .and_then(|a| a.read_raw())
        .map_err(|e| {
            (
                "h5md".to_string(),
                format!("attribute `version`: {}", line(e)),
            )
        })?;
    if version.first() != Some(&1) {
        return Err(("h5md".into(), format!("version {version:?}; allowed: 1.x")));
    }
    let particles = file
        .group("particles")
        .map_err(|_| ("particles".to_string(), "no group `particles`".to_string()))?;
    let (name, all) = match particles.group("all") {
        Ok(g) => ("all".to_string(), g),
        Err(_) => {
            let names = particles.member_names().unwrap_or_default();
            match names.as_slice() {
                [one] => (
                    one.clone(),
                    particles
                        .group(one)
                        .map_err(|e| (format!("particles/{one}"), line(e)))?,
                ),
                _ => {
                    return Err((
                        "particles".into(),
                        format!("groups {names:?}; allowed: `all` or a single particles group"),
                    ))
                }
            }
        }
    };
    let here = |item: &str| format!("particles/{name}/{item}");
    let position = element(&all, "position", &here("position"))?
        .ok_or_else(|| (here("position"), "no element `position`".to_string()))?;
    let (step, time) = match &position {
        Element::Series { group, steps, .. } => {
            let k = frame_index(frame, steps.len()).map_err(|(_, m)| (here("position"), m))?;
            let time = times(group, steps.len(), &here("position/time"))?.map(|t| t[k]);
            (Some(steps[k]), time)
        }
        Element::Fixed(_) => {
            frame_index(frame, 1).map_err(|(_, m)| (here("position"), m))?;
            (None, None)
        }
    };
    let sides = box_sides(&all, dimension, step, &here("box"))?;
    let mut positions = vectors(&position, step, dimension, &here("position"))?;
    let n = positions.len();
    for p in &mut positions {
        for (k, x) in p.iter_mut().take(dimension).enumerate() {
            let l = sides[k];
            if x.is_finite() && !(0.0..l).contains(x) {
                *x -= l * (*x / l).floor();
                if *x >= l {
                    *x = 0.0;
                }
            }
        }
    }
    let optional = |item: &str, width: usize| -> std::result::Result<Option<Vec<Vec3>>, Fault> {
        match element(&all, item, &here(item))? {
            Some(e) => {
                let list = vectors(&e, step, width, &here(item))?;
                if list.len() != n {
                    return Err((
                        here(item),
                        format!("{} values for {n} particles", list.len()),
                    ));
                }
                Ok(Some(list))
            }
            None => Ok(None),
        }
    };
    let velocities = optional("velocity", dimension)?;
    let spins = optional("angular_velocity", 3)?;
    let scalars = |item: &str| -> std::result::Result<Option<Vec<f64>>, Fault> {
        match element(&all, item, &here(item))? {
            Some(e) => {
                let list = values(&e, step, &[n], &here(item))?;
                Ok(Some(list))
            }
            None => Ok(None),
        }
    };
    let masses = scalars("mass")?;
    let diameters = scalars("diameter")?;
    let species = match scalars("species")? {
        Some(list) => Some(
            list.iter()
                .enumerate()
                .map(|(i, &s)| {
                    if s >= 0.0 && s.fract() == 0.0 && s < 1e9 {
                        Ok(s as usize)
                    } else {
                        Err((
                            here("species"),
                            format!("record {i}: species {s}; allowed: an integer >= 0"),
                        ))
                    }
                })
                .collect::<std::result::Result<Vec<usize>, Fault>>()?,
        ),
        None => None,
    };
    Ok(Configuration {
        dimension,
        sides,
        positions,
        velocities,
        diameters,
        masses,
        species,
        spins,
        time,
    })
}

/// The box's sides: `dimension` as asked, `boundary` periodic, `edges` a vector (or a
/// diagonal matrix; if time-dependent, at the position's step).
fn box_sides(
    all: &Group,
    dimension: usize,
    step: Option<i64>,
    at: &str,
) -> std::result::Result<Vec<f64>, Fault> {
    let fault = |m: String| (at.to_string(), m);
    let b = all
        .group("box")
        .map_err(|_| fault("no group `box`".into()))?;
    let d: i64 = b
        .attr("dimension")
        .and_then(|a| a.read_scalar())
        .map_err(|e| fault(format!("attribute `dimension`: {}", line(e))))?;
    if d != dimension as i64 {
        return Err(fault(format!(
            "dimension {d} in the file; the run asks for {dimension}"
        )));
    }
    let boundary =
        strings(&b, "boundary").map_err(|e| fault(format!("attribute `boundary`: {e}")))?;
    if boundary.len() != dimension || boundary.iter().any(|s| s != "periodic") {
        return Err(fault(format!(
            "boundary {boundary:?}; allowed: \"periodic\" on each of the {dimension} axes"
        )));
    }
    let at_edges = format!("{at}/edges");
    let edges = element(&b, "edges", &at_edges)?
        .ok_or_else(|| fault("no `edges`: the box's sides are required".into()))?;
    let sample = match &edges {
        Element::Fixed(ds) => ds.shape(),
        Element::Series { value, .. } => value.shape().get(1..).unwrap_or(&[]).to_vec(),
    };
    if sample.iter().product::<usize>() > 9 || sample.len() > 2 {
        return Err(fault(format!(
            "edges of shape {sample:?}; allowed: [{dimension}] or [{dimension}][{dimension}]"
        )));
    }
    let raw = values(&edges, step, &sample, &at_edges)?;
    let sides: Vec<f64> = if raw.len() == dimension {
        raw
    } else if raw.len() == dimension * dimension {
        let tilted = (0..dimension)
            .flat_map(|i| (0..dimension).map(move |j| (i, j)))
            .any(|(i, j)| i != j && raw[i * dimension + j] != 0.0);
        if tilted {
            return Err(fault(
                "a tilted (triclinic) box; allowed: an orthogonal one (diagonal edges)".into(),
            ));
        }
        (0..dimension).map(|i| raw[i * dimension + i]).collect()
    } else {
        return Err(fault(format!(
            "edges of shape {sample:?}; allowed: [{dimension}] or [{dimension}][{dimension}]"
        )));
    };
    Ok(sides)
}

/// A string or an array of strings of an attribute (variable or fixed length).
fn strings(g: &Group, name: &str) -> std::result::Result<Vec<String>, String> {
    let a = g.attr(name).map_err(line)?;
    if let Ok(v) = a.read_raw::<VarLenUnicode>() {
        return Ok(v.iter().map(|s| s.as_str().to_string()).collect());
    }
    if let Ok(v) = a.read_raw::<VarLenAscii>() {
        return Ok(v.iter().map(|s| s.as_str().to_string()).collect());
    }
    if let Ok(v) = a.read_raw::<hdf5::types::FixedAscii<64>>() {
        return Ok(v.iter().map(|s| s.as_str().to_string()).collect());
    }
    a.read_raw::<hdf5::types::FixedUnicode<64>>()
        .map(|v| v.iter().map(|s| s.as_str().to_string()).collect())
        .map_err(|_| "not a string or strings".to_string())
}

/// The element `name` of `g`, if there is one.
fn element(g: &Group, name: &str, at: &str) -> std::result::Result<Option<Element>, Fault> {
    if !g.link_exists(name) {
        return Ok(None);
    }
    if let Ok(ds) = g.dataset(name) {
        return Ok(Some(Element::Fixed(ds)));
    }
    let group = g.group(name).map_err(|e| (at.to_string(), line(e)))?;
    let value = group.dataset("value").map_err(|_| {
        (
            at.to_string(),
            "a time-dependent group without `value`".to_string(),
        )
    })?;
    let frames = value.shape().first().copied().unwrap_or(0);
    let steps = series(&group, "step", frames, &format!("{at}/step"))?;
    Ok(Some(Element::Series {
        group,
        value,
        steps,
    }))
}

/// The `step` (i64) or `time` (f64, as read) of `frames` samples: a dataset of one per
/// sample, or a scalar increment with an optional `offset` attribute.
fn series(g: &Group, name: &str, frames: usize, at: &str) -> std::result::Result<Vec<i64>, Fault> {
    let ds = g
        .dataset(name)
        .map_err(|_| (at.to_string(), format!("no `{name}` dataset")))?;
    if ds.is_scalar() {
        let step: i64 = ds.read_scalar().map_err(|e| (at.to_string(), line(e)))?;
        let offset: i64 = ds.attr("offset").and_then(|a| a.read_scalar()).unwrap_or(0);
        return Ok((0..frames as i64)
            .map(|k| offset.saturating_add(k.saturating_mul(step)))
            .collect());
    }
    let steps: Vec<i64> = checked_read(&ds, at)?;
    if steps.len() != frames {
        return Err((
            at.to_string(),
            format!("{} steps for {frames} samples of `value`", steps.len()),
        ));
    }
    Ok(steps)
}

/// The `time` of each of `frames` samples, if the group has a `time`.
fn times(g: &Group, frames: usize, at: &str) -> std::result::Result<Option<Vec<f64>>, Fault> {
    let Ok(ds) = g.dataset("time") else {
        return Ok(None);
    };
    if ds.is_scalar() {
        let dt: f64 = ds.read_scalar().map_err(|e| (at.to_string(), line(e)))?;
        let offset: f64 = ds
            .attr("offset")
            .and_then(|a| a.read_scalar())
            .unwrap_or(0.0);
        return Ok(Some((0..frames).map(|k| offset + k as f64 * dt).collect()));
    }
    let t: Vec<f64> = checked_read(&ds, at)?;
    if t.len() != frames {
        return Err((
            at.to_string(),
            format!("{} times for {frames} samples", t.len()),
        ));
    }
    Ok(Some(t))
}

/// A whole dataset, refused if it claims more values than haff reads.
fn checked_read<T: hdf5::H5Type>(ds: &Dataset, at: &str) -> std::result::Result<Vec<T>, Fault> {
    let size: usize = ds
        .shape()
        .iter()
        .try_fold(1usize, |a, &b| a.checked_mul(b))
        .unwrap_or(usize::MAX);
    if size > MOST_VALUES {
        return Err((
            at.to_string(),
            format!("shape {:?}: more values than haff reads", ds.shape()),
        ));
    }
    ds.read_raw::<T>().map_err(|e| (at.to_string(), line(e)))
}

/// The values of `e` at `step` (a time-independent dataset: its only sample), of the
/// sample shape `sample`, row-major.
fn values(
    e: &Element,
    step: Option<i64>,
    sample: &[usize],
    at: &str,
) -> std::result::Result<Vec<f64>, Fault> {
    let want: usize = sample.iter().product();
    let (ds, index) = match e {
        Element::Fixed(ds) => (ds, None),
        Element::Series { value, steps, .. } => {
            let k = match step {
                Some(s) => steps.iter().position(|t| *t == s).ok_or_else(|| {
                    (
                        at.to_string(),
                        format!("no sample at step {s}, the position's"),
                    )
                })?,
                // Positions without time: the element's first sample.
                None => 0,
            };
            (value, Some(k))
        }
    };
    let shape = ds.shape();
    let inner = match index {
        Some(_) => shape.get(1..).unwrap_or(&[]),
        None => &shape[..],
    };
    if inner != sample {
        let expected = match index {
            Some(_) => format!("[frames]{sample:?}"),
            None => format!("{sample:?}"),
        };
        return Err((
            at.to_string(),
            format!("shape {shape:?}; allowed: {expected}"),
        ));
    }
    if want > MOST_VALUES {
        return Err((
            at.to_string(),
            format!("shape {shape:?}: more values than haff reads"),
        ));
    }
    let read = match (index, sample.len()) {
        (None, _) => ds.read_raw::<f64>(),
        (Some(k), 1) => ds
            .read_slice_1d::<f64, _>(s![k, ..])
            .map(|a| a.into_raw_vec_and_offset().0),
        (Some(k), 2) => ds
            .read_slice_2d::<f64, _>(s![k, .., ..])
            .map(|a| a.into_raw_vec_and_offset().0),
        _ => return Err((at.to_string(), format!("shape {shape:?}"))),
    };
    read.map_err(|e| (at.to_string(), line(e)))
}

/// Vectors of `width` components (the rest 0) of `e` at `step`.
fn vectors(
    e: &Element,
    step: Option<i64>,
    width: usize,
    at: &str,
) -> std::result::Result<Vec<Vec3>, Fault> {
    let shape = match e {
        Element::Fixed(ds) => ds.shape(),
        Element::Series { value, .. } => value.shape().get(1..).unwrap_or(&[]).to_vec(),
    };
    let n = shape.first().copied().unwrap_or(0);
    let flat = values(e, step, &[n, width], at)?;
    Ok(flat
        .chunks_exact(width)
        .map(|c| {
            let mut v = [0.0; 3];
            v[..width].copy_from_slice(c);
            v
        })
        .collect())
}
