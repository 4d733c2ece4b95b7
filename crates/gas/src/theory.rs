//! The Enskog–Boltzmann kinetic theory of granular gases (DSMC samples it; the event-driven
//! engine and DSMC are compared with it), for smooth hard spheres of diameter sigma, mass m,
//! number density n and packing fraction phi in D = 1, 2, 3.
//!
//! Collision rate of a pair with relative velocity g (Enskog, homogeneous):
//! g2(phi) sigma^(D-1) / V times the integral over impact directions e of (g.e)^+, which is
//! c_D |g| with c_D = integral of (cos theta)^+ over the unit sphere = the volume of the unit
//! (D-1)-ball: 1, 2, pi (so c_D sigma^(D-1) is the geometric cross-section, pi sigma^2 in 3D).
//! Averaged over a Maxwellian of temperature T (relative velocity variance 2T/m per
//! component, so E[(g.e)^+] = sqrt(T / (pi m))), the collision frequency of a particle is
//!
//!   omega = g2 n sigma^(D-1) S_D sqrt(T / (pi m)),   S_D = 2, 2 pi, 4 pi,
//!
//! i.e. 2 g2 n sqrt(T/(pi m)) in 1D, 2 g2 n sigma sqrt(pi T/m) in 2D and the familiar
//! 4 sqrt(pi) g2 n sigma^2 sqrt(T/m) in 3D (Brilliantov & Pöschel, *Kinetic Theory of
//! Granular Gases*, Oxford 2004, Ch. 6; Chapman & Cowling 1970, Sec. 16.4). Each collision
//! with constant eps removes (1 - eps^2) m (g.e)^2 / 4 of energy, on average (1 - eps^2) T for
//! Maxwellian impact speeds, so d ln T / d(collisions per particle) = -(1 - eps^2) / D, and
//! dT/dt = -zeta T with zeta = (1 - eps^2) omega / D: Haff's law
//! T(t) = T0 / (1 + t / tau)^2 with 1/tau = (1 - eps^2) omega0 / (2 D) (Haff 1983, J. Fluid
//! Mech. 134, 401). In the homogeneous cooling state the first Sonine correction multiplies
//! omega by (1 - a2/16) and zeta by (1 + 3 a2/16) (van Noije & Ernst 1998, Granular Matter 1,
//! 57), so the cooling per collision by about (1 + a2/4).

pub mod gauss;
pub mod hydrodynamics;
pub mod mixture;
pub mod rough;
pub mod rough_sonine;
pub mod rough_viscoelastic;
pub mod sonine;
pub mod transport;
pub mod usf;

pub use hydrodynamics::{
    dilute_elastic_viscosity, enskog_thermal_conductivity, long_wavelength_structure_factor,
    HcsTransport,
};
pub use mixture::{DrivenState, MixtureHcs, MixtureTheory};
pub use sonine::{second_sonine, SonineHierarchy};
use std::f64::consts::PI;
pub use transport::{NavierStokes, ReducedTransport};
pub use usf::ShearState;

/// The dimensions the engines support.
pub fn check_dimension<const D: usize>() -> crate::Result<()> {
    if (1..=3).contains(&D) {
        Ok(())
    } else {
        Err(crate::Error::out_of_range("dimension", D, "1, 2, 3"))
    }
}

/// Close packing, the upper end of the packing fractions the engines accept: 1 (rods),
/// pi / (2 sqrt 3) (hexagonal disks), pi / (3 sqrt 2) (fcc spheres).
pub fn close_packing<const D: usize>() -> f64 {
    match D {
        1 => 1.0,
        2 => PI / (2.0 * 3f64.sqrt()),
        _ => PI / (3.0 * 2f64.sqrt()),
    }
}

