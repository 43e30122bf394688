//! The report's root stress section: the reference FE's tooth root
//! (fillet) stresses per blank pair and load, from the `summary.json` of
//! every mesh level's reference sweep that computed them
//! ([`crate::reference::reference_root_stress`]): the finest level's
//! extremes with where they sit, then each level's largest tension beside
//! the finest one's (how much the value still moves with the mesh), the
//! design's nominal root stress as an order-of-magnitude anchor, and the
//! reduced model's root stress against the reference's.

use crate::reference::reference_stage::reference_dir;
use crate::reference::reference_summary::BlankSummary;
use crate::report::figures::{figure_lines, Figure};
use charts::{te_curve, Series};
use formats::root_stress::{FilletPlace, RootStressSummary};
use formats::stiffness_file::ROOT_STRESS_GRID;
use geometry::design::PairData;
use geometry::nominal_root_stress::nominal_root_stress;
use geometry::scene::LoadedScene;
use std::fmt::Write as _;
use std::path::Path;

/// Mesh levels of the reference, coarsest first.
pub const LEVELS: [&str; 3] = ["reduced", "medium", "reference"];

/// One level, blank pair and load.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub level: String,
    /// `<pinion blank>_<wheel blank>`.
    pub blanks: String,
    pub torque_nm: f64,
    pub stress: RootStressSummary,
}

/// The blank-pair folders of `dir` that hold a `summary.json`, the
/// standard blanks first (as the report's other tables); none when `dir`
/// does not exist.
fn summary_dirs(dir: &Path) -> Vec<std::path::PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut pairs: Vec<_> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.join("summary.json").is_file())
        .collect();
    pairs.sort_by_key(|p| (!p.ends_with("standard_standard"), p.clone()));
    pairs
}

/// The rows of every level's sweep under `out` for `scene` that has root
/// stress; blank pairs in folder order.
pub fn rows(out: &Path, scene: &str) -> anyhow::Result<Vec<Row>> {
    let mut rows = Vec::new();
    for level in LEVELS {
        let dir = reference_dir(out, scene, level);
        for p in summary_dirs(&dir) {
            let text = std::fs::read_to_string(p.join("summary.json"))?;
            // A summary of an older layout is not this section's to judge.
            let Ok(s) = serde_json::from_str::<BlankSummary>(&text) else {
                continue;
            };
            let blanks = format!("{}_{}", s.pinion_blank, s.wheel_blank);
            for l in &s.loads {
                if let Some(stress) = l.root_stress {
                    rows.push(Row {
                        level: level.to_string(),
                        blanks: blanks.clone(),
                        torque_nm: l.torque_nm,
                        stress,
                    });
                }
            }
        }
    }
    Ok(rows)
}

fn place(p: &FilletPlace) -> String {
    format!(
        "tooth {}, ξ {:.2}, h {:.2}, {:.1}°",
        p.tooth, p.xi, p.height, p.pinion_rotation_deg
    )
}

/// The reduced model's (LTCA) root stress of one blank pair and load.
#[derive(Debug, Clone, PartialEq)]
pub struct ReducedRow {
    pub blanks: String,
    pub torque_nm: f64,
    pub stress: RootStressSummary,
}

/// The LTCA's root stress under `out` for `scene`, every blank pair whose
/// stiffness files held root-stress coefficients.
pub fn reduced_rows(out: &Path, scene: &str) -> anyhow::Result<Vec<ReducedRow>> {
    let mut rows = Vec::new();
    for p in summary_dirs(&out.join(scene).join("ltca")) {
        let text = std::fs::read_to_string(p.join("summary.json"))?;
        let Ok(s) = serde_json::from_str::<formats::summaries::BlankSummary>(&text) else {
            continue;
        };
        let blanks = format!("{}_{}", s.pinion_blank.name(), s.wheel_blank.name());
        for l in &s.loads {
            if let Some(stress) = l.root_stress {
                rows.push(ReducedRow {
                    blanks: blanks.clone(),
                    torque_nm: l.torque_nm,
                    stress,
                });
            }
        }
    }
    Ok(rows)
}

/// Largest |difference| of the reduced model's tension from the
/// reference's the report accepts, % (the target both members are judged
/// by, from 100 N·m on).
pub const TENSION_TARGET_PCT: f64 = 5.0;

/// Loads from which the comparison is judged, N·m (below, the stresses
/// are those of the unloaded geometry's first touch).
pub const JUDGED_FROM_NM: f64 = 100.0;

