//! The report's "reduced model at its grid limit" section: the LTCA of the
//! standard blanks on a family of equally refined contact grids and on the
//! scene's own stiffness files (`validate grid-convergence`), the family's
//! mean and peak-to-peak TE per load extrapolated to the grid's limit,
//! against the finest reference FE sweep. It separates the part of the reduced model's difference that its
//! own discretization makes from the part that stays.
//!
//! The limit is Richardson's over the three finest grids where their
//! values change monotonically (the reference's rule, [`uncertainty`]), else the finest grid's
//! value with the two finest grids' difference as its uncertainty
//! ([`limit`]); the verdicts ([`verdict`]) judge the limit's difference to
//! the reference against the targets.

use crate::report::comparison::{read, ComparisonError};
use crate::report::comparison_row::Row;
use crate::report::sections::reference_uncertainty::{
    uncertainty, Estimate, MEAN_TARGET_PCT, PTP_TARGET_PCT,
};
use crate::studies::grid_convergence::{GridConvergence, GridRun};
use std::fmt::Write as _;
use std::path::Path;

/// A quantity's value at the grid limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Limit {
    /// Richardson over three grids: observed order and limit.
    Extrapolated { order: f64, value: f64 },
    /// Not monotone: the finest grid's value, the two finest grids'
    /// difference its uncertainty.
    Finest { value: f64, spread: f64 },
}

impl Limit {
    pub fn value(&self) -> f64 {
        match *self {
            Limit::Extrapolated { value, .. } | Limit::Finest { value, .. } => value,
        }
    }
}

/// The limit of values `f` on element sizes `h` (coarse to fine, at least
/// three), by the reference's own rule ([`uncertainty`]): Richardson over
/// the three finest where it applies, else the finest with the two finest
/// grids' difference.
pub fn limit(h: &[f64], f: &[f64]) -> Option<Limit> {
    let n = f.len();
    if n < 3 {
        return None;
    }
    Some(match uncertainty(h, f)?.estimate {
        Estimate::Richardson { order, limit } => Limit::Extrapolated {
            order,
            value: limit,
        },
        Estimate::Spread => Limit::Finest {
            value: f[n - 1],
            spread: (f[n - 1] - f[n - 2]).abs(),
        },
    })
}

/// The verdict on a limit's difference `diff_pct` to the reference against
/// `target_pct`.
pub fn verdict(diff_pct: f64, target_pct: f64) -> &'static str {
    if diff_pct.abs() <= target_pct {
        "within the target"
    } else {
        "outside the target"
    }
}

fn limit_cell(l: &Option<Limit>) -> String {
    match l {
        Some(Limit::Extrapolated { order, value }) => format!("{value:.2} (order {order:.1})"),
        Some(Limit::Finest { value, spread }) => {
            format!("{value:.2} (not monotone; ±{spread:.2})")
        }
        None => "–".into(),
    }
}

/// The section's markdown from `<out>/<scene>/grid_convergence/summary.json`
/// and the loaded-TE rows (standard blanks); empty when the study has not run.
pub fn build(out: &Path, scene: &str, rows: &[Row]) -> Result<String, ComparisonError> {
    let path = out
        .join(scene)
        .join("grid_convergence")
        .join("summary.json");
    let Some(gc) = read::<GridConvergence>(&path)? else {
        return Ok(String::new());
    };
    let family: Vec<&GridRun> = gc.runs.iter().filter(|r| !r.is_scene).collect();
    let Some(own) = gc.runs.iter().find(|r| r.is_scene) else {
        return Ok(String::new());
    };
    if family.len() < 3 {
        return Ok(String::new());
    }
    let h: Vec<f64> = family.iter().map(|r| r.h).collect();
    let label = |r: &GridRun| format!("{} × {}", r.grid[0], r.grid[1]);
    let per_torque_ms = |r: &GridRun| r.cpu_s_per_position * 1e3 / r.loads.len().max(1) as f64;
    let mut s = String::new();
    let _ = writeln!(s, "### The reduced model at its grid limit\n");
    let _ = writeln!(
        s,
        "The reduced model's quasi-static LTCA (standard blanks) on a family of contact grids refined equally in both directions, each with its reduced-order mesh refined to the grid ({}), extrapolated per load to the grid's limit (element size h = 1/√(profile · face); Richardson over the three finest where monotone), against the finest reference FE; beside it the scene's own stiffness files ({} grid), which every other result of this report uses. CPU per position and torque: {} (family), {:.2} ms (the scene's).\n",
        family.iter().map(|r| label(r)).collect::<Vec<_>>().join(", "),
        label(own),
        family
            .iter()
            .map(|r| format!("{:.2} ms", per_torque_ms(r)))
            .collect::<Vec<_>>()
            .join(" / "),
        per_torque_ms(own)
    );
    let _ = writeln!(
        s,
        "| N·m | mean TE per grid of the family, µrad | limit | scene's grid | reference | limit / scene's grid vs reference % | ptp TE per grid of the family, µrad | limit | scene's grid | reference | limit / scene's grid vs reference % | verdict on the limit, mean / ptp |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|");
    let mut judged = Vec::new();
    let mut judged_own = Vec::new();
    for (i, &(t, own_mean, own_ptp)) in own.loads.iter().enumerate() {
        let Some(r) = rows.iter().find(|r| {
            r.pinion_blank == "standard"
                && r.wheel_blank == "standard"
                && (r.torque_nm - t).abs() < 1e-9
        }) else {
            continue;
        };
        let mean: Vec<f64> = family.iter().map(|g| g.loads[i].1).collect();
        let ptp: Vec<f64> = family.iter().map(|g| g.loads[i].2).collect();
        let (lm, lp) = (limit(&h, &mean), limit(&h, &ptp));
        let rel = |v: f64, reference: f64| 100.0 * (v - reference) / reference;
        let dm = lm.map(|l| rel(l.value(), r.reference_te_mean_urad));
        let dp = lp.map(|l| rel(l.value(), r.reference_te_ptp_urad));
        let fmt = |v: &[f64]| {
            v.iter()
                .map(|x| format!("{x:.2}"))
                .collect::<Vec<_>>()
                .join(" / ")
        };
        let pct = |d: Option<f64>| d.map_or("–".into(), |d| format!("{d:+.2}"));
        let v = match (dm, dp) {
            (Some(a), Some(b)) => {
                if t >= 100.0 {
                    judged.push((t, a, b));
                    judged_own.push((
                        t,
                        rel(own_mean, r.reference_te_mean_urad),
                        rel(own_ptp, r.reference_te_ptp_urad),
                    ));
                }
                format!(
                    "{} / {}",
                    verdict(a, MEAN_TARGET_PCT),
                    verdict(b, PTP_TARGET_PCT)
                )
            }
            _ => "–".into(),
        };
        let _ = writeln!(
            s,
            "| {t} | {} | {} | {own_mean:.2} | {:.2} | {} / {:+.2} | {} | {} | {own_ptp:.2} | {:.2} | {} / {:+.2} | {v} |",
            fmt(&mean),
            limit_cell(&lm),
            r.reference_te_mean_urad,
            pct(dm),
            rel(own_mean, r.reference_te_mean_urad),
            fmt(&ptp),
            limit_cell(&lp),
            r.reference_te_ptp_urad,
            pct(dp),
            rel(own_ptp, r.reference_te_ptp_urad)
        );
    }
    s.push('\n');
    if !judged.is_empty() {
        let _ = writeln!(
            s,
            "{}\n{}\n",
            summary_sentence("At its grid limit the reduced model's", &judged),
            summary_sentence(
                &format!("On the scene's own {} grid the reduced model's", label(own)),
                &judged_own
            )
        );
    }
    Ok(s)
}

