//! Navier–Stokes transport coefficients of smooth inelastic hard spheres (D = 3) and disks
//! (D = 2) with a constant restitution α, from the Chapman–Enskog solution in the (standard)
//! first Sonine approximation: the dilute gas of Brey, Dufty, Kim & Santos (Phys. Rev. E 58,
//! 4638 (1998), D-dimensional in Brey & Cubero 2001 and Garzó, Santos & Montanero, Physica A
//! 376, 94 (2007)) and the Enskog gas of Garzó & Dufty (Phys. Rev. E 59, 5895 (1999);
//! D-dimensional as in Garzó, Dufty & Hrenya, Phys. Rev. E 76, 031303 (2007) and Garzó,
//! *Granular Gaseous Flows*, Springer 2019). The constitutive relations are
//!
//!   P_ij = p δ_ij − η (∂_i u_j + ∂_j u_i − (2/D) δ_ij ∇·u) − γ δ_ij ∇·u,
//!   q = −κ ∇T − μ ∇n,   j_tracer = −D_s ∇n_tracer.
//!
//! Units: η0 = (D+2) Γ(D/2) / (8 π^{(D−1)/2}) σ^{1−D} (m T)^{1/2} ([`dilute_elastic_viscosity`]),
//! ν0 = n T / η0, κ0 = D (D+2) / (2(D−1)) η0 / m, D0 = 2D/(D+2) T / (m ν0) (the elastic dilute
//! values: 5/(16σ²) (mT/π)^{1/2}, 75/(64σ²) (T/(πm))^{1/2}, 3/(8nσ²) (T/(πm))^{1/2} in 3D;
//! 1/(2σ) (mT/π)^{1/2}, (2/σ) (T/(πm))^{1/2}, 1/(2nσ) (T/(πm))^{1/2} in 2D). Reduced: η* = η/η0,
//! γ* = γ/η0, κ* = κ/κ0, μ* = n μ / (T κ0), D* = D_s/D0, ζ* = ζ/ν0; χ the contact value
//! ([`contact_value`]), p* = p/(nT) = 1 + 2^{D−2} (1+α) φ χ, a2 of van Noije & Ernst
//! ([`van_noije_ernst_a2`]).
//!
//! The collision frequencies (dilute; the Enskog ones are χ times these):
//!
//!   ζ*   = (D+2)/(4D) (1 − α²) (1 + 3a2/16),
//!   ν_η* = 3/(4D) (1 − α + 2D/3) (1 + α) (1 − a2/32),
//!   ν_κ* = (1+α)/D [(D−1)/2 + 3(D+8)(1−α)/16 + (4 + 5D − 3(4−D)α) a2/512],
//!   ν_D* = (D+2)/(2D) (1+α)/2 (1 − a2/32)   (tracer identical to the gas; derived below).
//!
//! The coefficients (Garzó & Dufty 1999 in D dimensions; the dilute gas is φ = 0):
//!
//!   η_k* = [1 − 2^{D−2}/(D+2) (1+α)(1−3α) φχ] / (ν_η* − ζ*/2),
//!   η*   = η_k* [1 + 2^{D−1}/(D+2) φχ (1+α)] + D/(D+2) γ*,
//!   γ*   = 2^{2D+1} / (π(D+2)) φ² χ (1+α) (1 − a2/16),
//!   κ_k* = (D−1)/D [1 + 2a2 + 3·2^{D−3}/(D+2) φχ (1+α)² (2α − 1 + a2(1+α))] / (ν_κ* − 2ζ*),
//!   κ*   = κ_k* [1 + 3·2^{D−2}/(D+2) φχ (1+α)] + 2^{2D+1}(D−1)/((D+2)² π) φ²χ (1+α)(1 + 7a2/16),
//!   μ_k* = 2 [ζ* κ_k* (1 + φ ∂_φ ln χ) + (D−1)/D a2 p* (1 + φ ∂_φ ln p*) − R] / (2ν_κ* − 3ζ*),
//!   μ*   = μ_k* [1 + 3·2^{D−2}/(D+2) φχ (1+α)],
//!   D*   = (D+2)/(2D) / (ν_D* − ζ*/2)   (Enskog: ν_D*, ζ* times χ, no collisional transfer),
//!
//! with R = 4/5 φχ (1 + (φ/2) ∂_φ ln χ)(1+α)[α(1−α) + (2/3 + α(1−α)/2) a2] in 3D (Garzó &
//! Dufty 1999; its D-dimensional form is not implemented, so μ of the Enskog gas of disks at
//! φ > 0 is `None`). The κ_k* above is Garzó & Dufty's 3D form with their a2 terms
//! (1/2)(1+p*)·2a2 and −5/(3(1+α))·2a2 collected: these cancel to 2a2 (test
//! `enskog_heat_flux_is_garzo_dufty_3d`).
//!
//! Derivations checked here. The dilute κ and μ follow from the moment of the first-order
//! Chapman–Enskog equation with (m V²/2) V: the source (D+2)/(2m) [(1 + 2a2) n T ∇T +
//! a2 T² ∇n] (from ⟨V⁴⟩ = (1 + a2) D(D+2) T²/m²), the collisional moment −ν_κ q, and
//! ∂_t^{(0)} q = 2ζ κ ∇T + (ζ κ T/n + 3ζ μ/2) ∇n (κ ∝ T^{1/2}, μ ∝ T^{3/2}/n, ζ ∝ n T^{1/2}),
//! so (ν_κ − 2ζ) κ = (D+2) n T (1 + 2a2)/(2m) and (ν_κ − 3ζ/2) μ = ζ κ T/n + (D+2) a2 T²/(2m):
//! the dilute forms above. The self-diffusion frequency: the momentum lost by a tagged
//! particle, (1+α)/2 times the elastic one, ∫ de Θ(ĝ·e)(ĝ·e)² e ∝ ĝ, and the gas's a2 enters
//! through ⟨|g| g·c1 S_2(c2²)⟩ = −⟨|g|³⟩/64 (Gaussian moments; c = V/v0), against the elastic
//! ⟨|g|³⟩/2: the factor 1 − a2/32; D* = 4/((1+α)(1 + α − (4 − 3α) a2/16)) (Brey, Ruiz-Montero,
//! Cubero & García-Rojo, Phys. Fluids 12, 876 (2000) in this first Sonine form).
//! Tests: the collision frequencies against Gauss quadrature of the collision integrals
//! ([`collision_integrals`]); α = 1 against Chapman & Cowling (3D) and Gass (2D); Garzó &
//! Dufty's printed 3D forms; the shear viscosity of [`HcsTransport`] and the elastic
//! conductivity [`super::enskog_thermal_conductivity`] now come from here.
//!
//! [`HcsTransport`]: super::HcsTransport

