//! Shared layout of every chart: colours, the SVG page and its title, the
//! chart area and its mesh (grid, ticks, tick labels), bounding boxes and
//! number formatting; rendering into a string written atomically.

use crate::numeric::nice_step;
use crate::PlotError;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// Viridis, sampled at 9 equally spaced stops.
const VIRIDIS: [(u8, u8, u8); 9] = [
    (68, 1, 84),
    (71, 44, 122),
    (59, 82, 139),
    (44, 114, 142),
    (33, 145, 140),
    (40, 174, 128),
    (94, 201, 98),
    (173, 220, 48),
    (253, 231, 37),
];

/// Perceptual colour map (viridis-like) for `t` in [0, 1] (clamped).
pub(crate) fn colormap(t: f64) -> RGBColor {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let s = t * (VIRIDIS.len() - 1) as f64;
    let j = (s.floor() as usize).min(VIRIDIS.len() - 2);
    let f = s - j as f64;
    let (a, b) = (VIRIDIS[j], VIRIDIS[j + 1]);
    let mix = |p: u8, q: u8| (p as f64 + f * (q as f64 - p as f64)).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Qualitative palette for curves (Tableau 10, black first).
pub(crate) const PALETTE: [RGBColor; 10] = [
    RGBColor(0, 0, 0),
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
    RGBColor(188, 189, 34),
];

pub(crate) type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;
pub(crate) type DResult<T = ()> = Result<T, String>;

pub(crate) const FONT: &str = "sans-serif";
pub(crate) const TITLE_H: u32 = 48;
pub(crate) const MARGIN: u32 = 14;
pub(crate) const X_LABEL_AREA: u32 = 58;
pub(crate) const Y_LABEL_AREA: u32 = 90;
const TITLE_FONT: f64 = 27.0;
pub(crate) const TICK_FONT: f64 = 18.0;
pub(crate) const DESC_FONT: f64 = 20.0;

pub(crate) fn de<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

pub(crate) fn text_style(size: f64, h: HPos, v: VPos) -> TextStyle<'static> {
    TextStyle::from((FONT, size).into_font()).pos(Pos::new(h, v))
}

/// Rough width of `text` in pixels for a plotters font size `size`
/// (the SVG font size is `size / 1.24`; sans-serif digits are ~0.64 em wide).
pub(crate) fn text_width(text: &str, size: f64) -> i32 {
    (text.chars().count() as f64 * 0.62 * size / 1.24).ceil() as i32
}

/// Renders into an SVG string of `size` pixels.
fn render_svg(size: (u32, u32), draw: impl FnOnce(&Area<'_>) -> DResult) -> DResult<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(de)?;
        draw(&root)?;
        root.present().map_err(de)?;
    }
    Ok(svg)
}

/// Renders and writes atomically, mapping errors to [`PlotError`].
pub(crate) fn render_to_file(
    path: &Path,
    size: (u32, u32),
    draw: impl FnOnce(&Area<'_>) -> DResult,
) -> Result<(), PlotError> {
    let svg = render_svg(size, draw).map_err(|msg| PlotError::Drawing {
        path: path.to_path_buf(),
        msg,
    })?;
    Ok(formats::output::write_atomic(path, svg.as_bytes())?)
}

/// Draws the title on top of `root` and splits the rest into the chart area
/// and a column of `right_w` pixels on the right (legend or colour bar).
pub(crate) fn frame<'a>(
    root: &Area<'a>,
    title: &str,
    right_w: u32,
) -> DResult<(Area<'a>, Area<'a>)> {
    let (w, _) = root.dim_in_pixel();
    let (top, body) = root.split_vertically(TITLE_H);
    top.draw(&Text::new(
        title.to_string(),
        ((w / 2) as i32, (TITLE_H / 2) as i32 + 2),
        text_style(TITLE_FONT, HPos::Center, VPos::Center),
    ))
    .map_err(de)?;
    let right_w = right_w.min(w / 2);
    Ok(body.split_horizontally(w - right_w))
}

pub(crate) fn chart_builder<'a, 'b>(area: &'a Area<'b>) -> ChartBuilder<'a, 'b, SVGBackend<'b>> {
    let mut cb = ChartBuilder::on(area);
    cb.margin(MARGIN)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA);
    cb
}

/// Absolute pixel ranges (x, y) of the plotting area that [`chart_builder`]
/// makes on `area`.
pub(crate) fn plot_pixel_range(
    area: &Area<'_>,
) -> DResult<(std::ops::Range<i32>, std::ops::Range<i32>)> {
    let probe = chart_builder(area)
        .build_cartesian_2d(0f64..1f64, 0f64..1f64)
        .map_err(de)?;
    Ok(probe.plotting_area().get_pixel_range())
}

/// Pixel spans onto which plotters maps the x and y ranges (it maps onto
/// `start..end - 1`).
pub(crate) fn pixel_spans(px: &(std::ops::Range<i32>, std::ops::Range<i32>)) -> (u32, u32) {
    (
        (px.0.end - px.0.start - 1).max(1) as u32,
        (px.1.end - px.1.start - 1).max(1) as u32,
    )
}

