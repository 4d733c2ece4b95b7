//! Uniform shear flow (USF) u = a y e_x of a dilute granular gas of smooth inelastic hard
//! spheres (D = 3) or disks (D = 2): the rheology from Grad's moment method and from a
//! BGK-type kinetic model, for the steady state without thermostat (viscous heating balances
//! collisional cooling; Santos, Garzó & Dufty, Phys. Rev. E 69, 061303 (2004); Montanero,
//! Garzó, Santos & Brey, J. Fluid Mech. 389, 391 (1999); DSMC: Brey, Ruiz-Montero & Moreno,
//! Phys. Rev. E 55, 2846 (1997)) and for the state held at temperature T by a Gaussian
//! thermostat at any shear rate.
//!
//! **Moment equations.** In the Lagrangian frame (peculiar velocity V) the USF is
//! homogeneous: ∂_t f − a V_y ∂f/∂V_x − ξ ∂_V·(V f) = J[f, f], where ξ is the friction of the
//! Gaussian thermostat (ξ = 0 without it; ξ < 0 heats). The second moment P_ij = ∫ m V_i V_j f
//! obeys exactly
//!
//!   ∂_t P_ij + a (δ_ix P_yj + δ_jx P_yi) + 2ξ P_ij = Λ_ij,  Λ_ij = ∫ m V_i V_j J[f, f].
//!
//! **Grad.** With Grad's distribution f = f_M [1 + m/(2 n T²) Π_ij V_i V_j], Π = P − p I, and
//! Λ linearized in Π (and a2 = 0), Λ_ij = −ν0 [β Π_ij + ζ* p δ_ij] with ν0 = n T / η0(T),
//! β = ν_η*(a2 = 0) = (1+α)(2D + 3 − 3α)/(4D) and ζ* = (D+2)(1 − α²)/(4D): the a2 = 0
//! frequencies of [`super::transport::collision_frequencies`], whose collision integrals are
//! checked there by quadrature (Λ_ij is the same integral). Steady state, reduced
//! a* = a/ν0, ξ* = ξ/ν0, P* = P/p, θ = β + 2ξ*, c = β − ζ*:
//!
//!   yy (and zz): θ P*_yy = c,  xy: θ P*_xy = −a* P*_yy,  xx: θ P*_xx = c − 2a* P*_xy,
//!   trace (energy): 2ξ* D = −2a* P*_xy − D ζ*  ⇒  θ²(θ − c) = 2 a*² c / D,
//!
//! so η* = −P*_xy / a* = c/θ², P*_yy = c/θ, P*_xx = D − (D−1) P*_yy; the cubic has one root
//! θ ≥ c (bisection here). Without thermostat ξ = 0, θ = β: a*² = D ζ* β² / (2(β − ζ*)),
//! η* = (β − ζ*)/β², and 2 a P_xy / (D n) = −ζ T (viscous heating = cooling). Linear Grad
//! gives P_zz = P_yy (no second normal stress difference; the quadratic terms in Π give a
//! small one, Santos, Garzó & Dufty 2004, not kept here).
//!
//! **BGK.** The kinetic model of Brey, Dufty & Santos (J. Stat. Phys. 97, 281 (1999)),
//! J → −ν_B (f − f_M) + (ζ/2) ∂_V·(V f), has exactly Λ_ij = −ν_B Π_ij − ζ P_ij, i.e. the Grad
//! form with β → ν_B* + ζ*. With ν_B* = ν_η* − ζ* = (1+α)[(D+1) + (D−1)α]/(4D) (a2 = 0), the
//! model's Navier–Stokes viscosity p/(ν_B + ζ/2) is Boltzmann's p/(ν_η − ζ/2), and its USF
//! pressure tensor (an exact solution of the model) coincides with Grad's.
//!
//! **Small shear.** The thermostatted state has η* → 1/(ν_η* − ζ*) as a* → 0: the
//! Navier–Stokes viscosity of the gas under this thermostat, not the 1/(ν_η* − ζ*/2) of the
//! homogeneous cooling state ([`super::transport`]), which the same moment equations give for
//! a constant a while T cools (test `cooling_shear_flow_has_the_hcs_viscosity`); the two agree
//! at α = 1, where the thermostatted gas is the classical non-Newtonian hard-sphere fluid:
//! θ²(θ − 1) = 2a*²/D, η* = 1/θ² = 1 − 4a*²/D + O(a*⁴), shear thinning as a*^{−4/3}.
//!
//! **Enskog (φ > 0)** Grad USF (Montanero, Garzó, Alam & Luding, Granular Matter 8, 103
//! (2006)) adds collisional transfer to P and Λ: not implemented.
//!
//! Rates: a* is in units of ν0 = n T / η0(T); per collision, a/ω = a* ν0/ω with ω the
//! Maxwellian collision frequency of [`super::collision_frequency`] (ν0/ω = 4/5 in 3D, 1 in
//! 2D: [`super::transport::reference_over_collision_frequency`]).

