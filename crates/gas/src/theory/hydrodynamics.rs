//! Navier–Stokes hydrodynamics of the homogeneous cooling state (HCS) of smooth inelastic
//! hard spheres (D = 3) and disks (D = 2): the Enskog shear viscosity in the first Sonine
//! approximation (Garzó & Dufty, Phys. Rev. E 59, 5895 (1999), generalized to D dimensions;
//! dilute limit Brey, Dufty, Kim & Santos, Phys. Rev. E 58, 4638 (1998)), the cooling rate,
//! and the linear stability of the transverse (shear) mode.
//!
//! A transverse velocity field u_⊥ e^{ik·r} obeys ∂_t u_⊥ = −ν k² u_⊥ with the kinematic
//! viscosity ν = η / (n m). Measured against the thermal speed v0 ∝ T^{1/2}, which decays as
//! ∂_t v0 = −(ζ/2) v0, the scaled amplitude u_⊥/v0 grows at the rate
//!
//!   s(k) = ζ/2 − ν k²,
//!
//! so the shear mode is unstable for k < k_c = sqrt(ζ / (2ν)), i.e. in boxes longer than
//! L_c = 2π / k_c (Goldhirsch & Zanetti 1993; Brey, Ruiz-Montero & Cubero 1998). ζ, ν and the
//! collision frequency ω all scale as T^{1/2}, so in the collision count of the HCS
//! (dc = ω dt) the rate s(k)/ω is a constant: the normalized transverse energy of the mode
//! grows as exp(2 c s(k)/ω).
//!
//! The D-dimensional Enskog forms used (α the restitution, χ the contact value, φ the packing
//! fraction, η0 the elastic Boltzmann viscosity, ν0 = n T / η0):
//!
//!   ζ* = ζ/ν0 = (D+2)/(4D) χ (1 − α²) (1 + 3 a2/16),
//!   ν_η* = 3/(4D) χ (1 − α + 2D/3) (1 + α) (1 − a2/32),
//!   η_k = η0 [1 − 2^{D−2}/(D+2) (1 + α)(1 − 3α) φ χ] / (ν_η* − ζ*/2),
//!   η = η_k [1 + 2^{D−1}/(D+2) φ χ (1 + α)] + D/(D+2) γ,
//!   γ = 2^{2D+1}/(π (D+2)) φ² χ (1 + α) (1 − a2/16) η0,
//!   η0 = (D+2) Γ(D/2) / (8 π^{(D−1)/2}) σ^{1−D} (m T)^{1/2}.
//!
//! Checks (tests below): at α = 1 they are the Enskog viscosities of Chapman & Cowling (3D,
//! first approximation: η0 [1/χ + 4/5 (bnχ)/χ + 4/25 (1 + 12/π) (bnχ)²/χ], b n = 4φ) and of
//! Gass (2D, J. Chem. Phys. 54, 1898 (1971): η0 [1/χ + 2φ + (1 + 8/π) φ² χ]); the cooling
//! rate is the Haff rate (1 − α²) ω / D of [`super::collision_frequency`] with the Sonine
//! factors; the growth rates are measured by eMD in `docs/structure.md`.

use super::{collision_frequency, contact_value, van_noije_ernst_a2};
use std::f64::consts::PI;

/// Γ(D/2) for D = 1, 2, 3.
fn gamma_half(d: usize) -> f64 {
    match d {
        1 => PI.sqrt(),
        2 => 1.0,
        _ => 0.5 * PI.sqrt(),
    }
}

/// The elastic Boltzmann shear viscosity of hard spheres (first Sonine approximation):
/// η0 = (D+2) Γ(D/2) / (8 π^{(D−1)/2}) σ^{1−D} (m T)^{1/2} (5/(16 σ²) (m T / π)^{1/2} in 3D,
/// 1/(2σ) (m T / π)^{1/2} in 2D).
pub fn dilute_elastic_viscosity<const D: usize>(diameter: f64, mass: f64, temperature: f64) -> f64 {
    let d = D as f64;
    (d + 2.0) * gamma_half(D) / (8.0 * PI.powf(0.5 * (d - 1.0)))
        * diameter.powi(1 - D as i32)
        * (mass * temperature).sqrt()
}

