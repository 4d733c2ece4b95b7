//! The thermal conductivity of elastic hard spheres measured between two thermal walls
//! (docs/shear.md): a gas in a box [20, 20, 80] closed on z by Maxwell walls at T = 1.4 and
//! 0.6, periodic on x and y, run to its steady state. Fourier's law q = -kappa dT/dz in the
//! bulk: the heat flux from the walls' energy tallies (the mean of what the hot wall gives
//! and the cold one takes, per unit area and time), the gradient from a quadratic fit of
//! the temperature profile over the middle half of the box (away from the Knudsen layers
//! at the walls) at its centre, kappa over kappa0 at the centre's temperature. Event-driven
//! MD against Enskog's conductivity at the centre's packing fraction; spatial DSMC (which
//! collides at the Enskog rate without collisional transfer) against Chapman-Enskog's over
//! chi, with cells of half a mean free path (27 simulated particles per physical one) and
//! with the default cells of one simulated particle per physical one (the cell-size
//! error). Both theories with the converged Sonine factor 1.025218 of the dilute gas.
//!
//! Every run goes through the driver (`sim::Simulation`: `profiles`, `wall_samples`).
//! Units: sigma = m = 1; 3D.

use super::{sig, Context, Entry, Outcome};
use gas::theory::transport::ELASTIC_CONDUCTIVITY_SONINE_FACTOR;
use gas::walls::Side;
use sim::error::Result;
use sim::plot::Figure;
use sim::Simulation;
use std::f64::consts::PI;
use std::fmt::Write as _;

const PAPER: &str = "Heat conduction between thermal walls (Chapman & Cowling; Enskog)";

pub fn entries() -> Vec<Entry> {
    vec![Entry {
        id: "kinetic-conductivity",
        paper: PAPER,
        item: "thermal conductivity of elastic spheres",
        shows: "the temperature profile between thermal walls at 1.4 and 0.6 and kappa / kappa0 \
                from Fourier's law: event-driven against Enskog, spatial DSMC against \
                Chapman-Enskog",
        typical_seconds: 40.0,
        run: conductivity,
    }]
}

const SIDES: [f64; 3] = [20.0, 20.0, 80.0];
const PARTICLES: usize = 1833;
const WALLS: (f64, f64) = (1.4, 0.6);
const BINS: usize = 40;
const BATCHES: usize = 5;

/// One engine's measurement: kappa / kappa0 (mean, error over batches), the centre's
/// temperature and packing fraction, and the time-averaged profile (z, T).
struct Measured {
    kappa: (f64, f64),
    centre_temperature: f64,
    centre_phi: f64,
    profile: Vec<(f64, f64)>,
}

/// Least squares of y = c0 + c1 x + c2 x^2; returns (c0, c1).
fn quadratic_fit(points: &[(f64, f64)]) -> (f64, f64) {
    // Normal equations, 3 x 3, solved by Cramer's rule.
    let s = |p: i32| points.iter().map(|(x, _)| x.powi(p)).sum::<f64>();
    let t = |p: i32| points.iter().map(|(x, y)| y * x.powi(p)).sum::<f64>();
    let m = [[s(0), s(1), s(2)], [s(1), s(2), s(3)], [s(2), s(3), s(4)]];
    let r = [t(0), t(1), t(2)];
    let det = |a: [[f64; 3]; 3]| {
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    };
    let with = |col: usize| {
        let mut a = m;
        for (row, value) in a.iter_mut().zip(r) {
            row[col] = value;
        }
        det(a)
    };
    let d = det(m);
    (with(0) / d, with(1) / d)
}

