//! Rough spheres in the homogeneous cooling state: the ratio of the rotational to the
//! translational temperature and the cooling rate per collision against the tangential
//! restitution beta at several normal restitutions alpha, the event-driven engine and
//! DSMC side by side, against the Maxwellian theory (`gas::theory::rough`: Huthmann &
//! Zippelius 1997; Luding, Huthmann, McNamara & Zippelius 1998).
//!
//! Method. Solid spheres (q = 2/5) in 3D start with Gaussian velocities at T = 1 and
//! angular velocities at the Maxwellian cooling state's T_rot = r T, so that what the
//! runs show beyond the Maxwellian ratio is the deviation the gas builds itself; over the
//! second half of the run (collisions per particle from C/2 to C) the ratio T_rot / T_tr
//! is averaged over the samples, and the cooling rate per collision is the slope of
//! -ln T_tr against collisions per particle; mean and standard error over seeds. The
//! event-driven gas is dilute (phi = 0.02, N = 4000: a box of 47 diameters, short of
//! the cooling gas's shear instability over these runs); homogeneous DSMC (the block
//! scheme) has no space at all: the Boltzmann equation's homogeneous cooling state.
//!
//! Beside the Maxwellian theory, the first Sonine approximation (`gas::theory::rough_sonine`):
//! its ratio, cooling rate and translational cumulant a20, the last against the measured
//! a2 (averaged over the same samples as the ratio).

use super::{sig, Context, Entry, Outcome};
use gas::theory::rough::RoughMaxwellian;
use gas::theory::rough_sonine::{self, RoughSonineHcs};
use sim::error::Result;
use sim::plot::Figure;
use sim::Simulation;
use std::fmt::Write as _;

const PAPER: &str = "Rough spheres in the HCS (Huthmann & Zippelius 1997; Luding et al. 1998)";

/// The inertia factor of a solid sphere.
const SOLID: f64 = 0.4;

pub fn entries() -> Vec<Entry> {
    vec![Entry {
        id: "rough-hcs",
        paper: PAPER,
        item: "T_rot / T_tr and cooling vs beta",
        shows: "the homogeneous cooling state of rough spheres: T_rot / T_tr and the cooling \
                rate per collision against beta at three alphas, event-driven and DSMC, \
                against the Maxwellian theory and the first Sonine approximation",
        typical_seconds: 120.0,
        run: hcs,
    }]
}

/// The engines of the study.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Method {
    EventDriven,
    Dsmc,
}

impl Method {
    fn name(self) -> &'static str {
        match self {
            Method::EventDriven => "event-driven",
            Method::Dsmc => "DSMC",
        }
    }

    fn run_lines(self, quick: bool) -> String {
        match self {
            Method::EventDriven => {
                let n = if quick { 1500 } else { 4000 };
                format!("[run]\nengine = \"event-driven\"\n__N__{n}\n")
            }
            Method::Dsmc => {
                let n = if quick { 5000 } else { 20000 };
                format!("[run]\nengine = \"dsmc\"\ndsmc_scheme = \"blocks\"\n__N__{n}\n")
            }
        }
    }
}

/// (ratio averaged over the second half, cooling rate per collision there, a2 averaged
/// there) of one run.
fn measure(
    method: Method,
    alpha: f64,
    beta: f64,
    collisions: f64,
    seed: u64,
    quick: bool,
) -> Result<(f64, f64, f64)> {
    let theory = RoughMaxwellian {
        dimension: 3,
        alpha,
        beta,
        inertia: SOLID,
    };
    let start = theory.hcs().map_or(1.0, |h| h.ratio);
    let lines = method.run_lines(quick);
    let (run_lines, particles) = lines.split_once("__N__").expect("marker");
    let particles = particles.trim();
    let text = format!(
        "[system]\ndimension = 3\nparticles = {particles}\npacking_fraction = 0.02\n\
         seed = {seed}\ninertia = {SOLID}\nrotational_temperature = {start}\n\
         [collision]\nlaw = \"constant\"\nrestitution = {alpha}\n\
         tangential_restitution = {beta}\n\
         {run_lines}collisions_per_particle = {collisions}\nsamples = 40\nspacing = \"linear\"\n"
    );
    let mut run = Simulation::from_toml(&text, "rough.toml".as_ref())?;
    run.run(&mut (), None)?;
    let late: Vec<&sim::observer::Sample> = run
        .samples()
        .iter()
        .filter(|s| s.collisions_per_particle >= 0.5 * collisions)
        .collect();
    let ratio = late
        .iter()
        .map(|s| s.rotational_temperature.expect("rough") / s.temperature)
        .sum::<f64>()
        / late.len() as f64;
    let a2 = late.iter().map(|s| s.a2).sum::<f64>() / late.len() as f64;
    let points: Vec<(f64, f64)> = late
        .iter()
        .map(|s| (s.collisions_per_particle, -s.temperature.ln()))
        .collect();
    Ok((ratio, super::slope(&points), a2))
}

