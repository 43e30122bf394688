//! SVG plots for the engineer: transmission-error curves, flank maps (ease-off
//! topography, roll-angle surface), contact paths with contact ellipses and
//! tooth sections.
//!
//! Every function takes plain data (no project types), renders the whole
//! picture into a string with the SVG backend of `plotters` and then writes it
//! atomically ([`formats::output::write_atomic`]): a reader never sees a
//! half-written file.
//!
//! Text is written as SVG `<text>` elements with the generic `sans-serif`
//! family; no font files are needed to produce the plots.
//!
//! The small numerical helpers used by the plots are public and tested on
//! their own: [`nice_ticks`] (1-2-5 tick/contour levels), [`iso_segments`]
//! (marching squares on a structured curvilinear grid) and
//! [`equal_aspect_ranges`] (axis ranges with the same length per pixel in x
//! and y).

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::{Path, PathBuf};

/// Error of a plot function. Every message names the output file.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The input cannot be plotted (no finite data, inconsistent lengths, ...).
    #[error("plot {}: invalid input: {msg}", .path.display())]
    Input { path: PathBuf, msg: String },
    /// The plotting library reported an error while drawing.
    #[error("plot {}: drawing failed: {msg}", .path.display())]
    Drawing { path: PathBuf, msg: String },
    /// Writing the file failed.
    #[error(transparent)]
    Write(#[from] formats::output::WriteError),
}

/// One curve of a line chart ([`te_curve`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend entry. Series with the same name share one colour and one legend entry.
    pub name: String,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    /// Draw dashed (thin) instead of solid (thick).
    pub dashed: bool,
}

/// Scalar field on a structured curvilinear grid of a flank ([`flank_map`]).
///
/// Node `(i, k)`, `i < n_face`, `k < n_profile`, is stored at index
/// `i * n_profile + k`; `x` is the face coordinate (cone distance, mm), `y` the
/// profile coordinate (height, mm). The cells are the quadrilaterals
/// `(i, k), (i+1, k), (i+1, k+1), (i, k+1)`. Non-finite values or coordinates
/// mark missing nodes: cells touching them are left blank.
#[derive(Debug, Clone, PartialEq)]
pub struct FlankMap {
    pub n_face: usize,
    pub n_profile: usize,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub value: Vec<f64>,
}

/// A named polyline ([`contact_path`], [`tooth_section`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PathSeries {
    pub name: String,
    pub points: Vec<(f64, f64)>,
}

/// A contact ellipse in the plane of a [`contact_path`] plot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipse {
    /// Centre (x, y) in mm.
    pub center: (f64, f64),
    /// Semi-axes (a, b) in mm; `a` lies along the direction `angle_rad`.
    pub semi_axes: (f64, f64),
    /// Angle of the `a` axis from the +x axis, counter-clockwise, rad.
    pub angle_rad: f64,
}

// ---------------------------------------------------------------------------
// Numerical helpers
// ---------------------------------------------------------------------------

/// Ticks at "nice" values (steps of 1, 2 or 5 × 10^k) inside `[lo, hi]`.
///
/// The step is the smallest nice step not smaller than `(hi - lo) / n`, so
/// there are at most `n + 1` ticks. The ticks are equally spaced, sorted
/// ascending and all lie within `[min(lo, hi), max(lo, hi)]`. A degenerate
/// range (`lo == hi`) gives `[lo]`; non-finite bounds give no ticks.
pub fn nice_ticks(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if !lo.is_finite() || !hi.is_finite() {
        return Vec::new();
    }
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (hi, lo) };
    if hi == lo {
        return vec![lo];
    }
    let n = n.max(1);
    let step = nice_step((hi - lo) / n as f64);
    if !(step.is_finite() && step > 0.0) {
        return vec![lo];
    }
    let k0 = (lo / step).ceil();
    let k1 = (hi / step).floor();
    if !(k0.is_finite() && k1.is_finite()) || k1 < k0 {
        return Vec::new();
    }
    let count = (k1 - k0) as i64;
    if count > 10 * (n as i64 + 1) {
        // only possible when |lo|/step exceeds f64 integer precision
        return vec![lo, hi];
    }
    let mut ticks: Vec<f64> = Vec::with_capacity(count as usize + 1);
    for j in 0..=count {
        let mut t = (k0 + j as f64) * step;
        // rounding of k*step may leave the range by an ulp: snap back
        t = t.clamp(lo, hi);
        if t == 0.0 {
            t = 0.0; // no negative zero
        }
        if ticks.last().is_none_or(|&p| t > p) {
            ticks.push(t);
        }
    }
    ticks
}

/// Smallest of {1, 2, 5, 10} × 10^k not below `raw` (> 0).
fn nice_step(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return f64::NAN;
    }
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let s = if f <= 1.0 + 1e-12 {
        1.0
    } else if f <= 2.0 + 1e-12 {
        2.0
    } else if f <= 5.0 + 1e-12 {
        5.0
    } else {
        10.0
    };
    s * mag
}

