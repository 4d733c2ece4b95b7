//! Rod-chain MD of Eq. (2) of Giese: conservation laws, exactness of free flight,
//! reversibility, the deterministic limit of Eq. (3) and equipartition.
//! Run: `cargo test --release -p haff-rods --test chain` (heavier cases: `-- --ignored`).

use rand::{Rng, SeedableRng};
use rods::chain::*;
use rods::deterministic::eps_numeric;

const GAMMA: f64 = 0.6173;

fn two(modes: usize, kappa: f64, c_h: f64) -> TwoRodSetup {
    TwoRodSetup {
        gamma: GAMMA,
        kappa,
        modes,
        gap: 1.0,
        c_h,
    }
}

/// N rods, lengths uniform in [0.5, 1.5], free gaps 1, velocities uniform in [−1, 1].
fn ring(n: usize, modes: usize, alpha: f64, c_h: f64, seed: u64, global_step: bool) -> Chain {
    let mut rng = rand_pcg::Pcg64::seed_from_u64(seed);
    let lengths: Vec<f64> = (0..n).map(|_| rng.random_range(0.5..1.5)).collect();
    let gap = 1.0;
    let mut positions = vec![0.0];
    for i in 1..n {
        positions.push(positions[i - 1] + 0.5 * (lengths[i - 1] + lengths[i]) + gap);
    }
    let perimeter = lengths.iter().sum::<f64>() + n as f64 * gap;
    let velocities: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
    Chain::new(ChainConfig {
        lengths,
        modes,
        alpha,
        b: 0.5 / (alpha * alpha),
        c: 1.0,
        rho: 1.0,
        perimeter,
        positions,
        velocities,
        c_h,
        global_step,
    })
    .unwrap()
}

fn mean(x: &[f64]) -> f64 {
    x.iter().sum::<f64>() / x.len() as f64
}

/// Mean and its standard error from `blocks` block means (blocks longer than the
/// correlation time, so the block means are ~independent).
fn block_stats(x: &[f64], blocks: usize) -> (f64, f64) {
    let means: Vec<f64> = x.chunks(x.len() / blocks).take(blocks).map(mean).collect();
    let m = mean(&means);
    let var = means.iter().map(|b| (b - m).powi(2)).sum::<f64>() / (blocks - 1) as f64;
    (m, (var / blocks as f64).sqrt())
}

/// Time-weighted block means of E_tr (each collision carries ∫E_tr dt over the time
/// to the next collision): mean of the block ratios and its standard error.
fn time_block_stats(recs: &[TwoRodRecord], blocks: usize) -> (f64, f64) {
    let ratios: Vec<f64> = recs
        .chunks(recs.len() / blocks)
        .take(blocks)
        .map(|b| {
            b.iter().map(|r| r.etr_integral).sum::<f64>() / b.iter().map(|r| r.span).sum::<f64>()
        })
        .collect();
    let m = mean(&ratios);
    let var = ratios.iter().map(|b| (b - m).powi(2)).sum::<f64>() / (blocks - 1) as f64;
    (m, (var / blocks as f64).sqrt())
}

#[test]
fn energy_two_rods_1e4_collisions() {
    // Measured: drift 3.3e-10 (c_h = 0.25), 2806 fine steps per collision.
    let run = run_two_rods(&two(8, 100.0, 0.25), 10_000, 0).unwrap();
    println!(
        "two rods: drift {:.3e}, steps/coll {}",
        run.energy_drift,
        run.stats.fine_steps / 10_000
    );
    assert!(run.energy_drift < 1e-8, "drift {}", run.energy_drift);
}