/// The pair correlation at contact g2(phi) of equal spheres: 1/(1 - phi) for rods (exact,
/// Tonks 1936), Henderson's (1 - 7 phi/16)/(1 - phi)^2 for disks (Mol. Phys. 30, 971
/// (1975)), Carnahan–Starling (1 - phi/2)/(1 - phi)^3 for spheres (J. Chem. Phys. 51, 635
/// (1969)). The last two are fluid-range approximations.
pub fn contact_value<const D: usize>(phi: f64) -> f64 {
    match D {
        1 => 1.0 / (1.0 - phi),
        2 => (1.0 - 7.0 * phi / 16.0) / (1.0 - phi).powi(2),
        _ => (1.0 - 0.5 * phi) / (1.0 - phi).powi(3),
    }
}

/// The contact value g_ij of a mixture at total packing fraction phi, with
/// x = sigma_i sigma_j / (sigma_i + sigma_j) * M and M = sum_s n_s sigma_s^(D-1) /
/// sum_s n_s sigma_s^D (x = 1/2 for equal diameters, where it is [`contact_value`]):
/// 1/(1 - phi) for rods (exact), Jenkins & Mancini (J. Appl. Mech. 54, 27 (1987))
/// 1/(1 - phi) + 9/8 phi x/(1 - phi)^2 for disks, Boublík–Mansoori–Carnahan–Starling–Leland
/// (J. Chem. Phys. 54, 1523 (1971)) 1/(1 - phi) + 3 phi x/(1 - phi)^2 + 2 phi^2 x^2/(1 - phi)^3
/// for spheres.
pub fn mixture_contact_value<const D: usize>(phi: f64, x: f64) -> f64 {
    let free = 1.0 - phi;
    match D {
        1 => 1.0 / free,
        2 => 1.0 / free + 9.0 / 8.0 * phi * x / (free * free),
        _ => 1.0 / free + 3.0 * phi * x / (free * free) + 2.0 * (phi * x).powi(2) / free.powi(3),
    }
}

/// Surface of the unit sphere S_D: 2, 2 pi, 4 pi.
pub fn sphere_surface<const D: usize>() -> f64 {
    match D {
        1 => 2.0,
        2 => 2.0 * PI,
        _ => 4.0 * PI,
    }
}

/// c_D, the integral of (e.u)^+ over unit vectors e for a unit vector u (the volume of the
/// unit (D-1)-ball): 1, 2, pi.
pub fn cross_section_factor<const D: usize>() -> f64 {
    match D {
        1 => 1.0,
        2 => 2.0,
        _ => PI,
    }
}

/// E|Z| for a standard normal vector Z in D dimensions: sqrt(2/pi), sqrt(pi/2), sqrt(8/pi).
pub fn mean_norm_of_gaussian<const D: usize>() -> f64 {
    match D {
        1 => (2.0 / PI).sqrt(),
        2 => (PI / 2.0).sqrt(),
        _ => (8.0 / PI).sqrt(),
    }
}

/// The Enskog collision frequency of one particle in a Maxwellian gas,
/// omega = g2(phi) n sigma^(D-1) S_D sqrt(T / (pi m)) (see the module documentation).
pub fn collision_frequency<const D: usize>(
    density: f64,
    diameter: f64,
    mass: f64,
    temperature: f64,
    phi: f64,
) -> f64 {
    contact_value::<D>(phi)
        * density
        * diameter.powi(D as i32 - 1)
        * sphere_surface::<D>()
        * (temperature / (PI * mass)).sqrt()
}

/// Mean free path: the mean speed sqrt(T/m) E|Z| over the collision frequency
/// (1 / (sqrt 2 pi n sigma^2 g2) in 3D, 1 / (sqrt 2 n sigma^(D-1) c_D g2) in general);
/// independent of T.
pub fn mean_free_path<const D: usize>(density: f64, diameter: f64, phi: f64) -> f64 {
    mean_norm_of_gaussian::<D>() / collision_frequency::<D>(density, diameter, 1.0, 1.0, phi)
}

/// Haff's time tau = 2 D / ((1 - eps^2) omega0): T(t) = T0 / (1 + t/tau)^2 (Maxwellian
/// cooling rate, a2 = 0).
pub fn haff_time<const D: usize>(eps: f64, omega0: f64) -> f64 {
    2.0 * D as f64 / ((1.0 - eps * eps) * omega0)
}

