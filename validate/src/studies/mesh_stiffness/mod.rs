//! `validate mesh-stiffness <scene>`: the mesh stiffness of the pair at one
//! position from the FE reference (both tet10 bodies in penalty contact,
//! smooth flanks) on the scene's mesh levels, against our LTCA's at the
//! same position and torques on the stiffness files of the same levels.
//!
//! At each operating torque T the torques T(1 − ε), T, T(1 + ε) are solved
//! (ε = [`solver::lumped::from_ltca::TANGENT_STEP`], the lumped model's) and
//!
//! ```text
//! κ_tangent = 2εT / (θ(T(1+ε)) − θ(T(1−ε)))     (N·m/rad, θ the wheel lag)
//! κ_secant  = T / (θ(T) − θ₀)                    (θ₀ the unloaded TE)
//! k = κ / (r₁ r₂)                                 (N/m along the normal)
//! ```
//!
//! The tangent is what the lumped model uses (k = dF/dδ); the secant F/δ
//! stands beside it. θ₀ is, for the FE, its own TE at 1e-3 N·m, for the
//! LTCA the UTCA TE. Both models' κ are turned into N/m with the same
//! levers r₁ = T/ΣFₙ, r₂ = T₂/ΣFₙ of our LTCA on the reduced level at T,
//! so the comparison in N/m is the comparison of κ. Frictionless in both
//! (the lumped scenes' LTCA is frictionless too; friction enters the 8-DOF
//! model separately).
//!
//! Position: unless given, the middle of the longest run of positions with
//! the fewest tooth pairs in contact in our LTCA over one mesh cycle at the
//! first operating torque ([`middle_of_fewest`]): the mesh's softest
//! stretch, where the loaded tooth pair(s) carry everything.
//!
//! The FE level results are kept under `<out>/<scene>/reference/mesh_stiffness/`
//! (added files with the hash of meshes, settings, position and torques,
//! as the convergence study's); the summary is the result set
//! `<out>/<scene>/mesh_stiffness/` (`summary.json`).

mod rows;
mod run;

pub use run::run;

use crate::reference::reference_ltca::ReferenceSettings;
use anyhow::Context;
use geometry::design::Member as Which;
use geometry::scene::{Blank, MeshLevel};
use serde::{Deserialize, Serialize};
use solver::lumped::from_ltca::torsional_tangent;
use std::path::{Path, PathBuf};

/// The summary file's name in the result set.
pub const SUMMARY_FILE: &str = "summary.json";

/// What the study solves.
#[derive(Debug, Clone)]
pub struct StiffnessStudy {
    /// FE mesh levels, coarse to fine.
    pub levels: Vec<String>,
    /// Position index in the scene's sweep; None: [`middle_of_fewest`].
    pub position: Option<usize>,
    pub settings: ReferenceSettings,
    pub block: usize,
    /// Memory the two FE factors may take together, bytes (None: what the
    /// system has available).
    pub memory_bytes: Option<usize>,
    /// The lumped scene whose reduced meshes and roughness grades the
    /// summary relates to (its reduced meshes compared by inputs hash, its
    /// `[lumped.roughness]` counted against the slices and the FE meshes).
    pub lumped_scene: Option<PathBuf>,
}

/// One model's stiffness at one operating torque.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ModelStiffness {
    /// "fe" (the FE reference) or "ltca" (our LTCA).
    pub model: String,
    pub level: String,
    /// Elements along the profile × face width of the level.
    pub elements: [u32; 2],
    /// Loaded TE at T, µrad.
    pub te_urad: f64,
    /// Unloaded TE θ₀ it is measured from, µrad.
    pub unloaded_te_urad: f64,
    pub tangent_nm_per_rad: f64,
    pub secant_nm_per_rad: f64,
    pub tangent_n_per_m: f64,
    pub secant_n_per_m: f64,
    /// FE only: the tangent at the check penalty factor, N/m.
    pub tangent_check_n_per_m: Option<f64>,
    /// LTCA only: tooth pairs carrying load at T(1 − ε), T, T(1 + ε) (a
    /// change inside the stencil makes the tangent the slope across an
    /// engagement).
    #[serde(default)]
    pub pairs_in_contact: Option<[usize; 3]>,
    /// (tangent − the finest FE level's tangent) / that, %.
    pub tangent_vs_finest_fe_pct: Option<f64>,
}

/// Both models at one operating torque.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct TorqueStiffness {
    pub torque_nm: f64,
    /// T(1 − ε), T, T(1 + ε), N·m.
    pub tangent_torques_nm: [f64; 3],
    /// r₁, r₂ of our LTCA (reduced level) at T, m.
    pub levers_m: [f64; 2],
    pub models: Vec<ModelStiffness>,
    /// Richardson extrapolation of the FE tangent over three levels
    /// (observed order ≥ [`MIN_ORDER`]), N/m, and its order.
    pub fe_extrapolated_tangent_n_per_m: Option<f64>,
    pub fe_observed_order: Option<f64>,
}

