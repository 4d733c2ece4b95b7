//! Uniform shear flow measured (docs/shear.md): the steady USF of a dilute granular gas vs
//! the restitution, by the event-driven engine (Lees–Edwards boundaries) and the
//! homogeneous DSMC (the frame of the flow), against Grad's method and the BGK model
//! (`gas::theory::usf`); and the shear viscosity at a small shear rate under the Gaussian
//! thermostat (DSMC) against Chapman–Enskog (elastic) and the thermostatted Navier–Stokes
//! viscosity 1 / (nu_eta* - zeta*) of the first Sonine approximation (inelastic;
//! docs/errata.md: not the cooling state's 1 / (nu_eta* - zeta*/2)).
//!
//! Every run goes through the driver (`sim::Simulation`, its `rheology`: second-half
//! averages with batch-mean errors). Units: sigma = m = 1; 3D.

use super::{sig, Context, Entry, Outcome};
use sim::error::Result;
use sim::plot::Figure;
use sim::Simulation;
use std::fmt::Write as _;

const PAPER: &str = "Uniform shear flow (Montanero, Garzó, Santos & Brey 1999; Garzó & Dufty 1999)";

pub fn entries() -> Vec<Entry> {
    vec![
        Entry {
            id: "kinetic-usf",
            paper: PAPER,
            item: "steady USF vs alpha",
            shows: "reduced shear rate and pressure tensor of the steady USF vs alpha: \
                    event-driven (Lees-Edwards) and DSMC against Grad and BGK",
            typical_seconds: 40.0,
            run: steady_usf,
        },
        Entry {
            id: "kinetic-viscosity",
            paper: PAPER,
            item: "shear viscosity vs alpha",
            shows: "eta / eta0 at a* = 0.1 under the thermostat (DSMC) against \
                    Chapman-Enskog and the thermostatted Navier-Stokes viscosity",
            typical_seconds: 15.0,
            run: viscosity,
        },
    ]
}

/// (mean, error) of `rheology[key]`.
type Measured = (f64, f64);

/// A named curve of (x, y, error) points.
type MeasuredCurve = (String, Vec<(f64, f64, f64)>);

fn measured(rheology: &serde_json::Value, key: &str) -> Measured {
    let r = &rheology[key];
    (
        r["mean"].as_f64().unwrap_or(f64::NAN),
        r["error"].as_f64().unwrap_or(f64::NAN),
    )
}

/// The rheology of the run of `text`.
fn rheology(text: &str) -> Result<serde_json::Value> {
    let mut run = Simulation::from_toml(text, "usf.toml".as_ref())?;
    run.run(&mut (), None)?;
    let series = run.pressure().expect("a sheared run measures the pressure");
    Ok(run.rheology(series))
}

fn run_text(
    engine: &str,
    particles: usize,
    phi: f64,
    alpha: f64,
    rate: f64,
    collisions: f64,
    extra: &str,
) -> String {
    format!(
        "[system]\ndimension = 3\nparticles = {particles}\npacking_fraction = {phi}\nseed = 7\n\
         [collision]\nlaw = \"constant\"\nrestitution = {alpha}\n\
         [run]\n{engine}collisions_per_particle = {collisions}\nsamples = 100\n\
         spacing = \"linear\"\n\
         {extra}[shear]\nrate = {rate}\n"
    )
}

const EMD: &str = "engine = \"event-driven\"\n";
const DSMC: &str = "engine = \"dsmc\"\ndsmc_scheme = \"blocks\"\n";

