//! `haff rods ...`: Giese's vibrating rods — the collision equation Eq. (3) (deterministic
//! and stochastic), the tabulated p(eps^2), the two-rod experiment and the rod-chain MD.

use crate::error::{CliError, CliResult};
use crate::output::{number, parse_count, parse_list, parse_number, stdout, write_csv, Allowed};
use crate::progress::Bar;
use crate::{RodsCollideArgs, RodsDeterministicArgs, RodsTableArgs, RunArgs};
use rods::deterministic::{
    eps_closed_form, eps_closed_form_general, eps_numeric, estimated_work, WORK_PER_SECOND,
};
use rods::ranges;
use rods::stochastic::{eps2_histogram, eps2_summary, sample_eps, Eps2Bin, Resolution, Table};
use sim::outdir::{run_hash, OutputDir, RunState};
use sim::plot::{self, Axes};
use sim::rod_ring::{RingDescription, RingRun};
use std::io::Write;
use std::path::Path;

fn library(flag: &str) -> impl Fn(rods::Error) -> CliError + '_ {
    move |e| CliError::argument(flag, e)
}

/// The most work one `rods deterministic` call may ask for: about a minute.
const DETERMINISTIC_WORK_LIMIT: f64 = rods::deterministic::WORK_LIMIT;

/// `haff rods deterministic`: eps of Eq. (3) at T_bath = 0 for every (gamma, kappa), with
/// the paper's closed form and the generalized one beside it (solved value last).
pub fn deterministic(args: &RodsDeterministicArgs) -> CliResult {
    let gammas = parse_list("--gamma", &args.gamma, Allowed::from(ranges::GAMMA))?;
    let kappas = parse_list("--kappa", &args.kappa, Allowed::from(ranges::KAPPA))?;
    let step = parse_number("--step", &args.step, Allowed::from(ranges::STEP))?;
    let work: f64 = gammas
        .iter()
        .flat_map(|&g| kappas.iter().map(move |&k| estimated_work(g, k, step / k)))
        .sum();
    if work > DETERMINISTIC_WORK_LIMIT {
        return Err(CliError::argument(
            "--gamma",
            format!(
                "these gamma, kappa and --step need about {:.0} s (the work grows as kappa / step \
                 and as 1/gamma^2 or gamma^2 away from 1); allowed: at most about {:.0} s per call, \
                 e.g. fewer values, gamma nearer 1, a smaller kappa or a larger --step",
                work / WORK_PER_SECOND,
                DETERMINISTIC_WORK_LIMIT / WORK_PER_SECOND
            ),
        ));
    }
    let mut rows = Vec::new();
    let mut undefined = false;
    // The closed forms are asymptotic in kappa |Gamma2 - Gamma1| >> 1; at gamma = 1 the
    // logarithm is -inf: an empty cell, not a number.
    let mut closed = |x: f64| {
        if x.is_finite() {
            number(x)
        } else {
            undefined = true;
            String::new()
        }
    };
    for &gamma in &gammas {
        for &kappa in &kappas {
            let eps = eps_numeric(gamma, kappa, step / kappa);
            rows.push(vec![
                number(gamma),
                number(kappa),
                closed(eps_closed_form(gamma, kappa)),
                closed(eps_closed_form_general(gamma, kappa)),
                number(eps),
            ]);
        }
    }
    if undefined {
        eprintln!(
            "haff: warning: the closed forms (ln of kappa |Gamma2 - Gamma1|) are undefined at \
             gamma = 1 and left empty; they need kappa |Gamma2 - Gamma1| >> 1"
        );
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

/// The whole numbers of `rods::ranges::REALIZATIONS`, for `--realizations`.
fn realizations_range() -> (usize, usize) {
    let r = ranges::REALIZATIONS;
    (r.low as usize, r.high as usize)
}

/// The energy ratio of `--bath-ratio` ("inf" for a cold bath).
fn bath_ratio(text: &Option<String>) -> CliResult<f64> {
    match text.as_deref().map(str::trim) {
        None | Some("inf") => Ok(f64::INFINITY),
        Some(t) => parse_number("--bath-ratio", t, Allowed::from(ranges::BATH_RATIO)),
    }
}

/// `haff rods collide`: eps from realizations of Eq. (3) with the noise of Eq. (5):
/// one row per realization, or the histogram of eps^2 with its distribution function.
pub fn collide(args: &RodsCollideArgs) -> CliResult {
    let gamma = parse_number("--gamma", &args.gamma, Allowed::from(ranges::GAMMA))?;
    let kappa = parse_number("--kappa", &args.kappa, Allowed::from(ranges::KAPPA))?;
    let ratio = bath_ratio(&args.bath_ratio)?;
    let (fewest, most) = realizations_range();
    let realizations = parse_count("--realizations", &args.realizations, fewest, most)?;
    let seed = parse_count("--seed", &args.seed, 0, usize::MAX)? as u64;
    if let Some(plot) = &args.plot {
        let parent = plot.parent().filter(|p| !p.as_os_str().is_empty());
        if parent.is_some_and(|p| !p.is_dir()) {
            return Err(CliError::argument(
                "--plot",
                format!("{}: the directory does not exist", plot.display()),
            ));
        }
    }
    // Each realization integrates Eq. (3) like `rods deterministic` (plus the noise);
    // the realizations share the machine's cores.
    let h = Resolution::default().h(kappa, ratio);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get()) as f64;
    let work = realizations as f64 * estimated_work(gamma, kappa, h) / cores;
    if work > DETERMINISTIC_WORK_LIMIT {
        return Err(CliError::argument(
            "--realizations",
            format!(
                "{realizations} realizations at gamma = {gamma}, kappa = {kappa} need about {:.0} s; \
                 allowed: at most about {:.0} s per call (fewer realizations, gamma nearer 1 or a \
                 smaller kappa)",
                work / WORK_PER_SECOND,
                DETERMINISTIC_WORK_LIMIT / WORK_PER_SECOND
            ),
        ));
    }
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
    let histogram = eps2_histogram(&eps, bins, max).map_err(library("--histogram"))?;
    let rows = histogram
        .iter()
        .map(|b| vec![number(b.eps2), number(b.density), number(b.cdf)]);
    write_csv(&mut out, &["eps2", "density", "cdf"], rows)?;
    out.flush()?;
    let (mean, above) = eps2_summary(&eps);
    eprintln!("gamma = {gamma}, kappa = {kappa}, E_tr/T_bath = {ratio}: <eps^2> = {mean:.4}, P(eps^2 > 1) = {above:.4}, {realizations} realizations");
    if let Some(path) = &args.plot {
        let title = format!("p(eps^2): gamma = {gamma}, E_tr/T_bath = {ratio}, kappa = {kappa}");
        plot_distribution(path, &title, &histogram)?;
    }
    Ok(())
}

fn plot_distribution(path: &Path, title: &str, histogram: &[Eps2Bin]) -> CliResult {
    let density = histogram.iter().map(|b| (b.eps2, b.density)).collect();
    let cdf = histogram.iter().map(|b| (b.eps2, b.cdf)).collect();
    let axes = Axes {
        title,
        x: "eps^2",
        y: "p(eps^2), distribution function",
        log_x: false,
        log_y: false,
    };
    Ok(plot::lines(
        path,
        axes,
        &[
            ("density p(eps^2)".into(), density),
            ("distribution function".into(), cdf),
        ],
    )?)
}

/// `haff rods table`: the quantiles of eps^2 on a log grid of E_tr/T_bath, as JSON for
/// `law = "stochastic"`, `distribution = "tabulated"`.
pub fn table(args: &RodsTableArgs) -> CliResult {
    let gamma = parse_number("--gamma", &args.gamma, Allowed::from(ranges::GAMMA))?;
    let kappa = parse_number("--kappa", &args.kappa, Allowed::from(ranges::KAPPA))?;
    let grid = parse_list("--ratios", &args.ratios, Allowed::from(ranges::BATH_RATIO))?;
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
    // Quantiles need two realizations at least.
    let (_, most) = realizations_range();
    let realizations = parse_count("--realizations", &args.realizations, 2, most)?;
    let seed = parse_count("--seed", &args.seed, 0, usize::MAX)? as u64;
    let ratios = Table::log_grid(min, max, count as usize);
    let progress = indicatif::ProgressBar::new(ratios.len() as u64);
    let table = Table::build_reporting(gamma, kappa, &ratios, realizations, seed, |_| {
        progress.inc(1)
    })
    .map_err(library("--gamma"))?;
    progress.finish_and_clear();
    sim::output::write_json_file(&args.out, &table).map_err(|e| CliError::argument("--out", e))?;
    let step = Resolution::default().step;
    eprintln!(
        "haff rods table: {} ratios x {realizations} realizations (h kappa = {step}) -> {}",
        ratios.len(),
        args.out.display()
    );
    Ok(())
}

/// `haff rods two-rods`: Figs. 1 and 2 of Giese — two cold rods on a ring, E_tr, eps and
/// the spectral entropy after every collision, and the mean modal spectrum
/// (`reproduce::giese::two_rods` runs the experiments and writes the files).
pub fn two_rods(args: &crate::RodsTwoRodsArgs) -> CliResult {
    use ::reproduce::giese::two_rods::{run_reporting, TwoRodsError, TwoRodsSettings};
    let gamma = parse_number(
        "--gamma",
        &args.gamma,
        Allowed::from(ranges::TWO_RODS_GAMMA),
    )?;
    let kappa = parse_number(
        "--kappa",
        &args.kappa,
        Allowed::from(ranges::TWO_RODS_KAPPA),
    )?;
    let modes: Vec<usize> = parse_list("--modes", &args.modes, Allowed::from(ranges::MODES))?
        .into_iter()
        .map(|m| m as usize)
        .collect();
    let collisions = parse_count("--collisions", &args.collisions, 1, 10_000_000)?;
    let transient = parse_count("--transient", &args.transient, 0, collisions - 1)?;
    let c_h = parse_number("--step", &args.step, Allowed::from(ranges::C_H))?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::argument("--out", format!("{}: {e}", args.out.display())))?;
    let settings = TwoRodsSettings {
        gamma,
        kappa,
        modes,
        collisions,
        transient,
        c_h,
        out: args.out.clone(),
    };
    let mut bar = crate::progress::Steps::new(settings.modes.len(), "experiments");
    let result = run_reporting(&settings, &mut |_| bar.step());
    bar.finish();
    let summaries = result.map_err(|e| match e {
        TwoRodsError::Run(e) => library("--modes")(e),
        TwoRodsError::Output(e) => CliError::from(e),
    })?;
    for s in &summaries {
        let relaxed = match s.eta_relaxation_collision {
            Some(k) => format!("eta relaxed at collision {k}"),
            None => "eta did not relax within the run".to_string(),
        };
        eprintln!(
            "M = {}: <E_tr>/E0 = {:.5} (E0/(2M+1) = {:.5}), time mean {:.5} (E0/(4M+1) = {:.5}), <eta> = {:.4} (eta_eq = {:.4}), {relaxed}; energy drift {:.1e}; {:.1} s",
            s.modes, s.mean_e_tr, s.equipartition_per_collision, s.time_mean_e_tr, s.equipartition_time,
            s.mean_eta, s.eta_equilibrium, s.energy_drift, s.wall_seconds
        );
    }
    Ok(())
}

