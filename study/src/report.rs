//! The collected study as a table (`cases.csv`), a report (`report.md`)
//! and charts: the reduced model against the reference over the cases,
//! the worst case named, every sentence made from the numbers it states.

use crate::collect::{Collected, Numbers, Row};
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// The project's accuracy targets for the reduced model against the fine
/// reference (mean TE within 1 %, peak-to-peak within 3 %): the report
/// counts the rows inside them.
pub const MEAN_TARGET_PCT: f64 = 1.0;
pub const PTP_TARGET_PCT: f64 = 3.0;

/// 100 (a − b) / b.
pub fn pct(a: f64, b: f64) -> f64 {
    100.0 * (a - b) / b
}

fn opt(v: Option<f64>) -> String {
    v.map(|x| format!("{x}")).unwrap_or_default()
}

/// `cases.csv`: one line per case, blank pair and torque.
pub fn csv(c: &Collected) -> String {
    let mut s = String::from(
        "case,offset_mm,pinion_axial_mm,wheel_axial_mm,shaft_angle_deg,blanks,torque_nm,utca_te_mean_urad,utca_te_ptp_urad",
    );
    let cols = [
        "te_mean_urad",
        "te_ptp_urad",
        "max_pressure_mpa",
        "pinion_root_tension_mpa",
        "wheel_root_tension_mpa",
    ];
    for a in ["ltca", "multibody", "reference"] {
        for col in cols {
            write!(s, ",{a}_{col}").unwrap();
        }
    }
    s.push('\n');
    for r in &c.rows {
        write!(
            s,
            "{},{},{},{},{},{},{},{},{}",
            r.case,
            r.offset_mm,
            r.pinion_axial_mm,
            r.wheel_axial_mm,
            r.shaft_angle_deg,
            r.blanks,
            r.torque_nm,
            opt(r.utca_te_mean_urad),
            opt(r.utca_te_ptp_urad)
        )
        .unwrap();
        for n in [&r.ltca, &r.multibody, &r.reference] {
            let v = |f: fn(&Numbers) -> Option<f64>| opt(n.as_ref().and_then(f));
            write!(
                s,
                ",{},{},{},{},{}",
                v(|n| Some(n.te_mean_urad)),
                v(|n| Some(n.te_ptp_urad)),
                v(|n| n.max_pressure_mpa),
                v(|n| n.pinion_root_tension_mpa),
                v(|n| n.wheel_root_tension_mpa)
            )
            .unwrap();
        }
        s.push('\n');
    }
    s
}

/// A row's reduced-model differences from the reference, %: the mean TE's
/// difference as a share of the reference's elastic mean (its mean less
/// the UTCA's mean at the same positions: a misalignment shifts the
/// geometric part, which may bring the whole mean near zero), and the
/// peak-to-peak TE's relative difference.
pub fn differences(r: &Row) -> Option<(f64, f64)> {
    let (_, red) = r.reduced()?;
    let refn = r.reference.as_ref()?;
    let elastic = refn.te_mean_urad - r.utca_te_mean_urad?;
    Some((
        100.0 * (red.te_mean_urad - refn.te_mean_urad) / elastic,
        pct(red.te_ptp_urad, refn.te_ptp_urad),
    ))
}

/// The sentences on the comparison: the worst mean and ptp differences
/// (case named) and how many rows lie within the targets.
pub fn verdict(c: &Collected) -> String {
    let compared: Vec<(&Row, (f64, f64))> = c
        .rows
        .iter()
        .filter_map(|r| differences(r).map(|d| (r, d)))
        .collect();
    if compared.is_empty() {
        return "The study has no row with both a reduced-model and a reference result: nothing is compared.".into();
    }
    let worst = |k: fn(&(f64, f64)) -> f64| {
        compared
            .iter()
            .max_by(|a, b| k(&a.1).abs().total_cmp(&k(&b.1).abs()))
            .copied()
            .expect("not empty")
    };
    let (rm, dm) = worst(|d| d.0);
    let (rp, dp) = worst(|d| d.1);
    let within = compared
        .iter()
        .filter(|(_, d)| d.0.abs() <= MEAN_TARGET_PCT && d.1.abs() <= PTP_TARGET_PCT)
        .count();
    let which = compared[0].0.reduced().map_or("", |r| r.0);
    let mut s = format!(
        "The reduced model ({which}) against the reference ({} level): the largest mean-TE difference is {:+.2} % of the reference's elastic mean ({}, {}, {} N·m); the largest peak-to-peak difference is {:+.2} % ({}, {}, {} N·m). ",
        c.reference_level, dm.0, rm.case, rm.blanks, rm.torque_nm, dp.1, rp.case, rp.blanks, rp.torque_nm
    );
    if within == compared.len() {
        write!(
            s,
            "All {} compared rows lie within the targets (mean {MEAN_TARGET_PCT} %, peak-to-peak {PTP_TARGET_PCT} %).",
            compared.len()
        )
        .unwrap();
    } else {
        write!(
            s,
            "{within} of {} compared rows lie within the targets (mean {MEAN_TARGET_PCT} %, peak-to-peak {PTP_TARGET_PCT} %).",
            compared.len()
        )
        .unwrap();
    }
    s
}

