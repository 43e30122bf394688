//! Contact pattern on a flank ([`contact_path`]): the flank outline, the
//! paths of contact and the contact ellipses, at equal aspect.

use crate::equal_aspect::{draw_equal_aspect, EqualAspectPlot, Line};
use crate::frame::{BBox, PALETTE};
use crate::legend::Sample;
use crate::PlotError;
use plotters::prelude::*;
use std::path::Path;

/// A named polyline ([`contact_path`], [`tooth_section`]).
///
/// [`tooth_section`]: crate::tooth_section
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
///
/// [`equal_aspect_ranges`]: crate::equal_aspect_ranges
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