#[cfg(test)]
pub(crate) mod collision_integrals;

use super::hydrodynamics::dilute_elastic_viscosity;
use super::{collision_frequency, contact_value, van_noije_ernst_a2};
use std::f64::consts::PI;

/// The dilute collision frequencies in units of ν0 = n T / η0 (multiply by χ for the Enskog
/// gas) at restitution α and Sonine coefficient a2 (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CollisionFrequencies {
    /// ζ*, the cooling rate.
    pub cooling: f64,
    /// ν_η*, the relaxation of the traceless pressure tensor.
    pub shear: f64,
    /// ν_κ*, the relaxation of the heat flux.
    pub heat: f64,
    /// ν_D*, the relaxation of a tagged particle's mean velocity.
    pub diffusion: f64,
}

/// The collision frequencies of the dilute gas, D = 2 or 3 (first Sonine approximation).
pub fn collision_frequencies<const D: usize>(alpha: f64, a2: f64) -> CollisionFrequencies {
    let d = D as f64;
    CollisionFrequencies {
        cooling: (d + 2.0) / (4.0 * d) * (1.0 - alpha * alpha) * (1.0 + 3.0 * a2 / 16.0),
        shear: 3.0 / (4.0 * d) * (1.0 - alpha + 2.0 * d / 3.0) * (1.0 + alpha) * (1.0 - a2 / 32.0),
        heat: (1.0 + alpha) / d
            * (0.5 * (d - 1.0)
                + 3.0 * (d + 8.0) * (1.0 - alpha) / 16.0
                + (4.0 + 5.0 * d - 3.0 * (4.0 - d) * alpha) * a2 / 512.0),
        diffusion: (d + 2.0) / (2.0 * d) * 0.5 * (1.0 + alpha) * (1.0 - a2 / 32.0),
    }
}

/// d ln χ / dφ of [`contact_value`]: Henderson (2D) −7/(16 − 7φ) + 2/(1 − φ),
/// Carnahan–Starling (3D) −1/(2 − φ) + 3/(1 − φ).
pub fn log_contact_value_slope<const D: usize>(phi: f64) -> f64 {
    match D {
        2 => -7.0 / (16.0 - 7.0 * phi) + 2.0 / (1.0 - phi),
        _ => -1.0 / (2.0 - phi) + 3.0 / (1.0 - phi),
    }
}

