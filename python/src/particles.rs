//! Particle files from Python (`haff.read_configuration`, `haff.write_configuration`):
//! `sim::particles`' readers and writers, the configuration as a dict of numpy arrays.

use crate::{config_error, sim_error};
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sim::particles::{self, Configuration, Format, Vec3};
use std::path::PathBuf;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(read_configuration, m)?)?;
    m.add_function(wrap_pyfunction!(write_configuration, m)?)?;
    Ok(())
}

fn format_of(name: &str) -> PyResult<Format> {
    Format::parse("format", name).map_err(sim_error)
}

/// Reads frame `frame` of a particle file; with `check`, refuses what a run cannot start
/// from (overlaps, particles outside the box, non-finite values), naming the record.
/// Returns `{"box", "positions", ["velocities", "diameters", "masses", "species",
/// "spins", "time"]}` ((N, D) and (N,) arrays; spins (N, 3)). `sides`: the box of a file
/// that holds none (a `.vtu` not written by haff).
#[pyfunction]
#[pyo3(signature = (path, format, dimension = 3, frame = -1, check = true, sides = None))]
fn read_configuration<'py>(
    py: Python<'py>,
    path: PathBuf,
    format: &str,
    dimension: usize,
    frame: i64,
    check: bool,
    sides: Option<Vec<f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let format = format_of(format)?;
    if !(1..=3).contains(&dimension) {
        return Err(crate::out_of_range("dimension", dimension, "1, 2 or 3"));
    }
    let c = py
        .detach(|| {
            let c = particles::read_with_box(&path, format, dimension, frame, sides.as_deref())?;
            if check {
                c.check(&path, false)?;
            }
            Ok::<_, sim::Error>(c)
        })
        .map_err(sim_error)?;
    let n = c.len();
    let d = c.dimension;
    let dict = PyDict::new(py);
    let matrix = |list: &[Vec3], width: usize| -> PyResult<Bound<'py, PyArray2<f64>>> {
        let flat: Vec<f64> = list.iter().flat_map(|v| v[..width].to_vec()).collect();
        PyArray1::from_vec(py, flat).reshape([n, width])
    };
    dict.set_item("box", PyArray1::from_vec(py, c.sides.clone()))?;
    dict.set_item("positions", matrix(&c.positions, d)?)?;
    if let Some(v) = &c.velocities {
        dict.set_item("velocities", matrix(v, d)?)?;
    }
    if let Some(x) = &c.diameters {
        dict.set_item("diameters", PyArray1::from_vec(py, x.clone()))?;
    }
    if let Some(x) = &c.masses {
        dict.set_item("masses", PyArray1::from_vec(py, x.clone()))?;
    }
    if let Some(s) = &c.species {
        let s: Vec<i64> = s.iter().map(|&k| k as i64).collect();
        dict.set_item("species", PyArray1::from_vec(py, s))?;
    }
    if let Some(w) = &c.spins {
        dict.set_item("spins", matrix(w, 3)?)?;
    }
    if let Some(t) = c.time {
        dict.set_item("time", t)?;
    }
    Ok(dict)
}

/// An (N, width) array of finite-or-not floats as vectors of three (the rest 0), or an
/// error naming `key`.
fn vectors(key: &str, array: PyReadonlyArray2<f64>, n: usize, width: usize) -> PyResult<Vec<Vec3>> {
    let view = array.as_array();
    if view.shape() != [n, width] {
        return Err(config_error(
            key,
            format!("shape {:?}; allowed: ({n}, {width})", view.shape()),
        ));
    }
    Ok(view
        .rows()
        .into_iter()
        .map(|row| {
            let mut v = [0.0; 3];
            for (k, x) in row.iter().enumerate() {
                v[k] = *x;
            }
            v
        })
        .collect())
}

fn scalars(key: &str, array: PyReadonlyArray1<f64>, n: usize) -> PyResult<Vec<f64>> {
    let view = array.as_array();
    if view.len() != n {
        return Err(config_error(
            key,
            format!("{} values for {n} particles", view.len()),
        ));
    }
    Ok(view.to_vec())
}

/// A configuration of the arrays Python gives (as `read_configuration` returns them),
/// their shapes checked against `box` (an empty box: the dimension of `dimension`, the
/// box left to `system.box`).
#[allow(clippy::too_many_arguments)] // the configuration's arrays, each optional
pub(crate) fn configuration(
    r#box: Vec<f64>,
    positions: PyReadonlyArray2<f64>,
    velocities: Option<PyReadonlyArray2<f64>>,
    diameters: Option<PyReadonlyArray1<f64>>,
    masses: Option<PyReadonlyArray1<f64>>,
    species: Option<Vec<usize>>,
    spins: Option<PyReadonlyArray2<f64>>,
    time: Option<f64>,
) -> PyResult<Configuration> {
    let d = match r#box.len() {
        0 => positions.as_array().shape()[1],
        d => d,
    };
    if !(1..=3).contains(&d) {
        return Err(config_error(
            "box",
            format!("{d} sides; allowed: 1, 2 or 3"),
        ));
    }
    let n = positions.as_array().shape()[0];
    Ok(Configuration {
        dimension: d,
        sides: r#box,
        positions: vectors("positions", positions, n, d)?,
        velocities: velocities
            .map(|v| vectors("velocities", v, n, d))
            .transpose()?,
        diameters: diameters.map(|x| scalars("diameters", x, n)).transpose()?,
        masses: masses.map(|x| scalars("masses", x, n)).transpose()?,
        species: species
            .map(|s| {
                if s.len() == n {
                    Ok(s)
                } else {
                    Err(config_error(
                        "species",
                        format!("{} values for {n} particles", s.len()),
                    ))
                }
            })
            .transpose()?,
        spins: spins.map(|w| vectors("spins", w, n, 3)).transpose()?,
        time,
    })
}

/// Writes a configuration (the dict of `read_configuration`) after checking it, as
/// `format`.
#[pyfunction]
#[pyo3(signature = (path, format, r#box, positions, velocities = None, diameters = None,
                    masses = None, species = None, spins = None, time = None))]
#[allow(clippy::too_many_arguments)] // the configuration's arrays, each optional
fn write_configuration(
    py: Python<'_>,
    path: PathBuf,
    format: &str,
    r#box: Vec<f64>,
    positions: PyReadonlyArray2<f64>,
    velocities: Option<PyReadonlyArray2<f64>>,
    diameters: Option<PyReadonlyArray1<f64>>,
    masses: Option<PyReadonlyArray1<f64>>,
    species: Option<Vec<usize>>,
    spins: Option<PyReadonlyArray2<f64>>,
    time: Option<f64>,
) -> PyResult<()> {
    let format = format_of(format)?;
    let c = configuration(
        r#box, positions, velocities, diameters, masses, species, spins, time,
    )?;
    py.detach(|| {
        c.check(&path, false)?;
        particles::write(&path, format, &c)
    })
    .map_err(sim_error)
}
