//! Seed 004's two design studies in the lumped section: the TE slope
//! (m′₂₁ = −0.001 / −0.005 / −0.010: impact force and RMS) and the
//! contact ratio (1.65 / 1.85 / 2.25: mesh stiffness, impact force, RMS;
//! its Table 4), from the ease-off variants of
//! `reference/scenes/seed004_lumped.toml` (`design_variant` in the
//! summaries). Ours are formatted from the summaries; seed 004's are the
//! named constants below.

use crate::report::published::{seed004, Seed004Table4Row};
use formats::lumped_summary::LumpedSummary;
use std::fmt::Write as _;

fn slope(r: &LumpedSummary) -> Option<f64> {
    r.design_variant.as_ref().and_then(|d| d.te_slope_m21)
}

fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1e-12)
}

/// Both study tables, or nothing when the summaries hold no variant.
pub fn markdown(s: &mut String, all: &[LumpedSummary]) {
    let te: Vec<(&LumpedSummary, f64)> = seed004()
        .te_slope
        .rows
        .iter()
        .filter_map(|row| {
            all.iter()
                .find(|r| slope(r).is_some_and(|x| same(x, row.m21)))
                .map(|r| (r, row.impact_force_n))
        })
        .collect();
    if !te.is_empty() {
        te_slope(s, &te);
    }
    let cr: Vec<&LumpedSummary> = all
        .iter()
        .filter(|r| slope(r).is_some_and(|x| same(x, seed004().table4.te_slope_m21)))
        .collect();
    if !cr.is_empty() {
        contact_ratio(s, &cr);
    }
}

fn te_slope(s: &mut String, rows: &[(&LumpedSummary, f64)]) {
    let (seed_rise, seed_source) = (
        seed004().te_slope.rms_rise_percent,
        &seed004().te_slope.source,
    );
    let _ = writeln!(
        s,
        "### Seed 004's TE-slope study\n\nEach m′₂₁ sets the design's parabolic motion error A = ½|m′₂₁|(τ/2)² (wheel side, at ±half a mesh cycle τ); crownings as in the design; our LTCA, seed 004's impact method and the 8-DOF run as above.\n"
    );
    let _ = writeln!(
        s,
        "| m′₂₁ (1/rad) | A (µrad) | contact ratio, ours | mean k (N/m) | impact force, ours (N) | impact force, seed 004 (N) | RMS λ̈, ours (m/s²) | RMS v·q̈, ours (m/s²) |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for (r, theirs) in rows {
        let Some(d) = r.design_variant.as_ref() else {
            continue;
        };
        let _ = writeln!(
            s,
            "| {:.3} | {:.2} | {:.3} | {:.4e} | {:.0} | {theirs:.1} | {:.1} | {:.1} |",
            d.te_slope_m21.unwrap_or(f64::NAN),
            d.motion_error_urad,
            r.loaded_contact_ratio,
            r.mesh_stiffness_n_per_m.mean,
            r.impact.seed004_force_n,
            r.rms_acceleration_m_s2.mesh_normal,
            r.relative_normal_acceleration_rms_m_s2
        );
    }
    let (first, last) = (rows[0].0, rows[rows.len() - 1].0);
    let rise = |f: &dyn Fn(&LumpedSummary) -> f64| 100.0 * (f(last) / f(first) - 1.0);
    let share: Vec<f64> = rows
        .iter()
        .map(|(r, theirs)| 100.0 * r.impact.seed004_force_n / theirs)
        .collect();
    let ours_force = rise(&|r| r.impact.seed004_force_n);
    let theirs_force = 100.0 * (rows[rows.len() - 1].1 / rows[0].1 - 1.0);
    let ours_rms = rise(&|r| r.rms_acceleration_m_s2.mesh_normal);
    let verdict = direction_clause(&[
        ("the impact force", ours_force, theirs_force),
        ("the RMS along the normal (λ̈)", ours_rms, seed_rise),
    ]);
    let steep = steepness_clause("impact-force change", ours_force, theirs_force);
    let _ = writeln!(
        s,
        "\nFrom the first row to the last: our impact force {ours_force:+.0} %, seed 004's {theirs_force:+.1} %; our RMS along the normal {ours_rms:+.0} % (λ̈) and {:+.0} % (v·q̈), seed 004's about {seed_rise:+.0} %. {verdict}{steep} Our impact force is seed 004's F_s with our LTCA's approach velocity, which grows with the TE parabola. Our impact forces are {:.1}–{:.1} % of seed 004's. Source: {seed_source}.\n",
        rise(&|r| r.relative_normal_acceleration_rms_m_s2),
        share.iter().copied().fold(f64::INFINITY, f64::min),
        share.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    );
}