/// Axis ranges with the same length per pixel in x and y.
///
/// `xs` and `ys` are the (lo, hi) data ranges that must be visible; the
/// narrower one (in data units per pixel) is widened symmetrically about its
/// centre so that `(x_hi - x_lo) / width_px == (y_hi - y_lo) / height_px`.
/// `width_px`/`height_px` are the pixel spans the ranges are mapped onto
/// (values below 1 are treated as 1). Reversed bounds are swapped; a range
/// that is degenerate in both directions gets a span of 1 data unit in the
/// direction with fewer pixels per unit; non-finite bounds are replaced by 0..1.
pub fn equal_aspect_ranges(
    xs: (f64, f64),
    ys: (f64, f64),
    width_px: u32,
    height_px: u32,
) -> ((f64, f64), (f64, f64)) {
    let sane = |r: (f64, f64)| {
        if r.0.is_finite() && r.1.is_finite() {
            (r.0.min(r.1), r.0.max(r.1))
        } else {
            (0.0, 1.0)
        }
    };
    let (x0, x1) = sane(xs);
    let (y0, y1) = sane(ys);
    let w = width_px.max(1) as f64;
    let h = height_px.max(1) as f64;
    let mut scale = ((x1 - x0) / w).max((y1 - y0) / h); // data units per pixel
    if !(scale.is_finite() && scale > 0.0) {
        scale = 1.0 / w.min(h);
    }
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let (hx, hy) = (0.5 * scale * w, 0.5 * scale * h);
    // keep the given bounds exactly when that direction is the binding one
    let xr = if (x1 - x0) / w >= scale {
        (x0, x1)
    } else {
        (cx - hx, cx + hx)
    };
    let yr = if (y1 - y0) / h >= scale {
        (y0, y1)
    } else {
        (cy - hy, cy + hy)
    };
    (xr, yr)
}

/// Iso-line of `grid.value` at `level`, by marching squares.
///
/// Returns the line as segments between points (x, y) on cell edges, found by
/// linear interpolation of the value along each edge. Every cell edge is
/// interpolated in one fixed orientation, so the end points shared by
/// neighbouring cells are bitwise equal. A node counts as "above" when
/// `value >= level`; ambiguous (saddle) cells are resolved with the mean of
/// the four corner values. Cells with a non-finite node are skipped; an
/// inconsistent grid gives no segments.
pub fn iso_segments(grid: &FlankMap, level: f64) -> Vec<((f64, f64), (f64, f64))> {
    let mut out = Vec::new();
    if !grid_is_consistent(grid) || !level.is_finite() {
        return out;
    }
    let np = grid.n_profile;
    let idx = |i: usize, k: usize| i * np + k;
    let node_ok =
        |j: usize| grid.x[j].is_finite() && grid.y[j].is_finite() && grid.value[j].is_finite();
    // crossing point of the edge a -> b (a, b node indices), if any
    let cross = |a: usize, b: usize| -> Option<(f64, f64)> {
        let (va, vb) = (grid.value[a], grid.value[b]);
        if (va >= level) == (vb >= level) {
            return None;
        }
        let t = (level - va) / (vb - va);
        Some((
            grid.x[a] + t * (grid.x[b] - grid.x[a]),
            grid.y[a] + t * (grid.y[b] - grid.y[a]),
        ))
    };
    for i in 0..grid.n_face - 1 {
        for k in 0..np - 1 {
            // corners counter-clockwise in (i, k): c0 (i,k), c1 (i+1,k), c2 (i+1,k+1), c3 (i,k+1)
            let c = [idx(i, k), idx(i + 1, k), idx(i + 1, k + 1), idx(i, k + 1)];
            if !c.iter().all(|&j| node_ok(j)) {
                continue;
            }
            // edges e0 = c0-c1, e1 = c1-c2, e2 = c3-c2, e3 = c0-c3 (canonical orientation:
            // from the lower to the higher node index)
            let e = [
                cross(c[0], c[1]),
                cross(c[1], c[2]),
                cross(c[3], c[2]),
                cross(c[0], c[3]),
            ];
            let hits: Vec<(usize, (f64, f64))> = e
                .iter()
                .enumerate()
                .filter_map(|(j, p)| p.map(|p| (j, p)))
                .collect();
            match hits.len() {
                2 => out.push((hits[0].1, hits[1].1)),
                4 => {
                    let (p0, p1, p2, p3) = (hits[0].1, hits[1].1, hits[2].1, hits[3].1);
                    let mean = c.iter().map(|&j| grid.value[j]).sum::<f64>() / 4.0;
                    let c0_above = grid.value[c[0]] >= level;
                    if (mean >= level) == c0_above {
                        // c0 and c2 are connected through the centre: cut off c1 and c3
                        out.push((p0, p1));
                        out.push((p2, p3));
                    } else {
                        // cut off c0 and c2
                        out.push((p3, p0));
                        out.push((p1, p2));
                    }
                }
                _ => {}
            }
        }
    }
    out
}

/// A straight segment between two points (x, y).
type Segment = ((f64, f64), (f64, f64));

fn grid_is_consistent(g: &FlankMap) -> bool {
    let n = g.n_face.checked_mul(g.n_profile);
    g.n_face >= 2
        && g.n_profile >= 2
        && n.is_some_and(|n| g.x.len() == n && g.y.len() == n && g.value.len() == n)
}

