//! The report's section "Lumped 8-DOF model (seeds 004/003)": `solver
//! lumped` on `reference/scenes/seed004_lumped.toml` against seed 004's
//! published numbers, then seed 003's part ([`super::lumped_seed003`]).
//!
//! Reads `<out>/seed004_lumped/lumped/summary.json` (one
//! [`LumpedSummary`] per blank pair) when present, and copies each pair's
//! charts (`mesh_force.svg`, `accelerations.svg`, `bearing_spectrum.svg`)
//! into the report directory as `lumped_<pinion>_<wheel>_<chart>.svg`. An
//! absent summary is one line of text, never a table of zeros.
//!
//! Every number of ours is formatted from the summary; seed 004's are read
//! from `reference/published/seed004_lumped.toml` ([`seed004`]).

use crate::report::figures::{copied, Figure};
use crate::report::published::seed004;
use formats::lumped_summary::{Directions, LumpedSummary};
use std::fmt::Write as _;
use std::path::Path;

/// The scene whose run the section reports.
pub const LUMPED_SCENE: &str = "seed004_lumped";

/// The charts of one blank pair, in the order shown: (title, file).
const CHARTS: [(&str, &str); 3] = [
    ("Dynamic mesh force", "mesh_force.svg"),
    ("Body accelerations", "accelerations.svg"),
    ("Bearing-force spectrum", "bearing_spectrum.svg"),
];

/// The section's markdown and the figures it shows (already written into
/// the report directory).
#[derive(Debug, Clone, Default)]
pub struct LumpedSection {
    pub markdown: String,
    pub figures: Vec<Figure>,
}

fn ours(d: &Directions) -> [f64; 7] {
    [
        d.pinion_x,
        d.pinion_y,
        d.pinion_z,
        d.wheel_x,
        d.wheel_y,
        d.wheel_z,
        d.mesh_normal,
    ]
}

/// The section from the stages' output root `out` (None: no root given),
/// its charts copied into `reports`: seed 004's runs, then seed 003's
/// ([`super::lumped_seed003`]), the mesh stiffness of seeds 003 and 004
/// against the FE reference ([`super::lumped_fe_stiffness`]), then the white-paper pair's order map
/// ([`super::lumped_order_map`]).
pub fn section(out: Option<&Path>, reports: &Path) -> LumpedSection {
    let mut sec = seed004_section(out, reports);
    if let Some(out) = out {
        sec.markdown.push_str(&super::lumped_seed003::markdown(out));
        sec.markdown
            .push_str(&super::lumped_fe_stiffness::markdown(out));
        let (md, figs) = super::lumped_order_map::subsection(out, reports);
        sec.markdown.push_str(&md);
        sec.figures.extend(figs);
    }
    sec
}

/// Seed 004's part.
fn seed004_section(out: Option<&Path>, reports: &Path) -> LumpedSection {
    let mut s = String::from("## Lumped 8-DOF model (seeds 004/003)\n\n");
    let Some(out) = out else {
        s.push_str("No lumped run: the report was built without an output root.\n\n");
        return LumpedSection {
            markdown: s,
            figures: vec![],
        };
    };
    let dir = out.join(LUMPED_SCENE).join("lumped");
    let path = dir.join("summary.json");
    let summaries: Vec<LumpedSummary> = match std::fs::read_to_string(&path)
        .map_err(|e| e.to_string())
        .and_then(|t| serde_json::from_str(&t).map_err(|e| e.to_string()))
    {
        Ok(v) => v,
        Err(e) => {
            let _ = writeln!(
                s,
                "No lumped run: `{}` cannot be read ({e}); `solver lumped reference/scenes/seed004_lumped.toml` writes it.\n",
                path.display()
            );
            return LumpedSection {
                markdown: s,
                figures: vec![],
            };
        }
    };
    if summaries.is_empty() {
        let _ = writeln!(
            s,
            "No lumped run: `{}` lists no blank pair.\n",
            path.display()
        );
        return LumpedSection {
            markdown: s,
            figures: vec![],
        };
    }
    let mut figures = Vec::new();
    let _ = writeln!(
        s,
        "Seed 004's 23/86 pair on our own LTCA: the mesh stiffness k(t) (tangent, dF/dδ) and the loaded transmission error of the scene `{LUMPED_SCENE}` as Fourier series drive the 8-DOF model (X, Y, Z and rotation of each member on its bearings), integrated with Dormand–Prince 5(4). Seed 004's published values stand beside ours; sources under the tables.\n"
    );
    // The scene's base runs (the design's own flanks at its first torque);
    // the ease-off variants go to the studies below.
    let base: Vec<&LumpedSummary> = summaries.iter().filter(|r| r.variant.is_empty()).collect();
    for r in &base {
        let blank = format!("{:?}_{:?}", r.pinion_blank, r.wheel_blank).to_lowercase();
        pair_markdown(&mut s, r);
        let mut figs = Vec::new();
        for (title, file) in CHARTS {
            figs.extend(copied(
                &format!(
                    "{title}, {:?} pinion / {:?} wheel",
                    r.pinion_blank, r.wheel_blank
                ),
                &dir.join(&blank).join(file),
                reports,
                &format!("lumped_{blank}_{file}"),
            ));
        }
        crate::report::figures::figure_lines(&mut s, &figs, false);
        figures.extend(figs);
    }
    differences_markdown(&mut s, base.first().copied().unwrap_or(&summaries[0]));
    super::lumped_studies::markdown(&mut s, &summaries);
    LumpedSection {
        markdown: s,
        figures,
    }
}

