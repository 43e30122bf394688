//! The report's loaded-contact figures: TE against pinion rotation per blank
//! and load, the multibody run (reduced model) against the reference FE
//! contact (the white paper's Figures 10 and 11), and the contact pattern at
//! the largest torque of both methods on the pinion flank (its Figure 12).
//!
//! Inputs are the stages' CSV files under `<out>/<scene>/`; a missing file
//! leaves its figure out.

use crate::report::figures::{column, read_csv, Csv, Figure};
use charts::{te_curve, Series};
use plotters::prelude::*;
use std::path::Path;

/// Cells of the contact-pattern map along the face (ξ) and the profile (η)
/// for the reference's nodes: about three flank nodes of the 35 × 75
/// reference mesh per cell and direction.
pub const PATTERN_CELLS: [usize; 2] = [50, 24];

/// The same for the reduced model's slices, which sample the flank more
/// sparsely (slices across the face, one contact line per position): half
/// as many cells each way, so that neighbouring samples meet.
pub const PATTERN_CELLS_SLICES: [usize; 2] = [25, 12];

/// TE against rotation for every blank combination with a reference run and
/// every torque: one SVG per blank and torque, written to `reports` as
/// `te_loaded_<blanks>_<T>nm.svg`; by torque, then blank combination with
/// the standard wheel first (side by side in the report).
pub fn te_figures(out: &Path, scene: &str, reports: &Path, torques: &[f64]) -> Vec<Figure> {
    let mut figs = Vec::new();
    let mut blanks: Vec<String> = crate::reference::reference_stage::LEVELS_FINEST_FIRST
        .iter()
        .filter_map(|l| {
            std::fs::read_dir(crate::reference::reference_stage::reference_dir(
                out, scene, l,
            ))
            .ok()
        })
        .flatten()
        .filter_map(|e| e.ok())
        .filter(|e| e.path().join("te.csv").exists())
        .filter_map(|e| e.file_name().into_string().ok())
        .collect();
    blanks.sort_by_key(|b| (!b.ends_with("_standard"), b.clone()));
    blanks.dedup();
    // The finest level's sweep of each.
    let references: Vec<(String, Csv)> = blanks
        .into_iter()
        .filter_map(|blank| {
            let csv = crate::reference::reference_stage::finest_reference(out, scene, &blank)
                .and_then(|d| read_csv(&d.join("te.csv")))?;
            Some((blank, csv))
        })
        .collect();
    for &t in torques {
        for (blank, reference) in &references {
            let mb_path = out
                .join(scene)
                .join("multibody")
                .join(blank)
                .join(format!("quasi_static_{t}nm.csv"));
            let mut series = Vec::new();
            if let Some(mb) = read_csv(&mb_path) {
                if let (Some(x), Some(y)) =
                    (column(&mb, "pinion_rotation_deg"), column(&mb, "te_urad"))
                {
                    series.push(Series {
                        name: "multibody 10 rpm (reduced model)".into(),
                        x: x.to_vec(),
                        y: y.to_vec(),
                        dashed: false,
                    });
                }
            }
            if let (Some(x), Some(y)) = (
                column(reference, "pinion_rotation_deg"),
                column(reference, &format!("te_{t}nm_urad")),
            ) {
                series.push(Series {
                    name: "reference FE contact".into(),
                    x: x.to_vec(),
                    y: y.to_vec(),
                    dashed: true,
                });
            }
            if series.len() < 2 {
                continue;
            }
            let file = reports.join(format!("te_loaded_{blank}_{t}nm.svg"));
            let title = format!("Loaded TE, {} blanks, {t} N·m", blank.replace('_', " / "));
            if te_curve(&file, &title, "pinion rotation (deg)", "TE (µrad)", &series).is_ok() {
                if let Ok(svg) = std::fs::read_to_string(&file) {
                    figs.push(Figure {
                        title,
                        file: format!("te_loaded_{blank}_{t}nm.svg"),
                        svg,
                    });
                }
            }
        }
    }
    figs
}