/// The reduced coefficients (units in the module documentation): depend on φ and α only.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReducedTransport {
    /// p* = p / (n T).
    pub pressure: f64,
    /// η* = η / η0.
    pub shear_viscosity: f64,
    /// γ* = γ / η0 (0 for the dilute gas).
    pub bulk_viscosity: f64,
    /// κ* = κ / κ0.
    pub thermal_conductivity: f64,
    /// μ* = n μ / (T κ0); `None` for the Enskog gas of disks at φ > 0 (not implemented).
    pub mu: Option<f64>,
    /// D* = D_s / D0 (tracer diffusion of a particle like the gas's).
    pub self_diffusion: f64,
    /// ζ* = ζ / ν0.
    pub cooling_rate: f64,
    /// The Sonine coefficient a2 of the homogeneous cooling state.
    pub a2: f64,
}

impl ReducedTransport {
    /// The Enskog gas at packing fraction φ (φ = 0: the dilute gas), restitution α, D = 2, 3.
    pub fn enskog<const D: usize>(phi: f64, alpha: f64) -> Self {
        assert!(D == 2 || D == 3, "transport coefficients: D = 2 or 3");
        let d = D as f64;
        let chi = contact_value::<D>(phi);
        let a2 = van_noije_ernst_a2::<D>(alpha);
        let nu = collision_frequencies::<D>(alpha, a2);
        let (zeta, nu_eta, nu_kappa) = (chi * nu.cooling, chi * nu.shear, chi * nu.heat);
        let two = |k: i32| 2f64.powi(k);
        let (pc, one_a) = (phi * chi, 1.0 + alpha);
        let pressure = 1.0 + two(D as i32 - 2) * one_a * pc;
        let bulk = two(2 * D as i32 + 1) / (PI * (d + 2.0)) * phi * pc * one_a * (1.0 - a2 / 16.0);
        let eta_k = (1.0 - two(D as i32 - 2) / (d + 2.0) * one_a * (1.0 - 3.0 * alpha) * pc)
            / (nu_eta - 0.5 * zeta);
        let shear =
            eta_k * (1.0 + two(D as i32 - 1) / (d + 2.0) * pc * one_a) + d / (d + 2.0) * bulk;
        let heat_transfer = 1.0 + 3.0 * two(D as i32 - 2) / (d + 2.0) * pc * one_a;
        let kappa_k = (d - 1.0) / d
            * (1.0
                + 2.0 * a2
                + 3.0 * two(D as i32 - 3) / (d + 2.0)
                    * pc
                    * one_a
                    * one_a
                    * (2.0 * alpha - 1.0 + a2 * one_a))
            / (nu_kappa - 2.0 * zeta);
        let kappa = kappa_k * heat_transfer
            + two(2 * D as i32 + 1) * (d - 1.0) / ((d + 2.0).powi(2) * PI)
                * phi
                * pc
                * one_a
                * (1.0 + 7.0 * a2 / 16.0);
        let mu = Self::mu_kinetic::<D>(phi, alpha, a2, zeta, nu_kappa, kappa_k, pressure)
            .map(|mu_k| mu_k * heat_transfer);
        ReducedTransport {
            pressure,
            shear_viscosity: shear,
            bulk_viscosity: bulk,
            thermal_conductivity: kappa,
            mu,
            self_diffusion: (d + 2.0) / (2.0 * d) / (chi * (nu.diffusion - 0.5 * nu.cooling)),
            cooling_rate: zeta,
            a2,
        }
    }

    /// μ_k* (module documentation); `None` where R is not implemented (D = 2, φ > 0).
    fn mu_kinetic<const D: usize>(
        phi: f64,
        alpha: f64,
        a2: f64,
        zeta: f64,
        nu_kappa: f64,
        kappa_k: f64,
        pressure: f64,
    ) -> Option<f64> {
        let d = D as f64;
        let chi = contact_value::<D>(phi);
        let slope = phi * log_contact_value_slope::<D>(phi);
        // φ ∂_φ p* = (p* − 1)(1 + φ ∂_φ ln χ).
        let pressure_slope = (pressure - 1.0) * (1.0 + slope);
        let transfer = if phi == 0.0 {
            0.0
        } else if D == 3 {
            let inelastic = alpha * (1.0 - alpha);
            0.8 * phi
                * chi
                * (1.0 + 0.5 * slope)
                * (1.0 + alpha)
                * (inelastic + (2.0 / 3.0 + 0.5 * inelastic) * a2)
        } else {
            return None;
        };
        let source = zeta * kappa_k * (1.0 + slope)
            + (d - 1.0) / d * a2 * (pressure + pressure_slope)
            - transfer;
        Some(2.0 * source / (2.0 * nu_kappa - 3.0 * zeta))
    }
}