fn cell(v: Option<f64>, digits: usize) -> String {
    v.map(|x| format!("{x:.digits$}"))
        .unwrap_or_else(|| "–".into())
}

/// `report.md`.
pub fn markdown(c: &Collected, charts: &[PathBuf]) -> String {
    let mut s = format!(
        "# Study {}\n\n{} cases; analyses: {}; reference level: {}.\n\n{}\n\n",
        c.study,
        c.cases,
        c.analyses
            .iter()
            .map(|a| a.name())
            .collect::<Vec<_>>()
            .join(", "),
        c.reference_level,
        verdict(c)
    );
    s.push_str("The mean difference is a share of the reference's elastic mean TE (its mean less the UTCA's mean at the same positions); the reduced model is the multibody 10 rpm run where the study ran it, else the LTCA.\n\n");
    s.push_str("| case | blanks | N·m | reduced mean µrad | reference mean µrad | mean diff % | reduced ptp µrad | reference ptp µrad | ptp diff % | reduced p_max MPa | reference p_max MPa | reduced σ_F pinion / wheel MPa | reference σ_F pinion / wheel MPa |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for r in &c.rows {
        let red = r.reduced().map(|x| x.1);
        let rf = r.reference.as_ref();
        let d = differences(r);
        let root = |n: Option<&Numbers>| {
            format!(
                "{} / {}",
                cell(n.and_then(|n| n.pinion_root_tension_mpa), 1),
                cell(n.and_then(|n| n.wheel_root_tension_mpa), 1)
            )
        };
        writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.case,
            r.blanks,
            r.torque_nm,
            cell(red.map(|n| n.te_mean_urad), 2),
            cell(rf.map(|n| n.te_mean_urad), 2),
            cell(d.map(|d| d.0), 2),
            cell(red.map(|n| n.te_ptp_urad), 2),
            cell(rf.map(|n| n.te_ptp_urad), 2),
            cell(d.map(|d| d.1), 2),
            cell(red.and_then(|n| n.max_pressure_mpa), 0),
            cell(rf.and_then(|n| n.max_pressure_mpa), 0),
            root(red),
            root(rf)
        )
        .unwrap();
    }
    for p in charts {
        let name = p
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        write!(s, "\n![{name}]({name})\n").unwrap();
    }
    s
}

/// The axis values of a row: E, P, G, ΔΣ.
fn axes(r: &Row) -> [f64; 4] {
    [
        r.offset_mm,
        r.pinion_axial_mm,
        r.wheel_axial_mm,
        r.shaft_angle_deg,
    ]
}
const AXES: [(&str, &str); 4] = [
    ("offset", "E (mm)"),
    ("pinion_axial", "P (mm)"),
    ("wheel_axial", "G (mm)"),
    ("shaft_angle", "ΔΣ (deg)"),
];

