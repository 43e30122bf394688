//! Our loaded TE against the white paper's published numbers (its Tables
//! 3 and 4), said in numbers: the white paper's pair is only partly
//! published (no ease-off, no lightweight web geometry), ours are chosen,
//! so the method is reproduced and the numbers are not. The paragraph gives
//! by how much they differ, per wheel blank: our reference's mean TE
//! against the published NLFEA mean (%), our reference's peak-to-peak over
//! the published NLFEA's (×), and the lightweight-over-standard ratio of
//! the mean TE, ours and theirs, per load.

use crate::report::comparison_row::Row;
use std::fmt::Write as _;

/// Smallest and largest of `v` (None when empty).
fn range(v: &[f64]) -> Option<[f64; 2]> {
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (!v.is_empty()).then_some([lo, hi])
}

/// Per wheel blank, over the loads with published values: our reference's
/// mean TE against the published NLFEA mean, % (min, max), its
/// peak-to-peak over the published one (min, max), and the loads.
#[derive(Debug, Clone, PartialEq)]
pub struct BlankDifference {
    pub wheel_blank: String,
    pub loads_nm: Vec<f64>,
    pub mean_difference_pct: [f64; 2],
    pub ptp_ratio: [f64; 2],
}

/// [`BlankDifference`] of each wheel blank of `rows`.
pub fn differences(rows: &[Row]) -> Vec<BlankDifference> {
    let mut blanks: Vec<&str> = rows.iter().map(|r| r.wheel_blank.as_str()).collect();
    blanks.dedup();
    blanks
        .into_iter()
        .filter_map(|b| {
            let with: Vec<(&Row, f64, f64)> = rows
                .iter()
                .filter(|r| r.wheel_blank == b)
                .filter_map(|r| {
                    Some((
                        r,
                        r.published_nlfea_te_mean_urad?,
                        r.published_nlfea_te_ptp_urad?,
                    ))
                })
                .collect();
            let mean: Vec<f64> = with
                .iter()
                .map(|(r, m, _)| (r.reference_te_mean_urad / m - 1.0) * 100.0)
                .collect();
            let ptp: Vec<f64> = with
                .iter()
                .map(|(r, _, p)| r.reference_te_ptp_urad / p)
                .collect();
            Some(BlankDifference {
                wheel_blank: b.to_string(),
                loads_nm: with.iter().map(|w| w.0.torque_nm).collect(),
                mean_difference_pct: range(&mean)?,
                ptp_ratio: range(&ptp)?,
            })
        })
        .collect()
}

/// Loads below this are left out of the lightweight-over-standard ratio:
/// there the TE is the unloaded geometry's (ease-off), not the web's
/// compliance (our choice of threshold), N·m.
pub const WEB_RATIO_MIN_LOAD_NM: f64 = 100.0;

/// Per load (from [`WEB_RATIO_MIN_LOAD_NM`] on) with both blanks
/// published: the lightweight wheel's mean TE over the standard wheel's,
/// ours (reference) and the white paper's (NLFEA).
pub fn lightweight_over_standard(rows: &[Row]) -> Vec<(f64, f64, f64)> {
    rows.iter()
        .filter(|r| r.wheel_blank == "standard" && r.torque_nm >= WEB_RATIO_MIN_LOAD_NM)
        .filter_map(|s| {
            let l = rows.iter().find(|l| {
                l.wheel_blank == "lightweight" && (l.torque_nm - s.torque_nm).abs() < 1e-9
            })?;
            Some((
                s.torque_nm,
                l.reference_te_mean_urad / s.reference_te_mean_urad,
                l.published_nlfea_te_mean_urad? / s.published_nlfea_te_mean_urad?,
            ))
        })
        .collect()
}