/// The steady USF at each alpha by both engines.
fn steady_usf(ctx: &Context) -> Result<Outcome> {
    let id = "kinetic-usf";
    // Quick: fewer spheres and collisions, the same alphas (ten rows).
    let alphas: &[f64] = &[0.5, 0.6, 0.7, 0.8, 0.9];
    let (n_emd, n_dsmc, collisions) = if ctx.quick {
        (500, 4000, 150.0)
    } else {
        (2000, 20000, 200.0)
    };
    let keys = ["reduced_shear_rate", "pxx", "pyy", "pzz", "pxy"];
    let mut rows = Vec::new();
    let mut md = String::from(
        "# kinetic-usf: the steady uniform shear flow vs alpha (3D, phi = 0.002)\n\n\
         **Paper.** Grad's 13-moment solution of the steady USF of dilute inelastic hard \
         spheres (Montanero, Garzó, Santos & Brey, J. Fluid Mech. 389, 391 (1999); \
         `gas::theory::usf::steady_grad`), and the BGK model (Brey, Dufty & Santos 1999), \
         which gives the same pressure tensor.\n\n\
         **We get** a* = a / nu0 (nu0 = n T / eta0(T)), P* = P / (n T); second-half averages, \
         batch-mean errors:\n\n\
         | alpha | method | a* | P*_xx | P*_yy | P*_zz | P*_xy |\n|---|---|---|---|---|---|---|\n",
    );
    let mut curves: Vec<MeasuredCurve> = Vec::new();
    let mut worst: f64 = 0.0;
    // Per alpha: the engines' a* (event-driven, DSMC) and P_zz - P_yy.
    let mut by_alpha: Vec<(f64, Vec<Measured>, f64)> = Vec::new();
    for (name, engine, n) in [("event-driven", EMD, n_emd), ("DSMC", DSMC, n_dsmc)] {
        let mut points = Vec::new();
        for &alpha in alphas {
            let r = rheology(&run_text(engine, n, 0.002, alpha, 0.02, collisions, ""))?;
            let values: Vec<Measured> = keys.iter().map(|k| measured(&r, k)).collect();
            let grad = gas::theory::usf::steady_grad::<3>(alpha);
            let cells: Vec<String> = values
                .iter()
                .map(|v| format!("{} ± {}", sig(v.0), sig(v.1)))
                .collect();
            let _ = writeln!(md, "| {alpha} | {name} | {} |", cells.join(" | "));
            worst = worst.max((values[0].0 / grad.reduced_shear_rate - 1.0).abs());
            match by_alpha.iter_mut().find(|(a, _, _)| *a == alpha) {
                Some(entry) => entry.1.push(values[0]),
                None => by_alpha.push((alpha, vec![values[0]], values[3].0 - values[2].0)),
            }
            points.push((alpha, values[0].0, values[0].1));
            let mut row = vec![alpha, if name == "DSMC" { 1.0 } else { 0.0 }];
            for v in &values {
                row.extend([v.0, v.1]);
            }
            row.extend([
                grad.reduced_shear_rate,
                grad.pxx,
                grad.pyy,
                grad.pxy,
                gas::theory::usf::steady_bgk::<3>(alpha).reduced_shear_rate,
            ]);
            rows.push(row);
        }
        curves.push((format!("a*, {name}"), points));
    }
    let theory: Vec<(f64, f64)> = (0..=50)
        .map(|i| 0.5 + 0.5 * i as f64 / 50.0)
        .map(|a| (a, gas::theory::usf::steady_grad::<3>(a).reduced_shear_rate))
        .collect();
    let _ = writeln!(
        md,
        "\nGrad's a* (BGK's pressure tensor is Grad's): {}.\n\nLargest |a*_measured / a*_Grad - 1|: {}.\n",
        alphas
            .iter()
            .map(|&a| format!("alpha {a}: {}", sig(gas::theory::usf::steady_grad::<3>(a).reduced_shear_rate)))
            .collect::<Vec<_>>()
            .join(", "),
        sig(worst)
    );
    // The engines' difference in a*, in combined standard errors, at the worst alpha.
    let spread = by_alpha
        .iter()
        .filter(|(_, v, _)| v.len() == 2)
        .map(|(_, v, _)| (v[0].0 - v[1].0).abs() / (v[0].1.powi(2) + v[1].1.powi(2)).sqrt())
        .fold(0.0, f64::max);
    let agree = spread < 4.0;
    let grad_gaps: Vec<String> = by_alpha
        .iter()
        .map(|(a, v, _)| {
            let grad = gas::theory::usf::steady_grad::<3>(*a).reduced_shear_rate;
            format!(
                "{} % at alpha = {a}",
                sig(100.0 * (v[v.len() - 1].0 / grad - 1.0))
            )
        })
        .collect();
    let n2: Vec<String> = by_alpha
        .iter()
        .map(|(a, _, d)| format!("{} ({a})", sig(*d)))
        .collect();
    let _ = writeln!(
        md,
        "**Difference.** The event-driven engine and the DSMC {} within 4 standard errors at \
         every alpha. Grad's a* is below the measured one by {} (DSMC), and Grad has \
         P_zz = P_yy where both engines give P_zz > P_yy (P*_zz - P*_yy = {}, event-driven): \
         its closure, linear in the traceless pressure with a2 = 0, is the approximation, \
         worse at strong dissipation. P*_xx, P*_yy and P*_xy are closer (docs/shear.md). The \
         BGK model with the Navier-Stokes collision frequency gives Grad's pressure tensor.\n",
        if agree { "agree" } else { "do not all agree" },
        grad_gaps.join(", "),
        n2.join(", ")
    );
    let mut figure = Figure::new("Steady uniform shear flow (3D)", "alpha", "a* = a / nu0");
    for (name, points) in curves {
        figure = figure.measured(name, points);
    }
    figure = figure.theory("Grad", theory);
    let header = [
        "alpha",
        "dsmc",
        "a_star",
        "a_star_error",
        "pxx",
        "pxx_error",
        "pyy",
        "pyy_error",
        "pzz",
        "pzz_error",
        "pxy",
        "pxy_error",
        "grad_a_star",
        "grad_pxx",
        "grad_pyy",
        "grad_pxy",
        "bgk_a_star",
    ];
    let files = vec![
        ctx.csv(id, &header, &rows)?,
        ctx.figure(id, &figure)?,
        ctx.markdown(id, &md)?,
    ];
    Ok(Outcome {
        summary: format!(
            "steady USF at {} values of alpha: a* within {:.1} % of Grad's",
            alphas.len(),
            100.0 * worst
        ),
        values: vec![
            ("largest_relative_difference_from_grad", worst),
            ("largest_engine_difference_in_errors", spread),
        ],
        files,
    })
}

