//! The report's "The reference's own uncertainty" section: the reference FE
//! sweeps of every mesh level that ran (`reference/`, `reference_medium/`,
//! `reference_reference/` under `<out>/<scene>/`), their mean and
//! peak-to-peak TE per blank pair and load, how far the finest level is
//! from its mesh limit (Richardson over three levels where the differences
//! are monotone, else the difference of the two finest levels) and from
//! its rigid-contact limit (the two penalty factors), how far it moves with
//! the contact formulation (a pinion-slave sweep, `reference_<level>_
//! pinion_slave/`, against the two-pass one at the positions both solved),
//! and the reduced model's difference to the finest level beside that
//! uncertainty.
//!
//! A verdict in the section is a function of the numbers it judges
//! ([`judge`], [`pressure_trend`]), each with tests of its outcomes.

use crate::reference::reference_ltca::ContactPasses;
use crate::reference::reference_stage::{
    reference_dir, reference_dir_with, BlankSummary, LEVELS_FINEST_FIRST,
};
use crate::report::comparison::{read, ComparisonError};
use crate::report::comparison_row::Row;
use crate::report::figures::{column, read_csv, Csv};
use crate::studies::convergence::richardson;
use geometry::scene::{FlankElements, Scene};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

/// The accuracy asked of the reduced model's peak-to-peak TE against the
/// reference, %.
pub const PTP_TARGET_PCT: f64 = 3.0;
/// The accuracy asked of the reduced model's mean TE, %.
pub const MEAN_TARGET_PCT: f64 = 1.0;
/// Loads from which the sentences judge (below it the TE is mostly the
/// unloaded geometry's and the light-load contact is another question).
pub const VERDICT_FROM_NM: f64 = 100.0;

/// One mesh level's sweep at one load.
#[derive(Debug, Clone, Serialize)]
pub struct LevelValue {
    pub level: String,
    /// Flank elements (profile × face) of the level.
    pub elements: [u32; 2],
    /// Relative element size 1/√(profile · face).
    pub h: f64,
    pub mean_urad: f64,
    pub ptp_urad: f64,
    /// TE extrapolated to the rigid contact (infinite penalty), µrad.
    pub rigid_mean_urad: Option<f64>,
    pub rigid_ptp_urad: Option<f64>,
    pub max_pressure_mpa: f64,
    pub positions: usize,
}

/// How far the finest level's value is from the mesh limit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Estimate {
    /// Three levels converging monotonically with an observed order of at
    /// least the convergence study's smallest: order and limit.
    Richardson { order: f64, limit: f64 },
    /// Not monotone, or two levels: the two finest levels' difference is
    /// the uncertainty.
    Spread,
}

/// The finest level's uncertainty of one quantity.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Uncertainty {
    pub estimate: Estimate,
    /// |finest − limit| (Richardson) or |finest − next finest| (spread),
    /// relative to the finest value, %.
    pub pct: f64,
    /// Levels it was estimated from.
    pub levels: usize,
}

/// The uncertainty of the finest of the values `f` at relative element
/// sizes `h` (coarse to fine); None with fewer than two levels.
pub fn uncertainty(h: &[f64], f: &[f64]) -> Option<Uncertainty> {
    let n = f.len();
    if n < 2 || h.len() != n {
        return None;
    }
    let fine = f[n - 1];
    let three = (n >= 3)
        .then(|| {
            richardson(
                [h[n - 3], h[n - 2], h[n - 1]],
                [f[n - 3], f[n - 2], f[n - 1]],
            )
        })
        .flatten();
    // As the convergence study: below its smallest order the levels are
    // not yet in the asymptotic range.
    let three = three.filter(|(order, _)| *order >= crate::studies::convergence::MIN_ORDER);
    Some(match three {
        Some((order, limit)) => Uncertainty {
            estimate: Estimate::Richardson { order, limit },
            pct: ((fine - limit) / fine).abs() * 100.0,
            levels: n,
        },
        None => Uncertainty {
            estimate: Estimate::Spread,
            pct: ((fine - f[n - 2]) / fine).abs() * 100.0,
            levels: n,
        },
    })
}

