//! Every figure haff draws, in one style (plotters), as PNG and SVG.
//!
//! The style is that of a journal figure: axis labels and tick labels at a legible size,
//! tick labels that read at a glance on log axes (`1e-3`, `0.01`, `250`), a colour-blind-safe
//! palette (Okabe & Ito 2008) in which no two curves share a colour (and, past eight curves,
//! a dash pattern tells them apart in print), theory as dashed lines, a paper's printed
//! values as markers, and the legend in its own panel beside the plot, where it cannot
//! cover data.

use crate::error::{Error, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// What a curve is, which sets how it is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Computed or measured data: a solid line.
    Line,
    /// Noisy raw data under a smoother curve (e.g. per-collision values under their running
    /// mean): a thin solid line.
    Noisy,
    /// A theory or reference curve: a dashed line.
    Theory,
    /// Values printed in a paper (or sparse measurements): markers, no line.
    Printed,
}

/// One named curve of a [`Figure`].
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub kind: Kind,
    /// Standard errors of the y values (drawn as vertical bars), if measured.
    pub errors: Option<Vec<f64>>,
}

/// A figure: title, axis labels (with symbols and units), scales, curves.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    pub title: String,
    pub x: String,
    pub y: String,
    pub log_x: bool,
    pub log_y: bool,
    pub curves: Vec<Curve>,
}

/// Pixel size of a figure (PNG and SVG alike).
const SIZE: (u32, u32) = (1200, 760);
/// Width of the legend panel (when there is a legend).
const LEGEND_WIDTH: u32 = 330;
const FONT: &str = "sans-serif";
const TITLE_SIZE: u32 = 26;
const AXIS_LABEL_SIZE: u32 = 24;
const TICK_SIZE: u32 = 19;
const LEGEND_SIZE: u32 = 18;
/// Line width in pixels.
const LINE_WIDTH: u32 = 3;

/// Okabe & Ito's colour-blind-safe palette, darkest first, yellow replaced by grey (it
/// vanishes on white).
const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(230, 159, 0),   // orange
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(0, 0, 0),       // black
    RGBColor(120, 120, 120), // grey
];

/// Dash and gap lengths (pixels) of curve `index`'s line: solid for the first eight data
/// curves, then dotted, dash-dotted...; theory curves are always dashed.
fn dashes(kind: Kind, index: usize) -> Option<(u32, u32)> {
    match (kind, index / PALETTE.len()) {
        (Kind::Theory, round) => Some((14 - 4 * (round as u32 % 3), 8)),
        (Kind::Line, 0) => None,
        (Kind::Line, round) => Some([(3, 5), (20, 6), (8, 4)][(round - 1) % 3]),
        (Kind::Printed, _) | (Kind::Noisy, _) => None,
    }
}

/// A tick label that reads at a glance: plain decimals from 1e-3 to 1e5 with at most
/// four significant digits and no trailing zeros, otherwise `1e-7`, `2.5e5`.
pub fn tick_label(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v == 0.0 { "0".into() } else { v.to_string() };
    }
    let trim = |s: String| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    let a = v.abs();
    if (1e-3..1e5).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
        let s = trim(format!("{v:.decimals$}"));
        if s == "-0" {
            "0".into()
        } else {
            s
        }
    } else {
        let s = format!("{v:.3e}");
        let (mantissa, exponent) = s.split_once('e').expect("{:e} has an exponent");
        format!("{}e{exponent}", trim(mantissa.to_string()))
    }
}

