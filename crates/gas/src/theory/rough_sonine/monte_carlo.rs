//! The oracle of the closed forms: Monte Carlo averages of the reference collision rule
//! `restitution::rough::collide` over pairs drawn from the Maxwellian of the scaled
//! velocities, each weighted by (g.n)^+ and by the Sonine weights W_k of both particles.
//! Nothing of `moments` is used to produce them: the collision is computed in physical
//! units (m = 1, sigma = 1, T_tr = 1, T_rot = theta) and scaled back.

use super::*;
use rand::{Rng, SeedableRng};
use rand_distr::StandardNormal;
use restitution::rough::{collide, Body, Tangential};
use std::f64::consts::PI;

/// One drawn pair: (g.n)^+, the six Delta psi of [`Moment`] (psi = 1 gives 2) and the four
/// weights of [`Weight`] (1, then the Sonine terms of both particles summed).
struct Pair {
    approach: f64,
    changes: [f64; 6],
    weights: [f64; 4],
}

/// S1 and S2 in d dimensions (module documentation of `super`).
fn s1(d: f64, x: f64) -> f64 {
    0.5 * d - x
}
fn s2(d: f64, x: f64) -> f64 {
    0.5 * x * x - 0.5 * (d + 2.0) * x + d * (d + 2.0) / 8.0
}

fn draw(theory: &RoughMaxwellian, theta: f64, rng: &mut rand_pcg::Pcg64) -> Pair {
    let planar = theory.dimension == 2;
    let (dt, dr) = degrees(theory);
    let (m, radius, q) = (1.0, 0.5, theory.inertia);
    let moment = q * m * radius * radius;
    let body = Body {
        mass: m,
        radius,
        inertia: q,
    };
    // Scaled velocities: each component N(0, 1/2); v = sqrt(2 T_tr / m) c with T_tr = 1,
    // omega = sqrt(2 theta / I) w.
    let mut gauss = |on: bool| {
        if on {
            rng.sample::<f64, _>(StandardNormal) * std::f64::consts::FRAC_1_SQRT_2
        } else {
            0.0
        }
    };
    let c: [[f64; 3]; 2] =
        std::array::from_fn(|_| std::array::from_fn(|k| gauss(!planar || k < 2)));
    let w: [[f64; 3]; 2] =
        std::array::from_fn(|_| std::array::from_fn(|k| gauss(!planar || k == 2)));
    let mut n: [f64; 3] = std::array::from_fn(|k| gauss(!planar || k < 2));
    let l = n.iter().map(|x| x * x).sum::<f64>().sqrt();
    n.iter_mut().for_each(|x| *x /= l);
    let (sv, sw) = (2f64.sqrt(), (2.0 * theta / moment).sqrt());
    let square = |x: &[f64; 3]| x.iter().map(|y| y * y).sum::<f64>();
    let (x, y) = (c.map(|v| square(&v)), w.map(|v| square(&v)));
    let weights = [
        1.0,
        s2(dt, x[0]) + s2(dt, x[1]),
        s2(dr, y[0]) + s2(dr, y[1]),
        s1(dt, x[0]) * s1(dr, y[0]) + s1(dt, x[1]) * s1(dr, y[1]),
    ];
    let g_n: f64 = (0..3).map(|k| (c[0][k] - c[1][k]) * n[k]).sum();
    if g_n <= 0.0 {
        return Pair {
            approach: 0.0,
            changes: [0.0; 6],
            weights,
        };
    }
    let rule = Tangential::new(theory.beta, None).expect("beta in [-1, 1]");
    let out = collide(
        &rule,
        theory.alpha,
        [body; 2],
        n,
        c.map(|v| v.map(|u| sv * u)),
        w.map(|v| v.map(|u| sw * u)),
    );
    let xp = out.velocities.map(|v| square(&v.map(|u| u / sv)));
    let yp = out.angular.map(|v| square(&v.map(|u| u / sw)));
    let sum = |f: &dyn Fn(usize) -> f64| f(0) + f(1);
    let changes = [
        2.0,
        sum(&|i| xp[i] - x[i]),
        sum(&|i| yp[i] - y[i]),
        sum(&|i| xp[i] * xp[i] - x[i] * x[i]),
        sum(&|i| yp[i] * yp[i] - y[i] * y[i]),
        sum(&|i| xp[i] * yp[i] - x[i] * y[i]),
    ];
    Pair {
        approach: g_n,
        changes,
        weights,
    }
}

/// Running mean and standard error of a sample mean.
#[derive(Clone, Copy, Default)]
struct Mean {
    sum: f64,
    squares: f64,
}

impl Mean {
    fn add(&mut self, x: f64) {
        self.sum += x;
        self.squares += x * x;
    }
    /// (mean, standard error) over `n` draws, times `scale`.
    fn get(&self, n: usize, scale: f64) -> (f64, f64) {
        let mean = self.sum / n as f64;
        let variance = (self.squares / n as f64 - mean * mean).max(0.0);
        (scale * mean, scale * (variance / n as f64).sqrt())
    }
}

/// E[(g.n)^+]_Maxwell = 1 / sqrt(2 pi) (g.n is N(0, 1) for scaled velocities): the
/// normalisation of the collisional moments.
fn normalisation() -> f64 {
    (2.0 * PI).sqrt()
}