/// One row of the study.
struct Row {
    method: Method,
    alpha: f64,
    beta: f64,
    ratio: (f64, f64),
    cooling: (f64, f64),
    theory_ratio: f64,
    theory_cooling: f64,
    /// The translational cumulant a2 (a20) measured.
    a2: (f64, f64),
    /// The first Sonine approximation (None: no cooling state of its linear equations).
    sonine: Option<RoughSonineHcs>,
}

/// The limits, in the event-driven engine (20 collisions per particle): perfectly rough
/// elastic spheres started without rotation (the largest relative change of the energy
/// per particle 3 (T_tr + T_rot) / 2, and the last T_rot / T_tr: equipartition), and
/// smooth spheres (beta = -1: rotation decoupled, no rotational column; their cooling per
/// collision, Haff's (1 - alpha^2) / 3 in the Maxwellian approximation).
fn limits(quick: bool) -> Result<(f64, f64, f64)> {
    let n = if quick { 1000 } else { 4000 };
    let run = |alpha: f64, beta: f64, rotation: &str| -> Result<Simulation> {
        let text = format!(
            "[system]\ndimension = 3\nparticles = {n}\npacking_fraction = 0.02\nseed = 3\n\
             {rotation}\n[collision]\nlaw = \"constant\"\nrestitution = {alpha}\n\
             tangential_restitution = {beta}\n\
             [run]\nengine = \"event-driven\"\ncollisions_per_particle = 20\nsamples = 20\n\
             spacing = \"linear\"\n"
        );
        let mut run = Simulation::from_toml(&text, "limits.toml".as_ref())?;
        run.run(&mut (), None)?;
        Ok(run)
    };
    let elastic = run(1.0, 1.0, "rotational_temperature = 0.0")?;
    let energy = |s: &sim::observer::Sample| {
        1.5 * (s.temperature + s.rotational_temperature.expect("rough"))
    };
    let e0 = energy(&elastic.samples()[0]);
    let drift = elastic
        .samples()
        .iter()
        .map(|s| (energy(s) / e0 - 1.0).abs())
        .fold(0.0, f64::max);
    // T_rot / T_tr averaged over the second half (collisions 10..20 per particle).
    let late: Vec<f64> = elastic
        .samples()
        .iter()
        .filter(|s| s.collisions_per_particle >= 10.0)
        .map(|s| s.rotational_temperature.expect("rough") / s.temperature)
        .collect();
    let equipartition = late.iter().sum::<f64>() / late.len() as f64;
    let smooth = run(SMOOTH_ALPHA, -1.0, "")?;
    assert!(smooth
        .samples()
        .iter()
        .all(|s| s.rotational_temperature.is_none()));
    let points: Vec<(f64, f64)> = smooth
        .samples()
        .iter()
        .filter(|s| s.collisions_per_particle >= 10.0)
        .map(|s| (s.collisions_per_particle, -s.temperature.ln()))
        .collect();
    Ok((drift, equipartition, super::slope(&points)))
}

/// The normal restitution of the smooth limit.
const SMOOTH_ALPHA: f64 = 0.8;

/// The cumulants up to which the first Sonine approximation is taken at its word: it drops
/// terms of the order of the cumulants squared (`gas::theory::rough_sonine`).
const SONINE_TRUSTED: f64 = 1.0;

/// The first Sonine cooling state where it is to be trusted.
fn trusted(sonine: &Option<RoughSonineHcs>) -> Option<&RoughSonineHcs> {
    sonine
        .as_ref()
        .filter(|h| h.largest_cumulant() < SONINE_TRUSTED)
}

