use super::*;
use crate::theory::transport::ReducedTransport;

/// The Grad moment equations of the USF in physical variables (n = 1, ν0(T) = T^{1/2}, so
/// a* = a / T^{1/2}) for [P_xx, P_yy, P_xy] (P_zz = P_yy by symmetry), p = tr P / D;
/// `thermostat`: ξ keeps tr P constant. Integrated by RK4 (error O(dt⁴)).
fn integrate<const D: usize>(
    alpha: f64,
    a: f64,
    thermostat: bool,
    start: [f64; 3],
    t_end: f64,
    dt: f64,
) -> [f64; 3] {
    let (beta, zeta) = grad_frequencies::<D>(alpha);
    let d = D as f64;
    let rhs = |p: [f64; 3]| -> [f64; 3] {
        let t = (p[0] + (d - 1.0) * p[1]) / d;
        let nu = t.sqrt();
        let xi2 = if thermostat {
            (-2.0 * a * p[2] - d * zeta * nu * t) / (d * t)
        } else {
            0.0
        };
        [
            -2.0 * a * p[2] - nu * (beta * (p[0] - t) + zeta * t) - xi2 * p[0],
            -nu * (beta * (p[1] - t) + zeta * t) - xi2 * p[1],
            -a * p[1] - nu * beta * p[2] - xi2 * p[2],
        ]
    };
    let add =
        |p: [f64; 3], k: [f64; 3], h: f64| [p[0] + h * k[0], p[1] + h * k[1], p[2] + h * k[2]];
    let mut p = start;
    let steps = (t_end / dt).ceil() as usize;
    for _ in 0..steps {
        let k1 = rhs(p);
        let k2 = rhs(add(p, k1, 0.5 * dt));
        let k3 = rhs(add(p, k2, 0.5 * dt));
        let k4 = rhs(add(p, k3, dt));
        for i in 0..3 {
            p[i] += dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    p
}

/// Oracles: the exact balances at the solution (energy 2 a P_xy/(D n) = −ζ T, trace D, with
/// P*_xx from the xx equation), and the elastic limit (a* = 0, P* = I, η* = 1 = the
/// Navier–Stokes η* of `transport` at α = 1).
#[test]
fn steady_grad_balances() {
    fn check<const D: usize>() {
        let d = D as f64;
        for alpha in [0.95, 0.8, 0.6, 0.3, 0.0] {
            let s = steady_grad::<D>(alpha);
            let (_, zeta) = grad_frequencies::<D>(alpha);
            assert!((2.0 * s.reduced_shear_rate * s.pxy / d + zeta).abs() < 1e-14);
            assert!((s.pxx + (d - 1.0) * s.pyy - d).abs() < 1e-14);
            assert!((s.viscosity + s.pxy / s.reduced_shear_rate).abs() < 1e-14);
            assert_eq!(s.thermostat, 0.0);
        }
        let s = steady_grad::<D>(1.0);
        assert_eq!(
            (s.reduced_shear_rate, s.pxx, s.pyy, s.pxy),
            (0.0, 1.0, 1.0, 0.0)
        );
        assert_eq!(
            s.viscosity,
            ReducedTransport::enskog::<D>(0.0, 1.0).shear_viscosity
        );
    }
    check::<2>();
    check::<3>();
}

/// Oracle: the time-dependent Grad equations integrated from equilibrium until steady (a
/// second route to the same fixed point: no cubic, no closed form). Tolerance 1e-9: RK4 at
/// dt = 0.01 and the remaining transient (e^{-40}).
#[test]
fn steady_grad_is_the_long_time_limit() {
    fn check<const D: usize>(alpha: f64) {
        let p = integrate::<D>(alpha, 1.0, false, [1.0, 1.0, 0.0], 400.0, 0.01);
        let t = (p[0] + (D as f64 - 1.0) * p[1]) / D as f64;
        let s = steady_grad::<D>(alpha);
        let got = [1.0 / t.sqrt(), p[0] / t, p[1] / t, p[2] / t];
        let want = [s.reduced_shear_rate, s.pxx, s.pyy, s.pxy];
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g - w).abs() < 1e-9,
                "D={D} alpha={alpha}: {got:?} vs {want:?}"
            );
        }
    }
    check::<3>(0.7);
    check::<3>(0.4);
    check::<2>(0.8);
}

/// Oracle: the thermostatted equations integrated at T = 1 until steady, for the elastic and
/// an inelastic gas; and the thermostatted state at the steady a* is the steady state (ξ = 0).
#[test]
fn thermostatted_grad_is_the_long_time_limit() {
    for (alpha, a) in [(1.0, 0.5), (1.0, 3.0), (0.6, 0.3), (0.6, 1.5)] {
        let p = integrate::<3>(alpha, a, true, [1.0, 1.0, 0.0], 60.0, 0.002);
        let s = thermostatted_grad::<3>(alpha, a);
        let got = [p[0], p[1], p[2]];
        let want = [s.pxx, s.pyy, s.pxy];
        for (g, w) in got.iter().zip(want) {
            assert!(
                (g - w).abs() < 1e-9,
                "alpha={alpha} a={a}: {got:?} vs {want:?}"
            );
        }
    }
    for alpha in [0.9, 0.5] {
        let steady = steady_grad::<2>(alpha);
        let held = thermostatted_grad::<2>(alpha, steady.reduced_shear_rate);
        assert!(held.thermostat.abs() < 1e-14 && (held.viscosity - steady.viscosity).abs() < 1e-14);
    }
}