/// The reduced model's largest tension against the reference's (finest
/// level) per blank pair and load, and the verdict on the target.
pub fn comparison(reference: &[Row], reduced: &[ReducedRow]) -> String {
    let Some(top) = finest(reference) else {
        return String::new();
    };
    let mut lines = Vec::new();
    let mut worst: Option<(f64, String)> = None;
    for r in reduced {
        let Some(f) = reference
            .iter()
            .find(|q| q.level == top && q.blanks == r.blanks && q.torque_nm == r.torque_nm)
        else {
            continue;
        };
        let diff = |a: f64, b: f64| 100.0 * (a - b) / b;
        let d = [
            diff(r.stress.pinion.tension_mpa, f.stress.pinion.tension_mpa),
            diff(r.stress.wheel.tension_mpa, f.stress.wheel.tension_mpa),
        ];
        lines.push(format!(
            "| {} | {} | {:.1} | {:.1} | {:+.1} | {:.1} | {:.1} | {:+.1} |",
            r.blanks,
            r.torque_nm,
            r.stress.pinion.tension_mpa,
            f.stress.pinion.tension_mpa,
            d[0],
            r.stress.wheel.tension_mpa,
            f.stress.wheel.tension_mpa,
            d[1]
        ));
        if r.torque_nm >= JUDGED_FROM_NM {
            for (k, member) in ["pinion", "wheel"].iter().enumerate() {
                if worst.as_ref().is_none_or(|(w, _)| d[k].abs() > w.abs()) {
                    worst = Some((
                        d[k],
                        format!("{member}, {} at {} N·m", r.blanks, r.torque_nm),
                    ));
                }
            }
        }
    }
    if lines.is_empty() {
        return String::new();
    }
    let mut s = format!(
        "The reduced model's root stress: the stiffness files' root-stress coefficients (the stress at a {} × {} grid of points on each fillet of the loaded tooth and its neighbours under each grid load, on the reduced-level meshes) combined with the LTCA's slice forces, at the scene's sweep positions; against the reference at mesh level `{top}` (its own positions):\n\n| blank pair | load, N·m | pinion tension reduced, MPa | reference, MPa | diff % | wheel tension reduced, MPa | reference, MPa | diff % |\n|---|---|---|---|---|---|---|---|\n",
        ROOT_STRESS_GRID[0],
        ROOT_STRESS_GRID[1]
    );
    for l in lines {
        s.push_str(&l);
        s.push('\n');
    }
    s.push('\n');
    if let Some((d, what)) = worst {
        let verdict = if d.abs() <= TENSION_TARGET_PCT {
            format!("within the {TENSION_TARGET_PCT:.0} % target")
        } else {
            format!("outside the {TENSION_TARGET_PCT:.0} % target")
        };
        let _ = writeln!(
            s,
            "From {JUDGED_FROM_NM:.0} N·m on, the largest difference is {d:+.1} % ({what}): {verdict}. The two differ in mesh (the reduced level's fillet elements against the finest level's), in where the stress is read (the grid's points against every fillet node), and in the contact model that loads the teeth.\n"
        );
    }
    s
}

