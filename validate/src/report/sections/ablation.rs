//! The report's ablation section: what each of the element's modelling
//! changes does. `solver ltca` runs its sweep once with the element and
//! once per ablated variant (one change switched off,
//! `summary.json`'s `ablation`); this section sets each against the
//! finest reference FE sweep's mean and peak-to-peak TE per blank pair and
//! load (the loaded-TE table's rows), with the CPU per position of both in
//! the same run.
//!
//! The loaded-pair rule's findings follow ([`loaded_pair_sentence`]).
//!
//! The verdict on a change ([`judge`]) counts the rows where switching it
//! on brings the reduced model's difference to the reference closer to
//! zero, separately for the mean and the peak-to-peak, from
//! [`FROM_LOAD_NM`] on (below, the TE is the unloaded geometry's).

use crate::report::comparison::{read, ComparisonError};
use crate::report::comparison_row::Row;
use formats::summaries::{BlankSummary, LoadSummary, LoadedPairRule};
use std::fmt::Write as _;
use std::path::Path;

/// Loads from which the rows are judged, N·m.
pub const FROM_LOAD_NM: f64 = 100.0;

/// One blank pair and load: the reference and the reduced model with and
/// without one change.
#[derive(Debug, Clone, PartialEq)]
pub struct AblationRow {
    pub blanks: String,
    pub torque_nm: f64,
    /// Reference mean and ptp TE, µrad.
    pub reference: [f64; 2],
    /// Element (change on) mean and ptp TE, µrad.
    pub with: [f64; 2],
    /// Variant (change off) mean and ptp TE, µrad.
    pub without: [f64; 2],
    /// CPU per position, s: [with, without].
    pub cpu_s: [f64; 2],
}

impl AblationRow {
    /// (model − reference) / reference, %, of mean and ptp.
    fn diff(model: [f64; 2], reference: [f64; 2]) -> [f64; 2] {
        [0, 1].map(|i| 100.0 * (model[i] - reference[i]) / reference[i])
    }
    pub fn with_diff(&self) -> [f64; 2] {
        Self::diff(self.with, self.reference)
    }
    pub fn without_diff(&self) -> [f64; 2] {
        Self::diff(self.without, self.reference)
    }
}

/// What switching one change on did over the judged rows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Effect {
    pub rows: usize,
    /// Rows where the change brings the mean / ptp closer to the reference.
    pub closer: [usize; 2],
    /// Mean |difference| without and with the change, %: [[mean, ptp] without, with].
    pub mean_abs: [[f64; 2]; 2],
    /// CPU per position with over without, mean over the rows.
    pub cost_ratio: f64,
}

/// The effect of a change over the rows from [`FROM_LOAD_NM`] on; None
/// when no row is that heavy.
pub fn judge(rows: &[AblationRow]) -> Option<Effect> {
    let r: Vec<&AblationRow> = rows
        .iter()
        .filter(|r| r.torque_nm >= FROM_LOAD_NM)
        .collect();
    if r.is_empty() {
        return None;
    }
    let n = r.len() as f64;
    let mut closer = [0; 2];
    let mut mean_abs = [[0.0; 2]; 2];
    let mut ratio = 0.0;
    for row in &r {
        let (w, wo) = (row.with_diff(), row.without_diff());
        for i in 0..2 {
            if w[i].abs() < wo[i].abs() {
                closer[i] += 1;
            }
            mean_abs[0][i] += wo[i].abs() / n;
            mean_abs[1][i] += w[i].abs() / n;
        }
        ratio += row.cpu_s[0] / row.cpu_s[1] / n;
    }
    Some(Effect {
        rows: r.len(),
        closer,
        mean_abs,
        cost_ratio: ratio,
    })
}

/// The sentence on one quantity: closer at all, none or some of the rows,
/// and the mean |difference| before and after.
fn quantity_sentence(what: &str, closer: usize, rows: usize, before: f64, after: f64) -> String {
    let where_ = if closer == rows {
        format!("comes closer to the reference at every one of the {rows} rows")
    } else if closer == 0 {
        format!("moves further from the reference at every one of the {rows} rows")
    } else {
        format!("comes closer to the reference at {closer} of the {rows} rows and moves further at the others")
    };
    let overall = if after < before {
        "smaller"
    } else if after > before {
        "larger"
    } else {
        "unchanged"
    };
    format!("the {what} {where_}; its mean |difference| is {overall}, {before:.2} % without the change and {after:.2} % with it")
}

