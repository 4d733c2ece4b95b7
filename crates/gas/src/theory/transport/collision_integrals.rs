//! The collision integrals of the dilute gas by Gauss quadrature, exact for polynomial
//! integrands: the independent oracle of the closed forms in [`super::collision_frequencies`]
//! (and of the Grad coefficients of [`super::super::usf`]). Test-only.
//!
//! Units m = σ = n = 1, T = 1/2 (thermal speed v0 = (2T/m)^{1/2} = 1), so the Maxwellian is
//! φ(c) = π^{−D/2} e^{−c²}. The weak form of the Boltzmann operator of inelastic hard
//! spheres (Brey, Dufty, Kim & Santos 1998, Eq. (5)),
//!
//!   ∫ ψ(c1) J[F, G](c1) dc1 = ∫∫ dc1 dc2 F(c1) G(c2) ∫ de Θ(g·e) (g·e) [ψ(c1') − ψ(c1)],
//!   c1' = c1 − (1+α)/2 (g·e) e,  c2' = c2 + (1+α)/2 (g·e) e,  g = c1 − c2,
//!
//! is averaged here with F = G = φ times polynomials. The integrand of a rotational scalar
//! (tensors contracted) is invariant under a joint rotation of c1, c2, e, so e is fixed along
//! the last axis and ∫ de gives S_D. With C = (c1 + c2)/2 (weight e^{−2C²}) and g (weight
//! e^{−g²/2}): Gauss–Hermite in every component of C and in the components of g normal to e;
//! along e, ∫_0^∞ g e^{−g²/2} P(g) dg splits into the even part of P (Gauss–Laguerre in
//! u = g²/2) and the odd part (g P_odd(g) is even: half the Gauss–Hermite integral over the
//! line). Eight nodes integrate polynomials of degree ≤ 15 per variable exactly; the
//! integrands here have degree ≤ 12.

use crate::theory::gauss::{hermite_rule, laguerre_rule};
use crate::theory::sphere_surface;
use std::f64::consts::PI;

const NODES: usize = 8;

/// ∫∫ dc1 dc2 φ(c1) φ(c2) ∫ de Θ(g·e)(g·e) F(c1, c2, e) for F a polynomial given as a
/// function of c1 and c2 with e the last unit vector (so g·e = c1[D−1] − c2[D−1]).
pub fn collision_average<const D: usize>(integrand: impl Fn(&[f64; D], &[f64; D]) -> f64) -> f64 {
    let hermite = hermite_rule(NODES);
    let laguerre = laguerre_rule(NODES);
    let dims = 2 * D - 1; // C (D components), g normal to e (D − 1)
    let mut index = vec![0usize; dims];
    let mut total = 0.0;
    loop {
        let (mut c_mid, mut g) = ([0.0; D], [0.0; D]);
        let mut weight = 1.0;
        for (k, &i) in index.iter().enumerate() {
            let (x, w) = (hermite.nodes[i], hermite.weights[i]);
            if k < D {
                c_mid[k] = x / 2f64.sqrt();
                weight *= w / 2f64.sqrt();
            } else {
                g[k - D] = x * 2f64.sqrt();
                weight *= w * 2f64.sqrt();
            }
        }
        let value = |g_e: f64| {
            let mut g = g;
            g[D - 1] = g_e;
            let c1: [f64; D] = std::array::from_fn(|k| c_mid[k] + 0.5 * g[k]);
            let c2: [f64; D] = std::array::from_fn(|k| c_mid[k] - 0.5 * g[k]);
            integrand(&c1, &c2)
        };
        let mut along = 0.0;
        for (&u, &w) in laguerre.nodes.iter().zip(&laguerre.weights) {
            let s = (2.0 * u).sqrt();
            along += w * 0.5 * (value(s) + value(-s));
        }
        for (&y, &w) in hermite.nodes.iter().zip(&hermite.weights) {
            let s = 2f64.sqrt() * y;
            along += w * y * 0.5 * (value(s) - value(-s));
        }
        total += weight * along;
        // Next multi-index (an odometer over the Hermite nodes).
        let mut k = 0;
        while k < dims {
            index[k] += 1;
            if index[k] < NODES {
                break;
            }
            index[k] = 0;
            k += 1;
        }
        if k == dims {
            break;
        }
    }
    total * sphere_surface::<D>() / PI.powi(D as i32)
}

