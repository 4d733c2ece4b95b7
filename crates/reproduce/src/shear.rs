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
use sim::error::Result;
use sim::plot::Figure;
use std::fmt::Write as _;

mod cases;
mod fit;

use cases::{cases, simulate, stable_case, Case, Method, Run};
use fit::{growth_rates, haff_ratio, linear_window, straight_line, MIN_GROWTH};

const PAPER: &str = "Shear instability (Goldhirsch & Zanetti 1993; Garzó & Dufty 1999)";

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

fn shear(ctx: &Context) -> Result<Outcome> {
    let id = "kinetic-shear";
    let growth = Growth::of_cases(ctx.quick)?;
    let mut files = growth.write(ctx, id)?;
    let below = Below::measure(ctx.quick)?;
    let (haff, haff_files) = HaffComparison::write(ctx, id, &growth, &below)?;
    files.extend(haff_files);
    files.push(ctx.markdown(id, &markdown(id, &growth, &below, &haff))?);
    Ok(outcome(&growth, &below, &haff, files))
}

/// A case's label and its points ((k/k_c)^2, lambda / (zeta/omega), error).
type Series = (String, Vec<(f64, f64, f64)>);

/// The growth rates of every case: the rows of `ID.csv`, the tables of `ID.md`, the
/// figure's series, the modes' energies of `ID-modes.csv` and the counts against theory.
struct Growth {
    rows: Vec<Vec<f64>>,
    /// The figure's points of each case.
    series: Vec<Series>,
    summary_table: String,
    table: String,
    worst: f64,
    within: usize,
    measured_shells: usize,
    /// The 2D eMD case at phi = 0.05, eps = 0.9 (box 4 L_c) and its runs.
    unstable: Option<(Case, Vec<Run>)>,
    /// The lowest shell of the first case (2D eMD, phi = 0.05, eps = 0.9): (measured,
    /// error, theory).
    lowest: (f64, f64, f64),
    mode_rows: Vec<Vec<f64>>,
}

impl Growth {
    fn of_cases(quick: bool) -> Result<Self> {
        let mut growth = Growth {
            rows: Vec::new(),
            series: Vec::new(),
            summary_table: String::from(
                "| case | method | k_c lambda | a (theory 1) | b = nu_eff / nu (theory 1) | L_c measured / theory |\n\
                 |---|---|---|---|---|---|\n",
            ),
            table: String::from(
                "| case | method | N | L / L_c | seeds | fit to c | k / k_c | lambda measured | theory | difference |\n\
                 |---|---|---|---|---|---|---|---|---|---|\n",
            ),
            worst: 0.0,
            within: 0,
            measured_shells: 0,
            unstable: None,
            lowest: (f64::NAN, f64::NAN, f64::NAN),
            mode_rows: Vec::new(),
        };
        for (index, case) in cases(quick).into_iter().enumerate() {
            growth.add_case(index, case)?;
        }
        Ok(growth)
    }

