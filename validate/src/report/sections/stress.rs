//! The report's stress-matrix section, formatted from
//! `<out>/<scene>/stress/summary.json` ([`StressSummary`]): the outcome
//! grid, the counts (cells, converged, refused with their reasons, failed,
//! skipped), the worst torque balance and energy drift, non-finite values,
//! and the torque from which each design's contact reaches an edge.

use crate::report::figures::{copied, Figure};
use crate::studies::stress::{Cell, Outcome, StressSummary, Study};
use std::fmt::Write as _;
use std::path::Path;

/// The section's markdown (None: no summary) and its figure.
#[derive(Debug, Clone, Default)]
pub struct StressSection {
    pub markdown: Option<String>,
    pub figure: Option<Figure>,
}

/// The file name of the outcome grid in the report directory.
pub const FIGURE_FILE: &str = "stress_outcomes.svg";

/// Reads the scene's stress summary under `out` and copies its chart into
/// `reports`; an unreadable summary is stated in the section.
pub fn section(out: &Path, scene: &str, reports: &Path) -> StressSection {
    let summary = match StressSummary::read(out, scene) {
        Ok(Some(s)) => s,
        Ok(None) => return StressSection::default(),
        Err(e) => {
            return StressSection {
                markdown: Some(format!(
                    "## Stress matrix\n\nThe stress summary could not be read ({e:#}); run `make stress` again.\n\n"
                )),
                figure: None,
            }
        }
    };
    let figure = copied(
        "Stress matrix: outcome per cell",
        &out.join(scene).join("stress").join("outcomes.svg"),
        reports,
        FIGURE_FILE,
    );
    StressSection {
        markdown: Some(markdown(&summary, figure.as_ref())),
        figure,
    }
}

/// The section's text, or one line saying that there is no summary.
pub fn text(s: &StressSection) -> String {
    match &s.markdown {
        Some(m) => m.clone(),
        None => "## Stress matrix\n\nNo stress matrix: `out/<scene>/stress/summary.json` is absent (`make stress` writes it).\n\n".into(),
    }
}

fn fmt_opt(v: Option<f64>) -> String {
    v.map_or_else(|| "–".into(), |x| format!("{x:.1e}"))
}

/// The section from a summary; `figure` the copied outcome grid.
pub fn markdown(s: &StressSummary, figure: Option<&Figure>) -> String {
    let mut m = String::new();
    let count = |k: usize| s.cells.iter().filter(|c| c.outcome.class() == k).count();
    let _ = writeln!(m, "## Stress matrix\n");
    let _ = writeln!(
        m,
        "The stress matrix on cached meshes and stiffness files ({} designs, standard blanks): loads from 0 N·m up to edge contact, slices per pair, stiffness grids, coast flanks, and undamped multibody runs at 300 N·m over one mesh cycle, at most 0.1 s (maximum step, tolerance, pinion speed). {} cells: **{} converged**, {} refused, {} failed, {} skipped (inputs not cached); {:.0} s wall time.\n",
        s.designs.len(),
        s.cells.len(),
        count(0),
        count(1),
        count(2),
        count(3),
        s.wall_s
    );
    if let Some(f) = figure {
        let _ = writeln!(m, "![{}]({})\n", f.title, f.file);
    }
    let worst_drift = s
        .cells
        .iter()
        .filter_map(|c| c.energy_drift.map(|b| (b, c)))
        .max_by(|a, b| a.0.total_cmp(&b.0));
    checks(&mut m, s, worst_drift);
    m.push('\n');
    edge_contacts(&mut m, s);
    m.push('\n');
    not_converged(&mut m, s);
    iteration_counts(&mut m, s, worst_drift);
    m
}

