//! Heat maps of 2D fields as PNG (plotters), for a look at a run without ParaView: the
//! coarse-grained density and vorticity of a clustering gas side by side, each with its
//! colour bar, axes in units of the particle diameter. The run's field observer
//! ([`crate::space`]) writes one `fields_NNNNNN.png` per field sample: the whole box in 2D,
//! the mid-plane layer of cells at z = L/2 in 3D.
//!
//! Colour maps:
//! - sequential ([`viridis`]): matplotlib's viridis (van der Walt, Smith & Firing 2015;
//!   perceptually uniform, readable in grey and by colour-blind readers);
//! - diverging ([`blue_white_red`]): ColorBrewer's RdBu (Brewer 2002), reversed so that
//!   negative is blue, with its centre made pure white.

use crate::error::{Error, Result};
use crate::plot::tick_label;
use gas::structure::Fields;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

/// 16 evenly spaced samples (entries 0, 17, ..., 255 of 256) of matplotlib's viridis
/// (`_viridis_data` of mpl-colormaps, CC0), as 8-bit RGB; linear in between.
const VIRIDIS: [[u8; 3]; 16] = [
    [68, 1, 84],
    [72, 26, 108],
    [71, 47, 125],
    [65, 68, 135],
    [57, 86, 140],
    [49, 104, 142],
    [42, 120, 142],
    [35, 136, 142],
    [31, 152, 139],
    [34, 168, 132],
    [53, 183, 121],
    [84, 197, 104],
    [122, 209, 81],
    [165, 219, 54],
    [210, 226, 27],
    [253, 231, 37],
];

/// ColorBrewer RdBu, 11 classes, reversed (#053061 ... #67001f), centre #f7f7f7 made white.
const BLUE_WHITE_RED: [[u8; 3]; 11] = [
    [5, 48, 97],
    [33, 102, 172],
    [67, 147, 195],
    [146, 197, 222],
    [209, 229, 240],
    [255, 255, 255],
    [253, 219, 199],
    [244, 165, 130],
    [214, 96, 77],
    [178, 24, 43],
    [103, 0, 31],
];

/// The colour at t in [0, 1] (clamped; NaN as 0) of evenly spaced control points.
fn interpolate(points: &[[u8; 3]], t: f64) -> RGBColor {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let x = t * (points.len() - 1) as f64;
    let i = (x.floor() as usize).min(points.len() - 2);
    let f = x - i as f64;
    let c = |a: usize| {
        let (p, q) = (f64::from(points[i][a]), f64::from(points[i + 1][a]));
        (p + f * (q - p)).round() as u8
    };
    RGBColor(c(0), c(1), c(2))
}

/// Viridis at t in [0, 1] (clamped): dark violet at 0, yellow at 1.
pub fn viridis(t: f64) -> RGBColor {
    interpolate(&VIRIDIS, t)
}

/// The diverging map at t in [-1, 1] (clamped): dark blue at -1, white at 0, dark red at 1.
pub fn blue_white_red(t: f64) -> RGBColor {
    interpolate(&BLUE_WHITE_RED, 0.5 * (t + 1.0))
}

/// How the values of a [`HeatMap`] are coloured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scale {
    /// [`viridis`] from 0 to `max` (values above in the top colour).
    Sequential { max: f64 },
    /// [`blue_white_red`] from -`max` to `max`.
    Diverging { max: f64 },
}

impl Scale {
    fn colour(&self, v: f64) -> RGBColor {
        match *self {
            Scale::Sequential { max } => viridis(v / max),
            Scale::Diverging { max } => blue_white_red(v / max),
        }
    }

    fn range(&self) -> Range<f64> {
        match *self {
            Scale::Sequential { max } => 0.0..max,
            Scale::Diverging { max } => -max..max,
        }
    }
}

/// A scalar field on a `grid` × `grid` square grid of side `side` (x fastest, y up), with
/// its title (what and in which unit) and colour scale.
#[derive(Debug, Clone, PartialEq)]
pub struct HeatMap {
    pub title: String,
    pub grid: usize,
    /// Side of the square, in the unit of the axes.
    pub side: f64,
    pub values: Vec<f64>,
    pub scale: Scale,
}