/// The verdict line of one change.
pub fn sentence(change: &str, e: &Effect) -> String {
    format!(
        "- Switching on the {change}: {}; {}. CPU per position and torque ×{:.2} (same run).",
        quantity_sentence(
            "mean TE",
            e.closer[0],
            e.rows,
            e.mean_abs[0][0],
            e.mean_abs[1][0]
        ),
        quantity_sentence(
            "peak-to-peak TE",
            e.closer[1],
            e.rows,
            e.mean_abs[0][1],
            e.mean_abs[1][1]
        ),
        e.cost_ratio
    )
}

fn find(loads: &[LoadSummary], t: f64) -> Option<&LoadSummary> {
    loads.iter().find(|l| (l.torque_nm - t).abs() < 1e-9)
}

/// The rows of one ablated variant `variant` from the LTCA summaries and
/// the loaded-TE table's reference values.
pub fn rows_of(ltca: &[BlankSummary], rows: &[Row], variant: &str) -> Vec<AblationRow> {
    let mut out = Vec::new();
    for b in ltca {
        let Some(v) = b.ablation.iter().find(|v| v.variant == variant) else {
            continue;
        };
        let (pb, wb) = (b.pinion_blank.name(), b.wheel_blank.name());
        for r in rows
            .iter()
            .filter(|r| r.pinion_blank == pb && r.wheel_blank == wb)
        {
            let (Some(w), Some(wo)) = (find(&b.loads, r.torque_nm), find(&v.loads, r.torque_nm))
            else {
                continue;
            };
            out.push(AblationRow {
                blanks: format!("{pb} / {wb}"),
                torque_nm: r.torque_nm,
                reference: [r.reference_te_mean_urad, r.reference_te_ptp_urad],
                with: [w.te_mean_urad, w.te_ptp_urad],
                without: [wo.te_mean_urad, wo.te_ptp_urad],
                cpu_s: [w.cpu_s_per_position, wo.cpu_s_per_position],
            });
        }
    }
    out
}

/// The loaded-pair rule's line for one blank pair.
pub fn loaded_pair_sentence(blanks: &str, r: &LoadedPairRule) -> String {
    let closes = match r.closing {
        0 => "it closes at none of them, so every loaded TE is that of the roll range's pairs"
            .to_string(),
        n if n == r.with_candidates => {
            format!("it closes at all {n} of them and is part of their contact problem")
        }
        n => format!("it closes at {n} of them and is part of their contact problem"),
    };
    let unchecked = if r.unchecked > 0 {
        format!(
            " At {} positions the candidate pairs {:?} could not be checked: the stiffness files do not hold their teeth.",
            r.unchecked, r.unchecked_pairs
        )
    } else {
        String::new()
    };
    if r.with_candidates == 0 {
        return format!(
            "- Loaded-pair rule ({blanks}): at none of the {} positions does a tooth pair beyond the active roll range lie below the largest loaded TE.{unchecked}",
            r.positions
        );
    }
    format!(
        "- Loaded-pair rule ({blanks}): at {} of {} positions a tooth pair beyond the active roll range lies below the largest loaded TE (it would penetrate a rigid mate); with the deflection of the loaded teeth, which moves their neighbours too, {closes}.{unchecked}",
        r.with_candidates, r.positions
    )
}

