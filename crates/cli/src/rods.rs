//! `haff rods ...`: Giese's vibrating rods — the collision equation Eq. (3) (deterministic
//! and stochastic), the tabulated p(eps^2), the two-rod experiment and the rod-chain MD.

use crate::error::{CliError, CliResult};
use crate::output::{number, parse_count, parse_list, parse_number, stdout, write_csv, Allowed};
use crate::plot::{self, Axes};
use crate::{RodsCollideArgs, RodsDeterministicArgs, RodsTableArgs};
use rods::deterministic::{eps_closed_form, eps_closed_form_general, eps_numeric};
use rods::stochastic::{sample_eps, Resolution, Table};
use std::io::Write;
use std::path::Path;

fn library(flag: &str) -> impl Fn(rods::Error) -> CliError + '_ {
    move |e| CliError::argument(flag, e)
}

/// `haff rods deterministic`: eps of Eq. (3) at T_bath = 0 for every (gamma, kappa), with
/// the paper's closed form and the generalized one beside it (solved value last).
pub fn deterministic(args: &RodsDeterministicArgs) -> CliResult {
    let gammas = parse_list("--gamma", &args.gamma, Allowed::between("gamma", 1e-3, 1e3))?;
    let kappas = parse_list("--kappa", &args.kappa, Allowed::between("kappa", 1.0, 1e5))?;
    let step = parse_number("--step", &args.step, Allowed::open("h kappa", 0.0, 1.0))?;
    let mut rows = Vec::new();
    for &gamma in &gammas {
        for &kappa in &kappas {
            let eps = eps_numeric(gamma, kappa, step / kappa);
            rows.push(vec![
                number(gamma),
                number(kappa),
                number(eps_closed_form(gamma, kappa)),
                number(eps_closed_form_general(gamma, kappa)),
                number(eps),
            ]);
        }
    }
    let header = [
        "gamma",
        "kappa",
        "closed_form",
        "closed_form_general",
        "eps",
    ];
    let mut out = stdout();
    write_csv(&mut out, &header, rows)?;
    Ok(out.flush()?)
}

/// The energy ratio of `--bath-ratio` ("inf" for a cold bath).
fn bath_ratio(text: &Option<String>) -> CliResult<f64> {
    match text.as_deref().map(str::trim) {
        None | Some("inf") => Ok(f64::INFINITY),
        Some(t) => parse_number(
            "--bath-ratio",
            t,
            Allowed::between("E_tr/T_bath", 1e-4, 1e6),
        ),
    }
}

/// `haff rods collide`: eps from realizations of Eq. (3) with the noise of Eq. (5):
/// one row per realization, or the histogram of eps^2 with its distribution function.
pub fn collide(args: &RodsCollideArgs) -> CliResult {
    let gamma = parse_number("--gamma", &args.gamma, Allowed::between("gamma", 1e-3, 1e3))?;
    let kappa = parse_number("--kappa", &args.kappa, Allowed::between("kappa", 1.0, 1e5))?;
    let ratio = bath_ratio(&args.bath_ratio)?;
    let realizations = parse_count("--realizations", &args.realizations, 1, 10_000_000)?;
    let seed = parse_count("--seed", &args.seed, 0, usize::MAX)? as u64;
    let eps = sample_eps(gamma, kappa, ratio, realizations, seed).map_err(library("--gamma"))?;
    let mut out = stdout();
    let Some(bins) = &args.histogram else {
        let rows = eps
            .iter()
            .enumerate()
            .map(|(k, e)| vec![k.to_string(), number(*e), number(e * e)]);
        write_csv(&mut out, &["realization", "eps", "eps2"], rows)?;
        return Ok(out.flush()?);
    };
    let bins = parse_count("--histogram", bins, 1, 100_000)?;
    let max = parse_number("--max", &args.max, Allowed::positive("largest eps^2"))?;
    let histogram = eps2_histogram(&eps, bins, max);
    let rows = histogram
        .iter()
        .map(|&(x, p, cdf)| vec![number(x), number(p), number(cdf)]);
    write_csv(&mut out, &["eps2", "density", "cdf"], rows)?;
    out.flush()?;
    let mean = eps.iter().map(|e| e * e).sum::<f64>() / eps.len() as f64;
    let above = eps.iter().filter(|e| **e > 1.0).count() as f64 / eps.len() as f64;
    eprintln!("gamma = {gamma}, kappa = {kappa}, E_tr/T_bath = {ratio}: <eps^2> = {mean:.4}, P(eps^2 > 1) = {above:.4}, {realizations} realizations");
    if let Some(path) = &args.plot {
        let title = format!("p(eps^2): gamma = {gamma}, E_tr/T_bath = {ratio}, kappa = {kappa}");
        plot_distribution(path, &title, &histogram)?;
    }
    Ok(())
}