use super::transport::{collision_frequencies, reference_over_collision_frequency};

/// The reduced rheology of a USF state: P* = P / (n T), rates in units of ν0 = n T / η0(T).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShearState {
    /// a* = a / ν0.
    pub reduced_shear_rate: f64,
    /// a / ω, the shear rate per collision (ω the Maxwellian collision frequency).
    pub shear_rate_per_collision: f64,
    /// ξ* = ξ / ν0, the Gaussian thermostat's friction (0 in the steady USF; < 0 heats).
    pub thermostat: f64,
    /// P*_xx (flow direction).
    pub pxx: f64,
    /// P*_yy (gradient direction).
    pub pyy: f64,
    /// P*_zz (vorticity direction, D = 3; `None` for disks).
    pub pzz: Option<f64>,
    /// P*_xy.
    pub pxy: f64,
    /// η* = −P_xy / (a η0(T)) = −P*_xy / a*.
    pub viscosity: f64,
    /// P*_xx − P*_yy.
    pub first_normal_difference: f64,
    /// P*_yy − P*_zz (D = 3).
    pub second_normal_difference: Option<f64>,
}

/// Grad's (β, ζ*) at restitution α: the a2 = 0 shear and cooling frequencies.
pub fn grad_frequencies<const D: usize>(alpha: f64) -> (f64, f64) {
    let nu = collision_frequencies::<D>(alpha, 0.0);
    (nu.shear, nu.cooling)
}

/// The BGK model's collision frequency ν_B* = ν_η* − ζ* (a2 = 0) in units of ν0.
pub fn bgk_collision_frequency<const D: usize>(alpha: f64) -> f64 {
    let (beta, zeta) = grad_frequencies::<D>(alpha);
    beta - zeta
}

/// The root θ ≥ c of θ²(θ − c) = k (c > 0, k ≥ 0) by bisection to machine precision: the
/// left side increases on [c, ∞), is −k ≤ 0 at c and ≥ k at c + k/c².
fn cubic_root(c: f64, k: f64) -> f64 {
    let (mut lo, mut hi) = (c, c + k / (c * c));
    for _ in 0..2000 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if mid * mid * (mid - c) < k {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The stationary moments for the collisional moment Λ = −ν0 [β Π + ζ* p I] at the reduced
/// shear rate a* (`None`: the steady USF without thermostat, ξ = 0).
fn stationary<const D: usize>(beta: f64, zeta: f64, rate: Option<f64>) -> ShearState {
    assert!(D == 2 || D == 3, "uniform shear flow: D = 2 or 3");
    let (d, c) = (D as f64, beta - zeta);
    let (a, theta) = match rate {
        None => ((d * zeta * beta * beta / (2.0 * c)).sqrt(), beta),
        Some(a) => (a, cubic_root(c, 2.0 * a * a * c / d)),
    };
    let pyy = c / theta;
    let pxy = -a * pyy / theta;
    let pxx = (c - 2.0 * a * pxy) / theta;
    let pzz = (D == 3).then_some(pyy);
    ShearState {
        reduced_shear_rate: a,
        shear_rate_per_collision: a * reference_over_collision_frequency::<D>(),
        thermostat: 0.5 * (theta - beta),
        pxx,
        pyy,
        pzz,
        pxy,
        viscosity: c / (theta * theta),
        first_normal_difference: pxx - pyy,
        second_normal_difference: pzz.map(|z| pyy - z),
    }
}

/// The steady USF of the dilute gas (no thermostat) in Grad's approximation: a* and P* as
/// functions of α alone.
pub fn steady_grad<const D: usize>(alpha: f64) -> ShearState {
    let (beta, zeta) = grad_frequencies::<D>(alpha);
    stationary::<D>(beta, zeta, None)
}

/// The steady USF of the BGK model (exact for the model; equal to Grad's pressure tensor).
pub fn steady_bgk<const D: usize>(alpha: f64) -> ShearState {
    let (_, zeta) = grad_frequencies::<D>(alpha);
    stationary::<D>(bgk_collision_frequency::<D>(alpha) + zeta, zeta, None)
}

/// The USF at the reduced shear rate a* held at constant T by the Gaussian thermostat, Grad.
pub fn thermostatted_grad<const D: usize>(alpha: f64, reduced_rate: f64) -> ShearState {
    let (beta, zeta) = grad_frequencies::<D>(alpha);
    stationary::<D>(beta, zeta, Some(reduced_rate))
}

/// The same for the BGK model.
pub fn thermostatted_bgk<const D: usize>(alpha: f64, reduced_rate: f64) -> ShearState {
    let (_, zeta) = grad_frequencies::<D>(alpha);
    stationary::<D>(
        bgk_collision_frequency::<D>(alpha) + zeta,
        zeta,
        Some(reduced_rate),
    )
}

#[cfg(test)]
mod tests;
