//! The shear instability of the homogeneous cooling state, measured: the growth rate of the
//! transverse momentum modes against Navier–Stokes hydrodynamics with the Enskog viscosity
//! (`gas::theory::HcsTransport`; Goldhirsch & Zanetti 1993; Brey, Ruiz-Montero & Cubero
//! 1998; Garzó & Dufty 1999), by eMD in 2D and 3D and by spatial DSMC with particle weights
//! below 1, and the temperature's departure from Haff's law after the onset.
//!
//! Units: sigma = m = T0 = 1. Time is counted in collisions per particle c, in which the
//! growth rate of a mode of the HCS is a constant: the normalized transverse energy E(c) of
//! the shell k (`gas::structure::hydrodynamic_modes`, 1 in a homogeneous gas) grows as
//! exp(lambda c), lambda = 2 s(k) / omega = (zeta / omega) (1 - (k / k_c)^2).
//!
//! The fit. Linear fluctuating hydrodynamics gives the ensemble mean of a mode of growth
//! rate lambda fed by thermal noise as E(c) = A exp(lambda c) - B, with B = D / lambda (for
//! a stable mode the same law gives the stationary value -B = 1 / (1 - (k_c / k)^2), 4/3 at
//! k = 2 k_c). The noise term B matters for the slow modes near k_c: the slope of ln E alone
//! would be biased upward by (E + B) / E. So the seed-averaged E(c) of each shell is fitted
//! with the three parameters (A, B, lambda) on the differences of ln E, and the error comes
//! from the jackknife over seeds (the fit of the average with each seed left out in turn):
//! fits of single seeds, whose energies scatter like exponential variables, are biased and
//! ill-conditioned for the slow modes. The fit ends where the mean energy of the lowest
//! shell, which grows fastest, reaches N/200: a flow of u^2 / T ~ 1 % in that mode, where
//! the measured slopes of ln E over windows of 20 collisions (kinetic-shear-modes.csv) start
//! to fall below their early values in the 2D eMD runs (at N/40 they had fallen by 10 to
//! 30 %: the onset of the nonlinear regime, in which the vortices feed density
//! fluctuations). Shells that grow less than e^1.5 by then are reported as not resolved.

use super::{mean_and_error, sig, Context, Entry, Outcome};
use gas::dsmc::{point_gas, SpatialOptions};
use gas::observe::temperature;
use gas::structure::hydrodynamic_modes;
use gas::theory::{long_wavelength_structure_factor, HcsTransport};
use gas::{Engine, EventDriven, SpatialDsmc};
use restitution::Constant;
use sim::error::Result;
use sim::plot::Figure;
use std::fmt::Write as _;

const PAPER: &str = "Shear instability (Goldhirsch & Zanetti 1993; Garzó & Dufty 1999)";

/// The lowest shell's energy, in units of N, at which the fit window ends.
const NONLINEAR_FRACTION: f64 = 1.0 / 200.0;

pub fn entries() -> Vec<Entry> {
    vec![Entry {
        id: "kinetic-shear",
        paper: PAPER,
        item: "shear-mode growth",
        shows: "growth rate of the transverse modes vs k (eMD 2D/3D, spatial DSMC) against \
                Navier-Stokes with the Enskog viscosity; T / T_Haff after the onset",
        typical_seconds: 150.0,
        run: shear,
    }]
}

fn engine_error(e: impl std::fmt::Display) -> sim::error::Error {
    super::numerical("engine", e)
}

/// How a case is simulated.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Method {
    EventDriven,
    /// Spatial DSMC with this many physical particles per simulated one.
    Dsmc {
        weight: f64,
    },
}

/// One gas in one box.
#[derive(Debug, Clone, Copy)]
struct Case {
    label: &'static str,
    dimension: usize,
    phi: f64,
    eps: f64,
    method: Method,
    /// Box side in critical lengths.
    boxes: f64,
    /// Shells 1 <= |n|^2 <= max_norm2.
    max_norm2: usize,
    collisions: f64,
    seeds: u64,
}

