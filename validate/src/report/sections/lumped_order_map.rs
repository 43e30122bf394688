//! The report's subsection "White-paper pair, lightweight wheel: bearing-force
//! order map": `solver lumped` on
//! `reference/scenes/white_paper_lightweight_lumped.toml` with
//! `[lumped.order_map]`, read from `<out>/<scene>/lumped/order_map.json`,
//! its order maps; then the whole-revolution subsection
//! ([`super::lightweight_revolution`]: the lobe checked against the solved
//! revolution, the multibody run-up's amplitudes beside the 8-DOF
//! model's, the run-up spectrograms of both wheel blanks). Every number is
//! formatted from the summaries; an absent summary is one line of text.

use crate::report::figures::{copied, Figure};
use formats::lumped_summary::OrderMapSummary;
use std::fmt::Write as _;
use std::path::Path;

/// The scene whose order map the subsection reports.
pub const ORDER_MAP_SCENE: &str = "white_paper_lightweight_lumped";

/// The subsection's markdown and its figures (copied into `reports`).
pub fn subsection(out: &Path, reports: &Path) -> (String, Vec<Figure>) {
    let mut s = String::from(
        "### White-paper pair, lightweight wheel: bearing-force order map (8-DOF model)\n\n",
    );
    let dir = out.join(ORDER_MAP_SCENE).join("lumped");
    let path = dir.join("order_map.json");
    let maps: Vec<OrderMapSummary> = match std::fs::read_to_string(&path)
        .map_err(|e| e.to_string())
        .and_then(|t| serde_json::from_str::<Vec<OrderMapSummary>>(&t).map_err(|e| e.to_string()))
    {
        Ok(v) if !v.is_empty() => v,
        Ok(_) => {
            let _ = writeln!(
                s,
                "No order map: `{}` lists no blank pair.\n",
                path.display()
            );
            return with_revolution(s, vec![], out, reports, &[]);
        }
        Err(e) => {
            let _ = writeln!(
                s,
                "No order map: `{}` cannot be read ({e}); `solver lumped reference/scenes/{ORDER_MAP_SCENE}.toml` writes it.\n",
                path.display()
            );
            return with_revolution(s, vec![], out, reports, &[]);
        }
    };
    let m0 = &maps[0];
    let _ = writeln!(
        s,
        "The {}/{} pair's wheel bearing force from the 8-DOF model, the excitation k(t), δ(t) a series over one wheel revolution ({} mesh cycles) instead of one mesh cycle: the lightweight wheel's web holes make the mesh stiffness change from tooth to tooth. A wheel's stiffness file holds the influence data of a few teeth only, so the LTCA sweeps the mesh cycles whose loaded teeth it holds and the per-revolution variation is fitted to that span as the lowest harmonic of the hole family (k = k̃(p)(1 + c₀ + a cos nψ + b sin nψ), n the holes, ψ the loaded wheel tooth's angle; `solver/src/lumped/revolution.rs`); the revolution's samples go in by a direct DFT. Spectra: the resultant of the wheel bearing force's X, Y, Z amplitudes over the kept wheel revolutions, in pinion orders.\n",
        m0.pinion_teeth, m0.wheel_teeth, m0.wheel_teeth
    );
    let _ = writeln!(
        s,
        "| Wheel | Teeth in the stiffness file | LTCA span, mesh cycles | Mean k per span cycle (MN/m) | Loaded wheel tooth per cycle | Lobe k peak-to-peak / mean k | Least k at wheel tooth | Span fit residual / ptp (k, δ) | Series harmonics (mesh, revolution) | Series residual / ptp (k, δ) | LTCA (s) |\n|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for m in &maps {
        let list = |v: &[f64], scale: f64, d: usize| {
            v.iter()
                .map(|x| format!("{:.*}", d, x * scale))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let solved = if m.wheel_solved_teeth.len() == 1 {
            "one (axisymmetric)".to_string()
        } else {
            m.wheel_solved_teeth
                .iter()
                .map(|t| t.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        };
        let _ = writeln!(
            s,
            "| {:?} | {} | {} | {} | {} | {:.3} | {} | {:.3}, {:.3} | {}, {} | {:.4}, {:.4} | {:.2} |",
            m.wheel_blank,
            solved,
            m.ltca_span_mesh_cycles,
            list(&m.cycle_mean_stiffness_n_per_m, 1e-6, 2),
            list(&m.cycle_wheel_tooth, 1.0, 2),
            m.stiffness_lobe_ptp_relative,
            m.stiffness_lobe_minimum_wheel_tooth
                .map_or("—".to_string(), |t| format!("{t:.2} (of {:.2} per lobe)", m.wheel_teeth as f64 / m.lobes.max(1) as f64)),
            m.span_fit_residual_of_ptp[0],
            m.span_fit_residual_of_ptp[1],
            m.mesh_harmonics,
            m.revolution_harmonics,
            m.revolution_series_residual_of_ptp[0],
            m.revolution_series_residual_of_ptp[1],
            m.ltca_wall_s
        );
    }
    s.push('\n');
    // Amplitudes at the marked orders, standard and lightweight side by side.
    let labels: Vec<String> = m0.speeds[0]
        .marked
        .iter()
        .map(|x| x.label.clone())
        .collect();
    let _ = write!(s, "| Pinion speed (rpm) | Wheel |");
    for l in &labels {
        let _ = write!(s, " {l} (N) |");
    }
    let _ = writeln!(s, " Integration (s) | Run (s) |");
    let _ = writeln!(s, "|---|---|{}---|---|", "---|".repeat(labels.len()));
    for (i, sp) in m0.speeds.iter().enumerate() {
        for m in &maps {
            let Some(r) = m.speeds.get(i) else { continue };
            let _ = write!(s, "| {:.0} | {:?} |", sp.pinion_speed_rpm, m.wheel_blank);
            for x in &r.marked {
                let _ = write!(s, " {:.3e} |", x.wheel_bearing_force_n);
            }
            let _ = writeln!(s, " {:.2} | {:.2} |", r.integration_wall_s, r.run_wall_s);
        }
    }
    let runs: usize = maps.iter().map(|m| m.speeds.len()).sum();
    let total: f64 = maps
        .iter()
        .map(|m| m.ltca_wall_s + m.speeds.iter().map(|r| r.run_wall_s).sum::<f64>())
        .sum();
    let _ = writeln!(
        s,
        "\nLine spacing {:.4} pinion orders (the kept wheel revolutions); {runs} runs, LTCA and runs {total:.1} s wall in all.\n",
        m0.speeds[0].order_resolution
    );
    let mut figs = Vec::new();
    for m in &maps {
        let stem = format!("order_map_{:?}_{:?}", m.pinion_blank, m.wheel_blank).to_lowercase();
        figs.extend(copied(
            &format!(
                "Order map of the wheel bearing force, 8-DOF model, {:?} pinion / {:?} wheel",
                m.pinion_blank, m.wheel_blank
            ),
            &dir.join(format!("{stem}.svg")),
            reports,
            &format!("lumped_{stem}.svg"),
        ));
    }
    crate::report::figures::figure_lines(&mut s, &figs, false);
    with_revolution(s, figs, out, reports, &maps)
}

/// Appends the whole-revolution subsection to `s` and its figures to `figs`.
fn with_revolution(
    mut s: String,
    mut figs: Vec<Figure>,
    out: &Path,
    reports: &Path,
    maps: &[OrderMapSummary],
) -> (String, Vec<Figure>) {
    let (md, more) = super::lightweight_revolution::subsection(out, reports, maps);
    s.push_str(&md);
    figs.extend(more);
    (s, figs)
}
