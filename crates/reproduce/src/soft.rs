//! The seeds' claim, measured: event-driven MD with the exact coefficient of restitution of
//! viscoelastic spheres (and DSMC with it) replaces force-based MD of the same spheres,
//! Eq. (2) of Müller & Pöschel 2011, while the gas is dilute; and where it stops doing so.
//!
//! One material (Y = 1e5, nu = 0.3, A = 0.01 in units sigma = m = T0 = 1: beta = 0.44, so
//! eps ~ 0.6 at the initial thermal speed and -> 1 as the gas cools), the same initial
//! spheres, four ways: soft-sphere MD (`gas::SoftSphere`), eMD with the exact law and with
//! the fast (Padé) law, and homogeneous DSMC with the exact law, each run until eMD has
//! cooled by about 100 in temperature, at packing fractions 0.05, 0.2 and 0.4.

use super::{logspace, mean_and_error, sig, Context, Entry, Outcome};
use gas::dsmc::{point_gas, Scheme};
use gas::observe::temperature;
use gas::soft::contact::{contact_duration, ViscoelasticMaterial};
use gas::theory::collision_frequency;
use gas::{SoftSphereOptions, System};
use restitution::{Restitution, ScaledForm, Viscoelastic};
use sim::driver::Driven;
use sim::engines::{self, EngineSpec, Setup};
use sim::error::Result;
use sim::plot::Figure;
use sim::schedule::{Measure, Schedule};
use std::fmt::Write as _;
use std::time::Instant;

const PAPER: &str = "Müller & Pöschel 2011 (eMD replaces force-based MD)";

pub fn entries() -> Vec<Entry> {
    vec![Entry {
        id: "kinetic-soft-sphere",
        paper: PAPER,
        item: "the same gas three ways",
        shows: "T(t) of viscoelastic spheres by soft-sphere MD, eMD (exact and fast law) and \
                DSMC at phi = 0.05, 0.2, 0.4; where the binary-collision picture breaks",
        typical_seconds: 30.0,
        run: three_ways,
    }]
}

fn engine_error(e: impl std::fmt::Display) -> sim::error::Error {
    super::numerical("engine", e)
}

const YOUNG: f64 = 1e5;
const POISSON: f64 = 0.3;
const DISSIPATIVE_CONSTANT: f64 = 0.01;

fn law(beta: f64, form: &str) -> Result<Box<dyn Restitution>> {
    let form: ScaledForm = form.parse().map_err(engine_error)?;
    Ok(Box::new(
        Viscoelastic::new(beta, form).map_err(engine_error)?,
    ))
}

/// An engine of `spec` for `system` at `phi` (the seed: DSMC's streams).
fn engine(
    spec: EngineSpec,
    system: System<3>,
    law: Box<dyn Restitution>,
    phi: f64,
    seed: u64,
) -> Result<Box<dyn Driven<3>>> {
    let setup = Setup {
        law,
        packing_fraction: phi,
        seed,
        baths: None,
    };
    engines::build(&spec, system, setup)
}

/// T at each of `times` through the run driver, and the wall time.
fn temperatures(engine: Box<dyn Driven<3>>, times: &[f64]) -> Result<(Vec<f64>, f64)> {
    let start = Instant::now();
    let schedule = Schedule::samples_at(times, Measure::Time);
    let t = sim::probe::sample(engine, schedule, |e| temperature(e.system()))?;
    Ok((t, start.elapsed().as_secs_f64()))
}

/// What soft-sphere MD reports of its contacts at a sample ([`gas::soft::ContactReport`]).
#[derive(Debug, Clone, Copy, serde::Serialize, serde::Deserialize)]
struct Contacts {
    temperature: f64,
    contact_steps: u64,
    multi_contact_steps: u64,
    max_relative_overlap: f64,
    time_step: f64,
}

