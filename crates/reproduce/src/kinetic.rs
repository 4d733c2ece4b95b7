//! Kinetic theory of granular gases against haff's engines: Haff's law in time (eMD and
//! DSMC), a2 of the homogeneous cooling state against the first (van Noije & Ernst 1998) and
//! second Sonine approximations, and the
//! t^(-5/3) cooling of viscoelastic spheres (Brilliantov & Pöschel, *Kinetic Theory of
//! Granular Gases*, Oxford 2004, Chs. 7, 8). Units: sigma = m = T0 = 1, 3D.

use super::{mean_and_error, sig, Context, Entry, Outcome};
use gas::dsmc::{point_gas, Scheme};
use gas::observe::{sonine_a2, temperature};
use gas::theory::{collision_frequency, second_sonine, van_noije_ernst_a2, SonineHierarchy};
use restitution::{Constant, Restitution, ScaledForm, Viscoelastic};
use sim::driver::Driven;
use sim::engines::{self, EngineSpec, Setup};
use sim::error::Result;
use sim::plot::Figure;
use sim::schedule::{Measure, Schedule};

const PAPER: &str = "Kinetic theory (Brilliantov & Pöschel 2004; van Noije & Ernst 1998)";

pub fn entries() -> Vec<Entry> {
    vec![
        Entry {
            id: "kinetic-haff",
            paper: PAPER,
            item: "Haff's law",
            shows: "T(t)/T_Haff of eMD and DSMC, eps = 0.9, phi = 0.05, no fitted parameter",
            typical_seconds: 6.0,
            run: haff,
        },
        Entry {
            id: "kinetic-a2",
            paper: PAPER,
            item: "a2(eps) of the HCS",
            shows: "a2 of the HCS by DSMC against the first and second Sonine approximations",
            typical_seconds: 20.0,
            run: a2,
        },
        Entry {
            id: "kinetic-viscoelastic",
            paper: PAPER,
            item: "viscoelastic cooling",
            shows: "T(t) of viscoelastic spheres (eMD and DSMC) and its t^(-5/3) tail",
            typical_seconds: 30.0,
            run: viscoelastic,
        },
    ]
}

fn engine_error(e: impl std::fmt::Display) -> sim::error::Error {
    super::numerical("engine", e)
}

/// The Enskog collision frequency at T = 1 in a gas of unit spheres at packing fraction phi.
fn enskog_frequency(phi: f64) -> f64 {
    let density = phi / gas::system::ball_volume::<3>(0.5);
    collision_frequency::<3>(density, 1.0, 1.0, 1.0, phi)
}

/// A homogeneous DSMC gas of `n` points (blocks scheme) with the given law.
fn dsmc(n: usize, phi: f64, law: Box<dyn Restitution>, seed: u64) -> Result<Box<dyn Driven<3>>> {
    let length = gas::system::monodisperse_box_side::<3>(n, 1.0, phi);
    let system = point_gas::<3>(n, [length; 3], 1.0, 1.0, 1.0, seed).map_err(engine_error)?;
    let spec = EngineSpec::HomogeneousDsmc(Scheme::default());
    engines::build(&spec, system, setup(law, phi, seed))
}

/// An eMD gas of `n` unit spheres at phi with the given law.
fn emd(n: usize, phi: f64, law: Box<dyn Restitution>, seed: u64) -> Result<Box<dyn Driven<3>>> {
    let system = gas::init::monodisperse::<3>(n, phi, 1.0, 1.0, 1.0, seed).map_err(engine_error)?;
    engines::build(&EngineSpec::EventDriven, system, setup(law, phi, seed))
}

fn setup(law: Box<dyn Restitution>, phi: f64, seed: u64) -> Setup {
    Setup {
        law,
        packing_fraction: phi,
        seed,
        baths: None,
    }
}

/// T at each of `times` (increasing), through the run driver.
fn temperatures(engine: Box<dyn Driven<3>>, times: &[f64]) -> Result<Vec<f64>> {
    let schedule = Schedule::samples_at(times, Measure::Time);
    sim::probe::sample(engine, schedule, |e| temperature(e.system()))
}