/// Every (method, alpha, beta) of the study, measured over `seeds` runs.
fn study(ctx: &Context, alphas: &[f64], betas: &[f64]) -> Result<Vec<Row>> {
    let (seeds, collisions) = if ctx.quick { (3, 16.0) } else { (8, 40.0) };
    let mut rows = Vec::new();
    for method in [Method::EventDriven, Method::Dsmc] {
        for &alpha in alphas {
            for &beta in betas {
                let runs = (0..seeds)
                    .map(|s| measure(method, alpha, beta, collisions, 11 + s as u64, ctx.quick))
                    .collect::<Result<Vec<(f64, f64, f64)>>>()?;
                let column =
                    |k: usize| -> Vec<f64> { runs.iter().map(|r| [r.0, r.1, r.2][k]).collect() };
                let theory = RoughMaxwellian {
                    dimension: 3,
                    alpha,
                    beta,
                    inertia: SOLID,
                };
                let hcs = theory.hcs().expect("beta > -1");
                rows.push(Row {
                    method,
                    alpha,
                    beta,
                    ratio: super::mean_and_error(&column(0)),
                    cooling: super::mean_and_error(&column(1)),
                    theory_ratio: hcs.ratio,
                    theory_cooling: hcs.cooling_per_collision,
                    a2: super::mean_and_error(&column(2)),
                    sonine: rough_sonine::hcs(&theory),
                });
            }
        }
    }
    Ok(rows)
}

/// T_rot / T_tr against beta (logarithmic: it spans 0.3 to 1000 towards smooth spheres):
/// the Maxwellian curves, the first Sonine curves from beta = 1 down to where they stop
/// being trusted, and both engines.
fn figure(alphas: &[f64], rows: &[Row]) -> Figure {
    let mut figure = Figure::new(
        "Rough spheres: T_rot / T_tr in the homogeneous cooling state",
        "beta",
        "T_rot / T_tr",
    )
    .log(false, true);
    for &alpha in alphas {
        let theory = |beta: f64| RoughMaxwellian {
            dimension: 3,
            alpha,
            beta,
            inertia: SOLID,
        };
        let betas = (0..=40).map(|k| -0.95 + 1.95 * k as f64 / 40.0);
        let maxwellian = betas
            .clone()
            .map(|beta| (beta, theory(beta).hcs().expect("beta > -1").ratio))
            .collect();
        figure = figure.theory(format!("Maxwellian, alpha = {alpha}"), maxwellian);
        let sonine: Vec<(f64, f64)> = betas
            .rev()
            .map(|beta| (beta, rough_sonine::hcs(&theory(beta))))
            .take_while(|(_, h)| trusted(h).is_some())
            .map(|(beta, h)| (beta, h.expect("trusted").ratio))
            .collect();
        figure = figure.theory(format!("first Sonine, alpha = {alpha}"), sonine);
        for method in [Method::EventDriven, Method::Dsmc] {
            let points = rows
                .iter()
                .filter(|r| r.alpha == alpha && r.method == method)
                .map(|r| (r.beta, r.ratio.0, r.ratio.1))
                .collect();
            figure = figure.measured(format!("{}, alpha = {alpha}", method.name()), points);
        }
    }
    figure
}

/// What the table shows beyond its rows: the largest DSMC deviations from the Maxwellian
/// ratio (deviation, alpha, beta) and from the trusted first Sonine one, and how far apart
/// the engines are (combined standard errors).
struct Spread {
    largest: (f64, f64, f64),
    largest_sonine: (f64, f64, f64),
    engines_apart: f64,
}

