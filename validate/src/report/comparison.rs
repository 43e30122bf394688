//! Loaded TE of the reduced model (the multibody 10 rpm run, and the
//! quasi-static LTCA) against the reference FE contact, per blank and load:
//! the white paper's Tables 3–5, our way, from the stages' `summary.json`
//! files, with the published values beside them.

use formats::summaries::DynamicSummary;
use geometry::design::PublishedDesign;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

#[derive(Deserialize)]
struct PubTe {
    load_nm: f64,
    mean_te_multibody_urad: f64,
    mean_te_nlfea_urad: f64,
    ptp_te_multibody_urad: f64,
    ptp_te_nlfea_urad: f64,
}

#[derive(Deserialize)]
struct PubTables {
    standard_blank: Vec<PubTe>,
    lightweight_blank: Vec<PubTe>,
}

#[derive(Deserialize)]
struct PubCpu {
    pinion_load_nm: f64,
    blank: String,
    cpu_step_s: f64,
    /// The multibody rows print minutes, the NLFEA rows days.
    cpu_total_min: Option<f64>,
    cpu_total_days: Option<f64>,
}

impl PubCpu {
    /// The printed total CPU in seconds.
    fn total_s(&self) -> Option<f64> {
        self.cpu_total_min
            .map(|m| m * 60.0)
            .or(self.cpu_total_days.map(|d| d * 86_400.0))
    }
}

#[derive(Deserialize)]
struct PubCpuTable {
    multibody: Vec<PubCpu>,
    nlfea_ltca: Vec<PubCpu>,
}

pub use crate::report::comparison_row::Row;

/// The white paper's Table 5 row of wheel blank `blank` at pinion load
/// `torque_nm`, in the multibody or the NLFEA rows `v`.
fn published_cpu_row<'a>(
    v: Option<&'a Vec<PubCpu>>,
    blank: &str,
    torque_nm: f64,
) -> Option<&'a PubCpu> {
    v?.iter()
        .find(|c| c.blank == blank && (c.pinion_load_nm - torque_nm).abs() < 1e-9)
}

/// The comparison: rows and the markdown section.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    pub rows: Vec<Row>,
    #[serde(skip)]
    pub markdown: String,
}

