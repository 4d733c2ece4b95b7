//! PNG figures of a run (plotters).

use crate::error::{CliError, CliResult};
use plotters::prelude::*;
use std::path::Path;

/// T(t) on log-log axes, with an optional reference curve (Haff's law), as a PNG.
pub fn temperature(
    path: &Path,
    samples: &[(f64, f64)],
    reference: Option<(&str, &dyn Fn(f64) -> f64)>,
) -> CliResult {
    let points: Vec<(f64, f64)> = samples
        .iter()
        .copied()
        .filter(|(t, y)| *t > 0.0 && *y > 0.0)
        .collect();
    if points.len() < 2 {
        return Ok(());
    }
    let (t0, t1) = (points[0].0, points.last().unwrap().0);
    let (lo, hi) = points
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), p| (a.min(p.1), b.max(p.1)));
    let draw = || -> Result<(), Box<dyn std::error::Error>> {
        let root = BitMapBackend::new(path, (900, 600)).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .caption("granular temperature", ("sans-serif", 24))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d((t0..t1).log_scale(), (lo * 0.8..hi * 1.25).log_scale())?;
        chart.configure_mesh().x_desc("time t").y_desc("T").draw()?;
        chart
            .draw_series(LineSeries::new(
                points.iter().copied(),
                BLUE.stroke_width(2),
            ))?
            .label("simulation")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE));
        if let Some((name, f)) = reference {
            let curve: Vec<(f64, f64)> = (0..200)
                .map(|k| t0 * (t1 / t0).powf(k as f64 / 199.0))
                .map(|t| (t, f(t)))
                .filter(|(_, y)| *y >= lo * 0.8 && *y <= hi * 1.25)
                .collect();
            chart
                .draw_series(LineSeries::new(curve, RED.stroke_width(1)))?
                .label(name)
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RED));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()?;
        root.present()?;
        Ok(())
    };
    draw().map_err(|e| CliError::argument("--out", format!("writing {}: {e}", path.display())))
}
