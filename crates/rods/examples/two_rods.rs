//! Figs. 1 and 2 of Giese with the rod-chain MD (two rods, γ = 0.6173, κ = 4000).
//!
//! `cargo run --release -p haff-rods --example two_rods -- [out_dir] [collisions]`
//! writes `fig1_etr.csv` (collision, E_tr/E0, ε, η), `fig1_spectrum.csv` (rod, ν, ⟨w⟩
//! over collisions 501..=collisions) and `fig2_eta.csv` (M, collision, η), and prints
//! the plateau of E_tr against E0/(2M+1), ⟨η⟩ against η_eq, relaxation times and costs.

use rods::chain::{eta_equilibrium, run_two_rods, TwoRodRecord, TwoRodSetup};
use std::fmt::Write as _;
use std::time::Instant;

const GAMMA: f64 = 0.6173;
const KAPPA: f64 = 4000.0;
/// Measured energy drift at M = 75, κ = 4000: 2.4e-8 over 600 collisions with c_h = 0.25,
/// 1.3e-12 over 100 with c_h = 0.125 (see the `energy_vs_c_h` test).
const C_H: f64 = 0.125;
const SKIP: usize = 500;

fn setup(modes: usize) -> TwoRodSetup {
    TwoRodSetup {
        gamma: GAMMA,
        kappa: KAPPA,
        modes,
        gap: 1.0,
        c_h: C_H,
    }
}

fn write(path: &std::path::Path, text: &str) {
    std::fs::write(path, text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}

/// First collision after which η − η_eq has fallen below 1/e of its value after the
/// first collision.
fn relaxation(recs: &[TwoRodRecord], eta_eq: f64) -> Option<usize> {
    let d0 = recs.first()?.eta - eta_eq;
    recs.iter()
        .find(|r| r.eta - eta_eq < d0 / std::f64::consts::E)
        .map(|r| r.collision)
}

/// First collision at which the mean of E_tr over the next 25 collisions has fallen
/// below plateau + (1 − plateau)/e (the cooling time of Fig. 1).
fn cooling(recs: &[TwoRodRecord], plateau: f64) -> Option<usize> {
    let thr = plateau + (1.0 - plateau) / std::f64::consts::E;
    recs.windows(25)
        .find(|w| w.iter().map(|r| r.e_tr).sum::<f64>() / 25.0 < thr)
        .map(|w| w[0].collision)
}

/// First collision with η within 20 % of η_eq.
fn within(recs: &[TwoRodRecord], eta_eq: f64) -> Option<usize> {
    recs.iter()
        .find(|r| r.eta < 1.2 * eta_eq)
        .map(|r| r.collision)
}

fn fig1(out: &std::path::Path, n: usize) {
    let m = 75;
    let clock = Instant::now();
    let run = run_two_rods(&setup(m), n, SKIP).expect("fig 1 run");
    let secs = clock.elapsed().as_secs_f64();
    let mut csv = String::from("collision,e_tr,eps,eta\n");
    for r in &run.records {
        writeln!(
            csv,
            "{},{:.6e},{:.6},{:.6}",
            r.collision, r.e_tr, r.eps, r.eta
        )
        .unwrap();
    }
    write(&out.join("fig1_etr.csv"), &csv);
    let tail = &run.records[SKIP.min(n - 1)..];
    let mut spec = vec![0.0; 2 * m];
    for r in tail {
        spec.iter_mut()
            .zip(&r.w)
            .for_each(|(s, w)| *s += w / tail.len() as f64);
    }
    let mut csv = String::from("rod,nu,w_mean\n");
    for (j, w) in spec.iter().enumerate() {
        writeln!(csv, "{},{},{:.6e}", j / m + 1, j % m + 1, w).unwrap();
    }
    write(&out.join("fig1_spectrum.csv"), &csv);
    let e_mean = tail.iter().map(|r| r.e_tr).sum::<f64>() / tail.len() as f64;
    println!(
        "  cooling (1/e of E_tr, 25-collision mean) at collision {:?}",
        cooling(&run.records, e_mean)
    );
    let eta_mean = tail.iter().map(|r| r.eta).sum::<f64>() / tail.len() as f64;
    let (wmin, wmax) = spec
        .iter()
        .fold((f64::MAX, 0.0f64), |a, &w| (a.0.min(w), a.1.max(w)));
    println!(
        "Fig. 1: M = {m}, kappa = {KAPPA}, {n} collisions in {secs:.1} s ({:.2} ms/collision)",
        secs * 1e3 / n as f64
    );
    println!(
        "  <E_tr>/E0 over collisions {}..{n} = {e_mean:.5}; E0/(2M+1) = {:.5}; E0/(4M+1) = {:.5}",
        SKIP + 1,
        1.0 / (2.0 * m as f64 + 1.0),
        1.0 / (4.0 * m as f64 + 1.0)
    );
    println!(
        "  time mean E_tr/E0 = {:.5} (free flights only: {:.5}; contact fraction {:.3})",
        run.time_mean_etr(),
        run.free_etr_integral / run.free_time,
        run.contact_time / (run.contact_time + run.free_time)
    );
    println!(
        "  <eta> = {eta_mean:.4}, eta_eq = {:.4}; <w> in [{wmin:.5}, {wmax:.5}] (1/2M = {:.5})",
        eta_equilibrium(m),
        0.5 / m as f64
    );
    println!(
        "  energy drift {:.2e}; fine steps/collision {}, checks/collision {}, ns/fine step {:.0}",
        run.energy_drift,
        run.stats.fine_steps / n as u64,
        run.stats.checks / n as u64,
        run.stats.step_seconds * 1e9 / run.stats.fine_steps as f64
    );
}

fn fig2(out: &std::path::Path, n: usize) {
    let mut csv = String::from("modes,collision,eta\n");
    for m in [10, 25, 50, 75, 100] {
        let clock = Instant::now();
        let run = run_two_rods(&setup(m), n, 0).expect("fig 2 run");
        let secs = clock.elapsed().as_secs_f64();
        for r in &run.records {
            writeln!(csv, "{m},{},{:.6}", r.collision, r.eta).unwrap();
        }
        let eq = eta_equilibrium(m);
        let tail = &run.records[n / 2..];
        let eta_tail = tail.iter().map(|r| r.eta).sum::<f64>() / tail.len() as f64;
        println!("Fig. 2: M = {m:3}: eta_1 = {:.3}, <eta> (collisions {}..{n}) = {eta_tail:.4}, eta_eq = {eq:.4}, \
                  1/e relaxation at collision {:?}, within 20% of eta_eq at {:?}; {:.2} ms/collision",
            run.records[0].eta, n / 2 + 1, relaxation(&run.records, eq), within(&run.records, eq), secs * 1e3 / n as f64);
    }
    write(&out.join("fig2_eta.csv"), &csv);
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let out = std::path::PathBuf::from(args.get(1).map_or("target/two_rods", |s| s.as_str()));
    let n: usize = args
        .get(2)
        .map_or(4500, |s| s.parse().expect("collisions: a number"));
    std::fs::create_dir_all(&out).expect("output directory");
    fig2(&out, 200.min(n));
    fig1(&out, n);
}