#[test]
fn energy_and_momentum_ring_1e4_collisions() {
    // Ten rods of unequal lengths (dense: up to 5 rods in one contact cluster).
    // Measured: drift 2.8e-11, |ΔP| 6.4e-14.
    let mut c = ring(10, 8, 100.0, 0.25, 7, true);
    let (e0, p0) = (c.energy(), c.momentum());
    let mut recs = c.run_collisions(10_000);
    assert_eq!(recs.len(), 10_000);
    // H equals the conserved modified Hamiltonian only with no contact open.
    while c.open_episodes() > 0 {
        recs.extend(c.run_collisions(1));
    }
    assert_eq!(c.collisions(), recs.len());
    let de = (c.energy() - e0).abs() / e0;
    let dp = (c.momentum() - p0).abs();
    println!(
        "ring: drift {de:.3e}, dP {dp:.3e}, steps/coll {}",
        c.stats().fine_steps / 10_000
    );
    assert!(de < 1e-8, "drift {de}");
    assert!(dp < 1e-11, "momentum change {dp}");
    // Every contact took part (the bookkeeping covers the wrap-around contact).
    for k in 0..10 {
        assert!(
            recs.iter().any(|r| r.contact == k),
            "contact {k} never collided"
        );
    }
}

#[test]
fn free_flight_is_exact_and_reversible() {
    // Rods moving apart never touch within t = 3: the state must be the analytic one.
    let mut c = Chain::new(ChainConfig {
        lengths: vec![1.0, 0.7, 1.3],
        modes: 6,
        alpha: 50.0,
        b: 1e-3,
        c: 1.0,
        rho: 1.0,
        perimeter: 30.0,
        positions: vec![0.0, 10.0, 20.0],
        velocities: vec![-0.1, 0.0, 0.1],
        c_h: 0.25,
        global_step: false,
    })
    .unwrap();
    c.set_mode(1, 3, 0.01, 0.02).unwrap();
    let (m, w) = (0.7, 3.0 * std::f64::consts::PI / 0.7);
    let t = 3.0;
    assert!(c.run_until(t).is_empty());
    let (q, p) = c.mode(1, 3);
    let (s, co) = (w * t).sin_cos();
    let q_exact = 0.01 * co + 0.02 / (m * w) * s;
    let p_exact = 0.02 * co - 0.01 * m * w * s;
    assert!(
        (q - q_exact).abs() < 1e-15 && (p - p_exact).abs() < 1e-14,
        "{q} {q_exact} {p} {p_exact}"
    );
    assert!((c.positions()[2] - 20.3).abs() < 1e-14);
    c.reverse_momenta().unwrap();
    c.run_until(2.0 * t);
    let (q, p) = c.mode(1, 3);
    assert!(
        (q - 0.01).abs() < 1e-15 && (p + 0.02).abs() < 1e-15,
        "{q} {p}"
    );
    assert!((c.positions()[0]).abs() < 1e-14 && (c.positions()[2] - 20.0).abs() < 1e-14);
}

#[test]
fn collisions_are_time_reversible() {
    // Strang splitting is symmetric and episodes live on the global grid t = k h
    // (h a power of two), so forward-flip-forward retraces the path through
    // collisions.
    let setup = two(6, 100.0, 0.25);
    let start = || {
        let mut c = setup.chain().unwrap();
        c.thermalize_modes(0.01, &mut rand_pcg::Pcg64::seed_from_u64(3))
            .unwrap();
        c
    };
    // First t = 4j ≥ 24 (a grid point for every power-of-two h ≤ 4) with no open episode.
    let t = (6..40)
        .map(|j| 4.0 * j as f64)
        .find(|&t| {
            let mut c = start();
            c.run_until(t);
            c.open_episodes() == 0
        })
        .unwrap();
    let mut c = start();
    let (x0, v0) = (c.positions(), c.velocities());
    let m0: Vec<(f64, f64)> = (1..=6).map(|nu| c.mode(0, nu)).collect();
    let n_fwd = c.run_until(t).len();
    assert!(n_fwd >= 4, "only {n_fwd} episodes");
    c.reverse_momenta().unwrap();
    let n_back = c.run_until(2.0 * t).len();
    c.reverse_momenta().unwrap();
    let (x1, v1) = (c.positions(), c.velocities());
    let m1: Vec<(f64, f64)> = (1..=6).map(|nu| c.mode(0, nu)).collect();
    let mut err: f64 = 0.0;
    for i in 0..2 {
        err = err.max((x1[i] - x0[i]).abs()).max((v1[i] - v0[i]).abs());
    }
    for (a, b) in m0.iter().zip(&m1) {
        err = err.max((a.0 - b.0).abs() * 100.0).max((a.1 - b.1).abs());
    }
    println!("t = {t}: episodes {n_fwd}/{n_back}, max deviation {err:.3e}");
    assert_eq!(n_fwd, n_back);
    // Measured 3.7e-10 after 8 episodes (rounding, amplified by the chaotic dynamics).
    assert!(err < 1e-8, "{err}");
}