impl Case {
    fn density(&self) -> f64 {
        match self.dimension {
            2 => self.phi / gas::system::ball_volume::<2>(0.5),
            _ => self.phi / gas::system::ball_volume::<3>(0.5),
        }
    }

    fn theory(&self) -> HcsTransport {
        let n = self.density();
        match (self.dimension, self.method) {
            (2, Method::EventDriven) => {
                HcsTransport::new::<2>(n, 1.0, 1.0, 1.0, self.phi, self.eps)
            }
            (2, Method::Dsmc { .. }) => {
                HcsTransport::enskog_factor_dsmc::<2>(n, 1.0, 1.0, 1.0, self.phi, self.eps)
            }
            (_, Method::EventDriven) => {
                HcsTransport::new::<3>(n, 1.0, 1.0, 1.0, self.phi, self.eps)
            }
            (_, Method::Dsmc { .. }) => {
                HcsTransport::enskog_factor_dsmc::<3>(n, 1.0, 1.0, 1.0, self.phi, self.eps)
            }
        }
    }

    /// The mean free path (`gas::theory::mean_free_path`, with the Enskog factor).
    fn mean_free_path(&self) -> f64 {
        let n = self.density();
        match self.dimension {
            2 => gas::theory::mean_free_path::<2>(n, 1.0, self.phi),
            _ => gas::theory::mean_free_path::<3>(n, 1.0, self.phi),
        }
    }

    fn side(&self) -> f64 {
        self.boxes * self.theory().critical_length()
    }

    /// Physical particles in the box.
    fn physical_particles(&self) -> f64 {
        self.density() * self.side().powi(self.dimension as i32)
    }

    /// Simulated particles.
    fn particles(&self) -> usize {
        let weight = match self.method {
            Method::EventDriven => 1.0,
            Method::Dsmc { weight } => weight,
        };
        (self.physical_particles() / weight).round() as usize
    }

    fn method_name(&self) -> String {
        match self.method {
            Method::EventDriven => "eMD".into(),
            Method::Dsmc { weight } => format!("spatial DSMC, F = {weight}"),
        }
    }
}

/// One run: per sample c, T, t and the transverse energy of each shell.
struct Run {
    collisions: Vec<f64>,
    times: Vec<f64>,
    temperatures: Vec<f64>,
    /// `energies[shell][sample]`.
    energies: Vec<Vec<f64>>,
    /// |k| of each shell.
    wave_numbers: Vec<f64>,
    particles: usize,
}

fn simulate(case: &Case, seed: u64) -> Result<Run> {
    match case.dimension {
        2 => simulate_in::<2>(case, seed),
        _ => simulate_in::<3>(case, seed),
    }
}

fn simulate_in<const D: usize>(case: &Case, seed: u64) -> Result<Run> {
    let law = Box::new(Constant::new(case.eps).map_err(engine_error)?);
    let n = case.particles();
    let side = case.side();
    let (mut engine, s0): (Box<dyn Engine<D>>, f64) = match case.method {
        Method::EventDriven => {
            // The side of N spheres at phi is the case's side to the rounding of N.
            let system = gas::init::monodisperse::<D>(n, case.phi, 1.0, 1.0, 1.0, seed)
                .map_err(engine_error)?;
            let engine = EventDriven::new(system, law).map_err(engine_error)?;
            (
                Box::new(engine),
                long_wavelength_structure_factor::<D>(case.phi),
            )
        }
        Method::Dsmc { .. } => {
            let system = point_gas::<D>(n, side, 1.0, 1.0, 1.0, seed).map_err(engine_error)?;
            let options = SpatialOptions::default();
            let engine =
                SpatialDsmc::new(system, case.phi, law, seed, options).map_err(engine_error)?;
            // Points placed independently: S(0) = 1.
            (Box::new(engine), 1.0)
        }
    };
    let mut run = Run {
        collisions: Vec::new(),
        times: Vec::new(),
        temperatures: Vec::new(),
        energies: Vec::new(),
        wave_numbers: Vec::new(),
        particles: n,
    };
    let samples = case.collisions.round() as u64;
    for i in 0..=samples {
        let target = (i as f64 * n as f64 / 2.0).round() as u64;
        let have = engine.counters().collisions;
        engine.run_collisions(target.saturating_sub(have));
        let (c, t) = (engine.collisions_per_particle(), engine.time());
        let system = engine.system();
        let shells = hydrodynamic_modes(system, case.max_norm2, s0);
        if run.energies.is_empty() {
            run.energies = vec![Vec::new(); shells.len()];
            run.wave_numbers = shells.iter().map(|s| s.k).collect();
        }
        for (e, s) in run.energies.iter_mut().zip(&shells) {
            e.push(s.transverse_energy);
        }
        run.temperatures.push(temperature(system));
        run.collisions.push(c);
        run.times.push(t);
    }
    Ok(run)
}

