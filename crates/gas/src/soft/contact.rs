//! The viscoelastic normal force of two spheres in contact, Eq. (2) of Müller & Pöschel
//! 2011 (MP2011): the Hertz force plus its viscoelastic dissipative part, clamped to be
//! repulsive,
//!
//!   F = max(0, ρ ξ^{3/2} + (3/2) A ρ √ξ ξ̇),   ρ = 2 Y √R_eff / (3 (1 − ν²)),
//!
//! with ξ the overlap, ξ̇ its rate, Y, ν and A the material's Young modulus, Poisson ratio
//! and dissipative constant, and R_eff = R1 R2 / (R1 + R2). The clamp ends a collision
//! when the force vanishes, before the overlap does (the improved criterion of Schwager &
//! Pöschel 2008): this is the force whose coefficient of restitution
//! `restitution::exact` computes, with β = (3/2) A (ρ / m_eff)^{2/5} (Eq. (8) of MP2011).

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// A viscoelastic material in the units of the run (any consistent units: the force of
/// Eq. (2) is Y times an area).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViscoelasticMaterial {
    /// Young modulus Y > 0.
    pub young: f64,
    /// Poisson ratio ν in (−1, 1/2).
    pub poisson: f64,
    /// Dissipative constant A >= 0 (a time).
    pub dissipative_constant: f64,
}

impl ViscoelasticMaterial {
    /// A validated material; errors name `young`, `poisson` or `dissipative_constant`.
    pub fn new(young: f64, poisson: f64, dissipative_constant: f64) -> Result<Self> {
        let material = ViscoelasticMaterial {
            young,
            poisson,
            dissipative_constant,
        };
        material.validate()?;
        Ok(material)
    }

    /// Checks the ranges (for materials read from check-points).
    pub fn validate(&self) -> Result<()> {
        if !(self.young.is_finite() && self.young > 0.0) {
            return Err(Error::out_of_range("young", self.young, "a finite Y > 0"));
        }
        if !(self.poisson.is_finite() && self.poisson > -1.0 && self.poisson < 0.5) {
            return Err(Error::out_of_range(
                "poisson",
                self.poisson,
                "-1 < nu < 0.5",
            ));
        }
        let a = self.dissipative_constant;
        if !(a.is_finite() && a >= 0.0) {
            return Err(Error::out_of_range(
                "dissipative_constant",
                a,
                "a finite A >= 0",
            ));
        }
        Ok(())
    }

    /// ρ = 2 Y √R_eff / (3 (1 − ν²)) of a pair of radii r1, r2 (Eq. (3) of MP2011).
    pub fn elastic_constant(&self, r1: f64, r2: f64) -> f64 {
        let effective_radius = r1 * r2 / (r1 + r2);
        2.0 * self.young * effective_radius.sqrt() / (3.0 * (1.0 - self.poisson * self.poisson))
    }

    /// ρ_w = 2 Y √R / (3 (1 − ν²)) of a sphere of radius r against a half-space of the
    /// same material (R_eff = r: Eq. (3) of MP2011 with the second radius infinite).
    pub fn wall_constant(&self, r: f64) -> f64 {
        2.0 * self.young * r.sqrt() / (3.0 * (1.0 - self.poisson * self.poisson))
    }

    /// β = (3/2) A (ρ / m_eff)^{2/5} of a pair (Eq. (8) of MP2011): the material constant of
    /// its coefficient of restitution, in the run's units.
    pub fn beta(&self, r1: f64, r2: f64, m1: f64, m2: f64) -> f64 {
        let effective_mass = m1 * m2 / (m1 + m2);
        1.5 * self.dissipative_constant * (self.elastic_constant(r1, r2) / effective_mass).powf(0.4)
    }
}

impl ViscoelasticMaterial {
    /// β of a sphere (r1, m1) of this material against a sphere (r2, m2) of `other`: for
    /// one material [`Self::beta`]; for unlike ones the combined modulus and the
    /// compliance-weighted dissipative constant of [`restitution::material::MaterialPair`].
    pub fn pair_beta(&self, other: &Self, r1: f64, r2: f64, m1: f64, m2: f64) -> f64 {
        if self == other {
            return self.beta(r1, r2, m1, m2);
        }
        let triple = |m: &Self| (m.young, m.poisson, m.dissipative_constant);
        restitution::material::MaterialPair::new(triple(self), triple(other))
            .expect("validated materials")
            .beta(r1, r2, m1, m2)
    }
}

/// The repulsive normal force of Eq. (2) at overlap `xi` > 0 and overlap rate `xi_dot`,
/// for the pair's ρ and the material's A; and its dissipative part (zero when clamped).
#[inline]
pub fn normal_force(rho: f64, a: f64, xi: f64, xi_dot: f64) -> (f64, f64) {
    let root = xi.sqrt();
    let elastic = rho * xi * root;
    let dissipative = 1.5 * a * rho * root * xi_dot;
    let total = elastic + dissipative;
    if total > 0.0 {
        (total, dissipative)
    } else {
        (0.0, -elastic)
    }
}

