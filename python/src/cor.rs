//! The coefficient of restitution: `eps`, `eps_v`, `beta`, `dashpot_eps`, `validity`.

use crate::{bounds, config_error, out_of_range, within};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use rayon::prelude::*;
use restitution::dashpot::{dashpot, DashpotCriterion};
use restitution::exact::VSTAR_MAX;
use restitution::material::{
    material_by_name, speed_from_vstar, ContactPair, Material, Sphere, UnitSystem,
};
use restitution::ranges::{Range, BETA, VSTAR};
use restitution::{Restitution, ScaledForm, Viscoelastic};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(eps, m)?)?;
    m.add_function(wrap_pyfunction!(eps_v, m)?)?;
    m.add_function(wrap_pyfunction!(beta, m)?)?;
    m.add_function(wrap_pyfunction!(dashpot_eps, m)?)?;
    m.add_function(wrap_pyfunction!(law_validity, m)?)?;
    Ok(())
}

/// The scaled form named `law` (every name `haff cor eps --law` takes).
fn parse_law(law: &str) -> PyResult<ScaledForm> {
    law.trim().parse().map_err(|e| config_error("law", e))
}

/// Values per piece of a parallel evaluation; smaller arrays are evaluated in one thread.
const PIECE: usize = 1 << 14;

/// `f` (a law over a slice) at every value, into a new float64 array, with the GIL released
/// (see [`evaluate`]); returns the array and the count of values where `valid` is false.
/// numpy allocates the array (with huge pages for large arrays): fresh pages cost ~4 us
/// each to fault in on this machine kind, 8 ns per value of a 4 KiB page, as much as the
/// fast law itself.
fn evaluated<'py>(
    py: Python<'py>,
    key: &str,
    values: &[f64],
    range: Range,
    f: impl Fn(&[f64], &mut [f64]) + Sync,
    valid: impl Fn(f64) -> bool + Sync,
) -> PyResult<(Bound<'py, PyArray1<f64>>, usize)> {
    // SAFETY: every element is written by `evaluate` before the array reaches Python (or
    // the array is dropped with the error).
    let out = unsafe { PyArray1::new(py, [values.len()], false) };
    // SAFETY: `out` is new, not shared with Python until returned.
    let slice = unsafe { out.as_slice_mut()? };
    let (f, valid) = (&f, &valid);
    let beyond = py.detach(|| evaluate(key, values, slice, range, f, valid))?;
    Ok((out, beyond))
}

/// `f` (a law over a slice) at every value into `out`, in pieces on both cores for large
/// arrays, counting the values where `valid` is false; a value outside `range` (or NaN) is
/// an error naming `key[index]` (and its piece is not evaluated).
fn evaluate(
    key: &str,
    values: &[f64],
    out: &mut [f64],
    range: Range,
    f: impl Fn(&[f64], &mut [f64]) + Sync,
    valid: impl Fn(f64) -> bool + Sync,
) -> PyResult<usize> {
    let in_range = |x: f64| range.contains(x);
    let piece = |(xs, ys): (&[f64], &mut [f64])| {
        let bad = xs.iter().any(|&x| !in_range(x));
        let beyond = xs.iter().filter(|&&x| !valid(x)).count();
        if !bad {
            f(xs, ys);
        }
        (bad, beyond)
    };
    let (bad, beyond) = if values.len() < 4 * PIECE {
        piece((values, out))
    } else {
        values
            .par_chunks(PIECE)
            .zip(out.par_chunks_mut(PIECE))
            .map(piece)
            .reduce(|| (false, 0), |a, b| (a.0 | b.0, a.1 + b.1))
    };
    if bad {
        let i = values.iter().position(|&x| !in_range(x)).unwrap_or(0);
        return Err(out_of_range(
            &format!("{key}[{i}]"),
            values[i],
            &bounds(key, range),
        ));
    }
    Ok(beyond)
}

/// eps(v*) of `law` for every value (the loop in Rust, GIL released). Returns the values and
/// how many lie beyond the form's range of validity (the Python side warns).
#[pyfunction]
#[pyo3(signature = (vstar, law))]
fn eps<'py>(
    py: Python<'py>,
    vstar: PyReadonlyArray1<'py, f64>,
    law: &str,
) -> PyResult<(Bound<'py, PyArray1<f64>>, usize, String)> {
    let form = parse_law(law)?;
    let values = vstar.as_slice()?;
    let validity = form.validity();
    let (out, beyond) = evaluated(
        py,
        "vstar",
        values,
        VSTAR,
        |xs, ys| form.eps_slice(xs, ys),
        |v| validity.contains(v),
    )?;
    Ok((out, beyond, validity.to_string()))
}