/// ε of the first impact of cold rods with M modes (κ = 100, length ratio γ, step
/// constant c_h).
fn first_eps(gamma: f64, modes: usize, c_h: f64) -> f64 {
    let setup = TwoRodSetup {
        gamma,
        kappa: 100.0,
        modes,
        gap: 1.0,
        c_h,
    };
    run_two_rods(&setup, 1, 0).unwrap().records[0].eps
}

/// The first impact of the MD against Eq. (3) of Giese with T_bath = 0 (`eps_numeric`, a
/// different method: the delay equation of the continuum rods), which is the limit
/// h → 0, M → ∞ of the MD. Both limits are taken by Richardson extrapolation at known
/// orders: the Strang splitting has an error O(h²) (measured: the difference falls by 4.1
/// when c_h halves), so e(M) = (4 ε(c_h/2) − ε(c_h))/3 with c_h = 0.125; the mode
/// truncation has an error a/M + O(1/M²), so L(M) = 2 e(2M) − e(M). Prints the M
/// ladder e(M) − ε_det and the extrapolants L(M) − ε_det, and asserts:
/// - |e(M) − ε_det| falls monotonically with M;
/// - the last extrapolant equals ε_det within the a-posteriori bound of a sequence that
///   converges at least geometrically with ratio 1/2 (measured ratio 4–8):
///   |L_last − ε_det| ≤ |L_last − L_previous| + the error of ε_det (its change when the
///   step of `eps_numeric` halves).
fn check_first_impact_limit(gamma: f64, ms: &[usize]) {
    let (det, det_fine) = (
        eps_numeric(gamma, 100.0, 5e-4),
        eps_numeric(gamma, 100.0, 2.5e-4),
    );
    let e: Vec<f64> = ms
        .iter()
        .map(|&m| {
            let (coarse, fine) = (first_eps(gamma, m, 0.125), first_eps(gamma, m, 0.0625));
            (4.0 * fine - coarse) / 3.0 - det_fine
        })
        .collect();
    let l: Vec<f64> = e.windows(2).map(|w| 2.0 * w[1] - w[0]).collect();
    for (m, d) in ms.iter().zip(&e) {
        println!(
            "gamma {gamma} M = {m}: eps - eps_det = {d:.7} (M·diff {:.4})",
            *m as f64 * d
        );
    }
    let shown: Vec<String> = l.iter().map(|x| format!("{x:.2e}")).collect();
    println!("gamma {gamma}: extrapolated limits - eps_det = {shown:?}");
    for w in e.windows(2) {
        assert!(w[1].abs() < w[0].abs(), "gamma {gamma}: {e:?}");
    }
    let (last, previous) = (l[l.len() - 1], l[l.len() - 2]);
    let bound = (last - previous).abs() + (det - det_fine).abs();
    assert!(
        last.abs() <= bound,
        "gamma {gamma}: limit - eps_det = {last:.3e}, bound {bound:.3e}"
    );
}

