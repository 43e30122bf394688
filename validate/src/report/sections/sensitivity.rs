//! The report's section "Misalignment sensitivity": `solver sensitivity`
//! on the report's scene (each of E, P, G, ΔΣ swept alone over the scene's
//! `[sensitivity]` range at its loads).
//!
//! Reads `<out>/<scene>/sensitivity/summary.json`
//! ([`SensitivitySummary`]) when present and copies its charts into the
//! report directory as `sensitivity_<chart>.svg`. An absent summary is one
//! line of text, never a table of zeros. Every number is formatted from the
//! summary.

use crate::report::figures::{copied, Figure};
use formats::sensitivity_summary::{SensitivityCurve, SensitivitySummary};
use std::fmt::Write as _;
use std::path::Path;

/// The chart files of `solver sensitivity` and their titles, in the order shown.
const CHARTS: [(&str, &str); 6] = [
    ("TE peak-to-peak against misalignment", "te_ptp.svg"),
    ("Mean TE against misalignment", "te_mean.svg"),
    (
        "Pattern centre along the face against misalignment",
        "pattern_centre_l.svg",
    ),
    (
        "Pattern centre in height against misalignment",
        "pattern_centre_d.svg",
    ),
    ("Pattern length against misalignment", "pattern_length.svg"),
    ("Largest pressure against misalignment", "max_pressure.svg"),
];

/// The root-stress charts, written by `solver sensitivity` when the
/// stiffness files hold root-stress coefficients.
const ROOT_STRESS_CHARTS: [(&str, &str); 2] = [
    (
        "Largest pinion root tension against misalignment",
        "pinion_root_stress.svg",
    ),
    (
        "Largest wheel root tension against misalignment",
        "wheel_root_stress.svg",
    ),
];

/// The section's markdown and the figures it shows (already written into
/// the report directory).
#[derive(Debug, Clone, Default)]
pub struct SensitivitySection {
    pub markdown: String,
    pub figures: Vec<Figure>,
}

fn absent(mut s: String, why: &str) -> SensitivitySection {
    let _ = writeln!(s, "No sensitivity study: {why}.\n");
    SensitivitySection {
        markdown: s,
        figures: vec![],
    }
}

/// The section for scene `scene` from the stages' output root `out`, its
/// charts copied into `reports`.
pub fn section(out: Option<&Path>, scene: Option<&str>, reports: &Path) -> SensitivitySection {
    let s = String::from("## Misalignment sensitivity\n\n");
    let (Some(out), Some(scene)) = (out, scene) else {
        return absent(s, "the report was built without an output root and scene");
    };
    let dir = out.join(scene).join("sensitivity");
    let path = dir.join("summary.json");
    let r: SensitivitySummary = match std::fs::read_to_string(&path)
        .map_err(|e| e.to_string())
        .and_then(|t| serde_json::from_str(&t).map_err(|e| e.to_string()))
    {
        Ok(r) => r,
        Err(e) => {
            return absent(
                s,
                &format!(
                    "`{}` cannot be read ({e}); `solver sensitivity <scene>` writes it (`make validate SENSITIVITY=1`)",
                    path.display()
                ),
            )
        }
    };
    let mut s = s;
    markdown(&mut s, &r);
    let with_root_stress = r.has_root_stress();
    let figures: Vec<Figure> = CHARTS
        .iter()
        .chain(ROOT_STRESS_CHARTS.iter().filter(|_| with_root_stress))
        .filter_map(|(title, file)| {
            copied(
                title,
                &dir.join(file),
                reports,
                &format!("sensitivity_{file}"),
            )
        })
        .collect();
    crate::report::figures::figure_lines(&mut s, &figures, false);
    SensitivitySection {
        markdown: s,
        figures,
    }
}

/// The text and one table per misalignment at the largest torque.
fn markdown(s: &mut String, r: &SensitivitySummary) {
    let b = &r.base;
    let _ = writeln!(
        s,
        "Each misalignment swept alone around the scene's own (E {} mm, P {} mm, G {} mm, ΔΣ {}°), {:?} pinion / {:?} wheel, {} positions of {}°, loaded TCA of the reduced model at {} N·m; the stiffness files are read once (they are body-fixed). Conventions (docs/misalignment.md): P and G positive away from the apex, ΔΣ positive opens the shaft angle, E positive in the direction of a conventional hypoid offset for the pinion's hand. The pattern is every slice that carries load over the sweep, on the pinion flank: L the cone distance, d the height above the pitch cone. Study wall time {:.1} s.\n",
        b.offset_mm,
        b.pinion_axial_mm,
        b.wheel_axial_mm,
        b.shaft_angle_deg,
        r.pinion_blank,
        r.wheel_blank,
        r.positions,
        r.step_deg,
        r.torques_nm
            .iter()
            .map(|t| t.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        r.wall_s
    );
    let root = r.has_root_stress();
    let _ = writeln!(
        s,
        "{}\n",
        if root {
            "σ_F: the largest first principal stress over the sweep on the loaded side's fillets of pinion and wheel (the reduced model's stress influence coefficients combined with the slice forces), ξ where it sits along the face (0 toe, 1 heel)."
        } else {
            "No root stress: the stiffness files hold no root-stress coefficients (`[stiffness] root_stress = false`)."
        }
    );
    let Some(&torque) = r.torques_nm.last() else {
        return;
    };
    for c in &r.curves {
        curve_table(s, c, torque, root);
    }
}

fn curve_table(s: &mut String, c: &SensitivityCurve, torque: f64, root: bool) {
    let _ = writeln!(
        s,
        "### {} ({}), ±{} {}, at {torque} N·m\n",
        c.symbol,
        c.component.field(),
        c.range,
        c.unit
    );
    let _ = writeln!(
        s,
        "| {} ({}) | TE ptp (µrad) | mean TE (µrad) | centre L (mm) | centre d (mm) | length (mm) | height (mm) | p_max (MPa) |{}",
        c.symbol,
        c.unit,
        if root {
            " σ_F pinion (MPa) | ξ pinion | σ_F wheel (MPa) | ξ wheel |"
        } else {
            ""
        }
    );
    s.push_str("|---:|---:|---:|---:|---:|---:|---:|---:|");
    s.push_str(if root { "---:|---:|---:|---:|\n" } else { "\n" });
    for p in &c.points {
        let Some(l) = p.loads.iter().find(|l| l.torque_nm == torque) else {
            continue;
        };
        let root_cells = match (&l.root_stress, root) {
            (Some(r), true) => format!(
                " {:.1} | {:.2} | {:.1} | {:.2} |",
                r.pinion.tension_mpa,
                r.pinion.tension_at.xi,
                r.wheel.tension_mpa,
                r.wheel.tension_at.xi
            ),
            _ => String::new(),
        };
        let _ = writeln!(
            s,
            "| {:+.4} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.0} |{root_cells}",
            p.value,
            l.te_ptp_urad,
            l.te_mean_urad,
            l.pattern_centre_l_mm,
            l.pattern_centre_d_mm,
            l.pattern_length_mm,
            l.pattern_height_mm,
            l.max_pressure_mpa
        );
    }
    s.push('\n');
}
