//! Eq. (3) with the noise of Eq. (5) against the Hamiltonian it was derived from: two rods
//! whose modes are drawn from the Boltzmann distribution at T_bath collide once in the
//! rod-chain MD of Eq. (2); the distribution of eps^2 must be that of Eq. (3) at the same
//! E_tr / T_bath and kappa (Giese's Markov approximation, exact for one collision).

use rand::SeedableRng;
use rayon::prelude::*;
use rods::chain::TwoRodSetup;
use rods::stochastic::sample_eps;

const GAMMA: f64 = 0.6173;
const KAPPA: f64 = 100.0;

/// eps of one impact of two rods with thermal modes (T = E0 / ratio, E0 = mu/2).
fn md_eps(modes: usize, ratio: f64, seed: u64) -> f64 {
    let setup = TwoRodSetup {
        gamma: GAMMA,
        kappa: KAPPA,
        modes,
        gap: 20.0,
        c_h: 0.125,
    };
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    setup.thermal_impact_eps(ratio, &mut rng).unwrap()
}

fn mean_and_error(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// Two-sample Kolmogorov-Smirnov distance.
fn ks(a: &mut [f64], b: &mut [f64]) -> f64 {
    a.sort_by(f64::total_cmp);
    b.sort_by(f64::total_cmp);
    let (mut i, mut j, mut d) = (0, 0, 0.0f64);
    while i < a.len() && j < b.len() {
        if a[i] <= b[j] {
            i += 1;
        } else {
            j += 1;
        }
        d = d.max((i as f64 / a.len() as f64 - j as f64 / b.len() as f64).abs());
    }
    d
}

fn compare(ratio: f64, modes: usize, samples: usize) -> (f64, f64, f64, f64) {
    let mut md: Vec<f64> = (0..samples as u64)
        .into_par_iter()
        .map(|k| md_eps(modes, ratio, 1000 + k).powi(2))
        .collect();
    let mut eq3: Vec<f64> = sample_eps(GAMMA, KAPPA, ratio, 4 * samples, 7)
        .unwrap()
        .into_iter()
        .map(|e| e * e)
        .collect();
    let ((m1, e1), (m2, e2)) = (mean_and_error(&md), mean_and_error(&eq3));
    let d = ks(&mut md, &mut eq3);
    let (n, m) = (md.len() as f64, eq3.len() as f64);
    let critical = 1.63 * ((n + m) / (n * m)).sqrt(); // 1 % level
    eprintln!(
        "E/T = {ratio}, M = {modes}: <eps^2> MD {m1:.4} +- {e1:.4}, Eq. (3) {m2:.4} +- {e2:.4}; KS {d:.4} (1 % critical {critical:.4})"
    );
    (m1 - m2, 4.0 * (e1 * e1 + e2 * e2).sqrt(), d, critical)
}

#[test]
fn thermal_two_rod_md_has_the_eps_distribution_of_eq3() {
    for ratio in [1.0, 10.0] {
        let (difference, tolerance, d, critical) = compare(ratio, 64, 400);
        assert!(
            difference.abs() < tolerance,
            "E/T = {ratio}: {difference} vs {tolerance}"
        );
        assert!(d < critical, "E/T = {ratio}: KS {d} >= {critical}");
    }
}

/// The same with 2000 impacts per ratio and 128 modes (about 1 min):
/// cargo test --release -p haff-rods --test eq3_vs_md -- --ignored --nocapture
#[test]
#[ignore]
fn thermal_two_rod_md_has_the_eps_distribution_of_eq3_precisely() {
    for ratio in [0.3, 1.0, 10.0] {
        let (difference, tolerance, d, critical) = compare(ratio, 128, 2000);
        assert!(
            difference.abs() < tolerance,
            "E/T = {ratio}: {difference} vs {tolerance}"
        );
        assert!(d < critical, "E/T = {ratio}: KS {d} >= {critical}");
    }
}
