//! Tests of the deterministic closed forms and of the stochastic collision equation,
//! Eqs. (3)-(7) of Giese. Fast (release): `cargo test --release -p haff-rods`.
use rand::Rng;
use rods::deterministic::{eps_closed_form, eps_closed_form_general, eps_numeric};
use rods::stochastic::markov::{canonical_step, glauber_eps2, ks_exponential, moments, run_chain};
use rods::stochastic::{
    covariance, realization_rng, sample_eps, solve, NoiseProcess, Resolution, Table,
};

/// numeric − generalized closed form, step h = 0.1/κ, against the lead's measurement
/// (h = 2e-4), each quoted to 2-3 significant digits: the tolerance is half a unit of the
/// last quoted digit.
#[test]
fn closed_form_general_below_one_half() {
    let lead = [
        (30.0, 0.1, 3.45e-3, 0.005e-3),
        (30.0, 0.3, 3.04e-3, 0.005e-3),
        (30.0, 0.45, 1.68e-3, 0.005e-3),
        (100.0, 0.1, 4.2e-4, 0.05e-4),
        (100.0, 0.3, 3.7e-4, 0.05e-4),
        (100.0, 0.45, 2.4e-4, 0.05e-4),
        (300.0, 0.1, 5.8e-5, 0.05e-5),
        (300.0, 0.3, 5.1e-5, 0.05e-5),
        (300.0, 0.45, 3.5e-5, 0.05e-5),
    ];
    for (k, g, d, tol) in lead {
        let n = eps_numeric(g, k, 0.1 / k);
        let m = n - eps_closed_form_general(g, k);
        println!("kappa {k} gamma {g}: numeric - general = {m:.4e} (lead {d:.2e})");
        assert!((m - d).abs() <= tol, "{k} {g}: {m} vs {d}");
        // and γ ↔ 1/γ: same value up to summation order
        assert!((eps_numeric(1.0 / g, k, 0.1 / k) - n).abs() < 1e-12);
    }
    // the paper's form is off by (lead) −2.2e-2 (γ 0.1) and −8.1e-3 (γ 0.3) at κ = 100
    for (g, d, tol) in [(0.1, -2.2e-2, 0.05e-2), (0.3, -8.1e-3, 0.05e-3)] {
        let m = eps_numeric(g, 100.0, 1e-3) - eps_closed_form(g, 100.0);
        println!("gamma {g}: numeric - paper = {m:.4e}");
        assert!((m - d).abs() <= tol, "{g}: {m}");
    }
}

/// 1/2 < γ < 2: both closed forms coincide and agree with the numerics to ≤ 3e-8 (lead)
/// once κ|Γ2 − Γ1| ≳ 10 (here: ≥ 31 at κ = 100, 1e-8 is the measured step error bound at
/// h = 5e-5, so the bound is 3e-8 + step error).
#[test]
fn closed_forms_agree_between_one_half_and_two() {
    for g in [0.6173, 0.75, 0.9, 1.0 / 0.6173, 1.5] {
        let (k, h) = (300.0, 5e-5);
        let n = eps_numeric(g, k, h);
        let (a, b) = (eps_closed_form(g, k), eps_closed_form_general(g, k));
        println!("gamma {g}: numeric {n:.9} paper {a:.9} diff {:.2e}", n - a);
        assert_eq!(a, b);
        assert!((n - a).abs() < 3e-8 + 1e-8, "{g}: {}", n - a);
    }
}