#[test]
fn first_collision_converges_to_deterministic_limit() {
    // Eq. (3) with T_bath = 0 is the M → ∞ limit. Measured (c_h → 0): ε_M − ε_det =
    // −0.00791, −0.00397, −0.00199, −0.00100, −0.00050 for M = 25 … 400 (M·Δε ≈ −0.198 to
    // −0.200: the truncation error is ≈ −0.2/M); extrapolants L − ε_det = −2.9e-5,
    // −1.5e-5, −4.0e-6, −7.3e-7 (bound 3.3e-6). At c_h = 0.25 the step error grows with M
    // (M·Δε = −0.224 at M = 200 against −0.201 at c_h = 0.0625).
    check_first_impact_limit(GAMMA, &[25, 50, 100, 200, 400]);
}

/// Equipartition of two rods with `m` modes (kappa = 1000, hard core), `n` collisions after
/// `skip`: the microcanonical predictions per collision E0/(2M+1), in time E0/(4M+1), and
/// eta_eq, each within 4 standard errors of 10 block means.
fn check_equipartition(m: usize, skip: usize, n: usize) {
    let run = run_two_rods(&two(m, 1000.0, 0.25), skip + n, skip).unwrap();
    let recs = &run.records[skip..];
    let e: Vec<f64> = recs.iter().map(|r| r.e_tr).collect();
    let eta: Vec<f64> = recs.iter().map(|r| r.eta).collect();
    let (me, se) = block_stats(&e, 10);
    let (mh, sh) = block_stats(&eta, 10);
    let e_eq = 1.0 / (2.0 * m as f64 + 1.0);
    let h_eq = eta_equilibrium(m);
    let t_avg = run.time_mean_etr();
    let (tb, st) = time_block_stats(recs, 10);
    println!("time-weighted block mean {tb:.4} ± {st:.4}");
    println!("E_tr: {me:.4} ± {se:.4} vs {e_eq:.4}; eta: {mh:.4} ± {sh:.4} vs {h_eq:.4}");
    println!(
        "time mean E_tr {t_avg:.4} (free flights only {:.4}) vs E0/(4M+1) = {:.4}; contact fraction {:.3}",
        run.free_etr_integral / run.free_time,
        1.0 / (4.0 * m as f64 + 1.0),
        run.contact_time / (run.contact_time + run.free_time)
    );
    assert!((me - e_eq).abs() < 4.0 * se, "{me} ± {se} vs {e_eq}");
    assert!((mh - h_eq).abs() < 4.0 * sh, "{mh} ± {sh} vs {h_eq}");
    let t_eq = 1.0 / (4.0 * m as f64 + 1.0);
    assert!((tb - t_eq).abs() < 4.0 * st, "{tb} ± {st} vs {t_eq}");
    assert!((t_avg - tb).abs() < 1e-3);
    assert!(run.energy_drift < 1e-8);
}

#[test]
fn equipartition_two_rods_small_m() {
    // Blocks of 1200 collisions, much longer than the ~10-collision relaxation. Measured:
    // E_tr 0.1130 ± 0.0022 vs 0.1111, η 0.1747 ± 0.0005 vs 0.1739, time mean
    // 0.0621 ± 0.0015 vs 0.0588 (2.2 σ).
    check_equipartition(4, 200, 12_000);
}

#[test]
fn eta_equilibrium_values() {
    // Exact Dirichlet mean vs Monte Carlo of normalized exponentials, and Giese's
    // large-M form 0.423/ln(2M).
    let mut rng = rand_pcg::Pcg64::seed_from_u64(1);
    let m = 3;
    let n = 200_000;
    let mut acc = 0.0;
    for _ in 0..n {
        let x: Vec<f64> = (0..2 * m).map(|_| -rng.random::<f64>().ln()).collect();
        let s: f64 = x.iter().sum();
        let w: Vec<f64> = x.iter().map(|v| v / s).collect();
        acc += spectral_entropy(&w);
    }
    let mc = acc / n as f64;
    assert!(
        (mc - eta_equilibrium(m)).abs() < 1e-3,
        "{mc} {}",
        eta_equilibrium(m)
    );
    let big = 1000;
    let giese = 0.4228 / (2.0 * big as f64).ln();
    assert!((eta_equilibrium(big) - giese).abs() < 1e-3);
}