/// Bounding box of finite points.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BBox {
    pub(crate) x0: f64,
    pub(crate) x1: f64,
    pub(crate) y0: f64,
    pub(crate) y1: f64,
}

impl BBox {
    pub(crate) fn empty() -> Self {
        BBox {
            x0: f64::INFINITY,
            x1: f64::NEG_INFINITY,
            y0: f64::INFINITY,
            y1: f64::NEG_INFINITY,
        }
    }
    pub(crate) fn add(&mut self, p: (f64, f64)) {
        if p.0.is_finite() && p.1.is_finite() {
            self.x0 = self.x0.min(p.0);
            self.x1 = self.x1.max(p.0);
            self.y0 = self.y0.min(p.1);
            self.y1 = self.y1.max(p.1);
        }
    }
    pub(crate) fn is_empty(&self) -> bool {
        self.x0 > self.x1
    }
    pub(crate) fn extent(&self) -> f64 {
        if self.is_empty() {
            0.0
        } else {
            (self.x1 - self.x0).max(self.y1 - self.y0)
        }
    }
}

/// Range padded by `frac` of its span on both sides; degenerate ranges get a
/// span of 10 % of their magnitude (or 1).
pub(crate) fn padded(lo: f64, hi: f64, frac: f64) -> (f64, f64) {
    let span = hi - lo;
    if span > 0.0 {
        (lo - frac * span, hi + frac * span)
    } else {
        let h = if lo != 0.0 { 0.1 * lo.abs() } else { 1.0 };
        (lo - h, hi + h)
    }
}

/// Splits a polyline at non-finite points into finite runs.
pub(crate) fn finite_runs(points: impl IntoIterator<Item = (f64, f64)>) -> Vec<Vec<(f64, f64)>> {
    let mut runs = vec![Vec::new()];
    for p in points {
        if p.0.is_finite() && p.1.is_finite() {
            runs.last_mut().unwrap().push(p);
        } else if !runs.last().unwrap().is_empty() {
            runs.push(Vec::new());
        }
    }
    runs.retain(|r| !r.is_empty());
    runs
}

/// Number of decimals needed to print multiples of `step`.
pub(crate) fn decimals_for(step: f64) -> usize {
    if !(step.is_finite() && step > 0.0) || step >= 1.0 {
        0
    } else {
        ((-step.log10()).ceil() as usize).min(12)
    }
}

pub(crate) fn fmt_num(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        s.trim_start_matches('-').to_string()
    } else {
        s.replace('-', "\u{2212}")
    }
}

/// Formats axis tick labels with a precision fitting the tick spacing.
fn tick_formatter(lo: f64, hi: f64, n: usize) -> impl Fn(&f64) -> String {
    let step = nice_step((hi - lo).abs() / n.max(1) as f64);
    let d = decimals_for(step);
    move |v: &f64| fmt_num(*v, d)
}

/// `text`, shortened with an ellipsis to fit `max_px` pixels (see [`text_width`]).
pub(crate) fn fit_text(text: &str, max_px: i32, size: f64) -> String {
    if text_width(text, size) <= max_px {
        return text.to_string();
    }
    let per_char = 0.62 * size / 1.24;
    let n = ((max_px as f64 / per_char).floor() as usize).max(2) - 1;
    let mut out: String = text.chars().take(n).collect();
    out.push('\u{2026}');
    out
}

/// Draws the mesh (grid, axes, tick labels, axis descriptions) of a chart.
pub(crate) fn draw_mesh<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    xr: (f64, f64),
    yr: (f64, f64),
    x_desc: &str,
    y_desc: &str,
    grid: bool,
) -> DResult {
    let fx = tick_formatter(xr.0, xr.1, 10);
    let fy = tick_formatter(yr.0, yr.1, 10);
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(x_desc)
        .y_desc(y_desc)
        .x_labels(10)
        .y_labels(10)
        .label_style((FONT, TICK_FONT))
        .axis_desc_style((FONT, DESC_FONT))
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .bold_line_style(RGBColor(205, 205, 205))
        .light_line_style(RGBColor(245, 245, 245));
    if !grid {
        mesh.disable_mesh();
    }
    mesh.draw().map_err(de)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colormap_hits_the_stops_and_clamps() {
        assert_eq!(colormap(0.0), RGBColor(68, 1, 84));
        assert_eq!(colormap(1.0), RGBColor(253, 231, 37));
        assert_eq!(colormap(0.5), RGBColor(33, 145, 140));
        assert_eq!(colormap(-3.0), colormap(0.0));
        assert_eq!(colormap(7.0), colormap(1.0));
        assert_eq!(colormap(f64::NAN), colormap(0.0));
    }

    #[test]
    fn fmt_num_prints_no_negative_zero() {
        assert_eq!(fmt_num(-0.0001, 2), "0.00");
        assert_eq!(fmt_num(-1.5, 1), "\u{2212}1.5");
        assert_eq!(fmt_num(2.0, 0), "2");
    }
}