/// Haff's law T(t) = 1 / (1 + t/t0)^2, 1/t0 = zeta0/2, with the cooling rate of the HCS
/// zeta0 = (1 - eps^2)/3 omega_E (1 + 3 a2/16) (Brilliantov & Pöschel 2004, Ch. 7; the
/// collision frequency carries (1 - a2/16), the energy loss per collision (1 + 3a2/16)/
/// (1 - a2/16)), omega_E the Enskog frequency at T0 = 1.
fn haff(ctx: &Context) -> Result<Outcome> {
    let id = "kinetic-haff";
    let (eps, phi) = (0.9, 0.05);
    let (n_emd, seeds, n_dsmc) = if ctx.quick {
        (1000, 2, 20_000)
    } else {
        (4000, 8, 200_000)
    };
    let omega = enskog_frequency(phi);
    let maxwell_t0 = 6.0 / ((1.0 - eps * eps) * omega);
    let a2 = van_noije_ernst_a2::<3>(eps);
    let t0 = maxwell_t0 / (1.0 + 3.0 * a2 / 16.0);
    let ratios: Vec<f64> = (0..=12)
        .map(|k| 0.05 * 200f64.powf(k as f64 / 12.0))
        .collect();
    let times: Vec<f64> = ratios.iter().map(|r| r * t0).collect();
    let law = || -> Result<Box<dyn Restitution>> {
        Ok(Box::new(Constant::new(eps).map_err(engine_error)?))
    };
    let mut runs = Vec::new();
    for seed in 0..seeds {
        let e = emd(n_emd, phi, law()?, 100 + seed)?;
        runs.push(temperatures(e, &times)?);
    }
    let d = dsmc(n_dsmc, phi, law()?, 7)?;
    let dsmc_t = temperatures(d, &times)?;
    let haff_law = |t: f64, tau: f64| 1.0 / (1.0 + t / tau).powi(2);
    let mut rows = Vec::new();
    let (mut emd_curve, mut dsmc_curve, mut maxwell_curve) = (vec![], vec![], vec![]);
    let mut worst_early: f64 = 0.0;
    let mut worst_dsmc: f64 = 0.0;
    for (k, &t) in times.iter().enumerate() {
        let ts: Vec<f64> = runs.iter().map(|r| r[k]).collect();
        let (mean, error) = mean_and_error(&ts);
        let theory = haff_law(t, t0);
        let maxwell = haff_law(t, maxwell_t0);
        rows.push(vec![t / t0, t, mean, error, dsmc_t[k], theory, maxwell]);
        emd_curve.push((t / t0, mean / theory));
        dsmc_curve.push((t / t0, dsmc_t[k] / theory));
        maxwell_curve.push((t / t0, maxwell / theory));
        if t <= 4.0 * t0 {
            worst_early = worst_early.max((mean / theory - 1.0).abs());
        }
        worst_dsmc = worst_dsmc.max((dsmc_t[k] / theory - 1.0).abs());
    }
    let last = rows.last().expect("times").clone();
    let emd_late = last[2] / last[5];
    let mut files = vec![ctx.csv(
        id,
        &[
            "t_over_t0",
            "time",
            "temperature_emd",
            "temperature_emd_error",
            "temperature_dsmc",
            "haff",
            "haff_maxwellian",
        ],
        &rows,
    )?];
    let fig = Figure::new(
        "Haff's law, eps = 0.9, phi = 0.05: T / T_Haff (Enskog rate, HCS a2)",
        "t / t0",
        "T / T_Haff",
    )
    .log(true, false)
    .line(
        format!("eMD, N = {n_emd}, mean of {seeds} seeds"),
        emd_curve,
    )
    .line(format!("DSMC (homogeneous), N = {n_dsmc}"), dsmc_curve)
    .theory(
        "Haff's law (= 1)",
        vec![(ratios[0], 1.0), (ratios[12], 1.0)],
    )
    .theory("Haff's law with a2 = 0 (Maxwellian rate)", maxwell_curve);
    files.push(ctx.figure(id, &fig)?);
    let md = format!(
        "# {id}: Haff's law in time\n\n\
         **Paper.** T(t) = T0 / (1 + t/t0)^2 with 2/t0 = zeta0 = (1 - eps^2)/3 omega_E \
         (1 + 3a2/16): omega_E the Enskog collision frequency at T0 (Carnahan–Starling \
         contact value), a2 = {} of the HCS (van Noije & Ernst). No parameter is fitted; \
         t0 = {} (with a2 = 0: {}).\n\n\
         **We get** (eps = 0.9, phi = 0.05, 3D): eMD with N = {n_emd} ({seeds} seeds) \
         within {} of Haff's law up to t = 4 t0; the homogeneous DSMC (N = {n_dsmc}, the \
         Enskog–Boltzmann equation with no spatial structure) within {} over the whole run \
         to {} t0. At {} t0 eMD gives T/T_Haff = {}.\n\n\
         **Difference.** The eMD box is {} mean free paths wide; late in the run the \
         homogeneous cooling state of so dissipative a gas develops shear modes (the \
         clustering instability, Goldhirsch & Zanetti 1993), and eMD then cools slower than \
         the homogeneous theory, which DSMC follows.\n",
        sig(a2),
        sig(t0),
        sig(maxwell_t0),
        sig(worst_early),
        sig(worst_dsmc),
        sig(ratios[12]),
        sig(ratios[12]),
        sig(emd_late),
        sig(box_in_free_paths(n_emd, phi)),
    );
    files.push(ctx.markdown(id, &md)?);
    Ok(Outcome {
        summary: format!(
            "eMD within {} of Haff's law to 4 t0, DSMC within {} to {} t0",
            sig(worst_early),
            sig(worst_dsmc),
            sig(ratios[12])
        ),
        values: vec![
            ("t0", t0),
            ("worst_emd_to_4t0", worst_early),
            ("worst_dsmc", worst_dsmc),
        ],
        files,
    })
}