/// The summary over the loads from 100 N·m: (torque, mean %, ptp %)
/// against the reference, of the model `subject` names.
pub fn summary_sentence(subject: &str, judged: &[(f64, f64, f64)]) -> String {
    let n = judged.len();
    let mean_in = judged
        .iter()
        .filter(|j| j.1.abs() <= MEAN_TARGET_PCT)
        .count();
    let ptp_in = judged
        .iter()
        .filter(|j| j.2.abs() <= PTP_TARGET_PCT)
        .count();
    let worst_m = judged.iter().map(|j| j.1.abs()).fold(0.0, f64::max);
    let worst_p = judged.iter().map(|j| j.2.abs()).fold(0.0, f64::max);
    let how = |k: usize| {
        if k == n {
            format!("at all {n} loads")
        } else if k == 0 {
            format!("at none of the {n} loads")
        } else {
            format!("at {k} of the {n} loads")
        }
    };
    format!(
        "- {subject} mean TE lies within {MEAN_TARGET_PCT} % of the reference {} (at most {worst_m:.2} %), its peak-to-peak TE within {PTP_TARGET_PCT} % {} (at most {worst_p:.2} %), loads from 100 N·m on.",
        how(mean_in),
        how(ptp_in)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn second_order_values_extrapolate_to_their_limit() {
        let h = [0.064, 0.043, 0.032];
        let f: Vec<f64> = h.iter().map(|x| 16.0 + 400.0 * x * x).collect();
        match limit(&h, &f).unwrap() {
            Limit::Extrapolated { order, value } => {
                assert!((order - 2.0).abs() < 1e-6, "{order}");
                assert!((value - 16.0).abs() < 1e-9, "{value}");
            }
            l => panic!("{l:?}"),
        }
    }

    #[test]
    fn non_monotone_values_give_the_finest_with_its_spread() {
        match limit(&[0.06, 0.04, 0.03], &[14.0, 14.5, 14.3]).unwrap() {
            Limit::Finest { value, spread } => {
                assert_eq!(value, 14.3);
                assert!((spread - 0.2).abs() < 1e-12, "{spread}");
            }
            l => panic!("{l:?}"),
        }
        assert!(limit(&[0.06, 0.04], &[1.0, 2.0]).is_none());
    }

    #[test]
    fn verdicts_and_summary_follow_the_numbers() {
        assert_eq!(verdict(0.9, 1.0), "within the target");
        assert_eq!(verdict(-3.5, 3.0), "outside the target");
        let all = summary_sentence(
            "At its grid limit the reduced model's",
            &[(300.0, 0.1, 0.9), (700.0, -0.1, -2.4)],
        );
        assert!(
            all.contains("within 1 % of the reference at all 2 loads (at most 0.10 %)"),
            "{all}"
        );
        assert!(
            all.contains("within 3 % at all 2 loads (at most 2.40 %)"),
            "{all}"
        );
        let some = summary_sentence("x", &[(300.0, 1.5, 0.9), (700.0, -0.1, -4.0)]);
        assert!(
            some.contains("at 1 of the 2 loads (at most 1.50 %)"),
            "{some}"
        );
        let none = summary_sentence("x", &[(300.0, 1.5, 5.0)]);
        assert!(none.contains("at none of the 1 loads"), "{none}");
    }
}