/// The Navier–Stokes transport coefficients and the cooling rate of the homogeneous cooling
/// state, in the units of the arguments (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NavierStokes {
    /// Hydrostatic pressure p = n T p*.
    pub pressure: f64,
    /// Shear viscosity η.
    pub shear_viscosity: f64,
    /// Bulk viscosity γ (0 in the dilute gas).
    pub bulk_viscosity: f64,
    /// Thermal conductivity κ (q = −κ ∇T − μ ∇n).
    pub thermal_conductivity: f64,
    /// The coefficient μ of the density gradient in the heat flux (`None`: not implemented).
    pub mu: Option<f64>,
    /// Self-diffusion coefficient D_s.
    pub self_diffusion: f64,
    /// Cooling rate ζ = −d ln T / dt.
    pub cooling_rate: f64,
    /// The Sonine coefficient a2 used.
    pub a2: f64,
}

impl NavierStokes {
    /// The Boltzmann (dilute) gas: [`Self::enskog`] at φ = 0.
    pub fn dilute<const D: usize>(
        density: f64,
        diameter: f64,
        mass: f64,
        temperature: f64,
        alpha: f64,
    ) -> Self {
        Self::enskog::<D>(density, diameter, mass, temperature, 0.0, alpha)
    }

    /// The Enskog gas at number density n and packing fraction φ (given separately: φ = 0 is
    /// the Boltzmann gas at any n).
    pub fn enskog<const D: usize>(
        density: f64,
        diameter: f64,
        mass: f64,
        temperature: f64,
        phi: f64,
        alpha: f64,
    ) -> Self {
        let r = ReducedTransport::enskog::<D>(phi, alpha);
        let d = D as f64;
        let eta0 = dilute_elastic_viscosity::<D>(diameter, mass, temperature);
        let nu0 = density * temperature / eta0;
        let kappa0 = d * (d + 2.0) / (2.0 * (d - 1.0)) * eta0 / mass;
        let diffusion0 = 2.0 * d / (d + 2.0) * temperature / (mass * nu0);
        NavierStokes {
            pressure: density * temperature * r.pressure,
            shear_viscosity: eta0 * r.shear_viscosity,
            bulk_viscosity: eta0 * r.bulk_viscosity,
            thermal_conductivity: kappa0 * r.thermal_conductivity,
            mu: r.mu.map(|mu| mu * temperature * kappa0 / density),
            self_diffusion: diffusion0 * r.self_diffusion,
            cooling_rate: nu0 * r.cooling_rate,
            a2: r.a2,
        }
    }
}

/// The Chapman–Enskog viscosity of elastic hard spheres (3D) over its first Sonine
/// approximation η0 = 5/(16σ²) (mT/π)^{1/2}: the converged Sonine series, 1.016034
/// (Pekeris & Alterman 1957; Chapman & Cowling 1970, §10.21). Its second and third orders
/// (1 + 3/202, 1.01588) are computed from the collision integrals by test
/// `elastic_viscosity_sonine_series_is_chapman_cowling`, which bounds the rest of the series.
pub const ELASTIC_VISCOSITY_SONINE_FACTOR: f64 = 1.016034;

/// The Chapman–Enskog thermal conductivity of elastic hard spheres (3D) over its first
/// Sonine approximation κ0 = 75/(64σ²) (T/(πm))^{1/2}: the converged series, 1.025218
/// (Pekeris & Alterman 1957; Chapman & Cowling 1970, §10.21). Its second order 1 + 1/44 and
/// third are computed from the collision integrals by test
/// `elastic_conductivity_sonine_series_is_chapman_cowling`.
pub const ELASTIC_CONDUCTIVITY_SONINE_FACTOR: f64 = 1.025218;

/// ν0 / ω: the unit of the reduced rates, n T / η0, over the Maxwellian collision frequency
/// ω of [`collision_frequency`] (4/5 in 3D, 1 in 2D).
pub fn reference_over_collision_frequency<const D: usize>() -> f64 {
    1.0 / dilute_elastic_viscosity::<D>(1.0, 1.0, 1.0)
        / collision_frequency::<D>(1.0, 1.0, 1.0, 1.0, 0.0)
}

#[cfg(test)]
mod tests;