/// The temperature and the contacts of soft-sphere MD at each of `times`.
fn contacts(engine: Box<dyn Driven<3>>, times: &[f64]) -> Result<Vec<Contacts>> {
    let schedule = Schedule::samples_at(times, Measure::Time);
    sim::probe::sample(engine, schedule, |e| {
        let report = e.report();
        let c = report.section("contacts");
        let count = |key: &str| match c.and_then(|c| c.get(key)) {
            Some(gas::engine::ReportValue::Count(n)) => n,
            _ => 0,
        };
        let real = |key: &str| c.map_or(f64::NAN, |c| c.number(key));
        Contacts {
            temperature: temperature(e.system()),
            contact_steps: count("contact_steps"),
            multi_contact_steps: count("multi_contact_steps"),
            max_relative_overlap: real("max_relative_overlap"),
            time_step: real("time_step"),
        }
    })
}

/// One seed at one density: T of each engine at the sample times, the soft-sphere delay
/// and contact statistics, wall times.
struct SeedRun {
    soft: Vec<f64>,
    exact: Vec<f64>,
    fast: Vec<f64>,
    dsmc: Vec<f64>,
    /// Time per particle spent in contact up to each sample, Δ(t) = Σ dt over
    /// particle-steps in contact / N.
    delay: Vec<f64>,
    contact_steps: u64,
    multi_contact_steps: u64,
    max_relative_overlap: f64,
    /// Wall seconds: soft-sphere, eMD exact, eMD fast, DSMC.
    seconds: [f64; 4],
}

fn seed_run(
    phi: f64,
    n: usize,
    seed: u64,
    times: &[f64],
    material: ViscoelasticMaterial,
    beta: f64,
) -> Result<SeedRun> {
    let system = gas::init::monodisperse::<3>(n, phi, 1.0, 1.0, 1.0, seed).map_err(engine_error)?;
    let spec = EngineSpec::SoftSphere(SoftSphereOptions::default(), material);
    let soft = engine(spec, system.clone(), law(beta, "exact")?, phi, seed)?;
    let start = Instant::now();
    let rows = contacts(soft, times)?;
    let soft_t = rows.iter().map(|r| r.temperature).collect();
    let delay = rows
        .iter()
        .map(|r| r.contact_steps as f64 * r.time_step / n as f64)
        .collect();
    let soft_s = start.elapsed().as_secs_f64();
    let exact = engine(
        EngineSpec::EventDriven,
        system.clone(),
        law(beta, "exact")?,
        phi,
        seed,
    )?;
    let (exact_t, exact_s) = temperatures(exact, times)?;
    let fast = engine(
        EngineSpec::EventDriven,
        system.clone(),
        law(beta, "fast")?,
        phi,
        seed,
    )?;
    let (fast_t, fast_s) = temperatures(fast, times)?;
    let points = point_gas::<3>(n, system.sides, 1.0, 1.0, 1.0, seed).map_err(engine_error)?;
    let spec = EngineSpec::HomogeneousDsmc(Scheme::default());
    let dsmc = engine(spec, points, law(beta, "exact")?, phi, seed)?;
    let (dsmc_t, dsmc_s) = temperatures(dsmc, times)?;
    let stats = *rows.last().expect("samples");
    Ok(SeedRun {
        soft: soft_t,
        exact: exact_t,
        fast: fast_t,
        dsmc: dsmc_t,
        delay,
        contact_steps: stats.contact_steps,
        multi_contact_steps: stats.multi_contact_steps,
        max_relative_overlap: stats.max_relative_overlap,
        seconds: [soft_s, exact_s, fast_s, dsmc_s],
    })
}

/// One density over several seeds.
struct Density {
    phi: f64,
    times: Vec<f64>,
    runs: Vec<SeedRun>,
    /// Contact duration at the initial relative thermal speed over the initial free time
    /// 1/omega.
    duration_over_free_time: f64,
}

impl Density {
    /// Seed mean of T of one engine at each time.
    fn mean(&self, curve: impl Fn(&SeedRun) -> &[f64]) -> Vec<f64> {
        (0..self.times.len())
            .map(|i| self.runs.iter().map(|r| curve(r)[i]).sum::<f64>() / self.runs.len() as f64)
            .collect()
    }

    /// Seed mean and standard error of T_engine / T_eMD(exact) at each time (the ratio per
    /// seed: the runs of a seed share their initial state).
    fn ratio(&self, curve: impl Fn(&SeedRun) -> &[f64]) -> Vec<(f64, f64)> {
        (0..self.times.len())
            .map(|i| {
                let r: Vec<f64> = self.runs.iter().map(|r| curve(r)[i] / r.exact[i]).collect();
                mean_and_error(&r)
            })
            .collect()
    }