/// The closed forms against Monte Carlo averages of the collision rule, every entry of the
/// table (24 per case, exact zeros included) at four cases, spheres and disks, both signs of
/// beta, theta above and below 1. Tolerance: 5 standard errors of each average (8 million
/// pairs a case; the standard errors are printed).
#[test]
fn closed_forms_are_monte_carlo_averages_of_the_collision_rule() {
    let draws = 8_000_000;
    for (case, (dimension, alpha, beta, q, theta)) in [
        (3, 0.8, 0.4, 0.4, 1.3),
        (3, 0.6, -0.3, 2.0 / 3.0, 2.5),
        (2, 0.7, 0.5, 0.5, 0.7),
        (2, 0.9, -0.5, 0.25, 3.0),
    ]
    .into_iter()
    .enumerate()
    {
        let theory = RoughMaxwellian {
            dimension,
            alpha,
            beta,
            inertia: q,
        };
        let mut rng = rand_pcg::Pcg64::seed_from_u64(101 + case as u64);
        let mut means = [[Mean::default(); 4]; 6];
        for _ in 0..draws {
            let p = draw(&theory, theta, &mut rng);
            for (row, change) in means.iter_mut().zip(p.changes) {
                for (cell, weight) in row.iter_mut().zip(p.weights) {
                    cell.add(p.approach * change * weight);
                }
            }
        }
        let closed = moments(&theory, theta);
        for (psi, row) in means.iter().enumerate() {
            for (k, cell) in row.iter().enumerate() {
                let (mc, error) = cell.get(draws, normalisation());
                let exact = closed.table[psi][k];
                println!(
                    "case {case} psi {psi} weight {k}: closed {exact:.6}, MC {mc:.6} ± {error:.2e}"
                );
                assert!(
                    (mc - exact).abs() < 5.0 * error,
                    "d {dimension} alpha {alpha} beta {beta} q {q} theta {theta}, psi {psi}, \
                     weight {k}: closed form {exact}, Monte Carlo {mc} ± {error}"
                );
            }
        }
    }
}

/// The residuals of (E1)–(E4), linear in the cumulants, as averages over drawn pairs of
/// the collision rule with the weight 1 + sum_k a_k W_k: per pair, each residual is a linear
/// combination of g^+ Delta psi W terms, so its average has a standard error.
fn measured_residuals(
    theory: &RoughMaxwellian,
    theta: f64,
    a: [f64; 3],
    draws: usize,
    seed: u64,
) -> [(f64, f64); 4] {
    let (dt, dr) = degrees(theory);
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    let mut means = [Mean::default(); 4];
    for _ in 0..draws {
        let p = draw(theory, theta, &mut rng);
        let weight = 1.0 + a[0] * p.weights[1] + a[1] * p.weights[2] + a[2] * p.weights[3];
        // N[psi] and N_0[psi] of this pair (times g^+).
        let full = p.changes.map(|x| p.approach * x * weight);
        let bare = p.changes.map(|x| p.approach * x);
        let z = full[1] / dt + full[2] / dr;
        let z0 = bare[1] / dt + bare[2] / dr;
        means[0].add(full[1] / dt - full[2] / dr);
        means[1].add(full[3] - (dt + 2.0) * (full[1] + a[0] * bare[1]));
        means[2].add(full[4] - (dr + 2.0) * (full[2] + a[1] * bare[2]));
        means[3].add(0.5 * full[5] - 0.25 * dt * dr * (z + a[2] * z0));
    }
    means.map(|m| m.get(draws, normalisation()))
}

/// The HCS of the linearised equations solves the moment equations measured with the
/// collision rule: at the solution every residual is within 5 standard errors of 0, while
/// at the Maxwellian state (its ratio, no cumulants) the fourth-moment equations are off
/// by more than 10 (the test can tell the two apart). 4 million pairs a case.
#[test]
fn the_sonine_hcs_solves_the_measured_moment_equations() {
    let draws = 4_000_000;
    for (case, (dimension, alpha, beta, q)) in [(3, 0.7, 0.0, 0.4), (2, 0.6, 0.3, 0.5)]
        .into_iter()
        .enumerate()
    {
        let theory = RoughMaxwellian {
            dimension,
            alpha,
            beta,
            inertia: q,
        };
        let hcs = hcs(&theory).expect("a cooling state");
        let solved = measured_residuals(
            &theory,
            hcs.ratio,
            [hcs.a20, hcs.a02, hcs.a11],
            draws,
            7 + case as u64,
        );
        for (e, (r, error)) in solved.iter().enumerate() {
            println!(
                "d {dimension}: (E{}) at the Sonine HCS {r:.3e} ± {error:.1e}",
                e + 1
            );
            assert!(
                r.abs() < 5.0 * error,
                "d {dimension} (E{}): {r} ± {error}",
                e + 1
            );
        }
        let maxwellian = theory.hcs().unwrap().ratio;
        let off = measured_residuals(&theory, maxwellian, [0.0; 3], draws, 7 + case as u64);
        let worst = off[1..]
            .iter()
            .map(|(r, e)| (r / e).abs())
            .fold(0.0, f64::max);
        println!("d {dimension}: Maxwellian state off by {worst:.1} standard errors");
        assert!(worst > 10.0, "d {dimension}: {off:?}");
    }
}