/// A stage's output that exists but cannot be read as this build's type:
/// written by another version, or a field renamed. The report fails rather
/// than leaving a table out.
#[derive(Debug, thiserror::Error)]
pub enum ComparisonError {
    #[error("{}: {message}; run the stage that writes it again", .path.display())]
    Unreadable { path: PathBuf, message: String },
    #[error(transparent)]
    Published(#[from] crate::report::published::PublishedError),
    #[error(transparent)]
    Mixed(#[from] formats::result_set::ResultSetError),
}

/// Reads a stage's JSON output: `Ok(None)` when the file is not there (the
/// stage has not run), an error when it is there and does not parse.
pub fn read<T: for<'de> Deserialize<'de>>(path: &Path) -> Result<Option<T>, ComparisonError> {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => {
            return Err(ComparisonError::Unreadable {
                path: path.to_path_buf(),
                message: e.to_string(),
            })
        }
    };
    serde_json::from_str(&text)
        .map(Some)
        .map_err(|e| ComparisonError::Unreadable {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
}

/// A study kept beside the reference sweep ([`formats::added_files`]).
#[derive(Debug)]
pub enum Study<T> {
    /// Not computed.
    Missing,
    /// Listed with its checksum, unchanged, of the sweep there now (where
    /// it depends on it), and readable as this build's type.
    Current(T),
    /// There, but not to be shown: why.
    NotShown(String),
}

/// Reads the study `<dir>/<rel>` through its registry entry.
pub fn read_study<T: for<'de> Deserialize<'de>>(
    dir: &Path,
    rel: &str,
) -> Result<Study<T>, ComparisonError> {
    use formats::added_files::{read_added, AddedState};
    Ok(match read_added(dir, rel)? {
        AddedState::Missing => Study::Missing,
        AddedState::Current(bytes) => match serde_json::from_slice(&bytes) {
            Ok(v) => Study::Current(v),
            Err(e) => Study::NotShown(format!("written by an older version ({e})")),
        },
        other => Study::NotShown(other.why_not().unwrap_or_default()),
    })
}

/// Builds the comparison from `<out>/<scene>/{multibody,reference}/summary.json`;
/// `published` names the design's published tables; `meshes` is the mesh
/// root, to tell whether the convergence study was computed on today's
/// meshes. `Ok(None)` when either stage has not run.
pub fn compare(
    out: &Path,
    scene: &str,
    published: &PublishedDesign,
    meshes: &Path,
) -> Result<Option<Comparison>, ComparisonError> {
    // The sets put side by side read the same design, meshes and stiffness
    // files wherever they share one.
    let mut sets = vec![
        out.join(scene).join("ltca"),
        out.join(scene).join("multibody"),
    ];
    sets.extend(
        crate::reference::reference_stage::LEVELS_FINEST_FIRST
            .iter()
            .map(|l| crate::reference::reference_stage::reference_dir(out, scene, l)),
    );
    for d in &sets {
        formats::result_set::verify_files(d)?;
    }
    formats::result_set::check_same_inputs(&sets.iter().map(|p| p.as_path()).collect::<Vec<_>>())?;
    let Some(mb) = read::<Vec<DynamicSummary>>(&out.join(scene).join("multibody/summary.json"))?
    else {
        return Ok(None);
    };
    // Every blank combination's own summary (runs of different scenes or
    // strides may have written them), per mesh level.
    let summaries = |level: &str| -> Result<
        Vec<crate::reference::reference_stage::BlankSummary>,
        ComparisonError,
    > {
        let mut v = Vec::new();
        if let Ok(d) = std::fs::read_dir(crate::reference::reference_stage::reference_dir(
            out, scene, level,
        )) {
            // One folder per blank pair (the studies' JSON files sit beside them).
            let mut dirs: Vec<PathBuf> = d
                .filter_map(|e| e.ok())
                .map(|e| e.path())
                .filter(|p| p.is_dir())
                .collect();
            dirs.sort();
            for p in dirs {
                v.extend(read(&p.join("summary.json"))?);
            }
        }
        Ok(v)
    };
    // The finest level of each blank combination judges the reduced model;
    // the reduced level's, when finer ones exist, is the second column.
    let reduced_level = summaries("reduced")?;
    let mut rf: Vec<crate::reference::reference_stage::BlankSummary> = Vec::new();
    for level in crate::reference::reference_stage::LEVELS_FINEST_FIRST {
        for r in summaries(level)? {
            if !rf
                .iter()
                .any(|q| q.pinion_blank == r.pinion_blank && q.wheel_blank == r.wheel_blank)
            {
                rf.push(r);
            }
        }
    }
    // Standard wheel first, as in the white paper's tables.
    rf.sort_by_key(|r| (r.pinion_blank.clone(), r.wheel_blank != "standard"));
    if rf.is_empty() {
        return Ok(None);
    }
    let pub_te: Option<PubTables> = published
        .loaded_te
        .as_deref()
        .map(crate::report::published::read_toml)
        .transpose()?;
    let pub_cpu: Option<PubCpuTable> = published
        .cpu
        .as_deref()
        .map(crate::report::published::read_toml)
        .transpose()?;
    let mut rows = Vec::new();
    for r in &rf {
        let Some(m) = mb.iter().find(|m| {
            m.pinion_blank.name() == r.pinion_blank && m.wheel_blank.name() == r.wheel_blank
        }) else {
            continue;
        };
        for l in &r.loads {
            let Some(q) = m
                .quasi_static
                .iter()
                .find(|q| (q.torque_nm - l.torque_nm).abs() < 1e-9)
            else {
                continue;
            };
            let table = pub_te.as_ref().map(|p| match r.wheel_blank.as_str() {
                "lightweight" => &p.lightweight_blank,
                _ => &p.standard_blank,
            });
            let pt = table.and_then(|t| t.iter().find(|p| (p.load_nm - l.torque_nm).abs() < 1e-9));
            let pub_mb = published_cpu_row(
                pub_cpu.as_ref().map(|c| &c.multibody),
                &r.wheel_blank,
                l.torque_nm,
            );
            let pub_fe = published_cpu_row(
                pub_cpu.as_ref().map(|c| &c.nlfea_ltca),
                &r.wheel_blank,
                l.torque_nm,
            );
            let blank = format!("{}_{}", r.pinion_blank, r.wheel_blank);
            let sampled = multibody_at_reference(out, scene, &blank, l.torque_nm);
            let coarse = (r.level != "reduced")
                .then(|| {
                    reduced_level
                        .iter()
                        .find(|q| {
                            q.pinion_blank == r.pinion_blank && q.wheel_blank == r.wheel_blank
                        })?
                        .loads
                        .iter()
                        .find(|q| (q.torque_nm - l.torque_nm).abs() < 1e-9)
                })
                .flatten();
            let sampled_coarse = coarse.and_then(|_| {
                multibody_at(
                    out,
                    scene,
                    &crate::reference::reference_stage::reference_dir(out, scene, "reduced")
                        .join(&blank),
                    &blank,
                    l.torque_nm,
                )
            });
            rows.push(Row {
                pinion_blank: r.pinion_blank.clone(),
                wheel_blank: r.wheel_blank.clone(),
                torque_nm: l.torque_nm,
                multibody_te_mean_urad: q.te_mean_urad,
                multibody_te_ptp_urad: q.te_ptp_urad,
                reference_te_mean_urad: l.te_mean_urad,
                reference_te_ptp_urad: l.te_ptp_urad,
                multibody_at_reference_mean_urad: sampled.map(|v| v.0),
                multibody_at_reference_ptp_urad: sampled.map(|v| v.1),
                te_mean_difference_pct: (sampled.map_or(q.te_mean_urad, |v| v.0) - l.te_mean_urad)
                    / l.te_mean_urad
                    * 100.0,
                te_ptp_difference_pct: (sampled.map_or(q.te_ptp_urad, |v| v.1) - l.te_ptp_urad)
                    / l.te_ptp_urad
                    * 100.0,
                reference_penalty_difference_pct: l.penalty_difference_pct,
                reference_max_pressure_mpa: l.max_pressure_mpa,
                multibody_steps: q.steps,
                multibody_cpu_s_per_step: q.cpu_s_per_step,
                multibody_cpu_s: q.cpu_s,
                multibody_table_cpu_s: m.table_cpu_s_per_position * m.table_positions as f64,
                reference_positions: r.positions,
                reference_cpu_s_per_position: r.cpu_s_per_position,
                reference_cpu_s: r.total_cpu_s,
                reference_level: r.level.clone(),
                reduced_level_reference_te_mean_urad: coarse.map(|c| c.te_mean_urad),
                reduced_level_reference_te_ptp_urad: coarse.map(|c| c.te_ptp_urad),
                reduced_level_te_mean_difference_pct: coarse.map(|c| {
                    (sampled_coarse.map_or(q.te_mean_urad, |v| v.0) - c.te_mean_urad)
                        / c.te_mean_urad
                        * 100.0
                }),
                reduced_level_te_ptp_difference_pct: coarse.map(|c| {
                    (sampled_coarse.map_or(q.te_ptp_urad, |v| v.1) - c.te_ptp_urad) / c.te_ptp_urad
                        * 100.0
                }),
                published_multibody_te_mean_urad: pt.map(|p| p.mean_te_multibody_urad),
                published_nlfea_te_mean_urad: pt.map(|p| p.mean_te_nlfea_urad),
                published_multibody_te_ptp_urad: pt.map(|p| p.ptp_te_multibody_urad),
                published_nlfea_te_ptp_urad: pt.map(|p| p.ptp_te_nlfea_urad),
                published_multibody_cpu_s_per_step: pub_mb.map(|c| c.cpu_step_s),
                published_nlfea_cpu_s_per_step: pub_fe.map(|c| c.cpu_step_s),
                published_multibody_cpu_total_s: pub_mb.and_then(PubCpu::total_s),
                published_nlfea_cpu_total_s: pub_fe.and_then(PubCpu::total_s),
            });
        }
    }
    let ref_dir = out.join(scene).join("reference");
    let shown = |rel: &str, why: &str, cmd: &str| {
        format!(
            "Not shown: {} is {why}; `{cmd}` recomputes it.",
            ref_dir.join(rel).display()
        )
    };
    let conv =
        read_study::<crate::studies::convergence::Convergence>(&ref_dir, "convergence.json")?;
    let conv_current = match &conv {
        Study::Current(c) if c.stale_levels(&meshes.join(scene)).is_empty() => Some(c),
        _ => None,
    };
    let line_load = other_note(read_study::<crate::studies::line_load::LineLoad>(
        &ref_dir,
        "line_load.json",
    )?);
    let line_load_current = line_load
        .as_ref()
        .and_then(|l| l.as_ref().ok())
        .filter(|l| l.current(&meshes.join(scene)));
    let mut markdown = markdown(&rows, &rf, conv_current);
    crate::report::differences::breakdown(
        &mut markdown,
        &rows,
        &rf,
        conv_current,
        line_load_current,
    );
    for r in &rf {
        let blank = format!("{}_{}", r.pinion_blank, r.wheel_blank);
        if let Some(line) = crate::report::differences::pattern_peak(out, scene, &blank) {
            let _ = writeln!(markdown, "{line}\n");
        }
    }
    if let Some(mu) = mb
        .iter()
        .map(|b| b.friction_coefficient)
        .find(|&mu| mu > 0.0)
    {
        let _ = writeln!(
            markdown,
            "Note: the reduced model ran with Coulomb friction μ = {mu}; the reference contact is frictionless, so part of the difference is friction.\n"
        );
    }
    const CONV: &str = "\n## Mesh convergence of the reference\n";
    match conv {
        Study::Missing => {}
        Study::NotShown(why) => {
            let _ = writeln!(
                markdown,
                "{CONV}\n{}",
                shown("convergence.json", &why, "make convergence")
            );
        }
        Study::Current(c) => {
            let stale = c.stale_levels(&meshes.join(scene));
            if stale.is_empty() {
                convergence_markdown(&mut markdown, &c);
            } else {
                let _ = writeln!(
                    markdown,
                    "{CONV}\nNot shown: the meshes of level(s) {} changed since the study ran; `make convergence` recomputes it.",
                    stale.join(", ")
                );
            }
        }
    }
    const LINE: &str = "\n## Line load: global FE + Weber–Banaschek against fine-mesh FE\n";
    match line_load {
        None => {}
        Some(Err(why)) => {
            let _ = writeln!(
                markdown,
                "{LINE}\n{}",
                shown("line_load.json", &why, "make convergence")
            );
        }
        Some(Ok(l)) if l.current(&meshes.join(scene)) => l.markdown(&mut markdown),
        Some(Ok(_)) => {
            let _ = writeln!(
                markdown,
                "{LINE}\nNot shown: the meshes changed since {} was computed; `make convergence` recomputes it.",
                ref_dir.join("line_load.json").display()
            );
        }
    }
    match read_study::<Vec<crate::studies::tradeoff::Point>>(&ref_dir, "tradeoff.json")? {
        Study::Missing => {}
        Study::Current(t) => tradeoff_markdown(&mut markdown, &t),
        Study::NotShown(why) => {
            let _ = writeln!(
                markdown,
                "\n## Reduced model: run time against error (slices per tooth pair)\n\n{}",
                shown("tradeoff.json", &why, "validate tradeoff")
            );
        }
    }
    Ok(Some(Comparison { rows, markdown }))
}

/// A study as an option: missing `None`, current `Some(Ok)`, there but
/// not to be shown `Some(Err(why))`.
fn other_note<T>(s: Study<T>) -> Option<Result<T, String>> {
    match s {
        Study::Missing => None,
        Study::Current(v) => Some(Ok(v)),
        Study::NotShown(why) => Some(Err(why)),
    }
}

/// Linear interpolation of (x, y) (x increasing) at `at`; None outside.
pub fn interpolate(x: &[f64], y: &[f64], at: f64) -> Option<f64> {
    let inside = !x.is_empty() && at >= x[0] && at <= x[x.len() - 1] + 1e-9;
    inside.then(|| solver::multibody::model::interpolate(x, y, at))
}

/// Mean and peak-to-peak of the multibody TE at the positions of the
/// finest reference of `blank`.
fn multibody_at_reference(out: &Path, scene: &str, blank: &str, t: f64) -> Option<(f64, f64)> {
    let dir = crate::reference::reference_stage::finest_reference(out, scene, blank)?;
    multibody_at(out, scene, &dir, blank, t)
}

/// Mean and peak-to-peak of the multibody TE at the positions of the
/// reference results in `dir`.
fn multibody_at(out: &Path, scene: &str, dir: &Path, blank: &str, t: f64) -> Option<(f64, f64)> {
    use crate::report::figures::{column, read_csv};
    let mb = read_csv(
        &out.join(scene)
            .join("multibody")
            .join(blank)
            .join(format!("quasi_static_{t}nm.csv")),
    )?;
    let rf = read_csv(&dir.join("te.csv"))?;
    use formats::columns::{PINION_ROTATION_DEG, TE_URAD};
    let (x, y) = (column(&mb, PINION_ROTATION_DEG)?, column(&mb, TE_URAD)?);
    let v: Vec<f64> = column(&rf, PINION_ROTATION_DEG)?
        .iter()
        .map(|&a| interpolate(x, y, a))
        .collect::<Option<_>>()?;
    Some(solver::ltca::mean_ptp(&v))
}

fn opt(v: Option<f64>, digits: usize) -> String {
    v.map_or("–".into(), |x| format!("{x:.digits$}"))
}

fn markdown(
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

fn convergence_markdown(s: &mut String, c: &crate::studies::convergence::Convergence) {
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

fn tradeoff_markdown(s: &mut String, pts: &[crate::studies::tradeoff::Point]) {
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

#[cfg(test)]
mod tests {
    use super::{interpolate, PubCpu};

    /// Table 5 prints the multibody totals in minutes and the NLFEA totals
    /// in days: both come out in seconds (4.0 min, 0.9 days as printed).
    #[test]
    fn published_cpu_totals_are_in_seconds() {
        let row = |min, days| PubCpu {
            pinion_load_nm: 300.0,
            blank: "standard".into(),
            cpu_step_s: 0.8,
            cpu_total_min: min,
            cpu_total_days: days,
        };
        assert_eq!(row(Some(4.0), None).total_s(), Some(240.0));
        assert_eq!(row(None, Some(0.9)).total_s(), Some(77_760.0));
        assert_eq!(row(None, None).total_s(), None);
    }

    /// A straight line is reproduced between samples; outside the samples
    /// there is no value.
    #[test]
    fn interpolation_of_a_line_and_its_ends() {
        let x = [0.0, 1.0, 3.0];
        let y = [1.0, 3.0, 7.0];
        assert_eq!(interpolate(&x, &y, 2.0), Some(5.0));
        assert_eq!(interpolate(&x, &y, 0.0), Some(1.0));
        assert_eq!(interpolate(&x, &y, 3.0), Some(7.0));
        assert_eq!(interpolate(&x, &y, 3.5), None);
        assert_eq!(interpolate(&x, &y, -0.1), None);
    }
}

#[cfg(test)]
mod read_tests {
    use super::*;

    /// A summary that is there but does not parse as this build's type (a
    /// field renamed by another version) is an error naming the file, not a
    /// missing table.
    #[test]
    fn summary_with_a_renamed_field_is_an_error_not_a_missing_table() {
        let dir = tempfile::tempdir().unwrap();
        let mb = dir.path().join("s/multibody");
        std::fs::create_dir_all(&mb).unwrap();
        assert!(
            compare(dir.path(), "s", &PublishedDesign::default(), dir.path())
                .unwrap()
                .is_none()
        );
        std::fs::write(
            mb.join("summary.json"),
            r#"[{"pinion_blank": "standard", "wheel_blank": "standard", "quasi_static_renamed": []}]"#,
        )
        .unwrap();
        let err = compare(dir.path(), "s", &PublishedDesign::default(), dir.path())
            .unwrap_err()
            .to_string();
        assert!(err.contains("multibody/summary.json"), "{err}");
    }

    /// A multibody set and an LTCA set stamped with different stiffness
    /// files (one rerun after `preprocess stiffness`, the other not) are
    /// refused by the report, naming the file and both runs.
    #[test]
    fn ltca_and_multibody_sets_from_other_stiffness_files_are_refused() {
        use formats::result_set::ResultSet;
        let dir = tempfile::tempdir().unwrap();
        let write = |stage: &str, sha: &str| {
            let mut set = ResultSet::begin(&dir.path().join("s").join(stage), stage).unwrap();
            set.record_input("design", "d0").unwrap();
            set.record_input("stiffness:pinion_standard_reduced", sha)
                .unwrap();
            set.commit().unwrap();
        };
        write("ltca", "aaaaaaaaaaaaaaaa");
        write("multibody", "aaaaaaaaaaaaaaaa");
        assert!(
            compare(dir.path(), "s", &PublishedDesign::default(), dir.path())
                .unwrap()
                .is_none()
        );
        write("multibody", "bbbbbbbbbbbbbbbb");
        let err = compare(dir.path(), "s", &PublishedDesign::default(), dir.path())
            .unwrap_err()
            .to_string();
        for w in [
            "stiffness:pinion_standard_reduced",
            "ltca",
            "multibody",
            "aaaaaaaaaaaa",
            "bbbbbbbbbbbb",
        ] {
            assert!(err.contains(w), "{w} not in: {err}");
        }
    }

    #[test]
    fn study_changed_after_it_was_written_is_not_shown() {
        use super::{read_study, Study};
        use formats::added_files::{add_json, Dependence};
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("reference");
        std::fs::create_dir_all(&dir).unwrap();
        let lock = formats::result_set::RunLock::shared(&dir, "study").unwrap();
        add_json(&lock, "a.json", &vec![1.0, 2.0], Dependence::Beside).unwrap();
        add_json(&lock, "b.json", &"text", Dependence::Beside).unwrap();
        drop(lock);
        assert!(matches!(
            read_study::<Vec<f64>>(&dir, "a.json").unwrap(),
            Study::Current(v) if v == [1.0, 2.0]
        ));
        // Registered but not this build's type.
        match read_study::<Vec<f64>>(&dir, "b.json").unwrap() {
            Study::NotShown(why) => assert!(why.contains("older version"), "{why}"),
            other => panic!("{other:?}"),
        }
        // A number edited by hand.
        std::fs::write(dir.join("a.json"), "[1.0, 2.5]").unwrap();
        match read_study::<Vec<f64>>(&dir, "a.json").unwrap() {
            Study::NotShown(why) => assert!(why.contains("changed"), "{why}"),
            other => panic!("{other:?}"),
        }
        // Written without a registry entry.
        std::fs::write(dir.join("c.json"), "[3.0]").unwrap();
        match read_study::<Vec<f64>>(&dir, "c.json").unwrap() {
            Study::NotShown(why) => assert!(why.contains("not listed"), "{why}"),
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            read_study::<Vec<f64>>(&dir, "d.json").unwrap(),
            Study::Missing
        ));
    }
}
