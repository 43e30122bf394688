//! A blank pair's result files beside its summary: the contact pattern,
//! the bodies' sizes and factoring times, and the summary on stderr.

use crate::reference::reference_ltca::{Member, PositionResult};
use crate::reference::reference_outputs::pattern_vtu;
use crate::reference::reference_summary::BlankSummary;
use formats::columns;
use formats::output::{write_atomic, write_json};
use std::fmt::Write as _;
use std::path::Path;

/// Contact pattern: the envelope of the pressure at the largest torque `t`
/// over all positions, on the pinion flank's (ξ, η), as
/// `pattern_<t>nm.csv` and `.vtu` in `sdir`.
pub(super) fn write_pattern(
    sdir: &Path,
    res: &[PositionResult],
    fp: &geometry::pair::FlankPair,
    t: f64,
) -> anyhow::Result<()> {
    let mut envelope: std::collections::HashMap<[u64; 3], ([f64; 3], f64)> =
        std::collections::HashMap::new();
    for r in res {
        for &(p, v) in &r.pattern {
            let e = envelope.entry(p.map(f64::to_bits)).or_insert((p, 0.0));
            e.1 = e.1.max(v);
        }
    }
    let mut pts: Vec<([f64; 3], f64)> = envelope.into_values().collect();
    pts.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
    let mut csv = format!(
        "x_m,y_m,z_m,{},{},{}\n",
        columns::XI,
        columns::ETA,
        columns::PRESSURE_MPA
    );
    for (p, v) in &pts {
        let (l, d) = fp.pinion.gen.frame.axial(p);
        let (xi, eta) = fp.pinion.bounds.to_unit(l, d);
        writeln!(csv, "{},{},{},{xi},{eta},{}", p[0], p[1], p[2], v * 1e-6)?;
    }
    write_atomic(&sdir.join(format!("pattern_{t}nm.csv")), csv.as_bytes())?;
    write_atomic(
        &sdir.join(format!("pattern_{t}nm.vtu")),
        pattern_vtu(&pts).as_bytes(),
    )?;
    Ok(())
}

/// Sizes and factoring times of this run's bodies, or of the run that
/// solved the positions (kept beside the position cache).
pub(super) fn body_stats(
    cache_dir: &Path,
    pinion: Option<&Member>,
    wheel: Option<&Member>,
) -> anyhow::Result<([usize; 2], [f64; 2])> {
    let bodies_path = cache_dir.join("bodies.json");
    Ok(match (pinion, wheel) {
        (Some(p), Some(w)) => {
            let b = (
                [p.compliance.dofs_free, w.compliance.dofs_free],
                [p.compliance.factor_s, w.compliance.factor_s],
            );
            write_json(&bodies_path, &b)?;
            b
        }
        _ => std::fs::read_to_string(&bodies_path)
            .ok()
            .and_then(|t| serde_json::from_str(&t).ok())
            .unwrap_or(([0; 2], [0.0; 2])),
    })
}

/// A blank pair's unloaded check and loads, on stderr.
pub(super) fn print_summary(summary: &BlankSummary) {
    let u = &summary.unloaded;
    eprintln!(
        "  unloaded ({} N·m): TE mean {:.2} µrad (UTCA {:.2}), ptp {:.2} µrad (UTCA {:.2}), largest difference {:.3} µrad",
        u.torque_nm, u.reference_te_mean_urad, u.utca_te_mean_urad, u.reference_te_ptp_urad,
        u.utca_te_ptp_urad, u.max_abs_difference_urad
    );
    for l in &summary.loads {
        eprintln!(
            "  {:6.1} N·m: TE mean {:8.2} µrad, ptp {:7.2} µrad, penalty check {:.3} %, max pressure {:.0} MPa",
            l.torque_nm, l.te_mean_urad, l.te_ptp_urad, l.penalty_difference_pct, l.max_pressure_mpa
        );
    }
}
