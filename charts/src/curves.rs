//! Line charts of curves ([`te_curve`]), e.g. the transmission error over
//! the pinion rotation.

use crate::frame::{
    chart_builder, de, draw_mesh, finite_runs, frame, padded, plot_pixel_range, render_to_file,
    BBox, PALETTE,
};
use crate::legend::{draw_legend, legend_width, Sample};
use crate::PlotError;
use plotters::prelude::*;
use std::path::Path;

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
