//! The reference sweep's root (fillet) stress outputs: per load, each
//! member's largest tension in a loaded flank's fillet and largest
//! compression in an other flank's fillet over the sweep, with where they
//! sit ([`RootStressSummary`], in the blank's `summary.json`), and every
//! position's fillets in `root_stress.csv`.

use crate::reference::reference_ltca::PositionResult;
use formats::columns;
use formats::output::write_atomic;
use preprocess::root_stress::FilletStress;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::Path;

/// Where on which fillet, at which position, an extreme stress sits.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FilletPlace {
    /// Pinion rotation from the sweep's start, deg.
    pub pinion_rotation_deg: f64,
    pub tooth: usize,
    /// Face-width position (0 toe, 1 heel) and fillet height (0 root, 1
    /// flank junction).
    pub xi: f64,
    pub height: f64,
}

/// One member's extreme root stresses over a sweep at one torque.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RootStressExtreme {
    /// Largest first principal stress in a loaded flank's fillet, MPa.
    pub tension_mpa: f64,
    pub tension_at: FilletPlace,
    /// Smallest third principal stress in an other flank's fillet, MPa
    /// (negative: compression).
    pub compression_mpa: f64,
    pub compression_at: FilletPlace,
}

/// Pinion's and wheel's extremes at one torque.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RootStressSummary {
    pub pinion: RootStressExtreme,
    pub wheel: RootStressExtreme,
}

/// The extremes of member `body` (0 pinion, 1 wheel) at torque index `k`
/// over the positions `res`, `rotation` turning a pinion angle into the
/// sweep's rotation (deg); None when a position has no root stress.
fn extreme(
    res: &[PositionResult],
    k: usize,
    body: usize,
    rotation: &dyn Fn(f64) -> f64,
) -> Option<RootStressExtreme> {
    let mut out: Option<RootStressExtreme> = None;
    for r in res {
        let fillets = &r.loads.get(k)?.root_stress.as_ref()?[body];
        for f in fillets {
            let place = |xi, height| FilletPlace {
                pinion_rotation_deg: rotation(r.phi),
                tooth: f.tooth,
                xi,
                height,
            };
            let e = out.get_or_insert(RootStressExtreme {
                tension_mpa: f64::NEG_INFINITY,
                tension_at: place(f64::NAN, f64::NAN),
                compression_mpa: f64::INFINITY,
                compression_at: place(f64::NAN, f64::NAN),
            });
            if f.loaded_side && f.max_principal_pa * 1e-6 > e.tension_mpa {
                e.tension_mpa = f.max_principal_pa * 1e-6;
                e.tension_at = place(f.max_xi, f.max_height);
            }
            if !f.loaded_side && f.min_principal_pa * 1e-6 < e.compression_mpa {
                e.compression_mpa = f.min_principal_pa * 1e-6;
                e.compression_at = place(f.min_xi, f.min_height);
            }
        }
    }
    out.filter(|e| e.tension_mpa.is_finite() && e.compression_mpa.is_finite())
}

/// Both members' extremes at torque index `k` (None when any position
/// lacks root stress).
pub fn root_stress_summary(
    res: &[PositionResult],
    k: usize,
    rotation: &dyn Fn(f64) -> f64,
) -> Option<RootStressSummary> {
    Some(RootStressSummary {
        pinion: extreme(res, k, 0, rotation)?,
        wheel: extreme(res, k, 1, rotation)?,
    })
}

/// Every position's fillets at every torque: `root_stress.csv`. Writes
/// nothing when no position has root stress.
pub(crate) fn write_root_stress_csv(
    path: &Path,
    res: &[PositionResult],
    rotation: &dyn Fn(f64) -> f64,
) -> anyhow::Result<()> {
    let mut s = format!(
        "{},torque_nm,member,tooth,fillet,sigma1_max_mpa,sigma1_xi,sigma1_height,sigma3_min_mpa,sigma3_xi,sigma3_height\n",
        columns::PINION_ROTATION_DEG
    );
    let mut any = false;
    for r in res {
        for l in &r.loads {
            let Some(rs) = &l.root_stress else { continue };
            for (member, fillets) in ["pinion", "wheel"].iter().zip(rs) {
                for f in fillets {
                    any = true;
                    row(&mut s, rotation(r.phi), l.torque_nm, member, f)?;
                }
            }
        }
    }
    if any {
        write_atomic(path, s.as_bytes())?;
    }
    Ok(())
}

fn row(s: &mut String, deg: f64, t: f64, member: &str, f: &FilletStress) -> std::fmt::Result {
    writeln!(
        s,
        "{deg},{t},{member},{},{},{},{},{},{},{},{}",
        f.tooth,
        if f.loaded_side { "loaded" } else { "opposite" },
        f.max_principal_pa * 1e-6,
        f.max_xi,
        f.max_height,
        f.min_principal_pa * 1e-6,
        f.min_xi,
        f.min_height
    )
}