/// Pixel size of a figure of two maps.
pub const SIZE: (u32, u32) = (1500, 720);
const FONT: &str = "sans-serif";
const TITLE_SIZE: u32 = 26;
const MAP_TITLE_SIZE: u32 = 22;
const AXIS_LABEL_SIZE: u32 = 22;
const TICK_SIZE: u32 = 18;
/// Width of a colour-bar panel (bar and its tick labels).
const BAR_PANEL: u32 = 130;
const BAR_WIDTH: u32 = 28;
/// Grids finer than this are drawn by sampling (a map is about this many pixels wide).
const MAX_DRAWN: usize = 512;

type Drawn = std::result::Result<Vec<(Range<i32>, Range<i32>)>, Box<dyn std::error::Error>>;

/// Writes `maps` side by side under `title` as a PNG of [`SIZE`], axes labelled `x / {unit}`
/// and `y / {unit}`.
pub fn write_png(path: &Path, title: &str, unit: &str, maps: &[HeatMap]) -> Result<()> {
    render(path, title, unit, maps)
        .map(|_| ())
        .map_err(|e| Error::Plot {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
}

/// Draws the figure; returns the pixel ranges (x, y) of each map's plotting area.
fn render(path: &Path, title: &str, unit: &str, maps: &[HeatMap]) -> Drawn {
    for m in maps {
        if m.values.len() != m.grid * m.grid || m.grid == 0 {
            return Err(format!(
                "{}: {} values on a {}² grid",
                m.title,
                m.values.len(),
                m.grid
            )
            .into());
        }
    }
    let root = BitMapBackend::new(path, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let titled = root.titled(title, (FONT, TITLE_SIZE))?;
    let mut areas = Vec::new();
    if !maps.is_empty() {
        let panels = titled.split_evenly((1, maps.len()));
        for (map, panel) in maps.iter().zip(&panels) {
            areas.push(draw_map(map, unit, panel)?);
        }
    }
    root.present()?;
    Ok(areas)
}

fn draw_map<DB: DrawingBackend>(
    map: &HeatMap,
    unit: &str,
    panel: &DrawingArea<DB, Shift>,
) -> std::result::Result<(Range<i32>, Range<i32>), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    let panel = panel.titled(&map.title, (FONT, MAP_TITLE_SIZE))?;
    let (width, height) = panel.dim_in_pixel();
    let (square, bar) = panel.split_horizontally(width.saturating_sub(BAR_PANEL));
    // A square plotting area, centred in what the labels leave.
    let (x_labels, y_labels, margin) = (60u32, 75u32, 12u32);
    let room_x = square
        .dim_in_pixel()
        .0
        .saturating_sub(y_labels + 2 * margin);
    let room_y = height.saturating_sub(x_labels + 2 * margin);
    let side = room_x.min(room_y);
    let (top, left) = (margin + (room_y - side) / 2, margin + (room_x - side) / 2);
    let bottom = height - top - side - x_labels;
    let mut chart = ChartBuilder::on(&square)
        .margin_top(top)
        .margin_bottom(bottom)
        .margin_left(left)
        .margin_right(square.dim_in_pixel().0 - left - y_labels - side)
        .x_label_area_size(x_labels)
        .y_label_area_size(y_labels)
        .build_cartesian_2d(0.0..map.side, 0.0..map.side)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(format!("x / {unit}"))
        .y_desc(format!("y / {unit}"))
        .axis_desc_style((FONT, AXIS_LABEL_SIZE))
        .label_style((FONT, TICK_SIZE))
        .x_labels(6)
        .y_labels(6)
        .x_label_formatter(&|v| tick_label(*v))
        .y_label_formatter(&|v| tick_label(*v))
        .draw()?;
    let g = map.grid;
    let drawn = g.min(MAX_DRAWN);
    let source = |i: usize| ((i as f64 + 0.5) * g as f64 / drawn as f64) as usize;
    let pixels = chart.plotting_area().get_pixel_range();
    // Cells in pixels (a filled rectangle covers [start, end) in both axes, so the cells
    // tile the plotting area exactly), y up.
    let area = chart.plotting_area().strip_coord_spec();
    let (w, h) = (pixels.0.len(), pixels.1.len());
    let x = |i: usize| (i * w / drawn) as i32;
    let y = |j: usize| (h - j * h / drawn) as i32;
    for c in 0..drawn * drawn {
        let (i, j) = (c % drawn, c / drawn);
        let value = map.values[source(i) + g * source(j)];
        area.draw(&Rectangle::new(
            [(x(i), y(j + 1)), (x(i + 1), y(j))],
            map.scale.colour(value).filled(),
        ))?;
    }
    frame(&area, w, h)?;

    // The colour bar, as tall as the map, its labels to the right.
    let range = map.scale.range();
    let mut bar_chart = ChartBuilder::on(&bar)
        .margin_top(top)
        .margin_bottom(bottom + x_labels)
        .margin_left(8)
        .margin_right(BAR_PANEL - 8 - BAR_WIDTH - 80)
        .set_label_area_size(LabelAreaPosition::Right, 80)
        .build_cartesian_2d(0.0..1.0, range.clone())?;
    bar_chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .label_style((FONT, TICK_SIZE))
        .y_labels(7)
        .y_label_formatter(&|v| {
            // A tick at zero comes out as a rounding error of the range's end points.
            let zero = v.abs() < 1e-9 * (range.end - range.start);
            format!("  {}", tick_label(if zero { 0.0 } else { *v }))
        })
        .draw()?;
    let (bw, bh) = bar_chart.plotting_area().dim_in_pixel();
    let (bw, bh) = (bw as usize, bh as usize);
    let bar = bar_chart.plotting_area().strip_coord_spec();
    for row in 0..bh {
        let t = (bh - row) as f64 - 0.5;
        let v = range.start + t / bh as f64 * (range.end - range.start);
        bar.draw(&Rectangle::new(
            [(0, row as i32), (bw as i32, row as i32 + 1)],
            map.scale.colour(v).filled(),
        ))?;
    }
    frame(&bar, bw, bh)?;
    Ok(pixels)
}

/// A black line around an area of w × h pixels (just outside it).
fn frame<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    w: usize,
    h: usize,
) -> std::result::Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    area.draw(&Rectangle::new(
        [(-1, -1), (w as i32, h as i32)],
        BLACK.stroke_width(1),
    ))?;
    Ok(())
}

