//! Fig. 3 of Giese: the density p(ε²) and the distribution function of ε² from 8000
//! realizations of Eq. (3) at κ = 100 for a) E_tr/T_bath = 10, γ = 0.6173; b) E/T = 1,
//! γ = 0.6173; c) E/T = 1, γ = 0.2173.
//!
//! Usage: `cargo run --release -p haff-rods --example fig3 -- OUT.csv [REALIZATIONS] [SEED]`
//!
//! Writes CSV rows `case,gamma,energy_ratio,eps2_lo,eps2_hi,density,cdf` (histogram of ε²
//! on [0, 4) with bin width 0.02, density normalized by all realizations; `cdf` is the
//! empirical distribution function at `eps2_hi`) and prints a summary per case.
use rods::stochastic::sample_eps;
use std::fmt::Write as _;
use std::time::Instant;

const CASES: [(&str, f64, f64); 3] = [("a", 0.6173, 10.0), ("b", 0.6173, 1.0), ("c", 0.2173, 1.0)];
const KAPPA: f64 = 100.0;
const BINS: usize = 200;
const XMAX: f64 = 4.0;

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().collect();
    let out = args
        .get(1)
        .ok_or("usage: fig3 OUT.csv [REALIZATIONS] [SEED]")?;
    let n: usize = match args.get(2) {
        Some(s) => s.parse().map_err(|e| format!("REALIZATIONS: {e}"))?,
        None => 8000,
    };
    let seed: u64 = match args.get(3) {
        Some(s) => s.parse().map_err(|e| format!("SEED: {e}"))?,
        None => 3,
    };
    let mut csv = String::from("case,gamma,energy_ratio,eps2_lo,eps2_hi,density,cdf\n");
    for (case, gamma, ratio) in CASES {
        let t = Instant::now();
        let mut e2: Vec<f64> = sample_eps(gamma, KAPPA, ratio, n, seed)?
            .into_iter()
            .map(|e| e * e)
            .collect();
        let dt = t.elapsed().as_secs_f64();
        e2.sort_by(f64::total_cmp);
        let nf = n as f64;
        let mean = e2.iter().sum::<f64>() / nf;
        let sd = (e2.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (nf - 1.0)).sqrt();
        let q = |p: f64| {
            let x = p * (nf - 1.0);
            let j = (x as usize).min(n.saturating_sub(2));
            let f = x - j as f64;
            if n == 1 {
                e2[0]
            } else {
                e2[j] + f * (e2[j + 1] - e2[j])
            }
        };
        let above = e2.iter().filter(|&&x| x > 1.0).count() as f64 / nf;
        println!(
            "case {case}: gamma {gamma} E/T {ratio} kappa {KAPPA} n {n}: {dt:.1} s ({:.2} ms wall per realization on all threads)\n  mean eps2 {mean:.4} +- {:.4} (sd {sd:.4}), quantiles 5% {:.4} 25% {:.4} 50% {:.4} 75% {:.4} 95% {:.4}, min {:.4} max {:.3}, P(eps2 > 1) = {above:.4}",
            1e3 * dt / nf,
            sd / nf.sqrt(),
            q(0.05),
            q(0.25),
            q(0.5),
            q(0.75),
            q(0.95),
            e2[0],
            e2[n - 1]
        );
        let w = XMAX / BINS as f64;
        let mut below = 0usize;
        for b in 0..BINS {
            let (lo, hi) = (b as f64 * w, (b + 1) as f64 * w);
            let start = below;
            while below < n && e2[below] < hi {
                below += 1;
            }
            let density = (below - start) as f64 / (nf * w);
            writeln!(
                csv,
                "{case},{gamma},{ratio},{lo:.4},{hi:.4},{density:.6},{:.6}",
                below as f64 / nf
            )
            .map_err(|e| e.to_string())?;
        }
    }
    std::fs::write(out, csv).map_err(|e| format!("{out}: {e}"))?;
    println!("wrote {out}");
    Ok(())
}