/// The contact formulation's share at one load: the pinion-slave sweep
/// against the two-pass sweep of the same mesh level, over the positions
/// both solved.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FormulationShare {
    pub level: String,
    pub positions: usize,
    pub two_pass_mean_urad: f64,
    pub pinion_slave_mean_urad: f64,
    pub two_pass_ptp_urad: f64,
    pub pinion_slave_ptp_urad: f64,
    /// (pinion-slave − two-pass) / two-pass, %.
    pub mean_pct: f64,
    pub ptp_pct: f64,
    /// The rotations both solved, deg.
    #[serde(skip)]
    pub rotations_deg: Vec<f64>,
    /// The reduced model (the multibody run at 10 rpm, sampled at the same
    /// rotations) against the pinion-slave sweep: (reduced − pinion-slave)
    /// / pinion-slave, % (mean, ptp).
    pub reduced_pct: Option<[f64; 2]>,
}

/// Rotations of two sweeps that agree within this, deg.
const SAME_ROTATION_DEG: f64 = 1e-6;

/// The share from the two sweeps' TE tables (`te.csv`) at torque `t`:
/// mean and peak-to-peak over the rotations both hold. None with fewer
/// than two common rotations or without the load's column.
pub fn formulation_share(
    two_pass: &Csv,
    pinion_slave: &Csv,
    t: f64,
    level: &str,
) -> Option<FormulationShare> {
    let col = format!("te_{t}nm_urad");
    let (r2, v2) = (
        column(two_pass, "pinion_rotation_deg")?,
        column(two_pass, &col)?,
    );
    let (r1, v1) = (
        column(pinion_slave, "pinion_rotation_deg")?,
        column(pinion_slave, &col)?,
    );
    let (rotations_deg, pairs): (Vec<f64>, Vec<(f64, f64)>) = r1
        .iter()
        .zip(v1)
        .filter_map(|(&r, &b)| {
            let k = r2.iter().position(|x| (x - r).abs() <= SAME_ROTATION_DEG)?;
            Some((r, (v2[k], b)))
        })
        .unzip();
    if pairs.len() < 2 {
        return None;
    }
    let (two, one): (Vec<f64>, Vec<f64>) = pairs.iter().copied().unzip();
    let (m2, p2) = solver::ltca::mean_ptp(&two);
    let (m1, p1) = solver::ltca::mean_ptp(&one);
    Some(FormulationShare {
        level: level.to_string(),
        positions: pairs.len(),
        two_pass_mean_urad: m2,
        pinion_slave_mean_urad: m1,
        two_pass_ptp_urad: p2,
        pinion_slave_ptp_urad: p1,
        mean_pct: (m1 - m2) / m2 * 100.0,
        ptp_pct: (p1 - p2) / p2 * 100.0,
        rotations_deg,
        reduced_pct: None,
    })
}

/// `share` with the reduced model's TE `te` (µrad) at pinion rotations
/// `rotation_deg` (increasing) compared at the share's rotations, linear
/// between samples; unchanged where a rotation lies outside the samples.
pub fn with_reduced(
    mut share: FormulationShare,
    rotation_deg: &[f64],
    te: &[f64],
) -> FormulationShare {
    use crate::report::comparison::interpolate;
    let v: Option<Vec<f64>> = share
        .rotations_deg
        .iter()
        .map(|&a| interpolate(rotation_deg, te, a))
        .collect();
    if let Some(v) = v.filter(|v| !v.is_empty()) {
        let (m, p) = solver::ltca::mean_ptp(&v);
        share.reduced_pct = Some([
            (m - share.pinion_slave_mean_urad) / share.pinion_slave_mean_urad * 100.0,
            (p - share.pinion_slave_ptp_urad) / share.pinion_slave_ptp_urad * 100.0,
        ]);
    }
    share
}

