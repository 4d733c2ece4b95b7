use super::collision_integrals::{collide, collision_average, linearized_frequency, sonine2};
use super::*;
use crate::theory::{enskog_thermal_conductivity, HcsTransport};

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1e-300)
}

/// The quadrature's collision frequencies (units m = σ = n = 1, T = 1/2) in units of
/// ν0 = n T / η0, as (value at a2 = 0, slope in a2).
fn quadrature_frequencies<const D: usize>(alpha: f64) -> [(f64, f64); 4] {
    let d = D as f64;
    let nu0 = 0.5 / dilute_elastic_viscosity::<D>(1.0, 1.0, 0.5);
    let traceless = |c: &[f64; D]| -> Vec<f64> {
        let c2: f64 = c.iter().map(|v| v * v).sum();
        let mut out = Vec::with_capacity(D * D);
        for i in 0..D {
            for j in 0..D {
                out.push(c[i] * c[j] - if i == j { c2 / d } else { 0.0 });
            }
        }
        out
    };
    let heat = |c: &[f64; D]| -> Vec<f64> {
        let c2: f64 = c.iter().map(|v| v * v).sum();
        c.iter().map(|v| (c2 - 0.5 * (d + 2.0)) * v).collect()
    };
    let velocity = |c: &[f64; D]| -> Vec<f64> { c.to_vec() };
    let scale = |(a, b): (f64, f64)| (a / nu0, b / nu0);
    // ζ = −∫ m c² J[f0, f0] / (D n T), with ∫ c² J = (1/2) ∫∫ f0 f0 (Δc1² + Δc2²).
    let energy_change = |c1: &[f64; D], c2: &[f64; D]| -> f64 {
        let (p1, p2) = collide(c1, c2, alpha);
        let sq = |v: &[f64; D]| v.iter().map(|x| x * x).sum::<f64>();
        sq(&p1) + sq(&p2) - sq(c1) - sq(c2)
    };
    let cooling = |weight: &dyn Fn(&[f64; D], &[f64; D]) -> f64| {
        -0.5 * collision_average::<D>(|c1, c2| weight(c1, c2) * energy_change(c1, c2)) / (0.5 * d)
    };
    let zeta = (
        cooling(&|_, _| 1.0),
        cooling(&|c1, c2| sonine2::<D>(c1) + sonine2::<D>(c2)),
    );
    [
        scale(zeta),
        scale(linearized_frequency::<D>(alpha, false, traceless)),
        scale(linearized_frequency::<D>(alpha, false, heat)),
        scale(linearized_frequency::<D>(alpha, true, velocity)),
    ]
}

/// Oracle: the collision integrals by Gauss quadrature (exact for these polynomial
/// integrands, [`collision_integrals`]), at a2 = 0 and their slopes in a2, against the closed
/// forms of ζ*, ν_η*, ν_κ*, ν_D* (Brey et al. 1998; Garzó & Dufty 1999 in D dimensions; ν_D*
/// derived in the module documentation). Agreement to 1e-12: round-off of ~10^6 terms.
#[test]
fn collision_frequencies_match_quadrature() {
    fn check<const D: usize>() {
        for alpha in [1.0, 0.9, 0.6, 0.2] {
            let q = quadrature_frequencies::<D>(alpha);
            let (at0, at1) = (
                collision_frequencies::<D>(alpha, 0.0),
                collision_frequencies::<D>(alpha, 1.0),
            );
            let closed = [
                (at0.cooling, at1.cooling - at0.cooling),
                (at0.shear, at1.shear - at0.shear),
                (at0.heat, at1.heat - at0.heat),
                (at0.diffusion, at1.diffusion - at0.diffusion),
            ];
            for (k, (quad, form)) in q.iter().zip(closed).enumerate() {
                let scale = form.0.abs().max(1e-3);
                assert!(
                    (quad.0 - form.0).abs() < 1e-12 * scale
                        && (quad.1 - form.1).abs() < 1e-12 * scale,
                    "D={D} alpha={alpha} frequency {k}: quadrature {quad:?} vs closed {form:?}"
                );
            }
        }
    }
    check::<2>();
    check::<3>();
}