/// `refine` simulated particles per physical one (the DSMC's `run.particle_weight` is its
/// inverse): cells of half a mean free path with enough particles in each.
fn measure(engine: &str, end_time: f64, refine: u32) -> Result<Measured> {
    let particles = PARTICLES * refine as usize;
    let engine = if refine > 1 {
        format!("{engine}particle_weight = {}\n", 1.0 / refine as f64)
    } else {
        engine.to_string()
    };
    let text = format!(
        "[system]\ndimension = 3\nparticles = {particles}\nbox = [{}, {}, {}]\nseed = 3\n\
         [collision]\nlaw = \"constant\"\nrestitution = 1.0\n\
         [run]\n{engine}end_time = {end_time}\nsamples = 400\nspacing = \"linear\"\n\
         [[wall]]\naxis = \"z\"\nside = \"low\"\nkind = \"thermal\"\ntemperature = {}\n\
         [[wall]]\naxis = \"z\"\nside = \"high\"\nkind = \"thermal\"\ntemperature = {}\n\
         [output]\nprofiles = {{ axis = \"z\", bins = {BINS} }}\n",
        SIDES[0], SIDES[1], SIDES[2], WALLS.0, WALLS.1
    );
    let mut run = Simulation::from_toml(&text, "conductivity.toml".as_ref())?;
    run.run(&mut (), None)?;
    let rows = run.profile_rows().expect("output.profiles");
    let walls = run.wall_samples().expect("walls");
    let (area, length) = (SIDES[0] * SIDES[1], SIDES[2]);
    // The second half in BATCHES spans of equal time.
    let (start, end) = (0.5 * end_time, end_time);
    let span = (end - start) / BATCHES as f64;
    let energy_at = |time: f64, side: Side| -> f64 {
        walls
            .iter()
            .rev()
            .find(|w| w.side == side && w.time <= time + 1e-9 * end_time)
            .map_or(0.0, |w| w.energy)
    };
    let time_of_sample = |time: f64| {
        walls
            .iter()
            .map(|w| w.time)
            .filter(|&t| t <= time + 1e-9 * end_time)
            .fold(0.0, f64::max)
    };
    let mut kappas = Vec::new();
    let (mut centre_temperature, mut centre_phi) = (0.0, 0.0);
    let mut totals = vec![(0.0, 0.0, 0usize); BINS];
    for b in 0..BATCHES {
        let (from, to) = (start + b as f64 * span, start + (b + 1) as f64 * span);
        let (t0, t1) = (time_of_sample(from), time_of_sample(to));
        let given = energy_at(t1, Side::Low) - energy_at(t0, Side::Low);
        let taken = energy_at(t1, Side::High) - energy_at(t0, Side::High);
        let flux = 0.5 * (given - taken) / (area * (t1 - t0));
        // Slab means over the batch's samples (after t0, up to t1).
        let mut slabs = vec![(0.0, 0.0, 0.0, 0usize); BINS];
        for r in rows.iter().filter(|r| r.time > t0 && r.time <= t1) {
            let k = ((r.position / length * BINS as f64) as usize).min(BINS - 1);
            if let Some(t) = r.temperature {
                slabs[k].0 = r.position;
                slabs[k].1 += t;
                slabs[k].2 += r.packing_fraction;
                slabs[k].3 += 1;
            }
        }
        let middle: Vec<(f64, f64)> = slabs
            .iter()
            .filter(|s| s.3 > 0 && (s.0 - 0.5 * length).abs() < 0.25 * length)
            .map(|s| (s.0 - 0.5 * length, s.1 / s.3 as f64))
            .collect();
        let (temperature, gradient) = quadratic_fit(&middle);
        let phi = slabs
            .iter()
            .filter(|s| s.3 > 0 && (s.0 - 0.5 * length).abs() < 0.05 * length)
            .map(|s| s.2 / s.3 as f64)
            .sum::<f64>()
            / slabs
                .iter()
                .filter(|s| s.3 > 0 && (s.0 - 0.5 * length).abs() < 0.05 * length)
                .count()
                .max(1) as f64;
        let kappa0 = 75.0 / 64.0 * (temperature / PI).sqrt();
        kappas.push(-flux / gradient / kappa0);
        centre_temperature += temperature / BATCHES as f64;
        centre_phi += phi / BATCHES as f64;
        for (total, s) in totals.iter_mut().zip(&slabs) {
            if s.3 > 0 {
                *total = (s.0, total.1 + s.1 / s.3 as f64, total.2 + 1);
            }
        }
    }
    let n = BATCHES as f64;
    let mean = kappas.iter().sum::<f64>() / n;
    let var = kappas.iter().map(|k| (k - mean).powi(2)).sum::<f64>() / (n - 1.0);
    Ok(Measured {
        kappa: (mean, (var / n).sqrt()),
        centre_temperature,
        centre_phi,
        profile: totals
            .iter()
            .filter(|t| t.2 > 0)
            .map(|t| (t.0, t.1 / t.2 as f64))
            .collect(),
    })
}