/// Colour of `v` in [0, 1]: dark blue → green → yellow.
fn ramp(v: f64) -> RGBColor {
    let stops = [
        (0.0, (68.0, 1.0, 84.0)),
        (0.33, (49.0, 104.0, 142.0)),
        (0.66, (53.0, 183.0, 121.0)),
        (1.0, (253.0, 231.0, 37.0)),
    ];
    let v = v.clamp(0.0, 1.0);
    let k = stops.iter().rposition(|s| s.0 <= v).unwrap_or(0).min(2);
    let (a, b) = (stops[k], stops[k + 1]);
    let f = (v - a.0) / (b.0 - a.0);
    let c = |x: f64, y: f64| (x + f * (y - x)).round() as u8;
    RGBColor(c(a.1 .0, b.1 .0), c(a.1 .1, b.1 .1), c(a.1 .2, b.1 .2))
}

/// The pressure envelope on a grid of `cells` over the unit flank (ξ, η):
/// each cell that holds points takes their largest pressure, as
/// (ξ₀, η₀, ξ₁, η₁, p). Cells without a point are not returned.
pub fn envelope_cells(
    pts: &[(f64, f64, f64)],
    cells: [usize; 2],
) -> Vec<(f64, f64, f64, f64, f64)> {
    let [nx, ny] = cells;
    let mut grid = vec![f64::NAN; nx * ny];
    for &(x, y, p) in pts {
        if !(0.0..=1.0).contains(&x) || !(0.0..=1.0).contains(&y) {
            continue;
        }
        let i = ((x * nx as f64) as usize).min(nx - 1);
        let j = ((y * ny as f64) as usize).min(ny - 1);
        let c = &mut grid[j * nx + i];
        *c = if c.is_nan() { p } else { c.max(p) };
    }
    let (dx, dy) = (1.0 / nx as f64, 1.0 / ny as f64);
    (0..nx * ny)
        .filter(|&k| !grid[k].is_nan())
        .map(|k| {
            let (i, j) = ((k % nx) as f64, (k / nx) as f64);
            (i * dx, j * dy, (i + 1.0) * dx, (j + 1.0) * dy, grid[k])
        })
        .collect()
}

/// A point of a contact pattern: ξ, η on the pinion flank, pressure MPa.
pub type PatternPoint = (f64, f64, f64);

/// The contact pattern at torque `t` of one blank combination, both models'
/// loaded points (pressure > 0): the reduced model's slices (quasi-static
/// LTCA, all positions at `t`) and the finest reference's nodal envelope.
pub fn pattern_points(
    out: &Path,
    scene: &str,
    blank: &str,
    t: f64,
) -> Option<(Vec<PatternPoint>, Vec<PatternPoint>)> {
    let reduced = read_csv(&out.join(scene).join("ltca").join(blank).join("slices.csv"))?;
    let reference = read_csv(
        &crate::reference::reference_stage::finest_reference(out, scene, blank)?
            .join(format!("pattern_{t}nm.csv")),
    )?;
    let pick = |csv: &Csv, at: Option<f64>| -> Vec<PatternPoint> {
        let (Some(xi), Some(eta), Some(p)) = (
            column(csv, "xi"),
            column(csv, "eta"),
            column(csv, "pressure_mpa"),
        ) else {
            return Vec::new();
        };
        let tq = column(csv, "torque_nm");
        (0..xi.len())
            .filter(|&i| match (at, tq) {
                (Some(t), Some(tq)) => (tq[i] - t).abs() < 1e-9 * t.max(1.0),
                _ => true,
            })
            .filter(|&i| p[i] > 0.0)
            .map(|i| (xi[i], eta[i], p[i]))
            .collect()
    };
    Some((pick(&reduced, Some(t)), pick(&reference, None)))
}