/// Whether the signs of our relative changes (%) match seed 004's, per
/// quantity `(name, ours, seed 004's)`: one sentence, computed. A change
/// within ±0.5 % counts as none.
pub fn direction_clause(q: &[(&str, f64, f64)]) -> String {
    let sign = |x: f64| {
        if x.abs() < 0.5 {
            0
        } else if x > 0.0 {
            1
        } else {
            -1
        }
    };
    let join = |v: &[&str]| match v {
        [] => String::new(),
        [a] => a.to_string(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    };
    let (same, other): (Vec<&str>, Vec<&str>) = (
        q.iter()
            .filter(|(_, a, b)| sign(*a) == sign(*b))
            .map(|x| x.0)
            .collect(),
        q.iter()
            .filter(|(_, a, b)| sign(*a) != sign(*b))
            .map(|x| x.0)
            .collect(),
    );
    match (same.is_empty(), other.is_empty()) {
        (_, true) if !same.is_empty() => {
            format!("The direction agrees with seed 004's for {}.", join(&same))
        }
        (true, false) => format!(
            "The direction differs from seed 004's for {}.",
            join(&other)
        ),
        (false, false) => format!(
            "The direction agrees with seed 004's for {} and differs for {}.",
            join(&same),
            join(&other)
        ),
        _ => String::new(),
    }
}

/// How our relative change (%) of `what` compares in size with seed 004's:
/// empty when the signs differ or either is within ±0.5 %.
pub fn steepness_clause(what: &str, ours: f64, theirs: f64) -> String {
    if ours.abs() < 0.5 || theirs.abs() < 0.5 || ours.signum() != theirs.signum() {
        return String::new();
    }
    let r = ours / theirs;
    if (0.8..=1.25).contains(&r) {
        format!(" Our {what} is about seed 004's ({r:.2} times).")
    } else if r > 1.0 {
        format!(" Our {what} is {r:.1} times seed 004's, steeper.")
    } else {
        format!(" Our {what} is {r:.2} times seed 004's, shallower.")
    }
}

fn contact_ratio(s: &mut String, runs: &[&LumpedSummary]) {
    let _ = writeln!(
        s,
        "### Seed 004's contact-ratio study (its Table 4)\n\nSeed 004 sets m′₂₁ = −0.00001 and does not say how it reaches its contact ratios. Ours are ease-off variants with that m′₂₁ and the lengthwise crowning changed (column 2); the contact ratio is measured, as the mean number of tooth pairs carrying load over the mesh cycle in our LTCA at the operating torque (in steps of one over the positions per cycle). Each of seed 004's rows is set beside our run of nearest contact ratio.\n"
    );
    let _ = writeln!(
        s,
        "| contact ratio, seed 004 | lengthwise / profile crowning (µm) | contact ratio, ours | mean k, ours (N/m) | seed 004 (N/m) | impact force, ours (N) | seed 004 (N) | RMS λ̈, ours (m/s²) | RMS v·q̈, ours (m/s²) | seed 004 (m/s²) |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
    let mut picked = Vec::new();
    let table4 = &seed004().table4;
    for row in &table4.rows {
        let (cr, k, f, rms) = (
            row.contact_ratio,
            row.mesh_stiffness_n_per_m,
            row.impact_force_n,
            row.rms_acceleration_m_s2,
        );
        let Some(r) = runs.iter().min_by(|a, b| {
            (a.loaded_contact_ratio - cr)
                .abs()
                .total_cmp(&(b.loaded_contact_ratio - cr).abs())
        }) else {
            continue;
        };
        let Some(d) = r.design_variant.as_ref() else {
            continue;
        };
        let _ = writeln!(
            s,
            "| {cr:.2} | {:.0} / {:.0} | {:.3} | {:.4e} | {k:.4e} | {:.0} | {f:.1} | {:.1} | {:.1} | {rms:.2} |",
            d.lengthwise_crowning_um,
            d.profile_crowning_um,
            r.loaded_contact_ratio,
            r.mesh_stiffness_n_per_m.mean,
            r.impact.seed004_force_n,
            r.rms_acceleration_m_s2.mesh_normal,
            r.relative_normal_acceleration_rms_m_s2
        );
        picked.push((*r, row));
    }
    if let (Some(&(lo, row_lo)), Some(&(hi, row_hi))) = (picked.first(), picked.last()) {
        let pct = |a: f64, b: f64| 100.0 * (b / a - 1.0);
        let ratio = |f: &dyn Fn(&LumpedSummary) -> f64, col: &dyn Fn(&Seed004Table4Row) -> f64| {
            let v: Vec<f64> = picked.iter().map(|(r, row)| col(row) / f(r)).collect();
            (
                v.iter().copied().fold(f64::INFINITY, f64::min),
                v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            )
        };
        let (k_lo, k_hi) = ratio(&|r| r.mesh_stiffness_n_per_m.mean, &|row| {
            row.mesh_stiffness_n_per_m
        });
        let (f_lo, f_hi) = ratio(&|r| r.impact.seed004_force_n, &|row| row.impact_force_n);
        let changes = [
            (
                "the mean k",
                pct(
                    lo.mesh_stiffness_n_per_m.mean,
                    hi.mesh_stiffness_n_per_m.mean,
                ),
                pct(row_lo.mesh_stiffness_n_per_m, row_hi.mesh_stiffness_n_per_m),
            ),
            (
                "the impact force",
                pct(lo.impact.seed004_force_n, hi.impact.seed004_force_n),
                pct(row_lo.impact_force_n, row_hi.impact_force_n),
            ),
            (
                "the RMS λ̈",
                pct(
                    lo.rms_acceleration_m_s2.mesh_normal,
                    hi.rms_acceleration_m_s2.mesh_normal,
                ),
                pct(row_lo.rms_acceleration_m_s2, row_hi.rms_acceleration_m_s2),
            ),
        ];
        let verdict = direction_clause(&changes);
        let _ = writeln!(
            s,
            "\nFrom the lowest contact ratio to the highest: our mean k {:+.0} % (seed 004 {:+.0} %), impact force {:+.0} % ({:+.0} %), RMS λ̈ {:+.0} % ({:+.0} %). {verdict} Seed 004's stiffness is {k_lo:.1}–{k_hi:.1} times ours, its impact force {f_lo:.0}–{f_hi:.0} times ours. Source: {}.\n",
            changes[0].1,
            changes[0].2,
            changes[1].1,
            changes[1].2,
            changes[2].1,
            changes[2].2,
            table4.source,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn changes_of_the_same_sign_agree_in_direction() {
        let v = direction_clause(&[("k", 13.0, 30.8), ("RMS", -61.0, -80.7)]);
        assert_eq!(v, "The direction agrees with seed 004's for k and RMS.");
    }

    #[test]
    fn changes_of_opposite_sign_differ_in_direction() {
        let v = direction_clause(&[("k", -3.0, 30.8)]);
        assert_eq!(v, "The direction differs from seed 004's for k.");
        let v = direction_clause(&[
            ("k", 13.0, 30.8),
            ("force", 4.0, -13.7),
            ("RMS", 0.2, -80.7),
        ]);
        assert_eq!(
            v,
            "The direction agrees with seed 004's for k and differs for force and RMS."
        );
    }

    #[test]
    fn steepness_is_said_only_for_changes_of_one_sign() {
        assert_eq!(
            steepness_clause("rise", 140.0, 15.0),
            " Our rise is 9.3 times seed 004's, steeper."
        );
        assert_eq!(
            steepness_clause("rise", 5.0, 15.0),
            " Our rise is 0.33 times seed 004's, shallower."
        );
        assert_eq!(
            steepness_clause("rise", 14.0, 15.0),
            " Our rise is about seed 004's (0.93 times)."
        );
        assert_eq!(steepness_clause("rise", -14.0, 15.0), "");
    }
}