/// The fit of the module documentation over the points (c, E > 0): the sum of squared
/// differences of ln E, profiled over lambda (golden section on (0, 12 / c_max]) with A and
/// B at each lambda from iteratively reweighted linear least squares (weights 1 / model^2,
/// which makes the residuals relative, i.e. those of ln E to first order). None for fewer
/// than 6 points; else (lambda, B).
fn fit_growth(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    if points.len() < 6 || points.iter().any(|p| p.1.is_nan() || p.1 <= 0.0) {
        return None;
    }
    // (residual of ln E, A, B) at fixed lambda.
    let at = |lambda: f64| -> (f64, f64, f64) {
        let mut model: Vec<f64> = points.iter().map(|p| p.1).collect();
        let (mut a, mut c0) = (1.0, 0.0);
        for _ in 0..6 {
            let (mut suu, mut su, mut s1, mut sue, mut se) = (0.0, 0.0, 0.0, 0.0, 0.0);
            for (&(c, e), &m) in points.iter().zip(&model) {
                let (u, w) = ((lambda * c).exp(), 1.0 / (m * m));
                suu += w * u * u;
                su += w * u;
                s1 += w;
                sue += w * u * e;
                se += w * e;
            }
            // Normal equations of E = A u + C (C = -B).
            let det = suu * s1 - su * su;
            a = (sue * s1 - su * se) / det;
            c0 = (suu * se - su * sue) / det;
            for (m, &(c, e)) in model.iter_mut().zip(points) {
                let fitted = a * (lambda * c).exp() + c0;
                *m = if fitted > 0.0 { fitted } else { e };
            }
        }
        let residual = points
            .iter()
            .map(|&(c, e)| {
                let fitted = a * (lambda * c).exp() + c0;
                if fitted > 0.0 {
                    (fitted.ln() - e.ln()).powi(2)
                } else {
                    f64::INFINITY
                }
            })
            .sum();
        (residual, a, -c0)
    };
    let c_max = points.last().map(|p| p.0).unwrap_or(1.0).max(1e-9);
    let (mut lo, mut hi) = (1e-4 / c_max, 12.0 / c_max);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..80 {
        let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if at(x1).0 < at(x2).0 {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    let lambda = 0.5 * (lo + hi);
    Some((lambda, at(lambda).2))
}

/// A shell's measured growth against theory.
struct ShellResult {
    k_over_kc: f64,
    /// The growth per collision of the seed-averaged energy and its jackknife error; None
    /// where the shell grew less than e^[`MIN_GROWTH`] in the window.
    measured: Option<(f64, f64)>,
    theory: f64,
}

/// The least growth exponent lambda c_end that separates a shell's growth from its noise
/// term (E grows at least 4.5-fold in the window).
const MIN_GROWTH: f64 = 1.5;

/// The mean over `runs` (all but `skip`) of each shell's energy at each sample, and the
/// mean collisions per particle.
fn averaged(runs: &[Run], skip: Option<usize>) -> (Vec<f64>, Vec<Vec<f64>>) {
    let kept: Vec<&Run> = runs
        .iter()
        .enumerate()
        .filter(|(i, _)| Some(*i) != skip)
        .map(|(_, r)| r)
        .collect();
    let samples = kept.iter().map(|r| r.collisions.len()).min().unwrap_or(0);
    let n = kept.len() as f64;
    let collisions = (0..samples)
        .map(|i| kept.iter().map(|r| r.collisions[i]).sum::<f64>() / n)
        .collect();
    let energies = (0..kept[0].energies.len())
        .map(|shell| {
            (0..samples)
                .map(|i| kept.iter().map(|r| r.energies[shell][i]).sum::<f64>() / n)
                .collect()
        })
        .collect();
    (collisions, energies)
}

/// The growth rate of every shell of `case`: the fit of the seed-averaged energies up to
/// where the lowest shell's mean reaches N x [`NONLINEAR_FRACTION`], with the jackknife
/// error over seeds (each seed left out in turn).
fn growth_rates(case: &Case) -> Result<(Vec<ShellResult>, Vec<Run>, f64)> {
    let runs: Vec<Run> = (0..case.seeds)
        .map(|s| simulate(case, 1000 + s))
        .collect::<Result<_>>()?;
    let theory = case.theory();
    let kc = theory.critical_wave_number();
    let ceiling = NONLINEAR_FRACTION * runs[0].particles as f64;
    let (collisions, energies) = averaged(&runs, None);
    let end = energies[0]
        .iter()
        .position(|&e| e > ceiling)
        .unwrap_or(collisions.len());
    let c_end = collisions[end.saturating_sub(1)];
    let fit = |collisions: &[f64], energies: &[f64]| -> Option<f64> {
        let points: Vec<(f64, f64)> = collisions[..end]
            .iter()
            .copied()
            .zip(energies[..end].iter().copied())
            .collect();
        fit_growth(&points).map(|f| f.0)
    };
    let leave_one_out: Vec<(Vec<f64>, Vec<Vec<f64>>)> =
        (0..runs.len()).map(|i| averaged(&runs, Some(i))).collect();
    let mut out = Vec::new();
    for (shell, &k) in runs[0].wave_numbers.iter().enumerate() {
        let measured = fit(&collisions, &energies[shell])
            .filter(|&lambda| lambda * c_end >= MIN_GROWTH)
            .and_then(|lambda| {
                let others: Vec<f64> = leave_one_out
                    .iter()
                    .filter_map(|(c, e)| fit(c, &e[shell]))
                    .collect();
                let n = others.len() as f64;
                if others.len() < 2 {
                    return None;
                }
                let mean = others.iter().sum::<f64>() / n;
                let variance =
                    (n - 1.0) / n * others.iter().map(|x| (x - mean).powi(2)).sum::<f64>();
                Some((lambda, variance.sqrt()))
            });
        out.push(ShellResult {
            k_over_kc: k / kc,
            measured,
            theory: 2.0 * theory.transverse_growth_per_collision(k),
        });
    }
    Ok((out, runs, c_end))
}

/// The samples before the lowest shell of `run` exceeds N x [`NONLINEAR_FRACTION`].
fn linear_window(run: &Run) -> usize {
    let ceiling = NONLINEAR_FRACTION * run.particles as f64;
    run.energies[0]
        .iter()
        .position(|&e| e > ceiling)
        .unwrap_or(run.energies[0].len())
}

/// A straight line y = a - b x through the resolved shells of a case, x = (k/k_c)^2 and
/// y = lambda / (zeta/omega) (theory: a = b = 1), weighted with the jackknife errors.
struct Line {
    intercept: f64,
    intercept_error: f64,
    slope: f64,
    slope_error: f64,
}

fn straight_line(shells: &[ShellResult], scale: f64) -> Option<Line> {
    let points: Vec<(f64, f64, f64)> = shells
        .iter()
        .filter_map(|s| {
            s.measured
                .filter(|m| m.1 > 0.0)
                .map(|(m, e)| (s.k_over_kc.powi(2), m / scale, 1.0 / (e / scale).powi(2)))
        })
        .collect();
    if points.len() < 3 {
        return None;
    }
    let (mut sw, mut sx, mut sy, mut sxx, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for &(x, y, w) in &points {
        sw += w;
        sx += w * x;
        sy += w * y;
        sxx += w * x * x;
        sxy += w * x * y;
    }
    let det = sw * sxx - sx * sx;
    let slope = (sw * sxy - sx * sy) / det;
    let intercept = (sxx * sy - sx * sxy) / det;
    Some(Line {
        intercept,
        intercept_error: (sxx / det).sqrt(),
        slope: -slope,
        slope_error: (sw / det).sqrt(),
    })
}

/// T / T_Haff(t) averaged over `runs` at each sample (T_Haff with the theory's cooling rate
/// at T0 = 1), with the mean collisions per particle.
fn haff_ratio(runs: &[Run], theory: &HcsTransport) -> Vec<(f64, f64, f64)> {
    let samples = runs.iter().map(|r| r.times.len()).min().unwrap_or(0);
    (0..samples)
        .map(|i| {
            let ratios: Vec<f64> = runs
                .iter()
                .map(|r| {
                    let haff = 1.0 / (1.0 + 0.5 * theory.cooling_rate * r.times[i]).powi(2);
                    r.temperatures[i] / haff
                })
                .collect();
            let c = runs.iter().map(|r| r.collisions[i]).sum::<f64>() / runs.len() as f64;
            let (mean, error) = mean_and_error(&ratios);
            (c, mean, error)
        })
        .collect()
}

fn cases(quick: bool) -> Vec<Case> {
    let emd2 = Case {
        label: "2D, phi = 0.05, eps = 0.9",
        dimension: 2,
        phi: 0.05,
        eps: 0.9,
        method: Method::EventDriven,
        boxes: 4.0,
        max_norm2: 10,
        collisions: 120.0,
        seeds: 8,
    };
    if quick {
        // Shells up to |n|^2 = 20 (k up to 1.1 k_c): 12 rows, the stable ones unresolved.
        return vec![Case {
            max_norm2: 20,
            collisions: 70.0,
            seeds: 3,
            ..emd2
        }];
    }
    vec![
        emd2,
        Case {
            label: "2D, phi = 0.25, eps = 0.9",
            phi: 0.25,
            boxes: 6.0,
            max_norm2: 20,
            collisions: 60.0,
            ..emd2
        },
        Case {
            label: "2D, phi = 0.05, eps = 0.8",
            eps: 0.8,
            collisions: 40.0,
            ..emd2
        },
        Case {
            label: "3D, phi = 0.2, eps = 0.9",
            dimension: 3,
            phi: 0.2,
            boxes: 3.0,
            max_norm2: 5,
            collisions: 100.0,
            seeds: 6,
            ..emd2
        },
        Case {
            label: "2D, phi = 0.05, eps = 0.9",
            method: Method::Dsmc { weight: 0.1 },
            collisions: 80.0,
            seeds: 4,
            ..emd2
        },
    ]
}

/// The box below L_c whose modes must stay at their stationary value.
fn stable_case(quick: bool) -> Case {
    Case {
        label: "2D, phi = 0.05, eps = 0.9, box L_c / 2",
        dimension: 2,
        phi: 0.05,
        eps: 0.9,
        method: Method::EventDriven,
        boxes: 0.5,
        max_norm2: 1,
        collisions: 120.0,
        seeds: if quick { 8 } else { 32 },
    }
}

fn shear(ctx: &Context) -> Result<Outcome> {
    let id = "kinetic-shear";
    let mut rows = Vec::new();
    let mut fig = Figure::new(
        "Shear mode of the HCS: growth per collision / (zeta/omega) vs (k/k_c)^2 (± jackknife errors)",
        "(k / k_c)^2",
        "lambda / (zeta / omega)",
    );
    let mut summary_table = String::from(
        "| case | method | k_c lambda | a (theory 1) | b = nu_eff / nu (theory 1) | L_c measured / theory |\n\
         |---|---|---|---|---|---|\n",
    );
    let mut table = String::from(
        "| case | method | N | L / L_c | seeds | fit to c | k / k_c | lambda measured | theory | difference |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut worst: f64 = 0.0;
    let mut within = 0usize;
    let mut measured_shells = 0usize;
    let mut unstable_runs = Vec::new();
    // The lowest shell of the first case (2D eMD, phi = 0.05, eps = 0.9): (measured, error,
    // theory).
    let mut lowest = (f64::NAN, f64::NAN, f64::NAN);
    let mut mode_rows = Vec::new();
    for (index, case) in cases(ctx.quick).into_iter().enumerate() {
        let (shells, runs, c_end) = growth_rates(&case)?;
        let theory = case.theory();
        let scale = theory.cooling_rate / theory.collision_frequency;
        let kc = theory.critical_wave_number();
        for (shell, &k) in runs[0].wave_numbers.iter().enumerate() {
            let samples = runs.iter().map(|r| r.collisions.len()).min().unwrap_or(0);
            for i in 0..samples {
                let e: Vec<f64> = runs.iter().map(|r| r.energies[shell][i]).collect();
                let c = runs.iter().map(|r| r.collisions[i]).sum::<f64>() / runs.len() as f64;
                let (mean, error) = mean_and_error(&e);
                mode_rows.push(vec![index as f64, k / kc, c, mean, error]);
            }
        }
        if index == 0 {
            let s = &shells[0];
            let (m, e) = s.measured.unwrap_or((f64::NAN, f64::NAN));
            lowest = (m, e, s.theory);
        }
        let mut points = Vec::new();
        for s in &shells {
            let (measured, error) = s.measured.unwrap_or((f64::NAN, f64::NAN));
            rows.push(vec![
                case.dimension as f64,
                case.phi,
                case.eps,
                matches!(case.method, Method::Dsmc { .. }) as u8 as f64,
                case.particles() as f64,
                case.boxes,
                case.seeds as f64,
                c_end,
                s.k_over_kc,
                measured,
                error,
                s.theory,
            ]);
            // Near k_c (k^2 > 0.8 k_c^2) the theory's rate tends to 0 and a relative
            // difference means nothing: such shells are shown, not counted.
            let counted = s.k_over_kc.powi(2) <= 0.8;
            let cells = if s.measured.is_some() {
                let difference = measured / s.theory - 1.0;
                points.push((s.k_over_kc.powi(2), measured / scale, error / scale));
                if counted {
                    measured_shells += 1;
                    if difference.abs() < 0.15 {
                        within += 1;
                    }
                    worst = worst.max(difference.abs());
                }
                format!(
                    "{measured:.4} ± {error:.4} | {:.4} | {:+.1} %",
                    s.theory,
                    100.0 * difference
                )
            } else {
                format!("grew less than e^{MIN_GROWTH} | {:.4} | —", s.theory)
            };
            let _ = writeln!(
                table,
                "| {} | {} | {} | {} | {} | {:.0} | {:.3} | {cells} |",
                case.label,
                case.method_name(),
                case.particles(),
                case.boxes,
                case.seeds,
                c_end,
                s.k_over_kc,
            );
        }
        if let Some(line) = straight_line(&shells, scale) {
            let _ = writeln!(
                summary_table,
                "| {} | {} | {:.2} | {:.3} ± {:.3} | {:.3} ± {:.3} | {:.3} |",
                case.label,
                case.method_name(),
                kc * case.mean_free_path(),
                line.intercept,
                line.intercept_error,
                line.slope,
                line.slope_error,
                (line.slope / line.intercept).sqrt(),
            );
        }
        fig = fig.measured(
            format!(
                "{}, {} ({} seeds)",
                case.label,
                case.method_name(),
                case.seeds
            ),
            points,
        );
        if index == 0 {
            // The 2D eMD case at phi = 0.05, eps = 0.9 (box 4 L_c), against Haff's law.
            unstable_runs.push((case, runs));
        }
    }
    fig = fig.theory("theory 1 - (k/k_c)^2", vec![(0.0, 1.0), (1.0, 0.0)]);
    let mut files = vec![ctx.csv(
        id,
        &[
            "dimension",
            "packing_fraction",
            "restitution",
            "dsmc",
            "particles",
            "box_over_lc",
            "seeds",
            "fit_end_collisions",
            "k_over_kc",
            "growth_per_collision",
            "growth_error",
            "growth_theory",
        ],
        &rows,
    )?];
    files.push(ctx.figure(id, &fig)?);
    files.push(ctx.csv(
        &format!("{id}-modes"),
        &[
            "case",
            "k_over_kc",
            "collisions_per_particle",
            "transverse_energy",
            "transverse_energy_error",
        ],
        &mode_rows,
    )?);

    // Below L_c: stationary modes; the temperature above and below L_c against Haff.
    let stable = stable_case(ctx.quick);
    let stable_runs: Vec<Run> = (0..stable.seeds)
        .map(|s| simulate(&stable, 2000 + s))
        .collect::<Result<_>>()?;
    let late: Vec<f64> = stable_runs
        .iter()
        .flat_map(|r| {
            let e = &r.energies[0];
            e[e.len() / 2..].to_vec()
        })
        .collect();
    let (stationary, stationary_error) = mean_and_error(&late);
    // The samples of one run are correlated over ~1/|lambda| collisions: the error of the
    // mean is taken from the scatter of the per-seed means instead.
    let per_seed: Vec<f64> = stable_runs
        .iter()
        .map(|r| {
            let e = &r.energies[0];
            e[e.len() / 2..].iter().sum::<f64>() / (e.len() - e.len() / 2) as f64
        })
        .collect();
    let (_, stationary_error_seeds) = mean_and_error(&per_seed);
    let stationary_error = stationary_error.max(stationary_error_seeds);
    let kc_ratio = stable.boxes; // k_c / k of the lowest shell (k = 2 pi / L)
    let stationary_theory = 1.0 / (1.0 - kc_ratio * kc_ratio);

    let theory = stable.theory();
    let below = haff_ratio(&stable_runs, &theory);
    let (unstable_case, unstable) = unstable_runs.pop().expect("the 2D eMD case runs");
    let above = haff_ratio(&unstable, &unstable_case.theory());
    let onset = above
        .iter()
        .find(|p| p.1 > 1.05)
        .map(|p| p.0)
        .unwrap_or(f64::NAN);
    let nonlinear = unstable
        .iter()
        .map(|r| r.collisions[linear_window(r).min(r.collisions.len() - 1)])
        .sum::<f64>()
        / unstable.len() as f64;
    let haff_rows: Vec<Vec<f64>> = above
        .iter()
        .zip(&below)
        .map(|(a, b)| vec![a.0, a.1, a.2, b.0, b.1, b.2])
        .collect();
    files.push(ctx.csv(
        &format!("{id}-haff"),
        &[
            "collisions_above",
            "t_over_haff_above",
            "error_above",
            "collisions_below",
            "t_over_haff_below",
            "error_below",
        ],
        &haff_rows,
    )?);
    let haff_fig = Figure::new(
        "T / T_Haff, 2D eMD, phi = 0.05, eps = 0.9: boxes above and below L_c",
        "collisions per particle",
        "T / T_Haff",
    )
    .line(
        format!(
            "box 4 L_c (N = {}), mean of {} seeds",
            unstable_case.particles(),
            unstable.len()
        ),
        above.iter().map(|p| (p.0, p.1)).collect(),
    )
    .line(
        format!(
            "box L_c / 2 (N = {}), mean of {} seeds",
            stable.particles(),
            stable_runs.len()
        ),
        below.iter().map(|p| (p.0, p.1)).collect(),
    )
    .theory(
        "Haff's law (= 1)",
        vec![(0.0, 1.0), (unstable_case.collisions, 1.0)],
    );
    files.push(ctx.figure(&format!("{id}-haff"), &haff_fig)?);
    let below_end = below.last().map(|p| (p.1, p.2)).unwrap_or((f64::NAN, 0.0));

    let md = format!(
        "# {id}: the shear instability of the homogeneous cooling state\n\n\
         **Paper.** Navier–Stokes hydrodynamics with the Enskog shear viscosity of inelastic \
         hard disks/spheres in the first Sonine approximation (Garzó & Dufty 1999 in D \
         dimensions; `gas::theory::HcsTransport`): the scaled transverse velocity grows at \
         s(k) = zeta/2 - nu k^2, so the normalized energy of a transverse mode grows per \
         collision per particle as exp(lambda c), lambda = 2 s / omega = (zeta/omega) \
         (1 - (k/k_c)^2). For spatial DSMC (the Boltzmann operator with the Enskog factor, \
         no collisional transfer) the same with the dilute coefficients and every rate times \
         chi (`HcsTransport::enskog_factor_dsmc`).\n\n\
         **We get** (fit of E(c) = A exp(lambda c) - B to the seed-averaged energies, up to the onset of the \
         nonlinear regime where the lowest shell reaches N/200; mean ± jackknife error over \
         seeds):\n\n{table}\n\
         {within} of {measured_shells} shells within 15 % of theory; the largest difference \
         is {}.\n\n\
         A straight line lambda / (zeta/omega) = a - b (k/k_c)^2 through each case's \
         shells (weighted by their errors) reads the measurement as an effective cooling \
         term a and viscosity b = nu_eff / nu (theory: a = b = 1), and the critical length \
         as L_c sqrt(b / a):\n\n{summary_table}\n\
         **Below L_c** (box L_c / 2, N = {}, {} seeds): the lowest transverse mode stays at \
         {} ± {} (stationary value of fluctuating hydrodynamics 1/(1 - (k_c/k)^2) = {}), and \
         T / T_Haff = {} ± {} after {} collisions per particle.\n\n\
         **Above L_c** (box 4 L_c): T / T_Haff exceeds 1.05 at c = {} collisions per \
         particle; the lowest shell reaches N/200 (the end of the fits) at c = {} on \
         average. The shear flow's kinetic energy decays only viscously, slower than the \
         thermal energy, so the gas cools slower than Haff's law once the vortices hold a \
         few per cent of the energy.\n\n\
         **Difference.** Long waves (k <= k_c/2) agree within 15 % but for a few shells; \
         toward k_c the measured growth falls below theory, as if the viscosity were larger \
         (b > 1 in the table). eMD and spatial DSMC at the same phi and eps agree with each \
         other there, so the excess belongs to neither engine: the theory is first order in \
         the gradients (Navier–Stokes) and first Sonine, and the excess is largest where \
         k_c lambda is (Burnett terms ~ (k lambda)^2). DSMC's cells add a numerical \
         viscosity, a factor 1 + 16/(75 pi) (cell / lambda)^2 (Alexander, Garcia & Alder \
         1998; 3D): 1.7 % for cells of half a mean free path, far less than the excess.\n",
        sig(worst),
        stable.particles(),
        stable.seeds,
        sig(stationary),
        sig(stationary_error),
        sig(stationary_theory),
        sig(below_end.0),
        sig(below_end.1),
        stable.collisions,
        sig(onset),
        sig(nonlinear),
    );
    files.push(ctx.markdown(id, &md)?);
    Ok(Outcome {
        summary: format!(
            "{within} of {measured_shells} shells within 15 % of the growth rate from theory \
             (worst {}); below L_c the mode stays at {} (theory {})",
            sig(worst),
            sig(stationary),
            sig(stationary_theory)
        ),
        values: vec![
            ("lowest_shell_growth", lowest.0),
            ("lowest_shell_growth_error", lowest.1),
            ("lowest_shell_growth_theory", lowest.2),
            ("worst_relative_difference", worst),
            ("shells_within_15_percent", within as f64),
            ("shells_measured", measured_shells as f64),
            ("stationary_energy_below", stationary),
            ("stationary_energy_below_error", stationary_error),
            ("stationary_energy_theory", stationary_theory),
            ("haff_onset_collisions", onset),
        ],
        files,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fit recovers lambda and B of noiseless data E = A e^{lambda c} - B, for a fast
    /// mode and for a slow one whose noise term dominates early.
    #[test]
    fn fit_recovers_a_known_growth() {
        for (lambda, b) in [(0.09, 0.07), (0.03, 1.3)] {
            let points: Vec<(f64, f64)> = (0..60)
                .map(|i| {
                    let c = i as f64;
                    (c, (1.0 + b) * (lambda * c).exp() - b)
                })
                .collect();
            let (fitted, noise) = fit_growth(&points).unwrap();
            assert!((fitted / lambda - 1.0).abs() < 1e-6, "{fitted} vs {lambda}");
            assert!((noise / b - 1.0).abs() < 1e-4, "{noise} vs {b}");
        }
    }
}
