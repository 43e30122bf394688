//! Plots at equal aspect (1 mm the same length in x and y): polylines,
//! translucent patches clipped to the view, and a legend; used by
//! [`crate::contact_path()`] and [`crate::tooth_section`].

use crate::frame::{
    chart_builder, de, draw_mesh, finite_runs, frame, padded, pixel_spans, plot_pixel_range,
    render_to_file, BBox, MARGIN, TITLE_H, X_LABEL_AREA, Y_LABEL_AREA,
};
use crate::legend::{draw_legend, legend_width, Sample};
use crate::numeric::equal_aspect_ranges;
use crate::PlotError;
use plotters::prelude::*;
use std::path::Path;

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
pub(crate) struct Line {
    pub(crate) points: Vec<(f64, f64)>,
    pub(crate) color: RGBColor,
    pub(crate) width: u32,
    pub(crate) markers: bool,
}

/// Everything drawn in an equal-aspect plot.
pub(crate) struct EqualAspectPlot<'d> {
    pub(crate) lines: Vec<Line>,
    pub(crate) patches: Vec<(Vec<(f64, f64)>, RGBColor)>, // closed polygons, filled translucent
    pub(crate) legend: Vec<(String, Sample)>,
    pub(crate) bbox: BBox,
    pub(crate) x_desc: &'d str,
    pub(crate) y_desc: &'d str,
}

const EQUAL_ASPECT_WIDTH: u32 = 1100;
/// Range of the page height of equal-aspect plots, px.
const EQUAL_ASPECT_HEIGHT: (f64, f64) = (480.0, 1000.0);

pub(crate) fn draw_equal_aspect(
    path: &Path,
    title: &str,
    plot: EqualAspectPlot<'_>,
) -> Result<(), PlotError> {
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