/// eps(v) of `law` with v* = beta^(1/2) v^(1/10) (v and beta in one unit system).
#[pyfunction]
#[pyo3(signature = (v, beta, law))]
fn eps_v<'py>(
    py: Python<'py>,
    v: PyReadonlyArray1<'py, f64>,
    beta: f64,
    law: &str,
) -> PyResult<(Bound<'py, PyArray1<f64>>, usize, String)> {
    let beta = within("beta", beta, BETA)?;
    let form = parse_law(law)?;
    let v_max = speed_from_vstar(beta, VSTAR_MAX).map_err(|e| config_error("beta", e))?;
    let speeds = v.as_slice()?;
    let viscoelastic = Viscoelastic::new(beta, form).map_err(|e| config_error("beta", e))?;
    let validity = viscoelastic.form().validity();
    // The speed where v* reaches the end of the validity (no power per value).
    let v_below = speed_from_vstar(beta, validity.below.min(VSTAR_MAX)).unwrap_or(f64::INFINITY);
    let v_below = if validity.below.is_finite() {
        v_below
    } else {
        f64::INFINITY
    };
    let (out, beyond) = evaluated(
        py,
        "v",
        speeds,
        Range::closed("v", 0.0, v_max),
        |xs, ys| {
            for (y, &x) in ys.iter_mut().zip(xs) {
                *y = viscoelastic.eps(x);
            }
        },
        |s| s < v_below,
    )?;
    Ok((out, beyond, validity.to_string()))
}

/// beta of two equal spheres (Eq. (8) of Müller & Pöschel 2011) in `units`.
#[pyfunction]
#[pyo3(signature = (material, radius, dissipative_constant, units, young, poisson, density))]
#[allow(clippy::too_many_arguments)]
fn beta(
    material: Option<&str>,
    radius: f64,
    dissipative_constant: f64,
    units: &str,
    young: Option<f64>,
    poisson: Option<f64>,
    density: Option<f64>,
) -> PyResult<f64> {
    let units: UnitSystem = units.parse().map_err(|e| config_error("units", e))?;
    let base = material
        .map(material_by_name)
        .transpose()
        .map_err(|e| config_error("material", e))?;
    let pick = |given: Option<f64>, from_base: Option<f64>, key: &str| {
        given
            .or(from_base)
            .ok_or_else(|| config_error(key, "missing: give it or material"))
    };
    if !(dissipative_constant.is_finite() && dissipative_constant > 0.0) {
        return Err(out_of_range(
            "dissipative_constant",
            dissipative_constant,
            "a finite number > 0 (A = 0 is an elastic material, eps = 1)",
        ));
    }
    let material = Material::new(
        base.as_ref().map_or("python", |m| m.name.as_str()),
        pick(young, base.as_ref().map(|m| m.young_modulus), "young")?,
        pick(poisson, base.as_ref().map(|m| m.poisson_ratio), "poisson")?,
        pick(density, base.as_ref().map(|m| m.density), "density")?,
        Some(dissipative_constant),
        "python",
    )
    .map_err(|e| config_error("material", e))?;
    let sphere = Sphere::of_material(radius, &material).map_err(|e| config_error("radius", e))?;
    let pair =
        ContactPair::new(&material, sphere, sphere).map_err(|e| config_error("material", e))?;
    let beta_si = pair
        .beta()
        .map_err(|e| config_error("dissipative_constant", e))?;
    Ok(units.beta_from_si(beta_si))
}

/// eps of the linear dash-pot at each damping ratio, with its criterion.
#[pyfunction]
#[pyo3(signature = (damping_ratio, criterion))]
fn dashpot_eps<'py>(
    py: Python<'py>,
    damping_ratio: PyReadonlyArray1<'py, f64>,
    criterion: &str,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    // The viscoelastic criterion's names, as `haff cor dashpot --criterion` parses them.
    let criterion: DashpotCriterion = criterion
        .trim()
        .parse::<restitution::exact::Criterion>()
        .map_err(|e| config_error("criterion", e))?
        .into();
    let ratios = damping_ratio.as_slice()?;
    if let Some(i) = ratios.iter().position(|r| !(0.0..=f64::MAX).contains(r)) {
        return Err(out_of_range(
            &format!("damping_ratio[{i}]"),
            ratios[i],
            "a finite number >= 0",
        ));
    }
    let out = ratios
        .iter()
        .map(|&r| dashpot(r, criterion).map(|o| o.eps))
        .collect::<Result<Vec<f64>, _>>()
        .map_err(|e| config_error("damping_ratio", e))?;
    Ok(PyArray1::from_vec(py, out))
}

/// The range of v* where `law` stands for the viscoelastic law (a Padé up to its first
/// pole or where eps leaves [0, 1], a series up to its radius of convergence), as
/// (low, high, description).
#[pyfunction]
fn law_validity(law: &str) -> PyResult<(f64, f64, String)> {
    let form = parse_law(law)?;
    let validity = form.validity();
    Ok((0.0, validity.below, validity.to_string()))
}