/// The checks table: non-finite values, the worst torque balance, tensile
/// slice forces, implausible deflections, TE decreasing with load and the
/// worst energy drift (`worst_drift`).
fn checks(m: &mut String, s: &StressSummary, worst_drift: Option<(f64, &Cell)>) {
    let worst_balance = s
        .cells
        .iter()
        .filter_map(|c| c.torque_balance.map(|b| (b, c)))
        .max_by(|a, b| a.0.total_cmp(&b.0));
    let non_finite = s.cells.iter().filter(|c| c.non_finite).count();
    let tensile = s
        .cells
        .iter()
        .filter(|c| c.compressive_only == Some(false))
        .count();
    let decreasing: Vec<String> = s
        .cells
        .iter()
        .filter(|c| c.te_monotonic == Some(false))
        .map(|c| format!("{} at {}", c.design, c.label))
        .collect();
    let _ = writeln!(m, "| check | result |");
    let _ = writeln!(m, "|---|---|");
    let _ = writeln!(
        m,
        "| cells with NaN or infinity in an output | {non_finite} |"
    );
    match worst_balance {
        Some((b, c)) => {
            let _ = writeln!(
                m,
                "| worst torque balance, |Σλ₁F − T| / T | {b:.1e} ({}, {} {}) |",
                c.design,
                c.study.name(),
                c.label
            );
        }
        None => {
            let _ = writeln!(m, "| worst torque balance | no LTCA cell ran |");
        }
    }
    let _ = writeln!(m, "| cells with a tensile slice force | {tensile} |");
    let mut implausible: Vec<String> = Vec::new();
    for c in &s.cells {
        let Some(r) = c.deflection_to_thickness else {
            continue;
        };
        if r > crate::studies::stress::DEFLECTION_LIMIT
            && !implausible
                .iter()
                .any(|d| d.starts_with(&format!("{} ", c.design)))
        {
            implausible.push(format!(
                "{} from {} ({:.0} %)",
                c.design,
                c.label,
                r * 100.0
            ));
        }
    }
    let _ = writeln!(
        m,
        "| loaded deflection above {:.0} % of the tooth thickness (TE flagged implausible) | {} |",
        crate::studies::stress::DEFLECTION_LIMIT * 100.0,
        if implausible.is_empty() {
            "nowhere".to_string()
        } else {
            implausible.join("; ")
        }
    );
    let _ = writeln!(
        m,
        "| TE decreasing with load | {} |",
        if decreasing.is_empty() {
            "nowhere".to_string()
        } else {
            decreasing.join("; ")
        }
    );
    if let Some((d, c)) = worst_drift {
        let _ = writeln!(
            m,
            "| worst energy drift of the undamped runs (of kinetic energy + work) | {d:.1e} ({}, {} {}) |",
            c.design,
            c.study.name(),
            c.label
        );
    }
}

/// Per design: its grid and positions, and the torque from which its
/// contact reaches an edge.
fn edge_contacts(m: &mut String, s: &StressSummary) {
    let _ = writeln!(
        m,
        "| design | grid | positions | edge contact from | edge | pinion rotation | overshoot | largest load run |"
    );
    let _ = writeln!(m, "|---|---|---|---|---|---|---|---|");
    for d in &s.designs {
        match (&d.edge_contact, d.edge_contact_torque_nm) {
            (Some(e), Some(t)) => {
                let _ = writeln!(
                    m,
                    "| {} | {} × {} | {} | {t} N·m | {} (pair {}) | {:.2}° | {:.3} mm | {} N·m |",
                    d.design,
                    d.grid[0],
                    d.grid[1],
                    d.positions,
                    e.edge.name(),
                    e.pair,
                    e.pinion_rotation_deg,
                    e.overshoot_mm,
                    d.largest_load_nm
                );
            }
            _ => {
                let _ = writeln!(
                    m,
                    "| {} | {} × {} | {} | none | | | | {} N·m |",
                    d.design, d.grid[0], d.grid[1], d.positions, d.largest_load_nm
                );
            }
        }
    }
}

/// The cells not converged, with the first line of their reason.
fn not_converged(m: &mut String, s: &StressSummary) {
    let mut reasons: Vec<String> = Vec::new();
    for c in &s.cells {
        let (kind, msg) = match &c.outcome {
            Outcome::Converged => continue,
            Outcome::Refused(x) => ("refused", x),
            Outcome::Failed(x) => ("failed", x),
            Outcome::Skipped(x) => ("skipped", x),
        };
        let first = msg.lines().next().unwrap_or("");
        reasons.push(format!(
            "- {} · {} {}: {kind}: {first}",
            c.design,
            c.study.name(),
            c.label
        ));
    }
    if !reasons.is_empty() {
        let _ = writeln!(m, "Cells not converged:\n");
        for r in reasons {
            let _ = writeln!(m, "{r}");
        }
        m.push('\n');
    }
}

