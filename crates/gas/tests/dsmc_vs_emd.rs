//! DSMC against event-driven MD of the same gas (issue 5): the two engines share nothing but
//! the collision law, so agreement of T(t) within statistical error checks both.

mod common;

use common::log_temperatures;
use gas::dsmc::{point_gas, Scheme};
use gas::init::monodisperse;
use gas::{EventDriven, HomogeneousDsmc};
use restitution::{Constant, Restitution};

fn viscoelastic(beta: f64) -> Box<dyn Restitution> {
    Box::new(common::viscoelastic(beta, "fast"))
}

/// ln T at the given times from eMD runs with independent seeds (N particles at phi).
fn emd_log_temperatures(
    law: &dyn Restitution,
    n: usize,
    phi: f64,
    seeds: std::ops::Range<u64>,
    times: &[f64],
) -> Vec<Vec<f64>> {
    seeds
        .map(|seed| {
            let system = monodisperse::<3>(n, phi, 1.0, 1.0, 1.0, seed).unwrap();
            // Cells of about a tenth of a mean free path (fewer crossings when dilute).
            let width = (0.05 / phi).max(1.0);
            let mut e = EventDriven::with_cell_width(system, law.box_clone(), width).unwrap();
            log_temperatures(&mut e, times)
        })
        .collect()
}

/// ln T at the given times from one large homogeneous DSMC run (blocks scheme).
fn dsmc_log_temperatures(law: &dyn Restitution, n: usize, phi: f64, times: &[f64]) -> Vec<f64> {
    let length = gas::system::monodisperse_box_side::<3>(n, 1.0, phi);
    let system = point_gas::<3>(n, length, 1.0, 1.0, 1.0, 99).unwrap();
    let mut d = HomogeneousDsmc::new(system, phi, law.box_clone(), 99, Scheme::default()).unwrap();
    log_temperatures(&mut d, times)
}

/// Compares eMD (K seeds) with DSMC at each time: z = (mean ln T_eMD - ln T_DSMC) / error,
/// the error from the spread over seeds and the DSMC fluctuation, which with N_dsmc
/// particles is that of K runs of N scaled by sqrt(N K / N_dsmc). Returns the worst |z|.
fn worst_z(emd: &[Vec<f64>], dsmc: &[f64], n: usize, n_dsmc: usize, label: &str) -> f64 {
    let k = emd.len() as f64;
    let mut worst: f64 = 0.0;
    for (col, &d) in dsmc.iter().enumerate() {
        let values: Vec<f64> = emd.iter().map(|run| run[col]).collect();
        let mean = values.iter().sum::<f64>() / k;
        let var = values.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (k - 1.0);
        let error = (var / k + var * n as f64 / n_dsmc as f64).sqrt();
        let z = (mean - d) / error;
        eprintln!(
            "{label}: sample {col}: ln T eMD {mean:.5} +- {:.5}, DSMC {d:.5}, T_eMD/T_DSMC - 1 = {:+.4}, z = {z:+.2}",
            (var / k).sqrt(),
            (mean - d).exp() - 1.0
        );
        worst = worst.max(z.abs());
    }
    worst
}

/// Constant eps = 0.9 at phi = 0.05 and viscoelastic spheres (fast law, beta = 1; eps
/// about 0.5 at the start) at phi = 0.005: eMD (N = 2000, 8 seeds) and homogeneous DSMC
/// (N = 2e5) give the same T(t) within 4 errors over decades of cooling. DSMC also cools
/// as t^(-5/3) at late times (Brilliantov & Pöschel 2004, Ch. 8). The viscoelastic comparison needs the dilute box (2.7 mean
/// free paths): at phi = 0.05 the eMD box is 12 mean free paths wide, beyond the size at
/// which the homogeneous state of a gas this dissipative turns unstable, and the eMD gas
/// then cools 4-10 % slower than the homogeneous DSMC (measured: z up to 8.9).
/// `cargo test --release -p haff-gas --test dsmc_vs_emd -- --ignored --nocapture`
#[test]
#[ignore]
fn dsmc_and_emd_cool_alike() {
    let (n, phi, n_dsmc) = (2000, 0.05, 200_000);
    let constant = Constant::new(0.9).unwrap();
    let times = [5.0, 20.0, 80.0, 320.0];
    let emd = emd_log_temperatures(&constant, n, phi, 0..8, &times);
    let dsmc = dsmc_log_temperatures(&constant, n_dsmc, phi, &times);
    assert!(worst_z(&emd, &dsmc, n, n_dsmc, "eps = 0.9") < 4.0);

    let (law, dilute) = (viscoelastic(1.0), 0.005);
    let times = [100.0, 1000.0, 10000.0, 50000.0];
    let emd = emd_log_temperatures(law.as_ref(), n, dilute, 10..18, &times);
    let dsmc = dsmc_log_temperatures(law.as_ref(), n_dsmc, dilute, &times);
    assert!(worst_z(&emd, &dsmc, n, n_dsmc, "viscoelastic") < 4.0);
    // The t^(-5/3) regime needs 1 - eps small (v* << 1), and v* ~ T^(1/20) falls slowly:
    // with beta = 1 the local exponent is still -1.74 between t = 1e6 and 1e7. With
    // beta = 0.01 (N = 2e5, `haff run`) it is -1.4299, -1.5706, -1.6316, -1.6543, -1.6634,
    // -1.6660, -1.6672 over log-spaced windows from 1e4 to 1e7. Asserted on the last window
    // (N = 2e4: the error of ln T is about sqrt(2/(3N)) = 0.006, of the exponent 0.006).
    let late = dsmc_log_temperatures(viscoelastic(0.01).as_ref(), 20_000, dilute, &[3.73e6, 1e7]);
    let exponent = (late[1] - late[0]) / (1e7f64 / 3.73e6).ln();
    eprintln!("DSMC viscoelastic (beta = 0.01): local exponent of T(t) between t = 3.7e6 and 1e7: {exponent:.4}");
    assert!((exponent + 5.0 / 3.0).abs() < 0.02, "{exponent}");
}