/// The elastic Enskog thermal conductivity of hard spheres (D = 3) and disks (D = 2) at
/// packing fraction phi, first Sonine approximation: Garzó & Dufty's D-dimensional
/// forms (Phys. Rev. E 59, 5895 (1999)) at α = 1, a2 = 0,
///
///   κ = κ0 [(1 + c)² / χ + 2^{2D+2} (D−1) / ((D+2)² π) φ² χ],  c = 3·2^{D−1}/(D+2) φ χ,
///   κ0 = D (D+2) / (2 (D−1)) η0 / m
///
/// (the Eucken ratio: (75/64) (T / (π m))^{1/2} / σ² in 3D, (2/σ) (T / (π m))^{1/2} in 2D).
/// In 3D with b n = 4φ, y = b n χ: κ = κ0 b n [1/y + 6/5 + (9/25 + 32/(25π)) y], Chapman
/// & Cowling's first approximation, whose tabulated 0.7575 (with their higher
/// approximations' factor 1.02513 on the kinetic parts) is 9/25 + 32/(25π) / 1.02513
/// (tests below). In 2D: κ0 [1/χ + 3φ + (9/4 + 4/π) φ² χ].
pub fn enskog_thermal_conductivity<const D: usize>(
    diameter: f64,
    mass: f64,
    temperature: f64,
    phi: f64,
) -> f64 {
    assert!(
        D >= 2,
        "thermal conductivity of hard rods: not defined here"
    );
    let d = D as f64;
    let eta0 = dilute_elastic_viscosity::<D>(diameter, mass, temperature);
    let kappa0 = d * (d + 2.0) / (2.0 * (d - 1.0)) * eta0 / mass;
    let chi = contact_value::<D>(phi);
    let c = 3.0 * 2f64.powi(D as i32 - 1) / (d + 2.0) * phi * chi;
    let collisional =
        2f64.powi(2 * D as i32 + 2) * (d - 1.0) / ((d + 2.0).powi(2) * PI) * phi * phi * chi;
    kappa0 * ((1.0 + c).powi(2) / chi + collisional)
}

/// The transport of the HCS at number density n, packing fraction phi (χ from
/// [`contact_value`], phi = 0 for the Boltzmann gas that DSMC samples), restitution eps and
/// temperature T, with a2 of van Noije & Ernst.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HcsTransport {
    /// Shear viscosity η.
    pub shear_viscosity: f64,
    /// Kinematic viscosity ν = η / (n m).
    pub kinematic_viscosity: f64,
    /// Cooling rate ζ = −d ln T / dt.
    pub cooling_rate: f64,
    /// Collision frequency per particle ω (Enskog, with the factor 1 − a2/16).
    pub collision_frequency: f64,
}

impl HcsTransport {
    /// D = 2 or 3 (the shear mode needs two dimensions).
    pub fn new<const D: usize>(
        density: f64,
        diameter: f64,
        mass: f64,
        temperature: f64,
        phi: f64,
        eps: f64,
    ) -> Self {
        let d = D as f64;
        let chi = contact_value::<D>(phi);
        let a2 = van_noije_ernst_a2::<D>(eps);
        let eta0 = dilute_elastic_viscosity::<D>(diameter, mass, temperature);
        let nu0 = density * temperature / eta0;
        let zeta_star = (d + 2.0) / (4.0 * d) * chi * (1.0 - eps * eps) * (1.0 + 3.0 * a2 / 16.0);
        let nu_eta_star =
            3.0 / (4.0 * d) * chi * (1.0 - eps + 2.0 * d / 3.0) * (1.0 + eps) * (1.0 - a2 / 32.0);
        let kinetic = eta0
            * (1.0
                - 2f64.powi(D as i32 - 2) / (d + 2.0)
                    * (1.0 + eps)
                    * (1.0 - 3.0 * eps)
                    * phi
                    * chi)
            / (nu_eta_star - 0.5 * zeta_star);
        let bulk = 2f64.powi(2 * D as i32 + 1) / (PI * (d + 2.0))
            * phi
            * phi
            * chi
            * (1.0 + eps)
            * (1.0 - a2 / 16.0)
            * eta0;
        let eta = kinetic * (1.0 + 2f64.powi(D as i32 - 1) / (d + 2.0) * phi * chi * (1.0 + eps))
            + d / (d + 2.0) * bulk;
        HcsTransport {
            shear_viscosity: eta,
            kinematic_viscosity: eta / (density * mass),
            cooling_rate: zeta_star * nu0,
            collision_frequency: collision_frequency::<D>(
                density,
                diameter,
                mass,
                temperature,
                phi,
            ) * (1.0 - a2 / 16.0),
        }
    }

