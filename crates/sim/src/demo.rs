//! The science of `haff demo`: a freely cooling gas held against Haff's law and the velocity
//! distribution of the homogeneous cooling state, and a 2D gas clustering. The runs are
//! ordinary run files ([`COOLING`], [`CLUSTERING`]), run by [`crate::Simulation`] as
//! `haff run` would; this module measures what the demo reports and draws its figures.

use crate::error::{Error, Result};
use crate::figures::haff_law;
use crate::observer::{Histogram, Sample};
use crate::particles::Configuration;
use crate::plot::Figure;
use crate::Simulation;
use gas::theory::van_noije_ernst_a2;
use plotters::prelude::*;
use std::path::Path;

/// The cooling gas: 3D, event-driven, eps = 0.9, 4000 spheres at packing fraction 0.05,
/// 200 collisions per particle (about 1 s on one core). Velocity histograms every 10
/// collisions per particle from 20 on, when the gas has reached the homogeneous cooling
/// state (its a2 relaxes within a few collisions per particle).
pub const COOLING: &str = r#"# haff demo, part 1: a freely cooling granular gas (Haff 1983).
# Change it and run it with: haff run cooling.toml --out my-cooling
[system]
dimension = 3
particles = 4000
packing_fraction = 0.05
temperature = 1.0
seed = 1

[collision]
law = "constant"
restitution = 0.9

[run]
engine = "event-driven"
collisions_per_particle = 200
samples = 201
spacing = "linear"
histogram_at = [20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120, 130, 140, 150, 160, 170, 180, 190, 200]
histogram_bins = 50
"#;

/// The clustering gas: 2D, eps = 0.7, 20000 disks at packing fraction 0.25 in a box of
/// 250 diameters, far above the critical length of the clustering instability at this
/// dissipation (Goldhirsch & Zanetti 1993); density maps and ParaView snapshots every 20
/// collisions per particle.
pub const CLUSTERING: &str = r#"# haff demo, part 2: clustering of a 2D granular gas (Goldhirsch & Zanetti 1993).
# Change it and run it with: haff run clustering.toml --out my-clustering
[system]
dimension = 2
particles = 20000
packing_fraction = 0.25
temperature = 1.0
seed = 1

[collision]
law = "constant"
restitution = 0.7

[run]
engine = "event-driven"
collisions_per_particle = 100
samples = 21
spacing = "linear"

[output]
fields = { every = 5, grid = 32 }
snapshots = { every = 5, format = "vtk" }
"#;

/// The samples from which the cooling gas counts as in the homogeneous cooling state.
const HCS_FROM: f64 = 20.0;
/// Blocks of the batch-means standard error of a2 (samples are correlated over about one
/// collision per particle; 10 blocks of 18 collisions per particle each are independent).
const BLOCKS: usize = 10;

/// What the cooling gas shows.
#[derive(Debug, Clone, PartialEq)]
pub struct CoolingReport {
    /// T / T_Haff at the end (Haff's law with the Enskog rate and the HCS's a2; no fit).
    pub haff_ratio: f64,
    /// Collisions per particle at the end.
    pub collisions_per_particle: f64,
    /// The mean a2 of the samples in the cooling state, its batch-means standard error.
    pub a2: (f64, f64),
    /// a2 of van Noije & Ernst's first Sonine approximation.
    pub a2_theory: f64,
}

/// The measurements of the cooling run `simulation` (complete).
pub fn cooling_report(simulation: &Simulation) -> Result<CoolingReport> {
    let samples = simulation.samples();
    let (first, last) = match (samples.first(), samples.last()) {
        (Some(first), Some(last)) => (first, last),
        _ => return Err(Error::input("demo", "the cooling run has no samples")),
    };
    let plan = simulation.plan();
    let tau = haff_law(plan, first.temperature)
        .ok_or_else(|| Error::input("demo", "the cooling run has no Haff's law"))?;
    let t_haff = gas::theory::haff_temperature(first.temperature, tau, last.time);
    let eps = match plan.law {
        crate::validate::LawSpec::Constant(eps) => eps,
        _ => {
            return Err(Error::input(
                "demo",
                "the cooling run's law is not constant",
            ))
        }
    };
    Ok(CoolingReport {
        haff_ratio: last.temperature / t_haff,
        collisions_per_particle: last.collisions_per_particle,
        a2: batch_mean(&hcs_a2(samples)),
        a2_theory: van_noije_ernst_a2::<3>(eps),
    })
}

fn hcs_a2(samples: &[Sample]) -> Vec<f64> {
    samples
        .iter()
        .filter(|s| s.collisions_per_particle >= HCS_FROM)
        .map(|s| s.a2)
        .collect()
}

/// The mean of `values` and its standard error from the means of [`BLOCKS`] consecutive
/// blocks (batch means: correct for correlated samples once a block outlasts the
/// correlation).
fn batch_mean(values: &[f64]) -> (f64, f64) {
    let n = values.len();
    let mean = values.iter().sum::<f64>() / n as f64;
    let size = n / BLOCKS;
    if size == 0 {
        return (mean, f64::NAN);
    }
    let means: Vec<f64> = values
        .chunks_exact(size)
        .take(BLOCKS)
        .map(|b| b.iter().sum::<f64>() / size as f64)
        .collect();
    let m = means.iter().sum::<f64>() / means.len() as f64;
    let variance = means.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (means.len() - 1) as f64;
    (mean, (variance / means.len() as f64).sqrt())
}

