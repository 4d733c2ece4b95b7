//! Self-diffusion of inelastic hard spheres in the homogeneous cooling state, from the
//! mean-square displacement (`output.msd`): the event-driven engine across alpha and phi
//! and the spatial DSMC of the dilute gas, side by side, against the Enskog self-diffusion
//! coefficient in the first Sonine approximation (`gas::theory::ReducedTransport`:
//! D* = (D+2)/(2D) / (chi (nu_D* - zeta*/2)), Brey, Ruiz-Montero, Cubero & Garcia-Rojo 2000).
//!
//! Method. In the HCS the reduced coefficient D* is constant while T falls, so
//! msd(t) = 2D int_0^t D_s(T(t')) dt' with D_s(T) = D* D0(T) ∝ sqrt(T): the slope of msd
//! against 2D I(t), I(t) = int_0^t D_E(T(t')) dt' (the theory's coefficient at the measured
//! temperature, integrated by the trapezoid over the samples, linear in collisions), is the
//! measured coefficient over the theory's, whatever the cooling. The slope is fitted over
//! the second half of I (past the ballistic start and the relaxation to the HCS's
//! distribution); its error from the spread over seeds. Units: sigma = m = T0 = 1; 3D.

use super::{sig, Context, Entry, Outcome};
use sim::error::Result;
use sim::plot::Figure;
use sim::Simulation;
use std::fmt::Write as _;

const PAPER: &str =
    "Self-diffusion in the HCS (Brey, Ruiz-Montero, Cubero & Garcia-Rojo 2000; Garzo & Montanero 2004)";

pub fn entries() -> Vec<Entry> {
    vec![Entry {
        id: "kinetic-diffusion",
        paper: PAPER,
        item: "self-diffusion vs alpha and phi",
        shows: "D_s / D_Enskog (first Sonine) from the mean-square displacement in the HCS: \
                event-driven at phi = 0.01, 0.1, 0.2 and spatial DSMC of the dilute gas",
        typical_seconds: 200.0,
        run: diffusion,
    }]
}

/// One configuration of the study.
#[derive(Debug, Clone, Copy)]
struct Case {
    /// 0: event-driven; k > 0: spatial DSMC with k simulated particles per physical one.
    refine: usize,
    phi: f64,
    /// Physical particles.
    particles: usize,
    /// Only at alpha = 1.
    elastic_only: bool,
}

impl Case {
    fn new(refine: usize, phi: f64, particles: usize) -> Self {
        Case {
            refine,
            phi,
            particles,
            elastic_only: false,
        }
    }

    fn dsmc(&self) -> bool {
        self.refine > 0
    }
}

/// The `[run]` lines of a case: the spatial DSMC in cells of a third of the mean free path
/// at phi = 0.01 (lambda = 11.8), as `sim/tests/diffusion.rs`.
fn run_lines(case: Case) -> String {
    if case.dsmc() {
        format!(
            "engine = \"dsmc\"\ndsmc_scheme = \"spatial\"\nparticle_weight = {}\n\
             collision_cell_width = 4.0\n",
            1.0 / case.refine as f64
        )
    } else {
        "engine = \"event-driven\"\n".into()
    }
}

/// D_s / D_Enskog of one run of `collisions` collisions per particle (see the module
/// documentation).
fn ratio(case: Case, alpha: f64, collisions: f64, seed: u64) -> Result<f64> {
    let samples = (2.0 * collisions).round() as usize;
    let simulated = case.particles * case.refine.max(1);
    let text = format!(
        "[system]\ndimension = 3\nparticles = {simulated}\npacking_fraction = {}\nseed = {seed}\n\
         [collision]\nlaw = \"constant\"\nrestitution = {alpha}\n\
         [run]\n{}collisions_per_particle = {collisions}\nsamples = {samples}\n\
         spacing = \"linear\"\n\
         [output]\nmsd = true\n",
        case.phi,
        run_lines(case)
    );
    let mut run = Simulation::from_toml(&text, "diffusion.toml".as_ref())?;
    run.run(&mut (), None)?;
    let density = 6.0 * case.phi / std::f64::consts::PI;
    let theory = |t: f64| {
        gas::theory::NavierStokes::enskog::<3>(density, 1.0, 1.0, t, case.phi, alpha).self_diffusion
    };
    let samples = run.samples();
    let msd = &run.msd().expect("output.msd measures the msd").samples;
    // I(t_k) by the trapezoid over the samples' temperatures.
    let mut integral = vec![0.0; samples.len()];
    for k in 1..samples.len() {
        let dt = samples[k].time - samples[k - 1].time;
        integral[k] = integral[k - 1]
            + 0.5 * dt * (theory(samples[k].temperature) + theory(samples[k - 1].temperature));
    }
    let last = integral[integral.len() - 1];
    let points: Vec<(f64, f64)> = integral
        .iter()
        .zip(msd)
        .filter(|(i, _)| **i >= 0.5 * last)
        .map(|(i, row)| (6.0 * i, row.msd))
        .collect();
    Ok(super::slope(&points))
}