    /// Runs the case number `index` and adds its shells.
    fn add_case(&mut self, index: usize, case: Case) -> Result<()> {
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
                self.mode_rows
                    .push(vec![index as f64, k / kc, c, mean, error]);
            }
        }
        if index == 0 {
            let s = &shells[0];
            let (m, e) = s.measured.unwrap_or((f64::NAN, f64::NAN));
            self.lowest = (m, e, s.theory);
        }
        let mut points = Vec::new();
        for s in &shells {
            let (measured, error) = s.measured.unwrap_or((f64::NAN, f64::NAN));
            self.rows.push(vec![
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
                    self.measured_shells += 1;
                    if difference.abs() < 0.15 {
                        self.within += 1;
                    }
                    self.worst = self.worst.max(difference.abs());
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
                self.table,
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
                self.summary_table,
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
        self.series.push((
            format!(
                "{}, {} ({} seeds)",
                case.label,
                case.method_name(),
                case.seeds
            ),
            points,
        ));
        if index == 0 {
            // The 2D eMD case at phi = 0.05, eps = 0.9 (box 4 L_c), against Haff's law.
            self.unstable = Some((case, runs));
        }
        Ok(())
    }

    /// The 2D eMD case above L_c and its runs.
    fn unstable(&self) -> (&Case, &[Run]) {
        let (case, runs) = self.unstable.as_ref().expect("the 2D eMD case runs");
        (case, runs)
    }

    /// Writes `ID.csv`, the figure and `ID-modes.csv`.
    fn write(&self, ctx: &Context, id: &str) -> Result<Vec<std::path::PathBuf>> {
        let (rows, mode_rows) = (&self.rows, &self.mode_rows);
        let mut fig = Figure::new(
            "Shear mode of the HCS: growth per collision / (zeta/omega) vs (k/k_c)^2 (± jackknife errors)",
            "(k / k_c)^2",
            "lambda / (zeta / omega)",
        );
        for (label, points) in &self.series {
            fig = fig.measured(label.clone(), points.clone());
        }
        let fig = &fig.theory("theory 1 - (k/k_c)^2", vec![(0.0, 1.0), (1.0, 0.0)]);
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
            rows,
        )?];
        files.push(ctx.figure(id, fig)?);
        files.push(ctx.csv(
            &format!("{id}-modes"),
            &[
                "case",
                "k_over_kc",
                "collisions_per_particle",
                "transverse_energy",
                "transverse_energy_error",
            ],
            mode_rows,
        )?);
        Ok(files)
    }
}

/// Below L_c (box L_c / 2): the lowest transverse mode's stationary energy against
/// fluctuating hydrodynamics.
struct Below {
    stable: Case,
    runs: Vec<Run>,
    stationary: f64,
    stationary_error: f64,
    stationary_theory: f64,
}

impl Below {
    fn measure(quick: bool) -> Result<Self> {
        let stable = stable_case(quick);
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
        // The samples of one run are correlated over ~1/|lambda| collisions: the error of
        // the mean is taken from the scatter of the per-seed means instead.
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
        Ok(Below {
            stable,
            runs: stable_runs,
            stationary,
            stationary_error,
            stationary_theory,
        })
    }
}

/// The temperature above and below L_c against Haff's law: where the gas departs from it,
/// and where the fits end.
struct HaffComparison {
    onset: f64,
    nonlinear: f64,
    /// T / T_Haff and its error at the last sample below L_c.
    below_end: (f64, f64),
}

impl HaffComparison {
    /// Compares, and writes `ID-haff.csv` and its figure.
    fn write(
        ctx: &Context,
        id: &str,
        growth: &Growth,
        below_lc: &Below,
    ) -> Result<(Self, Vec<std::path::PathBuf>)> {
        let (stable, stable_runs) = (&below_lc.stable, &below_lc.runs);
        let theory = stable.theory();
        let below = haff_ratio(stable_runs, &theory);
        let (unstable_case, unstable) = growth.unstable();
        let above = haff_ratio(unstable, &unstable_case.theory());
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
        let mut files = vec![ctx.csv(
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
        )?];
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
        let comparison = HaffComparison {
            onset,
            nonlinear,
            below_end,
        };
        Ok((comparison, files))
    }
}

/// `ID.md`: what theory says, what the runs give, where and why they differ.
fn markdown(id: &str, growth: &Growth, below: &Below, haff: &HaffComparison) -> String {
    let Growth {
        table,
        summary_table,
        within,
        measured_shells,
        worst,
        ..
    } = growth;
    let (stable, stationary, stationary_error, stationary_theory) = (
        &below.stable,
        below.stationary,
        below.stationary_error,
        below.stationary_theory,
    );
    let HaffComparison {
        onset,
        nonlinear,
        below_end,
    } = *haff;
    format!(
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
        sig(*worst),
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
    )
}

/// The summary line and the values of the item.
fn outcome(
    growth: &Growth,
    below: &Below,
    haff: &HaffComparison,
    files: Vec<std::path::PathBuf>,
) -> Outcome {
    let (worst, within, measured_shells, lowest) = (
        growth.worst,
        growth.within,
        growth.measured_shells,
        growth.lowest,
    );
    let (stationary, stationary_error, stationary_theory) = (
        below.stationary,
        below.stationary_error,
        below.stationary_theory,
    );
    let onset = haff.onset;
    Outcome {
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
    }
}