/// The first Sonine correction of the distribution of one scaled velocity component
/// c = v_x / sqrt(2T/m): the d-dimensional S2(c^2) = c^4/2 - (d+2) c^2/2 + d(d+2)/8
/// averaged over the other components of the Maxwellian gives c_x^4/2 - 3 c_x^2/2 + 3/8
/// in any d (so that <c_x^4> = (3/4)(1 + a2), as for the whole vector).
pub fn sonine_component(c: f64, a2: f64) -> f64 {
    let maxwellian = (-c * c).exp() / std::f64::consts::PI.sqrt();
    maxwellian * (1.0 + a2 * (c.powi(4) / 2.0 - 1.5 * c * c + 0.375))
}

/// `path`: the histograms of the cooling state averaged (the scaled distribution of the HCS
/// is stationary) against the Maxwellian and its first Sonine correction, on a log scale.
pub fn velocity_distribution_figure(
    path: &Path,
    histograms: &[Histogram],
    report: &CoolingReport,
) -> Result<()> {
    let late: Vec<&Histogram> = histograms
        .iter()
        .filter(|h| h.collisions_per_particle >= HCS_FROM)
        .collect();
    let Some(first) = late.first() else {
        return Ok(());
    };
    let measured: Vec<(f64, f64)> = (0..first.bins.len())
        .map(|b| {
            let mean = late.iter().map(|h| h.bins[b].1).sum::<f64>() / late.len() as f64;
            (first.bins[b].0, mean)
        })
        .filter(|p| p.1 > 0.0)
        .collect();
    // The theory over the measured range only: the first Sonine correction is an expansion
    // about the Maxwellian, not a model of the far tails (where 1 + a2 S2 turns negative
    // for a2 < 0).
    let reach = measured.iter().map(|p| p.0.abs()).fold(0.0, f64::max) + 0.2;
    let grid: Vec<f64> = (0..=200)
        .map(|k| reach * (2.0 * k as f64 / 200.0 - 1.0))
        .collect();
    let curve = |a2: f64| -> Vec<(f64, f64)> {
        grid.iter().map(|&c| (c, sonine_component(c, a2))).collect()
    };
    Figure::new(
        format!(
            "velocity distribution, cooling state ({} histograms, eps = 0.9)",
            late.len()
        ),
        "c = v_x / sqrt(2T/m)",
        "f(c)",
    )
    .log(false, true)
    .printed("simulation", measured)
    .theory("Maxwellian exp(-c^2)/sqrt(pi)", curve(0.0))
    .theory(
        format!(
            "first Sonine, a2 = {:.4} (van Noije & Ernst)",
            report.a2_theory
        ),
        curve(report.a2_theory),
    )
    .write_png(path)
}

/// `path`: the disks of a 2D configuration drawn to scale (dark blue on white).
pub fn snapshot_figure(path: &Path, configuration: &Configuration, title: &str) -> Result<()> {
    let failed = |e: Box<dyn std::error::Error>| Error::Plot {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    draw_disks(path, configuration, title).map_err(failed)
}

fn draw_disks(
    path: &Path,
    configuration: &Configuration,
    title: &str,
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    const PIXELS: u32 = 1000;
    let (lx, ly) = (configuration.sides[0], configuration.sides[1]);
    let root = BitMapBackend::new(path, (PIXELS, PIXELS + 40)).into_drawing_area();
    root.fill(&WHITE)?;
    let (top, plot) = root.split_vertically(40);
    top.titled(title, ("sans-serif", 24))?;
    let scale = f64::from(PIXELS) / lx.max(ly);
    let colour = RGBColor(49, 104, 142);
    for (k, p) in configuration.positions.iter().enumerate() {
        let d = configuration.diameters.as_ref().map_or(1.0, |d| d[k]);
        let radius = (0.5 * d * scale).max(1.0);
        let centre = ((p[0] * scale) as i32, ((ly - p[1]) * scale) as i32);
        plot.draw(&Circle::new(centre, radius, colour.filled()))?;
    }
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Sonine-corrected component distribution is normalized and has
    /// <c^4> = (3/4)(1 + a2): trapezoidal quadrature on [-8, 8] (error far below 1e-10).
    #[test]
    fn the_sonine_component_has_the_moments_of_a2() {
        let a2 = 0.123;
        let h = 1e-3;
        let moment = |k: i32| -> f64 {
            (0..=16000)
                .map(|i| -8.0 + h * i as f64)
                .map(|c| c.powi(k) * sonine_component(c, a2) * h)
                .sum()
        };
        assert!((moment(0) - 1.0).abs() < 1e-10);
        assert!((moment(2) - 0.5).abs() < 1e-10);
        assert!((moment(4) - 0.75 * (1.0 + a2)).abs() < 1e-10);
    }

    /// Batch means of independent values: the standard error of the mean of 1000 values
    /// of a known sequence with mean 0.5 and variance 1/12 within its statistics.
    #[test]
    fn batch_means_of_a_uniform_sequence() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
        let values: Vec<f64> = (0..1000).map(|_| rng.random::<f64>()).collect();
        let (mean, error) = batch_mean(&values);
        let exact = (1.0f64 / 12.0 / 1000.0).sqrt();
        // The error estimate from 10 blocks has a relative spread of 1/sqrt(2 * 9) = 24 %.
        assert!(
            (error / exact - 1.0).abs() < 3.0 * 0.24,
            "{error} vs {exact}"
        );
        assert!((mean - 0.5).abs() < 4.0 * exact);
    }
}
