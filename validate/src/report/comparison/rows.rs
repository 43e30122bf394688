//! One row per blank combination and load: the multibody 10 rpm run
//! against the finest reference (and the reduced level's beside it), with
//! the published values of the same load.

use super::published_tables::{published_cpu_row, PubCpu, PubCpuTable};
use super::{read, ComparisonError, Row};
use crate::reference::reference_stage::BlankSummary;
use crate::report::published::PublishedTeTables;
use formats::summaries::DynamicSummary;
use std::path::{Path, PathBuf};

/// Every blank combination's own summary at mesh `level` (runs of
/// different scenes or strides may have written them).
fn level_summaries(
    out: &Path,
    scene: &str,
    level: &str,
) -> Result<Vec<BlankSummary>, ComparisonError> {
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
}

/// The reduced level's summaries and, per blank combination, the finest
/// level's (standard wheel first).
pub(super) fn reference_summaries(
    out: &Path,
    scene: &str,
) -> Result<(Vec<BlankSummary>, Vec<BlankSummary>), ComparisonError> {
    // The finest level of each blank combination judges the reduced model;
    // the reduced level's, when finer ones exist, is the second column.
    let reduced_level = level_summaries(out, scene, "reduced")?;
    let mut rf: Vec<BlankSummary> = Vec::new();
    for level in crate::reference::reference_stage::LEVELS_FINEST_FIRST {
        for r in level_summaries(out, scene, level)? {
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
    Ok((reduced_level, rf))
}

/// The rows of every finest-level summary in `rf` and load that the
/// multibody run `mb` has too.
pub(super) fn build(
    out: &Path,
    scene: &str,
    mb: &[DynamicSummary],
    rf: &[BlankSummary],
    reduced_level: &[BlankSummary],
    pub_te: Option<&PublishedTeTables>,
    pub_cpu: Option<&PubCpuTable>,
) -> Vec<Row> {
    let mut rows = Vec::new();
    for r in rf {
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
    rows
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

#[cfg(test)]
mod tests {
    use super::interpolate;

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