/// Oracle: the units by a route that does not use η0: the quadrature's elastic ν_D equals
/// 2ω/D with ω the Maxwellian collision frequency of `theory::collision_frequency`
/// (so D0 = T/(m ν_D) = 3/(8nσ²)(T/(πm))^{1/2} in 3D).
#[test]
fn diffusion_frequency_is_two_omega_over_d() {
    fn check<const D: usize>() {
        let (nu_d, _) = linearized_frequency::<D>(1.0, true, |c: &[f64; D]| c.to_vec());
        let omega = collision_frequency::<D>(1.0, 1.0, 1.0, 0.5, 0.0);
        assert!(
            close(nu_d, 2.0 * omega / D as f64, 1e-12),
            "D={D}: {nu_d} vs {omega}"
        );
    }
    check::<2>();
    check::<3>();
}

/// Oracle: the Chapman–Enskog values of elastic hard spheres and disks in closed form
/// (Chapman & Cowling 1970, Ch. 10 and 16; 2D: Gass 1971), at arbitrary n, σ, m, T.
#[test]
fn elastic_dilute_limits_are_chapman_enskog() {
    let (n, s, m, t) = (0.37, 1.3, 2.1, 0.8);
    let ns = NavierStokes::dilute::<3>(n, s, m, t, 1.0);
    assert!(close(
        ns.shear_viscosity,
        5.0 / (16.0 * s * s) * (m * t / PI).sqrt(),
        1e-14
    ));
    assert!(close(
        ns.thermal_conductivity,
        75.0 / (64.0 * s * s) * (t / (PI * m)).sqrt(),
        1e-14
    ));
    assert!(close(
        ns.self_diffusion,
        3.0 / (8.0 * n * s * s) * (t / (PI * m)).sqrt(),
        1e-14
    ));
    assert_eq!(
        (ns.mu, ns.cooling_rate, ns.bulk_viscosity, ns.a2),
        (Some(0.0), 0.0, 0.0, 0.0)
    );
    let ns = NavierStokes::dilute::<2>(n, s, m, t, 1.0);
    assert!(close(
        ns.shear_viscosity,
        0.5 / s * (m * t / PI).sqrt(),
        1e-14
    ));
    assert!(close(
        ns.thermal_conductivity,
        2.0 / s * (t / (PI * m)).sqrt(),
        1e-14
    ));
    assert!(close(
        ns.self_diffusion,
        0.5 / (n * s) * (t / (PI * m)).sqrt(),
        1e-14
    ));
    assert_eq!((ns.mu, ns.cooling_rate), (Some(0.0), 0.0));
}

/// Oracle: the elastic Enskog gas. 3D: Chapman & Cowling's first approximation with
/// b n = 4φ, y = b n χ: η0 [1/χ + 4y/(5χ) + 4/25 (1 + 12/π) y²/χ], κ0 b n [1/y + 6/5 +
/// (9/25 + 32/(25π)) y], bulk (4/9) n² σ⁴ χ (π m T)^{1/2}, D0/χ. 2D: Gass's η0 [1/χ + 2φ +
/// (1 + 8/π) φ² χ] and κ0 [1/χ + 3φ + (9/4 + 4/π) φ² χ]; μ = 0 in both.
#[test]
fn elastic_enskog_limits_are_chapman_cowling_and_gass() {
    let (s, m, t) = (1.0, 1.0, 1.0);
    for phi in [0.05, 0.2, 0.4] {
        let n = 6.0 * phi / PI;
        let chi = contact_value::<3>(phi);
        let (bn, y) = (4.0 * phi, 4.0 * phi * chi);
        let eta0 = 5.0 / (16.0 * PI.sqrt());
        let kappa0 = 75.0 / (64.0 * PI.sqrt());
        let ns = NavierStokes::enskog::<3>(n, s, m, t, phi, 1.0);
        let eta = eta0 * (1.0 / chi + 0.8 * y / chi + 4.0 / 25.0 * (1.0 + 12.0 / PI) * y * y / chi);
        assert!(close(ns.shear_viscosity, eta, 1e-13));
        let kappa = kappa0 * bn * (1.0 / y + 1.2 + (0.36 + 32.0 / (25.0 * PI)) * y);
        assert!(close(ns.thermal_conductivity, kappa, 1e-13));
        assert!(close(
            ns.bulk_viscosity,
            4.0 / 9.0 * n * n * chi * (PI * m * t).sqrt(),
            1e-13
        ));
        let d0 = 3.0 / (8.0 * n) * (t / (PI * m)).sqrt();
        assert!(close(ns.self_diffusion, d0 / chi, 1e-13));
        assert_eq!(ns.mu, Some(0.0));
        let n = 4.0 * phi / PI;
        let chi = contact_value::<2>(phi);
        let ns = NavierStokes::enskog::<2>(n, s, m, t, phi, 1.0);
        let gass = 0.5 / PI.sqrt() * (1.0 / chi + 2.0 * phi + (1.0 + 8.0 / PI) * phi * phi * chi);
        assert!(close(ns.shear_viscosity, gass, 1e-13));
        let by_hand =
            2.0 / PI.sqrt() * (1.0 / chi + 3.0 * phi + (2.25 + 4.0 / PI) * phi * phi * chi);
        assert!(close(ns.thermal_conductivity, by_hand, 1e-13));
        assert!(close(
            enskog_thermal_conductivity::<2>(s, m, t, phi),
            by_hand,
            1e-13
        ));
    }
}