    /// The transport that DSMC with the Enskog factor samples ([`crate::SpatialDsmc`]: the
    /// Boltzmann collision operator with its rate multiplied by χ(φ), collision partners
    /// taken in the same cell with no offset): the dilute (φ = 0) coefficients with every
    /// collision rate times χ, and no collisional transfer. So ζ and ω are χ times, η and ν
    /// 1/χ times their dilute values, and L_c is the dilute L_c over χ: in units of the mean
    /// free path, which also shrinks by χ, the instability is that of the dilute gas.
    pub fn enskog_factor_dsmc<const D: usize>(
        density: f64,
        diameter: f64,
        mass: f64,
        temperature: f64,
        phi: f64,
        eps: f64,
    ) -> Self {
        let chi = contact_value::<D>(phi);
        let dilute = Self::new::<D>(density, diameter, mass, temperature, 0.0, eps);
        HcsTransport {
            shear_viscosity: dilute.shear_viscosity / chi,
            kinematic_viscosity: dilute.kinematic_viscosity / chi,
            cooling_rate: dilute.cooling_rate * chi,
            collision_frequency: dilute.collision_frequency * chi,
        }
    }

    /// The growth rate s(k) = ζ/2 − ν k² of the scaled transverse velocity at wave number k.
    pub fn transverse_growth_rate(&self, k: f64) -> f64 {
        0.5 * self.cooling_rate - self.kinematic_viscosity * k * k
    }

    /// s(k) / ω: the growth rate per collision per particle (independent of T in the HCS).
    pub fn transverse_growth_per_collision(&self, k: f64) -> f64 {
        self.transverse_growth_rate(k) / self.collision_frequency
    }

    /// k_c = sqrt(ζ / (2ν)), below which the shear mode grows.
    pub fn critical_wave_number(&self) -> f64 {
        (0.5 * self.cooling_rate / self.kinematic_viscosity).sqrt()
    }

    /// L_c = 2π / k_c: periodic boxes longer than L_c have an unstable shear mode.
    pub fn critical_length(&self) -> f64 {
        2.0 * PI / self.critical_wave_number()
    }
}

/// The long-wavelength limit S(0) of the static structure factor of the homogeneous hard
/// sphere fluid, 1 / (∂(βp)/∂n), from the equation of state Z = 1 + 2^{D−1} φ χ(φ) with the
/// contact value of [`contact_value`] (Carnahan–Starling in 3D: (1−φ)⁴ divided by
/// 1 + 4φ + 4φ² − 4φ³ + φ⁴; Henderson in 2D; Tonks (1−φ)² in 1D). d(φZ)/dφ by a central
/// difference of step 1e-5 (error ~1e-10).
pub fn long_wavelength_structure_factor<const D: usize>(phi: f64) -> f64 {
    let phi_z = |x: f64| x * (1.0 + 2f64.powi(D as i32 - 1) * x * contact_value::<D>(x));
    let h = 1e-5;
    let derivative = if phi > h {
        (phi_z(phi + h) - phi_z(phi - h)) / (2.0 * h)
    } else {
        (phi_z(phi + h) - phi_z(phi)) / h
    };
    1.0 / derivative
}

