//! The comparison's markdown: the loaded-TE table (Tables 3–4 our way), the
//! run times (Table 5), the mesh-convergence and trade-off tables.

use super::Row;
use std::fmt::Write as _;

fn opt(v: Option<f64>, digits: usize) -> String {
    v.map_or("–".into(), |x| format!("{x:.digits$}"))
}

pub(super) fn markdown(
    rows: &[Row],
    rf: &[crate::reference::reference_stage::BlankSummary],
    conv: Option<&crate::studies::convergence::Convergence>,
) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "## Loaded TE: reduced model against the reference FE contact (Tables 3 and 4)\n"
    );
    let _ = writeln!(
        s,
        "Reduced model: the multibody run with the wheel at 10 rpm and the torque on the pinion (FE-analytical contact element from the stiffness files). Reference: both gear bodies as full tet10 FE bodies in two-pass node-to-surface penalty contact on their own quadratic flank faces, solved statically at every position (`validate reference`). Differences are (reduced − reference) / reference. Published: the white paper's multibody and NLFEA values.\n"
    );
    for r in rf {
        let _ = writeln!(
            s,
            "Reference {} / {}: {} mesh level, {} positions every {:.2}° over {} mesh cycles, {} + {} dofs, penalty factor {} (check: {}).\n",
            r.pinion_blank, r.wheel_blank, r.level, r.positions, r.step_deg, r.mesh_cycles, r.dofs[0], r.dofs[1], r.penalty_factor, r.penalty_factor_check
        );
        let u = &r.unloaded;
        let _ = writeln!(
            s,
            "Unloaded check ({} N·m): reference TE mean {:.2} µrad, ptp {:.2} µrad; UTCA of the generated flanks at the same positions: mean {:.2} µrad, ptp {:.2} µrad; largest difference {:.2} µrad (mean {:+.2} µrad). The difference measures how faithfully the meshed flank faces follow the generated flanks.\n",
            u.torque_nm, u.reference_te_mean_urad, u.reference_te_ptp_urad, u.utca_te_mean_urad, u.utca_te_ptp_urad, u.max_abs_difference_urad, u.mean_difference_urad
        );
    }
    let _ = writeln!(s, "Reduced-model values are the full 10 rpm run, with the same run sampled at the reference's positions in brackets; the differences use the sampled values (a sparse reference misses peaks that the full run has).\n");
    let _ = writeln!(s, "The reference level of each row is named in its second column; where it is finer than the reduced level, the last column gives the same reduced model against the reference solved on the reduced model's own meshes (mean / ptp TE and their differences): how much the yardstick's own discretization moves the verdict.\n");
    if let Some(c) = conv {
        let _ = writeln!(s, "The last column is the mesh-convergence study's single position (pinion rotation {:.1}°, standard blanks): the Richardson-extrapolated TE∞ of the reference there, and the reduced model's quasi-static TE at that position against it (the section on mesh convergence below has every level).\n", c.pinion_rotation_deg);
    }
    let _ = writeln!(s, "| wheel blank | reference level | load, N·m | mean TE reduced, µrad | mean TE reference, µrad | diff % | ptp TE reduced, µrad | ptp TE reference, µrad | diff % | penalty check % | published mean MB / NLFEA | published ptp MB / NLFEA | reduced-level reference: mean / ptp, µrad (diff %) | at the convergence position: TE∞, µrad (reduced model vs TE∞ %) |");
    let _ = writeln!(
        s,
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for r in rows {
        let coarse = match (
            r.reduced_level_reference_te_mean_urad,
            r.reduced_level_reference_te_ptp_urad,
            r.reduced_level_te_mean_difference_pct,
            r.reduced_level_te_ptp_difference_pct,
        ) {
            (Some(m), Some(p), Some(dm), Some(dp)) => {
                format!("{m:.2} / {p:.2} ({dm:+.2} / {dp:+.1})")
            }
            _ => "–".into(),
        };
        let at_position = conv
            .filter(|_| r.pinion_blank == "standard" && r.wheel_blank == "standard")
            .and_then(|c| {
                c.torques
                    .iter()
                    .find(|t| (t.torque_nm - r.torque_nm).abs() < 1e-9)
            })
            .and_then(|t| {
                Some(format!(
                    "{:.2} ({})",
                    t.extrapolated_te_urad?,
                    t.reduced_model_error_pct
                        .map_or("–".into(), |e| format!("{e:+.2}"))
                ))
            })
            .unwrap_or_else(|| "–".into());
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.2} ({}) | {:.2} | {:+.2} | {:.2} ({}) | {:.2} | {:+.1} | {:.3} | {} / {} | {} / {} | {} | {} |",
            r.wheel_blank,
            r.reference_level,
            r.torque_nm,
            r.multibody_te_mean_urad,
            opt(r.multibody_at_reference_mean_urad, 2),
            r.reference_te_mean_urad,
            r.te_mean_difference_pct,
            r.multibody_te_ptp_urad,
            opt(r.multibody_at_reference_ptp_urad, 2),
            r.reference_te_ptp_urad,
            r.te_ptp_difference_pct,
            r.reference_penalty_difference_pct,
            opt(r.published_multibody_te_mean_urad, 1),
            opt(r.published_nlfea_te_mean_urad, 1),
            opt(r.published_multibody_te_ptp_urad, 1),
            opt(r.published_nlfea_te_ptp_urad, 1),
            coarse,
            at_position,
        );
    }
    let _ = writeln!(s, "\n## Run time (Table 5)\n");
    let _ = writeln!(s, "Measured on this machine (2 cores). Reduced model: the multibody 10 rpm run (integration steps, CPU per step, the run's CPU), the contact-element table it integrates on (CPU; built once per blank pair and shared by its loads) and their sum. Reference: positions, CPU per position (unit-load columns, condensation and both penalties for all loads), and the total: the positions' times plus factoring both bodies. The white paper's totals (Table 5, printed in minutes and days) are given in seconds.\n");
    let _ = writeln!(s, "| wheel blank | load, N·m | MB steps | MB s/step | MB run, s | MB table, s | MB run + table, s | reference level | reference positions | reference s/position | reference total, s | published MB s/step | published MB total, s | published NLFEA s/step | published NLFEA total, s |");
    let _ = writeln!(
        s,
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.2e} | {:.2} | {:.2} | {:.2} | {} | {} | {:.2} | {:.0} | {} | {} | {} | {} |",
            r.wheel_blank,
            r.torque_nm,
            r.multibody_steps,
            r.multibody_cpu_s_per_step,
            r.multibody_cpu_s,
            r.multibody_table_cpu_s,
            r.multibody_cpu_s + r.multibody_table_cpu_s,
            r.reference_level,
            r.reference_positions,
            r.reference_cpu_s_per_position,
            r.reference_cpu_s,
            opt(r.published_multibody_cpu_s_per_step, 1),
            opt(r.published_multibody_cpu_total_s, 0),
            opt(r.published_nlfea_cpu_s_per_step, 0),
            opt(r.published_nlfea_cpu_total_s, 0),
        );
    }
    s
}