fn pair_markdown(s: &mut String, r: &LumpedSummary) {
    let seed = seed004();
    let (seed_impact_n, seed_harmonics) = (seed.impact_force_n, seed.stiffness_harmonics);
    let (seed_k_source, seed_impact_source) =
        (&seed.mean_mesh_stiffness_source, &seed.impact_force_source);
    let _ = writeln!(
        s,
        "### {:?} pinion / {:?} wheel: {:.0} rpm, {:.2} N·m on the pinion, mesh frequency {:.1} Hz, {:.0} mesh cycles with the first {:.0} dropped\n",
        r.pinion_blank,
        r.wheel_blank,
        r.pinion_speed_rpm,
        r.pinion_torque_nm,
        r.mesh_frequency_hz,
        r.mesh_cycles,
        r.dropped_mesh_cycles
    );
    let _ = writeln!(
        s,
        "| direction | RMS acceleration, ours (m/s²) | share of the mesh normal λ̈, ours (%) | share of v·q̈, ours (%) | seed 004 (m/s²) | seed 004 share (%) |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    let rms = ours(&r.rms_acceleration_m_s2);
    let share = ours(&r.rms_acceleration_share_percent);
    let relative = r.relative_normal_acceleration_rms_m_s2;
    for (k, d) in seed004().table3.iter().enumerate() {
        let (label, pub_rms, pub_share) = (&d.direction, d.rms_acceleration_m_s2, d.share_percent);
        let of_relative = if k < 6 {
            format!("{:.2}", rms[k] / relative * 100.0)
        } else {
            "—".to_string()
        };
        let _ = writeln!(
            s,
            "| {label} | {:.2} | {:.2} | {of_relative} | {pub_rms:.2} | {pub_share:.2} |",
            rms[k], share[k]
        );
    }
    let _ = writeln!(
        s,
        "\nSource: {}. Our mesh-normal row is λ̈ = v·q̈ − ë, which holds the static transmission error's own curvature ë(t); the bodies' relative acceleration along the normal without it, v·q̈, is {relative:.2} m/s², and the next column gives the shares over it. Seed 004 does not say which of the two its mesh-normal row is.\n",
        seed004().table3_source,
    );
    let k = &r.mesh_stiffness_n_per_m;
    let static_force = r.pinion_torque_nm / r.levers_m[0];
    let _ = writeln!(s, "| quantity | ours | seed 004 |");
    let _ = writeln!(s, "|---|---|---|");
    let _ = writeln!(
        s,
        "| mean mesh stiffness, tangent (N/m) | {:.3e} (secant {:.3e}) | {:.2e} |",
        k.mean,
        r.secant_mesh_stiffness_mean_n_per_m,
        seed004().mean_mesh_stiffness_n_per_m
    );
    let _ = writeln!(
        s,
        "| meshing-impact force (N) | {:.0} ({}) | {seed_impact_n:.0} |",
        r.impact_force_n, r.impact.model
    );
    let _ = writeln!(
        s,
        "| impact velocity (m/s), entering pair's stiffness (N/m) | {:.4}, {:.3e} | not published |",
        r.impact.velocity_m_s, r.impact.entering_pair_stiffness_n_per_m
    );
    let _ = writeln!(
        s,
        "| stiffness harmonics | {} | up to order {seed_harmonics} |",
        k.harmonics.len()
    );
    for (name, f) in [
        ("stiffness k(t)", k),
        ("transmission error e(t)", &r.transmission_error_m),
        ("loaded deflection δ(t)", &r.loaded_deflection_m),
    ] {
        let _ = writeln!(
            s,
            "| {name}: harmonics, largest residual / bound (% of peak-to-peak) | {}, {:.1} / {:.1}{} | not published |",
            f.harmonics.len(),
            f.max_residual_of_ptp * 100.0,
            f.tolerance_of_ptp * 100.0,
            if f.met { "" } else { " (bound not met)" }
        );
    }
    let _ = writeln!(
        s,
        "| dynamic mesh force min / mean / max (N); static T₁/r₁ (N) | {:.0} / {:.0} / {:.0}; {static_force:.0} | not published |",
        r.mesh_force_min_n, r.mesh_force_mean_n, r.mesh_force_max_n
    );
    let _ = writeln!(
        s,
        "| dynamic factor max Fₙ / (T₁/r₁) | {:.3} | not published |",
        r.dynamic_factor
    );
    let _ = writeln!(
        s,
        "\nSeed 004: k_m from {seed_k_source}; impact force from {seed_impact_source}.\n"
    );
}

/// The bearing stiffnesses as the run used them: one value when all six
/// are equal, else per member and direction.
fn bearings_text(k: &[[f64; 3]; 2]) -> String {
    let all: Vec<f64> = k.iter().flatten().copied().collect();
    if all.iter().all(|&v| v == all[0]) {
        format!("{:.3e} N/m in every direction", all[0])
    } else {
        format!(
            "pinion {:.3e} / {:.3e} / {:.3e} N/m and wheel {:.3e} / {:.3e} / {:.3e} N/m (X / Y / Z)",
            k[0][0], k[0][1], k[0][2], k[1][0], k[1][1], k[1][2]
        )
    }
}

fn differences_markdown(s: &mut String, r: &LumpedSummary) {
    let (seed_k, seed_impact_n) = (
        seed004().mean_mesh_stiffness_n_per_m,
        seed004().impact_force_n,
    );
    let static_force = r.pinion_torque_nm / r.levers_m[0];
    let k_ratio = seed_k / r.mesh_stiffness_n_per_m.mean;
    let _ = writeln!(
        s,
        "### Why ours differs from seed 004\n\n\
- **Meshes.** The scene runs the coarse 6 × 10 flank-element meshes of `reference/scenes/seed004_lumped.toml`; the stiffness, loaded TE and impact velocity come from that reduced model, not a converged one.\n\
- **Bearings.** Seed 004 publishes no bearing stiffness; the scene assumes {} with {:.0} % damping. The body accelerations depend on that choice: with it the linear model's natural frequencies are {} Hz against the mesh frequency {:.1} Hz.\n\
- **Our design file.** Seed 004 gives no flank modification; `reference/seed004_23x86.toml` carries an assumed ease-off (profile and lengthwise crowning, a parabolic motion error). The localized contact it gives lowers the tangent stiffness at this load and shapes the loaded TE that drives the model.\n\
- **Mean stiffness.** Seed 004's {seed_k:.1e} N/m is {k_ratio:.1} times our tangent mean; it is a \"typical value\" from its Table 1, beside a mesh frequency of 2π × 1000 rad/s (its case study runs at about 2260 Hz) and an impact velocity of 0.5 m/s (its case study publishes no impact velocity to set it against).\n\
- **Impact.** Seed 004's {seed_impact_n:.0} N is {:.1} times the static mesh force T₁/r₁ = {static_force:.0} N of this load; ours is seed 004's F_s formula with the impact velocity ({:.4} m/s) and entering pair's stiffness of our LTCA, {:.0} N.\n",
        bearings_text(&r.bearing_stiffness_n_per_m),
        100.0 * r.bearing_damping_ratio,
        r.natural_frequencies_hz
            .iter()
            .map(|f| format!("{f:.0}"))
            .collect::<Vec<_>>()
            .join(", "),
        r.mesh_frequency_hz,
        seed_impact_n / static_force,
        r.impact.velocity_m_s,
        r.impact_force_n
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed004_table3_shares_are_its_rms_over_the_mesh_normal() {
        let t = &seed004().table3;
        assert_eq!(t.len(), 7, "six body directions and the mesh normal");
        let normal = t[6].rms_acceleration_m_s2;
        for d in t {
            let share = d.rms_acceleration_m_s2 / normal * 100.0;
            assert!((share - d.share_percent).abs() < 0.01, "{}", d.direction);
        }
    }
}