/// The multibody runs' root tension: per blank pair the 10 rpm runs'
/// largest tension over the sweep against the LTCA's at the same load,
/// and the run-up's dynamic against quasi-static tension. `dynamic`: the
/// `solver dynamic` summaries; `reduced`: the LTCA's rows.
pub fn multibody(dynamic: &[formats::summaries::DynamicSummary], reduced: &[ReducedRow]) -> String {
    let mut rows = Vec::new();
    let mut runups = Vec::new();
    let mut worst: Option<f64> = None;
    for d in dynamic {
        let blanks = format!("{}_{}", d.pinion_blank.name(), d.wheel_blank.name());
        for q in &d.quasi_static {
            let (Some(mb), Some(l)) = (
                q.root_tension_mpa,
                reduced
                    .iter()
                    .find(|r| r.blanks == blanks && r.torque_nm == q.torque_nm),
            ) else {
                continue;
            };
            let lt = [l.stress.pinion.tension_mpa, l.stress.wheel.tension_mpa];
            let diff = [0, 1].map(|k| 100.0 * (mb[k] / lt[k] - 1.0));
            for d in diff {
                worst = Some(worst.map_or(d, |w: f64| if d.abs() > w.abs() { d } else { w }));
            }
            rows.push(format!(
                "| {blanks} | {} | {:.1} | {:.1} | {:+.2} | {:.1} | {:.1} | {:+.2} |",
                q.torque_nm, mb[0], lt[0], diff[0], mb[1], lt[1], diff[1]
            ));
        }
        if let Some((r, t)) = d
            .runup
            .as_ref()
            .and_then(|r| r.root_tension_mpa.map(|t| (r, t)))
        {
            runups.push(format!(
                "| {blanks} | {} | {}–{} rpm in {} s | {:.1} | {:.1} | {:.3} | {:.1} | {:.1} | {:.3} |",
                r.pinion_torque_nm,
                r.rpm[0],
                r.rpm[1],
                r.sim_time_s,
                t.dynamic[0],
                t.quasi_static[0],
                t.dynamic[0] / t.quasi_static[0],
                t.dynamic[1],
                t.quasi_static[1],
                t.dynamic[1] / t.quasi_static[1]
            ));
        }
    }
    let mut s = String::new();
    if !rows.is_empty() {
        let _ = writeln!(
            s,
            "The multibody runs' root stress: the contact-element table holds, at each of its nodes (pinion rotation × wheel lag), the loaded teeth's largest fillet tension of both members, interpolated at every step as the torque is. The 10 rpm runs' largest tension over the sweep against the LTCA's at the same load (the same model; the difference is the table's interpolation and the runs' finer steps):\n\n| blank pair | load, N·m | pinion multibody, MPa | LTCA, MPa | diff % | wheel multibody, MPa | LTCA, MPa | diff % |\n|---|---|---|---|---|---|---|---|"
        );
        for r in rows {
            let _ = writeln!(s, "{r}");
        }
        if let Some(w) = worst {
            let _ = writeln!(s, "\nThe largest difference is {w:+.2} %.\n");
        }
    }
    if !runups.is_empty() {
        let _ = writeln!(
            s,
            "The run-up's largest root tension, dynamic against quasi-static (the table at the static lag of the same pinion rotations); their ratio is the run's dynamic factor on the root stress:\n\n| blank pair | load, N·m | run-up | pinion dynamic, MPa | quasi-static, MPa | ratio | wheel dynamic, MPa | quasi-static, MPa | ratio |\n|---|---|---|---|---|---|---|---|---|"
        );
        for r in runups {
            let _ = writeln!(s, "{r}");
        }
        s.push('\n');
    }
    s
}

/// The `solver dynamic` summaries under `out` for `scene` (none when
/// absent or of another layout).
fn dynamic_summaries(out: &Path, scene: &str) -> Vec<formats::summaries::DynamicSummary> {
    std::fs::read_to_string(out.join(scene).join("multibody").join("summary.json"))
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok())
        .unwrap_or_default()
}

/// The section: its markdown and its figures.
#[derive(Debug, Clone, Default)]
pub struct RootStressSection {
    pub markdown: String,
    pub figures: Vec<Figure>,
}

/// The nominal root stress of the design (an estimate,
/// [`geometry::nominal_root_stress`]) beside the reference's largest
/// tension at the finest level, per blank pair and load.
pub fn nominal(rows: &[Row], pair: &PairData, alpha_n: f64) -> String {
    let Some(top) = finest(rows) else {
        return String::new();
    };
    let lines: Vec<String> = rows
        .iter()
        .filter(|r| r.level == top && r.torque_nm > 0.0)
        .map(|r| {
            let n = nominal_root_stress(pair, alpha_n, r.torque_nm);
            let [p, w] = n.sigma_pa.map(|s| s * 1e-6);
            format!(
                "| {} | {} | {:.1} | {:.1} | {:.2} | {:.1} | {:.1} | {:.2} |",
                r.blanks,
                r.torque_nm,
                p,
                r.stress.pinion.tension_mpa,
                r.stress.pinion.tension_mpa / p,
                w,
                r.stress.wheel.tension_mpa,
                r.stress.wheel.tension_mpa / w
            )
        })
        .collect();
    if lines.is_empty() {
        return String::new();
    }
    let n = nominal_root_stress(pair, alpha_n, 1.0);
    let mut s = format!(
        "An order-of-magnitude anchor, an estimate and not a rating: the nominal root stress σ_F0 = F_mt / (b m_mn) · Y_Fa · Y_Sa · Y_ε of the design data alone, with the structure of ISO 10300-3:2014 method B1 (virtual cylindrical gears in the normal section at the mean point) and ISO 6336-3 method B's form and stress correction factors for the load at the tip (`geometry::nominal_root_stress`; checked against the published spur-gear table of Y_Fa and Y_Sa). Chosen by us: the bevel-spiral and load-sharing factors are 1 and no load factor enters, so σ_F0 is the stress of the load spread evenly over the face width; the web of a lightweight blank does not enter. Here: virtual teeth {:.1} / {:.1}, Y_Fa {:.3} / {:.3}, Y_Sa {:.3} / {:.3} (pinion / wheel), ε_vα {:.3}, Y_ε {:.3}.\n\n| blank pair | load, N·m | pinion σ_F0, MPa | reference tension, MPa | ratio | wheel σ_F0, MPa | reference tension, MPa | ratio |\n|---|---|---|---|---|---|---|---|\n",
        n.teeth[0].z,
        n.teeth[1].z,
        n.factors[0].y_fa,
        n.factors[1].y_fa,
        n.factors[0].y_sa,
        n.factors[1].y_sa,
        n.contact_ratio,
        n.y_epsilon
    );
    for l in lines {
        s.push_str(&l);
        s.push('\n');
    }
    s.push('\n');
    s
}