/// Splits a legend entry into lines of at most `width` characters at spaces.
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split_whitespace() {
        match lines.last_mut() {
            Some(line) if line.chars().count() + 1 + word.chars().count() <= width => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

type Drawn = std::result::Result<(), Box<dyn std::error::Error>>;

impl Figure {
    /// A figure with linear axes and no curves.
    pub fn new(title: impl Into<String>, x: impl Into<String>, y: impl Into<String>) -> Self {
        Figure {
            title: title.into(),
            x: x.into(),
            y: y.into(),
            log_x: false,
            log_y: false,
            curves: Vec::new(),
        }
    }

    /// Logarithmic x and/or y axis.
    pub fn log(mut self, log_x: bool, log_y: bool) -> Self {
        self.log_x = log_x;
        self.log_y = log_y;
        self
    }

    /// Adds a curve.
    pub fn curve(mut self, kind: Kind, name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        self.curves.push(Curve {
            name: name.into(),
            points,
            kind,
            errors: None,
        });
        self
    }

    /// Adds measurements with their standard errors: markers with vertical error bars
    /// (points (x, y, error)).
    pub fn measured(mut self, name: impl Into<String>, points: Vec<(f64, f64, f64)>) -> Self {
        self.curves.push(Curve {
            name: name.into(),
            points: points.iter().map(|p| (p.0, p.1)).collect(),
            kind: Kind::Printed,
            errors: Some(points.iter().map(|p| p.2).collect()),
        });
        self
    }

    /// Adds a data curve (solid line).
    pub fn line(self, name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        self.curve(Kind::Line, name, points)
    }

    /// Adds noisy raw data (a thin line).
    pub fn noisy(self, name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        self.curve(Kind::Noisy, name, points)
    }

    /// Adds a theory curve (dashed line).
    pub fn theory(self, name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        self.curve(Kind::Theory, name, points)
    }

    /// Adds printed values (markers).
    pub fn printed(self, name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        self.curve(Kind::Printed, name, points)
    }

    fn drawable(&self, p: &(f64, f64)) -> bool {
        let (x, y) = *p;
        x.is_finite() && y.is_finite() && (!self.log_x || x > 0.0) && (!self.log_y || y > 0.0)
    }

    /// The padded ranges of the drawable points, or None if fewer than two.
    fn ranges(&self) -> Option<((f64, f64), (f64, f64))> {
        let all: Vec<(f64, f64)> = self
            .curves
            .iter()
            .flat_map(|c| c.points.iter().copied().filter(|p| self.drawable(p)))
            .collect();
        if all.len() < 2 {
            return None;
        }
        let bounds = |f: fn(&(f64, f64)) -> f64| {
            all.iter()
                .map(f)
                .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)))
        };
        let pad = |(lo, hi): (f64, f64), log: bool| {
            if log {
                let (lo, hi) = if lo == hi {
                    (lo / 2.0, hi * 2.0)
                } else {
                    (lo, hi)
                };
                ((hi / lo).powf(-0.04) * lo, (hi / lo).powf(0.04) * hi)
            } else {
                let d = if hi > lo { hi - lo } else { lo.abs().max(1.0) };
                (lo - 0.04 * d, hi + 0.04 * d)
            }
        };
        Some((
            pad(bounds(|p| p.0), self.log_x),
            pad(bounds(|p| p.1), self.log_y),
        ))
    }

    /// Writes the figure as a PNG (nothing if it has fewer than two drawable points).
    pub fn write_png(&self, path: &Path) -> Result<()> {
        self.write_with(path, |f| {
            f.render(BitMapBackend::new(path, SIZE).into_drawing_area())
        })
    }

    /// Writes the figure as an SVG (nothing if it has fewer than two drawable points).
    pub fn write_svg(&self, path: &Path) -> Result<()> {
        self.write_with(path, |f| {
            f.render(SVGBackend::new(path, SIZE).into_drawing_area())
        })
    }

    /// Writes `stem.png` and `stem.svg`.
    pub fn write_png_and_svg(&self, stem: &Path) -> Result<()> {
        self.write_png(&stem.with_extension("png"))?;
        self.write_svg(&stem.with_extension("svg"))
    }

    fn write_with(&self, path: &Path, draw: impl Fn(&Self) -> Drawn) -> Result<()> {
        if self.ranges().is_none() {
            return Ok(());
        }
        draw(self).map_err(|e| Error::Plot {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
    }

    fn render<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Drawn
    where
        DB::ErrorType: 'static,
    {
        let ((x0, x1), (y0, y1)) = self.ranges().expect("checked by write_with");
        root.fill(&WHITE)?;
        let titled = root.titled(&self.title, (FONT, TITLE_SIZE))?;
        let legend = self.curves.iter().any(|c| !c.name.is_empty());
        let (plot, panel) = if legend {
            let width = titled.dim_in_pixel().0;
            titled.split_horizontally(width.saturating_sub(LEGEND_WIDTH))
        } else {
            let width = titled.dim_in_pixel().0;
            titled.split_horizontally(width)
        };
        let mut builder = ChartBuilder::on(&plot);
        builder
            .margin_top(10)
            .margin_right(25)
            .margin_left(10)
            .x_label_area_size(70)
            .y_label_area_size(105);
        // A log axis is drawn as a linear axis of log10 (plotters' own log axis drops the
        // labels of some decades over wide ranges): over three decades or more only the
        // decades are labelled, over less every tick, as its value.
        let to_axis = |log: bool, v: f64| if log { v.log10() } else { v };
        let (span_x, span_y) = (x1.log10() - x0.log10(), y1.log10() - y0.log10());
        let log_label = |v: f64, span: f64| {
            if span >= 3.0 {
                if (v - v.round()).abs() < 1e-6 {
                    // Decades: plain from 0.001 to 1000, else 1e-7, 1e4.
                    let k = v.round() as i32;
                    if (-3..=3).contains(&k) {
                        tick_label(10f64.powi(k))
                    } else {
                        format!("1e{k}")
                    }
                } else {
                    String::new()
                }
            } else {
                // Two significant digits: 1.6, 2.5, 4, 6.3, 10 (ticks at 10^(k/5)).
                let value = 10f64.powf(v);
                let digits = 10f64.powi(1 - value.log10().floor() as i32);
                tick_label((value * digits).round() / digits)
            }
        };
        let x_label = |v: &f64| {
            if self.log_x {
                log_label(*v, span_x)
            } else {
                tick_label(*v)
            }
        };
        let y_label = |v: &f64| {
            if self.log_y {
                log_label(*v, span_y)
            } else {
                tick_label(*v)
            }
        };
        let mut chart = builder.build_cartesian_2d(
            to_axis(self.log_x, x0)..to_axis(self.log_x, x1),
            to_axis(self.log_y, y0)..to_axis(self.log_y, y1),
        )?;
        chart
            .configure_mesh()
            .x_desc(self.x.as_str())
            .y_desc(self.y.as_str())
            .axis_desc_style((FONT, AXIS_LABEL_SIZE))
            .label_style((FONT, TICK_SIZE))
            .x_label_formatter(&x_label)
            .y_label_formatter(&y_label)
            .x_labels(if self.log_x { 12 } else { 8 })
            .y_labels(if self.log_y { 12 } else { 8 })
            .bold_line_style(RGBColor(215, 215, 215))
            .light_line_style(RGBColor(245, 245, 245))
            .max_light_lines(4)
            .draw()?;
        for (index, curve) in self.curves.iter().enumerate() {
            let color = PALETTE[index % PALETTE.len()];
            let data: Vec<(f64, f64)> = curve
                .points
                .iter()
                .copied()
                .filter(|p| self.drawable(p))
                .map(|(x, y)| (to_axis(self.log_x, x), to_axis(self.log_y, y)))
                .collect();
            match (curve.kind, dashes(curve.kind, index)) {
                (Kind::Printed, _) => {
                    chart.draw_series(data.iter().map(|&p| Circle::new(p, 6, color.filled())))?;
                    if let Some(errors) = &curve.errors {
                        let bars = curve.points.iter().zip(errors).filter_map(|(&(x, y), &e)| {
                            let ends = [(x, y - e), (x, y + e)];
                            (e.is_finite() && ends.iter().all(|p| self.drawable(p))).then(|| {
                                let ends = ends
                                    .map(|(x, y)| (to_axis(self.log_x, x), to_axis(self.log_y, y)));
                                PathElement::new(ends.to_vec(), color.stroke_width(2))
                            })
                        });
                        chart.draw_series(bars)?;
                    }
                }
                (kind, None) => {
                    // Segment by segment: plotters joins a thick polyline with miters,
                    // which spike far out of the plot at sharp zigzags of noisy data.
                    let width = if kind == Kind::Noisy { 1 } else { LINE_WIDTH };
                    chart
                        .draw_series(data.windows(2).map(|pair| {
                            PathElement::new(pair.to_vec(), color.stroke_width(width))
                        }))?;
                }
                (_, Some((dash, gap))) => {
                    chart.draw_series(DashedLineSeries::new(
                        data,
                        dash,
                        gap,
                        color.stroke_width(LINE_WIDTH),
                    ))?;
                }
            }
        }
        if legend {
            self.draw_legend(&panel)?;
        }
        root.present()?;
        Ok(())
    }

    /// The legend panel: a sample of each curve's line or marker and its name, wrapped.
    fn draw_legend<DB: DrawingBackend>(&self, panel: &DrawingArea<DB, Shift>) -> Drawn
    where
        DB::ErrorType: 'static,
    {
        let font = (FONT, LEGEND_SIZE).into_font().color(&BLACK);
        let line_height = LEGEND_SIZE as i32 + 6;
        let mut y = 30;
        for (index, curve) in self.curves.iter().enumerate() {
            if curve.name.is_empty() {
                continue;
            }
            let color = PALETTE[index % PALETTE.len()];
            let mid = y + LEGEND_SIZE as i32 / 2;
            match (curve.kind, dashes(curve.kind, index)) {
                (Kind::Printed, _) => {
                    panel.draw(&Circle::new((22, mid), 6, color.filled()))?;
                }
                (kind, None) => {
                    let width = if kind == Kind::Noisy { 1 } else { LINE_WIDTH };
                    panel.draw(&PathElement::new(
                        vec![(5, mid), (40, mid)],
                        color.stroke_width(width),
                    ))?;
                }
                (_, Some((dash, gap))) => {
                    let mut x = 5;
                    while x < 40 {
                        let end = (x + dash as i32).min(40);
                        panel.draw(&PathElement::new(
                            vec![(x, mid), (end, mid)],
                            color.stroke_width(LINE_WIDTH),
                        ))?;
                        x = end + gap as i32;
                    }
                }
            }
            for line in wrap(&curve.name, 30) {
                panel.draw(&Text::new(line, (50, y), font.clone()))?;
                y += line_height;
            }
            y += 8;
        }
        Ok(())
    }
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
/// "equilibrium..." are reference lines (dashed).
pub fn lines(path: &Path, axes: Axes, series: &[(String, Vec<(f64, f64)>)]) -> Result<()> {
    let mut figure = Figure::new(axes.title, axes.x, axes.y).log(axes.log_x, axes.log_y);
    for (name, points) in series {
        let kind = if name.starts_with("theory") || name.starts_with("equilibrium") {
            Kind::Theory
        } else {
            Kind::Line
        };
        figure = figure.curve(kind, name.as_str(), points.clone());
    }
    figure.write_png(path)
}

/// T(t) on log-log axes, with an optional reference curve (Haff's law) sampled over the
/// run's time span, as a PNG.
pub fn temperature(
    path: &Path,
    samples: &[(f64, f64)],
    species: &[(String, Vec<(f64, f64)>)],
    reference: Option<(&str, &dyn Fn(f64) -> f64)>,
) -> Result<()> {
    let positive = |points: &[(f64, f64)]| -> Vec<(f64, f64)> {
        points
            .iter()
            .copied()
            .filter(|(t, y)| *t > 0.0 && *y > 0.0)
            .collect()
    };
    let points = positive(samples);
    let mut figure = Figure::new("granular temperature", "time t", "temperature T").log(true, true);
    let curve = match (reference, points.first(), points.last()) {
        (Some((name, f)), Some(first), Some(last)) => {
            let (t0, t1) = (first.0, last.0);
            let curve = (0..200)
                .map(|k| t0 * (t1 / t0).powf(k as f64 / 199.0))
                .map(|t| (t, f(t)))
                .collect();
            Some((name, curve))
        }
        _ => None,
    };
    let label = if species.is_empty() {
        "simulation"
    } else {
        "mixture"
    };
    figure = figure.line(label, points);
    for (name, points) in species {
        figure = figure.line(name, positive(points));
    }
    if let Some((name, curve)) = curve {
        figure = figure.theory(name, curve);
    }
    figure.write_png(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_read_at_a_glance() {
        let cases = [
            (1e-7, "1e-7"),
            (2.5e-5, "2.5e-5"),
            (1e-3, "0.001"),
            (0.01, "0.01"),
            (0.5, "0.5"),
            (1.0, "1"),
            (12.5, "12.5"),
            (250.0, "250"),
            (1000.0, "1000"),
            (1e4, "10000"),
            (1.5e4, "15000"),
            (1e5, "1e5"),
            (3.0e6, "3e6"),
            (-0.2, "-0.2"),
            (0.0, "0"),
            (0.30000000000000004, "0.3"),
        ];
        for (v, want) in cases {
            assert_eq!(tick_label(v), want, "{v}");
        }
    }

    #[test]
    fn legend_entries_wrap_at_spaces() {
        assert_eq!(
            wrap("equilibrium (equipartition with the modes)", 30),
            vec!["equilibrium (equipartition", "with the modes)"]
        );
    }

    #[test]
    fn no_two_of_the_first_eight_curves_look_alike() {
        let looks: Vec<_> = (0..16)
            .map(|i| (PALETTE[i % 8], dashes(Kind::Line, i)))
            .collect();
        for i in 0..looks.len() {
            for j in 0..i {
                assert_ne!(looks[i], looks[j], "{i} {j}");
            }
        }
    }

    #[test]
    fn writes_png_and_svg() {
        let dir = std::env::temp_dir().join(format!("haff-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let stem = dir.join("figure");
        Figure::new("a test", "v* (scaled impact speed)", "eps")
            .log(true, true)
            .line("data", vec![(1e-3, 1.0), (1.0, 0.5), (1e3, 1e-7)])
            .theory("theory", vec![(1e-3, 0.9), (1e3, 2e-7)])
            .printed("printed", vec![(1.0, 0.4)])
            .write_png_and_svg(&stem)
            .unwrap();
        let png = std::fs::read(stem.with_extension("png")).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        let svg = std::fs::read_to_string(stem.with_extension("svg")).unwrap();
        assert!(svg.contains("<svg") && svg.contains("1e-7"));
        if std::env::var_os("HAFF_KEEP_TEST_FIGURE").is_none() {
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }
}