#[test]
fn invalid_parameters_are_rejected() {
    let ok = ChainConfig {
        lengths: vec![1.0, 1.0],
        modes: 4,
        alpha: 100.0,
        b: 1e-4,
        c: 1.0,
        rho: 1.0,
        perimeter: 6.0,
        positions: vec![0.0, 3.0],
        velocities: vec![1.0, -1.0],
        c_h: 0.25,
        global_step: true,
    };
    assert!(Chain::new(ok.clone()).is_ok());
    let cases: Vec<(ChainConfig, &str)> = vec![
        (
            ChainConfig {
                lengths: vec![1.0],
                positions: vec![0.0],
                velocities: vec![0.0],
                ..ok.clone()
            },
            "lengths",
        ),
        (
            ChainConfig {
                modes: 0,
                ..ok.clone()
            },
            "modes",
        ),
        (
            ChainConfig {
                alpha: -1.0,
                ..ok.clone()
            },
            "alpha",
        ),
        (
            ChainConfig {
                c_h: 2.0,
                ..ok.clone()
            },
            "c_h",
        ),
        (
            ChainConfig {
                positions: vec![0.0, 1.01],
                ..ok.clone()
            },
            "gap 0",
        ),
        (
            ChainConfig {
                perimeter: 4.0,
                ..ok.clone()
            },
            "gap 1",
        ),
    ];
    for (cfg, what) in cases {
        let err = Chain::new(cfg).unwrap_err().to_string();
        assert!(err.contains(what), "{err}");
    }
}

#[test]
#[ignore] // cargo test --release -p haff-rods --test chain -- --ignored --nocapture energy_vs_c_h
fn energy_vs_c_h() {
    for m in [8, 75] {
        let kappa = if m == 8 { 100.0 } else { 4000.0 };
        let n = if m == 8 { 2000 } else { 100 };
        for c_h in [0.0625, 0.125, 0.25, 0.5] {
            let run = run_two_rods(&two(m, kappa, c_h), n, 0).unwrap();
            let st = run.stats;
            println!(
                "M={m} kappa={kappa} c_h={c_h}: drift {:.2e} over {n}, steps/coll {}, checks/coll {}, ns/fine step {:.0}",
                run.energy_drift,
                st.fine_steps / n as u64,
                st.checks / n as u64,
                st.step_seconds * 1e9 / st.fine_steps as f64
            );
            // Measured: <= 2.8e-10 for c_h <= 0.25; 4.8e-6 (M = 8), 1.3e-5 (M = 75) at 0.5.
            // c_h = 0.5 is a documented measurement (the splitting's modified Hamiltonian
            // is far from H at that step; see the `rods::chain` module docs), not a
            // requirement: only the step constants in use (<= 0.25) must conserve energy.
            if c_h <= 0.25 {
                assert!(run.energy_drift < 1e-9, "c_h = {c_h}: {}", run.energy_drift);
            }
        }
    }
}

