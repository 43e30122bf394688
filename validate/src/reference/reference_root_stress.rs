//! The reference sweep's root (fillet) stress outputs: per load, each
//! member's largest tension in a loaded flank's fillet and largest
//! compression in an other flank's fillet over the sweep, with where they
//! sit ([`RootStressSummary`], in the blank's `summary.json`), and every
//! position's fillets in `root_stress.csv`.

use crate::reference::reference_ltca::PositionResult;
use formats::output::write_atomic;
use formats::root_stress::{fillets_csv, summarize, RootStressSummary};
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

/// Every position's fillets at every torque: `root_stress.csv`
/// ([`formats::root_stress::fillets_csv`]). Writes nothing when no
/// position has root stress.
pub(crate) fn write_root_stress_csv(
    path: &Path,
    res: &[PositionResult],
    rotation: &dyn Fn(f64) -> f64,
) -> anyhow::Result<()> {
    let rows = res.iter().flat_map(|r| {
        r.loads.iter().filter_map(move |l| {
            l.root_stress
                .as_ref()
                .map(|rs| (rotation(r.phi), l.torque_nm, rs))
        })
    });
    if let Some(s) = fillets_csv(rows) {
        write_atomic(path, s.as_bytes())?;
    }
    Ok(())
}
