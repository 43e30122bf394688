//! Run time against error ([`pareto_chart`]): the settings of a stage as
//! points on log–log axes, each series' Pareto front as a line, the default
//! setting ringed and a target error as a dashed horizontal line.

use crate::frame::{
    chart_builder, de, frame, padded, plot_pixel_range, render_to_file, text_style, BBox, PALETTE,
};
use crate::legend::{draw_legend, legend_width, Sample};
use crate::PlotError;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};
use std::path::Path;

/// One setting of a stage: its cost and its error.
#[derive(Debug, Clone, PartialEq)]
pub struct ParetoPoint {
    /// Cost, e.g. CPU seconds (> 0).
    pub cost: f64,
    /// Error, e.g. percent (≥ 0; zero is drawn at the axis' lower end).
    pub error: f64,
    /// Written beside the point.
    pub label: String,
    /// The stage's default setting: ringed.
    pub is_default: bool,
}

/// The settings one parameter of a stage runs through.
#[derive(Debug, Clone, PartialEq)]
pub struct ParetoSeries {
    pub name: String,
    pub points: Vec<ParetoPoint>,
}

/// Indices of the points no other point beats in both cost and error
/// (ties kept), sorted by cost.
pub fn pareto_front(points: &[ParetoPoint]) -> Vec<usize> {
    let finite = |p: &ParetoPoint| p.cost.is_finite() && p.error.is_finite();
    let mut front: Vec<usize> = (0..points.len())
        .filter(|&i| finite(&points[i]))
        .filter(|&i| {
            let a = &points[i];
            !points.iter().any(|b| {
                finite(b)
                    && b.cost <= a.cost
                    && b.error <= a.error
                    && (b.cost < a.cost || b.error < a.error)
            })
        })
        .collect();
    front.sort_by(|&a, &b| points[a].cost.total_cmp(&points[b].cost));
    front
}