/// A chart per misalignment axis with more than one value: the reduced
/// model's and the reference's ptp TE over the axis, per blank pair and
/// torque, on the slice of cases whose other axes sit at their values
/// nearest zero.
pub fn charts(c: &Collected, dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for (a, (file, label)) in AXES.iter().enumerate() {
        let mut values: Vec<f64> = c.rows.iter().map(|r| axes(r)[a]).collect();
        values.sort_by(f64::total_cmp);
        values.dedup();
        if values.len() < 2 {
            continue;
        }
        // The other axes' values nearest zero.
        let nearest: Vec<f64> = (0..4)
            .map(|b| {
                c.rows
                    .iter()
                    .map(|r| axes(r)[b])
                    .min_by(|x, y| x.abs().total_cmp(&y.abs()))
                    .unwrap_or(0.0)
            })
            .collect();
        let slice: Vec<&Row> = c
            .rows
            .iter()
            .filter(|r| (0..4).all(|b| b == a || axes(r)[b] == nearest[b]))
            .collect();
        let mut keys: Vec<(String, f64)> = slice
            .iter()
            .map(|r| (r.blanks.clone(), r.torque_nm))
            .collect();
        keys.sort_by(|x, y| x.0.cmp(&y.0).then(x.1.total_cmp(&y.1)));
        keys.dedup();
        let mut series = Vec::new();
        for (blanks, t) in &keys {
            let mut pts: Vec<&&Row> = slice
                .iter()
                .filter(|r| &r.blanks == blanks && r.torque_nm == *t)
                .collect();
            pts.sort_by(|x, y| axes(x)[a].total_cmp(&axes(y)[a]));
            let x: Vec<f64> = pts.iter().map(|r| axes(r)[a]).collect();
            if pts.first().is_some_and(|r| r.reduced().is_some()) {
                series.push(charts::Series {
                    name: format!("{blanks} {t} N·m reduced"),
                    x: x.clone(),
                    y: pts
                        .iter()
                        .map(|r| r.reduced().map_or(f64::NAN, |n| n.1.te_ptp_urad))
                        .collect(),
                    dashed: false,
                });
            }
            if pts.first().is_some_and(|r| r.reference.is_some()) {
                series.push(charts::Series {
                    name: format!("{blanks} {t} N·m reference"),
                    x,
                    y: pts
                        .iter()
                        .map(|r| r.reference.as_ref().map_or(f64::NAN, |n| n.te_ptp_urad))
                        .collect(),
                    dashed: true,
                });
            }
        }
        if series.is_empty() {
            continue;
        }
        let path = dir.join(format!("ptp_over_{file}.svg"));
        charts::te_curve(
            &path,
            &format!("{}: peak-to-peak TE over {label}", c.study),
            label,
            "peak-to-peak TE (µrad)",
            &series,
        )?;
        out.push(path);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn n(mean: f64, ptp: f64) -> Numbers {
        Numbers {
            te_mean_urad: mean,
            te_ptp_urad: ptp,
            max_pressure_mpa: None,
            pinion_root_tension_mpa: None,
            wheel_root_tension_mpa: None,
        }
    }

    fn row(case: &str, e: f64, reduced: Numbers, reference: Option<Numbers>) -> Row {
        Row {
            case: case.into(),
            offset_mm: e,
            pinion_axial_mm: 0.0,
            wheel_axial_mm: 0.0,
            shaft_angle_deg: 0.0,
            blanks: "standard_standard".into(),
            torque_nm: 300.0,
            utca_te_mean_urad: Some(0.0),
            utca_te_ptp_urad: None,
            ltca: Some(reduced),
            multibody: None,
            reference,
        }
    }

    fn collected(rows: Vec<Row>) -> Collected {
        Collected {
            study: "s".into(),
            analyses: vec![],
            reference_level: "reference".into(),
            cases: rows.len(),
            rows,
        }
    }

    #[test]
    fn verdict_names_the_worst_case_and_counts_rows_within_the_targets() {
        let c = collected(vec![
            row("a", 0.0, n(100.5, 10.1), Some(n(100.0, 10.0))),
            row("b", 0.05, n(98.0, 10.5), Some(n(100.0, 10.0))),
        ]);
        let v = verdict(&c);
        assert!(
            v.contains("mean-TE difference is -2.00 % of the reference's elastic mean (b,"),
            "{v}"
        );
        assert!(v.contains("peak-to-peak difference is +5.00 % (b,"), "{v}");
        assert!(v.contains("1 of 2 compared rows lie within"), "{v}");
    }

    #[test]
    fn verdict_says_all_rows_within_when_they_are() {
        let c = collected(vec![row("a", 0.0, n(100.5, 10.1), Some(n(100.0, 10.0)))]);
        assert!(verdict(&c).contains("All 1 compared rows lie within"));
    }

    #[test]
    fn verdict_without_reference_compares_nothing() {
        let c = collected(vec![row("a", 0.0, n(100.5, 10.1), None)]);
        assert!(verdict(&c).contains("nothing is compared"));
    }

    #[test]
    fn csv_has_a_line_per_row_and_empty_cells_for_missing_analyses() {
        let c = collected(vec![row("a", 0.0, n(1.0, 2.0), None)]);
        let t = csv(&c);
        let lines: Vec<&str> = t.lines().collect();
        assert_eq!(lines.len(), 2);
        assert_eq!(lines[0].split(',').count(), lines[1].split(',').count());
        assert!(lines[1].ends_with(",,,,,,,,,,"), "{}", lines[1]);
    }
}