#[test]
#[ignore] // cargo test --release -p haff-rods --test chain -- --ignored --nocapture equipartition_m8
fn equipartition_m8() {
    // Measured: E_tr 0.0583 ± 0.0008 vs 0.0588, eta 0.1406 ± 0.0005 vs 0.1413, time mean
    // 0.0305 ± 0.0005 vs 0.0303.
    check_equipartition(8, 500, 20_000);
}
#[test]
fn simultaneous_collisions_in_different_places() {
    // Four equal rods, velocities +1, −1, +1, −1: contacts 0 and 2 close at the same
    // instant, and by symmetry must give identical episodes.
    let alpha = 100.0;
    let mut c = Chain::new(ChainConfig {
        lengths: vec![1.0; 4],
        modes: 6,
        alpha,
        b: 0.5 / (alpha * alpha),
        c: 1.0,
        rho: 1.0,
        perimeter: 8.0,
        positions: vec![0.0, 2.0, 4.0, 6.0],
        velocities: vec![1.0, -1.0, 1.0, -1.0],
        c_h: 0.25,
        global_step: false,
    })
    .unwrap();
    let e0 = c.energy();
    let recs = c.run_collisions(2);
    assert_eq!(recs.len(), 2);
    let (a, b) = (recs[0], recs[1]);
    assert_eq!([a.contact.min(b.contact), a.contact.max(b.contact)], [0, 2]);
    assert_eq!((a.t_start, a.t_end), (b.t_start, b.t_end));
    assert!((a.eps() - b.eps()).abs() < 1e-12, "{} {}", a.eps(), b.eps());
    // Equal rods: ε = 1 − O(1/κ) at first impact (γ = 1 in Giese's closed form).
    println!("equal rods, first impact eps = {}", a.eps());
    assert!(a.eps() > 0.9 && a.eps() <= 1.0);
    assert!(c.open_episodes() == 0 && (c.energy() - e0).abs() / e0 < 1e-10);
}

#[test]
fn two_rods_on_a_tight_ring() {
    // N = 2 with short free gaps: both contacts (which join the same two rods) are
    // often active together, so the cluster closes into a ring.
    let alpha = 200.0;
    let mut c = Chain::new(ChainConfig {
        lengths: vec![1.0, 0.6],
        modes: 5,
        alpha,
        b: 0.5 / (alpha * alpha),
        c: 1.0,
        rho: 1.0,
        perimeter: 1.6 + 2.0 * 0.3,
        positions: vec![0.0, 0.8 + 0.3],
        velocities: vec![0.6, -1.0],
        c_h: 0.25,
        global_step: true,
    })
    .unwrap();
    let (e0, p0) = (c.energy(), c.momentum());
    let mut recs = c.run_collisions(2000);
    while c.open_episodes() > 0 {
        recs.extend(c.run_collisions(1));
    }
    let both = recs
        .windows(2)
        .filter(|w| w[1].t_start < w[0].t_end && w[0].contact != w[1].contact)
        .count();
    let de = (c.energy() - e0).abs() / e0;
    println!(
        "tight ring: {} episodes, {both} overlapping pairs, drift {de:.2e}",
        recs.len()
    );
    assert!(
        both > 0,
        "no overlapping episodes: the test does not exercise the ring closure"
    );
    assert!(de < 1e-8 && (c.momentum() - p0).abs() < 1e-12);
}

#[test]
#[ignore] // cargo test --release -p haff-rods --test chain -- --ignored --nocapture ring_energy
fn ring_energy() {
    for (n, m, global) in [
        (10, 8, true),
        (10, 8, false),
        (100, 4, true),
        (100, 4, false),
    ] {
        let mut c = ring(n, m, 100.0, 0.25, 7, global);
        let e0 = c.energy();
        let clock = std::time::Instant::now();
        let mut k = c.run_collisions(10_000).len();
        // Wait for a moment with no open contact (H = modified Hamiltonian); a dense
        // ring of 100 rods may not have one soon, then H is off by O(c_h²) contact energy.
        for _ in 0..2000 {
            if c.open_episodes() == 0 {
                break;
            }
            k += c.run_collisions(1).len();
        }
        let secs = clock.elapsed().as_secs_f64();
        let st = c.stats();
        println!(
            "N={n} M={m} global={global}: drift {:.2e} (open {}), step changes {}, steps/coll {}, checks/coll {}, {:.0} us/coll",
            (c.energy() - e0).abs() / e0,
            c.open_episodes(),
            st.step_changes,
            st.fine_steps / k as u64,
            st.checks / k as u64,
            secs * 1e6 / k as f64
        );
        // Measured: global step 2.8e-11 (N = 10), 4.2e-10 (N = 100, 22 contacts open at the
        // end); per-cluster steps 1.6e-5 and 4.0e-5: changing h mid-contact shifts the
        // modified Hamiltonian (documented limitation of `global_step: false`, printed
        // above as a measurement, not asserted). The global step must conserve energy.
        if global {
            assert!((c.energy() - e0).abs() < 1e-8 * e0);
        }
    }
}

