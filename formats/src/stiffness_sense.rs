//! Physical sense of a stiffness file's numbers, checked by every reader
//! before use: a compliance is finite, a unit load moves its own point into
//! the tooth (positive diagonal of the loaded tooth's total and local
//! blocks), the loaded tooth's total block is reciprocal (Maxwell–Betti:
//! C_ij = C_ji, since C = Wᵀ K⁻¹ W with K symmetric), and the global
//! block, the one the contact element interpolates, is what the file says
//! it is: total − local on the loaded tooth, total on its neighbours.

use crate::stiffness_file::StiffnessData;

/// Largest |C_ij − C_ji| / C_ii accepted on the loaded tooth's total block.
/// The FE fields are symmetric by construction to round-off (the stiffness
/// stage reports about 1e-12); 1e-6 leaves room and still catches any edit.
pub const RECIPROCITY_TOLERANCE: f64 = 1e-6;

/// Largest |global − (total − local)| / C_ii accepted (C_ii the loaded
/// point's total diagonal): the writer forms global by that one
/// subtraction, so only an edit or a damaged file departs from it.
pub const SPLIT_TOLERANCE: f64 = 1e-9;

/// The first thing wrong with `d`'s numbers, in words a user can act on;
/// `None` when they make sense.
pub fn first_problem(d: &StiffnessData) -> Option<String> {
    let np = d.points();
    let no = d.offsets.len();
    let ns = d.solved_teeth.len();
    for (name, v) in [
        ("compliance/total", &d.total),
        ("compliance/local", &d.local),
        ("compliance/global", &d.global),
        ("grid/depth_h", &d.depth_h),
        ("grid/position", &d.position),
        ("grid/normal", &d.normal),
        ("grid/lever", &d.lever),
    ] {
        if let Some(k) = v.iter().position(|x| !x.is_finite()) {
            return Some(format!("{name}[{k}] = {} is not finite", v[k]));
        }
    }
    let Some(o0) = d.offsets.iter().position(|&o| o == 0) else {
        return Some("teeth/offsets has no 0 (the loaded tooth itself)".into());
    };
    if d.total.len() != ns * no * np * np
        || d.local.len() != ns * np * np
        || d.global.len() != ns * no * np * np
    {
        return Some("compliance blocks do not match the grid and teeth".into());
    }
    for s in 0..ns {
        let t = &d.total[(s * no + o0) * np * np..(s * no + o0 + 1) * np * np];
        let l = &d.local[s * np * np..(s + 1) * np * np];
        for i in 0..np {
            let (cii, lii) = (t[i * np + i], l[i * np + i]);
            if cii <= 0.0 || lii <= 0.0 {
                return Some(format!(
                    "solved tooth {}, grid point {i}: diagonal compliance total {cii:e}, local {lii:e} m/N; a unit load must move its own point into the tooth (> 0)",
                    d.solved_teeth[s]
                ));
            }
            for j in 0..i {
                let r = (t[i * np + j] - t[j * np + i]).abs() / cii.min(t[j * np + j]);
                if r > RECIPROCITY_TOLERANCE {
                    return Some(format!(
                        "solved tooth {}, grid points {i} and {j}: |C_ij - C_ji| / C_ii = {r:.2e} > {RECIPROCITY_TOLERANCE:e} (not reciprocal)",
                        d.solved_teeth[s]
                    ));
                }
            }
        }
    }
    split_problem(d, o0)
}

/// The first entry of the global block that is not total − local (loaded
/// tooth) or total (neighbours).
fn split_problem(d: &StiffnessData, o0: usize) -> Option<String> {
    let np = d.points();
    let no = d.offsets.len();
    for s in 0..d.solved_teeth.len() {
        let diag = |i: usize| d.total[(s * no + o0) * np * np + i * np + i];
        for o in 0..no {
            let start = (s * no + o) * np * np;
            for i in 0..np {
                for j in 0..np {
                    let k = start + i * np + j;
                    let local = if o == o0 {
                        d.local[s * np * np + i * np + j]
                    } else {
                        0.0
                    };
                    let expected = d.total[k] - local;
                    let r = (d.global[k] - expected).abs() / diag(i);
                    if r > SPLIT_TOLERANCE {
                        return Some(format!(
                            "solved tooth {}, offset {}, grid points {i} -> {j}: compliance/global = {:e} m/N, but total - local = {expected:e} m/N (relative difference {r:.2e} > {SPLIT_TOLERANCE:e})",
                            d.solved_teeth[s], d.offsets[o], d.global[k]
                        ));
                    }
                }
            }
        }
    }
    None
}