/// Pareto chart: x = cost (log), y = error (log), one colour per series,
/// its front as a line, every point labelled, the default ringed, `target`
/// as a dashed line.
///
/// Errors: [`PlotError::Input`] without series or without a point of
/// positive finite cost.
pub fn pareto_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    target: f64,
    series: &[ParetoSeries],
) -> Result<(), PlotError> {
    let input = |msg: String| PlotError::Input {
        path: path.to_path_buf(),
        msg,
    };
    if series.is_empty() {
        return Err(input("no series".into()));
    }
    // Errors of zero (exact agreement) sit one decade below the smallest
    // positive error or the target.
    let positive = series
        .iter()
        .flat_map(|s| &s.points)
        .map(|p| p.error)
        .filter(|e| e.is_finite() && *e > 0.0)
        .fold(target.max(f64::MIN_POSITIVE), f64::min);
    let floor = positive / 10.0;
    let xy = |p: &ParetoPoint| (p.cost.log10(), p.error.max(floor).log10());
    let mut bb = BBox::empty();
    for p in series.iter().flat_map(|s| &s.points) {
        if p.cost > 0.0 {
            bb.add(xy(p));
        }
    }
    if bb.is_empty() {
        return Err(input("no point of positive finite cost".into()));
    }
    if target > 0.0 {
        bb.add((bb.x0, target.log10()));
    }
    let xr = padded(bb.x0, bb.x1, 0.08);
    let yr = padded(bb.y0, bb.y1, 0.08);
    let names: Vec<&str> = series.iter().map(|s| s.name.as_str()).collect();
    let mut entries: Vec<(String, Sample)> = series
        .iter()
        .enumerate()
        .map(|(j, s)| {
            (
                s.name.clone(),
                Sample::LineMarker(PALETTE[j % PALETTE.len()]),
            )
        })
        .collect();
    entries.push((
        format!("target {target} %"),
        Sample::Line {
            color: RGBColor(120, 120, 120),
            width: 1,
            dashed: true,
        },
    ));
    entries.push((
        "default (ringed)".into(),
        Sample::Line {
            color: RGBColor(0, 0, 0),
            width: 2,
            dashed: false,
        },
    ));
    let legend_w = legend_width(&names).max(legend_width(&["default (ringed)"]));
    let pow10 = |v: &f64| log_tick(*v);
    render_to_file(path, (1100, 650), |root| {
        let (main, side) = frame(root, title, legend_w)?;
        let px = plot_pixel_range(&main)?;
        let mut chart = chart_builder(&main)
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
            .map_err(de)?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .x_labels(8)
            .y_labels(8)
            .label_style((crate::frame::FONT, crate::frame::TICK_FONT))
            .axis_desc_style((crate::frame::FONT, crate::frame::DESC_FONT))
            .x_label_formatter(&pow10)
            .y_label_formatter(&pow10)
            .bold_line_style(RGBColor(205, 205, 205))
            .light_line_style(RGBColor(245, 245, 245))
            .draw()
            .map_err(de)?;
        if target > 0.0 {
            chart
                .draw_series(DashedLineSeries::new(
                    [(xr.0, target.log10()), (xr.1, target.log10())],
                    8,
                    5,
                    RGBColor(120, 120, 120).stroke_width(1),
                ))
                .map_err(de)?;
        }
        for (j, s) in series.iter().enumerate() {
            let color = PALETTE[j % PALETTE.len()];
            let front: Vec<(f64, f64)> = pareto_front(&s.points)
                .into_iter()
                .filter(|&i| s.points[i].cost > 0.0)
                .map(|i| xy(&s.points[i]))
                .collect();
            if front.len() > 1 {
                chart
                    .draw_series(LineSeries::new(front, color.stroke_width(2)))
                    .map_err(de)?;
            }
            for p in s
                .points
                .iter()
                .filter(|p| p.cost > 0.0 && p.error.is_finite())
            {
                let at = xy(p);
                chart
                    .draw_series(std::iter::once(Circle::new(at, 5, color.filled())))
                    .map_err(de)?;
                if p.is_default {
                    chart
                        .draw_series(std::iter::once(Circle::new(at, 11, BLACK.stroke_width(2))))
                        .map_err(de)?;
                }
                chart
                    .draw_series(std::iter::once(Text::new(
                        p.label.clone(),
                        at,
                        text_style(15.0, HPos::Left, VPos::Bottom),
                    )))
                    .map_err(de)?;
            }
        }
        let top = px.1.start - side.get_base_pixel().1;
        draw_legend(&side, top, &entries)
    })
}

/// The label of a tick at log₁₀ value `v`: 10^v to two significant
/// digits, plain between 0.001 and 10,000, else in e-notation.
pub(crate) fn log_tick(v: f64) -> String {
    let x = 10f64.powf(v);
    if (1e-3..1e4).contains(&x) {
        let d = (1 - x.log10().floor() as i32).max(0) as usize;
        let s = format!("{x:.d$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        format!("{x:.1e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(cost: f64, error: f64) -> ParetoPoint {
        ParetoPoint {
            cost,
            error,
            label: String::new(),
            is_default: false,
        }
    }

    #[test]
    fn log_ticks_are_plain_numbers_in_the_middle_range() {
        assert_eq!(log_tick(0.0), "1");
        assert_eq!(log_tick(-1.0), "0.1");
        assert_eq!(log_tick(2f64.log10()), "2");
        assert_eq!(log_tick(0.03f64.log10()), "0.03");
        assert_eq!(log_tick(-5.0), "1.0e-5");
    }

    #[test]
    fn pareto_front_drops_dominated_points_and_sorts_by_cost() {
        let pts = [
            p(3.0, 1.0),
            p(1.0, 5.0),
            p(2.0, 6.0),
            p(4.0, 1.0),
            p(0.5, f64::NAN),
        ];
        assert_eq!(pareto_front(&pts), vec![1, 0]);
    }
}