/// The box side over the critical length 2 pi / k_perp of the HCS's transverse (shear)
/// mode, k_perp^2 = zeta n m / (2 eta) (Brey, Ruiz-Montero & Cubero 1998; Goldhirsch &
/// Zanetti 1993): with eta = eta* eta0, zeta = zeta* n T / eta0 and
/// eta0 = 5 / (16 sigma^2) (m T / pi)^(1/2), k_perp sigma = n sigma^3 (128 pi zeta* / (25 eta*))^(1/2).
/// Above 1 the shear mode grows and the gas leaves the HCS (vortices, then clusters).
fn box_over_critical(case: Case, alpha: f64) -> f64 {
    let r = gas::theory::ReducedTransport::enskog::<3>(case.phi, alpha);
    let n = 6.0 * case.phi / std::f64::consts::PI;
    let k = n * (128.0 * std::f64::consts::PI * r.cooling_rate / (25.0 * r.shear_viscosity)).sqrt();
    let side = (case.particles as f64 / n).cbrt();
    side * k / (2.0 * std::f64::consts::PI)
}

/// The relative shift of D_s by the periodic box, xi T / (6 pi eta L) over Enskog's D_s
/// (Yeh & Hummer 2004, xi = 2.837297 for a cubic box), at T = 1 in the elastic gas.
fn finite_size_shift(case: Case) -> f64 {
    let n = 6.0 * case.phi / std::f64::consts::PI;
    let ns = gas::theory::NavierStokes::enskog::<3>(n, 1.0, 1.0, 1.0, case.phi, 1.0);
    let side = (case.particles as f64 / n).cbrt();
    2.837297 / (6.0 * std::f64::consts::PI * ns.shear_viscosity * side) / ns.self_diffusion
}

fn diffusion(ctx: &Context) -> Result<Outcome> {
    let id = "kinetic-diffusion";
    let alphas: &[f64] = if ctx.quick {
        &[1.0, 0.9, 0.8, 0.7, 0.6]
    } else {
        &[1.0, 0.9, 0.8, 0.7, 0.6, 0.5]
    };
    let (seeds, collisions) = if ctx.quick { (3, 40.0) } else { (6, 60.0) };
    let cases: Vec<Case> = if ctx.quick {
        vec![Case::new(0, 0.01, 2000), Case::new(8, 0.01, 2000)]
    } else {
        vec![
            Case::new(0, 0.01, 4000),
            Case::new(8, 0.01, 4000),
            Case {
                elastic_only: true,
                ..Case::new(32, 0.01, 4000)
            },
            Case::new(0, 0.1, 2000),
            Case::new(0, 0.2, 2000),
        ]
    };
    let mut md = format!(
        "# kinetic-diffusion: self-diffusion in the homogeneous cooling state (3D)\n\n\
         **Paper.** The self-diffusion coefficient of inelastic hard spheres in the first \
         Sonine approximation, D* = (D+2)/(2D) / (chi (nu_D* - zeta*/2)) in units of the \
         elastic dilute D0 (Brey, Ruiz-Montero, Cubero & Garcia-Rojo 2000; Garzo & \
         Montanero 2004 compare it with a second Sonine approximation and DSMC). \
         `gas::theory::ReducedTransport`. L / L_c: the box over the critical length of \
         the HCS's shear mode (above 1 the cooling gas forms vortices, then clusters).\n\n\
         **We get** D_s / D_Enskog: the slope of the mean-square displacement against 2D \
         times the theory's coefficient integrated over the measured cooling (module \
         documentation of `reproduce::diffusion`), {collisions} collisions per particle, \
         the second half fitted, mean and standard error over {seeds} seeds. Spatial DSMC: \
         cells of a third of the mean free path, k simulated particles per physical one \
         (about 1.2 k per cell).\n\n\
         | method | phi | N | alpha | L / L_c | D* Enskog (first Sonine) | D_s / D_Enskog |\n\
         |---|---|---|---|---|---|---|\n"
    );
    let (rows, figure, results) = measure_all(&cases, alphas, seeds, collisions, &mut md)?;
    let (elastic, values) = difference(&cases, alphas, &results, &mut md);
    let files = vec![
        ctx.csv(
            id,
            &[
                "dsmc",
                "refine",
                "phi",
                "alpha",
                "ratio",
                "ratio_error",
                "theory",
                "box_over_critical",
            ],
            &rows,
        )?,
        ctx.figure(id, &figure)?,
        ctx.markdown(id, &md)?,
    ];
    Ok(Outcome {
        summary: format!(
            "self-diffusion in the HCS at {} alphas; dilute DSMC elastic / first Sonine = {:.4}",
            alphas.len(),
            elastic
        ),
        values,
        files,
    })
}