pub(super) fn convergence_markdown(s: &mut String, c: &crate::studies::convergence::Convergence) {
    let _ = writeln!(s, "\n## Mesh convergence of the reference\n");
    let _ = writeln!(
        s,
        "The reference LTCA at pinion rotation {:.1}° of the sweep, standard blanks, on three mesh levels (`validate convergence`; one set of unit-load columns per level serves every torque). h = 1/√(profile × face elements). The unloaded column is the meshed geometry's fidelity at that position: TE at 1e-3 N·m minus the UTCA of the generated flanks (target 0.1 µrad).\n",
        c.pinion_rotation_deg,
    );
    let _ = writeln!(s, "| level | elements profile × face | h | dofs pinion + wheel | constraints | unloaded TE − UTCA, µrad | factor s | position s |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for l in &c.levels {
        let _ = writeln!(
            s,
            "| {} | {} × {} | {:.4} | {} + {} | {} | {:+.4} | {:.0} + {:.0} | {:.0} |",
            l.level,
            l.profile_elements,
            l.face_elements,
            l.h,
            l.dofs[0],
            l.dofs[1],
            l.constraints,
            l.unloaded_te_urad - l.utca_te_urad,
            l.factor_s[0],
            l.factor_s[1],
            l.position_s
        );
    }
    let _ = writeln!(
        s,
        "\nPer torque: TE on each level and its difference to the Richardson extrapolation TE∞ (observed order p; no extrapolation where the levels do not converge monotonically or p < {:.1}, i.e. not yet in the asymptotic range); the penalty check of the finest level; the reduced model's quasi-static LTCA at the same position against TE∞ and against the finest level. The sweeps of the comparison above use the reduced level's meshes, so its column is the reference's own discretization error there.\n",
        crate::studies::convergence::MIN_ORDER
    );
    let names: Vec<&str> = c.levels.iter().map(|l| l.level.as_str()).collect();
    let _ = writeln!(
        s,
        "| load, N·m | {} | p | TE∞, µrad | penalty check % | reduced model, µrad (vs TE∞ %) | reduced model vs {} % |",
        names
            .iter()
            .map(|n| format!("{n}, µrad (vs TE∞ %)"))
            .collect::<Vec<_>>()
            .join(" | "),
        names.last().unwrap_or(&"finest level")
    );
    let _ = writeln!(s, "|---|{}---|---|---|---|---|", "---|".repeat(names.len()));
    for (i, t) in c.torques.iter().enumerate() {
        let pct = |e: Option<f64>| e.map_or("–".into(), |e| format!("{e:+.2}"));
        let levels: Vec<String> = c
            .levels
            .iter()
            .zip(&t.error_to_extrapolation_pct)
            .map(|(l, &e)| format!("{:.2} ({})", l.te_urad[i], pct(e)))
            .collect();
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {:.2} ({}) | {:+.2} |",
            t.torque_nm,
            levels.join(" | "),
            opt(t.observed_order, 2),
            opt(t.extrapolated_te_urad, 2),
            c.levels.last().map_or("–".into(), |l| format!(
                "{:.3}",
                l.penalty_difference_pct[i]
            )),
            t.reduced_model_te_urad,
            pct(t.reduced_model_error_pct),
            t.reduced_model_vs_finest_pct
        );
    }
}

pub(super) fn tradeoff_markdown(s: &mut String, pts: &[crate::studies::tradeoff::Point]) {
    let _ = writeln!(
        s,
        "\n## Reduced model: run time against error (slices per tooth pair)\n"
    );
    let _ = writeln!(s, "Quasi-static LTCA at the reference's positions (`validate tradeoff`), against the reference. The stiffness grid is the scene's; its density is not varied here.\n");
    let _ = writeln!(s, "| wheel blank | slices | load, N·m | mean TE, µrad | diff % | ptp TE, µrad | diff % | ms/position |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for p in pts {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.2} | {:+.2} | {:.2} | {:+.1} | {:.2} |",
            p.wheel_blank,
            p.slices,
            p.torque_nm,
            p.te_mean_urad,
            p.mean_error_pct,
            p.te_ptp_urad,
            p.ptp_error_pct,
            p.s_per_position * 1e3
        );
    }
}