/// Near γ = 1 both closed forms fail (lead: +1.44e-3 at γ 0.99, κ 100; +7.7e-6 at κ 300;
/// +1.6e-3 at γ 0.95, κ 30), and γ = 1 gives ε = 1 (the closed forms → −∞).
#[test]
fn near_equal_rods() {
    for (g, k, h, d, tol) in [
        (0.99, 100.0, 2e-4, 1.44e-3, 0.005e-3),
        (0.99, 300.0, 2e-4, 7.7e-6, 0.05e-6),
        (0.95, 30.0, 2e-4, 1.6e-3, 0.05e-3),
    ] {
        let m = eps_numeric(g, k, h) - eps_closed_form_general(g, k);
        println!("gamma {g} kappa {k}: numeric - closed = {m:.4e}");
        assert!((m - d).abs() <= tol, "{g} {k}: {m}");
    }
    assert_eq!(eps_closed_form_general(1.0, 100.0), f64::NEG_INFINITY);
    for k in [30.0, 100.0] {
        // second-order step error (measured ratio of successive differences ≈ 4):
        // Richardson extrapolation from h and h/2
        let (e1, e2) = (eps_numeric(1.0, k, 0.1 / k), eps_numeric(1.0, k, 0.05 / k));
        let ex = (4.0 * e2 - e1) / 3.0;
        println!("gamma 1 kappa {k}: eps(h) {e1:.9} eps(h/2) {e2:.9} extrapolated {ex:.9}");
        assert!((ex - 1.0).abs() < 1e-6, "{k}: {ex}");
    }
}

/// Mean and standard error of a sample.
fn mean_se(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    let v = x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0);
    (m, (v / n).sqrt())
}

/// The sampled Q_i has the covariance Eq. (5) of Giese: mean 0, variance κ²(T/E)Γ/24 and
/// the parabolic correlation at lags 0, Γ/8, Γ/4, Γ/2, 3Γ/4. Estimator per realization:
/// the average over the N grid positions (stationarity); tolerance 4 standard errors of
/// the mean over M independent realizations.
#[test]
fn noise_covariance_is_eq5() {
    let (gamma, kappa, r) = (0.6173, 100.0, 2.0);
    let period = 1.0 + gamma;
    // variance from Eq. (5) at lag 0: (Γ/4)(1/4 − 1/12) = Γ/24
    let var = kappa * kappa / r * period / 24.0;
    assert!((covariance(period, kappa, r, 0.0) - var).abs() < 1e-12 * var);
    let (n, m) = (64usize, 4000usize);
    let lags = [0usize, 8, 16, 32, 48];
    let mut est: Vec<Vec<f64>> = vec![Vec::with_capacity(m); lags.len() + 1];
    let mut rng = realization_rng(42, 0);
    for _ in 0..m {
        let q = NoiseProcess::sample(period, kappa, r, n, &mut rng);
        let g = q.grid();
        est[0].push(g.iter().sum::<f64>() / n as f64);
        for (l, &lag) in lags.iter().enumerate() {
            est[l + 1].push((0..n).map(|k| g[k] * g[(k + lag) % n]).sum::<f64>() / n as f64);
        }
    }
    let (mean, se) = mean_se(&est[0]);
    println!("mean {mean:.4} +- {se:.4} (0)");
    assert!(mean.abs() < 4.0 * se);
    for (l, &lag) in lags.iter().enumerate() {
        let exact = covariance(period, kappa, r, lag as f64 * period / n as f64);
        let (c, se) = mean_se(&est[l + 1]);
        println!("lag {lag}/{n}: {c:.3} +- {se:.3} (Eq. 5: {exact:.3})");
        assert!((c - exact).abs() < 4.0 * se, "lag {lag}: {c} vs {exact}");
    }
}

/// E_tr/T_bath = ∞ reproduces the deterministic value exactly (same integrator, Q ≡ 0).
#[test]
fn infinite_ratio_is_deterministic() {
    let v = sample_eps(0.6173, 100.0, f64::INFINITY, 3, 9).unwrap();
    let d = eps_numeric(0.6173, 100.0, Resolution::default().h(100.0, f64::INFINITY));
    assert_eq!(v, vec![d; 3]);
}

/// Per-realization seeding: the sample does not depend on the number of threads.
#[test]
fn thread_count_independent() {
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| sample_eps(0.6173, 100.0, 1.0, 12, 5).unwrap())
    };
    let (a, b) = (run(1), run(2));
    assert_eq!(a, b);
    assert!(a.iter().all(|e| e.is_finite() && *e > 0.0));
}

