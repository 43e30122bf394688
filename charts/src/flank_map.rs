//! Colour maps of a scalar field on a flank grid with labelled iso-lines
//! and a colour bar ([`flank_map`]): ease-off topography, roll angles.

use crate::frame::{
    chart_builder, colormap, de, decimals_for, draw_mesh, fmt_num, frame, padded, plot_pixel_range,
    render_to_file, text_style, text_width, Area, BBox, DResult, DESC_FONT,
};
use crate::numeric::{grid_is_consistent, iso_segments, nice_step, nice_ticks, Segment};
use crate::PlotError;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};
use std::path::Path;

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
    let (cells, bb, vmin, vmax) = finite_cells(grid);
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

    let bar = ColourBar {
        levels: &levels,
        level_text: &level_text,
        range: (cmin, cmax),
        max_text: &max_text,
        min_text: &min_text,
        label: colorbar_label,
        label_x,
    };

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
        let labels = label_places(|m| area.map_coordinate(m), &px, &contours, &level_text);
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
        colour_bar(&side, &px, &bar)
    })
}

/// A grid cell: its polygon and the mean of its four node values.
type Cell = (Vec<(f64, f64)>, f64);

/// The grid cells with four finite nodes (polygon, mean value), their
/// bounding box, and the smallest and largest finite node value.
fn finite_cells(grid: &FlankMap) -> (Vec<Cell>, BBox, f64, f64) {
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
    (cells, bb, vmin, vmax)
}

/// Where the iso-lines' labels go: per level, the segment midpoint (in
/// pixels, `map` from the data) farthest from the labels already placed
/// and from the plot border `px`, if far enough; with its text and width.
fn label_places(
    map: impl Fn(&(f64, f64)) -> (i32, i32),
    px: &(std::ops::Range<i32>, std::ops::Range<i32>),
    contours: &[Vec<Segment>],
    level_text: &[String],
) -> Vec<((i32, i32), String, i32)> {
    let (ax, ay) = (px.0.clone(), px.1.clone());
    let mut placed: Vec<(i32, i32)> = Vec::new();
    let mut labels = Vec::new();
    for (segs, text) in contours.iter().zip(level_text) {
        let tw = text_width(text, CONTOUR_FONT);
        let mut best: Option<((i32, i32), f64)> = None;
        for &(a, b) in segs {
            let m = (0.5 * (a.0 + b.0), 0.5 * (a.1 + b.1));
            let p = map(&m);
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
    labels
}

/// The colour bar: its levels (ticks) with their texts, the colour range,
/// the texts at its ends, its label and the label's x in the column.
struct ColourBar<'a> {
    levels: &'a [f64],
    level_text: &'a [String],
    range: (f64, f64),
    max_text: &'a str,
    min_text: &'a str,
    label: &'a str,
    label_x: i32,
}

/// Draws the colour bar in its column `side`, spanning the plot's pixel
/// rows `px.1`.
fn colour_bar(
    side: &Area<'_>,
    px: &(std::ops::Range<i32>, std::ops::Range<i32>),
    bar: &ColourBar,
) -> DResult {
    let (levels, level_text, (cmin, cmax)) = (bar.levels, bar.level_text, bar.range);
    let (max_text, min_text, colorbar_label, label_x) =
        (bar.max_text, bar.min_text, bar.label, bar.label_x);
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
    for (&l, text) in levels.iter().zip(level_text) {
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
        max_text.to_string(),
        (bx0 - 8, top - 14),
        end_style.clone(),
    ))
    .map_err(de)?;
    side.draw(&Text::new(
        min_text.to_string(),
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
}