/// One sentence per blank pair: the reduced model against the pinion-slave
/// sweep over the loads from `from_nm` on, judged against the targets.
pub fn pinion_slave_sentence(blank: &str, rows: &[&LoadRow], from_nm: f64) -> Option<String> {
    let d: Vec<[f64; 2]> = rows
        .iter()
        .filter(|r| r.torque_nm >= from_nm)
        .filter_map(|r| r.formulation.as_ref()?.reduced_pct)
        .collect();
    if d.is_empty() {
        return None;
    }
    let part = |k: usize, target: f64, what: &str| {
        let within = d.iter().filter(|x| x[k].abs() <= target).count();
        let worst = d.iter().map(|x| x[k].abs()).fold(0.0, f64::max);
        let verdict = if within == d.len() {
            format!("within {target} % at all {} loads", d.len())
        } else {
            format!("within {target} % at {within} of the {} loads", d.len())
        };
        format!("its {what} {verdict} (at most {worst:.2} %)")
    };
    Some(format!(
        "- Against the pinion-slave sweep at its own positions ({}, loads from {from_nm} N·m on), the reduced model's multibody run has {}, {}.",
        blank.replace('_', " / "),
        part(0, MEAN_TARGET_PCT, "mean TE"),
        part(1, PTP_TARGET_PCT, "peak-to-peak TE")
    ))
}

/// The reference's uncertainty that a verdict weighs, %: the larger of the
/// mesh's and the contact formulation's, whichever are known.
pub fn reference_pct(mesh: Option<Uncertainty>, formulation_pct: Option<f64>) -> Option<f64> {
    match (mesh.map(|u| u.pct), formulation_pct.map(f64::abs)) {
        (Some(a), Some(b)) => Some(a.max(b)),
        (a, b) => a.or(b),
    }
}

/// What the reduced model's difference `diff_pct` to the finest reference
/// amounts to, with the target `target_pct` and the reference's own
/// uncertainty `reference_pct` (%).
pub fn judge(diff_pct: f64, target_pct: f64, reference_pct: Option<f64>) -> &'static str {
    if diff_pct.abs() <= target_pct {
        "within the target"
    } else if reference_pct.is_some_and(|u| diff_pct.abs() <= u) {
        "within the reference's uncertainty"
    } else {
        "outside both"
    }
}

/// How the peak pressure changes over the levels, coarse to fine.
pub fn pressure_trend(p: &[f64]) -> &'static str {
    use crate::report::trend::{trend, Trend};
    match trend(p) {
        Trend::Single => "one level only",
        Trend::Rises => "grows with every refinement",
        Trend::Falls => "falls with every refinement",
        Trend::Neither => "changes direction between refinements",
    }
}

/// One blank pair and load over the levels.
#[derive(Debug, Clone, Serialize)]
pub struct LoadRow {
    pub blank: String,
    pub torque_nm: f64,
    /// Coarse to fine.
    pub levels: Vec<LevelValue>,
    pub mean: Option<Uncertainty>,
    pub ptp: Option<Uncertainty>,
    /// (finest − its rigid limit) / finest, %.
    pub penalty_mean_pct: Option<f64>,
    pub penalty_ptp_pct: Option<f64>,
    /// The reduced model against the finest level, % (from the loaded-TE
    /// comparison), when it judges against that level.
    pub reduced_mean_difference_pct: Option<f64>,
    pub reduced_ptp_difference_pct: Option<f64>,
    /// The contact formulation's share at the finest level that has a
    /// pinion-slave sweep.
    pub formulation: Option<FormulationShare>,
}

/// The section's numbers and markdown.
#[derive(Debug, Clone, Default, Serialize)]
pub struct ReferenceUncertainty {
    pub rows: Vec<LoadRow>,
    #[serde(skip)]
    pub markdown: String,
}

fn elements(scene: &Scene, level: &str) -> Option<FlankElements> {
    match level {
        "reduced" => Some(scene.mesh.reduced_order),
        "medium" => Some(scene.mesh.medium()),
        "reference" => Some(scene.mesh.reference),
        _ => None,
    }
}

