//! Giese, *Stochastic coefficient of restitution — a new approach to the dynamics of
//! granular media* (vibrating rods with internal modes): Figs. 1, 2 (two rods of the
//! Hamiltonian MD, `rods::chain`), Fig. 3 (p(eps^2) from realizations of Eq. (3),
//! `rods::stochastic`) and the deterministic limit of Eq. (3) against the paper's closed
//! form and the generalized one (`rods::deterministic`). See docs/giese.md. The two-rod
//! experiment of `haff rods two-rods` (any gamma, kappa and mode counts) is [`two_rods`],
//! which draws its curves as Figs. 1 and 2 do.

use super::{logspace, numerical, sig, Context, Entry, Outcome};
use rods::chain::{eta_within, run_two_rods, TwoRodRun, TwoRodSetup};
use rods::deterministic::{eps_closed_form, eps_closed_form_general, eps_numeric};
use rods::stochastic::{eps2_histogram, eps2_quantiles, eps2_summary, sample_eps, Resolution};
use sim::error::Result;
use sim::output::number;
use sim::plot::Figure;
use std::fmt::Write as _;

mod deterministic;
mod fig3;
pub mod two_rods;
use deterministic::deterministic;
use fig3::fig3;
use two_rods::{
    e_tr_curve, eta_curve, over_collisions, over_modes, rod_spectrum, running_curve, running_mean,
    spectrum_entries,
};

const PAPER: &str = "Giese";

/// The length ratio of Figs. 1, 2 and 3a, b.
const GAMMA: f64 = 0.6173;
/// The integrator's step constant of the two-rod runs (energy drift <= 1e-10).
const C_H: f64 = 0.125;

pub fn entries() -> Vec<Entry> {
    vec![
        Entry {
            id: "giese-fig1",
            paper: PAPER,
            item: "Fig. 1",
            shows: "two rods (M = 75 modes): E_tr after each collision and the mean modal spectrum",
            typical_seconds: 13.0,
            run: fig1,
        },
        Entry {
            id: "giese-fig2",
            paper: PAPER,
            item: "Fig. 2",
            shows: "spectral entropy eta over the collisions for M = 10..100 modes",
            typical_seconds: 2.5,
            run: fig2,
        },
        Entry {
            id: "giese-fig3",
            paper: PAPER,
            item: "Fig. 3 (a, b, c)",
            shows: "p(eps^2) and its distribution function from 8000 realizations of Eq. (3)",
            typical_seconds: 30.0,
            run: fig3,
        },
        Entry {
            id: "giese-deterministic",
            paper: PAPER,
            item: "Eq. (3), T_bath = 0",
            shows:
                "the deterministic eps(gamma) against the paper's and the generalized closed form",
            typical_seconds: 1.0,
            run: deterministic,
        },
    ]
}

fn rods_error(e: rods::Error) -> sim::Error {
    numerical("rods", e)
}

/// The two-rod experiment of Figs. 1 and 2 (gamma = [`GAMMA`], c_h = [`C_H`]).
fn experiment(kappa: f64, modes: usize, collisions: usize, transient: usize) -> Result<TwoRodRun> {
    let setup = TwoRodSetup {
        gamma: GAMMA,
        kappa,
        modes,
        gap: 1.0,
        c_h: C_H,
    };
    run_two_rods(&setup, collisions, transient).map_err(rods_error)
}

/// A horizontal line at `y` from `x0` to `x1`.
fn level(y: f64, x0: f64, x1: f64) -> Vec<(f64, f64)> {
    vec![(x0, y), (x1, y)]
}

/// A vertical line at `x` from `y0` to `y1`.
fn vertical(x: f64, y0: f64, y1: f64) -> Vec<(f64, f64)> {
    vec![(x, y0), (x, y1)]
}