/// The density n / <n> and vorticity omega_z (z component) of a plane of `fields`: the
/// whole grid in 2D, in 3D the layer of cells k = G/2 (from z = L/2 to L/2 + L/G for even
/// G, around L/2 for odd G); None in 1D. `mean_density` is N / L^D.
pub fn plane<const D: usize>(
    fields: &Fields<D>,
    mean_density: f64,
) -> Option<(Vec<f64>, Vec<f64>)> {
    let g = fields.grid;
    let start = match D {
        2 => 0,
        3 => g * g * (g / 2),
        _ => return None,
    };
    let cells = start..start + g * g;
    let density = fields.density[cells.clone()]
        .iter()
        .map(|n| n / mean_density)
        .collect();
    let vorticity = fields.vorticity[cells].iter().map(|w| w[2]).collect();
    Some((density, vorticity))
}

/// The two maps of a field sample: density n / <n> on [0, max(3, ⌈largest⌉)] and vorticity
/// omega_z symmetric about zero up to the largest |omega_z|; `side` in the axes' unit.
pub fn density_and_vorticity(
    grid: usize,
    side: f64,
    density: Vec<f64>,
    vorticity: Vec<f64>,
) -> [HeatMap; 2] {
    let largest = |v: &[f64]| {
        v.iter()
            .map(|x| x.abs())
            .filter(|x| x.is_finite())
            .fold(0.0, f64::max)
    };
    let top = largest(&density).ceil().max(3.0);
    let omega = largest(&vorticity);
    let omega = if omega > 0.0 { omega } else { 1.0 };
    [
        HeatMap {
            title: "density n / <n>".into(),
            grid,
            side,
            values: density,
            scale: Scale::Sequential { max: top },
        },
        HeatMap {
            title: "vorticity omega_z".into(),
            grid,
            side,
            values: vorticity,
            scale: Scale::Diverging { max: omega },
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn luminance(c: RGBColor) -> f64 {
        // Relative luminance of sRGB (ITU-R BT.709 weights on linearized channels).
        let lin = |u: u8| {
            let c = f64::from(u) / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        0.2126 * lin(c.0) + 0.7152 * lin(c.1) + 0.0722 * lin(c.2)
    }

    #[test]
    fn colour_maps() {
        assert_eq!(viridis(0.0), RGBColor(68, 1, 84));
        assert_eq!(viridis(1.0), RGBColor(253, 231, 37));
        assert_eq!(viridis(-1.0), viridis(0.0));
        assert_eq!(viridis(7.0), viridis(1.0));
        // Luminance rises monotonically (up to the rounding to 8 bits).
        let mut last = -1.0;
        for k in 0..=1000 {
            let l = luminance(viridis(k as f64 / 1000.0));
            assert!(l >= last - 1e-3, "viridis luminance falls at {k}");
            last = f64::max(l, last);
        }
        assert!(luminance(viridis(1.0)) > 20.0 * luminance(viridis(0.0)));
        assert_eq!(blue_white_red(0.0), RGBColor(255, 255, 255));
        assert_eq!(blue_white_red(-1.0), RGBColor(5, 48, 97));
        assert_eq!(blue_white_red(1.0), RGBColor(103, 0, 31));
        // Luminance rises to white at 0 and falls after, symmetric to a few per cent.
        for k in 1..=100 {
            let t = k as f64 / 100.0;
            let (neg, pos) = (luminance(blue_white_red(-t)), luminance(blue_white_red(t)));
            assert!(neg <= luminance(blue_white_red(-t + 0.01)) + 1e-3);
            assert!(pos <= luminance(blue_white_red(t - 0.01)) + 1e-3);
            assert!((neg - pos).abs() < 0.1, "{t}: {neg} {pos}");
        }
    }

    /// A synthetic field: dense (n / <n> = 3) in the lower-left quarter, empty elsewhere,
    /// no vorticity. The map of the dense quarter is the top of viridis, the vorticity map
    /// white; the PNG has the figure's size.
    #[test]
    fn dense_region_in_the_top_colour() {
        let dir = std::env::temp_dir().join(format!("haff-maps-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("maps.png");
        let g = 16;
        let density: Vec<f64> = (0..g * g)
            .map(|c| {
                if c % g < g / 2 && c / g < g / 2 {
                    3.0
                } else {
                    0.0
                }
            })
            .collect();
        let maps = density_and_vorticity(g, 40.0, density, vec![0.0; g * g]);
        assert_eq!(maps[0].scale, Scale::Sequential { max: 3.0 });
        let areas = render(&path, "test", "sigma", &maps).unwrap();
        let decoder = png::Decoder::new(std::fs::File::open(&path).unwrap());
        let mut reader = decoder.read_info().unwrap();
        let mut buffer = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buffer).unwrap();
        assert_eq!((info.width, info.height), SIZE);
        assert_eq!(info.color_type, png::ColorType::Rgb);
        let pixel = |x: i32, y: i32| {
            let k = 3 * (y as usize * info.width as usize + x as usize);
            RGBColor(buffer[k], buffer[k + 1], buffer[k + 2])
        };
        let at = |(xs, ys): &(Range<i32>, Range<i32>), fx: f64, fy: f64| {
            // fy from the bottom (y up)
            let x = xs.start + (fx * (xs.end - xs.start) as f64) as i32;
            let y = ys.end - 1 - (fy * (ys.end - ys.start) as f64) as i32;
            pixel(x, y)
        };
        let (d, w) = (&areas[0], &areas[1]);
        assert_eq!(d.0.len(), d.1.len(), "square map");
        assert_eq!(at(d, 0.25, 0.25), viridis(1.0));
        assert_eq!(at(d, 0.75, 0.75), viridis(0.0));
        assert_eq!(at(d, 0.75, 0.25), viridis(0.0));
        assert_eq!(at(w, 0.5, 0.5), RGBColor(255, 255, 255));
        if std::env::var_os("HAFF_KEEP_TEST_FIGURE").is_none() {
            std::fs::remove_dir_all(&dir).unwrap();
        }
    }
}