/// The box side of `n` unit spheres at phi in mean free paths.
fn box_in_free_paths(n: usize, phi: f64) -> f64 {
    let length = gas::system::monodisperse_box_side::<3>(n, 1.0, phi);
    let density = phi / gas::system::ball_volume::<3>(0.5);
    length / gas::theory::mean_free_path::<3>(density, 1.0, phi)
}

/// a2 of the HCS by homogeneous DSMC (the exact Enskog–Boltzmann HCS): batch means of
/// snapshots from 10 to 50 collisions per particle over several seeds, against the first
/// (van Noije & Ernst) and second Sonine approximations and the Sonine hierarchy with all
/// its terms (`gas::theory::SonineHierarchy`).
fn a2(ctx: &Context) -> Result<Outcome> {
    let id = "kinetic-a2";
    let phi = 0.05;
    let (n, seeds, batches) = if ctx.quick {
        (10_000, 1, 4)
    } else {
        (100_000, 4, 8)
    };
    let epsilons = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95];
    let mut rows = Vec::new();
    let (mut measured, mut worst_z_weak) = (vec![], 0.0f64);
    for &eps in &epsilons {
        let mut means = Vec::new();
        for seed in 0..seeds {
            let law = Box::new(Constant::new(eps).map_err(engine_error)?);
            // Batch means over runs of relative length (the engine's own count, not the
            // driver's schedule of absolute targets).
            let mut d = dsmc(n, phi, law, 1000 + seed)?;
            let per_particle = |c: f64| (c * n as f64 / 2.0).round() as u64;
            d.run_collisions(per_particle(10.0));
            for _ in 0..batches {
                let mut sum = 0.0;
                for _ in 0..10 {
                    d.run_collisions(per_particle(40.0 / (10.0 * batches as f64)));
                    sum += sonine_a2(d.system());
                }
                means.push(sum / 10.0);
            }
        }
        let (mean, error) = mean_and_error(&means);
        let vne = van_noije_ernst_a2::<3>(eps);
        let (second, third) = second_sonine::<3>(eps).map_err(engine_error)?;
        rows.push(vec![eps, mean, error, vne, second, third]);
        measured.push((eps, mean));
        if eps >= 0.7 {
            worst_z_weak = worst_z_weak.max(((mean - vne) / error).abs());
        }
    }
    let row = |eps: f64| rows.iter().find(|r| r[0] == eps).expect("eps").clone();
    let (strong, middle, weak) = (row(0.3), row(0.5), row(0.9));
    // the hierarchy with all terms at eps = 0.9, where its orders K = 4..6 agree to 1e-5
    let orders = (4..=6)
        .map(|k| {
            let hierarchy = SonineHierarchy::new(3, k, 0.9).map_err(engine_error)?;
            let a = hierarchy.coefficients().ok_or_else(|| {
                engine_error(format!(
                    "the Sonine hierarchy of order {k} did not converge"
                ))
            })?;
            Ok(a[0])
        })
        .collect::<Result<Vec<f64>>>()?;
    let converged = orders[2];
    let mut files = vec![ctx.csv(
        id,
        &[
            "eps",
            "a2_dsmc",
            "a2_dsmc_error",
            "a2_van_noije_ernst",
            "a2_second_sonine",
            "a3_second_sonine",
        ],
        &rows,
    )?];
    let fine: Vec<f64> = (0..=100).map(|k| 0.05 + 0.95 * k as f64 / 100.0).collect();
    let first_curve: Vec<(f64, f64)> = fine
        .iter()
        .map(|&e| (e, van_noije_ernst_a2::<3>(e)))
        .collect();
    let second_curve = fine
        .iter()
        .map(|&e| second_sonine::<3>(e).map(|(a, _)| (e, a)))
        .collect::<gas::Result<Vec<(f64, f64)>>>()
        .map_err(engine_error)?;
    let fig = Figure::new(
        "a2 of the homogeneous cooling state (3D)",
        "coefficient of restitution eps",
        "Sonine coefficient a2",
    )
    .printed(
        format!("DSMC, N = {n}, {seeds} seed(s) (error bars < marker)"),
        measured,
    )
    .theory(
        "first Sonine approximation (van Noije & Ernst 1998)",
        first_curve,
    )
    .theory(
        "second Sonine approximation (linear in a2, a3)",
        second_curve,
    );
    files.push(ctx.figure(id, &fig)?);
    let md = format!(
        "# {id}: a2 of the homogeneous cooling state\n\n\
         **Paper.** The first Sonine approximation (van Noije & Ernst 1998): a2 = 16 (1 - eps) \
         (1 - 2 eps^2) / (81 - 17 eps + 30 eps^2 (1 - eps)) in 3D. The second Sonine \
         approximation (Brilliantov & Pöschel, EPL 74, 424 (2006); Santos & Montanero, \
         Granular Matter 11, 157 (2009)) keeps a3 and the moment equation p = 6, linear in a2 \
         and a3; haff computes its collisional moments by exact quadrature \
         (`gas::theory::SonineHierarchy`, which at first order reproduces van Noije & Ernst \
         to 1e-11), and also the hierarchy with all its terms to order K = 6.\n\n\
         **We get** (homogeneous DSMC, the exact Enskog–Boltzmann HCS, N = {n}, {seeds} \
         seed(s), batch means from 10 to 50 collisions per particle):\n\n\
         | eps | DSMC | first Sonine | second Sonine (a3) |\n\
         |---|---|---|---|\n\
         | 0.9 | {} ± {} | {} | {} ({}) |\n\
         | 0.5 | {} ± {} | {} | {} ({}) |\n\
         | 0.3 | {} ± {} | {} | {} ({}) |\n\n\
         At eps = 0.9 the hierarchy with all terms gives {} (K = 4, 5, 6: {}, {}, {}); for \
         eps >= 0.7 the largest deviation of DSMC from the first Sonine approximation is {} \
         standard errors.\n\n\
         **Difference.** At weak dissipation the second Sonine approximation closes most of \
         the gap between the first one and the full hierarchy (eps = 0.9: it moves a2 by {} \
         of {}), and DSMC agrees with the full hierarchy ({} standard errors). At strong dissipation the two approximations bracket the \
         measured a2 from either side (eps = 0.3: first {} above, second {} below DSMC): the \
         Sonine series converges ever more slowly there, its truncations oscillate \
         (the breakdown of the Sonine expansion, Brilliantov & Pöschel 2006), and a3 is \
         no longer small ({} at eps = 0.3). eMD at phi = 0.005 agrees with this DSMC within 3 \
         errors (docs/event-driven.md, `sonine_a2_study`).\n",
        sig(weak[1]),
        sig(weak[2]),
        sig(weak[3]),
        sig(weak[4]),
        sig(weak[5]),
        sig(middle[1]),
        sig(middle[2]),
        sig(middle[3]),
        sig(middle[4]),
        sig(middle[5]),
        sig(strong[1]),
        sig(strong[2]),
        sig(strong[3]),
        sig(strong[4]),
        sig(strong[5]),
        sig(converged),
        sig(orders[0]),
        sig(orders[1]),
        sig(orders[2]),
        sig(worst_z_weak),
        sig(weak[4] - weak[3]),
        sig(converged - weak[3]),
        sig((weak[1] - converged) / weak[2]),
        sig(strong[3] - strong[1]),
        sig(strong[1] - strong[4]),
        sig(strong[5]),
    );
    files.push(ctx.markdown(id, &md)?);
    Ok(Outcome {
        summary: format!(
            "a2(0.9) = {} ± {} (first Sonine {}, second {}), a2(0.3) = {} (first {}, second {})",
            sig(weak[1]),
            sig(weak[2]),
            sig(weak[3]),
            sig(weak[4]),
            sig(strong[1]),
            sig(strong[3]),
            sig(strong[4])
        ),
        values: vec![
            ("a2_0.9", weak[1]),
            ("a2_0.9_error", weak[2]),
            ("a2_0.3", strong[1]),
            ("a2_0.3_error", strong[2]),
            ("a2_second_sonine_0.9", weak[4]),
            ("a2_second_sonine_0.3", strong[4]),
            ("a2_hierarchy_0.9", converged),
        ],
        files,
    })
}

