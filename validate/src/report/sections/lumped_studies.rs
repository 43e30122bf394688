//! Seed 004's two design studies in the lumped section: the TE slope
//! (m′₂₁ = −0.001 / −0.005 / −0.010: impact force and RMS) and the
//! contact ratio (1.65 / 1.85 / 2.25: mesh stiffness, impact force, RMS;
//! its Table 4), from the ease-off variants of
//! `reference/scenes/seed004_lumped.toml` (`design_variant` in the
//! summaries). Ours are formatted from the summaries; seed 004's are the
//! named constants below.

use crate::report::published::seed004;
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
    let _ = writeln!(
        s,
        "\nFrom the first row to the last: our impact force {:+.0} %, seed 004's {:+.1} %; our RMS along the normal {:+.0} % (λ̈) and {:+.0} % (v·q̈), seed 004's about {seed_rise:+.0} %. The direction agrees; our rise is far steeper, since our impact force is seed 004's F_s with our LTCA's approach velocity, which grows with the TE parabola. Our impact forces are {:.1}–{:.1} % of seed 004's. Source: {seed_source}.\n",
        rise(&|r| r.impact.seed004_force_n),
        100.0 * (rows[rows.len() - 1].1 / rows[0].1 - 1.0),
        rise(&|r| r.rms_acceleration_m_s2.mesh_normal),
        rise(&|r| r.relative_normal_acceleration_rms_m_s2),
        share.iter().copied().fold(f64::INFINITY, f64::min),
        share.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    );
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
        picked.push(*r);
    }
    if let (Some(lo), Some(hi)) = (picked.first(), picked.last()) {
        let pct = |a: f64, b: f64| 100.0 * (b / a - 1.0);
        let ratio = |f: &dyn Fn(&LumpedSummary) -> f64, col: &dyn Fn(usize) -> f64| {
            let v: Vec<f64> = picked
                .iter()
                .enumerate()
                .map(|(i, r)| col(i) / f(r))
                .collect();
            (
                v.iter().copied().fold(f64::INFINITY, f64::min),
                v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            )
        };
        let (k_lo, k_hi) = ratio(&|r| r.mesh_stiffness_n_per_m.mean, &|i| {
            table4.rows[i].mesh_stiffness_n_per_m
        });
        let (f_lo, f_hi) = ratio(&|r| r.impact.seed004_force_n, &|i| {
            table4.rows[i].impact_force_n
        });
        let _ = writeln!(
            s,
            "\nFrom the lowest contact ratio to the highest: our mean k {:+.0} % (seed 004 {:+.0} %), impact force {:+.0} % ({:+.0} %), RMS λ̈ {:+.0} % ({:+.0} %). The directions agree with seed 004's: more pairs in contact, a stiffer mesh, a softer engagement and less vibration. Seed 004's stiffness is {k_lo:.1}–{k_hi:.1} times ours, its impact force {f_lo:.0}–{f_hi:.0} times ours. Source: {}.\n",
            pct(lo.mesh_stiffness_n_per_m.mean, hi.mesh_stiffness_n_per_m.mean),
            pct(table4.rows[0].mesh_stiffness_n_per_m, table4.rows[2].mesh_stiffness_n_per_m),
            pct(lo.impact.seed004_force_n, hi.impact.seed004_force_n),
            pct(table4.rows[0].impact_force_n, table4.rows[2].impact_force_n),
            pct(lo.rms_acceleration_m_s2.mesh_normal, hi.rms_acceleration_m_s2.mesh_normal),
            pct(table4.rows[0].rms_acceleration_m_s2, table4.rows[2].rms_acceleration_m_s2),
            table4.source,
        );
    }
}