/// Convergence in h and n_max with common random numbers (the low noise modes are shared,
/// see `noise`): mean paired difference of ε² between the default resolution and
/// (h/2, 4× noise points) resp. (h, 4× noise points) is zero within 4 standard errors.
#[test]
fn converged_in_step_and_modes() {
    let fine = Resolution {
        step: 0.05,
        oversample: 2.0,
    };
    let modes = Resolution {
        step: 0.1,
        oversample: 4.0,
    };
    for (r, n) in [(1.0, 150u64), (0.1, 60)] {
        let mut d_fine = Vec::new();
        let mut d_modes = Vec::new();
        let mut base = Vec::new();
        for k in 0..n {
            let e2 = |res: &Resolution| {
                let mut rng = realization_rng(77, k);
                let s = solve(0.6173, 100.0, r, res, &mut rng).unwrap();
                // the adaptive horizon ended the integration, not the hard cap
                assert!(s.stopped);
                s.eps.powi(2)
            };
            let b = e2(&Resolution::default());
            base.push(b);
            d_fine.push(b - e2(&fine));
            d_modes.push(b - e2(&modes));
        }
        let (mb, seb) = mean_se(&base);
        let (mf, sef) = mean_se(&d_fine);
        let (mm, sem) = mean_se(&d_modes);
        println!("r {r}: <eps2> {mb:.4} +- {seb:.4}; default - fine {mf:.5} +- {sef:.5}; default - 4x modes {mm:.5} +- {sem:.5}");
        assert!(mf.abs() < 4.0 * sef && mm.abs() < 4.0 * sem);
    }
}

/// Glauber form Eq. (7): E' ~ Exp(mean T) independent of E, so the chain Eq. (6) samples
/// exp(−E/T) exactly (iid after one step): mean 1 ± 4/√n, second moment 2 ± 4·√20/√n,
/// and the KS distance below the 1% critical value 1.63/√n.
#[test]
fn glauber_chain_is_exponential() {
    let n = 200_000;
    let mut rng = realization_rng(3, 0);
    let ch = run_chain(5.0, n, |r| glauber_eps2(r, rng.random()));
    let (m1, m2) = moments(&ch);
    let ks = ks_exponential(&ch);
    let sq = (n as f64).sqrt();
    println!(
        "Glauber chain: mean {m1:.4} m2 {m2:.4} KS {ks:.5} (1% critical {:.5})",
        1.63 / sq
    );
    assert!((m1 - 1.0).abs() < 4.0 / sq);
    assert!((m2 - 2.0).abs() < 4.0 * 20f64.sqrt() / sq);
    assert!(ks < 1.63 / sq);
}

/// Stationarity of exp(−E/T_bath) under the exact kernel of Eq. (6) with direct solves of
/// Eq. (3): E ~ Exp(1) (conditioned on E ≥ 1e-3) mapped by one collision must give
/// E' ~ Exp(1). Tolerances: 4 standard errors for mean (1) and second moment (2); KS below
/// the 1% critical value 1.63/√n plus the conditioning bound P(E < 1e-3) ≤ 1e-3.
/// Measured (κ = 30, n = 2000, seed 5): mean 0.978 ± 0.021, m2 1.876 ± 0.093, KS 0.0151.
#[test]
fn canonical_density_is_stationary_direct() {
    check_canonical(30.0, 2000, 5);
}

/// Heavier version at κ = 100 (≈ 20 s on 2 cores), run with
/// `cargo test --release -p haff-rods --test stochastic -- --ignored canonical_kappa100`.
/// Measured (n = 8000, seed 11): mean 0.990 ± 0.011, m2 1.984 ± 0.050, KS 0.0144.
#[test]
#[ignore]
fn canonical_kappa100() {
    check_canonical(100.0, 8000, 11);
}