/// Each case at each alpha over the seeds: the table's rows (into `md`), the CSV rows, the
/// figure, and (case index, alpha, mean, error) of each.
#[allow(clippy::type_complexity)]
fn measure_all(
    cases: &[Case],
    alphas: &[f64],
    seeds: usize,
    collisions: f64,
    md: &mut String,
) -> Result<(Vec<Vec<f64>>, Figure, Vec<(usize, f64, f64, f64)>)> {
    let mut rows = Vec::new();
    let mut figure = Figure::new(
        "Self-diffusion in the HCS over Enskog's first Sonine value",
        "alpha",
        "D_s / D_Enskog",
    );
    // (case index, alpha) -> (mean, error)
    let mut results: Vec<(usize, f64, f64, f64)> = Vec::new();
    for (c, &case) in cases.iter().enumerate() {
        let mut points = Vec::new();
        for &alpha in alphas.iter().filter(|&&a| a == 1.0 || !case.elastic_only) {
            let values = (0..seeds)
                .map(|s| ratio(case, alpha, collisions, 31 + s as u64))
                .collect::<Result<Vec<f64>>>()?;
            let (mean, error) = super::mean_and_error(&values);
            let reduced =
                gas::theory::ReducedTransport::enskog::<3>(case.phi, alpha).self_diffusion;
            let method = if case.dsmc() {
                format!("spatial DSMC, k = {}", case.refine)
            } else {
                "event-driven".into()
            };
            let critical = box_over_critical(case, alpha);
            let _ = writeln!(
                *md,
                "| {method} | {} | {} | {alpha} | {:.2} | {} | {} ± {} |",
                case.phi,
                case.particles,
                critical,
                sig(reduced),
                sig(mean),
                sig(error)
            );
            rows.push(vec![
                case.dsmc() as u8 as f64,
                case.refine as f64,
                case.phi,
                alpha,
                mean,
                error,
                reduced,
                critical,
            ]);
            points.push((alpha, mean, error));
            results.push((c, alpha, mean, error));
        }
        let name = if case.dsmc() {
            format!("spatial DSMC, phi = {}, k = {}", case.phi, case.refine)
        } else {
            format!("event-driven, phi = {}", case.phi)
        };
        figure = figure.measured(name, points);
    }
    figure = figure.theory(
        "Enskog, first Sonine",
        vec![(alphas[alphas.len() - 1], 1.0), (1.0, 1.0)],
    );
    Ok((rows, figure, results))
}