/// The section from the sweeps under `out` for `scene`, its figures
/// written into `reports`.
pub fn build(out: &Path, scene: &LoadedScene, reports: &Path) -> anyhow::Result<RootStressSection> {
    let name = scene.scene.name.as_str();
    let rows = rows(out, name)?;
    let mut markdown = text(&rows);
    markdown.push_str(&nominal(
        &rows,
        &scene.pair,
        scene.pair.pressure_angle[scene.scene.loaded_flank.index()],
    ));
    let reduced = reduced_rows(out, name)?;
    markdown.push_str(&comparison(&rows, &reduced));
    let mb = multibody(&dynamic_summaries(out, name), &reduced);
    if markdown.is_empty() && !mb.is_empty() {
        markdown.push_str("## Tooth root stress\n\n");
    }
    markdown.push_str(&mb);
    let figures = match finest(&rows) {
        Some(top) => cycle_figures(out, name, top, &rows, reports),
        None => Vec::new(),
    };
    if !figures.is_empty() {
        let _ = writeln!(
            markdown,
            "The largest tension in each tooth's loaded fillet over the pinion rotation at the largest load (mesh level `{top}`), one curve per tooth, at the solved positions where that tooth's flank carries load; where the LTCA wrote its `root_stress.csv`, also the largest over the loaded teeth of both models, the reduced model dashed (its positions are the scene's sweep, the reference's every stride-th of them).\n",
            top = finest(&rows).unwrap_or_default()
        );
        figure_lines(&mut markdown, &figures, true);
    }
    Ok(RootStressSection { markdown, figures })
}

/// Per blank pair of the level `level` at its largest load, one chart per
/// member: each loaded tooth's largest loaded-fillet tension against the
/// pinion rotation, from `root_stress.csv`.
fn cycle_figures(
    out: &Path,
    scene: &str,
    level: &str,
    rows: &[Row],
    reports: &Path,
) -> Vec<Figure> {
    let mut figs = Vec::new();
    let mut pairs: Vec<&str> = rows
        .iter()
        .filter(|r| r.level == level)
        .map(|r| r.blanks.as_str())
        .collect();
    pairs.dedup();
    for blanks in pairs {
        let Some(t) = rows
            .iter()
            .filter(|r| r.level == level && r.blanks == blanks)
            .map(|r| r.torque_nm)
            .reduce(f64::max)
        else {
            continue;
        };
        let path = reference_dir(out, scene, level)
            .join(blanks)
            .join("root_stress.csv");
        let Ok(text) = std::fs::read_to_string(&path) else {
            continue;
        };
        let reduced = std::fs::read_to_string(
            out.join(scene)
                .join("ltca")
                .join(blanks)
                .join("root_stress.csv"),
        )
        .ok();
        for member in ["pinion", "wheel"] {
            if let Some(r) = &reduced {
                let series: Vec<Series> =
                    [("reference FE", &text, false), ("reduced model", r, true)]
                        .into_iter()
                        .filter_map(|(name, csv, dashed)| {
                            let (x, y) = envelope(csv, member, t);
                            (!x.is_empty()).then(|| Series {
                                name: name.into(),
                                x,
                                y,
                                dashed,
                            })
                        })
                        .collect();
                if series.len() == 2 {
                    figs.extend(tension_chart(
                        reports,
                        format!("root_stress_envelope_{blanks}_{member}_{t}nm.svg"),
                        format!(
                            "Largest root tension of the {member} over the loaded teeth, reduced model and reference FE, {} blanks, {t} N·m",
                            blanks.replace('_', " / ")
                        ),
                        &series,
                    ));
                }
            }
            let series = tooth_series(&text, member, t);
            if series.is_empty() {
                continue;
            }
            figs.extend(tension_chart(
                reports,
                format!("root_stress_{blanks}_{member}_{t}nm.svg"),
                format!(
                    "Root stress of the {member}'s teeth, {} blanks, {t} N·m",
                    blanks.replace('_', " / ")
                ),
                &series,
            ));
        }
    }
    figs
}