fn check_canonical(kappa: f64, n: usize, seed: u64) {
    let pairs = canonical_step(0.6173, kappa, n, seed, 1e-3).unwrap();
    let e1: Vec<f64> = pairs.iter().map(|p| p.1).collect();
    let e2: Vec<f64> = e1.iter().map(|x| x * x).collect();
    let (m1, se1) = mean_se(&e1);
    let (m2, se2) = mean_se(&e2);
    let ks = ks_exponential(&e1);
    let crit = 1.63 / (n as f64).sqrt() + 1e-3;
    println!("kappa {kappa}: E' mean {m1:.4} +- {se1:.4}, m2 {m2:.4} +- {se2:.4}, KS {ks:.4} (< {crit:.4})");
    assert!((m1 - 1.0).abs() < 4.0 * se1);
    assert!((m2 - 2.0).abs() < 4.0 * se2);
    assert!(ks < crit);
}

/// Critical value c(α) of the one-sample Kolmogorov–Smirnov statistic √n·D at
/// α = 1e-3 (asymptotic Kolmogorov distribution: P(K > c) = 2 Σ (−1)^(k−1) e^(−2k²c²)).
const KS_C_1E3: f64 = 1.9495;

/// Quantile function (linear in u) of one row of a [`Table`], as `Table::sample` at a
/// grid ratio.
fn row_quantile(q: &[f64], u: f64) -> f64 {
    let l = q.len() - 1;
    let x = u * l as f64;
    let k = (x as usize).min(l - 1);
    q[k] + (x - k as f64) * (q[k + 1] - q[k])
}

/// The quantile rule of `Table::build` (order statistics interpolated linearly; the end
/// points such that the extreme bins hold the mean of their samples), repeated here to
/// rebuild a row from a resample.
fn row_from_sample(mut e2: Vec<f64>, levels: usize) -> Vec<f64> {
    e2.sort_by(f64::total_cmp);
    let n = e2.len();
    let mut q: Vec<f64> = (0..=levels)
        .map(|k| {
            let x = (n - 1) as f64 * k as f64 / levels as f64;
            let j = (x as usize).min(n - 2);
            e2[j] + (x - j as f64) * (e2[j + 1] - e2[j])
        })
        .collect();
    let top = &e2[(n * (levels - 1) / levels).min(n - 1)..];
    q[levels] =
        (2.0 * top.iter().sum::<f64>() / top.len() as f64 - q[levels - 1]).max(q[levels - 1]);
    let bot = &e2[..n.div_ceil(levels).max(1)];
    q[0] = (2.0 * bot.iter().sum::<f64>() / bot.len() as f64 - q[1]).clamp(0.0, q[1]);
    q
}

/// Parametric bootstrap of the table's sampling noise: every row rebuilt from
/// `realizations` draws of that row's own distribution.
fn resampled(table: &Table, seed: u64) -> Table {
    let mut rng = realization_rng(seed, 7);
    let quantiles = table
        .quantiles
        .iter()
        .map(|q| {
            let e2 = (0..table.realizations)
                .map(|_| row_quantile(q, rng.random()))
                .collect();
            row_from_sample(e2, table.levels)
        })
        .collect();
    Table {
        quantiles,
        ..table.clone()
    }
}

/// What the table tests measure with one table: the chain Eq. (6) driven by the table
/// (`steps` collisions from E = T, the first 1000 dropped; mean, second moment, and every
/// 20th state, sorted, for the KS distance: lag-20 autocorrelation 0.8^20 ≈ 0.01) and the
/// one-step map of the canonical density, E ~ Exp(1) → E' = ε²E (`steps` draws; mean,
/// sorted sample).
struct TableRun {
    m1: f64,
    m2: f64,
    one: f64,
    chain: Vec<f64>,
    step: Vec<f64>,
}