/// The viscosity at a* = 0.1 under the thermostat (DSMC) vs alpha.
fn viscosity(ctx: &Context) -> Result<Outcome> {
    let id = "kinetic-viscosity";
    // 1, 0.95, ..., 0.55 (as twentieths: printed as such).
    let alphas: Vec<f64> = (0..10).map(|i| (20 - i) as f64 / 20.0).collect();
    let (n, collisions) = if ctx.quick {
        (10000, 60.0)
    } else {
        (40000, 120.0)
    };
    let phi = 1e-3;
    let density = 6.0 * phi / std::f64::consts::PI;
    let eta0 = gas::theory::dilute_elastic_viscosity::<3>(1.0, 1.0, 1.0);
    let reduced_rate = 0.1;
    let rate = reduced_rate * density / eta0;
    let mut rows = Vec::new();
    let mut points = Vec::new();
    let mut md = String::from(
        "# kinetic-viscosity: the shear viscosity at a* = 0.1 under the Gaussian thermostat \
         (DSMC, 3D)\n\n\
         **Paper.** Chapman–Enskog's viscosity of elastic hard spheres (Chapman & Cowling \
         1970: eta0 times 1.016034, the converged Sonine series, whose second and third orders are \
         computed by `gas::theory::transport`'s tests) and the Navier–Stokes viscosity \
         of inelastic hard spheres in the first Sonine approximation (Garzó & Dufty 1999), \
         here for a gas held at T by the thermostat: 1 / (nu_eta* - zeta*) \
         (`gas::theory::usf::thermostatted_grad`; docs/errata.md).\n\n\
         **We get:**\n\n\
         | alpha | eta / eta0 measured | thermostatted Grad (first Sonine) | elastic: Chapman-Enskog x thinning |\n|---|---|---|---|\n",
    );
    let mut elastic_ratio = f64::NAN;
    for &alpha in &alphas {
        let extra = "[driving]\nkind = \"gaussian-thermostat\"\n";
        let r = rheology(&run_text(DSMC, n, phi, alpha, rate, collisions, extra))?;
        let (eta, error) = measured(&r, "reduced_viscosity");
        let grad = gas::theory::usf::thermostatted_grad::<3>(alpha, reduced_rate).viscosity;
        let chapman = if alpha == 1.0 {
            gas::theory::transport::ELASTIC_VISCOSITY_SONINE_FACTOR * grad
        } else {
            f64::NAN
        };
        if alpha == 1.0 {
            elastic_ratio = eta / chapman;
        }
        let _ = writeln!(
            md,
            "| {alpha} | {} ± {} | {} | {} |",
            sig(eta),
            sig(error),
            sig(grad),
            sig(chapman)
        );
        points.push((alpha, eta, error));
        rows.push(vec![alpha, eta, error, grad, chapman]);
    }
    let theory: Vec<(f64, f64)> = (0..=50)
        .map(|i| 0.5 + 0.5 * i as f64 / 50.0)
        .map(|a| {
            (
                a,
                gas::theory::usf::thermostatted_grad::<3>(a, reduced_rate).viscosity,
            )
        })
        .collect();
    let figure = Figure::new(
        "Shear viscosity under the thermostat, a* = 0.1",
        "alpha",
        "eta / eta0",
    )
    .measured("DSMC", points)
    .theory("thermostatted Grad (first Sonine)", theory);
    let _ = writeln!(
        md,
        "\nElastic: measured / Chapman-Enskog (1.016034 x Grad's thinning) = {}.\n",
        sig(elastic_ratio)
    );
    let worst = rows
        .iter()
        .filter(|r| r[0] < 1.0)
        .map(|r| (r[1] / r[3] - 1.0).abs())
        .fold(0.0, f64::max);
    let hcs = gas::theory::ReducedTransport::enskog::<3>(0.0, 0.7).shear_viscosity;
    let _ = writeln!(
        md,
        "**Difference.** Elastic: Chapman-Enskog's viscosity (with its Sonine factor 1.016034) \
         within {} %. Inelastic: the thermostatted first-Sonine viscosity 1 / (nu_eta* - \
         zeta*) within {} % (largest at the smallest alpha, where the first Sonine \
         approximation is known to weaken), and not the cooling state's 1 / (nu_eta* - \
         zeta*/2) ({} at alpha = 0.7): a thermostat changes the Navier-Stokes viscosity \
         (docs/errata.md).\n",
        sig(100.0 * (elastic_ratio - 1.0).abs()),
        sig(100.0 * worst),
        sig(hcs)
    );
    let files = vec![
        ctx.csv(
            id,
            &["alpha", "eta", "eta_error", "grad", "chapman_enskog"],
            &rows,
        )?,
        ctx.figure(id, &figure)?,
        ctx.markdown(id, &md)?,
    ];
    Ok(Outcome {
        summary: format!(
            "viscosity at {} values of alpha; elastic / Chapman-Enskog = {:.4}",
            alphas.len(),
            elastic_ratio
        ),
        values: vec![("elastic_over_chapman_enskog", elastic_ratio)],
        files,
    })
}