/// A chart of loaded-fillet tension against the pinion rotation written
/// into `reports` as `file`; None when it cannot be written.
fn tension_chart(reports: &Path, file: String, title: String, series: &[Series]) -> Option<Figure> {
    let target = reports.join(&file);
    te_curve(
        &target,
        &title,
        "pinion rotation (deg)",
        "largest loaded-fillet tension (MPa)",
        series,
    )
    .ok()?;
    let svg = std::fs::read_to_string(&target).ok()?;
    Some(Figure { title, file, svg })
}

/// The loaded fillets' rows of `member` at torque `t` in a
/// `root_stress.csv` text: (rotation deg, tooth, largest tension MPa).
fn loaded_rows<'a>(
    csv: &'a str,
    member: &'a str,
    t: f64,
) -> impl Iterator<Item = (f64, usize, f64)> + 'a {
    csv.lines().skip(1).filter_map(move |line| {
        let c: Vec<&str> = line.split(',').collect();
        if c.len() < 6 || c[2] != member || c[4] != "loaded" {
            return None;
        }
        let (Ok(deg), Ok(torque), Ok(tooth), Ok(sigma)) = (
            c[0].parse::<f64>(),
            c[1].parse::<f64>(),
            c[3].parse::<usize>(),
            c[5].parse::<f64>(),
        ) else {
            return None;
        };
        (torque == t).then_some((deg, tooth, sigma))
    })
}

/// One series per tooth of `member`: its loaded fillet's largest tension
/// (MPa) against the rotation at torque `t`, from a `root_stress.csv` text.
fn tooth_series(csv: &str, member: &str, t: f64) -> Vec<Series> {
    let mut by_tooth: std::collections::BTreeMap<usize, (Vec<f64>, Vec<f64>)> = Default::default();
    for (deg, tooth, sigma) in loaded_rows(csv, member, t) {
        let e = by_tooth.entry(tooth).or_default();
        e.0.push(deg);
        e.1.push(sigma);
    }
    by_tooth
        .into_iter()
        .map(|(tooth, (x, y))| Series {
            name: format!("tooth {tooth}"),
            x,
            y,
            dashed: false,
        })
        .collect()
}

/// The largest loaded-fillet tension over the teeth of `member` (MPa)
/// against the rotation at torque `t`, from a `root_stress.csv` text, in
/// rotation order.
fn envelope(csv: &str, member: &str, t: f64) -> (Vec<f64>, Vec<f64>) {
    let mut at: Vec<(f64, f64)> = Vec::new();
    for (deg, _, sigma) in loaded_rows(csv, member, t) {
        match at.iter_mut().find(|p| p.0 == deg) {
            Some(p) => p.1 = p.1.max(sigma),
            None => at.push((deg, sigma)),
        }
    }
    at.sort_by(|a, b| a.0.total_cmp(&b.0));
    at.into_iter().unzip()
}

/// The finest level among `rows`.
fn finest(rows: &[Row]) -> Option<&str> {
    LEVELS
        .iter()
        .rev()
        .find(|l| rows.iter().any(|r| r.level == **l))
        .copied()
}

/// The section's markdown (empty without rows).
pub fn text(rows: &[Row]) -> String {
    let Some(top) = finest(rows) else {
        return String::new();
    };
    let mut s = String::from("## Tooth root stress (reference FE)\n\n");
    let _ = writeln!(
        s,
        "The reference FE gives the stress in the root fillets of every tooth that carries load, at every position and torque of its sweep: the recovered nodal stress of the tet10 field (at a node, the volume-weighted mean of the holding elements' stresses there) at the body's surface nodes on the fillet the blade edge generates under each flank. Per blank pair and load, the largest first principal stress in a loaded flank's fillet (tension: the bending stress that fatigue is judged by) and the smallest third principal stress in the other flank's fillet (compression), over all positions and teeth, with where they sit: tooth, face-width position ξ (0 toe, 1 heel), fillet height h (0 root, 1 junction with the flank) and pinion rotation from the sweep's start. Mesh level `{top}`; frictionless contact, smooth flanks.\n"
    );
    let _ = writeln!(
        s,
        "| blank pair | load, N·m | pinion tension, MPa | where | pinion compression, MPa | wheel tension, MPa | where | wheel compression, MPa |\n|---|---|---|---|---|---|---|---|"
    );
    for r in rows.iter().filter(|r| r.level == top) {
        let (p, w) = (&r.stress.pinion, &r.stress.wheel);
        let _ = writeln!(
            s,
            "| {} | {} | {:.1} | {} | {:.1} | {:.1} | {} | {:.1} |",
            r.blanks,
            r.torque_nm,
            p.tension_mpa,
            place(&p.tension_at),
            p.compression_mpa,
            w.tension_mpa,
            place(&w.tension_at),
            w.compression_mpa
        );
    }
    s.push('\n');
    s.push_str(&mesh_dependence(rows, top));
    s
}