fn conductivity(ctx: &Context) -> Result<Outcome> {
    let id = "kinetic-conductivity";
    let end_time = if ctx.quick { 1000.0 } else { 8000.0 };
    let emd = measure("engine = \"event-driven\"\n", end_time, 1)?;
    let spatial = "engine = \"dsmc\"\ndsmc_scheme = \"spatial\"\n";
    // 27 simulated particles per physical one: cells of half a mean free path hold 10.
    let dsmc = measure(spatial, end_time, 27)?;
    // One per physical particle: the default cells widen to hold 10 (over a mean free path).
    let coarse = measure(spatial, end_time, 1)?;
    let enskog = ELASTIC_CONDUCTIVITY_SONINE_FACTOR
        * gas::theory::ReducedTransport::enskog::<3>(emd.centre_phi, 1.0).thermal_conductivity;
    let boltzmann =
        ELASTIC_CONDUCTIVITY_SONINE_FACTOR / gas::theory::contact_value::<3>(dsmc.centre_phi);
    let coarse_theory =
        ELASTIC_CONDUCTIVITY_SONINE_FACTOR / gas::theory::contact_value::<3>(coarse.centre_phi);
    let mut md = format!(
        "# kinetic-conductivity: the thermal conductivity of elastic hard spheres between \
         thermal walls (3D)\n\n\
         **Paper.** Fourier's law with Chapman-Enskog's conductivity of hard spheres, \
         kappa0 = 75 / (64 sigma^2) (T / (pi m))^(1/2) times the converged Sonine factor \
         1.025218 (second and third orders computed by `gas::theory::transport`'s tests), \
         and Enskog's at finite density (first Sonine, times the same factor).\n\n\
         **We get** {PARTICLES} spheres in a box [20, 20, 80] between Maxwell walls at {} and \
         {} on z, t = 0 .. {end_time}; the second half in {BATCHES} batches: the flux from \
         the walls' energy, the gradient at the centre from a quadratic fit over the middle \
         half, kappa / kappa0 at the centre's temperature:\n\n\
         | engine | T centre | phi centre | kappa / kappa0 | theory | measured / theory |\n\
         |---|---|---|---|---|---|\n",
        WALLS.0, WALLS.1
    );
    let mut rows = Vec::new();
    for (code, name, m, theory, which) in [
        (0.0, "event-driven", &emd, enskog, "Enskog"),
        (
            1.0,
            "spatial DSMC, 27 per particle",
            &dsmc,
            boltzmann,
            "Chapman-Enskog / chi",
        ),
        (
            2.0,
            "spatial DSMC, default cells",
            &coarse,
            coarse_theory,
            "Chapman-Enskog / chi",
        ),
    ] {
        let _ = writeln!(
            md,
            "| {name} | {} | {} | {} ± {} | {} ({which}) | {} ± {} |",
            sig(m.centre_temperature),
            sig(m.centre_phi),
            sig(m.kappa.0),
            sig(m.kappa.1),
            sig(theory),
            sig(m.kappa.0 / theory),
            sig(m.kappa.1 / theory)
        );
        for &(z, t) in &m.profile {
            rows.push(vec![code, z, t, m.kappa.0, m.kappa.1, theory]);
        }
    }
    let emd_ratio = (emd.kappa.0 / enskog, emd.kappa.1 / enskog);
    let dsmc_ratio = (dsmc.kappa.0 / boltzmann, dsmc.kappa.1 / boltzmann);
    let coarse_ratio = (
        coarse.kappa.0 / coarse_theory,
        coarse.kappa.1 / coarse_theory,
    );
    let _ = writeln!(
        md,
        "\n**Difference.** Event-driven / Enskog = {} ± {}; spatial DSMC with cells of half \
         a mean free path / Chapman-Enskog = {} ± {} (statistical errors). With one \
         simulated particle per physical one the DSMC's cells widen to hold 10 particles \
         (wider than a mean free path here) and its conductivity comes out {} ± {} of \
         Chapman-Enskog's: the cell-size error of DSMC's transport coefficients, which grows \
         as (cell / mean free path)^2 (Alexander, Garcia & Alder 1998; Hadjiconstantinou \
         2000); what remains with cells of half a mean free path is the same error's tail \
         with that of the time step, not resolved further here. The temperature jumps at the walls (the Knudsen layers, a mean free path \
         thick) are why the gradient is fitted in the middle half only; the gradient's \
         Knudsen number (mean free path times |dT/dz| / T) is about 0.03, so Burnett terms \
         are below the errors. The Sonine factor of the dilute gas applied to Enskog's whole \
         conductivity is an approximation of O(phi) (its collisional part has none).\n",
        sig(emd_ratio.0),
        sig(emd_ratio.1),
        sig(dsmc_ratio.0),
        sig(dsmc_ratio.1),
        sig(coarse_ratio.0),
        sig(coarse_ratio.1)
    );
    let figure = Figure::new(
        "Temperature between thermal walls at 1.4 and 0.6",
        "z / sigma",
        "T",
    )
    .line("event-driven", emd.profile.clone())
    .line("spatial DSMC", dsmc.profile.clone())
    .line("spatial DSMC, default cells", coarse.profile.clone());
    let files = vec![
        ctx.csv(
            id,
            &["dsmc", "z", "temperature", "kappa", "kappa_error", "theory"],
            &rows,
        )?,
        ctx.figure(id, &figure)?,
        ctx.markdown(id, &md)?,
    ];
    Ok(Outcome {
        summary: format!(
            "kappa / theory: event-driven {:.3}, spatial DSMC {:.3}",
            emd_ratio.0, dsmc_ratio.0
        ),
        values: vec![
            ("emd_over_enskog", emd_ratio.0),
            ("emd_error", emd_ratio.1),
            ("dsmc_over_chapman_enskog", dsmc_ratio.0),
            ("dsmc_error", dsmc_ratio.1),
            ("coarse_dsmc_over_chapman_enskog", coarse_ratio.0),
        ],
        files,
    })
}