/// One FE level's size and cost.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct FeLevelCost {
    pub level: String,
    pub elements: [u32; 2],
    pub dofs: [usize; 2],
    pub constraints: usize,
    /// Whole Cholesky factors (pinion, wheel) and their estimate, GB.
    pub factor_gb: [f64; 2],
    pub estimated_factor_gb: [f64; 2],
    pub factor_s: [f64; 2],
    /// The position at all torques (after factoring), s.
    pub position_s: f64,
    /// The FE's TE at 1e-3 N·m and the UTCA's at the position, µrad.
    pub unloaded_te_urad: f64,
    pub utca_te_urad: f64,
}

/// The study's summary.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct MeshStiffnessSummary {
    pub scene: String,
    pub design: String,
    pub teeth: [u32; 2],
    /// Position index in the sweep, pinion rotation from the sweep start.
    pub position_index: usize,
    pub pinion_rotation_deg: f64,
    /// How the position was chosen.
    pub position_choice: String,
    /// Tooth pairs in contact at each position of one mesh cycle (LTCA,
    /// reduced level, first operating torque).
    pub pairs_in_contact: Vec<usize>,
    /// Our LTCA's tangent k over that mesh cycle (reduced level, first
    /// operating torque): min, mean, max, N/m.
    pub cycle_tangent_n_per_m: [f64; 3],
    pub torques: Vec<TorqueStiffness>,
    pub fe_levels: Vec<FeLevelCost>,
    /// FE levels not solved, with why (e.g. the factor memory check).
    pub fe_levels_skipped: Vec<(String, String)>,
    /// LTCA levels without stiffness files, with why.
    pub ltca_levels_skipped: Vec<(String, String)>,
    /// The lumped scene compared with, and whether its reduced meshes have
    /// the same inputs hash as this scene's (None: not compared).
    pub lumped_scene: Option<String>,
    pub reduced_meshes_match_lumped: Option<bool>,
    /// Seed 003's roughness against what resolves it.
    pub roughness: Option<crate::studies::asperity_resolution::Resolution>,
    pub penalty_factors: [f64; 2],
    /// Peak resident memory of the study's process, GiB, and its wall time, s.
    pub peak_memory_gb: f64,
    pub wall_s: f64,
}

/// Tooth pairs carrying more than 0.1 % of the total normal force.
fn loaded_pairs(l: &solver::ltca::PositionLoad) -> usize {
    let total: f64 = l.pair_force.iter().map(|f| f.1).sum();
    l.pair_force.iter().filter(|f| f.1 > 1e-3 * total).count()
}

/// The middle of the longest run of consecutive entries equal to the
/// smallest value of `pairs` (the first such run on a tie); 0 when empty.
pub fn middle_of_fewest(pairs: &[usize]) -> usize {
    let Some(&min) = pairs.iter().min() else {
        return 0;
    };
    let (mut best, mut best_len, mut i) = (0, 0, 0);
    while i < pairs.len() {
        if pairs[i] != min {
            i += 1;
            continue;
        }
        let start = i;
        while i < pairs.len() && pairs[i] == min {
            i += 1;
        }
        if i - start > best_len {
            (best, best_len) = (start, i - start);
        }
    }
    best + (best_len - 1) / 2
}

/// κ (tangent, secant, tangent at the check penalty) from the TE at
/// `torques` (ascending, rad), the three torques of `t3` picked from them.
fn kappas(torques: &[f64], te: &[f64], t3: [f64; 3], te0: f64) -> anyhow::Result<[f64; 2]> {
    let at = |t: f64| -> anyhow::Result<f64> {
        torques
            .iter()
            .position(|&x| (x - t).abs() <= 1e-12 * t.abs().max(1.0))
            .map(|i| te[i])
            .with_context(|| format!("no solution at {t} N·m"))
    };
    let tangent =
        torsional_tangent([t3[0], t3[2]], [at(t3[0])?, at(t3[2])?]).with_context(|| {
            format!(
                "the loaded TE does not grow from {} to {} N·m",
                t3[0], t3[2]
            )
        })?;
    let secant = t3[1] / (at(t3[1])? - te0);
    Ok([tangent, secant])
}

/// Whether the reduced pinion and wheel meshes of two scene folders have
/// the same inputs hash (None when either manifest lacks them).
fn same_reduced_meshes(a: &Path, b: &Path) -> Option<bool> {
    let hashes = |dir: &Path| -> Option<Vec<String>> {
        let m = formats::manifest::Manifest::read(dir).ok()?;
        [Which::Pinion, Which::Wheel]
            .iter()
            .map(|&w| {
                let stem = formats::paths::mesh_stem(w, Blank::Standard, MeshLevel::Reduced);
                m.meshes.get(&stem).map(|e| e.inputs_hash.clone())
            })
            .collect()
    };
    Some(hashes(a)? == hashes(b)?)
}

#[cfg(test)]
mod tests {
    use super::middle_of_fewest;

    /// The longest run of the smallest count wins; its middle (lower on an
    /// even length) is taken.
    #[test]
    fn position_is_the_middle_of_the_longest_fewest_pairs_run() {
        assert_eq!(middle_of_fewest(&[2, 1, 2, 1, 1, 1, 2]), 4);
        assert_eq!(middle_of_fewest(&[3, 2, 2, 3, 2, 2, 2, 2]), 5);
        assert_eq!(middle_of_fewest(&[2, 2, 2]), 1);
        assert_eq!(middle_of_fewest(&[]), 0);
    }
}