// ---------------------------------------------------------------------------
// Colours
// ---------------------------------------------------------------------------

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
fn colormap(t: f64) -> RGBColor {
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
const PALETTE: [RGBColor; 10] = [
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

// ---------------------------------------------------------------------------
// Drawing infrastructure
// ---------------------------------------------------------------------------

type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;
type DResult<T = ()> = Result<T, String>;

const FONT: &str = "sans-serif";
const TITLE_H: u32 = 48;
const MARGIN: u32 = 14;
const X_LABEL_AREA: u32 = 58;
const Y_LABEL_AREA: u32 = 90;
const TITLE_FONT: f64 = 27.0;
const TICK_FONT: f64 = 18.0;
const DESC_FONT: f64 = 20.0;

fn de<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

fn text_style(size: f64, h: HPos, v: VPos) -> TextStyle<'static> {
    TextStyle::from((FONT, size).into_font()).pos(Pos::new(h, v))
}

/// Rough width of `text` in pixels for a plotters font size `size`
/// (the SVG font size is `size / 1.24`; sans-serif digits are ~0.64 em wide).
fn text_width(text: &str, size: f64) -> i32 {
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
fn render_to_file(
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
fn frame<'a>(root: &Area<'a>, title: &str, right_w: u32) -> DResult<(Area<'a>, Area<'a>)> {
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

fn chart_builder<'a, 'b>(area: &'a Area<'b>) -> ChartBuilder<'a, 'b, SVGBackend<'b>> {
    let mut cb = ChartBuilder::on(area);
    cb.margin(MARGIN)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA);
    cb
}

/// Absolute pixel ranges (x, y) of the plotting area that [`chart_builder`]
/// makes on `area`.
fn plot_pixel_range(area: &Area<'_>) -> DResult<(std::ops::Range<i32>, std::ops::Range<i32>)> {
    let probe = chart_builder(area)
        .build_cartesian_2d(0f64..1f64, 0f64..1f64)
        .map_err(de)?;
    Ok(probe.plotting_area().get_pixel_range())
}

/// Pixel spans onto which plotters maps the x and y ranges (it maps onto
/// `start..end - 1`).
fn pixel_spans(px: &(std::ops::Range<i32>, std::ops::Range<i32>)) -> (u32, u32) {
    (
        (px.0.end - px.0.start - 1).max(1) as u32,
        (px.1.end - px.1.start - 1).max(1) as u32,
    )
}

/// Bounding box of finite points.
#[derive(Debug, Clone, Copy)]
struct BBox {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
}

impl BBox {
    fn empty() -> Self {
        BBox {
            x0: f64::INFINITY,
            x1: f64::NEG_INFINITY,
            y0: f64::INFINITY,
            y1: f64::NEG_INFINITY,
        }
    }
    fn add(&mut self, p: (f64, f64)) {
        if p.0.is_finite() && p.1.is_finite() {
            self.x0 = self.x0.min(p.0);
            self.x1 = self.x1.max(p.0);
            self.y0 = self.y0.min(p.1);
            self.y1 = self.y1.max(p.1);
        }
    }
    fn is_empty(&self) -> bool {
        self.x0 > self.x1
    }
    fn extent(&self) -> f64 {
        if self.is_empty() {
            0.0
        } else {
            (self.x1 - self.x0).max(self.y1 - self.y0)
        }
    }
}

/// Range padded by `frac` of its span on both sides; degenerate ranges get a
/// span of 10 % of their magnitude (or 1).
fn padded(lo: f64, hi: f64, frac: f64) -> (f64, f64) {
    let span = hi - lo;
    if span > 0.0 {
        (lo - frac * span, hi + frac * span)
    } else {
        let h = if lo != 0.0 { 0.1 * lo.abs() } else { 1.0 };
        (lo - h, hi + h)
    }
}

/// Splits a polyline at non-finite points into finite runs.
fn finite_runs(points: impl IntoIterator<Item = (f64, f64)>) -> Vec<Vec<(f64, f64)>> {
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
fn decimals_for(step: f64) -> usize {
    if !(step.is_finite() && step > 0.0) || step >= 1.0 {
        0
    } else {
        ((-step.log10()).ceil() as usize).min(12)
    }
}

fn fmt_num(v: f64, decimals: usize) -> String {
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
fn fit_text(text: &str, max_px: i32, size: f64) -> String {
    if text_width(text, size) <= max_px {
        return text.to_string();
    }
    let per_char = 0.62 * size / 1.24;
    let n = ((max_px as f64 / per_char).floor() as usize).max(2) - 1;
    let mut out: String = text.chars().take(n).collect();
    out.push('\u{2026}');
    out
}

/// How a legend entry is drawn.
#[derive(Debug, Clone, Copy)]
enum Sample {
    Line {
        color: RGBColor,
        width: u32,
        dashed: bool,
    },
    LineMarker(RGBColor),
    Patch(RGBColor),
}

const LEGEND_FONT: f64 = 18.0;
const LEGEND_ROW: i32 = 26;

/// Width of a legend column for these names.
fn legend_width(names: &[&str]) -> u32 {
    let longest = names
        .iter()
        .map(|s| text_width(s, LEGEND_FONT))
        .max()
        .unwrap_or(0);
    (longest + 66).clamp(120, 380) as u32
}

/// Framed legend at vertical pixel offset `top` of `area`.
fn draw_legend(area: &Area<'_>, top: i32, entries: &[(String, Sample)]) -> DResult {
    if entries.is_empty() {
        return Ok(());
    }
    let (w, h) = area.dim_in_pixel();
    let fit = (((h as i32 - top - 12) / LEGEND_ROW).max(1)) as usize;
    let (shown, more) = if entries.len() > fit {
        (fit.saturating_sub(1), entries.len() - fit.saturating_sub(1))
    } else {
        (entries.len(), 0)
    };
    let rows = shown + usize::from(more > 0);
    let (x0, x1) = (4, w as i32 - 8);
    let y1 = top + rows as i32 * LEGEND_ROW + 10;
    area.draw(&Rectangle::new([(x0, top), (x1, y1)], WHITE.filled()))
        .map_err(de)?;
    area.draw(&Rectangle::new(
        [(x0, top), (x1, y1)],
        RGBColor(160, 160, 160).stroke_width(1),
    ))
    .map_err(de)?;
    let style = text_style(LEGEND_FONT, HPos::Left, VPos::Center);
    for (j, (name, sample)) in entries.iter().take(shown).enumerate() {
        let y = top + 5 + j as i32 * LEGEND_ROW + LEGEND_ROW / 2;
        let (sx0, sx1) = (x0 + 8, x0 + 40);
        match *sample {
            Sample::Line {
                color,
                width,
                dashed,
            } => {
                let st = color.stroke_width(width);
                if dashed {
                    for s in [0, 12, 24] {
                        area.draw(&PathElement::new(vec![(sx0 + s, y), (sx0 + s + 7, y)], st))
                            .map_err(de)?;
                    }
                } else {
                    area.draw(&PathElement::new(vec![(sx0, y), (sx1, y)], st))
                        .map_err(de)?;
                }
            }
            Sample::LineMarker(color) => {
                area.draw(&PathElement::new(
                    vec![(sx0, y), (sx1, y)],
                    color.stroke_width(2),
                ))
                .map_err(de)?;
                area.draw(&Circle::new(((sx0 + sx1) / 2, y), 3, color.filled()))
                    .map_err(de)?;
            }
            Sample::Patch(color) => {
                area.draw(&Rectangle::new(
                    [(sx0, y - 6), (sx1, y + 6)],
                    color.mix(0.3).filled(),
                ))
                .map_err(de)?;
                area.draw(&Rectangle::new(
                    [(sx0, y - 6), (sx1, y + 6)],
                    color.stroke_width(1),
                ))
                .map_err(de)?;
            }
        }
        let shown_name = fit_text(name, x1 - (sx1 + 8) - 4, LEGEND_FONT);
        area.draw(&Text::new(shown_name, (sx1 + 8, y), style.clone()))
            .map_err(de)?;
    }
    if more > 0 {
        let y = top + 5 + shown as i32 * LEGEND_ROW + LEGEND_ROW / 2;
        area.draw(&Text::new(
            format!("\u{2026} {more} more"),
            (x0 + 8, y),
            style.clone(),
        ))
        .map_err(de)?;
    }
    Ok(())
}

/// Draws the mesh (grid, axes, tick labels, axis descriptions) of a chart.
fn draw_mesh<DB: DrawingBackend>(
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

// ---------------------------------------------------------------------------
// 1. Line chart (transmission error)
// ---------------------------------------------------------------------------

/// Line chart of one or more curves with a legend and a grid, e.g. the
/// transmission error (y, µrad) over the pinion rotation (x, deg), with the
/// envelope as a solid line and the individual tooth-pair curves dashed.
///
/// Axes: x and y are the series' own units, described by `x_label` and
/// `y_label` (include the unit there, e.g. `"pinion rotation (deg)"`). The
/// ranges cover all finite points with 5 % margins. Non-finite points break
/// a curve. Series with the same name share one colour and one legend entry.
///
/// Errors: [`PlotError::Input`] if there are no series, if a series' `x` and
/// `y` differ in length, or if there is no finite point at all.
pub fn te_curve(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<(), PlotError> {
    let input = |msg: String| PlotError::Input {
        path: path.to_path_buf(),
        msg,
    };
    if series.is_empty() {
        return Err(input("no series".into()));
    }
    let mut bb = BBox::empty();
    for s in series {
        if s.x.len() != s.y.len() {
            return Err(input(format!(
                "series '{}': {} x values but {} y values",
                s.name,
                s.x.len(),
                s.y.len()
            )));
        }
        for (&x, &y) in s.x.iter().zip(&s.y) {
            bb.add((x, y));
        }
    }
    if bb.is_empty() {
        return Err(input("no finite data point in any series".into()));
    }
    let xr = padded(bb.x0, bb.x1, 0.05);
    let yr = padded(bb.y0, bb.y1, 0.05);

    // colours and legend entries: one per distinct name, in order of appearance
    let mut names: Vec<&str> = Vec::new();
    let mut entries: Vec<(String, Sample)> = Vec::new();
    let mut colors = Vec::with_capacity(series.len());
    for s in series {
        let j = match names.iter().position(|n| *n == s.name) {
            Some(j) => j,
            None => {
                names.push(&s.name);
                let color = PALETTE[(names.len() - 1) % PALETTE.len()];
                entries.push((
                    s.name.clone(),
                    Sample::Line {
                        color,
                        width: if s.dashed { 1 } else { 2 },
                        dashed: s.dashed,
                    },
                ));
                names.len() - 1
            }
        };
        colors.push(PALETTE[j % PALETTE.len()]);
    }
    let legend_w = legend_width(&names);

    render_to_file(path, (1100, 650), |root| {
        let (main, side) = frame(root, title, legend_w)?;
        let px = plot_pixel_range(&main)?;
        let mut chart = chart_builder(&main)
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
            .map_err(de)?;
        draw_mesh(&mut chart, xr, yr, x_label, y_label, true)?;
        // dashed first, solid (envelopes) on top
        for pass_dashed in [true, false] {
            for (s, &color) in series.iter().zip(&colors) {
                if s.dashed != pass_dashed {
                    continue;
                }
                for run in finite_runs(s.x.iter().copied().zip(s.y.iter().copied())) {
                    if run.len() == 1 {
                        chart
                            .draw_series(std::iter::once(Circle::new(run[0], 2, color.filled())))
                            .map_err(de)?;
                    } else if s.dashed {
                        chart
                            .draw_series(DashedLineSeries::new(run, 7, 4, color.stroke_width(1)))
                            .map_err(de)?;
                    } else {
                        chart
                            .draw_series(LineSeries::new(run, color.stroke_width(2)))
                            .map_err(de)?;
                    }
                }
            }
        }
        let top = px.1.start - side.get_base_pixel().1;
        draw_legend(&side, top, &entries)
    })
}

// ---------------------------------------------------------------------------
// 2. Flank map (ease-off, roll angles)
// ---------------------------------------------------------------------------

const CONTOUR_FONT: f64 = 15.0;
const BAR_TICK_FONT: f64 = 17.0;
const BAR_END_FONT: f64 = 16.0;
/// Left and right edge of the colour bar in its column, px.
const BAR_X: (i32, i32) = (16, 44);

/// Colour map of a scalar field on a flank with iso-lines, e.g. the ease-off
/// topography (µm) or the surface of roll angles (deg).
///
/// Axes: x = face coordinate (cone distance along the face width, mm),
/// y = profile coordinate (height, mm); the axes are scaled to fill the plot,
/// not to equal aspect. Each grid cell is filled with the colour of the mean
/// of its four node values (viridis-like map from the minimum to the maximum
/// finite value); the colour bar on the right is labelled `colorbar_label`
/// (with the unit). Iso-lines are drawn at the ~8 "nice" levels of
/// [`nice_ticks`] strictly inside the value range; the levels are the ticks of
/// the colour bar (marked across it), and each iso-line carries its value
/// where there is room. Minimum and maximum are printed at the ends of the
/// colour bar.
///
/// Errors: [`PlotError::Input`] if the grid sizes are inconsistent (fewer than
/// 2 × 2 nodes, or `x`, `y`, `value` not of length `n_face * n_profile`) or
/// no cell has four finite nodes.
pub fn flank_map(
    path: &Path,
    title: &str,
    grid: &FlankMap,
    colorbar_label: &str,
) -> Result<(), PlotError> {
    let input = |msg: String| PlotError::Input {
        path: path.to_path_buf(),
        msg,
    };
    if !grid_is_consistent(grid) {
        return Err(input(format!(
            "flank grid {} x {} needs at least 2 x 2 nodes and x, y, value of length {} (got {}, {}, {})",
            grid.n_face,
            grid.n_profile,
            grid.n_face.saturating_mul(grid.n_profile),
            grid.x.len(),
            grid.y.len(),
            grid.value.len()
        )));
    }
    let np = grid.n_profile;
    let node_ok =
        |j: usize| grid.x[j].is_finite() && grid.y[j].is_finite() && grid.value[j].is_finite();
    // cells with four finite nodes: (polygon, mean value)
    let mut cells: Vec<(Vec<(f64, f64)>, f64)> = Vec::new();
    let mut bb = BBox::empty();
    let (mut vmin, mut vmax) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..grid.n_face - 1 {
        for k in 0..np - 1 {
            let c = [
                i * np + k,
                (i + 1) * np + k,
                (i + 1) * np + k + 1,
                i * np + k + 1,
            ];
            if !c.iter().all(|&j| node_ok(j)) {
                continue;
            }
            let poly: Vec<(f64, f64)> = c.iter().map(|&j| (grid.x[j], grid.y[j])).collect();
            for &j in &c {
                bb.add((grid.x[j], grid.y[j]));
                vmin = vmin.min(grid.value[j]);
                vmax = vmax.max(grid.value[j]);
            }
            let mean = c.iter().map(|&j| grid.value[j]).sum::<f64>() / 4.0;
            cells.push((poly, mean));
        }
    }
    if cells.is_empty() {
        return Err(input("no grid cell with four finite nodes".into()));
    }
    let xr = padded(bb.x0, bb.x1, 0.03);
    let yr = padded(bb.y0, bb.y1, 0.03);
    let flat = vmax - vmin <= 1e-12 * vmax.abs().max(vmin.abs()).max(1e-300);
    let (cmin, cmax) = if flat {
        padded(vmin, vmax, 0.0)
    } else {
        (vmin, vmax)
    };
    let levels: Vec<f64> = if flat {
        Vec::new()
    } else {
        // no iso-lines hugging the extremes (tiny islands, boundary slivers)
        let guard = 0.02 * (vmax - vmin);
        nice_ticks(vmin, vmax, 8)
            .into_iter()
            .filter(|&l| l > vmin + guard && l < vmax - guard)
            .collect()
    };
    let level_dec = if levels.len() >= 2 {
        decimals_for(levels[1] - levels[0])
    } else {
        decimals_for(nice_step((vmax - vmin).abs().max(1e-300) / 8.0))
    };
    let contours: Vec<Vec<Segment>> = levels.iter().map(|&l| iso_segments(grid, l)).collect();
    let tcol = |v: f64| colormap((v - cmin) / (cmax - cmin));
    let ext_dec = (level_dec + 1).min(12);
    let level_text: Vec<String> = levels.iter().map(|&l| fmt_num(l, level_dec)).collect();
    let max_text = format!("max {}", fmt_num(vmax, ext_dec));
    let min_text = format!("min {}", fmt_num(vmin, ext_dec));
    let tick_w = level_text
        .iter()
        .map(|t| text_width(t, BAR_TICK_FONT))
        .max()
        .unwrap_or(0);
    let end_w = text_width(&max_text, BAR_END_FONT).max(text_width(&min_text, BAR_END_FONT));
    // x of the (rotated) colour bar label in the column, and the column width
    let label_x = (BAR_X.1 + 10 + tick_w + 22).max(BAR_X.0 + 30);
    let colorbar_w = ((label_x + 22).max(BAR_X.0 - 8 + end_w + 8)) as u32;

    render_to_file(path, (1100, 720), |root| {
        let (main, side) = frame(root, title, colorbar_w)?;
        let px = plot_pixel_range(&main)?;
        let mut chart = chart_builder(&main)
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
            .map_err(de)?;
        draw_mesh(
            &mut chart,
            xr,
            yr,
            "face coordinate (cone distance, mm)",
            "profile coordinate (height, mm)",
            false,
        )?;
        // cells: fill plus an outline of the same colour to hide anti-aliasing seams
        for (poly, mean) in &cells {
            let col = tcol(*mean);
            chart
                .draw_series(std::iter::once(Polygon::new(poly.clone(), col.filled())))
                .map_err(de)?;
            let mut closed = poly.clone();
            closed.push(poly[0]);
            chart
                .draw_series(std::iter::once(PathElement::new(
                    closed,
                    col.stroke_width(1),
                )))
                .map_err(de)?;
        }
        // iso-lines
        let line_col = RGBColor(20, 20, 20);
        for segs in &contours {
            chart
                .draw_series(
                    segs.iter()
                        .map(|&(a, b)| PathElement::new(vec![a, b], line_col.stroke_width(1))),
                )
                .map_err(de)?;
        }
        // iso-line labels: per level, the segment midpoint farthest from the
        // labels already placed and from the plot border
        let area = chart.plotting_area();
        let (ax, ay) = (px.0.clone(), px.1.clone());
        let mut placed: Vec<(i32, i32)> = Vec::new();
        let mut labels = Vec::new();
        for (segs, text) in contours.iter().zip(&level_text) {
            let tw = text_width(text, CONTOUR_FONT);
            let mut best: Option<((i32, i32), f64)> = None;
            for &(a, b) in segs {
                let m = (0.5 * (a.0 + b.0), 0.5 * (a.1 + b.1));
                let p = area.map_coordinate(&m);
                let border = [
                    (p.0 - ax.start - tw / 2) as f64,
                    (ax.end - p.0 - tw / 2) as f64,
                    (p.1 - ay.start - 10) as f64,
                    (ay.end - p.1 - 10) as f64,
                ]
                .into_iter()
                .fold(f64::INFINITY, f64::min);
                if border < 2.0 {
                    continue;
                }
                let near = placed
                    .iter()
                    .map(|q| (((p.0 - q.0).pow(2) + (p.1 - q.1).pow(2)) as f64).sqrt())
                    .fold(f64::INFINITY, f64::min);
                let score = near.min(3.0 * border);
                if best.is_none_or(|(_, s)| score > s) {
                    best = Some((p, score));
                }
            }
            if let Some((p, score)) = best {
                if score > 50.0 {
                    placed.push(p);
                    labels.push((p, text.clone(), tw));
                }
            }
        }
        for (p, text, tw) in labels {
            root.draw(&Rectangle::new(
                [(p.0 - tw / 2 - 3, p.1 - 9), (p.0 + tw / 2 + 3, p.1 + 9)],
                WHITE.mix(0.8).filled(),
            ))
            .map_err(de)?;
            root.draw(&Text::new(
                text,
                p,
                text_style(CONTOUR_FONT, HPos::Center, VPos::Center),
            ))
            .map_err(de)?;
        }
        // colour bar
        let base = side.get_base_pixel();
        let top = px.1.start - base.1 + 26;
        let bottom = px.1.end - base.1 - 26;
        let (bx0, bx1) = BAR_X;
        let span = (bottom - top).max(1);
        let n_slices = 128;
        for s in 0..n_slices {
            let y0 = bottom - (s * span) / n_slices;
            let y1 = bottom - ((s + 1) * span) / n_slices;
            let t = (s as f64 + 0.5) / n_slices as f64;
            side.draw(&Rectangle::new(
                [(bx0, y1 - 1), (bx1, y0)],
                colormap(t).filled(),
            ))
            .map_err(de)?;
        }
        side.draw(&Rectangle::new(
            [(bx0, top), (bx1, bottom)],
            BLACK.stroke_width(1),
        ))
        .map_err(de)?;
        let vy = |v: f64| bottom - (((v - cmin) / (cmax - cmin)) * span as f64).round() as i32;
        let tick_style = text_style(BAR_TICK_FONT, HPos::Left, VPos::Center);
        for (&l, text) in levels.iter().zip(&level_text) {
            let y = vy(l);
            side.draw(&PathElement::new(
                vec![(bx0, y), (bx1 + 6, y)],
                BLACK.stroke_width(1),
            ))
            .map_err(de)?;
            side.draw(&Text::new(text.clone(), (bx1 + 10, y), tick_style.clone()))
                .map_err(de)?;
        }
        let end_style = text_style(BAR_END_FONT, HPos::Left, VPos::Center);
        side.draw(&Text::new(
            max_text.clone(),
            (bx0 - 8, top - 14),
            end_style.clone(),
        ))
        .map_err(de)?;
        side.draw(&Text::new(
            min_text.clone(),
            (bx0 - 8, bottom + 14),
            end_style,
        ))
        .map_err(de)?;
        side.draw(&Text::new(
            colorbar_label.to_string(),
            (label_x, (top + bottom) / 2),
            text_style(DESC_FONT, HPos::Center, VPos::Center).transform(FontTransform::Rotate270),
        ))
        .map_err(de)?;
        Ok(())
    })
}

// ---------------------------------------------------------------------------
// 3. Contact path and ellipses; 4. tooth section (equal aspect)
// ---------------------------------------------------------------------------

/// Polygon of 72 points of an ellipse.
fn ellipse_polygon(center: (f64, f64), a: f64, b: f64, angle: f64) -> Vec<(f64, f64)> {
    let (s, c) = angle.sin_cos();
    (0..72)
        .map(|j| {
            let t = j as f64 * std::f64::consts::TAU / 72.0;
            let (u, v) = (a * t.cos(), b * t.sin());
            (center.0 + c * u - s * v, center.1 + s * u + c * v)
        })
        .collect()
}

/// Sutherland–Hodgman clipping of a closed polygon to an axis-aligned box.
fn clip_polygon(poly: &[(f64, f64)], b: &BBox) -> Vec<(f64, f64)> {
    let mut pts = poly.to_vec();
    // inside test and intersection for each of the four half planes
    let planes: [(usize, f64, bool); 4] = [
        (0, b.x0, true),
        (0, b.x1, false),
        (1, b.y0, true),
        (1, b.y1, false),
    ];
    for (axis, lim, lower) in planes {
        if pts.is_empty() {
            break;
        }
        let coord = |p: (f64, f64)| if axis == 0 { p.0 } else { p.1 };
        let inside = |p: (f64, f64)| {
            if lower {
                coord(p) >= lim
            } else {
                coord(p) <= lim
            }
        };
        let mut out = Vec::with_capacity(pts.len() + 4);
        for j in 0..pts.len() {
            let cur = pts[j];
            let prev = pts[(j + pts.len() - 1) % pts.len()];
            let (ci, pi) = (inside(cur), inside(prev));
            if ci != pi {
                let t = (lim - coord(prev)) / (coord(cur) - coord(prev));
                let mut q = (prev.0 + t * (cur.0 - prev.0), prev.1 + t * (cur.1 - prev.1));
                if axis == 0 {
                    q.0 = lim;
                } else {
                    q.1 = lim;
                }
                out.push(q);
            }
            if ci {
                out.push(cur);
            }
        }
        pts = out;
    }
    pts
}

/// A polyline of an equal-aspect plot.
struct Line {
    points: Vec<(f64, f64)>,
    color: RGBColor,
    width: u32,
    markers: bool,
}

/// Everything drawn in an equal-aspect plot.
struct EqualAspectPlot<'d> {
    lines: Vec<Line>,
    patches: Vec<(Vec<(f64, f64)>, RGBColor)>, // closed polygons, filled translucent
    legend: Vec<(String, Sample)>,
    bbox: BBox,
    x_desc: &'d str,
    y_desc: &'d str,
}

const EQUAL_ASPECT_WIDTH: u32 = 1100;
/// Range of the page height of equal-aspect plots, px.
const EQUAL_ASPECT_HEIGHT: (f64, f64) = (480.0, 1000.0);

fn draw_equal_aspect(path: &Path, title: &str, plot: EqualAspectPlot<'_>) -> Result<(), PlotError> {
    let names: Vec<&str> = plot.legend.iter().map(|(n, _)| n.as_str()).collect();
    let legend_w = legend_width(&names);
    let bb = plot.bbox;
    let xr0 = padded(bb.x0, bb.x1, 0.05);
    let yr0 = padded(bb.y0, bb.y1, 0.05);
    // page height fitted to the data's aspect ratio (the final ranges are
    // made exact by `equal_aspect_ranges` for whatever the plot area is)
    let width = EQUAL_ASPECT_WIDTH;
    let plot_w = (width - legend_w.min(width / 2) - 2 * MARGIN - Y_LABEL_AREA) as f64;
    let plot_h = plot_w * (yr0.1 - yr0.0) / (xr0.1 - xr0.0);
    let extra_h = (TITLE_H + 2 * MARGIN + X_LABEL_AREA) as f64;
    let height = (extra_h + plot_h).clamp(EQUAL_ASPECT_HEIGHT.0, EQUAL_ASPECT_HEIGHT.1) as u32;
    render_to_file(path, (width, height), |root| {
        let (main, side) = frame(root, title, legend_w)?;
        let px = plot_pixel_range(&main)?;
        let (w_px, h_px) = pixel_spans(&px);
        let (xr, yr) = equal_aspect_ranges(xr0, yr0, w_px, h_px);
        let view = BBox {
            x0: xr.0,
            x1: xr.1,
            y0: yr.0,
            y1: yr.1,
        };
        let mut chart = chart_builder(&main)
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
            .map_err(de)?;
        draw_mesh(&mut chart, xr, yr, plot.x_desc, plot.y_desc, true)?;
        for (poly, color) in &plot.patches {
            let clipped = clip_polygon(poly, &view);
            if clipped.len() < 3 {
                continue;
            }
            chart
                .draw_series(std::iter::once(Polygon::new(
                    clipped.clone(),
                    color.mix(0.25).filled(),
                )))
                .map_err(de)?;
            let mut closed = clipped.clone();
            closed.push(clipped[0]);
            chart
                .draw_series(std::iter::once(PathElement::new(
                    closed,
                    color.stroke_width(1),
                )))
                .map_err(de)?;
        }
        for Line {
            points,
            color,
            width,
            markers,
        } in &plot.lines
        {
            for run in finite_runs(points.iter().copied()) {
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        run.clone(),
                        color.stroke_width(*width),
                    )))
                    .map_err(de)?;
                if *markers {
                    chart
                        .draw_series(run.iter().map(|&p| Circle::new(p, 3, color.filled())))
                        .map_err(de)?;
                }
            }
        }
        let top = px.1.start - side.get_base_pixel().1;
        draw_legend(&side, top, &plot.legend)
    })
}

const OUTLINE_COLOR: RGBColor = RGBColor(0, 0, 0);
const ELLIPSE_COLOR: RGBColor = RGBColor(120, 120, 120);

/// Contact pattern on a flank: the flank outline, the paths of contact and
/// the contact ellipses, at equal aspect.
///
/// Axes: x = cone distance along the tooth (mm), y = height above the pitch
/// cone (mm); 1 mm has the same length on the page in x and in y (see
/// [`equal_aspect_ranges`]). The `outline` polygon is closed automatically;
/// each path is a polyline with a marker at every point (non-finite points
/// break it). Each ellipse is drawn as a 72-point polygon with a translucent
/// fill; it is not clipped by the flank, but a semi-axis that is not finite
/// or longer than twice the outline's extent (its larger bounding-box side)
/// is shortened to twice that extent, and the part outside the visible range
/// is cut off. The visible range covers the outline, the paths and the
/// ellipses (the latter up to half an extent beyond the rest) plus 5 %.
///
/// Errors: [`PlotError::Input`] if there is no finite point to plot at all.
pub fn contact_path(
    path: &Path,
    title: &str,
    outline: &[(f64, f64)],
    paths: &[PathSeries],
    ellipses: &[Ellipse],
) -> Result<(), PlotError> {
    let mut outline_bb = BBox::empty();
    outline.iter().for_each(|&p| outline_bb.add(p));
    let mut base = outline_bb;
    for s in paths {
        s.points.iter().for_each(|&p| base.add(p));
    }
    for e in ellipses {
        base.add(e.center);
    }
    if base.is_empty() {
        return Err(PlotError::Input {
            path: path.to_path_buf(),
            msg: "no finite point in the outline, the paths or the ellipse centres".into(),
        });
    }
    let mut extent = outline_bb.extent();
    if extent <= 0.0 {
        extent = base.extent();
    }
    if extent <= 0.0 || !extent.is_finite() {
        extent = 1.0;
    }
    let cap = |s: f64| {
        let s = s.abs();
        if s.is_finite() && s <= 2.0 * extent {
            s
        } else {
            2.0 * extent
        }
    };
    let mut patches = Vec::new();
    let mut bbox = base;
    let limit = BBox {
        x0: base.x0 - 0.5 * extent,
        x1: base.x1 + 0.5 * extent,
        y0: base.y0 - 0.5 * extent,
        y1: base.y1 + 0.5 * extent,
    };
    for e in ellipses {
        if !(e.center.0.is_finite() && e.center.1.is_finite()) {
            continue;
        }
        let angle = if e.angle_rad.is_finite() {
            e.angle_rad
        } else {
            0.0
        };
        let poly = ellipse_polygon(e.center, cap(e.semi_axes.0), cap(e.semi_axes.1), angle);
        for &p in &poly {
            bbox.add((p.0.clamp(limit.x0, limit.x1), p.1.clamp(limit.y0, limit.y1)));
        }
        patches.push((poly, ELLIPSE_COLOR));
    }

    let mut lines = Vec::new();
    let mut legend = Vec::new();
    let finite_outline: Vec<(f64, f64)> = outline
        .iter()
        .copied()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    if finite_outline.len() >= 2 {
        let mut closed = finite_outline.clone();
        closed.push(finite_outline[0]);
        lines.push(Line {
            points: closed,
            color: OUTLINE_COLOR,
            width: 2,
            markers: false,
        });
        legend.push((
            "flank outline".to_string(),
            Sample::Line {
                color: OUTLINE_COLOR,
                width: 2,
                dashed: false,
            },
        ));
    }
    for (j, s) in paths.iter().enumerate() {
        let color = PALETTE[1 + j % (PALETTE.len() - 1)];
        lines.push(Line {
            points: s.points.clone(),
            color,
            width: 2,
            markers: true,
        });
        legend.push((s.name.clone(), Sample::LineMarker(color)));
    }
    if !patches.is_empty() {
        legend.push(("contact ellipses".to_string(), Sample::Patch(ELLIPSE_COLOR)));
    }
    draw_equal_aspect(
        path,
        title,
        EqualAspectPlot {
            lines,
            patches,
            legend,
            bbox,
            x_desc: "cone distance (mm)",
            y_desc: "height above pitch cone (mm)",
        },
    )
}

/// Tooth section: named polylines (e.g. concave and convex flank profiles,
/// root and tip lines) with a legend, at equal aspect.
///
/// Axes: x and y in mm in the plane of the section; 1 mm has the same length
/// on the page in x and in y (see [`equal_aspect_ranges`]). The ranges cover
/// all finite points plus 5 %; non-finite points break a curve.
///
/// Errors: [`PlotError::Input`] if there is no finite point to plot.
pub fn tooth_section(path: &Path, title: &str, curves: &[PathSeries]) -> Result<(), PlotError> {
    let mut bbox = BBox::empty();
    for c in curves {
        c.points.iter().for_each(|&p| bbox.add(p));
    }
    if bbox.is_empty() {
        return Err(PlotError::Input {
            path: path.to_path_buf(),
            msg: "no finite point in any curve".into(),
        });
    }
    let mut lines = Vec::new();
    let mut legend = Vec::new();
    for (j, c) in curves.iter().enumerate() {
        let color = PALETTE[j % PALETTE.len()];
        lines.push(Line {
            points: c.points.clone(),
            color,
            width: 2,
            markers: false,
        });
        legend.push((
            c.name.clone(),
            Sample::Line {
                color,
                width: 2,
                dashed: false,
            },
        ));
    }
    draw_equal_aspect(
        path,
        title,
        EqualAspectPlot {
            lines,
            patches: Vec::new(),
            legend,
            bbox,
            x_desc: "x (mm)",
            y_desc: "y (mm)",
        },
    )
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
    fn clip_polygon_cuts_a_square_to_the_box() {
        let sq = [(-1.0, -1.0), (3.0, -1.0), (3.0, 3.0), (-1.0, 3.0)];
        let b = BBox {
            x0: 0.0,
            x1: 2.0,
            y0: 0.0,
            y1: 2.0,
        };
        let c = clip_polygon(&sq, &b);
        assert!(c.len() >= 4);
        for p in &c {
            assert!((0.0..=2.0).contains(&p.0) && (0.0..=2.0).contains(&p.1));
        }
    }

    #[test]
    fn fmt_num_prints_no_negative_zero() {
        assert_eq!(fmt_num(-0.0001, 2), "0.00");
        assert_eq!(fmt_num(-1.5, 1), "\u{2212}1.5");
        assert_eq!(fmt_num(2.0, 0), "2");
    }
}
