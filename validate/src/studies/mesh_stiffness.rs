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

use crate::reference::reference_ltca::ReferenceSettings;
use crate::studies::convergence::{richardson, LevelResult, LevelSolve, StudyPosition, MIN_ORDER};
use anyhow::Context;
use formats::memory_estimate::TooLarge;
use formats::result_set::{ResultSet, RunLock};
use geometry::design::Member as Which;
use geometry::scene::{Blank, LoadedScene, MeshLevel};
use serde::{Deserialize, Serialize};
use solver::lumped::from_ltca::{mesh_samples, tangent_torques, torsional_tangent};
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

/// Runs the study.
pub fn run(
    scene: &LoadedScene,
    meshes: &Path,
    out: &Path,
    study: &StiffnessStudy,
) -> anyhow::Result<MeshStiffnessSummary> {
    let t0 = std::time::Instant::now();
    let sc = &scene.scene;
    let Some(&first_torque) = sc.pinion_torque_nm.first() else {
        anyhow::bail!("scene {}: pinion_torque_nm is empty", sc.name);
    };
    let mut set = ResultSet::begin(
        &out.join(&sc.name).join("mesh_stiffness"),
        &format!("validate mesh-stiffness {}", scene.path.display()),
    )?;
    // Our LTCA over one mesh cycle at the first torque (reduced level):
    // pairs in contact and the tangent k, for the position and the context.
    let pos0 = StudyPosition::new(scene, 0)?;
    let g = &pos0.g;
    let fp = g.side(pos0.side);
    let rs = geometry::utca::roll_surface(fp, &sc.utca)?;
    let scene_meshes = meshes.join(&sc.name);
    // Each level's stiffness files, recorded as inputs of the set.
    let mut compliance =
        |level: MeshLevel| -> anyhow::Result<solver::element::compliance::PairCompliance> {
            let load = |m| {
                solver::stage::context::member_compliance_at(
                    scene,
                    g,
                    &scene_meshes,
                    m,
                    Blank::Standard,
                    pos0.side,
                    level,
                )
            };
            let (pinion, wheel) = (load(Which::Pinion)?, load(Which::Wheel)?);
            for plan in [&pinion.1, &wheel.1] {
                for (key, sha) in formats::stiffness_plan::inputs_of(&scene_meshes, plan)? {
                    set.record_input(&key, &sha)?;
                }
            }
            Ok(solver::element::compliance::PairCompliance {
                pinion: pinion.0,
                wheel: wheel.0,
            })
        };
    let reduced = compliance(MeshLevel::Reduced)?;
    let mut sweep = solver::stage::context::scene_sweep(scene, g, Blank::Standard);
    sweep.friction = 0.0;
    let cycle = solver::ltca::run(fp, &rs, &reduced, &sweep, &tangent_torques(first_torque))
        .context("LTCA over the mesh cycle")?;
    let samples = mesh_samples(&cycle, first_torque, 1.0, g.data.mesh_cycle())?;
    let pairs: Vec<usize> = cycle[..samples.time_s.len()]
        .iter()
        .map(|p| loaded_pairs(&p.loads[1]))
        .collect();
    let k = &samples.tangent_n_per_m;
    let cycle_tangent = [
        k.iter().copied().fold(f64::INFINITY, f64::min),
        k.iter().sum::<f64>() / k.len() as f64,
        k.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    ];
    let (index, choice) = match study.position {
        Some(i) => (i, "given on the command line".to_string()),
        None => (
            middle_of_fewest(&pairs),
            format!(
                "the middle of the longest run of positions with the fewest tooth pairs in contact ({}) in our LTCA over one mesh cycle at {first_torque} N·m",
                pairs.iter().min().copied().unwrap_or(0)
            ),
        ),
    };
    let pos = StudyPosition::new(scene, index)?;

    // Every torque, ascending.
    let mut torques: Vec<f64> = sc
        .pinion_torque_nm
        .iter()
        .flat_map(|&t| tangent_torques(t))
        .collect();
    torques.sort_by(f64::total_cmp);
    torques.dedup();

    // The FE reference per level.
    let lock = RunLock::shared(
        &out.join(&sc.name).join("reference"),
        &format!("validate mesh-stiffness {}", sc.name),
    )?;
    let solve = LevelSolve {
        scene,
        meshes,
        position: &pos,
        torques_nm: &torques,
        settings: study.settings,
        block: study.block,
        memory_bytes: study.memory_bytes,
        lock: &lock,
        cache: "mesh_stiffness",
    };
    let mut fe: Vec<LevelResult> = Vec::new();
    let mut fe_skipped = Vec::new();
    for level in &study.levels {
        match solve.level_result(level) {
            Ok(r) => fe.push(r),
            Err(e) if e.downcast_ref::<TooLarge>().is_some() => {
                eprintln!("mesh-stiffness: FE level {level} not solved: {e:#}");
                fe_skipped.push((level.clone(), format!("{e:#}")));
            }
            Err(e) => return Err(e),
        }
    }
    drop(lock);
    fe.sort_by(|a, b| b.h.total_cmp(&a.h));

    // Our LTCA at the position per level with stiffness files.
    let at = solver::ltca::Sweep {
        start: pos.phi,
        positions: 1,
        ..sweep
    };
    let mut ltca = Vec::new();
    let mut ltca_skipped = Vec::new();
    for level in MeshLevel::FINEST_FIRST.iter().rev().copied() {
        let pc = match level {
            MeshLevel::Reduced => Ok(reduced.clone()),
            l => compliance(l),
        };
        match pc {
            Ok(pc) => {
                let r = solver::ltca::run(fp, &rs, &pc, &at, &torques)
                    .with_context(|| format!("LTCA at the position, level {}", level.name()))?;
                ltca.push((level, r.into_iter().next().context("one position")?));
            }
            Err(e) => ltca_skipped.push((level.name().to_string(), format!("{e:#}"))),
        }
    }
    for l in &fe {
        for (m, sha) in [Which::Pinion, Which::Wheel].iter().zip(&l.mesh_sha256) {
            let stem = formats::paths::stem_named(*m, Blank::Standard, &l.level);
            set.record_input(&format!("mesh:{stem}"), sha)?;
        }
    }
    let elements = |level: &str| {
        let e = match MeshLevel::from_name(level) {
            Some(MeshLevel::Medium) => sc.mesh.medium(),
            Some(MeshLevel::Reference) => sc.mesh.reference,
            _ => sc.mesh.reduced_order,
        };
        [e.profile, e.face]
    };

    let mut rows = Vec::new();
    for &t in &sc.pinion_torque_nm {
        let t3 = tangent_torques(t);
        let mid = torques
            .iter()
            .position(|&x| x == t)
            .context("operating torque solved")?;
        let red = &ltca.first().context("the reduced level's LTCA")?.1.loads[mid];
        let total: f64 = red.pair_force.iter().map(|f| f.1).sum();
        let levers = [t / total, red.wheel_torque_nm / total];
        let to_n_per_m = |kappa: f64| kappa / (levers[0] * levers[1]);
        let mut models = Vec::new();
        for l in &fe {
            let te: Vec<f64> = l.te_urad.iter().map(|v| v * 1e-6).collect();
            let [kt, ks] = kappas(&torques, &te, t3, l.unloaded_te_urad * 1e-6)
                .with_context(|| format!("FE level {}", l.level))?;
            let check = (l.te_check_urad.len() == torques.len())
                .then(|| {
                    let tc: Vec<f64> = l.te_check_urad.iter().map(|v| v * 1e-6).collect();
                    kappas(&torques, &tc, t3, l.unloaded_te_urad * 1e-6).ok()
                })
                .flatten()
                .map(|[k, _]| to_n_per_m(k));
            models.push(ModelStiffness {
                model: "fe".into(),
                level: l.level.clone(),
                elements: [l.profile_elements, l.face_elements],
                te_urad: l.te_urad[mid],
                unloaded_te_urad: l.unloaded_te_urad,
                tangent_nm_per_rad: kt,
                secant_nm_per_rad: ks,
                tangent_n_per_m: to_n_per_m(kt),
                secant_n_per_m: to_n_per_m(ks),
                tangent_check_n_per_m: check,
                pairs_in_contact: None,
                tangent_vs_finest_fe_pct: None,
            });
        }
        for (level, r) in &ltca {
            let te: Vec<f64> = r.loads.iter().map(|l| l.te).collect();
            let [kt, ks] = kappas(&torques, &te, t3, r.utca_te)
                .with_context(|| format!("LTCA level {}", level.name()))?;
            models.push(ModelStiffness {
                model: "ltca".into(),
                level: level.name().into(),
                elements: elements(level.name()),
                te_urad: te[mid] * 1e6,
                unloaded_te_urad: r.utca_te * 1e6,
                tangent_nm_per_rad: kt,
                secant_nm_per_rad: ks,
                tangent_n_per_m: to_n_per_m(kt),
                secant_n_per_m: to_n_per_m(ks),
                tangent_check_n_per_m: None,
                pairs_in_contact: Some(t3.map(|x| {
                    let i = torques.iter().position(|&y| y == x).unwrap_or(mid);
                    loaded_pairs(&r.loads[i])
                })),
                tangent_vs_finest_fe_pct: None,
            });
        }
        if let Some(finest) = fe.last().map(|l| l.level.clone()) {
            let kf = models
                .iter()
                .find(|m| m.model == "fe" && m.level == finest)
                .map(|m| m.tangent_n_per_m)
                .unwrap_or(f64::NAN);
            for m in &mut models {
                m.tangent_vs_finest_fe_pct = Some((m.tangent_n_per_m - kf) / kf * 100.0);
            }
        }
        let fit = (fe.len() == 3)
            .then(|| {
                let k: Vec<f64> = models
                    .iter()
                    .filter(|m| m.model == "fe")
                    .map(|m| m.tangent_n_per_m)
                    .collect();
                richardson([fe[0].h, fe[1].h, fe[2].h], [k[0], k[1], k[2]])
            })
            .flatten()
            .filter(|&(p, _)| p >= MIN_ORDER);
        rows.push(TorqueStiffness {
            torque_nm: t,
            tangent_torques_nm: t3,
            levers_m: levers,
            models,
            fe_extrapolated_tangent_n_per_m: fit.map(|f| f.1),
            fe_observed_order: fit.map(|f| f.0),
        });
    }

    let (lumped_name, same, roughness) = match &study.lumped_scene {
        Some(p) => {
            let lumped = geometry::scene::Scene::load(p)?;
            let same = same_reduced_meshes(&scene_meshes, &meshes.join(&lumped.scene.name));
            let res = crate::studies::asperity_resolution::resolution(&lumped, fp, sc)?;
            (Some(lumped.scene.name.clone()), same, res)
        }
        None => (None, None, None),
    };
    let fe_levels = fe
        .iter()
        .map(|l| FeLevelCost {
            level: l.level.clone(),
            elements: [l.profile_elements, l.face_elements],
            dofs: l.dofs,
            constraints: l.constraints,
            factor_gb: l.factor_bytes.map(|b| b as f64 / 1e9),
            estimated_factor_gb: l.estimated_factor_bytes.map(|b| b / 1e9),
            factor_s: l.factor_s,
            position_s: l.position_s,
            unloaded_te_urad: l.unloaded_te_urad,
            utca_te_urad: l.utca_te_urad,
        })
        .collect();
    let summary = MeshStiffnessSummary {
        scene: sc.name.clone(),
        design: scene.pair.name.clone(),
        teeth: [g.data.members[0].teeth, g.data.members[1].teeth],
        position_index: index,
        pinion_rotation_deg: (pos.step * index as f64).to_degrees(),
        position_choice: choice,
        pairs_in_contact: pairs,
        cycle_tangent_n_per_m: cycle_tangent,
        torques: rows,
        fe_levels,
        fe_levels_skipped: fe_skipped,
        ltca_levels_skipped: ltca_skipped,
        lumped_scene: lumped_name,
        reduced_meshes_match_lumped: same,
        roughness,
        penalty_factors: [
            study.settings.penalty_factor,
            study.settings.penalty_factor_check,
        ],
        peak_memory_gb: formats::output::peak_memory_gb(),
        wall_s: t0.elapsed().as_secs_f64(),
    };
    formats::output::write_json(&set.path().join(SUMMARY_FILE), &summary)?;
    set.commit()?;
    Ok(summary)
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