/// The largest iteration counts and the worst energy drift (`worst_drift`).
fn iteration_counts(m: &mut String, s: &StressSummary, worst_drift: Option<(f64, &Cell)>) {
    let iters = |st: Study| {
        s.cells
            .iter()
            .filter(|c| c.study == st)
            .filter_map(|c| c.iterations)
            .max()
    };
    let _ = writeln!(
        m,
        "Largest iteration counts: LTCA fixed point {} (active-set changes {}), multibody Newton iterations per run {}. Torque balance of the LTCA cells is relative to the pinion torque (N·m at 0 N·m); worst energy drift {}.\n",
        [Study::Load, Study::Slices, Study::Grid, Study::Flank]
            .into_iter()
            .filter_map(iters)
            .max()
            .map_or("–".into(), |v| v.to_string()),
        s.cells
            .iter()
            .filter_map(|c| c.active_set_changes)
            .max()
            .map_or("–".into(), |v| v.to_string()),
        [Study::MaxStep, Study::Tolerance, Study::Speed, Study::MultibodyLoad]
            .into_iter()
            .filter_map(iters)
            .max()
            .map_or("–".into(), |v| v.to_string()),
        fmt_opt(worst_drift.map(|w| w.0))
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::studies::stress::{Cell, DesignSummary};
    use formats::summaries::{Edge, EdgeContact};

    fn cell(design: &str, study: Study, label: &str, outcome: Outcome, balance: f64) -> Cell {
        Cell {
            design: design.into(),
            study,
            value: 0.0,
            unit: String::new(),
            label: label.into(),
            outcome,
            iterations: Some(4),
            active_set_changes: Some(2),
            steps: None,
            rejected_steps: None,
            sim_time_s: None,
            non_finite: false,
            torque_balance: Some(balance),
            compressive_only: Some(true),
            te_monotonic: Some(true),
            te_mean_urad: Some(100.0),
            energy_drift: None,
            edge_contact: None,
            deflection_to_thickness: None,
            cpu_s: 0.1,
        }
    }

    #[test]
    fn stress_section_counts_outcomes_names_reasons_worst_balance_and_edge_torques() {
        let s = StressSummary {
            scene: "default".into(),
            designs: vec![DesignSummary {
                design: "seed001_9x40".into(),
                scene: "s.toml".into(),
                grid: [6, 10],
                positions: 41,
                edge_contact_torque_nm: Some(100.0),
                edge_contact: Some(EdgeContact {
                    edge: Edge::WheelTip,
                    pinion_rotation_deg: 2.5,
                    pair: 1,
                    overshoot_mm: 0.0123,
                }),
                largest_load_nm: 5000.0,
            }],
            cells: vec![
                cell(
                    "seed001_9x40",
                    Study::Load,
                    "0 N·m",
                    Outcome::Converged,
                    0.0,
                ),
                cell(
                    "seed001_9x40",
                    Study::Load,
                    "5000 N·m",
                    Outcome::Converged,
                    3.2e-16,
                ),
                cell(
                    "seed001_9x40",
                    Study::Speed,
                    "10 rpm",
                    Outcome::Refused("pinion_torque_nm = 0 is below 1e-3".into()),
                    0.0,
                ),
                cell(
                    "seed001_9x40",
                    Study::Flank,
                    "coast",
                    Outcome::Skipped("no coast stiffness file".into()),
                    0.0,
                ),
            ],
            wall_s: 12.0,
        };
        let m = markdown(&s, None);
        assert!(
            m.contains("4 cells: **2 converged**, 1 refused, 0 failed, 1 skipped"),
            "{m}"
        );
        assert!(m.contains("3.2e-16 (seed001_9x40, load 5000 N·m)"), "{m}");
        assert!(m.contains("| seed001_9x40 | 6 × 10 | 41 | 100 N·m | wheel tip (pair 1) | 2.50° | 0.012 mm | 5000 N·m |"), "{m}");
        assert!(
            m.contains(
                "- seed001_9x40 · pinion speed 10 rpm: refused: pinion_torque_nm = 0 is below 1e-3"
            ),
            "{m}"
        );
        assert!(m.contains("coast: skipped: no coast stiffness file"), "{m}");
        // An absent summary: one line under the heading.
        let absent = text(&StressSection::default());
        assert_eq!(absent.trim().lines().count(), 3, "{absent}");
        assert!(absent.contains("summary.json` is absent"));
    }

    #[test]
    fn stress_section_reads_the_summary_and_copies_the_chart() {
        let dir = tempfile::tempdir().unwrap();
        let (out, reports) = (dir.path().join("out"), dir.path().join("reports"));
        assert!(section(&out, "x", &reports).markdown.is_none());
        let sdir = out.join("x").join("stress");
        std::fs::create_dir_all(&reports).unwrap();
        // Written as the study writes it: one committed set.
        let set = formats::result_set::ResultSet::begin(&sdir, "validate stress x").unwrap();
        let s = StressSummary {
            scene: "x".into(),
            designs: Vec::new(),
            cells: vec![cell("x", Study::Slices, "5", Outcome::Converged, 1e-17)],
            wall_s: 1.0,
        };
        std::fs::write(
            set.path().join("summary.json"),
            serde_json::to_string(&s).unwrap(),
        )
        .unwrap();
        std::fs::write(set.path().join("outcomes.svg"), "<svg/>").unwrap();
        set.commit().unwrap();
        let sec = section(&out, "x", &reports);
        let m = sec.markdown.unwrap();
        assert!(
            m.contains("1 cells: **1 converged**") && m.contains(FIGURE_FILE),
            "{m}"
        );
        assert!(reports.join(FIGURE_FILE).exists());
    }
}