/// Reads every level's blank summaries of `scene` under `out` and builds
/// the section; `rows` are the loaded-TE comparison's rows. A summary that
/// is there but cannot be read is an error, not a level left out.
pub fn build(
    out: &Path,
    scene: &Scene,
    rows: &[Row],
) -> Result<ReferenceUncertainty, ComparisonError> {
    let mut per: Vec<(String, String, BlankSummary)> = Vec::new();
    for &level in LEVELS_FINEST_FIRST.iter().rev() {
        let dir = reference_dir(out, &scene.name, level);
        let Ok(d) = std::fs::read_dir(&dir) else {
            continue;
        };
        let mut dirs: Vec<_> = d
            .filter_map(|e| e.ok())
            .map(|e| e.path())
            .filter(|p| p.join("summary.json").exists())
            .collect();
        dirs.sort();
        for p in dirs {
            let Some(s) = read::<BlankSummary>(&p.join("summary.json"))? else {
                continue;
            };
            let blank = format!("{}_{}", s.pinion_blank, s.wheel_blank);
            per.push((level.to_string(), blank, s));
        }
    }
    let mut blanks: Vec<String> = per.iter().map(|p| p.1.clone()).collect();
    blanks.sort_by_key(|b| (!b.ends_with("_standard"), b.clone()));
    blanks.dedup();
    let mut out_rows = Vec::new();
    for blank in &blanks {
        let of_blank: Vec<&(String, String, BlankSummary)> =
            per.iter().filter(|p| &p.1 == blank).collect();
        let Some(first) = of_blank.first() else {
            continue;
        };
        // The two-pass and pinion-slave TE tables of each level that has
        // both (finest first), read once for all loads.
        let sweeps: Vec<(&str, Csv, Csv)> = LEVELS_FINEST_FIRST
            .iter()
            .filter_map(|&level| {
                let te = |dir: std::path::PathBuf| read_csv(&dir.join(blank).join("te.csv"));
                Some((
                    level,
                    te(reference_dir(out, &scene.name, level))?,
                    te(reference_dir_with(
                        out,
                        &scene.name,
                        level,
                        ContactPasses::PinionSlave,
                    ))?,
                ))
            })
            .collect();
        for load in &first.2.loads {
            let t = load.torque_nm;
            let mut levels: Vec<LevelValue> = of_blank
                .iter()
                .filter_map(|(level, _, s)| {
                    let e = elements(scene, level)?;
                    let l = s.loads.iter().find(|l| (l.torque_nm - t).abs() < 1e-9)?;
                    Some(LevelValue {
                        level: level.clone(),
                        elements: [e.profile, e.face],
                        h: 1.0 / (e.profile as f64 * e.face as f64).sqrt(),
                        mean_urad: l.te_mean_urad,
                        ptp_urad: l.te_ptp_urad,
                        rigid_mean_urad: l.te_rigid_mean_urad,
                        rigid_ptp_urad: l.te_rigid_ptp_urad,
                        max_pressure_mpa: l.max_pressure_mpa,
                        positions: s.positions,
                    })
                })
                .collect();
            levels.sort_by(|a, b| b.h.total_cmp(&a.h));
            let h: Vec<f64> = levels.iter().map(|l| l.h).collect();
            let mean: Vec<f64> = levels.iter().map(|l| l.mean_urad).collect();
            let ptp: Vec<f64> = levels.iter().map(|l| l.ptp_urad).collect();
            let fine = levels.last();
            let share = |v: f64, r: Option<f64>| r.map(|r| (v - r) / v * 100.0);
            let reduced = rows.iter().find(|r| {
                format!("{}_{}", r.pinion_blank, r.wheel_blank) == *blank
                    && (r.torque_nm - t).abs() < 1e-9
                    && fine.is_some_and(|f| f.level == r.reference_level)
            });
            let formulation = sweeps.iter().find_map(|(level, two, one)| {
                let share = formulation_share(two, one, t, level)?;
                let mb = read_csv(
                    &out.join(&scene.name)
                        .join("multibody")
                        .join(blank)
                        .join(format!("quasi_static_{t}nm.csv")),
                );
                use formats::columns::{PINION_ROTATION_DEG, TE_URAD};
                Some(
                    match mb.as_ref().and_then(|mb| {
                        Some((column(mb, PINION_ROTATION_DEG)?, column(mb, TE_URAD)?))
                    }) {
                        Some((x, y)) => with_reduced(share, x, y),
                        None => share,
                    },
                )
            });
            out_rows.push(LoadRow {
                formulation,
                blank: blank.clone(),
                torque_nm: t,
                mean: uncertainty(&h, &mean),
                ptp: uncertainty(&h, &ptp),
                penalty_mean_pct: fine.and_then(|f| share(f.mean_urad, f.rigid_mean_urad)),
                penalty_ptp_pct: fine.and_then(|f| share(f.ptp_urad, f.rigid_ptp_urad)),
                reduced_mean_difference_pct: reduced.map(|r| r.te_mean_difference_pct),
                reduced_ptp_difference_pct: reduced.map(|r| r.te_ptp_difference_pct),
                levels,
            });
        }
    }
    let markdown = markdown(&out_rows);
    Ok(ReferenceUncertainty {
        rows: out_rows,
        markdown,
    })
}

