//! The report's subsection "White-paper pair, lightweight wheel over its
//! whole revolution", from the scene
//! `reference/scenes/white_paper_lightweight_runup.toml` (every wheel tooth
//! solved):
//!
//! - the 8-DOF model's lobe check: the per-revolution stiffness lobe fitted
//!   over the whole revolution's LTCA, over its first mesh cycles only (as
//!   a stiffness file of those teeth gives it) and by the order-map scene
//!   (8 teeth solved, [`super::lumped_order_map::ORDER_MAP_SCENE`]), where
//!   each is least against the web holes, and how well the per-cycle mean
//!   stiffness repeats every z₂/n teeth (`<out>/<scene>/lumped/order_map.json`);
//! - the wheel bearing-force amplitudes at the marked orders from the
//!   multibody run-up (`<out>/<scene>/multibody/<pair>/runup_orders.json`,
//!   the window of one wheel revolution whose mean speed is nearest) beside
//!   the 8-DOF model's at the same pinion speeds (solved revolution, and
//!   the order-map scene's extrapolated lobe where it has the speed);
//! - the run-up spectrograms of both wheel blanks.
//!
//! Every number is formatted from those files; absent ones are one line
//! of text.

use crate::report::figures::{copied, Figure};
use formats::lumped_summary::{OrderMapSpeed, OrderMapSummary};
use formats::summaries::{RunupOrderWindow, RunupOrders};
use std::fmt::Write as _;
use std::path::Path;

/// The scene of the whole-revolution run-up and order map.
pub const RUNUP_SCENE: &str = "white_paper_lightweight_runup";

/// The marked orders the comparison shows (labels of
/// `solver::signal::runup_orders::marked_orders` for 20/43 and 3 holes).
pub(crate) const SHOWN: [&str; 5] = ["20", "40", "3·20/43", "20-1.40", "20+1.40"];

fn read<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, String> {
    std::fs::read_to_string(path)
        .map_err(|e| e.to_string())
        .and_then(|t| serde_json::from_str(&t).map_err(|e| e.to_string()))
}

/// The run-up window whose mean pinion speed is nearest `rpm`.
pub fn nearest_window(orders: &RunupOrders, rpm: f64) -> Option<&RunupOrderWindow> {
    orders.windows.iter().min_by(|a, b| {
        (a.mean_pinion_rpm - rpm)
            .abs()
            .total_cmp(&(b.mean_pinion_rpm - rpm).abs())
    })
}

/// Amplitude (N) at the marked order `label` of a list of marked orders.
pub(crate) fn at(marked: &[formats::lumped_summary::MarkedOrder], label: &str) -> Option<f64> {
    marked
        .iter()
        .find(|m| m.label == label)
        .map(|m| m.wheel_bearing_force_n)
}

/// The side bands z₁ ± 3z₁/z₂ of the white-paper pair (20 ± 1.40)
/// together, N.
pub(crate) fn side_bands(marked: &[formats::lumped_summary::MarkedOrder]) -> f64 {
    at(marked, "20-1.40").unwrap_or(0.0) + at(marked, "20+1.40").unwrap_or(0.0)
}

/// The marked orders of one window.
type WindowMarks = [formats::lumped_summary::MarkedOrder];

pub(crate) fn cells(marked: &[formats::lumped_summary::MarkedOrder]) -> String {
    SHOWN
        .iter()
        .map(|l| at(marked, l).map_or("—".into(), |v| format!("{v:.3e}")))
        .collect::<Vec<_>>()
        .join(" | ")
}

/// Signed distance (teeth) from `t` to the nearest of `holes` on the
/// period `lobe` (z₂/n teeth), in (−lobe/2, lobe/2].
pub fn from_nearest_hole(t: f64, holes: &[f64], lobe: f64) -> Option<f64> {
    holes
        .iter()
        .map(|h| {
            let d = (t - h).rem_euclid(lobe);
            if d > 0.5 * lobe {
                d - lobe
            } else {
                d
            }
        })
        .min_by(|a, b| a.abs().total_cmp(&b.abs()))
}