fn table_run(table: &Table, seed: u64, steps: usize) -> TableRun {
    let mut rng = realization_rng(seed, 1);
    let ch = run_chain(1.0, steps, |r| table.sample(r, rng.random()));
    let (m1, m2) = moments(&ch[1000..]);
    let mut chain: Vec<f64> = ch[1000..].iter().step_by(20).copied().collect();
    chain.sort_by(f64::total_cmp);
    let mut step: Vec<f64> = (0..steps)
        .map(|_| {
            let e = -(-rng.random::<f64>()).ln_1p();
            table.sample(e, rng.random()) * e
        })
        .collect();
    let one = step.iter().sum::<f64>() / steps as f64;
    step.sort_by(f64::total_cmp);
    TableRun {
        m1,
        m2,
        one,
        chain,
        step,
    }
}

/// Empirical distribution function of a sorted sample at x.
fn ecdf(sorted: &[f64], x: f64) -> f64 {
    sorted.partition_point(|&v| v <= x) as f64 / sorted.len() as f64
}

/// The Markov chain Eq. (6) driven by a [`Table`] (κ = 30, r = 0.01..100, 13 ratios, 1200
/// realizations per ratio; ≈ 16 s on 2 cores, 12 s of it building the table) has the
/// stationary density exp(−E/T): mean 1, second moment 2, KS distance from Exp(1); and
/// so has one step of the tabulated kernel from the canonical density. See
/// [`check_table`] for the tolerances. With the former 300 realizations the bootstrap
/// gives ± 0.069 for the chain mean (5 sd = 0.35, looser than the former hard-coded
/// 0.25); with 1200 every bound is tighter than the former ones. Measured (seed 4): chain mean
/// 1.0038 (tolerance 0.19), m2 2.0016 (0.63), KS 0.0049 (critical 0.078); one-step mean
/// 0.9988 (0.039), KS 0.0029 (0.0195). Over table seeds 1..6 the largest deviations were
/// 2.0 (chain mean, seed 3), 2.6 (m2, seed 5) and 2.5 (one-step mean, seed 5) replica
/// standard deviations; over seeds 1..12 the one-step mean scattered by 0.0090 against a
/// bootstrap standard deviation of 0.0076, consistent within the scatter's own error.
#[test]
fn table_chain_is_exponential() {
    let ratios = Table::log_grid(0.01, 100.0, 13);
    let table = Table::build(0.6173, 30.0, &ratios, 1200, 4).unwrap();
    check_table(&table);
}

/// κ = 100 table, r = 0.01..1000 (16 ratios), 2000 realizations per ratio (≈ 80 s on 2
/// cores): `cargo test --release -p haff-rods --test stochastic -- --ignored table_kappa100`.
/// Tolerances as in [`check_table`]. Measured (seed 21): chain mean 0.9325
/// (± 0.0300), m2 1.788 (± 0.105), KS 0.038 (critical 0.052); one-step mean 0.9849
/// (± 0.0065), KS 0.0108 (critical 0.0136).
#[test]
#[ignore]
fn table_kappa100() {
    let ratios = Table::log_grid(0.01, 1000.0, 16);
    let table = Table::build(0.6173, 100.0, &ratios, 2000, 21).unwrap();
    check_table(&table);
}

