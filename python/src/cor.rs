//! The coefficient of restitution: `eps`, `eps_v`, `beta`, `dashpot_eps`, `validity`.

use crate::{config_error, out_of_range};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use restitution::dashpot::{dashpot, DashpotCriterion};
use restitution::exact::VSTAR_MAX;
use restitution::material::{
    material_by_name, speed_from_vstar, ContactPair, Material, Sphere, UnitSystem,
};
use restitution::{Restitution, ScaledForm, Viscoelastic};

/// The beta (any unit system) `eps_v` accepts, as `haff cor eps --beta`: beyond it the
/// speeds of v* <= 1e6 underflow or overflow f64.
const BETA_RANGE: (f64, f64) = (1e-30, 1e30);

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

/// The first value of `values` outside `low ..= high` (or NaN), as an error naming `key`.
fn check_range(key: &str, values: &[f64], low: f64, high: f64) -> PyResult<()> {
    match values.iter().position(|x| !(low..=high).contains(x)) {
        None => Ok(()),
        Some(i) => Err(out_of_range(
            &format!("{key}[{i}]"),
            values[i],
            &format!("{low} <= {key} <= {high}"),
        )),
    }
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
    check_range("vstar", values, 0.0, VSTAR_MAX)?;
    let (out, beyond) = py.detach(|| {
        let validity = form.validity();
        let out: Vec<f64> = values.iter().map(|&v| form.eps(v)).collect();
        let beyond = values.iter().filter(|&&v| !validity.contains(v)).count();
        (out, beyond)
    });
    Ok((
        PyArray1::from_vec(py, out),
        beyond,
        form.validity().to_string(),
    ))
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
    if !(BETA_RANGE.0..=BETA_RANGE.1).contains(&beta) {
        return Err(out_of_range(
            "beta",
            beta,
            &format!("{} <= beta <= {}", BETA_RANGE.0, BETA_RANGE.1),
        ));
    }
    let form = parse_law(law)?;
    let v_max = speed_from_vstar(beta, VSTAR_MAX).map_err(|e| config_error("beta", e))?;
    let speeds = v.as_slice()?;
    check_range("v", speeds, 0.0, v_max)?;
    let validity = form.validity().to_string();
    let viscoelastic = Viscoelastic::new(beta, form).map_err(|e| config_error("beta", e))?;
    let (out, beyond) = py.detach(|| {
        let validity = viscoelastic.form().validity();
        let out: Vec<f64> = speeds.iter().map(|&s| viscoelastic.eps(s)).collect();
        let beyond = speeds
            .iter()
            .filter(|&&s| !validity.contains(viscoelastic.vstar(s)))
            .count();
        (out, beyond)
    });
    Ok((PyArray1::from_vec(py, out), beyond, validity))
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
    let criterion = match criterion.trim() {
        "improved" => DashpotCriterion::Improved,
        "naive" => DashpotCriterion::Naive,
        other => {
            return Err(config_error(
                "criterion",
                format!("'{other}' is not a criterion; allowed: improved, naive"),
            ))
        }
    };
    let ratios = damping_ratio.as_slice()?;
    check_range("damping_ratio", ratios, 0.0, f64::MAX)?;
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