/// Each level's largest tension beside the finest level's, and the
/// largest relative change between the two finest levels present.
fn mesh_dependence(rows: &[Row], top: &str) -> String {
    let levels: Vec<&str> = LEVELS
        .iter()
        .copied()
        .filter(|l| rows.iter().any(|r| r.level == *l))
        .collect();
    if levels.len() < 2 {
        return String::new();
    }
    let mut s = format!(
        "Largest tension per mesh level (pinion / wheel, MPa), the levels' meshes of the same bodies:\n\n| blank pair | load, N·m | {} |\n|---|---|{}\n",
        levels.join(" | "),
        "---|".repeat(levels.len())
    );
    let next = levels[levels.len() - 2];
    let mut worst: Option<(f64, String)> = None;
    for r in rows.iter().filter(|r| r.level == top) {
        let at = |level: &str| {
            rows.iter()
                .find(|q| q.level == level && q.blanks == r.blanks && q.torque_nm == r.torque_nm)
                .map(|q| [q.stress.pinion.tension_mpa, q.stress.wheel.tension_mpa])
        };
        let cells: Vec<String> = levels
            .iter()
            .map(|l| at(l).map_or("–".into(), |v| format!("{:.1} / {:.1}", v[0], v[1])))
            .collect();
        let _ = writeln!(
            s,
            "| {} | {} | {} |",
            r.blanks,
            r.torque_nm,
            cells.join(" | ")
        );
        if let (true, Some(a), Some(b)) = (r.torque_nm >= JUDGED_FROM_NM, at(next), at(top)) {
            for (k, member) in ["pinion", "wheel"].iter().enumerate() {
                let d = 100.0 * (a[k] - b[k]) / b[k];
                if worst.as_ref().is_none_or(|(w, _)| d.abs() > w.abs()) {
                    worst = Some((d, format!("{member}, {} at {} N·m", r.blanks, r.torque_nm)));
                }
            }
        }
    }
    s.push('\n');
    if let Some((d, what)) = worst {
        let _ = writeln!(
            s,
            "From the `{next}` to the `{top}` level, from {JUDGED_FROM_NM:.0} N·m on, the largest tension moves by at most {:.1} % ({what}): the fillet stress of the finest level is that close to its own mesh's answer, not a converged value (a recovered nodal stress at a curved surface converges at first order).\n",
            d.abs()
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use formats::root_stress::RootStressExtreme;

    fn extreme(t: f64) -> RootStressExtreme {
        let p = FilletPlace {
            pinion_rotation_deg: 3.5,
            tooth: 1,
            xi: 0.6,
            height: 0.55,
        };
        RootStressExtreme {
            tension_mpa: t,
            tension_at: p,
            compression_mpa: -1.1 * t,
            compression_at: p,
        }
    }

    fn row(level: &str, t: f64, p: f64, w: f64) -> Row {
        Row {
            level: level.into(),
            blanks: "standard_standard".into(),
            torque_nm: t,
            stress: RootStressSummary {
                pinion: extreme(p),
                wheel: extreme(w),
            },
        }
    }

    /// The finest level's table, and the change from the next level
    /// computed from the rows (here the wheel's 300 → 330 MPa: 10 %).
    #[test]
    fn root_stress_section_tabulates_the_finest_level_and_its_change_from_the_next() {
        let rows = vec![
            row("medium", 300.0, 200.0, 300.0),
            row("reference", 300.0, 210.0, 330.0),
        ];
        let t = text(&rows);
        assert!(t.contains("| standard_standard | 300 | 210.0 | tooth 1, ξ 0.60, h 0.55, 3.5° | -231.0 | 330.0 |"), "{t}");
        assert!(t.contains("| medium | reference |"), "{t}");
        assert!(t.contains("200.0 / 300.0 | 210.0 / 330.0"), "{t}");
        assert!(
            t.contains("moves by at most 9.1 % (wheel, standard_standard at 300 N·m)"),
            "{t}"
        );
    }

    /// The per-tooth curves take the loaded fillets of one member at one
    /// torque only, tooth by tooth in rotation order.
    #[test]
    fn root_stress_curves_are_one_per_tooth_of_the_loaded_fillets() {
        let csv = "pinion_rotation_deg,torque_nm,member,tooth,fillet,sigma1_max_mpa,sigma1_xi,sigma1_height,sigma3_min_mpa,sigma3_xi,sigma3_height
0,300,pinion,1,loaded,170,0.5,0.5,-10,0.5,0.5
0,300,pinion,1,opposite,30,0.5,0.5,-170,0.5,0.5
0,300,wheel,42,loaded,160,0.5,0.5,-10,0.5,0.5
0,700,pinion,1,loaded,330,0.5,0.5,-20,0.5,0.5
0.5,300,pinion,1,loaded,175,0.5,0.5,-10,0.5,0.5
0.5,300,pinion,2,loaded,20,0.5,0.5,-1,0.5,0.5
";
        let s = tooth_series(csv, "pinion", 300.0);
        assert_eq!(s.len(), 2);
        assert_eq!(
            (s[0].name.as_str(), &s[0].x[..], &s[0].y[..]),
            ("tooth 1", &[0.0, 0.5][..], &[170.0, 175.0][..])
        );
        assert_eq!((s[1].name.as_str(), &s[1].y[..]), ("tooth 2", &[20.0][..]));
        assert_eq!(tooth_series(csv, "wheel", 300.0)[0].y, vec![160.0]);
    }

    fn reduced(t: f64, p: f64, w: f64) -> ReducedRow {
        let r = row("reference", t, p, w);
        ReducedRow {
            blanks: r.blanks,
            torque_nm: t,
            stress: r.stress,
        }
    }

    /// The reduced model against the finest level: the differences per
    /// row, and the verdict from the largest one from 100 N·m on (the
    /// 1 N·m row's 50 % does not count): within the target at 3.0 %,
    /// outside it at 10.0 %.
    #[test]
    fn reduced_root_stress_is_judged_within_or_outside_the_target() {
        let reference = vec![
            row("reference", 1.0, 1.0, 1.0),
            row("reference", 300.0, 200.0, 300.0),
        ];
        let within = comparison(
            &reference,
            &[reduced(1.0, 1.5, 1.0), reduced(300.0, 206.0, 297.0)],
        );
        assert!(
            within.contains(
                "| standard_standard | 300 | 206.0 | 200.0 | +3.0 | 297.0 | 300.0 | -1.0 |"
            ),
            "{within}"
        );
        assert!(within.contains("largest difference is +3.0 % (pinion, standard_standard at 300 N·m): within the 5 % target"), "{within}");
        let outside = comparison(&reference, &[reduced(300.0, 180.0, 300.0)]);
        assert!(outside.contains("largest difference is -10.0 % (pinion, standard_standard at 300 N·m): outside the 5 % target"), "{outside}");
        assert_eq!(comparison(&[], &[reduced(300.0, 1.0, 1.0)]), "");
    }

    /// One level only: the table without the mesh comparison; no rows: no
    /// section.
    #[test]
    fn root_stress_section_without_a_second_level_or_any_rows() {
        let t = text(&[row("reduced", 100.0, 70.0, 75.0)]);
        assert!(t.contains("Mesh level `reduced`"), "{t}");
        assert!(!t.contains("per mesh level"), "{t}");
        assert_eq!(text(&[]), "");
    }

    /// The nominal table at the finest level: σ_F0 from the design data
    /// (computed here independently of the section: F_mt/(b m_mn) times the
    /// factors) and the reference's tension over it; zero-torque rows and
    /// coarser levels left out; no rows, no table.
    #[test]
    fn nominal_root_stress_table_sets_the_estimate_beside_the_finest_level() {
        let pair = geometry::design_file::load_pair(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../reference/white_paper_20x43.toml"
        )))
        .unwrap();
        let a = pair.pressure_angle[0];
        let rows = vec![
            row("medium", 700.0, 1.0, 1.0),
            row("reference", 0.0, 0.0, 0.0),
            row("reference", 700.0, 374.2, 309.7),
        ];
        let t = nominal(&rows, &pair, a);
        let n = nominal_root_stress(&pair, a, 700.0);
        let f_mt =
            2.0 * 700.0 / (2.0 * pair.mean_cone_distance * pair.members[0].pitch_angle.sin());
        let by_hand = f_mt / (pair.face_width * pair.normal_module)
            * n.factors[0].y_fa
            * n.factors[0].y_sa
            * (0.25 + 0.75 / n.contact_ratio);
        assert!((n.sigma_pa[0] / by_hand - 1.0).abs() < 1e-12);
        let p = n.sigma_pa[0] * 1e-6;
        let line = format!(
            "| standard_standard | 700 | {p:.1} | 374.2 | {:.2} |",
            374.2 / p
        );
        assert!(t.contains(&line), "{line} not in\n{t}");
        assert_eq!(t.matches("| standard_standard |").count(), 1, "{t}");
        assert!(t.contains("ISO 10300-3:2014 method B1"), "{t}");
        assert_eq!(nominal(&[], &pair, a), "");
    }

    /// The multibody table: 10 rpm against the LTCA (here the wheel's
    /// 161.6 against 160 MPa: +1.00 %, the largest) and the run-up's ratio;
    /// a summary without root tension gives nothing.
    #[test]
    fn multibody_root_tension_is_set_beside_the_ltca_and_the_runup_ratio_computed() {
        use formats::summaries::{
            DynamicSummary, QuasiStaticSummary, RunupRootTension, RunupSummary,
        };
        use geometry::gear_body::Blank;
        let qs = |t: f64, r: Option<[f64; 2]>| QuasiStaticSummary {
            torque_nm: t,
            te_mean_urad: 0.0,
            te_ptp_urad: 0.0,
            steps: 1,
            rejected_steps: 0,
            cpu_s: 0.0,
            cpu_s_per_step: 0.0,
            root_tension_mpa: r,
        };
        let mut d = DynamicSummary {
            pinion_blank: Blank::Standard,
            wheel_blank: Blank::Standard,
            inertia_kgm2: [1.0; 2],
            inertia_source: "scene".into(),
            damping_nm_s_per_rad: 0.0,
            friction_coefficient: 0.0,
            table_positions: 4,
            table_lag_nodes: 8,
            table_build_s: 0.0,
            table_cpu_s_per_position: 0.0,
            quasi_static: vec![qs(300.0, Some([180.0, 161.6]))],
            runup: Some(RunupSummary {
                pinion_torque_nm: 300.0,
                rpm: [0.0, 1000.0],
                sim_time_s: 0.15,
                max_step_s: 1e-5,
                steps: 1,
                rejected_steps: 0,
                cpu_s: 0.0,
                cpu_s_per_step: 0.0,
                te_dynamic_minus_static_urad: [0.0; 2],
                root_tension_mpa: Some(RunupRootTension {
                    dynamic: [200.0, 170.0],
                    quasi_static: [180.0, 160.0],
                }),
            }),
            backlash_urad: None,
            free_play_urad: None,
            rattle: None,
            force_law: "element".into(),
            impact_law: None,
            load_run: None,
            compliant: None,
            ste_dte: None,
            dir: "x".into(),
        };
        let t = multibody(std::slice::from_ref(&d), &[reduced(300.0, 180.0, 160.0)]);
        assert!(
            t.contains(
                "| standard_standard | 300 | 180.0 | 180.0 | +0.00 | 161.6 | 160.0 | +1.00 |"
            ),
            "{t}"
        );
        assert!(t.contains("The largest difference is +1.00 %."), "{t}");
        assert!(
            t.contains("| 200.0 | 180.0 | 1.111 | 170.0 | 160.0 | 1.062 |"),
            "{t}"
        );
        d.quasi_static = vec![qs(300.0, None)];
        d.runup = None;
        assert_eq!(multibody(&[d], &[reduced(300.0, 180.0, 160.0)]), "");
    }

    /// The envelope takes the largest loaded-fillet tension over the teeth
    /// at each rotation of one member and torque, in rotation order.
    #[test]
    fn root_stress_envelope_is_the_largest_over_teeth_per_rotation() {
        let csv = "h
0.5,300,pinion,1,loaded,175,0.5,0.5,-10,0.5,0.5
0,300,pinion,1,loaded,170,0.5,0.5,-10,0.5,0.5
0,300,pinion,2,loaded,40,0.5,0.5,-10,0.5,0.5
0,300,pinion,2,opposite,400,0.5,0.5,-10,0.5,0.5
0,700,pinion,1,loaded,330,0.5,0.5,-20,0.5,0.5
0.5,300,pinion,2,loaded,180,0.5,0.5,-10,0.5,0.5
0,300,wheel,42,loaded,160,0.5,0.5,-10,0.5,0.5
";
        assert_eq!(
            envelope(csv, "pinion", 300.0),
            (vec![0.0, 0.5], vec![170.0, 180.0])
        );
    }
}