/// The chain (2·10⁶ steps) and the one-step map (2·10⁶ draws) of `table` against
/// Exp(1). Their deviations from Exp(1) are dominated by the table's own sampling noise
/// (finitely many realizations per ratio; the chain amplifies kernel errors ~5×, its
/// lag-1 autocorrelation being ≈ 0.8), not by the Monte Carlo error of the run (chain
/// mean ± 0.002). That noise is measured by a parametric bootstrap: B = 40 tables whose
/// rows are rebuilt from as many draws of each row's own distribution ([`resampled`]),
/// each run with 4·10⁵ steps and draws (so each replica also carries more Monte Carlo
/// noise than the main run: the spread over replicas bounds both). With s the standard
/// deviation over the replicas:
/// - mean, second moment, one-step mean: |x − exact| < 5 s; with s estimated from 40
///   replicas this is a t test with 39 degrees of freedom, P(|t| > 5) = 1.3e-5;
/// - KS distance D of the thinned chain and of the one-step sample from Exp(1): D <
///   c(α)/√n_eff at α = 1e-3, with n_eff = 1/(4 s_F²), s_F the largest replica standard
///   deviation of the empirical distribution function at the 19 points F = k/20 (a
///   Brownian bridge of n samples has the largest standard deviation 1/(2√n)). The
///   table noise of F is smoother than a Brownian bridge (few degrees of freedom), so
///   this critical value is approximate; over the replicas D* = sup|F* − F| stayed far
///   below it (at 300 realizations: largest of 30 replicas 0.096, critical 0.14).
///
/// Not covered by the bootstrap: the interpolation in ln r and the clamping below
/// r = 0.01, systematic errors of the table; over six 300-realization tables the
/// one-step mean was 0.9956 ± 0.0043, so they are below the noise.
fn check_table(table: &Table) {
    use rayon::prelude::*;
    let json = serde_json::to_string(table).unwrap();
    assert_eq!(&serde_json::from_str::<Table>(&json).unwrap(), table);
    let main = table_run(table, 1, 2_000_000);
    let replicas: Vec<TableRun> = (0..40u64)
        .into_par_iter()
        .map(|b| table_run(&resampled(table, b), 100 + b, 400_000))
        .collect();
    let spread = |f: &dyn Fn(&TableRun) -> f64| {
        let x: Vec<f64> = replicas.iter().map(f).collect();
        let m = x.iter().sum::<f64>() / x.len() as f64;
        (x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (x.len() - 1) as f64).sqrt()
    };
    let (s1, s2, s_one) = (spread(&|r| r.m1), spread(&|r| r.m2), spread(&|r| r.one));
    let points: Vec<f64> = (1..20).map(|k| -(1.0 - k as f64 / 20.0).ln()).collect();
    let ks_critical = |sample: &dyn Fn(&TableRun) -> &Vec<f64>| {
        let s_f = points
            .iter()
            .map(|&x| spread(&|r| ecdf(sample(r), x)))
            .fold(0.0, f64::max);
        let n_eff = 1.0 / (4.0 * s_f * s_f);
        KS_C_1E3 / n_eff.sqrt()
    };
    let (crit_chain, crit_step) = (ks_critical(&|r| &r.chain), ks_critical(&|r| &r.step));
    let (ks_chain, ks_step) = (ks_exponential(&main.chain), ks_exponential(&main.step));
    println!(
        "table chain: mean {:.4} (± {s1:.4}) m2 {:.4} (± {s2:.4}) KS {ks_chain:.4} \
         (< {crit_chain:.4}); one step: mean {:.4} (± {s_one:.4}) KS {ks_step:.4} \
         (< {crit_step:.4})",
        main.m1, main.m2, main.one
    );
    assert!((main.m1 - 1.0).abs() < 5.0 * s1, "chain mean {}", main.m1);
    assert!((main.m2 - 2.0).abs() < 5.0 * s2, "chain m2 {}", main.m2);
    assert!(
        (main.one - 1.0).abs() < 5.0 * s_one,
        "one-step mean {}",
        main.one
    );
    assert!(ks_chain < crit_chain, "chain KS {ks_chain}");
    assert!(ks_step < crit_step, "one-step KS {ks_step}");
}

/// Sample autocorrelation of `x` at lag `k`.
fn autocorrelation(x: &[f64], k: usize) -> f64 {
    let n = x.len();
    let m = x.iter().sum::<f64>() / n as f64;
    let var = x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / n as f64;
    (0..n - k).map(|i| (x[i] - m) * (x[i + k] - m)).sum::<f64>() / (n as f64 * var)
}