/// The post-collision velocities for e along the last axis.
pub fn collide<const D: usize>(c1: &[f64; D], c2: &[f64; D], alpha: f64) -> ([f64; D], [f64; D]) {
    let g_e = c1[D - 1] - c2[D - 1];
    let (mut p1, mut p2) = (*c1, *c2);
    p1[D - 1] -= 0.5 * (1.0 + alpha) * g_e;
    p2[D - 1] += 0.5 * (1.0 + alpha) * g_e;
    (p1, p2)
}

/// S_2(c²) = c⁴/2 − (D+2) c²/2 + D(D+2)/8, the second Sonine polynomial.
pub fn sonine2<const D: usize>(c: &[f64; D]) -> f64 {
    let (d, x) = (D as f64, c.iter().map(|v| v * v).sum::<f64>());
    0.5 * x * x - 0.5 * (d + 2.0) * x + d * (d + 2.0) / 8.0
}

/// A Maxwellian average ∫ φ(c) F(c) dc by the product Gauss–Hermite rule.
pub fn maxwellian_average<const D: usize>(integrand: impl Fn(&[f64; D]) -> f64) -> f64 {
    let hermite = hermite_rule(NODES);
    let mut index = [0usize; D];
    let mut total = 0.0;
    loop {
        let c: [f64; D] = std::array::from_fn(|k| hermite.nodes[index[k]]);
        let w: f64 = index.iter().map(|&i| hermite.weights[i]).product();
        total += w * integrand(&c);
        let mut k = 0;
        while k < D {
            index[k] += 1;
            if index[k] < NODES {
                break;
            }
            index[k] = 0;
            k += 1;
        }
        if k == D {
            break;
        }
    }
    total / PI.powf(0.5 * D as f64)
}

/// A linearized collision frequency in the units above, as (value at a2 = 0, its slope in
/// a2): ν = −∫ ψ_i L[φ ψ_i] / ∫ φ ψ_i ψ_i with the linearized operator
/// L[h] = −(J[f0, h] + J[h, f0]) about f0 = φ (1 + a2 S_2) (`tracer`: only −J[h, f0], the
/// collisions of a tagged particle with the gas). `psi` returns the components ψ_i (a
/// contracted tensor is a list of its components).
pub fn linearized_frequency<const D: usize>(
    alpha: f64,
    tracer: bool,
    psi: impl Fn(&[f64; D]) -> Vec<f64>,
) -> (f64, f64) {
    let norm = maxwellian_average::<D>(|c| psi(c).iter().map(|p| p * p).sum());
    let gain = |c1: &[f64; D], c2: &[f64; D], sonine_weight: &dyn Fn(&[f64; D]) -> f64| {
        // ∫ ψ(J[f0, h] + J[h, f0]) = ∫∫ f0(1) h(2) [Δψ(1) + Δψ(2)]; tracer: ∫∫ h(1) f0(2) Δψ(1).
        let (p1, p2) = collide(c1, c2, alpha);
        let (a1, b1, a2_, b2) = (psi(c1), psi(&p1), psi(c2), psi(&p2));
        if tracer {
            let h1 = &a1;
            sonine_weight(c2) * (0..h1.len()).map(|i| h1[i] * (b1[i] - a1[i])).sum::<f64>()
        } else {
            let h2 = &a2_;
            sonine_weight(c1)
                * (0..h2.len())
                    .map(|i| h2[i] * (b1[i] - a1[i] + b2[i] - a2_[i]))
                    .sum::<f64>()
        }
    };
    let zeroth = collision_average::<D>(|c1, c2| gain(c1, c2, &|_| 1.0));
    let slope = collision_average::<D>(|c1, c2| gain(c1, c2, &|c| sonine2::<D>(c)));
    (-zeroth / norm, -slope / norm)
}
