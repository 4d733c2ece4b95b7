//! Observables of the velocity distribution.

use crate::system::{dot, System};

/// Granular temperature T = <m |c|^2> / D with c the peculiar velocity.
pub fn temperature<const D: usize>(s: &System<D>) -> f64 {
    let (mean, _) = mean_velocity(s);
    let sum: f64 = s
        .velocities
        .iter()
        .zip(&s.masses)
        .map(|(v, m)| {
            let c: [f64; D] = std::array::from_fn(|k| v[k] - mean[k]);
            m * dot(&c, &c)
        })
        .sum();
    sum / (s.len() * D) as f64
}

/// The Sonine coefficient a2 = D/(D+2) <c^4>/<c^2>^2 - 1 of the peculiar velocities.
pub fn sonine_a2<const D: usize>(s: &System<D>) -> f64 {
    let (mean, _) = mean_velocity(s);
    let (mut c2, mut c4) = (0.0, 0.0);
    for v in &s.velocities {
        let c: [f64; D] = std::array::from_fn(|k| v[k] - mean[k]);
        let x = dot(&c, &c);
        c2 += x;
        c4 += x * x;
    }
    let n = s.len() as f64;
    D as f64 / (D as f64 + 2.0) * (c4 / n) / (c2 / n).powi(2) - 1.0
}

/// Kinetic energy.
pub fn kinetic_energy<const D: usize>(s: &System<D>) -> f64 {
    s.velocities
        .iter()
        .zip(&s.masses)
        .map(|(v, m)| 0.5 * m * dot(v, v))
        .sum()
}

/// Mass-weighted mean velocity and total momentum.
pub fn mean_velocity<const D: usize>(s: &System<D>) -> ([f64; D], [f64; D]) {
    let total: f64 = s.masses.iter().sum();
    let p: [f64; D] = std::array::from_fn(|k| {
        s.velocities
            .iter()
            .zip(&s.masses)
            .map(|(v, m)| m * v[k])
            .sum()
    });
    (std::array::from_fn(|k| p[k] / total), p)
}