/// The numbers joined as "a, b, c".
fn join(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| v.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

fn or_none(x: Option<usize>) -> f64 {
    x.map_or(f64::NAN, |c| c as f64)
}

fn fig1(ctx: &Context) -> Result<Outcome> {
    let id = "giese-fig1";
    // Full: the paper's run (kappa = alpha V0 l / c = 4000, M = 75, 500 + 4000 collisions).
    let (kappa, modes, collisions, transient) = if ctx.quick {
        (1000.0, 8, 3000, 300)
    } else {
        (4000.0, 75, 4500, 500)
    };
    let run = experiment(kappa, modes, collisions, transient)?;
    let s = run.summary();
    let (window, running) = running_mean(&run.records);
    let mut rows = Vec::new();
    for r in &run.records {
        let mean = running
            .iter()
            .find(|(k, _)| *k == r.collision)
            .map_or(String::new(), |(_, m)| number(*m));
        rows.push(vec![
            r.collision.to_string(),
            number(r.e_tr),
            number(r.eps),
            number(r.eta),
            mean,
            number(s.equipartition_per_collision),
        ]);
    }
    let mut files = vec![ctx.csv_cells(
        id,
        &[
            "collision",
            "e_tr",
            "eps",
            "eta",
            "e_tr_running_mean",
            "equipartition_per_collision",
        ],
        rows,
    )?];
    let spectrum = run.mean_spectrum();
    let flat = rods::chain::equipartition_mode_share(modes);
    let spectrum_rows: Vec<Vec<f64>> = spectrum_entries(&spectrum, modes)
        .map(|(rod, mode, w)| vec![rod as f64, mode as f64, w, flat])
        .collect();
    files.push(ctx.csv(
        &format!("{id}-spectrum"),
        &["rod", "mode", "w", "equipartition"],
        &spectrum_rows,
    )?);

    let fig = Figure::new(
        format!("Giese Fig. 1: two rods, gamma = {GAMMA}, kappa = {kappa}, M = {modes}"),
        "collision n",
        "E_tr / E0 after collision n",
    )
    .log(true, true)
    .noisy("E_tr after each collision", e_tr_curve(&run.records))
    .line(
        format!("mean of {window} collisions"),
        running_curve(&running),
    )
    .theory(
        "equipartition per collision E0/(2M+1)",
        over_collisions(s.equipartition_per_collision, collisions),
    );
    files.push(ctx.figure(id, &fig)?);
    let (rod1, rod2) = (
        rod_spectrum(&spectrum, modes, 0),
        rod_spectrum(&spectrum, modes, 1),
    );
    let fig = Figure::new(
        format!(
            "Giese Fig. 1 inset: mean modal energies, collisions {}..{collisions}",
            transient + 1
        ),
        "mode nu",
        "<w> = <E_nu / E_bath>",
    )
    .line("rod 1 (shorter)", rod1.clone())
    .line("rod 2 (longer)", rod2.clone())
    .theory("equipartition 1/(2M)", over_modes(flat, modes));
    files.push(ctx.figure(&format!("{id}-spectrum"), &fig)?);

    let w_min = spectrum.iter().copied().fold(f64::INFINITY, f64::min);
    let w_max = spectrum.iter().copied().fold(0.0, f64::max);
    let rod_mean = |v: &[(f64, f64)]| v.iter().map(|p| p.1).sum::<f64>() / v.len() as f64;
    let (m1, m2) = (rod_mean(&rod1), rod_mean(&rod2));
    let cooling = or_none(s.cooling_collision);
    // Standard error of the plateau from 10 block means (blocks much longer than the
    // relaxation).
    let tail: Vec<f64> = run.after_transient().iter().map(|r| r.e_tr).collect();
    let block = tail.len() / 10;
    let blocks: Vec<f64> = tail
        .chunks_exact(block.max(1))
        .map(|b| b.iter().sum::<f64>() / b.len() as f64)
        .collect();
    let nb = blocks.len() as f64;
    let block_mean = blocks.iter().sum::<f64>() / nb;
    let plateau_se =
        (blocks.iter().map(|b| (b - block_mean).powi(2)).sum::<f64>() / (nb - 1.0) / nb).sqrt();
    let sigmas = (s.mean_e_tr - s.equipartition_per_collision) / plateau_se;
    let md = format!(
        "# {id}: Giese Fig. 1 — two rods, E_tr after each collision and the modal spectrum\n\n\
         **Paper.** Two cold rods (gamma = 0.6173, alpha V0 l / c = 4000, N_modes = 75) collide \
         alternately at either end: E_tr decays over about 100 collisions and then fluctuates \
         around the equipartition value mu V0^2 / 2(2 N_modes + 1) (dashed); the inset, w \
         averaged over collisions 501..4500, is flat (\"homogeneous partition\").\n\n\
         **We get.** Hamiltonian MD of Eq. (2) (`rods::chain::run_two_rods`, kappa = {kappa}, \
         M = {modes}, {collisions} collisions, c_h = {C_H}; energy drift {}). Mean E_tr/E0 \
         per collision over collisions {}..{collisions}: **{}** +- {} (10 blocks) against \
         E0/(2M+1) = {} ({:+.1} standard errors); the time average {} against E0/(4M+1) = {}. The {window}-collision running mean first \
         falls below twice the plateau at collision {}. Spectrum: <w> between {} and {} for \
         all {} modes (1/(2M) = {}), rod means {} and {}. <eta> = {} (eta_eq = {}).\n\n\
         **Difference.** The plateau agrees with Giese's dashed value within {:.1} standard \
         errors. It is the per-collision mean, E0/(2M+1) exactly (collisions sample E_tr with weight ~ V, \
         docs/giese.md), while the time average is E0/(4M+1) — Giese's dashed value is the \
         former. The spectrum is flat (no periodic structure, which the paper reports only for \
         particular gamma). The cooling: our running mean stays within twice the plateau from \
         collision {} on, while Giese sees E_tr decay over \"approximately 100 collisions\", \
         a time he reads off a single noisy run by eye and does not define further.\n",
        sig(s.energy_drift),
        transient + 1,
        sig(s.mean_e_tr),
        sig(plateau_se),
        sig(s.equipartition_per_collision),
        sigmas,
        sig(s.time_mean_e_tr),
        sig(s.equipartition_time),
        cooling,
        sig(w_min),
        sig(w_max),
        2 * modes,
        sig(flat),
        sig(m1),
        sig(m2),
        sig(s.mean_eta),
        sig(s.eta_equilibrium),
        sigmas.abs().max(0.1),
        cooling,
    );
    files.push(ctx.markdown(id, &md)?);
    Ok(Outcome {
        summary: format!(
            "M = {modes}: <E_tr>/E0 = {} per collision (E0/(2M+1) = {}), time mean {} \
             (E0/(4M+1) = {}), spectrum {}..{} (1/2M = {})",
            sig(s.mean_e_tr),
            sig(s.equipartition_per_collision),
            sig(s.time_mean_e_tr),
            sig(s.equipartition_time),
            sig(w_min),
            sig(w_max),
            sig(flat)
        ),
        values: vec![
            ("modes", modes as f64),
            ("mean_e_tr", s.mean_e_tr),
            ("equipartition_per_collision", s.equipartition_per_collision),
            ("time_mean_e_tr", s.time_mean_e_tr),
            ("equipartition_time", s.equipartition_time),
            ("mean_eta", s.mean_eta),
            ("eta_equilibrium", s.eta_equilibrium),
            ("cooling_collision", cooling),
            ("spectrum_min", w_min),
            ("spectrum_max", w_max),
            ("rod1_mean_w", m1),
            ("rod2_mean_w", m2),
            ("energy_drift", s.energy_drift),
            ("mean_e_tr_se", plateau_se),
        ],
        files,
    })
}

fn fig2(ctx: &Context) -> Result<Outcome> {
    let id = "giese-fig2";
    let (kappa, modes, collisions, transient): (f64, &[usize], usize, usize) = if ctx.quick {
        (1000.0, &[4, 8, 16], 150, 75)
    } else {
        (4000.0, &[10, 25, 50, 75, 100], 200, 100)
    };
    let mut rows = Vec::new();
    let mut fig = Figure::new(
        format!("Giese Fig. 2: spectral entropy, gamma = {GAMMA}, kappa = {kappa}"),
        "collision n",
        "eta / eta_eq,  eta = 1 - h / ln(2M)",
    )
    .log(true, false);
    let mut table = String::new();
    let mut values = Vec::new();
    let names: [(&str, &str, &str); 5] = [
        ("mean_eta_1", "relaxation_1", "within_20_1"),
        ("mean_eta_2", "relaxation_2", "within_20_2"),
        ("mean_eta_3", "relaxation_3", "within_20_3"),
        ("mean_eta_4", "relaxation_4", "within_20_4"),
        ("mean_eta_5", "relaxation_5", "within_20_5"),
    ];
    let mut summary = Vec::new();
    let (mut worst, mut relaxations, mut withins) = (0.0f64, Vec::new(), Vec::new());
    for (k, &m) in modes.iter().enumerate() {
        let run = experiment(kappa, m, collisions, transient)?;
        let s = run.summary();
        let eq = s.eta_equilibrium;
        for r in &run.records {
            rows.push(vec![m as f64, r.collision as f64, r.eta, eq]);
        }
        fig = fig.line(format!("M = {m}"), eta_curve(&run.records, eq));
        let relax = or_none(s.eta_relaxation_collision);
        let within = or_none(s.eta_within_20_percent_collision);
        debug_assert_eq!(
            s.eta_within_20_percent_collision,
            eta_within(&run.records, eq, 0.2)
        );
        let _ = writeln!(
            table,
            "| {m} | {} | {} | {relax} | {within} |",
            sig(s.mean_eta),
            sig(eq)
        );
        summary.push(format!("M = {m}: 1/e at {relax}, 20 % at {within}"));
        worst = worst.max((s.mean_eta / eq - 1.0).abs());
        relaxations.push(relax);
        withins.push(within);
        let (a, b, c) = names[k];
        values.extend([(a, s.mean_eta), (b, relax), (c, within)]);
    }
    values.push(("worst_relative_eta_deviation", worst));
    fig = fig.theory("equilibrium eta = eta_eq", over_collisions(1.0, collisions));
    let files = vec![
        ctx.csv(id, &["modes", "collision", "eta", "eta_equilibrium"], &rows)?,
        ctx.figure(id, &fig)?,
    ];
    let md = format!(
        "# {id}: Giese Fig. 2 — spectral entropy\n\n\
         **Paper.** eta = 1 - h/ln(2 N_modes) after each collision of the two-rod run \
         (gamma = 0.6173, kappa = 4000) for several N_modes decays from 1 to \
         eta_eq ~ 0.423/ln(2 N_modes) in about 20 collisions, essentially independent of \
         N_modes — faster than the cooling of Fig. 1.\n\n\
         **We get.** Two-rod MD, kappa = {kappa}, {collisions} collisions per M, means over \
         collisions {}..{collisions}; eta_eq = 1 - (H_2M - 1)/ln(2M) exactly (Dirichlet \
         weights). The figure shows eta/eta_eq, so that every M relaxes to the same dashed \
         line.\n\n\
         | M | <eta> | eta_eq | 1/e relaxation (collision) | within 20 % of eta_eq |\n\
         |---|---|---|---|---|\n{table}\n\
         **Difference.** <eta> agrees with eta_eq to {:.1} % or better for every M (the \
         fluctuations of eta after one collision are large, see the figure). The 1/e \
         relaxation takes {} collisions and the approach to within 20 % of eta_eq {} \
         collisions for M = {} — a few tens of collisions at most, growing much more slowly \
         than M, as Giese's ~20 collisions \"essentially independent of N_modes\" (read off \
         by eye in the paper; it gives no number per N_modes).\n",
        transient + 1,
        100.0 * worst,
        join(&relaxations),
        join(&withins),
        modes
            .iter()
            .map(|m| m.to_string())
            .collect::<Vec<_>>()
            .join(", "),
    );
    let mut files = files;
    files.push(ctx.markdown(id, &md)?);
    Ok(Outcome {
        summary: summary.join("; "),
        values,
        files,
    })
}
