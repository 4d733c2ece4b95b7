//! Kinetic theory of the homogeneous cooling state (`gas::theory`): the Enskog collision
//! frequency, Haff's time, the Sonine coefficient a2 (any dimension) and the Sonine
//! hierarchy (2D, 3D).

use crate::out_of_range;
use gas::system::ball_volume;
use gas::theory;
use pyo3::prelude::*;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(theory_collision_frequency, m)?)?;
    m.add_function(wrap_pyfunction!(theory_haff_time, m)?)?;
    m.add_function(wrap_pyfunction!(theory_a2, m)?)?;
    m.add_function(wrap_pyfunction!(theory_sonine, m)?)?;
    Ok(())
}

/// `f::<D>(...)` for the dimension `d` (1, 2 or 3), else an error naming `dimension`.
macro_rules! in_dimension {
    ($d:expr, $D:ident => $body:expr) => {
        match $d {
            1 => {
                const $D: usize = 1;
                Ok($body)
            }
            2 => {
                const $D: usize = 2;
                Ok($body)
            }
            3 => {
                const $D: usize = 3;
                Ok($body)
            }
            other => Err(out_of_range("dimension", other, "1, 2 or 3")),
        }
    };
}

/// `x` finite and > 0, else an error naming `key`.
fn positive(key: &str, x: f64) -> PyResult<f64> {
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(out_of_range(key, x, "a finite number > 0"))
    }
}

/// The Enskog collision frequency of one sphere in a Maxwellian gas at packing fraction
/// phi: omega = g2(phi) n sigma^(D-1) S_D sqrt(T / (pi m)), n = phi / V_ball(sigma / 2).
#[pyfunction]
fn theory_collision_frequency(
    dimension: i64,
    packing_fraction: f64,
    temperature: f64,
    diameter: f64,
    mass: f64,
) -> PyResult<f64> {
    let (t, sigma, m) = (
        positive("temperature", temperature)?,
        positive("diameter", diameter)?,
        positive("mass", mass)?,
    );
    in_dimension!(dimension, D => {
        if !(packing_fraction > 0.0 && packing_fraction < theory::close_packing::<D>()) {
            return Err(out_of_range(
                "packing_fraction",
                packing_fraction,
                &format!("0 < phi < {} (close packing)", theory::close_packing::<D>()),
            ));
        }
        let density = packing_fraction / ball_volume::<D>(0.5 * sigma);
        theory::collision_frequency::<D>(density, sigma, m, t, packing_fraction)
    })
}

/// Haff's time tau = 2 D / ((1 - eps^2) omega0): T(t) = T0 / (1 + t/tau)^2.
#[pyfunction]
fn theory_haff_time(dimension: i64, restitution: f64, omega0: f64) -> PyResult<f64> {
    if !(0.0..1.0).contains(&restitution) {
        return Err(out_of_range("restitution", restitution, "0 <= eps < 1"));
    }
    let omega0 = positive("omega0", omega0)?;
    in_dimension!(dimension, D => theory::haff_time::<D>(restitution, omega0))
}

/// a2 of the homogeneous cooling state, first Sonine approximation (van Noije & Ernst 1998).
#[pyfunction]
fn theory_a2(dimension: i64, restitution: f64) -> PyResult<f64> {
    if !(0.0..=1.0).contains(&restitution) {
        return Err(out_of_range("restitution", restitution, "0 <= eps <= 1"));
    }
    in_dimension!(dimension, D => theory::van_noije_ernst_a2::<D>(restitution))
}

/// a_2 ... a_K of the homogeneous cooling state from the Sonine hierarchy truncated at order
/// K = `order` (2 ..= 10; `gas::theory::SonineHierarchy`, Brilliantov & Pöschel 2006),
/// linearized in the a_k (`linear`: at K = 2 van Noije & Ernst, at K = 3 the second Sonine
/// approximation) or with all its terms (None where Newton's method does not converge).
#[pyfunction]
#[pyo3(signature = (dimension, restitution, order = 3, linear = true))]
fn theory_sonine(
    py: Python<'_>,
    dimension: i64,
    restitution: f64,
    order: i64,
    linear: bool,
) -> PyResult<Option<Vec<f64>>> {
    if !(dimension == 2 || dimension == 3) {
        return Err(out_of_range("dimension", dimension, "2 or 3"));
    }
    if !(0.0..=1.0).contains(&restitution) {
        return Err(out_of_range("restitution", restitution, "0 <= eps <= 1"));
    }
    if !(2..=10).contains(&order) {
        return Err(out_of_range("order", order, "2 <= order <= 10"));
    }
    // The collisional moments take seconds at high orders: without the GIL.
    let result = py.detach(|| {
        theory::SonineHierarchy::new(dimension as usize, order as usize, restitution).map(|h| {
            if linear {
                Some(h.linearized())
            } else {
                h.coefficients()
            }
        })
    });
    result.map_err(|e| crate::config_error("restitution", e))
}