/// Duration of an elastic Hertz collision of F = ρ ξ^{3/2} between effective mass m_eff
/// at impact speed v: t_c = c (m_eff / ρ)^{2/5} v^{−1/5}. From the energy integral
/// t_c = 2 ∫_0^{ξ_max} dξ / √(v² − (4/5)(ρ/m_eff) ξ^{5/2}), ξ_max = (5 m_eff v² / (4ρ))^{2/5}:
/// c = 2 (5/4)^{2/5} I with I = ∫_0^1 (1 − w^{5/2})^{−1/2} dw = (2/5) B(2/5, 1/2)
/// = (2/5) √π Γ(2/5) / Γ(9/10) (Brilliantov & Pöschel 2004, Ch. 3).
pub fn hertz_duration(rho: f64, effective_mass: f64, v: f64) -> f64 {
    HERTZ_DURATION_COEFFICIENT * (effective_mass / rho).powf(0.4) * v.powf(-0.2)
}

/// Duration of a viscoelastic contact of Eq. (2) of MP2011 (until the force vanishes) at
/// impact speed v: τ_c(v*) (m_eff / ρ)^{2/5} v^{−1/5}, with τ_c the scaled duration of
/// Eq. (9) of MP2011 ([`restitution::exact::solve`], improved criterion) at
/// v* = β^{1/2} v^{1/10}, β = (3/2) A (ρ / m_eff)^{2/5}. Without damping τ_c is the Hertz
/// coefficient ([`hertz_duration`]); damping shortens the contact.
pub fn contact_duration(rho: f64, a: f64, effective_mass: f64, v: f64) -> Result<f64> {
    let beta = 1.5 * a * (rho / effective_mass).powf(0.4);
    let vstar = beta.sqrt() * v.powf(0.1);
    let scaled = restitution::exact::solve(vstar, restitution::exact::Criterion::Improved)?;
    Ok(scaled.duration * (effective_mass / rho).powf(0.4) * v.powf(-0.2))
}

/// c of [`hertz_duration`], 2 (5/4)^{2/5} (2/5) √π Γ(2/5) / Γ(9/10) (Γ from Python's
/// math.gamma); the test recomputes I by quadrature.
pub const HERTZ_DURATION_COEFFICIENT: f64 = 3.218_065_459_719_043_5;

#[cfg(test)]
mod tests {
    use super::*;

    /// The coefficient of the Hertz duration from its integral I = ∫_0^1 (1 − w^{5/2})^{−1/2}
    /// dw, by the midpoint rule after w = 1 − u² (smooth integrand 2u / √(1 − (1 − u²)^{5/2}),
    /// error O(1/n²) ~ 1e-10).
    #[test]
    fn hertz_duration_coefficient() {
        let n = 100_000;
        let integral: f64 = (0..n)
            .map(|i| {
                let u = (i as f64 + 0.5) / n as f64;
                2.0 * u / (1.0 - (1.0 - u * u).powf(2.5)).sqrt() / n as f64
            })
            .sum();
        let coefficient = 2.0 * 1.25f64.powf(0.4) * integral;
        assert!(
            (coefficient / HERTZ_DURATION_COEFFICIENT - 1.0).abs() < 1e-8,
            "{coefficient}"
        );
    }

    /// Undamped, the contact lasts the Hertz duration; damping shortens it.
    #[test]
    fn damped_contacts_are_shorter_than_hertz() {
        let (rho, m, v) = (3.0, 0.5, 2.0);
        let hertz = hertz_duration(rho, m, v);
        assert!((contact_duration(rho, 0.0, m, v).unwrap() / hertz - 1.0).abs() < 1e-10);
        let mut previous = hertz;
        for a in [0.01, 0.1, 1.0, 10.0] {
            let damped = contact_duration(rho, a, m, v).unwrap();
            println!("A = {a}: t_c / t_Hertz = {}", damped / hertz);
            assert!(damped < previous, "A = {a}");
            previous = damped;
        }
    }

    #[test]
    fn force_is_clamped_repulsive() {
        let (f, d) = normal_force(2.0, 0.1, 0.01, -10.0);
        assert_eq!(f, 0.0);
        assert!(d < 0.0);
        let (f, d) = normal_force(2.0, 0.1, 0.01, 0.5);
        assert!((f - (2.0 * 1e-3 + 1.5 * 0.1 * 2.0 * 0.1 * 0.5)).abs() < 1e-15);
        assert!((d - 0.015).abs() < 1e-15);
    }

    #[test]
    fn bad_materials_name_the_key() {
        for (m, key) in [
            (ViscoelasticMaterial::new(0.0, 0.3, 0.0), "young"),
            (ViscoelasticMaterial::new(1.0, 0.5, 0.0), "poisson"),
            (
                ViscoelasticMaterial::new(1.0, 0.3, -1.0),
                "dissipative_constant",
            ),
        ] {
            assert!(m.unwrap_err().to_string().contains(key));
        }
    }
}