/// (bin centre, density, distribution function at the bin's upper edge) of eps^2 on [0, max).
fn eps2_histogram(eps: &[f64], bins: usize, max: f64) -> Vec<(f64, f64, f64)> {
    let width = max / bins as f64;
    let mut counts = vec![0usize; bins];
    for e in eps {
        let k = (e * e / width) as usize;
        if k < bins {
            counts[k] += 1;
        }
    }
    let n = eps.len() as f64;
    let mut below = 0;
    counts
        .iter()
        .enumerate()
        .map(|(k, &c)| {
            below += c;
            (
                (k as f64 + 0.5) * width,
                c as f64 / (n * width),
                below as f64 / n,
            )
        })
        .collect()
}

fn plot_distribution(path: &Path, title: &str, histogram: &[(f64, f64, f64)]) -> CliResult {
    let density = histogram.iter().map(|&(x, p, _)| (x, p)).collect();
    let cdf = histogram.iter().map(|&(x, _, c)| (x, c)).collect();
    let axes = Axes {
        title,
        x: "eps^2",
        y: "p(eps^2), distribution function",
        log_x: false,
        log_y: false,
    };
    plot::lines(
        path,
        axes,
        &[
            ("density p(eps^2)".into(), density),
            ("distribution function".into(), cdf),
        ],
    )
}

/// `haff rods table`: the quantiles of eps^2 on a log grid of E_tr/T_bath, as JSON for
/// `law = "stochastic"`, `distribution = "tabulated"`.
pub fn table(args: &RodsTableArgs) -> CliResult {
    let gamma = parse_number("--gamma", &args.gamma, Allowed::between("gamma", 1e-3, 1e3))?;
    let kappa = parse_number("--kappa", &args.kappa, Allowed::between("kappa", 1.0, 1e5))?;
    let grid = parse_list(
        "--ratios",
        &args.ratios,
        Allowed::between("E_tr/T_bath", 1e-4, 1e6),
    )?;
    let [min, max, count] = grid[..] else {
        return Err(CliError::argument(
            "--ratios",
            "give MIN,MAX,COUNT (log-spaced grid)",
        ));
    };
    if !(max > min && (2.0..=1000.0).contains(&count) && count.fract() == 0.0) {
        return Err(CliError::argument(
            "--ratios",
            "need MIN < MAX and an integer 2 <= COUNT <= 1000",
        ));
    }
    let realizations = parse_count("--realizations", &args.realizations, 2, 10_000_000)?;
    let seed = parse_count("--seed", &args.seed, 0, usize::MAX)? as u64;
    let ratios = Table::log_grid(min, max, count as usize);
    let progress = indicatif::ProgressBar::new(ratios.len() as u64);
    let table = Table::build_reporting(gamma, kappa, &ratios, realizations, seed, |_| {
        progress.inc(1)
    })
    .map_err(library("--gamma"))?;
    progress.finish_and_clear();
    let text = serde_json::to_string_pretty(&table)?;
    std::fs::write(&args.out, text + "\n")
        .map_err(|e| CliError::argument("--out", format!("{}: {e}", args.out.display())))?;
    let step = Resolution::default().step;
    eprintln!(
        "haff rods table: {} ratios x {realizations} realizations (h kappa = {step}) -> {}",
        ratios.len(),
        args.out.display()
    );
    Ok(())
}