    /// The delay model of soft-sphere MD: a contact holds its pair for the time it lasts,
    /// which hard spheres spend in free flight, so the soft-sphere gas is the eMD gas with
    /// its clock behind by the time per particle spent in contact, Δ(t):
    /// T_soft(t) / T_eMD(t) = T_eMD(t − Δ) / T_eMD(t), with ln T_eMD of the seed mean
    /// interpolated linearly in t between the samples (and T = 1 at t = 0).
    fn delay_model(&self) -> Vec<f64> {
        let exact = self.mean(|r| &r.exact);
        let delay = self.mean(|r| &r.delay);
        let mut t = vec![0.0];
        t.extend(&self.times);
        let mut ln_t = vec![0.0];
        ln_t.extend(exact.iter().map(|x| x.ln()));
        let at = |x: f64| {
            let k = t.partition_point(|&s| s <= x).clamp(1, t.len() - 1);
            let w = (x - t[k - 1]) / (t[k] - t[k - 1]);
            ln_t[k - 1] + w * (ln_t[k] - ln_t[k - 1])
        };
        self.times
            .iter()
            .zip(&delay)
            .map(|(&time, &d)| (at(time - d) - at(time)).exp())
            .collect()
    }

    /// Fraction of a particle's time spent in contact, Δ(t) / t, at each time.
    fn contact_time_fraction(&self) -> Vec<f64> {
        self.mean(|r| &r.delay)
            .iter()
            .zip(&self.times)
            .map(|(d, t)| d / t)
            .collect()
    }

    fn multi_contact_fraction(&self) -> f64 {
        let multi: u64 = self.runs.iter().map(|r| r.multi_contact_steps).sum();
        let all: u64 = self.runs.iter().map(|r| r.contact_steps).sum();
        multi as f64 / all.max(1) as f64
    }

    /// Mean wall seconds of each engine per run.
    fn seconds(&self) -> [f64; 4] {
        std::array::from_fn(|k| {
            self.runs.iter().map(|r| r.seconds[k]).sum::<f64>() / self.runs.len() as f64
        })
    }
}

fn density(phi: f64, n: usize, collisions: f64, seeds: &[u64]) -> Result<Density> {
    let material =
        ViscoelasticMaterial::new(YOUNG, POISSON, DISSIPATIVE_CONSTANT).map_err(engine_error)?;
    let beta = material.beta(0.5, 0.5, 1.0, 1.0);
    // The end: eMD (exact law) of the first seed after `collisions` per particle.
    let system =
        gas::init::monodisperse::<3>(n, phi, 1.0, 1.0, 1.0, seeds[0]).map_err(engine_error)?;
    let mut probe = engine(EngineSpec::EventDriven, system, law(beta, "exact")?, phi, 0)?;
    probe.run_collisions((collisions * n as f64 / 2.0) as u64);
    let times = logspace(0.01 * probe.time(), probe.time(), 15);
    let runs = seeds
        .iter()
        .map(|&seed| seed_run(phi, n, seed, &times, material, beta))
        .collect::<Result<Vec<_>>>()?;
    let density = phi / gas::system::ball_volume::<3>(0.5);
    let omega = collision_frequency::<3>(density, 1.0, 1.0, 1.0, phi);
    let rho = material.elastic_constant(0.5, 0.5);
    // At the relative thermal speed sqrt(2 T / m_eff) = 2 (T = m = 1), damping included.
    let duration = contact_duration(rho, DISSIPATIVE_CONSTANT, 0.5, 2.0).map_err(engine_error)?;
    Ok(Density {
        phi,
        times,
        runs,
        duration_over_free_time: duration * omega,
    })
}