/// The paragraph; empty without published values.
pub fn paragraph(rows: &[Row]) -> String {
    let d = differences(rows);
    if d.is_empty() {
        return String::new();
    }
    let mut s = String::from("### Our pair against the white paper's published numbers\n\n");
    let _ = writeln!(
        s,
        "The white paper publishes its pair's design data (its Table 1) but not its ease-off nor its lightweight web (hole size, web thickness); ours are chosen, so this report reproduces the method of its Tables 3 and 4, not their numbers. By how much the numbers differ (our reference FE against the published NLFEA):\n"
    );
    for b in &d {
        let loads: Vec<String> = b.loads_nm.iter().map(|t| format!("{t}")).collect();
        let _ = writeln!(
            s,
            "- {} wheel blank ({} N·m): mean TE {:+.1} … {:+.1} %, peak-to-peak TE {:.2} … {:.2} times the published.",
            b.wheel_blank,
            loads.join(", "),
            b.mean_difference_pct[0],
            b.mean_difference_pct[1],
            b.ptp_ratio[0],
            b.ptp_ratio[1]
        );
    }
    let lw = lightweight_over_standard(rows);
    if let (Some(o), Some(t)) = (
        range(&lw.iter().map(|x| x.1).collect::<Vec<_>>()),
        range(&lw.iter().map(|x| x.2).collect::<Vec<_>>()),
    ) {
        let _ = writeln!(
            s,
            "- Lightweight over standard mean TE from {} N·m on (below it the TE is the unloaded geometry's): ours {:.2} … {:.2}, the white paper's {:.2} … {:.2} (same loads): the web we chose is {} than the paper's.",
            WEB_RATIO_MIN_LOAD_NM,
            o[0],
            o[1],
            t[0],
            t[1],
            if o[1] < t[0] {
                "stiffer"
            } else if o[0] > t[1] {
                "softer"
            } else {
                "neither clearly stiffer nor softer"
            }
        );
    }
    s.push('\n');
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(blank: &str, t: f64, ours: [f64; 2], theirs: [f64; 2]) -> Row {
        Row {
            wheel_blank: blank.into(),
            pinion_blank: "standard".into(),
            torque_nm: t,
            reference_te_mean_urad: ours[0],
            reference_te_ptp_urad: ours[1],
            published_nlfea_te_mean_urad: Some(theirs[0]),
            published_nlfea_te_ptp_urad: Some(theirs[1]),
            ..Row::default()
        }
    }

    #[test]
    fn differences_and_ratios_come_from_both_tables() {
        let rows = [
            row("standard", 300.0, [350.0, 16.0], [310.0, 5.0]),
            row("standard", 700.0, [707.0, 12.0], [630.0, 7.5]),
            row("lightweight", 300.0, [1000.0, 80.0], [1200.0, 20.0]),
            row("lightweight", 700.0, [2150.0, 160.0], [3000.0, 40.0]),
        ];
        let d = differences(&rows);
        assert_eq!(d.len(), 2);
        assert!((d[0].mean_difference_pct[0] - (707.0 / 630.0 - 1.0) * 100.0).abs() < 1e-9);
        assert!((d[0].mean_difference_pct[1] - (350.0 / 310.0 - 1.0) * 100.0).abs() < 1e-9);
        assert!((d[0].ptp_ratio[0] - 1.6).abs() < 1e-12 && (d[0].ptp_ratio[1] - 3.2).abs() < 1e-12);
        let lw = lightweight_over_standard(&rows);
        assert!(
            (lw[0].1 - 1000.0 / 350.0).abs() < 1e-12 && (lw[0].2 - 1200.0 / 310.0).abs() < 1e-12
        );
        let p = paragraph(&rows);
        assert!(
            p.contains("the web we chose is stiffer than the paper's"),
            "{p}"
        );
    }

    #[test]
    fn a_softer_or_overlapping_web_is_said_so() {
        let soft = [
            row("standard", 300.0, [350.0, 16.0], [310.0, 5.0]),
            row("lightweight", 300.0, [2000.0, 80.0], [1200.0, 20.0]),
        ];
        assert!(paragraph(&soft).contains("is softer than the paper's"));
        let same = [
            row("standard", 300.0, [350.0, 16.0], [350.0, 5.0]),
            row("lightweight", 300.0, [1200.0, 80.0], [1200.0, 20.0]),
        ];
        assert!(paragraph(&same).contains("neither clearly stiffer nor softer"));
        assert!(paragraph(&[]).is_empty());
    }
}