#[test]
#[ignore] // cargo test --release -p haff-rods --test chain -- --ignored --nocapture other_gammas
fn other_gammas() {
    // First impact vs Eq. (3) at other length ratios, including γ = 0.3 where the closed
    // form fails, extrapolated as in `first_collision_converges_to_deterministic_limit`.
    // Measured (c_h → 0) M·(ε_M − ε_det) at M = 50/200: γ = 0.3: −0.261/−0.263,
    // γ = 0.9: −0.154/−0.153, γ = 2: −0.215/−0.216; extrapolants L − ε_det at the
    // finest level −1.7e-6, 6.4e-7, −9.0e-7 (bounds 6.5e-6, 1.4e-6, 3.8e-6). Energy
    // drift over 200 collisions ≤ 6.2e-11.
    for g in [0.3, 0.9, 2.0] {
        check_first_impact_limit(g, &[25, 50, 100, 200, 400]);
        // Energy over 200 collisions at the default step constant.
        for m in [50, 200] {
            let s = TwoRodSetup {
                gamma: g,
                kappa: 100.0,
                modes: m,
                gap: 1.0,
                c_h: 0.25,
            };
            let run = run_two_rods(&s, 200, 0).unwrap();
            println!("gamma {g} M {m}: drift {:.1e}", run.energy_drift);
            assert!(run.energy_drift < 1e-9);
        }
    }
}

#[test]
fn saved_chain_continues_bit_for_bit() {
    // Saved in the middle of the run with a contact episode open, loaded, and both
    // copies continued: the same trajectory to the last bit.
    let mut a = ring(10, 8, 100.0, 0.25, 7, true);
    a.run_collisions(300);
    while a.open_episodes() == 0 {
        a.run_collisions(1);
    }
    let text = serde_json::to_string(&a).unwrap();
    let mut b: Chain = serde_json::from_str(&text).unwrap();
    let (ra, rb) = (a.run_collisions(300), b.run_collisions(300));
    assert_eq!(ra, rb);
    assert_eq!(a.positions(), b.positions());
    assert_eq!(a.velocities(), b.velocities());
    assert_eq!(a.energy().to_bits(), b.energy().to_bits());
    assert_eq!(a.time().to_bits(), b.time().to_bits());
}

/// The chain engine run in pieces (`gas::Engine::run_paused`, paused every few impacts,
/// as the run driver cuts a run for its interruptions) ends where one `run_until` to the
/// same times ends: positions, velocities, energy and the impact count (which orders the
/// episodes of a run toward a time by their start) to the last bit.
#[test]
fn chain_engine_pieces_compose_to_one_run() {
    use gas::Engine;
    use rods::engine::ChainEngine;
    let targets = [40.0, 90.0, 150.0];
    let mut whole = ChainEngine::new(ring(12, 6, 100.0, 0.25, 9, true));
    let mut pieces = ChainEngine::new(ring(12, 6, 100.0, 0.25, 9, true));
    for &t in &targets {
        whole.run_until(t);
        let mut calls = 0;
        while pieces.time() < t {
            let pause = pieces.counters().collisions + 3;
            pieces.run_paused(t, u64::MAX, pause);
            calls += 1;
        }
        assert!(calls > 3, "the run was cut into pieces ({calls})");
        assert_eq!(whole.counters(), pieces.counters(), "t = {t}");
        assert_eq!(whole.time().to_bits(), pieces.time().to_bits());
        let (a, b) = (whole.chain(), pieces.chain());
        assert_eq!(a.positions(), b.positions());
        assert_eq!(a.velocities(), b.velocities());
        assert_eq!(a.energy().to_bits(), b.energy().to_bits());
    }
    assert!(whole.counters().collisions > 20);
}
