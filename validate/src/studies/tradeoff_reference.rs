//! Run time against error of the FE reference, read from the
//! mesh-convergence study (`validate convergence`,
//! `<out>/<scene>/reference/convergence.json`): each mesh level's TE at the
//! study's position against the Richardson extrapolation.
//!
//! Error: the largest |TE − TE∞| / TE∞ over the torques that have an
//! extrapolation, %. Cost: the study's recorded times of that level: both
//! bodies' factorisations plus the one position's contact solve (s; CPU of
//! the position, wall time of the factorisations as recorded). The default
//! is `validate reference`'s default level (reduced).

use crate::studies::convergence::Convergence;
use crate::studies::tradeoff_stage::{StageTradeoff, TradeoffPoint};
use anyhow::Context;
use std::path::Path;

const LEVEL: &str = "mesh level (elements per flank)";
/// `validate reference --level`'s default.
pub const DEFAULT_LEVEL: &str = "reduced";

/// The study, or None where `validate convergence` has not been run.
pub fn run(out: &Path, scene: &str) -> anyhow::Result<Option<StageTradeoff>> {
    // Read through the reference folder's registry of added files: only a
    // study listed there with its bytes unchanged.
    let dir = out.join(scene).join("reference");
    let p = dir.join("convergence.json");
    let bytes = match formats::added_files::read_added(&dir, "convergence.json")? {
        formats::added_files::AddedState::Current(b) => b,
        formats::added_files::AddedState::Missing => return Ok(None),
        other => {
            eprintln!(
                "stage trade-offs: not using {}: {}; `make convergence` recomputes it",
                p.display(),
                other.why_not().unwrap_or_default()
            );
            return Ok(None);
        }
    };
    let c: Convergence =
        serde_json::from_slice(&bytes).with_context(|| format!("reading {}", p.display()))?;
    let mut st = StageTradeoff::new(
        "reference",
        "FE reference: time against the error to the Richardson extrapolation",
        "both factorisations + one position (s)",
        &format!(
            "largest |TE − TE∞| / TE∞ over the torques with an extrapolation (observed order ≥ {}), one position ({:.2}° pinion rotation), standard blanks; from `validate convergence`",
            crate::studies::convergence::MIN_ORDER,
            c.pinion_rotation_deg
        ),
    );
    for (k, l) in c.levels.iter().enumerate() {
        let label = format!("{} ({} × {})", l.level, l.profile_elements, l.face_elements);
        let errs: Vec<f64> = c
            .torques
            .iter()
            .filter_map(|t| t.error_to_extrapolation_pct.get(k).copied().flatten())
            .collect();
        if errs.is_empty() {
            st.skip(
                LEVEL,
                &label,
                "no torque has a Richardson extrapolation".into(),
            );
            continue;
        }
        st.push(TradeoffPoint {
            parameter: LEVEL.into(),
            setting: label,
            value: (l.profile_elements * l.face_elements) as f64,
            cpu_s: l.factor_s[0] + l.factor_s[1] + l.position_s,
            error_pct: errs.iter().fold(0.0f64, |a, e| a.max(e.abs())),
            secondary_error_pct: None,
            is_default: l.level == DEFAULT_LEVEL,
        });
    }
    st.finish();
    Ok(Some(st))
}
