//! Where the reduced model and the reference differ, from the studies that
//! isolate each part (meshed geometry, light load, one position against the
//! finest level, the line-load check of the stiffness files) and from the
//! reference's contact pattern (edge contact): sentences for the report,
//! generated from the stages' files.

use std::fmt::Write as _;
use std::path::Path;

/// Where the reduced model and the reference differ, part by part, from the
/// studies that isolate each part (written when the reference is finer
/// than the reduced level).
pub fn breakdown(
    s: &mut String,
    rows: &[crate::report::comparison_row::Row],
    rf: &[crate::reference::reference_stage::BlankSummary],
    conv: Option<&crate::studies::convergence::Convergence>,
    line_load: Option<&crate::studies::line_load::LineLoad>,
) {
    if rf.iter().all(|r| r.level == "reduced") {
        return;
    }
    let _ = writeln!(
        s,
        "### Where the differences come from
"
    );
    let _ = writeln!(s, "Each part of the reduced model measured on its own against the fine FE (no parameter fitted):
");
    for r in rf.iter().filter(|r| r.level != "reduced") {
        let _ = writeln!(
            s,
            "- Meshed flank geometry ({} / {}): the fine reference at {} N·m against the UTCA of the generated flanks differs by {:.3} µrad at most: the fine meshes carry the generated flanks, so the differences below are mechanical.",
            r.pinion_blank, r.wheel_blank, r.unloaded.torque_nm, r.unloaded.max_abs_difference_urad
        );
    }
    let lightest = rows
        .iter()
        .map(|r| r.torque_nm)
        .fold(f64::INFINITY, f64::min);
    for r in rows
        .iter()
        .filter(|r| r.torque_nm == lightest && r.reference_level != "reduced")
    {
        let Some(u) = rf
            .iter()
            .find(|q| q.pinion_blank == r.pinion_blank && q.wheel_blank == r.wheel_blank)
            .map(|q| q.unloaded.utca_te_mean_urad)
        else {
            continue;
        };
        let _ = writeln!(
            s,
            "- Light load ({} wheel, {} N·m): the reduced model's mean TE lies {:+.2} µrad ({:+.2} %) from the fine reference's. Above the UTCA's mean ({:.2} µrad), the elastic part of the mean TE is {:.2} µrad in the reduced model and {:.2} µrad in the fine reference.",
            r.wheel_blank,
            r.torque_nm,
            r.multibody_te_mean_urad - r.reference_te_mean_urad,
            r.te_mean_difference_pct,
            u,
            r.multibody_te_mean_urad - u,
            r.reference_te_mean_urad - u
        );
    }
    if let Some(c) = conv {
        let pcts: Vec<String> = c
            .torques
            .iter()
            .map(|t| {
                format!(
                    "{:+.2} % at {} N·m",
                    t.reduced_model_vs_finest_pct, t.torque_nm
                )
            })
            .collect();
        let _ = writeln!(
            s,
            "- One position, quasi-static LTCA against the finest reference level (standard blanks, pinion rotation {:.1}°): {}. Where the sweep means above differ by about as much, the difference is in the compliance level, not in the positions the multibody run or the sweep sample.",
            c.pinion_rotation_deg,
            pcts.join(", ")
        );
    }
    if let Some(l) = line_load {
        if let Some(level) = l.levels.last() {
            let cases: Vec<String> = level
                .cases
                .iter()
                .map(|c| {
                    format!(
                        "{:.2} % at most ({:.2} % mean) for b = {} mm",
                        c.max_abs_difference_pct, c.mean_abs_difference_pct, c.half_width_mm
                    )
                })
                .collect();
            let _ = writeln!(
                s,
                "- Stiffness file's global field + Weber–Banaschek against the {} FE under a Hertzian line load on one pinion tooth ({} stiffness file): {}.",
                level.level,
                l.stiffness_file,
                cases.join(", ")
            );
        }
    }
    let _ = writeln!(s);
}

/// Within this of the flank's unit outline (ξ, η ∈ [0, 1]) a pressure peak
/// is edge contact.
const EDGE_BAND: f64 = 0.03;

/// Where the finest reference's pressure envelope (at the largest torque)
/// peaks on the pinion flank, and whether that is on the flank's edge: one
/// sentence, None without a pattern file.
pub fn pattern_peak(out: &Path, scene: &str, blank: &str) -> Option<String> {
    use crate::report::figures::{column, read_csv};
    let dir = crate::reference::reference_stage::finest_reference(out, scene, blank)?;
    let file = std::fs::read_dir(&dir)
        .ok()?
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .find(|p| {
            p.extension().is_some_and(|x| x == "csv")
                && p.file_name()
                    .is_some_and(|n| n.to_string_lossy().starts_with("pattern_"))
        })?;
    let csv = read_csv(&file)?;
    let (xi, eta, p) = (
        column(&csv, "xi")?,
        column(&csv, "eta")?,
        column(&csv, "pressure_mpa")?,
    );
    let k = (0..p.len()).max_by(|&a, &b| p[a].total_cmp(&p[b]))?;
    let edge = [
        (eta[k] > 1.0 - EDGE_BAND, "the tip"),
        (eta[k] < EDGE_BAND, "the flank's lower limit (root side)"),
        (xi[k] < EDGE_BAND, "the toe"),
        (xi[k] > 1.0 - EDGE_BAND, "the heel"),
    ]
    .into_iter()
    .find(|e| e.0)
    .map(|e| e.1);
    let name = file.file_stem()?.to_string_lossy().into_owned();
    Some(match edge {
        Some(at) => format!(
            "Contact pattern {} ({}): the reference's pressure peaks at {:.0} MPa on the flank's edge at {at} (ξ {:.3}, η {:.3}): edge contact, which the reduced model's slices on the smooth flank (Hertz per slice) do not resolve; its peak is not comparable there.",
            blank.replace('_', " / "), name, p[k], xi[k], eta[k]
        ),
        None => format!(
            "Contact pattern {} ({}): the reference's pressure peaks at {:.0} MPa inside the flank (ξ {:.3}, η {:.3}), away from its edges.",
            blank.replace('_', " / "), name, p[k], xi[k], eta[k]
        ),
    })
}