/// One two-rod experiment's outcome for the summary.
#[derive(Debug, serde::Serialize)]
struct TwoRodSummary {
    modes: usize,
    collisions: usize,
    transient: usize,
    wall_seconds: f64,
    energy_drift: f64,
    /// Mean E_tr/E0 per collision after the transient, and Giese's E0/(2M+1).
    mean_e_tr: f64,
    equipartition_per_collision: f64,
    /// Time average of E_tr/E0 after the transient, and E0/(4M+1).
    time_mean_e_tr: f64,
    equipartition_time: f64,
    mean_eta: f64,
    eta_equilibrium: f64,
    eta_relaxation_collision: Option<usize>,
    eta_within_20_percent_collision: Option<usize>,
    cooling_collision: Option<usize>,
}

/// `haff rods two-rods`: Figs. 1 and 2 of Giese — two cold rods on a ring, E_tr, eps and
/// the spectral entropy after every collision, and the mean modal spectrum.
pub fn two_rods(args: &crate::RodsTwoRodsArgs) -> CliResult {
    use rods::chain::*;
    let gamma = parse_number("--gamma", &args.gamma, Allowed::between("gamma", 1e-2, 1e2))?;
    let kappa = parse_number("--kappa", &args.kappa, Allowed::between("kappa", 1.0, 1e6))?;
    let modes: Vec<usize> = parse_list(
        "--modes",
        &args.modes,
        Allowed::between("modes", 1.0, 2000.0),
    )?
    .into_iter()
    .map(|m| m as usize)
    .collect();
    let collisions = parse_count("--collisions", &args.collisions, 1, 10_000_000)?;
    let transient = parse_count("--transient", &args.transient, 0, collisions - 1)?;
    let c_h = parse_number("--step", &args.step, Allowed::between("c_h", 1e-4, 1.0))?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::argument("--out", format!("{}: {e}", args.out.display())))?;
    let mut rows = Vec::new();
    let mut spectra = Vec::new();
    let mut summaries = Vec::new();
    let (mut energy, mut entropy) = (Vec::new(), Vec::new());
    for &m in &modes {
        let setup = TwoRodSetup {
            gamma,
            kappa,
            modes: m,
            gap: 1.0,
            c_h,
        };
        let clock = std::time::Instant::now();
        let run = run_two_rods(&setup, collisions, transient).map_err(library("--modes"))?;
        let wall_seconds = clock.elapsed().as_secs_f64();
        let tail = &run.records[transient..];
        let mean =
            |f: fn(&TwoRodRecord) -> f64| tail.iter().map(f).sum::<f64>() / tail.len() as f64;
        let (mean_e_tr, eq) = (mean(|r| r.e_tr), eta_equilibrium(m));
        summaries.push(TwoRodSummary {
            modes: m,
            collisions,
            transient,
            wall_seconds,
            energy_drift: run.energy_drift,
            mean_e_tr,
            equipartition_per_collision: 1.0 / (2.0 * m as f64 + 1.0),
            time_mean_e_tr: run.time_mean_etr(),
            equipartition_time: 1.0 / (4.0 * m as f64 + 1.0),
            mean_eta: mean(|r| r.eta),
            eta_equilibrium: eq,
            eta_relaxation_collision: eta_relaxation(&run.records, eq),
            eta_within_20_percent_collision: eta_within(&run.records, eq, 0.2),
            cooling_collision: cooling_collision(&run.records, mean_e_tr, 25, 2.0),
        });
        for r in &run.records {
            rows.push(vec![
                m.to_string(),
                r.collision.to_string(),
                number(r.e_tr),
                number(r.eps),
                number(r.eta),
            ]);
        }
        for (j, w) in mean_spectrum(tail).iter().enumerate() {
            spectra.push(vec![
                m.to_string(),
                (j / m + 1).to_string(),
                (j % m + 1).to_string(),
                number(*w),
            ]);
        }
        let label = format!("M = {m}");
        energy.push((
            label.clone(),
            run.records
                .iter()
                .map(|r| (r.collision as f64, r.e_tr))
                .collect(),
        ));
        energy.push((
            format!("equilibrium 1/(2M+1), M = {m}"),
            vec![
                (1.0, 1.0 / (2.0 * m as f64 + 1.0)),
                (collisions as f64, 1.0 / (2.0 * m as f64 + 1.0)),
            ],
        ));
        let window = 25.min(run.records.len());
        let running = run.records.windows(window).map(|w| {
            let mean = w.iter().map(|r| r.e_tr).sum::<f64>() / window as f64;
            (w[window / 2].collision as f64, mean)
        });
        energy.push((
            format!("M = {m}, mean of {window} collisions"),
            running.collect(),
        ));
        entropy.push((
            label,
            run.records
                .iter()
                .map(|r| (r.collision as f64, r.eta))
                .collect(),
        ));
        entropy.push((
            format!("equilibrium eta_eq, M = {m}"),
            vec![(1.0, eq), (collisions as f64, eq)],
        ));
    }
    let file = |name: &str| args.out.join(name);
    let mut f = std::io::BufWriter::new(std::fs::File::create(file("two_rods.csv"))?);
    write_csv(&mut f, &["modes", "collision", "e_tr", "eps", "eta"], rows)?;
    f.flush()?;
    let mut f = std::io::BufWriter::new(std::fs::File::create(file("spectrum.csv"))?);
    write_csv(&mut f, &["modes", "rod", "mode", "w"], spectra)?;
    f.flush()?;
    let mut f = std::fs::File::create(file("summary.json"))?;
    serde_json::to_writer_pretty(&mut f, &summaries)?;
    writeln!(f)?;
    let title = format!("two rods, gamma = {gamma}, kappa = {kappa}: E_tr/E0 after each collision");
    let axes = Axes {
        title: &title,
        x: "collision",
        y: "E_tr / E0",
        log_x: true,
        log_y: true,
    };
    plot::lines(&file("energy.png"), axes, &energy)?;
    let title = format!("two rods, gamma = {gamma}, kappa = {kappa}: spectral entropy");
    let axes = Axes {
        title: &title,
        x: "collision",
        y: "eta = 1 - h / ln(2M)",
        log_x: true,
        log_y: false,
    };
    plot::lines(&file("entropy.png"), axes, &entropy)?;
    plot_spectrum(&file("spectrum.png"), &summaries, &args.out)?;
    for s in &summaries {
        eprintln!(
            "M = {}: <E_tr>/E0 = {:.5} (E0/(2M+1) = {:.5}), time mean {:.5} (E0/(4M+1) = {:.5}), <eta> = {:.4} (eta_eq = {:.4}), eta relaxed at collision {:?}; energy drift {:.1e}; {:.1} s",
            s.modes, s.mean_e_tr, s.equipartition_per_collision, s.time_mean_e_tr, s.equipartition_time,
            s.mean_eta, s.eta_equilibrium, s.eta_relaxation_collision, s.energy_drift, s.wall_seconds
        );
    }
    Ok(())
}