#[cfg(test)]
mod tests {
    /// Oracles: the dilute values in closed form (Chapman & Cowling's (75/64) (T/(πm))^{1/2}
    /// / σ² in 3D), Chapman & Cowling's 3D Enskog form b n [1/y + 6/5 + 0.7674 y], and
    /// the 2D form expanded by hand.
    #[test]
    fn enskog_conductivities_reduce_to_their_textbook_forms() {
        use super::super::contact_value;
        use super::enskog_thermal_conductivity as kappa;
        use std::f64::consts::PI;
        let k3 = kappa::<3>(1.0, 1.0, 1.0, 0.0);
        assert!((k3 - 75.0 / 64.0 / PI.sqrt()).abs() < 1e-15, "{k3}");
        let k2 = kappa::<2>(1.0, 1.0, 1.0, 0.0);
        assert!((k2 - 2.0 / PI.sqrt()).abs() < 1e-15, "{k2}");
        // Scaling: sqrt(T / m) / sigma^(D-1).
        assert!((kappa::<3>(2.0, 4.0, 9.0, 0.0) - k3 * 1.5 / 4.0).abs() < 1e-15);
        for phi in [0.05, 0.2, 0.4] {
            let (bn, y) = (4.0 * phi, 4.0 * phi * contact_value::<3>(phi));
            let textbook = k3 * bn * (1.0 / y + 1.2 + (0.36 + 32.0 / (25.0 * PI)) * y);
            assert!((kappa::<3>(1.0, 1.0, 1.0, phi) / textbook - 1.0).abs() < 1e-13);
            // Chapman & Cowling's 0.7575 is the same coefficient with 1.02513 factored out
            // (0.75745: equal to the digits they give).
            assert!(((0.36 + 32.0 / (25.0 * PI) / 1.02513) - 0.7575).abs() < 1e-4);
            let chi2 = contact_value::<2>(phi);
            let by_hand = k2 * (1.0 / chi2 + 3.0 * phi + (2.25 + 4.0 / PI) * phi * phi * chi2);
            assert!((kappa::<2>(1.0, 1.0, 1.0, phi) / by_hand - 1.0).abs() < 1e-13);
        }
    }

    use super::*;

    #[test]
    fn elastic_limits_are_the_enskog_viscosities() {
        for phi in [0.0, 0.05, 0.2, 0.4] {
            let n3 = 6.0 * phi / PI;
            let eta0 = dilute_elastic_viscosity::<3>(1.0, 1.0, 1.0);
            assert!((eta0 - 5.0 / (16.0 * PI.sqrt())).abs() < 1e-15);
            let chi = contact_value::<3>(phi);
            let bn_chi = 4.0 * phi * chi;
            let chapman_cowling = eta0
                * (1.0 / chi
                    + 0.8 * bn_chi / chi
                    + 4.0 / 25.0 * (1.0 + 12.0 / PI) * bn_chi * bn_chi / chi);
            let eta = HcsTransport::new::<3>(n3, 1.0, 1.0, 1.0, phi, 1.0).shear_viscosity;
            assert!(
                (eta / chapman_cowling - 1.0).abs() < 1e-12,
                "3D {phi}: {eta} {chapman_cowling}"
            );
            let n2 = 4.0 * phi / PI;
            let eta0 = dilute_elastic_viscosity::<2>(1.0, 1.0, 1.0);
            assert!((eta0 - 0.5 / PI.sqrt()).abs() < 1e-15);
            let chi = contact_value::<2>(phi);
            let gass = eta0 * (1.0 / chi + 2.0 * phi + (1.0 + 8.0 / PI) * phi * phi * chi);
            let eta = HcsTransport::new::<2>(n2, 1.0, 1.0, 1.0, phi, 1.0).shear_viscosity;
            assert!((eta / gass - 1.0).abs() < 1e-12, "2D {phi}: {eta} {gass}");
        }
    }

    /// ζ = (1 − eps²) ω_M (1 + 3a2/16) / D, ω_M the Maxwellian Enskog collision frequency.
    #[test]
    fn cooling_rate_is_haffs() {
        for (phi, eps) in [(0.05, 0.9), (0.25, 0.7)] {
            let n = 6.0 * phi / PI;
            let t = HcsTransport::new::<3>(n, 1.0, 1.0, 2.0, phi, eps);
            let a2 = van_noije_ernst_a2::<3>(eps);
            let omega = collision_frequency::<3>(n, 1.0, 1.0, 2.0, phi);
            let haff = (1.0 - eps * eps) * omega * (1.0 + 3.0 * a2 / 16.0) / 3.0;
            assert!((t.cooling_rate / haff - 1.0).abs() < 1e-12);
            let n = 4.0 * phi / PI;
            let t = HcsTransport::new::<2>(n, 1.0, 1.0, 2.0, phi, eps);
            let a2 = van_noije_ernst_a2::<2>(eps);
            let omega = collision_frequency::<2>(n, 1.0, 1.0, 2.0, phi);
            let haff = (1.0 - eps * eps) * omega * (1.0 + 3.0 * a2 / 16.0) / 2.0;
            assert!((t.cooling_rate / haff - 1.0).abs() < 1e-12);
        }
    }

