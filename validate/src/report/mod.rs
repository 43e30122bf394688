//! `reports/report.md`, a self-contained `reports/report.html`,
//! `reports/summary.json` and `reports/results.md`, written atomically.
//!
//! The report opens with what a reader came for, the loaded TE of the
//! reduced model against the reference FE contact and the white paper's
//! Tables 3 and 4, with its figures; then run times; then the details: the
//! unloaded TCA, the cross-check of the surface of roll angles and the
//! method notes. Each figure stands under the section that discusses it.

pub mod comparison;
pub mod comparison_row;
pub mod differences;
pub mod figures;
pub mod gather;
pub mod html;
pub mod layout;
pub mod published;
pub mod published_comparison;
pub mod results;
pub mod run;
pub mod sections;
pub mod trend;

use crate::report::figures::{figure_lines, figures_before_table, Figure};
use crate::report::gather::ReportFigures;
use crate::report::published::Published;
use crate::studies::utca_check::UtcaCheck;
use formats::output::{write_atomic, write_json, WriteError};
use sections::{stage_tradeoffs, stress};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

#[derive(Debug, Clone, Serialize)]
pub struct Summary<'a> {
    pub utca: &'a UtcaCheck,
    /// Per blank and load: TE of the reduced model and the reference, their
    /// differences and run times.
    pub loaded_te: Option<&'a [crate::report::comparison::Row]>,
    pub published_te_ptp_1nm_urad: Option<&'a Published>,
    pub te_ptp_difference_percent: Option<f64>,
}

/// The unloaded TCA: TE, contact ratio, run time, the published value where
/// there is one, and the flank stage's plots.
fn unloaded_section(s: &mut String, c: &UtcaCheck, published: Option<&Published>, figs: &[Figure]) {
    let _ = writeln!(s, "## Unloaded tooth contact ({} flank)\n", c.side);
    let _ = writeln!(s, "| quantity | this toolkit | published |");
    let _ = writeln!(s, "|---|---|---|");
    match published {
        Some(p) => {
            let d = (c.fast_te_ptp_urad - p.value) / p.value * 100.0;
            let _ = writeln!(
                s,
                "| TE peak-to-peak, µrad | {:.2} (unloaded) | {:.1} at 1 N·m ({}); difference {:+.1}% |",
                c.fast_te_ptp_urad, p.value, p.source, d
            );
        }
        None => {
            let _ = writeln!(
                s,
                "| TE peak-to-peak, µrad | {:.2} (unloaded) | not available |",
                c.fast_te_ptp_urad
            );
        }
    }
    let _ = writeln!(s, "| TE mean, µrad | {:.2} | |", c.fast_te_mean_urad);
    let _ = writeln!(s, "| conjugate contact ratio | {:.3} | |", c.contact_ratio);
    let _ = writeln!(
        s,
        "| run time per position | {:.3} ms (surface of roll angles) | direct search {:.1} ms |\n",
        c.fast_ms_per_position, c.direct_ms_per_position
    );
    if let Some(p) = published {
        let _ = writeln!(
            s,
            "The peak-to-peak row is a calibration, not a validation. The white paper does not publish this pair's ease-off (crowning, motion error); it was chosen so that the unloaded TE comes out at the published {:.1} µrad peak-to-peak at 1 N·m, so agreement here shows the ease-off does what it was chosen for and says nothing yet about the TCA. The independent checks of the unloaded TCA are the direct contact search below and the reference FE's unloaded run in the loaded-TE section above.\n",
            p.value
        );
    }
    figure_lines(s, figs, true);
}

/// The cross-check of the surface of roll angles against the direct search.
fn roll_surface_section(s: &mut String, c: &UtcaCheck) {
    let _ = writeln!(
        s,
        "## Surface of roll angles against the direct contact search\n\nThe fast UTCA finds contact through the tabulated surface of roll angles; the reference places both flanks, projects every pinion point onto the wheel flank and minimises the gap. Largest difference: **{:.4} µrad**; smallest gap on the active flanks at the reference TE: {:.2e} µm (no penetration).\n",
        c.max_abs_difference_urad, c.min_gap_um
    );
    let _ = writeln!(
        s,
        "| pinion rotation, deg | fast TE, µrad | direct TE, µrad | difference, µrad |"
    );
    let _ = writeln!(s, "|---|---|---|---|");
    for r in &c.rows {
        let _ = writeln!(
            s,
            "| {:.2} | {:.4} | {:.4} | {:+.4} |",
            r.pinion_rotation_deg, r.fast_te_urad, r.direct_te_urad, r.difference_urad
        );
    }
    s.push('\n');
}