/// The markdown rows and the CSV rows of the study, and its [`Spread`].
fn table(rows: &[Row]) -> (String, Vec<Vec<f64>>, Spread) {
    let mut md = String::new();
    let mut csv = Vec::new();
    let mut spread = Spread {
        largest: (0.0, 0.0, 0.0),
        largest_sonine: (0.0, 0.0, 0.0),
        engines_apart: 0.0,
    };
    for r in rows {
        let deviation = r.ratio.0 / r.theory_ratio - 1.0;
        let sonine = trusted(&r.sonine).map(|h| r.ratio.0 / h.ratio - 1.0);
        if r.method == Method::Dsmc {
            if deviation.abs() > spread.largest.0.abs() {
                spread.largest = (deviation, r.alpha, r.beta);
            }
            if let Some(d) = sonine.filter(|d| d.abs() > spread.largest_sonine.0.abs()) {
                spread.largest_sonine = (d, r.alpha, r.beta);
            }
        }
        if r.method == Method::EventDriven {
            if let Some(d) = rows
                .iter()
                .find(|d| d.method == Method::Dsmc && d.alpha == r.alpha && d.beta == r.beta)
            {
                let apart = (r.ratio.0 - d.ratio.0).abs() / r.ratio.1.hypot(d.ratio.1);
                spread.engines_apart = spread.engines_apart.max(apart);
            }
        }
        let (s_ratio, s_deviation, s_cooling, s_a20) = match &r.sonine {
            Some(h) => (
                sig(h.ratio),
                match sonine {
                    Some(d) => format!("{:+.1} %", 100.0 * d),
                    None => format!("(a cumulant {}: not trusted)", sig(h.largest_cumulant())),
                },
                sig(h.cooling_per_collision),
                sig(h.a20),
            ),
            None => ("none".into(), "—".into(), "—".into(), "—".into()),
        };
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} ± {} | {} | {:+.1} % | {} ± {} | {} | {s_ratio} | \
             {s_deviation} | {s_cooling} | {} ± {} | {s_a20} |",
            r.method.name(),
            r.alpha,
            r.beta,
            sig(r.ratio.0),
            sig(r.ratio.1),
            sig(r.theory_ratio),
            100.0 * deviation,
            sig(r.cooling.0),
            sig(r.cooling.1),
            sig(r.theory_cooling),
            sig(r.a2.0),
            sig(r.a2.1),
        );
        let h = r.sonine.as_ref();
        let or_nan = |f: fn(&RoughSonineHcs) -> f64| h.map_or(f64::NAN, f);
        csv.push(vec![
            (r.method == Method::Dsmc) as u8 as f64,
            r.alpha,
            r.beta,
            r.ratio.0,
            r.ratio.1,
            r.theory_ratio,
            r.cooling.0,
            r.cooling.1,
            r.theory_cooling,
            or_nan(|h| h.ratio),
            or_nan(|h| h.cooling_per_collision),
            r.a2.0,
            r.a2.1,
            or_nan(|h| h.a20),
            or_nan(|h| h.largest_cumulant()),
        ]);
    }
    (md, csv, spread)
}

/// The CSV's columns: the study's first nine, then the first Sonine approximation's and
/// the measured a2.
const CSV_HEADER: [&str; 15] = [
    "dsmc",
    "alpha",
    "beta",
    "ratio",
    "ratio_error",
    "theory_ratio",
    "cooling",
    "cooling_error",
    "theory_cooling",
    "sonine_ratio",
    "sonine_cooling",
    "a2",
    "a2_error",
    "sonine_a20",
    "sonine_largest_cumulant",
];