/// The note's **Difference** (into `md`): the engines against each other and the theory,
/// the DSMC's particles per cell, the dense gas, the instability. Returns the elastic
/// DSMC's ratio and the outcome's values.
fn difference(
    cases: &[Case],
    alphas: &[f64],
    results: &[(usize, f64, f64, f64)],
    md: &mut String,
) -> (f64, Vec<(&'static str, f64)>) {
    let find = |c: usize, alpha: f64| {
        results
            .iter()
            .find(|r| r.0 == c && r.1 == alpha)
            .map(|r| (r.2, r.3))
            .expect("every case at every alpha")
    };
    // The dilute gas: event-driven (case 0) against DSMC (case 1) at every alpha.
    let largest_difference = alphas
        .iter()
        .map(|&a| {
            let (e, ee) = find(0, a);
            let (d, de) = find(1, a);
            (e - d).abs() / (ee * ee + de * de).sqrt()
        })
        .fold(0.0, f64::max);
    let (elastic, elastic_error) = find(1, 1.0);
    let (elastic_md, elastic_md_error) = find(0, 1.0);
    let lowest = alphas[alphas.len() - 1];
    let (inelastic, inelastic_error) = find(1, lowest);
    let (inelastic_md, inelastic_md_error) = find(0, lowest);
    let _ = write!(
        *md,
        "\n**Difference.** The elastic dilute gas: DSMC (k = 8) {} ± {}, event-driven {} ± \
         {} of the first Sonine value, where Chapman-Enskog's converged series is 1.01896 \
         times it (Alder, Gass & Wainwright 1970; `sim/tests/diffusion.rs` holds both \
         engines to it). At alpha = {lowest}: DSMC {} ± {}, event-driven {} ± {}; the two \
         engines agree within {} combined standard errors at every alpha. The first Sonine \
         value's error thus changes with alpha by the difference of these (the second \
         Sonine correction, not computed here).",
        sig(elastic),
        sig(elastic_error),
        sig(elastic_md),
        sig(elastic_md_error),
        sig(inelastic),
        sig(inelastic_error),
        sig(inelastic_md),
        sig(inelastic_md_error),
        sig(largest_difference)
    );
    let extrapolated = refined(cases, (elastic, elastic_error), &find, md);
    for (c, &case) in cases
        .iter()
        .enumerate()
        .filter(|(_, c)| !c.dsmc() && c.phi > 0.05)
    {
        let (e, ee) = find(c, 1.0);
        let _ = write!(
            *md,
            " At phi = {} the elastic event-driven gas gives {} ± {} of Enskog's first \
             Sonine value: Enskog leaves out the correlated motion of the surrounding fluid \
             (backflow) that raises D at moderate density (Alder, Gass & Wainwright 1970); \
             the periodic box of {} spheres lowers D by about {} % (Yeh & Hummer 2004), so \
             the infinite gas lies further above.",
            case.phi,
            sig(e),
            sig(ee),
            case.particles,
            sig(100.0 * finite_size_shift(case))
        );
    }
    let _ = writeln!(
        *md,
        " Inelastic gases at finite density in boxes near or above the shear mode's critical \
         length (L / L_c in the table) leave the HCS: their vortices carry spheres \
         together and the mean-square displacement grows faster than diffusion, hence \
         ratios far above 1; those rows measure the instability, not D.\n"
    );
    let mut values = vec![
        ("dilute_dsmc_elastic_over_first_sonine", elastic),
        ("dilute_dsmc_elastic_error", elastic_error),
        ("dilute_md_elastic_over_first_sonine", elastic_md),
        ("dilute_md_elastic_error", elastic_md_error),
        ("largest_engine_difference_in_errors", largest_difference),
        ("dilute_dsmc_lowest_alpha_over_first_sonine", inelastic),
        ("dilute_dsmc_lowest_alpha_error", inelastic_error),
    ];
    if let Some((limit, error)) = extrapolated {
        values.push(("dilute_dsmc_elastic_extrapolated", limit));
        values.push(("dilute_dsmc_elastic_extrapolated_error", error));
    }
    (elastic, values)
}

/// The elastic DSMC with more particles per cell (into `md`), and the extrapolation of
/// the k = 8 and finer values to infinitely many; None without a finer case.
fn refined(
    cases: &[Case],
    (elastic, elastic_error): (f64, f64),
    find: &dyn Fn(usize, f64) -> (f64, f64),
    md: &mut String,
) -> Option<(f64, f64)> {
    let c = cases.iter().position(|c| c.refine > 8)?;
    let (e, ee) = find(c, 1.0);
    // The excess as 1 / (particles per cell): D(k) = D_inf + b / k, from k = 8 and k.
    let q = cases[c].refine as f64 / 8.0;
    let limit = (q * e - elastic) / (q - 1.0);
    let limit_error = (q * q * ee * ee + elastic_error * elastic_error).sqrt() / (q - 1.0);
    let _ = write!(
        *md,
        " With k = {} (about {:.0} particles per cell) the elastic DSMC gives {} ± {}: the \
         DSMC's excess over Chapman-Enskog falls as one over the particles per cell, and \
         extrapolated so (D(k) = D_inf + b / k) it is {} ± {} against Chapman-Enskog's 1.01896. \
         The excess is DSMC's: the momentum a particle gives its partners stays among the \
         few particles of its cell, which collide with it again before they part (a \
         correlation of order one over the particles per cell that lengthens the velocity \
         memory); Rader, Gallis, Torczynski & Wagner (2006) measured such a convergence \
         in the particles per cell for DSMC's conductivity.",
        cases[c].refine,
        1.2 * cases[c].refine as f64,
        sig(e),
        sig(ee),
        sig(limit),
        sig(limit_error)
    );
    Some((limit, limit_error))
}