/// `haff rods chain RUN.toml`, `haff rods chain --resume DIR`: the rod-chain MD on a ring
/// and ED + Monte Carlo of the same rods (`sim::rod_ring`).
pub fn chain(args: &RunArgs) -> CliResult {
    let (mut run, out) = match (&args.file, &args.resume) {
        (Some(path), None) => {
            let out = args.out.clone().unwrap_or_else(|| path.with_extension(""));
            let in_file = CliError::in_file(path);
            let description = RingDescription::from_path(path).map_err(&in_file)?;
            let run = RingRun::new(&description).map_err(in_file)?;
            if args.check {
                let text = toml::to_string(run.description())
                    .map_err(|e| CliError::argument("--check", e))?;
                let mut stdout = stdout();
                write!(stdout, "{text}")?;
                return Ok(stdout.flush()?);
            }
            (run, out)
        }
        (None, Some(dir)) => {
            let run = RingRun::resume(dir).map_err(CliError::resume)?;
            (run, args.out.clone().unwrap_or_else(|| dir.clone()))
        }
        _ => {
            return Err(CliError::argument(
                "haff rods chain",
                "give a run file (haff rods chain FILE.toml) or --resume DIR, exactly one",
            ))
        }
    };
    let count = |flag: &str, text: &Option<String>| {
        text.as_ref()
            .map(|t| parse_count(flag, t, 1, 1_000_000))
            .transpose()
    };
    let every = count("--checkpoint-every", &args.checkpoint_every)?.or(run.checkpoint_interval());
    let stop_after = count("--stop-after-samples", &args.stop_after_samples)?;
    let hash = run_hash(run.description());
    let mut dir = OutputDir::open(
        &out,
        args.resume.as_deref(),
        "rods chain",
        &hash,
        args.force,
    )?;
    run.set_checkpoints(&out, every);
    if !run.run(&mut Bar::samples(), stop_after)? {
        dir.set_state(RunState::Stopped)?;
        eprintln!(
            "haff rods chain: stopped after {} samples; continue with --resume {}",
            stop_after.unwrap_or(0),
            out.display()
        );
        return Ok(());
    }
    run.write(&out)?;
    dir.set_state(RunState::Complete)?;
    eprintln!(
        "haff rods chain: {} rods, {:.2} s; output in {}",
        run.ring().rods,
        run.chain_seconds(),
        out.display()
    );
    Ok(())
}