/// Oracle: Garzó & Dufty's 3D κ_k*, κ*, μ_k* as printed (with c = 2 a2; transcribed as
/// in MFIX's `gt_pde_gd_99`, but with d ln χ/dφ where that code has dχ/dφ): the terms
/// (1/2)(1 + p*)c and −5c/(3(1+α)) that the D-dimensional form here collects.
#[test]
fn enskog_heat_flux_is_garzo_dufty_3d() {
    for phi in [0.0, 0.1, 0.3] {
        for alpha in [0.95, 0.8, 0.5] {
            let (chi, e) = (contact_value::<3>(phi), alpha);
            let c = 32.0 * (1.0 - e) * (1.0 - 2.0 * e * e)
                / (81.0 - 17.0 * e + 30.0 * e * e * (1.0 - e));
            let dlnchi =
                phi * (contact_value::<3>(phi + 1e-6) / contact_value::<3>(phi - 1e-6)).ln() / 2e-6;
            let p = 1.0 + 2.0 * (1.0 + e) * phi * chi;
            let zeta = 5.0 / 12.0 * chi * (1.0 - e * e) * (1.0 + 3.0 / 32.0 * c);
            let nu_k = chi / 3.0
                * (1.0 + e)
                * (1.0 + 33.0 / 16.0 * (1.0 - e) + (19.0 - 3.0 * e) / 1024.0 * c);
            let kk = 2.0 / 3.0
                * (1.0
                    + 0.5 * (1.0 + p) * c
                    + 0.6
                        * phi
                        * chi
                        * (1.0 + e).powi(2)
                        * (2.0 * e - 1.0 + (0.5 * (1.0 + e) - 5.0 / (3.0 * (1.0 + e))) * c))
                / (nu_k - 2.0 * zeta);
            let kappa = kk * (1.0 + 1.2 * phi * chi * (1.0 + e))
                + 256.0 / 25.0 * phi * phi / PI * chi * (1.0 + e) * (1.0 + 7.0 / 32.0 * c);
            // p*/3 + (2/3) φ (1+α)(χ + φ χ') = (p* + φ ∂_φ p*)/3.
            let dp = 2.0 * (1.0 + e) * phi * chi * (1.0 + dlnchi);
            let muk = 2.0
                * ((1.0 + dlnchi) * zeta * kk + (p + dp) / 3.0 * c
                    - 0.8
                        * phi
                        * chi
                        * (1.0 + 0.5 * dlnchi)
                        * (1.0 + e)
                        * (e * (1.0 - e) + 0.25 * (4.0 / 3.0 + e * (1.0 - e)) * c))
                / (2.0 * nu_k - 3.0 * zeta);
            let mu = muk * (1.0 + 1.2 * phi * chi * (1.0 + e));
            let r = ReducedTransport::enskog::<3>(phi, alpha);
            assert!(close(r.thermal_conductivity, kappa, 1e-13), "{phi} {alpha}");
            // 1e-8: the central difference of ln χ (step 1e-6) in the oracle.
            assert!(
                close(r.mu.unwrap(), mu, 1e-8),
                "{phi} {alpha}: {:?} vs {mu}",
                r.mu
            );
        }
    }
}