/// The section's markdown from `<out>/<scene>/ltca/summary.json` and the
/// loaded-TE rows; empty when the LTCA has no ablation.
pub fn build(out: &Path, scene: &str, rows: &[Row]) -> Result<String, ComparisonError> {
    let path = out.join(scene).join("ltca").join("summary.json");
    let Some(ltca) = read::<Vec<BlankSummary>>(&path)? else {
        return Ok(String::new());
    };
    let mut variants: Vec<(String, String)> = Vec::new();
    for b in &ltca {
        for v in &b.ablation {
            if !variants.iter().any(|x| x.0 == v.variant) {
                variants.push((v.variant.clone(), v.change_off.clone()));
            }
        }
    }
    if variants.is_empty() || rows.is_empty() {
        return Ok(String::new());
    }
    let level = rows[0].reference_level.clone();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "### Ablation: what each modelling change of the element does\n"
    );
    let _ = writeln!(
        s,
        "The reduced model's quasi-static LTCA (not the multibody run of the table above; they differ by a few hundredths of a µrad) with the element as it is and with one modelling change switched off, against the reference FE on its finest mesh level that ran (`{level}`); differences (model − reference) / reference in %, CPU per position and torque from the same `solver ltca` run. Verdicts from {FROM_LOAD_NM} N·m on.\n"
    );
    for (name, change) in &variants {
        let r = rows_of(&ltca, rows, name);
        if r.is_empty() {
            continue;
        }
        let _ = writeln!(s, "Change: {change}.\n");
        let _ = writeln!(
            s,
            "| blanks | N·m | reference mean / ptp, µrad | with the change: mean / ptp, µrad (diff %) | without: mean / ptp, µrad (diff %) | CPU per position with / without, ms |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|");
        for row in &r {
            let (w, wo) = (row.with_diff(), row.without_diff());
            let _ = writeln!(
                s,
                "| {} | {} | {:.2} / {:.2} | {:.2} / {:.2} ({:+.2} / {:+.1}) | {:.2} / {:.2} ({:+.2} / {:+.1}) | {:.2} / {:.2} |",
                row.blanks,
                row.torque_nm,
                row.reference[0],
                row.reference[1],
                row.with[0],
                row.with[1],
                w[0],
                w[1],
                row.without[0],
                row.without[1],
                wo[0],
                wo[1],
                row.cpu_s[0] * 1e3,
                row.cpu_s[1] * 1e3
            );
        }
        s.push('\n');
        if let Some(e) = judge(&r) {
            let _ = writeln!(s, "{}\n", sentence(change, &e));
        }
    }
    for b in &ltca {
        if let Some(r) = &b.loaded_pair_rule {
            let blanks = format!("{} / {}", b.pinion_blank.name(), b.wheel_blank.name());
            let _ = writeln!(s, "{}", loaded_pair_sentence(&blanks, r));
        }
    }
    s.push('\n');
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(t: f64, with: [f64; 2], without: [f64; 2]) -> AblationRow {
        AblationRow {
            blanks: "standard / standard".into(),
            torque_nm: t,
            reference: [100.0, 10.0],
            with,
            without,
            cpu_s: [1.1e-3, 1e-3],
        }
    }

    #[test]
    fn a_change_that_brings_every_row_closer_is_said_to() {
        let r = [
            row(300.0, [100.5, 10.2], [101.0, 11.0]),
            row(500.0, [99.8, 9.9], [99.0, 9.5]),
        ];
        let e = judge(&r).unwrap();
        assert_eq!(e.closer, [2, 2]);
        assert!((e.cost_ratio - 1.1).abs() < 1e-12);
        let s = sentence("edge cut", &e);
        assert!(s.contains("mean TE comes closer to the reference at every one of the 2 rows"));
        assert!(s.contains("is smaller, 1.00 % without the change and 0.35 % with it"));
        assert!(s.contains("×1.10"), "{s}");
    }

    fn rule(with: usize, closing: usize, unchecked: Vec<i32>) -> LoadedPairRule {
        LoadedPairRule {
            positions: 73,
            with_candidates: with,
            closing,
            unchecked: usize::from(!unchecked.is_empty()) * 3,
            unchecked_pairs: unchecked,
        }
    }

    #[test]
    fn loaded_pair_rule_sentence_follows_its_counts() {
        let none = loaded_pair_sentence("standard / standard", &rule(0, 0, vec![]));
        assert!(none.contains("at none of the 73 positions"), "{none}");
        let open = loaded_pair_sentence("standard / standard", &rule(10, 0, vec![]));
        assert!(open.contains("at 10 of 73 positions") && open.contains("closes at none of them"));
        let some = loaded_pair_sentence("standard / lightweight", &rule(10, 4, vec![3]));
        assert!(some.contains("closes at 4 of them"), "{some}");
        assert!(some.contains("At 3 positions the candidate pairs [3] could not be checked"));
        let all = loaded_pair_sentence("x", &rule(4, 4, vec![]));
        assert!(all.contains("closes at all 4 of them"));
    }

    #[test]
    fn a_change_that_moves_every_row_away_is_said_to() {
        let r = [row(300.0, [102.0, 12.0], [101.0, 11.0])];
        let e = judge(&r).unwrap();
        assert_eq!(e.closer, [0, 0]);
        let s = sentence("edge cut", &e);
        assert!(s.contains("moves further from the reference at every one of the 1 rows"));
        assert!(s.contains("is larger"), "{s}");
    }

    #[test]
    fn a_mixed_change_is_said_to_be_mixed_and_light_loads_are_not_judged() {
        let r = [
            row(1.0, [200.0, 20.0], [100.0, 10.0]),
            row(300.0, [100.5, 10.5], [101.0, 10.2]),
            row(700.0, [101.5, 9.8], [101.0, 9.5]),
        ];
        let e = judge(&r).unwrap();
        assert_eq!(e.rows, 2);
        assert_eq!(e.closer, [1, 1]);
        let s = sentence("edge cut", &e);
        assert!(s.contains(
            "closer to the reference at 1 of the 2 rows and moves further at the others"
        ));
        assert!(judge(&r[..1]).is_none());
    }
}