fn hcs(ctx: &Context) -> Result<Outcome> {
    let id = "rough-hcs";
    let alphas: &[f64] = if ctx.quick {
        &[0.9, 0.7]
    } else {
        &[0.9, 0.7, 0.5]
    };
    let betas: &[f64] = if ctx.quick {
        &[-0.5, 0.0, 0.5, 1.0]
    } else {
        &[-0.8, -0.6, -0.4, -0.2, 0.0, 0.2, 0.4, 0.6, 0.8, 1.0]
    };
    let (seeds, collisions) = if ctx.quick { (3, 16.0) } else { (8, 40.0) };
    let rows = study(ctx, alphas, betas)?;
    let (md_rows, csv, spread) = table(&rows);
    let mut md = format!(
        "# rough-hcs: rough spheres in the homogeneous cooling state (3D, q = 2/5)\n\n\
         **Paper.** (the theory) The Maxwellian approximation (Gaussian translational and angular \
         velocities, uncorrelated): T_rot / T_tr = r solves B r^2 + (C - A) r - B = 0 \
         (Huthmann & Zippelius 1997; Luding et al. 1998, Eq. (10)), the cooling rate per \
         collision (4/3)(A - B r); `gas::theory::rough` (its rates checked against Monte \
         Carlo averages of the collision rule). The first Sonine approximation, linear in the \
         cumulants a20, a02, a11 (Santos, Kremer & dos Santos 2011): `gas::theory::rough_sonine` \
         (its collisional moments checked likewise); \"none\" where its linear equations have \
         no cooling state, \"not trusted\" where a cumulant exceeds {SONINE_TRUSTED}.\n\n\
         **We get** the ratio averaged over collisions {} to {collisions} per particle and \
         the slope of -ln T_tr against collisions there, started at the Maxwellian ratio, \
         {seeds} seeds; event-driven: phi = 0.02; DSMC: the homogeneous block scheme; a2 \
         the translational velocities' Sonine coefficient averaged like the ratio.\n\n\
         | method | alpha | beta | T_rot/T_tr | Maxwellian | deviation | cooling per collision \
         | Maxwellian | first Sonine | deviation from it | its cooling | a2 | its a20 |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|\n{md_rows}",
        collisions / 2.0
    );
    let Spread {
        largest,
        largest_sonine,
        engines_apart,
    } = spread;
    let _ = write!(
        md,
        "\n**Difference.** The two engines agree within {:.1} combined standard errors at \
         every point. Against the Maxwellian ratio the Boltzmann gas (DSMC) deviates by up \
         to {:+.1} % (alpha = {}, beta = {}). The Maxwellian theory leaves out the \
         non-Gaussian distributions of both velocities and the correlation between the \
         translational and angular velocities the collisions build (Brilliantov, Pöschel, \
         Kranz & Zippelius, Phys. Rev. Lett. 98, 128001 (2007); the cumulants a20, a02, a11 \
         of Santos, Kremer & dos Santos 2011 and Kremer, Santos & Garzó 2014). The first \
         Sonine approximation takes the cumulants in: where it is trusted, DSMC deviates from \
         it by at most {:+.1} % (alpha = {}, beta = {}); towards smooth spheres (beta near \
         -1) its rotational cumulant a02 grows beyond 1 and it overshoots or has no solution.\n",
        engines_apart,
        100.0 * largest.0,
        largest.1,
        largest.2,
        100.0 * largest_sonine.0,
        largest_sonine.1,
        largest_sonine.2
    );
    let (drift, equipartition, smooth_cooling) = limits(ctx.quick)?;
    let _ = write!(
        md,
        "\n**Limits.** alpha = beta = 1 from T_rot = 0: the energy per particle \
         3 (T_tr + T_rot) / 2 changed by at most {drift:.1e} (relative) over 20 collisions per \
         particle while rotation took its share: T_rot / T_tr = {} over its second half \
         (equipartition: 1). beta = -1 (smooth, alpha = {SMOOTH_ALPHA}): no rotation is exchanged (no \
         rotational column; the spins of a rough engine stay bit for bit, \
         crates/gas/tests/rough.rs), and the translational cooling per collision is {} \
         against Haff's Maxwellian (1 - alpha^2)/3 = {} (its first Sonine correction, \
         (1 + 3 a2 / 16) with van Noije & Ernst's a2, gives {}).\n",
        sig(equipartition),
        sig(smooth_cooling),
        sig((1.0 - SMOOTH_ALPHA * SMOOTH_ALPHA) / 3.0),
        sig((1.0 - SMOOTH_ALPHA * SMOOTH_ALPHA) / 3.0
            * (1.0 + 3.0 * gas::theory::van_noije_ernst_a2::<3>(SMOOTH_ALPHA) / 16.0)
            / (1.0 - gas::theory::van_noije_ernst_a2::<3>(SMOOTH_ALPHA) / 16.0))
    );
    let files = vec![
        ctx.csv(id, &CSV_HEADER, &csv)?,
        ctx.figure(id, &figure(alphas, &rows))?,
        ctx.markdown(id, &md)?,
    ];
    Ok(Outcome {
        summary: format!(
            "rough HCS at {} alphas x {} betas; DSMC vs Maxwellian ratio up to {:+.1} %, vs the \
             trusted first Sonine ratio up to {:+.1} %; engines within {:.1} sigma",
            alphas.len(),
            betas.len(),
            100.0 * largest.0,
            100.0 * largest_sonine.0,
            engines_apart
        ),
        values: vec![
            ("largest_deviation", largest.0),
            ("largest_deviation_from_sonine", largest_sonine.0),
            ("engines_apart_sigma", engines_apart),
            ("elastic_energy_drift", drift),
            ("elastic_equipartition", equipartition),
            ("smooth_cooling_per_collision", smooth_cooling),
        ],
        files,
    })
}