/// Oracle: the dilute forms of Brey, Dufty, Kim & Santos (1998) in D dimensions:
/// η* = 1/(ν_η* − ζ*/2), κ* = (D−1)/D (1 + 2a2)/(ν_κ* − 2ζ*),
/// μ* = 2ζ* (κ* + (D−1) a2/(D ζ*))/(2ν_κ* − 3ζ*), D* = 4/((1+α)(1 + α − (4−3α) a2/16)),
/// with the collision frequencies of the quadrature test; and the dilute gas is the Enskog
/// gas at φ = 0 (bulk viscosity 0).
#[test]
fn dilute_coefficients_are_brey_dufty_kim_santos() {
    fn check<const D: usize>() {
        let d = D as f64;
        for alpha in [0.95, 0.7, 0.3] {
            let r = ReducedTransport::enskog::<D>(0.0, alpha);
            let a2 = van_noije_ernst_a2::<D>(alpha);
            let nu = collision_frequencies::<D>(alpha, a2);
            let kappa = (d - 1.0) / d * (1.0 + 2.0 * a2) / (nu.heat - 2.0 * nu.cooling);
            let mu = 2.0 * nu.cooling * (kappa + (d - 1.0) * a2 / (d * nu.cooling))
                / (2.0 * nu.heat - 3.0 * nu.cooling);
            let diffusion = 4.0 / ((1.0 + alpha) * (1.0 + alpha - (4.0 - 3.0 * alpha) * a2 / 16.0));
            assert!(close(
                r.shear_viscosity,
                1.0 / (nu.shear - 0.5 * nu.cooling),
                1e-14
            ));
            assert!(close(r.thermal_conductivity, kappa, 1e-14));
            assert!(close(r.mu.unwrap(), mu, 1e-13));
            assert!(close(r.self_diffusion, diffusion, 1e-13));
            assert_eq!(r.bulk_viscosity, 0.0);
            let (a, b) = (
                NavierStokes::dilute::<D>(0.2, 1.0, 1.0, 2.0, alpha),
                NavierStokes::enskog::<D>(0.2, 1.0, 1.0, 2.0, 0.0, alpha),
            );
            assert_eq!(a, b);
        }
    }
    check::<2>();
    check::<3>();
}

/// Oracle: `HcsTransport::new`'s shear viscosity and cooling rate (hydrodynamics.rs: the
/// same forms written out as the HCS's, kept there so that the shear-mode studies keep
/// their bits) equal these to round-off; and the Enskog gas of disks has no μ at φ > 0.
#[test]
fn hcs_transport_is_these_coefficients() {
    for (phi, eps) in [(0.0, 0.9), (0.1, 0.7), (0.35, 0.4)] {
        let ns = NavierStokes::enskog::<3>(0.3, 1.0, 1.0, 1.5, phi, eps);
        let hcs = HcsTransport::new::<3>(0.3, 1.0, 1.0, 1.5, phi, eps);
        assert!(
            close(hcs.shear_viscosity, ns.shear_viscosity, 2e-15),
            "3D {phi} {eps}"
        );
        assert!(
            close(hcs.cooling_rate, ns.cooling_rate, 2e-15),
            "3D {phi} {eps}"
        );
        let ns = NavierStokes::enskog::<2>(0.3, 1.0, 1.0, 1.5, phi, eps);
        let hcs = HcsTransport::new::<2>(0.3, 1.0, 1.0, 1.5, phi, eps);
        assert!(
            close(hcs.shear_viscosity, ns.shear_viscosity, 2e-15),
            "2D {phi} {eps}"
        );
        assert!(
            close(hcs.cooling_rate, ns.cooling_rate, 2e-15),
            "2D {phi} {eps}"
        );
    }
    assert_eq!(ReducedTransport::enskog::<2>(0.1, 0.8).mu, None);
}

/// Oracle: central differences of ln χ (step 1e-6, error ~1e-11).
#[test]
fn contact_value_slopes() {
    for phi in [0.0, 0.2, 0.45] {
        let h = 1e-6;
        let fd2 = ((contact_value::<2>(phi + h) / contact_value::<2>(phi - h)).ln()) / (2.0 * h);
        let fd3 = ((contact_value::<3>(phi + h) / contact_value::<3>(phi - h)).ln()) / (2.0 * h);
        assert!((log_contact_value_slope::<2>(phi) - fd2).abs() < 1e-8);
        assert!((log_contact_value_slope::<3>(phi) - fd3).abs() < 1e-8);
    }
    assert!((reference_over_collision_frequency::<3>() - 0.8).abs() < 1e-15);
    assert!((reference_over_collision_frequency::<2>() - 1.0).abs() < 1e-15);
}

