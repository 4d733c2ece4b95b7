//! PNG figures of a run (plotters).

use crate::error::{Error, Result};
use plotters::prelude::*;
use std::path::Path;

/// T(t) on log-log axes, with an optional reference curve (Haff's law), as a PNG.
pub fn temperature(
    path: &Path,
    samples: &[(f64, f64)],
    reference: Option<(&str, &dyn Fn(f64) -> f64)>,
) -> Result<()> {
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
    let draw = || -> std::result::Result<(), Box<dyn std::error::Error>> {
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
    draw().map_err(|e| Error::Plot {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}

/// Axis scales of [`lines`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Axes<'a> {
    pub title: &'a str,
    pub x: &'a str,
    pub y: &'a str,
    pub log_x: bool,
    pub log_y: bool,
}

/// Several named curves on one chart as a PNG; curves named "theory..." or
/// "equilibrium..." are thin reference lines in the colour of the curve before them.
pub fn lines(path: &Path, axes: Axes, series: &[(String, Vec<(f64, f64)>)]) -> Result<()> {
    let keep = |&(x, y): &(f64, f64)| {
        x.is_finite() && y.is_finite() && (!axes.log_x || x > 0.0) && (!axes.log_y || y > 0.0)
    };
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|(_, s)| s.iter().copied().filter(keep))
        .collect();
    if all.len() < 2 {
        return Ok(());
    }
    let bounds = |f: fn(&(f64, f64)) -> f64| {
        all.iter()
            .map(f)
            .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)))
    };
    let (x0, x1) = bounds(|p| p.0);
    let (y0, y1) = bounds(|p| p.1);
    let pad = |lo: f64, hi: f64, log: bool| {
        if log {
            (lo / 1.3, hi * 1.3)
        } else {
            let d = (hi - lo).max(1e-300);
            (lo - 0.05 * d, hi + 0.05 * d)
        }
    };
    let ((x0, x1), (y0, y1)) = (pad(x0, x1, axes.log_x), pad(y0, y1, axes.log_y));
    let draw = || -> std::result::Result<(), Box<dyn std::error::Error>> {
        let root = BitMapBackend::new(path, (900, 600)).into_drawing_area();
        root.fill(&WHITE)?;
        let mut builder = ChartBuilder::on(&root);
        builder
            .caption(axes.title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(75);
        macro_rules! finish {
            ($chart:expr) => {{
                let mut chart = $chart;
                chart
                    .configure_mesh()
                    .x_desc(axes.x)
                    .y_desc(axes.y)
                    .draw()?;
                let mut curve = 0;
                for (name, points) in series {
                    // A reference line takes the colour of the curve before it.
                    let reference = name.starts_with("theory") || name.starts_with("equilibrium");
                    if !reference {
                        curve += 1;
                    }
                    let color = Palette99::pick(curve.max(1) - 1).to_rgba();
                    let width = if reference { 1 } else { 2 };
                    let data: Vec<(f64, f64)> = points.iter().copied().filter(keep).collect();
                    chart
                        .draw_series(LineSeries::new(data, color.stroke_width(width)))?
                        .label(name.as_str())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
                }
                chart
                    .configure_series_labels()
                    .background_style(WHITE.mix(0.8))
                    .border_style(BLACK)
                    .draw()?;
            }};
        }
        match (axes.log_x, axes.log_y) {
            (false, false) => finish!(builder.build_cartesian_2d(x0..x1, y0..y1)?),
            (true, false) => finish!(builder.build_cartesian_2d((x0..x1).log_scale(), y0..y1)?),
            (false, true) => finish!(builder.build_cartesian_2d(x0..x1, (y0..y1).log_scale())?),
            (true, true) => {
                finish!(builder.build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?)
            }
        }
        root.present()?;
        Ok(())
    };
    draw().map_err(|e| Error::Plot {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}