const MIN: f64 = crate::studies::convergence::MIN_ORDER;

fn estimate_text(u: Option<Uncertainty>) -> String {
    match u {
        Some(Uncertainty {
            estimate: Estimate::Richardson { order, limit },
            pct,
            ..
        }) => format!("{limit:.2} (order {order:.1}); {pct:.1} %"),
        Some(Uncertainty {
            estimate: Estimate::Spread,
            pct,
            levels: 2,
        }) => format!("two levels only; {pct:.1} % (their difference)"),
        Some(Uncertainty {
            estimate: Estimate::Spread,
            pct,
            ..
        }) => format!("not monotone or order below {MIN}; {pct:.1} % (two finest)"),
        None => "one level".into(),
    }
}

fn opt_pct(v: Option<f64>) -> String {
    v.map_or("–".into(), |x| format!("{x:+.2} %"))
}

/// The section's markdown from its rows.
pub fn markdown(rows: &[LoadRow]) -> String {
    let mut s = String::new();
    if rows.is_empty() {
        return s;
    }
    let _ = writeln!(
        s,
        "### The reference's own uncertainty: mesh levels, penalty and contact formulation\n"
    );
    let _ = writeln!(
        s,
        "The reference FE sweep on every mesh level that ran, the same positions and loads. The finest level's uncertainty is its distance from the mesh limit: Richardson's extrapolation over three levels where the three values change monotonically (observed order and limit), else the difference of the two finest levels. The penalty's share is the finest level's distance from its rigid-contact limit (TE at the two penalty factors, TE(p) = TE∞ + c/p per position). The contact formulation's share is how far a sweep that enforces only the pinion's nodes against the wheel's faces (pinion-slave) lies from the two-pass reference at the positions both solved: the two differ where the contact runs onto a flank edge, and neither is known to be the better there (an independent code would tell). The reduced model's difference to the finest level (the loaded-TE table's) stands beside them, judged against the {MEAN_TARGET_PCT} % (mean) and {PTP_TARGET_PCT} % (peak-to-peak) targets and the reference's uncertainty, the larger of the mesh's and the formulation's.\n"
    );
    let _ = writeln!(
        s,
        "| blanks | N·m | levels (profile × face) | mean TE per level, µrad | mesh limit of the mean (order); uncertainty | ptp TE per level, µrad | mesh limit of the ptp (order); uncertainty | penalty share mean / ptp | contact formulation: pinion-slave against two-pass mean / ptp (level, positions) | reduced model mean / ptp against the finest | verdict mean / ptp |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|");
    for r in rows {
        let join = |f: &dyn Fn(&LevelValue) -> String| {
            r.levels.iter().map(f).collect::<Vec<_>>().join(" / ")
        };
        let verdict = match (r.reduced_mean_difference_pct, r.reduced_ptp_difference_pct) {
            (Some(m), Some(p)) => format!(
                "{} / {}",
                judge(
                    m,
                    MEAN_TARGET_PCT,
                    reference_pct(r.mean, r.formulation.as_ref().map(|f| f.mean_pct))
                ),
                judge(
                    p,
                    PTP_TARGET_PCT,
                    reference_pct(r.ptp, r.formulation.as_ref().map(|f| f.ptp_pct))
                )
            ),
            _ => "–".into(),
        };
        let formulation = r.formulation.as_ref().map_or("–".into(), |f| {
            format!(
                "{:+.2} % / {:+.1} % ({}, {})",
                f.mean_pct, f.ptp_pct, f.level, f.positions
            )
        });
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} / {} | {} | {} / {} | {} |",
            r.blank.replace('_', " / "),
            r.torque_nm,
            join(&|l| format!("{} × {}", l.elements[0], l.elements[1])),
            join(&|l| format!("{:.2}", l.mean_urad)),
            estimate_text(r.mean),
            join(&|l| format!("{:.2}", l.ptp_urad)),
            estimate_text(r.ptp),
            opt_pct(r.penalty_mean_pct),
            opt_pct(r.penalty_ptp_pct),
            formulation,
            opt_pct(r.reduced_mean_difference_pct),
            opt_pct(r.reduced_ptp_difference_pct),
            verdict
        );
    }
    s.push('\n');
    let mut pairs: Vec<&str> = rows.iter().map(|r| r.blank.as_str()).collect();
    pairs.dedup();
    for b in &pairs {
        let of: Vec<&LoadRow> = rows.iter().filter(|r| r.blank == *b).collect();
        if let Some(line) = pinion_slave_sentence(b, &of, VERDICT_FROM_NM) {
            let _ = writeln!(s, "{line}");
        }
    }
    s.push('\n');
    // The peak pressure per level at the largest load of each blank pair.
    let mut blanks: Vec<&str> = rows.iter().map(|r| r.blank.as_str()).collect();
    blanks.dedup();
    for b in blanks {
        let Some(r) = rows
            .iter()
            .filter(|r| r.blank == b)
            .max_by(|x, y| x.torque_nm.total_cmp(&y.torque_nm))
        else {
            continue;
        };
        if r.levels.len() < 2 {
            continue;
        }
        let p: Vec<f64> = r.levels.iter().map(|l| l.max_pressure_mpa).collect();
        let _ = writeln!(
            s,
            "Peak contact pressure of the reference, {} at {} N·m: {} MPa ({}): it {}. Where the peak sits on a flank edge (a corner of the contact) it is no converged number; the TE, an integral of the contact, is.\n",
            b.replace('_', " / "),
            r.torque_nm,
            p.iter()
                .map(|x| format!("{x:.0}"))
                .collect::<Vec<_>>()
                .join(" / "),
            r.levels
                .iter()
                .map(|l| l.level.as_str())
                .collect::<Vec<_>>()
                .join(" / "),
            pressure_trend(&p)
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn judge_names_target_reference_uncertainty_or_neither() {
        assert_eq!(judge(-2.5, 3.0, Some(1.0)), "within the target");
        assert_eq!(
            judge(4.0, 3.0, Some(5.0)),
            "within the reference's uncertainty"
        );
        assert_eq!(judge(6.9, 3.0, Some(5.0)), "outside both");
        assert_eq!(judge(6.9, 3.0, None), "outside both");
    }

    #[test]
    fn pressure_trend_reads_the_direction_of_every_refinement() {
        assert_eq!(
            pressure_trend(&[900.0, 1200.0, 1890.0]),
            "grows with every refinement"
        );
        assert_eq!(
            pressure_trend(&[1900.0, 1200.0]),
            "falls with every refinement"
        );
        assert_eq!(
            pressure_trend(&[900.0, 1300.0, 1200.0]),
            "changes direction between refinements"
        );
        assert_eq!(pressure_trend(&[900.0]), "one level only");
    }

    /// f(h) = 10 + 4 h²: three levels give order 2 and the limit 10, the
    /// finest level's uncertainty its distance from it.
    #[test]
    fn second_order_values_extrapolate_to_their_limit() {
        let h = [0.2, 0.1, 0.05];
        let f = h.map(|x| 10.0 + 4.0 * x * x);
        let u = uncertainty(&h, &f).unwrap();
        let Estimate::Richardson { order, limit } = u.estimate else {
            panic!("{u:?}");
        };
        assert!(
            (order - 2.0).abs() < 1e-6 && (limit - 10.0).abs() < 1e-9,
            "{u:?}"
        );
        assert!((u.pct - 100.0 * 0.01 / 10.01).abs() < 1e-9, "{u:?}");
    }

    /// A value that rises then falls has no Richardson limit: the two
    /// finest levels' difference is the uncertainty; so it is with two
    /// levels; one level gives none.
    #[test]
    fn non_monotone_or_two_levels_give_the_spread_of_the_two_finest() {
        let u = uncertainty(&[0.2, 0.1, 0.05], &[16.0, 17.0, 16.5]).unwrap();
        assert_eq!(u.estimate, Estimate::Spread);
        assert!((u.pct - 100.0 * 0.5 / 16.5).abs() < 1e-12);
        let u = uncertainty(&[0.1, 0.05], &[17.0, 16.0]).unwrap();
        assert_eq!(u.estimate, Estimate::Spread);
        assert!((u.pct - 100.0 / 16.0).abs() < 1e-12);
        assert!(uncertainty(&[0.1], &[17.0]).is_none());
    }

    /// Two levels are said to be two levels, not a failed Richardson.
    #[test]
    fn estimate_text_names_two_levels_apart_from_a_non_monotone_three() {
        let two = uncertainty(&[0.1, 0.05], &[17.0, 16.0]);
        assert!(estimate_text(two).starts_with("two levels only"));
        let three = uncertainty(&[0.2, 0.1, 0.05], &[16.0, 17.0, 16.5]);
        assert!(estimate_text(three).starts_with("not monotone"));
        let rich = uncertainty(&[0.2, 0.1, 0.05], &[10.16, 10.04, 10.01]);
        assert!(
            estimate_text(rich).contains("(order 2.0)"),
            "{}",
            estimate_text(rich)
        );
    }

    fn table(rot: &[f64], te: &[f64]) -> Csv {
        (
            vec!["pinion_rotation_deg".into(), "te_700nm_urad".into()],
            vec![rot.to_vec(), te.to_vec()],
        )
    }

    /// The share is taken over the rotations both sweeps solved: the
    /// two-pass sweep's other rotations (here its largest value) are left
    /// out of its mean and peak-to-peak.
    #[test]
    fn formulation_share_compares_the_common_positions_only() {
        let two = table(
            &[0.0, 0.5, 1.0, 1.5, 2.0],
            &[100.0, 999.0, 104.0, 999.0, 102.0],
        );
        let one = table(&[0.0, 1.0, 2.0], &[103.0, 106.0, 104.0]);
        let f = formulation_share(&two, &one, 700.0, "reference").unwrap();
        assert_eq!(f.positions, 3);
        assert!((f.two_pass_mean_urad - 102.0).abs() < 1e-12, "{f:?}");
        assert!(
            (f.pinion_slave_mean_urad - 313.0 / 3.0).abs() < 1e-12,
            "{f:?}"
        );
        assert!(
            (f.two_pass_ptp_urad - 4.0).abs() < 1e-12
                && (f.pinion_slave_ptp_urad - 3.0).abs() < 1e-12
        );
        assert!((f.mean_pct - (313.0 / 3.0 - 102.0) / 102.0 * 100.0).abs() < 1e-9);
        assert!((f.ptp_pct + 25.0).abs() < 1e-9);
        // One common rotation, or another load, gives no share.
        assert!(formulation_share(&two, &table(&[0.0], &[1.0]), 700.0, "reference").is_none());
        assert!(formulation_share(&two, &one, 300.0, "reference").is_none());
    }

    /// The reduced model is sampled at the share's rotations (linear
    /// between its samples) and compared with the pinion-slave values; a
    /// rotation outside its samples leaves the comparison out.
    #[test]
    fn the_reduced_model_is_compared_with_the_pinion_slave_sweep_at_its_positions() {
        let two = table(&[0.0, 1.0, 2.0], &[100.0, 104.0, 102.0]);
        let one = table(&[0.0, 2.0], &[110.0, 106.0]);
        let share = formulation_share(&two, &one, 700.0, "reference").unwrap();
        // Reduced model: 111 at 0°, 107.1 at 2° (between samples at 1.5°
        // and 2.5°): mean 109.05 against 108, ptp 3.9 against 4.
        let s = with_reduced(share.clone(), &[0.0, 1.5, 2.5], &[111.0, 107.0, 107.2]);
        let [m, p] = s.reduced_pct.unwrap();
        assert!((m - (109.05 - 108.0) / 108.0 * 100.0).abs() < 1e-9, "{m}");
        assert!((p - (3.9 - 4.0) / 4.0 * 100.0).abs() < 1e-9, "{p}");
        assert!(with_reduced(share, &[0.5, 2.5], &[1.0, 2.0])
            .reduced_pct
            .is_none());
    }

    fn row(t: f64, reduced: Option<[f64; 2]>) -> LoadRow {
        LoadRow {
            blank: "standard_lightweight".into(),
            torque_nm: t,
            levels: Vec::new(),
            mean: None,
            ptp: None,
            penalty_mean_pct: None,
            penalty_ptp_pct: None,
            reduced_mean_difference_pct: None,
            reduced_ptp_difference_pct: None,
            formulation: Some(FormulationShare {
                level: "reference".into(),
                positions: 2,
                two_pass_mean_urad: 1.0,
                pinion_slave_mean_urad: 1.0,
                two_pass_ptp_urad: 1.0,
                pinion_slave_ptp_urad: 1.0,
                mean_pct: 0.0,
                ptp_pct: 0.0,
                rotations_deg: Vec::new(),
                reduced_pct: reduced,
            }),
        }
    }

    /// The sentence counts the loads within each target from 100 N·m on
    /// and names the largest difference; without any comparison there is
    /// no sentence.
    #[test]
    fn pinion_slave_sentence_counts_the_loads_within_each_target() {
        let rows = [
            row(1.0, Some([5.0, 9.0])),
            row(100.0, Some([0.5, 2.0])),
            row(700.0, Some([-0.2, -3.5])),
        ];
        let refs: Vec<&LoadRow> = rows.iter().collect();
        let s = pinion_slave_sentence("standard_lightweight", &refs, 100.0).unwrap();
        assert!(
            s.contains("mean TE within 1 % at all 2 loads (at most 0.50 %)"),
            "{s}"
        );
        assert!(
            s.contains("peak-to-peak TE within 3 % at 1 of the 2 loads (at most 3.50 %)"),
            "{s}"
        );
        let none = [row(300.0, None)];
        let refs: Vec<&LoadRow> = none.iter().collect();
        assert!(pinion_slave_sentence("standard_lightweight", &refs, 100.0).is_none());
    }

    /// The verdict weighs the larger of the mesh's and the formulation's
    /// uncertainty, either alone where only one is known.
    #[test]
    fn the_reference_uncertainty_is_the_larger_of_mesh_and_formulation() {
        let mesh = uncertainty(&[0.1, 0.05], &[17.0, 16.0]);
        let m = mesh.unwrap().pct;
        assert_eq!(reference_pct(mesh, Some(-20.0)), Some(20.0));
        assert_eq!(reference_pct(mesh, Some(0.1)), Some(m));
        assert_eq!(reference_pct(mesh, None), Some(m));
        assert_eq!(reference_pct(None, Some(-2.4)), Some(2.4));
        assert_eq!(reference_pct(None, None), None);
        // A 2.5 % difference: outside the 1 % target, within a 2.6 %
        // formulation share, outside a 0.2 % mesh uncertainty alone.
        assert_eq!(
            judge(2.5, 1.0, reference_pct(None, Some(2.6))),
            "within the reference's uncertainty"
        );
        assert_eq!(judge(2.5, 1.0, Some(0.2)), "outside both");
    }

    /// A level's summary that is there but unreadable stops the section
    /// with the file named; without any summary the section is empty.
    #[test]
    fn an_unreadable_level_summary_is_an_error_not_a_level_left_out() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../reference/scenes/default.toml");
        let scene = geometry::scene::Scene::load(&path).unwrap().scene;
        let out = tempfile::tempdir().unwrap();
        let built = build(out.path(), &scene, &[]).unwrap();
        assert!(built.rows.is_empty() && built.markdown.is_empty());
        let dir = reference_dir(out.path(), &scene.name, "medium").join("standard_standard");
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("summary.json"), "{ not json").unwrap();
        let e = build(out.path(), &scene, &[]).unwrap_err();
        assert!(e.to_string().contains("summary.json"), "{e}");
    }
}