/// The table of docs/transport.md (run with `--ignored --nocapture`).
#[test]
#[ignore]
fn print_table() {
    for alpha in [1.0, 0.9, 0.8, 0.7, 0.6, 0.5] {
        let (r2, r3) = (
            ReducedTransport::enskog::<2>(0.0, alpha),
            ReducedTransport::enskog::<3>(0.0, alpha),
        );
        println!(
            "| {alpha:.1} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} |",
            r2.shear_viscosity,
            r2.thermal_conductivity,
            r2.mu.unwrap(),
            r2.self_diffusion,
            r3.shear_viscosity,
            r3.thermal_conductivity,
            r3.mu.unwrap(),
            r3.self_diffusion
        );
    }
}

/// The viscosity of elastic hard spheres (D = 3) and disks (D = 2) in the Sonine
/// approximation of order M, over the first (M = 1): A_00 (A^{-1})_00 with the matrix
/// A_pq = −∫ ψ_p (J[φ, φψ_q] + J[φψ_q, φ]) of the linearized operator on
/// ψ_p = (c c − c²/D 1) S_p(c²), S_p the Sonine polynomials of index D/2 + 1 (the shear source
/// lies along ψ_0, which is orthogonal to the others). By quadrature (exact: degree ≤ 12).
fn elastic_viscosity_sonine_series<const D: usize>(order: usize) -> f64 {
    let m = D as f64 / 2.0 + 1.0;
    let sonine = |p: usize, x: f64| match p {
        0 => 1.0,
        1 => m + 1.0 - x,
        _ => 0.5 * (m + 1.0) * (m + 2.0) - (m + 2.0) * x + 0.5 * x * x,
    };
    let psi = |p: usize, c: &[f64; D]| -> Vec<f64> {
        let c2: f64 = c.iter().map(|v| v * v).sum();
        let s = sonine(p, c2);
        let mut out = Vec::with_capacity(D * D);
        for i in 0..D {
            for j in 0..D {
                out.push(s * (c[i] * c[j] - if i == j { c2 / D as f64 } else { 0.0 }));
            }
        }
        out
    };
    let element = |p: usize, q: usize| {
        -collision_average::<D>(|c1, c2| {
            let (p1, p2) = collide(c1, c2, 1.0);
            let (a1, b1, a2, b2, h2) =
                (psi(p, c1), psi(p, &p1), psi(p, c2), psi(p, &p2), psi(q, c2));
            (0..h2.len())
                .map(|i| h2[i] * (b1[i] - a1[i] + b2[i] - a2[i]))
                .sum::<f64>()
        })
    };
    let a: Vec<Vec<f64>> = (0..order)
        .map(|p| (0..order).map(|q| element(p, q)).collect())
        .collect();
    a[0][0] * first_of_inverse(&a)
}

/// The thermal conductivity of elastic hard spheres (D = 3) and disks (D = 2) in the Sonine
/// approximation of order M over the first: A_11 (A^{-1})_11 on ψ_p = c S_p(c²), p = 1 .. M
/// (S_0 would be the momentum, conserved), the heat source along ψ_1; as
/// [`elastic_viscosity_sonine_series`] otherwise.
fn elastic_conductivity_sonine_series<const D: usize>(order: usize) -> f64 {
    let m = D as f64 / 2.0;
    let sonine = |p: usize, x: f64| match p {
        1 => m + 1.0 - x,
        2 => 0.5 * (m + 1.0) * (m + 2.0) - (m + 2.0) * x + 0.5 * x * x,
        _ => {
            (m + 1.0) * (m + 2.0) * (m + 3.0) / 6.0 - 0.5 * (m + 2.0) * (m + 3.0) * x
                + 0.5 * (m + 3.0) * x * x
                - x * x * x / 6.0
        }
    };
    let psi = |p: usize, c: &[f64; D]| -> Vec<f64> {
        let s = sonine(p, c.iter().map(|v| v * v).sum());
        c.iter().map(|v| s * v).collect()
    };
    let element = |p: usize, q: usize| {
        -collision_average::<D>(|c1, c2| {
            let (p1, p2) = collide(c1, c2, 1.0);
            let (a1, b1, a2, b2, h2) =
                (psi(p, c1), psi(p, &p1), psi(p, c2), psi(p, &p2), psi(q, c2));
            (0..D)
                .map(|i| h2[i] * (b1[i] - a1[i] + b2[i] - a2[i]))
                .sum::<f64>()
        })
    };
    let a: Vec<Vec<f64>> = (1..=order)
        .map(|p| (1..=order).map(|q| element(p, q)).collect())
        .collect();
    a[0][0] * first_of_inverse(&a)
}