/// Oracle: the series of the elastic cubic θ²(θ − 1) = k, k = 2a*²/D: θ = 1 + k − 2k² + …,
/// η* = 1/θ² = 1 − 2k + 7k² + O(k³); and the shear-thinning tail η* → k^{−2/3}.
#[test]
fn elastic_thermostatted_viscosity_is_shear_thinning() {
    for a in [1e-3, 0.05] {
        let k = 2.0 * a * a / 3.0;
        let eta = thermostatted_grad::<3>(1.0, a).viscosity;
        assert!(
            (eta - (1.0 - 2.0 * k + 7.0 * k * k)).abs() < 50.0 * k * k * k + 1e-15,
            "{a}: {eta}"
        );
    }
    let a = 1e6;
    let tail = (2.0 * a * a / 2.0f64).powf(-2.0 / 3.0);
    assert!((thermostatted_grad::<2>(1.0, a).viscosity / tail - 1.0).abs() < 1e-3);
}

/// Oracle: the Navier–Stokes viscosities of `transport`'s collision frequencies at a2 = 0.
/// Held at T by the thermostat, η*(a* → 0) = 1/(ν_η* − ζ*); with a constant a while T cools
/// (the moment equations integrated from T = 1 at a = 10⁻⁴, a* ≤ 6·10⁻⁴ throughout), the
/// normal solution has the HCS viscosity 1/(ν_η* − ζ*/2) of Brey et al. (1998) at a2 = 0.
/// Tolerance 1e-5: O(a*²) (Burnett) terms and the decayed transient (e^{−15}).
#[test]
fn cooling_shear_flow_has_the_hcs_viscosity() {
    for alpha in [0.9, 0.7] {
        let nu = collision_frequencies::<3>(alpha, 0.0);
        let held = thermostatted_grad::<3>(alpha, 1e-5).viscosity;
        assert!((held * (nu.shear - nu.cooling) - 1.0).abs() < 1e-9);
        let a = 1e-4;
        let p = integrate::<3>(alpha, a, false, [1.0, 1.0, 0.0], 40.0, 0.005);
        let t = (p[0] + 2.0 * p[1]) / 3.0;
        let eta = -p[2] * t.sqrt() / (a * t);
        let hcs = 1.0 / (nu.shear - 0.5 * nu.cooling);
        assert!(
            (eta / hcs - 1.0).abs() < 1e-5,
            "alpha={alpha}: {eta} vs {hcs}"
        );
        assert!((held / hcs - 1.0).abs() > 1e-3);
    }
}

/// Oracle: the BGK model's moment equations are Grad's with β → ν_B* + ζ* (module
/// documentation); with ν_B* fixed by the Navier–Stokes viscosity the pressure tensors agree.
#[test]
fn bgk_pressure_tensor_is_grads() {
    for alpha in [0.9, 0.6, 0.2] {
        let (g, b) = (steady_grad::<3>(alpha), steady_bgk::<3>(alpha));
        for (x, y) in [
            (g.reduced_shear_rate, b.reduced_shear_rate),
            (g.pxx, b.pxx),
            (g.pxy, b.pxy),
        ] {
            assert!((x - y).abs() < 1e-14, "{alpha}: {g:?} vs {b:?}");
        }
        let (g, b) = (
            thermostatted_grad::<2>(alpha, 0.7),
            thermostatted_bgk::<2>(alpha, 0.7),
        );
        assert!((g.viscosity - b.viscosity).abs() < 1e-14);
        let nu = collision_frequencies::<3>(alpha, 0.0);
        let (nb, z) = (bgk_collision_frequency::<3>(alpha), nu.cooling);
        assert!((1.0 / (nb + 0.5 * z) - 1.0 / (nu.shear - 0.5 * z)).abs() < 1e-14);
        let closed = (1.0 + alpha) * (4.0 + 2.0 * alpha) / 12.0;
        assert!((nb - closed).abs() < 1e-15);
    }
}

/// The table of docs/transport.md (run with `--ignored --nocapture`).
#[test]
#[ignore]
fn print_table() {
    for alpha in [1.0, 0.9, 0.8, 0.7, 0.6, 0.5] {
        let (s2, s3) = (steady_grad::<2>(alpha), steady_grad::<3>(alpha));
        println!(
            "| {alpha:.1} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} |",
            s2.reduced_shear_rate, s2.pxx, s2.pyy, s2.pxy, s2.viscosity,
            s3.reduced_shear_rate, s3.pxx, s3.pyy, s3.pxy, s3.viscosity
        );
    }
}
