//! Tooth sections ([`tooth_section`]): named profile polylines at equal
//! aspect.

use crate::equal_aspect::{draw_equal_aspect, EqualAspectPlot, Line};
use crate::frame::{BBox, PALETTE};
use crate::legend::Sample;
use crate::{PathSeries, PlotError};
use std::path::Path;

/// Tooth section: named polylines (e.g. concave and convex flank profiles,
/// root and tip lines) with a legend, at equal aspect.
///
/// Axes: x and y in mm in the plane of the section; 1 mm has the same length
/// on the page in x and in y (see [`equal_aspect_ranges`]). The ranges cover
/// all finite points plus 5 %; non-finite points break a curve.
///
/// Errors: [`PlotError::Input`] if there is no finite point to plot.
///
/// [`equal_aspect_ranges`]: crate::equal_aspect_ranges
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