/// Ratios as "1.035, 1.61".
fn join(ratios: impl Iterator<Item = f64>) -> String {
    ratios
        .map(|r| format!("{r:.3}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// "1.0053 ± 0.0007".
fn pm((mean, error): (f64, f64)) -> String {
    format!("{mean:.4} ± {error:.4}")
}

fn three_ways(ctx: &Context) -> Result<Outcome> {
    let id = "kinetic-soft-sphere";
    let (n, collisions, phis, seeds): (usize, f64, &[f64], &[u64]) = if ctx.quick {
        (300, 5.0, &[0.05, 0.4], &[11, 12])
    } else {
        (2000, 20.0, &[0.05, 0.2, 0.4], &[11, 12, 13, 14, 15, 16])
    };
    let runs: Vec<Density> = phis
        .iter()
        .map(|&phi| density(phi, n, collisions, seeds))
        .collect::<Result<_>>()?;
    let mut rows = Vec::new();
    let mut fig = Figure::new(
        "Viscoelastic spheres: T / T(eMD, exact law) of soft-sphere MD, and the delay model",
        "t / t_end",
        "T / T_eMD",
    )
    .log(true, false);
    let mut table = String::from(
        "| phi | t_c / t_free | time in contact, first → last | multi-contact fraction | \
         max overlap / sigma | T_soft / T_eMD at t_end / 100: measured, delay model | at \
         t_end / 10 | at t_end | eMD fast vs exact | DSMC / eMD at t_end | T_end | wall s: \
         soft-sphere / eMD exact / fast / DSMC |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut largest = Vec::new();
    // (measured, model) at t_end / 10 per density, for the text.
    let mut middle = Vec::new();
    let mut early = Vec::new();
    for d in &runs {
        let end = *d.times.last().expect("times");
        let (soft, exact, fast, dsmc) = (
            d.mean(|r| &r.soft),
            d.mean(|r| &r.exact),
            d.mean(|r| &r.fast),
            d.mean(|r| &r.dsmc),
        );
        let ratio = d.ratio(|r| &r.soft);
        let model = d.delay_model();
        let fraction = d.contact_time_fraction();
        for i in 0..d.times.len() {
            rows.push(vec![
                d.phi,
                d.times[i],
                soft[i],
                exact[i],
                fast[i],
                dsmc[i],
                ratio[i].0,
                ratio[i].1,
                fraction[i],
                model[i],
            ]);
        }
        let x = |i: usize| d.times[i] / end;
        fig = fig
            .measured(
                format!("soft-sphere MD, phi = {}", d.phi),
                (0..d.times.len())
                    .map(|i| (x(i), ratio[i].0, ratio[i].1))
                    .collect(),
            )
            .theory(
                format!("delay model, phi = {}", d.phi),
                (0..d.times.len()).map(|i| (x(i), model[i])).collect(),
            );
        let (first, mid, last) = (0, d.times.len() / 2, d.times.len() - 1);
        let fast_vs_exact = fast
            .iter()
            .zip(&exact)
            .map(|(a, b)| (a / b - 1.0).abs())
            .fold(0.0, f64::max);
        let seconds = d.seconds();
        let at = |i: usize| format!("{}, {:.4}", pm(ratio[i]), model[i]);
        let _ = writeln!(
            table,
            "| {} | {:.3} | {:.3} → {:.3} | {:.3} | {:.4} | {} | {} | {} | {:.2} % | {:.3} | {:.4} \
             | {:.2} / {:.3} / {:.3} / {:.3} |",
            d.phi,
            d.duration_over_free_time,
            fraction[first],
            fraction[last],
            d.multi_contact_fraction(),
            d.runs.iter().map(|r| r.max_relative_overlap).fold(0.0, f64::max),
            at(first),
            at(mid),
            at(last),
            100.0 * fast_vs_exact,
            dsmc[last] / exact[last],
            exact[last],
            seconds[0],
            seconds[1],
            seconds[2],
            seconds[3],
        );
        let worst = (0..d.times.len())
            .map(|i| (ratio[i].0 - 1.0).abs())
            .fold(0.0, f64::max);
        largest.push((worst, ratio[last].1));
        middle.push((ratio[mid].0, model[mid]));
        early.push(format!(
            "{:.2} ± {:.2} %",
            100.0 * (ratio[first].0 - 1.0),
            100.0 * ratio[first].1
        ));
    }
    fig = fig.theory("eMD, exact law (= 1)", vec![(0.01, 1.0), (1.0, 1.0)]);
    let mut files = vec![ctx.csv(
        id,
        &[
            "packing_fraction",
            "time",
            "temperature_soft_sphere",
            "temperature_emd_exact",
            "temperature_emd_fast",
            "temperature_dsmc",
            "soft_over_emd",
            "soft_over_emd_error",
            "contact_time_fraction",
            "delay_model",
        ],
        &rows,
    )?];
    files.push(ctx.figure(id, &fig)?);
    let md = format!(
        "# {id}: the same gas three ways\n\n\
         **Paper.** Müller & Pöschel 2011: the coefficient of restitution of the force of \
         Eq. (2) makes event-driven MD and DSMC of viscoelastic spheres as exact as MD with \
         that force, at a fraction of the cost, as long as collisions are binary and short.\n\n\
         **We get** (N = {n} spheres, Y = {YOUNG}, nu = {POISSON}, A = {DISSIPATIVE_CONSTANT} \
         in units sigma = m = T0 = 1, {} seeds, each run by all four engines from the same \
         initial state; the runs end when eMD has had {collisions} collisions per particle; \
         T_soft / T_eMD is the seed mean of the per-seed ratio ± its standard error, at 15 \
         times from 0.01 t_end to t_end; temperatures are seed means; wall seconds per \
         run):\n\n\
         {table}\n\
         The time step is not the cause: halving it moves T_soft by at most 1e-4 while \
         the runs stay on one trajectory (`bench/peers/lammps/three_ways.py --dt-factor \
         0.5`, 16 seeds, bench/peers/lammps/README.md), and LAMMPS's soft-sphere gas \
         agrees with haff's at every time within the errors there.\n\n\
         **Difference.** Soft-sphere MD and eMD with the exact law agree within a few per \
         cent at every density, but not within the statistical error: the soft-sphere gas \
         is warmer, by {early} at t_end / 100 (phi = {all_phis}). A contact holds its pair \
         for a time that hard spheres spend in free flight, so the soft gas collides and \
         cools later. The delay model (T_soft(t) = T_eMD(t − Δ), Δ the measured time per \
         particle in contact) accounts for that in the dilute gas, where a particle spends \
         a few per cent of its time in contact, and overshoots in the dense ones once they \
         have cooled a little: at t_end / 10 it predicts {dense_model} where \
         {dense_measured} is measured (phi = {dense_phis}). Particles in contact still move \
         and meet others (multi-particle contacts; at phi = 0.4 lasting contacts in \
         clusters, and the time in contact grows as the gas cools), so contact time is not \
         simply lost time; the binary-collision picture of eMD fails, and no coefficient \
         of restitution can absorb it. In the dilute gas the difference shrinks as the gas \
         cools: contacts get shorter relative to the free time (∝ T^(2/5)) and the late \
         viscoelastic cooling T ∝ t^(-5/3) forgets the past. The fast law equals the \
         exact one to ~1e-13 in eps, so its runs follow the exact law's until chaos \
         amplifies that difference (column eMD fast vs exact: the largest difference \
         over the run). DSMC departs for another reason: it has no \
         space, while the eMD and MD boxes develop the shear and clustering instability (at \
         phi = 0.2 eMD's lowest transverse mode reaches 66 times its homogeneous value \
         within 20 collisions per particle, `[output] modes`, docs/structure.md), and an \
         inhomogeneous gas cools more slowly than the homogeneous cooling state.\n",
        seeds.len(),
        early = early.join(", "),
        all_phis = phis
            .iter()
            .map(|p| p.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        dense_model = join(middle[1..].iter().map(|m| m.1)),
        dense_measured = join(middle[1..].iter().map(|m| m.0)),
        dense_phis = phis[1..]
            .iter()
            .map(|p| p.to_string())
            .collect::<Vec<_>>()
            .join(", "),
    );
    files.push(ctx.markdown(id, &md)?);
    Ok(Outcome {
        summary: format!(
            "soft-sphere MD vs eMD (exact law), largest seed-mean difference: {}",
            runs.iter()
                .zip(&largest)
                .map(|(d, w)| format!("phi = {}: {}", d.phi, sig(w.0)))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        values: vec![
            ("soft_vs_emd_dilute", largest[0].0),
            ("soft_vs_emd_dense", largest.last().expect("densities").0),
            ("statistical", largest[0].1),
        ],
        files,
    })
}