/// (A^{-1})_00 of a symmetric positive definite matrix, by Gaussian elimination.
fn first_of_inverse(a: &[Vec<f64>]) -> f64 {
    let order = a.len();
    let mut aug: Vec<Vec<f64>> = (0..order)
        .map(|p| {
            let mut row = a[p].clone();
            row.push(if p == 0 { 1.0 } else { 0.0 });
            row
        })
        .collect();
    for k in 0..order {
        let pivot = aug[k].clone();
        for row in aug.iter_mut().skip(k + 1) {
            let f = row[k] / pivot[k];
            for (x, p) in row.iter_mut().zip(&pivot).skip(k) {
                *x -= f * p;
            }
        }
    }
    let mut x = vec![0.0; order];
    for k in (0..order).rev() {
        let s: f64 = (k + 1..order).map(|c| aug[k][c] * x[c]).sum();
        x[k] = (aug[k][order] - s) / aug[k][k];
    }
    x[0]
}

/// Oracle: Chapman & Cowling (1970, §10.21): the second Sonine approximation of the
/// thermal conductivity of elastic hard spheres is the first times 1 + 1/44 exactly; the
/// converged series is 1.025218 (Pekeris & Alterman 1957), which
/// [`ELASTIC_CONDUCTIVITY_SONINE_FACTOR`] holds: past the third order by less than the
/// third order's increment. (The third order's Sonine polynomial has degree 6 in c, the
/// integrand 14: within the quadrature's exact 15.)
#[test]
fn elastic_conductivity_sonine_series_is_chapman_cowling() {
    let second = elastic_conductivity_sonine_series::<3>(2);
    assert!(close(second, 1.0 + 1.0 / 44.0, 1e-12), "{second}");
    let third = elastic_conductivity_sonine_series::<3>(3);
    let beyond = ELASTIC_CONDUCTIVITY_SONINE_FACTOR - third;
    assert!(beyond > 0.0 && beyond < third - second, "{third}: {beyond}");
    println!(
        "3D third order {third}; 2D: second {}, third {}",
        elastic_conductivity_sonine_series::<2>(2),
        elastic_conductivity_sonine_series::<2>(3)
    );
}

/// Oracle: Chapman & Cowling (1970, §10.21): the second Sonine approximation of the
/// viscosity of elastic hard spheres is the first times 1 + 3/202 exactly, the third
/// 1.01588; the converged series is 1.016034 (Pekeris & Alterman 1957), which
/// [`ELASTIC_VISCOSITY_SONINE_FACTOR`] holds: checked to lie past the third order by less
/// than the third order's increment (0.0010; the rest is 0.00016 — twice the geometric tail
/// 7.6e-5 the first increments' ratio would predict: the series converges more slowly).
/// 2D: the same series for disks, printed for the record.
#[test]
fn elastic_viscosity_sonine_series_is_chapman_cowling() {
    let second = elastic_viscosity_sonine_series::<3>(2);
    assert!(close(second, 1.0 + 3.0 / 202.0, 1e-12), "{second}");
    let third = elastic_viscosity_sonine_series::<3>(3);
    assert!((third - 1.01588).abs() < 1e-5, "{third}");
    let beyond = ELASTIC_VISCOSITY_SONINE_FACTOR - third;
    assert!(beyond > 0.0 && beyond < third - second, "{beyond}");
    let second_2d = elastic_viscosity_sonine_series::<2>(2);
    let third_2d = elastic_viscosity_sonine_series::<2>(3);
    println!("2D: second order {second_2d}, third {third_2d}");
    assert!(third_2d > second_2d && second_2d > 1.0);
}