/// The whole report as markdown.
pub fn markdown(
    c: &UtcaCheck,
    published: Option<&Published>,
    loaded: Option<&crate::report::comparison::Comparison>,
    figs: &ReportFigures,
) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Validation report: scene `{}`\n", c.name);
    let _ = writeln!(
        s,
        "First the loaded transmission error (TE) of the reduced model against the reference FE contact and the white paper's Tables 3 and 4, with the TE curves and contact patterns; then the run times. The details follow: the unloaded TCA, the cross-check of its surface of roll angles, and the notes on the reference's mesh convergence and the line-load check.\n"
    );
    let parts = loaded.map(|l| layout::split(&l.markdown));
    match &parts {
        Some(p) => s.push_str(&p.te),
        None => {
            let _ = writeln!(
                s,
                "## Loaded TCA\n\nNo comparison: run `solver dynamic` and `validate reference` first (`make validate REFERENCE=1` does).\n"
            );
        }
    }
    if !figs.loaded_te.is_empty() {
        let _ = writeln!(
            s,
            "TE against pinion rotation per load: the reduced model's multibody run at 10 rpm (solid) against the reference FE contact (dashed), as in the white paper's Figures 10 and 11; standard wheel blank first.\n"
        );
        figure_lines(&mut s, &figs.loaded_te, true);
    }
    s.push_str(&figs.reference_uncertainty.markdown);
    s.push_str(&figs.ablation);
    s.push_str(&figs.grid_convergence);
    if let Some(l) = loaded {
        s.push_str(&published_comparison::paragraph(&l.rows));
    }
    s.push_str(&figs.calibrated_variant.markdown);
    if let Some(p) = &parts {
        s.push_str(&p.discussion);
    }
    let pattern_text = parts.as_ref().map_or("", |p| p.patterns.as_str());
    if !figs.patterns.is_empty() || !pattern_text.is_empty() {
        match figs.pattern_torque_nm {
            Some(t) => {
                let _ = writeln!(s, "### Contact pattern at {t} N·m\n");
            }
            None => {
                let _ = writeln!(s, "### Contact pattern\n");
            }
        }
        s.push_str(pattern_text);
        if !figs.pattern_numbers.is_empty() {
            s.push_str(&figs.pattern_numbers);
            s.push('\n');
        }
        if !figs.patterns.is_empty() {
            let _ = writeln!(
                s,
                "Pressure envelope over all positions on the pinion flank (ξ along the face, η up the profile): the reduced model's slices on the left, the reference FE's nodes on the right, one colour scale per figure.\n"
            );
            figure_lines(&mut s, &figs.patterns, false);
        }
    }
    s.push_str(&figs.root_stress.markdown);
    if let Some(p) = &parts {
        s.push_str(&p.run_time);
    }
    let tradeoff = parts.as_ref().map_or("", |p| p.tradeoff.as_str());
    match &figs.tradeoff {
        Some(f) => s.push_str(&figures_before_table(tradeoff, std::slice::from_ref(f))),
        None => s.push_str(tradeoff),
    }
    if let Some(cl) = &figs.contact_laws {
        s.push_str(&cl.markdown);
    }
    unloaded_section(&mut s, c, published, &figs.unloaded);
    roll_surface_section(&mut s, c);
    s.push_str(&stress::text(&figs.stress));
    s.push_str(&stage_tradeoffs::text(&figs.stage_tradeoffs));
    if let Some(p) = &parts {
        s.push_str(&p.details);
    }
    s.push_str(&figs.lumped.markdown);
    s.push_str(&figs.sensitivity.markdown);
    s.push_str(&figs.compliant.markdown);
    s.push_str(&figs.gearbox.markdown);
    s.push_str(&figs.ste_dte.markdown);
    s.push_str(&figs.rattle.markdown);
    while s.ends_with("\n\n") {
        s.pop();
    }
    s
}

/// What [`write`] did besides the report files.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Written {
    /// The README had the results markers and now holds the results table.
    pub readme_updated: bool,
}

/// Writes `report.md`, `report.html`, `summary.json` and `results.md` into
/// `dir` (the figures' SVG files are there already, see
/// [`crate::report::gather::report_figures`]), and the results table into the
/// README at `readme` between its markers (when it has them and there is a
/// loaded comparison).
pub fn write(
    dir: &Path,
    c: &UtcaCheck,
    published: Option<&Published>,
    loaded: Option<&crate::report::comparison::Comparison>,
    figures: &ReportFigures,
    readme: &Path,
) -> Result<Written, WriteError> {
    let md =
        markdown(c, published, loaded, figures) + &crate::report::figures::left_out_section(dir);
    write_atomic(&dir.join("report.md"), md.as_bytes())?;
    let inline = |file: &str| -> Option<String> {
        figures
            .all()
            .find(|f| f.file == file)
            .map(|f| f.svg.clone())
    };
    let page = html::page(&format!("Validation report: {}", c.name), &md, &inline);
    write_atomic(&dir.join("report.html"), page.as_bytes())?;
    let summary = Summary {
        utca: c,
        loaded_te: loaded.map(|l| l.rows.as_slice()),
        published_te_ptp_1nm_urad: published,
        te_ptp_difference_percent: published
            .map(|p| (c.fast_te_ptp_urad - p.value) / p.value * 100.0),
    };
    write_json(&dir.join("summary.json"), &summary)?;
    let rows = loaded.map_or(&[][..], |l| l.rows.as_slice());
    let table = results::markdown(&c.name, rows, &results::Stamp::now());
    write_atomic(&dir.join("results.md"), table.as_bytes())?;
    let readme_updated = !rows.is_empty() && results::update_readme(readme, &table)?;
    Ok(Written { readme_updated })
}