/// Haff's law T(t) = T0 / (1 + t/tau)^2 with tau from [`haff_time`].
pub fn haff_temperature(t0: f64, tau: f64, t: f64) -> f64 {
    t0 / (1.0 + t / tau).powi(2)
}

/// Haff's time of a monodisperse gas of `n` spheres of diameter `diameter` and mass `mass`
/// in the volume `volume` at packing fraction `phi` and temperature `t0`, with the Enskog
/// collision frequency ([`collision_frequency`]).
pub fn enskog_haff_time<const D: usize>(
    eps: f64,
    n: usize,
    volume: f64,
    diameter: f64,
    mass: f64,
    t0: f64,
    phi: f64,
) -> f64 {
    let omega0 = collision_frequency::<D>(n as f64 / volume, diameter, mass, t0, phi);
    haff_time::<D>(eps, omega0)
}

/// Collisions per particle by time t under Haff's law: omega0 tau ln(1 + t/tau)
/// (integral of omega0 sqrt(T/T0) dt).
pub fn haff_collisions_per_particle(omega0: f64, tau: f64, t: f64) -> f64 {
    omega0 * tau * (t / tau).ln_1p()
}

/// The Sonine coefficient a2 of the homogeneous cooling state in the first Sonine
/// approximation, linearized in a2 (van Noije & Ernst 1998, Granular Matter 1, 57; Brilliantov
/// & Pöschel 2004, Ch. 7):
/// a2 = 16 (1 - eps)(1 - 2 eps^2) / (9 + 24 D - eps (41 - 8 D) + 30 eps^2 (1 - eps)).
/// Its error grows with the dissipation (second-order Sonine terms, Brilliantov & Pöschel,
/// Europhys. Lett. 74, 424 (2006)).
pub fn van_noije_ernst_a2<const D: usize>(eps: f64) -> f64 {
    let d = D as f64;
    16.0 * (1.0 - eps) * (1.0 - 2.0 * eps * eps)
        / (9.0 + 24.0 * d - eps * (41.0 - 8.0 * d) + 30.0 * eps * eps * (1.0 - eps))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mixture_contact_value_reduces_to_the_pure_one() {
        for phi in [0.05, 0.2, 0.4] {
            let (a2, b2) = (
                contact_value::<2>(phi),
                mixture_contact_value::<2>(phi, 0.5),
            );
            let (a3, b3) = (
                contact_value::<3>(phi),
                mixture_contact_value::<3>(phi, 0.5),
            );
            assert!((a2 - b2).abs() < 1e-14 * a2 && (a3 - b3).abs() < 1e-14 * a3);
        }
    }

    #[test]
    fn three_dimensional_values() {
        let omega = collision_frequency::<3>(0.1, 1.0, 1.0, 1.0, 0.0);
        assert!((omega - 4.0 * PI.sqrt() * 0.1).abs() < 1e-15);
        for phi in [0.0, 0.2] {
            let lambda = mean_free_path::<3>(0.1, 1.0, phi);
            let g2 = contact_value::<3>(phi);
            assert!((lambda - 1.0 / (2f64.sqrt() * PI * 0.1 * g2)).abs() < 1e-12);
            let lambda2 = mean_free_path::<2>(0.1, 1.0, phi);
            let g2 = contact_value::<2>(phi);
            assert!((lambda2 - 1.0 / (2f64.sqrt() * 2.0 * 0.1 * g2)).abs() < 1e-12);
        }
        // 81 - 17 eps + 30 eps^2 (1 - eps) in 3D.
        let eps = 0.7;
        let a2 = 16.0 * 0.3 * (1.0 - 2.0 * eps * eps)
            / (81.0 - 17.0 * eps + 30.0 * eps * eps * (1.0 - eps));
        assert!((van_noije_ernst_a2::<3>(eps) - a2).abs() < 1e-15);
    }
}
