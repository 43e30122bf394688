//! The reference sweep's root (fillet) stress outputs: per load, each
//! member's largest tension in a loaded flank's fillet and largest
//! compression in an other flank's fillet over the sweep, with where they
//! sit ([`RootStressSummary`], in the blank's `summary.json`), and every
//! position's fillets in `root_stress.csv`.

use crate::reference::reference_ltca::PositionResult;
use formats::columns;
use formats::output::write_atomic;
use formats::root_stress::{summarize, FilletStress, RootStressSummary};
use std::fmt::Write as _;
use std::path::Path;

/// Both members' extremes at torque index `k` over the positions `res`,
/// `rotation` turning a pinion angle into the sweep's rotation (deg);
/// None when a position lacks root stress.
pub fn root_stress_summary(
    res: &[PositionResult],
    k: usize,
    rotation: &dyn Fn(f64) -> f64,
) -> Option<RootStressSummary> {
    summarize(res.iter().map(|r| {
        (
            rotation(r.phi),
            r.loads.get(k).and_then(|l| l.root_stress.as_ref()),
        )
    }))
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