/// The mean modal spectrum of the last M as w(mode) per rod (inset of Fig. 1).
fn plot_spectrum(path: &Path, summaries: &[TwoRodSummary], dir: &Path) -> CliResult {
    let Some(last) = summaries.last() else {
        return Ok(());
    };
    let text = std::fs::read_to_string(dir.join("spectrum.csv"))?;
    let mut rods: [Vec<(f64, f64)>; 2] = [Vec::new(), Vec::new()];
    for line in text.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        if cells.len() == 4 && cells[0] == last.modes.to_string() {
            let rod: usize = cells[1].parse().unwrap_or(1);
            let (mode, w) = (
                cells[2].parse().unwrap_or(0.0),
                cells[3].parse().unwrap_or(0.0),
            );
            rods[(rod - 1).min(1)].push((mode, w));
        }
    }
    let flat = 0.5 / last.modes as f64;
    let title = format!(
        "mean modal energies w after collision {} (M = {})",
        last.transient, last.modes
    );
    let axes = Axes {
        title: &title,
        x: "mode nu",
        y: "<w>",
        log_x: false,
        log_y: false,
    };
    let [a, b] = rods;
    let equal = vec![(1.0, flat), (last.modes as f64, flat)];
    plot::lines(
        path,
        axes,
        &[
            ("rod 1".into(), a),
            ("rod 2".into(), b),
            ("equilibrium 1/(2M)".into(), equal),
        ],
    )
}