/// The subsection's markdown and figures; `extrapolated` the order-map
/// scene's maps (8 teeth solved), when present.
pub fn subsection(
    out: &Path,
    reports: &Path,
    extrapolated: &[OrderMapSummary],
) -> (String, Vec<Figure>) {
    let mut s = String::from(
        "### White-paper pair, lightweight wheel over its whole revolution (multibody run-up and 8-DOF model)\n\n",
    );
    let path = out.join(RUNUP_SCENE).join("lumped").join("order_map.json");
    let maps: Vec<OrderMapSummary> = match read(&path) {
        Ok(v) => v,
        Err(e) => {
            let _ = writeln!(
                s,
                "No whole-revolution order map: `{}` cannot be read ({e}); `make lightweight` runs the scene `reference/scenes/{RUNUP_SCENE}.toml`.\n",
                path.display()
            );
            return (s, vec![]);
        }
    };
    let mut figs = Vec::new();
    if let Some(m) = maps.iter().find(|m| m.lobes > 0) {
        lobe_check(&mut s, m, extrapolated);
    }
    comparison(&mut s, out, &maps, extrapolated);
    for m in &maps {
        let pair = format!("{:?}_{:?}", m.pinion_blank, m.wheel_blank).to_lowercase();
        let from = out
            .join(RUNUP_SCENE)
            .join("multibody")
            .join(&pair)
            .join("runup_spectrogram.svg");
        figs.extend(copied(
            &format!(
                "Multibody run-up spectrogram of the wheel bearing force, {:?} pinion / {:?} wheel (scene {RUNUP_SCENE})",
                m.pinion_blank, m.wheel_blank
            ),
            &from,
            reports,
            &format!("runup_{pair}_spectrogram.svg"),
        ));
        let stem = format!("order_map_{pair}");
        figs.extend(copied(
            &format!(
                "Order map of the wheel bearing force, 8-DOF model on the solved revolution, {:?} pinion / {:?} wheel",
                m.pinion_blank, m.wheel_blank
            ),
            &out.join(RUNUP_SCENE).join("lumped").join(format!("{stem}.svg")),
            reports,
            &format!("runup_scene_{stem}.svg"),
        ));
    }
    crate::report::figures::figure_lines(&mut s, &figs, false);
    (s, figs)
}

/// The lobe of the 8-DOF model against the solved revolution.
fn lobe_check(s: &mut String, m: &OrderMapSummary, extrapolated: &[OrderMapSummary]) {
    let lobe = m.wheel_teeth as f64 / m.lobes.max(1) as f64;
    let holes: Vec<f64> = m
        .hole_wheel_teeth
        .iter()
        .map(|h| {
            // Within one lobe, [0, lobe) (a hole at a whole lobe is at 0).
            let x = h.rem_euclid(lobe);
            if lobe - x < 1e-9 * lobe {
                0.0
            } else {
                x
            }
        })
        .collect();
    let _ = writeln!(
        s,
        "The {:?} wheel's stiffness file holds {} of its {} teeth ({}), so the LTCA sweeps a whole wheel revolution ({} mesh cycles) and its k(t), δ(t) drive the 8-DOF runs ({}). The web holes' centres lie at the loaded flank of wheel teeth {} ({} within one lobe of {lobe:.2} teeth).\n",
        m.wheel_blank,
        m.wheel_solved_teeth.len(),
        m.wheel_teeth,
        if m.wheel_solved_teeth.len() == m.wheel_teeth { "every tooth" } else { "not every tooth" },
        m.ltca_span_mesh_cycles,
        if m.excitation.is_empty() { "excitation not recorded" } else { &m.excitation },
        m.hole_wheel_teeth.iter().map(|h| format!("{h:.2}")).collect::<Vec<_>>().join(", "),
        holes.iter().map(|h| format!("{h:.2}")).collect::<Vec<_>>().join(", "),
    );
    let _ = writeln!(
        s,
        "| Lobe fitted to | LTCA span, mesh cycles | Lobe k peak-to-peak / mean k | Least k at wheel tooth (of {lobe:.2} per lobe) | From the nearest hole, teeth |\n|---|---|---|---|---|"
    );
    let mut row = |what: &str, cycles: usize, ptp: f64, min: Option<f64>| {
        let _ = writeln!(
            s,
            "| {what} | {cycles} | {ptp:.4} | {} | {} |",
            min.map_or("—".into(), |t| format!("{t:.2}")),
            min.and_then(|t| from_nearest_hole(t, &holes, lobe))
                .map_or("—".into(), |d| format!("{d:+.2}"))
        );
    };
    row(
        "the whole revolution",
        m.ltca_span_mesh_cycles,
        m.stiffness_lobe_ptp_relative,
        m.stiffness_lobe_minimum_wheel_tooth,
    );
    if let Some(f) = &m.short_span_lobe {
        row(
            "its first mesh cycles only",
            f.span_mesh_cycles,
            f.stiffness_lobe_ptp_relative,
            f.stiffness_lobe_minimum_wheel_tooth,
        );
    }
    if let Some(e) = extrapolated.iter().find(|e| e.wheel_blank == m.wheel_blank) {
        row(
            &format!(
                "the order-map scene's {}-tooth file",
                e.wheel_solved_teeth.len()
            ),
            e.ltca_span_mesh_cycles,
            e.stiffness_lobe_ptp_relative,
            e.stiffness_lobe_minimum_wheel_tooth,
        );
    }
    s.push('\n');
    if let Some([max, rms]) = m.lobe_repeat_mismatch_of_mean {
        let _ = writeln!(
            s,
            "Three-fold repeat of the FE data: the mean k of each mesh cycle against the mean k {lobe:.2} teeth on (linearly interpolated), max {:.4} and rms {:.4} of the mean k, against the lobe's peak-to-peak {:.4}.\n",
            max, rms, m.stiffness_lobe_ptp_relative
        );
    }
    let per_tooth: Vec<String> = m
        .cycle_wheel_tooth
        .iter()
        .zip(&m.cycle_mean_stiffness_n_per_m)
        .map(|(t, k)| format!("{t:.1}: {:.1}", k * 1e-6))
        .collect();
    let _ = writeln!(
        s,
        "Mean k per mesh cycle over the revolution (force-weighted loaded wheel tooth: MN/m): {}.\n",
        per_tooth.join(", ")
    );
}