    /// The dilute 3D viscosity of Brey, Dufty, Kim & Santos (1998):
    /// η = η0 / (ν_η* − ζ*/2), ν_η* = (3 − α)(1 + α)(1 − a2/32)/4, ζ* = 5/12 (1 − α²)(1 + 3a2/16).
    #[test]
    fn dilute_limit_is_brey_dufty_kim_santos() {
        let eps: f64 = 0.8;
        let a2 = van_noije_ernst_a2::<3>(eps);
        let nu = (3.0 - eps) * (1.0 + eps) * (1.0 - a2 / 32.0) / 4.0;
        let zeta = 5.0 / 12.0 * (1.0 - eps * eps) * (1.0 + 3.0 * a2 / 16.0);
        let expected = dilute_elastic_viscosity::<3>(1.0, 1.0, 1.0) / (nu - 0.5 * zeta);
        let eta = HcsTransport::new::<3>(1e-3, 1.0, 1.0, 1.0, 0.0, eps).shear_viscosity;
        assert!((eta / expected - 1.0).abs() < 1e-12);
    }

    #[test]
    fn time_independent_growth_and_critical_length() {
        let a = HcsTransport::new::<2>(0.3, 1.0, 1.0, 1.0, 0.25, 0.9);
        let b = HcsTransport::new::<2>(0.3, 1.0, 1.0, 0.01, 0.25, 0.9);
        let k = 0.1;
        let (ga, gb) = (
            a.transverse_growth_per_collision(k),
            b.transverse_growth_per_collision(k),
        );
        assert!((ga - gb).abs() < 1e-12 * ga.abs().max(1e-3));
        assert!(a.transverse_growth_rate(a.critical_wave_number()).abs() < 1e-14);
        assert!((a.critical_length() - b.critical_length()).abs() < 1e-9 * a.critical_length());
    }

    /// DSMC's Enskog-factor Boltzmann gas is the dilute gas with lengths in mean free paths
    /// (`theory::mean_free_path`, computed independently from the collision frequency):
    /// the same L_c / λ and the same growth per collision at the same k λ.
    #[test]
    fn enskog_factor_dsmc_is_the_dilute_gas_in_mean_free_paths() {
        use crate::theory::mean_free_path;
        let (phi, eps) = (0.25, 0.8);
        let n = phi / crate::system::ball_volume::<2>(0.5);
        let dsmc = HcsTransport::enskog_factor_dsmc::<2>(n, 1.0, 1.0, 2.0, phi, eps);
        let dilute = HcsTransport::new::<2>(n, 1.0, 1.0, 2.0, 0.0, eps);
        let (lambda, lambda0) = (
            mean_free_path::<2>(n, 1.0, phi),
            mean_free_path::<2>(n, 1.0, 0.0),
        );
        let ratio = dsmc.critical_length() / lambda / (dilute.critical_length() / lambda0);
        assert!((ratio - 1.0).abs() < 1e-12, "L_c / lambda ratio {ratio}");
        for k_lambda in [0.01, 0.1, 0.3] {
            let (a, b) = (
                dsmc.transverse_growth_per_collision(k_lambda / lambda),
                dilute.transverse_growth_per_collision(k_lambda / lambda0),
            );
            assert!((a - b).abs() < 1e-12 * b.abs().max(1e-3), "{a} vs {b}");
        }
    }

    #[test]
    fn carnahan_starling_compressibility() {
        for phi in [0.05f64, 0.2, 0.4] {
            let cs = (1.0 - phi).powi(4)
                / (1.0 + 4.0 * phi + 4.0 * phi * phi - 4.0 * phi.powi(3) + phi.powi(4));
            assert!((long_wavelength_structure_factor::<3>(phi) - cs).abs() < 1e-8);
            assert!(
                ((long_wavelength_structure_factor::<1>(phi)) - (1.0 - phi).powi(2)).abs() < 1e-8
            );
        }
    }
}
