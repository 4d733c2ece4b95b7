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

fn library(flag: &str) -> impl Fn(String) -> CliError + '_ {
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
    let table =
        Table::build(gamma, kappa, &ratios, realizations, seed).map_err(library("--gamma"))?;
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