/// Viscoelastic spheres (fast law): eMD and DSMC T(t) with beta = 1 at phi = 0.005 (a box
/// below the instability size), and the local exponent d ln T / d ln t of a DSMC gas with
/// beta = 0.01, which approaches -5/3 (Brilliantov & Pöschel 2004, Ch. 8: T ~ t^(-5/3)
/// once 1 - eps ~ T^(1/10) is small).
fn viscoelastic(ctx: &Context) -> Result<Outcome> {
    let id = "kinetic-viscoelastic";
    let phi = 0.005;
    let (n_emd, n_dsmc, late_n) = if ctx.quick {
        (500, 20_000, 5_000)
    } else {
        (2000, 200_000, 50_000)
    };
    let law = |beta: f64| -> Result<Box<dyn Restitution>> {
        let form: ScaledForm = "fast".parse().map_err(engine_error)?;
        Ok(Box::new(
            Viscoelastic::new(beta, form).map_err(engine_error)?,
        ))
    };
    let end = if ctx.quick { 1e4 } else { 5e4 };
    let times: Vec<f64> = (0..=16)
        .map(|k| 10.0 * (end / 10.0f64).powf(k as f64 / 16.0))
        .collect();
    let emd_t = temperatures(emd(n_emd, phi, law(1.0)?, 5)?, &times)?;
    let dsmc_t = temperatures(dsmc(n_dsmc, phi, law(1.0)?, 6)?, &times)?;
    // The local exponent of a less dissipative gas over seven decades.
    let late_times: Vec<f64> = (0..=10).map(|k| 1e3 * 10f64.powf(k as f64 / 2.0)).collect();
    let late_t = temperatures(dsmc(late_n, phi, law(0.01)?, 8)?, &late_times)?;
    let exponents: Vec<(f64, f64)> = late_times
        .windows(2)
        .zip(late_t.windows(2))
        .map(|(t, temp)| {
            (
                (t[0] * t[1]).sqrt(),
                (temp[1] / temp[0]).ln() / (t[1] / t[0]).ln(),
            )
        })
        .collect();
    let last_exponent = exponents.last().expect("windows").1;
    let rows: Vec<Vec<f64>> = times
        .iter()
        .zip(emd_t.iter().zip(&dsmc_t))
        .map(|(&t, (&a, &b))| vec![t, a, b])
        .collect();
    let mut files = vec![ctx.csv(id, &["time", "temperature_emd", "temperature_dsmc"], &rows)?];
    files.push(
        ctx.csv(
            &format!("{id}-exponent"),
            &["time", "local_exponent"],
            &exponents
                .iter()
                .map(|&(t, x)| vec![t, x])
                .collect::<Vec<_>>(),
        )?,
    );
    let worst = emd_t
        .iter()
        .zip(&dsmc_t)
        .map(|(a, b)| (a / b - 1.0).abs())
        .fold(0.0f64, f64::max);
    let (t_end, temp_end) = (times[16], dsmc_t[16]);
    let asymptote: Vec<(f64, f64)> = times
        .iter()
        .filter(|&&t| t >= 100.0)
        .map(|&t| (t, temp_end * (t / t_end).powf(-5.0 / 3.0)))
        .collect();
    let fig = Figure::new(
        "viscoelastic spheres (fast law, beta = 1), phi = 0.005",
        "time t",
        "temperature T",
    )
    .log(true, true)
    .line(
        format!("eMD, N = {n_emd}"),
        times.iter().copied().zip(emd_t.iter().copied()).collect(),
    )
    .line(
        format!("DSMC, N = {n_dsmc}"),
        times.iter().copied().zip(dsmc_t.iter().copied()).collect(),
    )
    .theory("t^(-5/3) through the last DSMC point", asymptote);
    files.push(ctx.figure(id, &fig)?);
    let fig = Figure::new(
        "viscoelastic cooling: local exponent d ln T / d ln t (DSMC, beta = 0.01)",
        "time t",
        "d ln T / d ln t",
    )
    .log(true, false)
    .line(format!("DSMC, N = {late_n}"), exponents.clone())
    .theory(
        "-5/3 (Brilliantov & Pöschel)",
        vec![
            (exponents[0].0, -5.0 / 3.0),
            (exponents.last().expect("windows").0, -5.0 / 3.0),
        ],
    );
    files.push(ctx.figure(&format!("{id}-exponent"), &fig)?);
    let md = format!(
        "# {id}: cooling of viscoelastic spheres\n\n\
         **Paper.** With eps(v) of viscoelastic spheres, 1 - eps ~ v^(1/5) shrinks as the \
         gas cools, and T(t) turns from Haff's t^(-2) to t^(-5/3) (Brilliantov & Pöschel \
         2004, Ch. 8).\n\n\
         **We get.** eMD (N = {n_emd}) and homogeneous DSMC (N = {n_dsmc}) with the fast law \
         at beta = 1, phi = 0.005: T(t) agree within {} (relative) over t = 10 to {}; \
         the local exponent of a DSMC gas with beta = 0.01 is {} between t = {} and {} \
         (-5/3 = -1.66667), approached from above as 1 - eps decreases.\n\n\
         **Difference.** The approach to -5/3 is slow (v* ~ T^(1/20)): with beta = 1 \
         the exponent is still about -1.74 at t = 1e7 (tests: `dsmc_vs_emd`). At phi = \
         0.05 the eMD box of this dissipative gas is beyond the instability size and eMD \
         cools 4–10 % slower than DSMC (docs/dsmc.md).\n",
        sig(worst),
        sig(end),
        sig(last_exponent),
        sig(late_times[9]),
        sig(late_times[10]),
    );
    files.push(ctx.markdown(id, &md)?);
    Ok(Outcome {
        summary: format!(
            "eMD vs DSMC within {} (beta = 1); local exponent {} at t = {} (beta = 0.01)",
            sig(worst),
            sig(last_exponent),
            sig(late_times[10])
        ),
        values: vec![
            ("worst_emd_vs_dsmc", worst),
            ("last_exponent", last_exponent),
        ],
        files,
    })
}