/// The chain Eq. (6) with a direct solve of Eq. (3) at every collision (κ = 100; E/T
/// floored at 1e-4 for the solve, bias ≤ P(E < 1e-4) = 1e-4 per step), 2 chains of 30000
/// steps (≈ 3 min on 2 cores):
/// `cargo test --release -p haff-rods --test stochastic -- --ignored direct_chain`.
/// Tolerances: mean and second moment within 4 batch-mean standard errors (batches of 100
/// steps ≫ the correlation time ≈ 8; normal, P = 6e-5 each). KS: the chains are thinned
/// to every L-th state, L the first lag at which the autocorrelations of E and of the
/// indicator E ≤ ln 2 (the median) are both below 0.05 in magnitude; for a geometrically
/// decaying correlation the thinned sample then has τ_int ≤ 1.05/0.95, so
/// n_eff = n_thinned/1.105, and D < c(α)/√n_eff at α = 1e-3, plus 1e-3 for the floor
/// (a kernel changed on a set of probability 1e-4 moves the stationary law by at most
/// 1e-4 times the ~10 steps the chain needs to forget it).
/// Measured: mean 0.9846 ± 0.0120, m2 1.9833 ± 0.0456 (lag-1 autocorrelation 0.78);
/// thinned every 15th state: KS 0.0213 (critical 0.0334, n_eff 3618).
/// Open discrepancy: with chain seeds 200, 201 instead of 100, 101 the test fails
/// (mean 0.9462 ± 0.0116, −4.6 se; m2 1.8185 ± 0.0405; KS 0.0342 > 0.0334). Every κ = 100
/// run leans the same way (`canonical_kappa100` one step 0.990 ± 0.011, `table_kappa100`
/// one step 0.9849 ± 0.0065 and chain 0.9325 ± 0.0300): a ≈ 1 % deficit of one step at
/// κ = 100, amplified ~5× by the chain. It is not the solver resolution: default minus
/// (h/2, 2× noise points) = −0.0004 ± 0.0003 in the one-step mean (4000 paired draws).
#[test]
#[ignore]
fn direct_chain() {
    use rayon::prelude::*;
    let n = 30_000;
    let chains: Vec<Vec<f64>> = (0..2u64)
        .into_par_iter()
        .map(|c| {
            let mut rng = realization_rng(100 + c, 0);
            let ch = run_chain(1.0, n, |r| {
                let s = solve(0.6173, 100.0, r.max(1e-4), &Resolution::default(), &mut rng);
                s.unwrap().eps.powi(2)
            });
            ch[20..].to_vec()
        })
        .collect();
    let all: Vec<f64> = chains.iter().flatten().copied().collect();
    let batch = |f: &dyn Fn(f64) -> f64| {
        let b: Vec<f64> = chains
            .iter()
            .flat_map(|c| c.chunks_exact(100))
            .map(|c| c.iter().map(|&x| f(x)).sum::<f64>() / c.len() as f64)
            .collect();
        mean_se(&b)
    };
    let (m1, se1) = batch(&|x| x);
    let (m2, se2) = batch(&|x| x * x);
    let median = 2f64.ln();
    let lag = (1..200)
        .find(|&k| {
            chains.iter().all(|c| {
                let ind: Vec<f64> = c
                    .iter()
                    .map(|&x| f64::from(u8::from(x <= median)))
                    .collect();
                autocorrelation(c, k).abs() < 0.05 && autocorrelation(&ind, k).abs() < 0.05
            })
        })
        .expect("the chains decorrelate within 200 steps");
    let thinned: Vec<f64> = chains
        .iter()
        .flat_map(|c| c.iter().step_by(lag).copied())
        .collect();
    let n_eff = thinned.len() as f64 / 1.105;
    let (ks, critical) = (ks_exponential(&thinned), KS_C_1E3 / n_eff.sqrt() + 1e-3);
    println!(
        "direct chain: mean {m1:.4} +- {se1:.4} m2 {m2:.4} +- {se2:.4}; lag-1 autocorrelation \
         {:.3}; thinned every {lag}: KS {ks:.4} (< {critical:.4}, n_eff {n_eff:.0}); KS of all \
         states {:.4}",
        autocorrelation(&chains[0], 1),
        ks_exponential(&all)
    );
    assert!((m1 - 1.0).abs() < 4.0 * se1);
    assert!((m2 - 2.0).abs() < 4.0 * se2);
    assert!(ks < critical, "KS {ks}");
}