/// Contact pattern at torque `t` of one blank combination: the reduced
/// model's slices (quasi-static LTCA, all positions) and the reference's
/// pressure envelope, on the pinion flank's unit coordinates (ξ along the
/// face, toe → heel; η up the profile, root → tip), one colour scale.
pub fn pattern_figure(
    out: &Path,
    scene: &str,
    blank: &str,
    t: f64,
    reports: &Path,
) -> Option<Figure> {
    let (a, b) = pattern_points(out, scene, blank, t)?;
    let p_max = a.iter().chain(&b).map(|p| p.2).fold(0.0, f64::max);
    // Points below 2% of the largest pressure are left out: the nodal
    // recovery leaves small positive values around the contact.
    let keep = |v: Vec<(f64, f64, f64)>| -> Vec<(f64, f64, f64)> {
        v.into_iter().filter(|p| p.2 >= 0.02 * p_max).collect()
    };
    let (a, b) = (keep(a), keep(b));
    if a.is_empty() || b.is_empty() {
        return None;
    }
    let peak = |v: &[(f64, f64, f64)]| v.iter().map(|p| p.2).fold(0.0, f64::max);
    let (peak_a, peak_b) = (peak(&a), peak(&b));
    let name = format!("pattern_{blank}_{t}nm.svg");
    let file = reports.join(&name);
    let title = format!(
        "Contact pattern at {t} N·m, {} blanks (pressure envelope, one colour scale 0 – {p_max:.0} MPa, from 2 %; frame: the flank)",
        blank.replace('_', " / ")
    );
    let draw = || -> Result<(), Box<dyn std::error::Error>> {
        let root = SVGBackend::new(&file, (1100, 480)).into_drawing_area();
        root.fill(&WHITE)?;
        let root = root.titled(&title, ("sans-serif", 20))?;
        let panels = root.split_evenly((1, 2));
        for (area, (name, pts, cells)) in panels.iter().zip([
            (
                format!("reduced model (LTCA slices), peak {peak_a:.0} MPa"),
                &a,
                PATTERN_CELLS_SLICES,
            ),
            (
                format!("reference FE (nodes), peak {peak_b:.0} MPa"),
                &b,
                PATTERN_CELLS,
            ),
        ]) {
            let mut chart = ChartBuilder::on(area)
                .caption(&name, ("sans-serif", 16))
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(50)
                .build_cartesian_2d(-0.05..1.05, -0.05..1.05)?;
            chart
                .configure_mesh()
                .x_desc("ξ (face, toe → heel)")
                .y_desc("η (profile, root → tip)")
                .draw()?;
            // The flank's outline and the envelope filled cell by cell.
            chart.draw_series(envelope_cells(pts, cells).into_iter().map(
                |(x0, y0, x1, y1, p)| {
                    Rectangle::new([(x0, y0), (x1, y1)], ramp(p / p_max).filled())
                },
            ))?;
            chart.draw_series(std::iter::once(Rectangle::new(
                [(0.0, 0.0), (1.0, 1.0)],
                BLACK.stroke_width(1),
            )))?;
        }
        root.present()?;
        Ok(())
    };
    draw().ok()?;
    Some(Figure {
        svg: std::fs::read_to_string(&file).ok()?,
        title,
        file: name,
    })
}

#[cfg(test)]
mod tests {
    use super::envelope_cells;

    /// Each cell takes the largest pressure of the points in it; points
    /// outside the flank and empty cells give nothing.
    #[test]
    fn envelope_cells_take_the_largest_pressure_per_cell() {
        let pts = [
            (0.10, 0.10, 5.0),
            (0.20, 0.20, 7.0),
            (0.90, 0.60, 1.0),
            (1.00, 1.00, 2.0),
            (1.20, 0.50, 9.0),
        ];
        let cells = envelope_cells(&pts, [2, 2]);
        assert_eq!(
            cells,
            vec![(0.0, 0.0, 0.5, 0.5, 7.0), (0.5, 0.5, 1.0, 1.0, 2.0)]
        );
    }
}