/// Multibody run-up windows beside the 8-DOF runs at the same speeds.
fn comparison(
    s: &mut String,
    out: &Path,
    maps: &[OrderMapSummary],
    extrapolated: &[OrderMapSummary],
) {
    let _ = writeln!(
        s,
        "Wheel bearing-force amplitude (resultant of X, Y, Z, N) at the marked pinion orders. Multibody: the run-up's window of one wheel revolution of pinion angle whose mean speed is nearest (`runup_orders.json`: orders on lines {:.4} pinion orders apart whatever the ramp, amplitudes averaged over the window's speed range; rigid bearings, torsional model). 8-DOF: the order map's run at that speed (bearings 1 GN/m). Both at 300 N·m.\n",
        maps.first().map_or(0.0, |m| m.pinion_teeth as f64 / m.wheel_teeth as f64)
    );
    let _ = writeln!(
        s,
        "| Pinion speed (rpm) | Wheel | Model | {} |\n|---|---|---|{}",
        SHOWN
            .iter()
            .map(|l| format!("{l} (N)"))
            .collect::<Vec<_>>()
            .join(" | "),
        "---|".repeat(SHOWN.len())
    );
    // Rigid bearings (`runup_orders.json`) and, with the scene's
    // `[bearings]`, compliant ones (`bearings_runup_orders.json`).
    let runups: Vec<[Option<RunupOrders>; 2]> = maps
        .iter()
        .map(|m| {
            let pair = format!("{:?}_{:?}", m.pinion_blank, m.wheel_blank).to_lowercase();
            let dir = out.join(RUNUP_SCENE).join("multibody").join(pair);
            ["runup_orders.json", "bearings_runup_orders.json"].map(|f| read(&dir.join(f)).ok())
        })
        .collect();
    let mut compliant = Vec::new();
    let speeds: Vec<f64> = maps
        .first()
        .map(|m| m.speeds.iter().map(|v| v.pinion_speed_rpm).collect())
        .unwrap_or_default();
    let mut bands = Vec::new();
    for &rpm in &speeds {
        let mut side = [None, None];
        for (m, ro) in maps.iter().zip(&runups) {
            let w = format!("{:?}", m.wheel_blank);
            let row = |v: &OrderMapSpeed| cells(&v.marked);
            if let Some(v) = m.speeds.iter().find(|v| v.pinion_speed_rpm == rpm) {
                let _ = writeln!(
                    s,
                    "| {rpm:.0} | {w} | 8-DOF, {} | {} |",
                    if m.excitation.is_empty() {
                        "revolution"
                    } else {
                        &m.excitation
                    },
                    row(v)
                );
            }
            // The extrapolated lobe: lightweight wheels only (a standard
            // wheel's runs are the same in both scenes).
            let lobed = extrapolated
                .iter()
                .find(|e| e.wheel_blank == m.wheel_blank && e.lobes > 0);
            if let Some(e) = lobed {
                if let Some(v) = e.speeds.iter().find(|v| v.pinion_speed_rpm == rpm) {
                    let _ = writeln!(
                        s,
                        "| {rpm:.0} | {w} | 8-DOF, lobe fitted to {} teeth | {} |",
                        e.wheel_solved_teeth.len(),
                        row(v)
                    );
                }
            }
            let [ro, co] = ro;
            if let (Some(rw), Some(cw)) = (
                ro.as_ref().and_then(|o| nearest_window(o, rpm)),
                co.as_ref().and_then(|o| nearest_window(o, rpm)),
            ) {
                let _ = writeln!(
                    s,
                    "| {rpm:.0} | {w} | multibody run-up, compliant bearings, {:.0} rpm ({:.0}–{:.0}) | {} |",
                    cw.mean_pinion_rpm,
                    cw.pinion_rpm[0],
                    cw.pinion_rpm[1],
                    cells(&cw.marked)
                );
                let ratio = |l: &str| Some(at(&cw.marked, l)? / at(&rw.marked, l)?.max(1e-300));
                let sum = |x: &WindowMarks| side_bands(x);
                compliant.push(format!(
                    "{w} at {rpm:.0} rpm: {}",
                    SHOWN
                        .iter()
                        .map(|l| ratio(l).map_or(format!("{l} —"), |r| format!("{l} {r:.2}")))
                        .chain([format!(
                            "side bands together {:.2}",
                            sum(&cw.marked) / sum(&rw.marked).max(1e-300)
                        )])
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
            }
            match ro.as_ref().and_then(|o| nearest_window(o, rpm)) {
                Some(win) => {
                    let _ = writeln!(
                        s,
                        "| {rpm:.0} | {w} | multibody run-up, {:.0} rpm ({:.0}–{:.0}) | {} |",
                        win.mean_pinion_rpm,
                        win.pinion_rpm[0],
                        win.pinion_rpm[1],
                        cells(&win.marked)
                    );
                    let sb = side_bands(&win.marked);
                    let hole = at(&win.marked, "3·20/43").unwrap_or(0.0);
                    side[usize::from(m.lobes > 0)] = Some([sb, hole]);
                }
                None => {
                    let _ = writeln!(
                        s,
                        "| {rpm:.0} | {w} | multibody run-up | no `runup_orders.json` |"
                    );
                }
            }
        }
        if let [Some(std), Some(light)] = side {
            bands.push(format!(
                "{rpm:.0} rpm: {:.1} and {:.1}",
                light[1] / std[1].max(1e-300),
                light[0] / std[0].max(1e-300)
            ));
        }
    }
    s.push('\n');
    if !bands.is_empty() {
        let _ = writeln!(
            s,
            "Multibody run-up, lightweight over standard wheel, at the hole order 3·20/43 and at the side bands 20 ± 1.40 (sum of both): {}. Where the second is near 1, the side bands do not stand above the windows' floor (the standard wheel's lines there: content not locked to the orders, such as the torsional mode's response while the ramp sweeps towards it).\n",
            bands.join("; ")
        );
    }
    if !compliant.is_empty() {
        let _ = writeln!(
            s,
            "Multibody run-up, compliant over rigid bearings (both wheel bearings' force together against the reaction to the contact force; the bearings of `{RUNUP_SCENE}`'s `[bearings]`), amplitude ratio per marked order: {}.\n",
            compliant.join("; ")
        );
    }
    let _ = writeln!(
        s,
        "The two models' wheel bearing forces differ in kind: the multibody's is the contact element's force vector in the fixed frame, whose direction and size change over the mesh cycle already at low speed (its mesh orders are mostly quasi-static), on rigid bearings; the 8-DOF model's mesh force acts along one fixed normal on bearings of 1 GN/m, so at low speed its bearing force holds only the dynamic part.\n"
    );
}
