//! The study's steps: the LTCA over one mesh cycle for the position, the
//! FE reference and our LTCA at that position per mesh level, the rows of
//! stiffnesses per operating torque, and the summary written as one set.

use super::rows::{fe_level_costs, torque_row};
use super::{
    loaded_pairs, middle_of_fewest, same_reduced_meshes, MeshStiffnessSummary, StiffnessStudy,
    SUMMARY_FILE,
};
use crate::studies::convergence::{LevelResult, LevelSolve, StudyPosition};
use anyhow::Context;
use formats::memory_estimate::TooLarge;
use formats::result_set::{ResultSet, RunLock};
use geometry::design::Member as Which;
use geometry::scene::{Blank, LoadedScene, MeshLevel};
use solver::ltca::PositionResult;
use solver::lumped::from_ltca::{mesh_samples, tangent_torques};
use std::path::Path;

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
    let levels = LevelFiles {
        scene,
        pos: &pos0,
        scene_meshes: &scene_meshes,
    };
    let reduced = levels.compliance(MeshLevel::Reduced, &mut set)?;
    let mut sweep = solver::stage::context::scene_sweep(scene, g, Blank::Standard);
    sweep.friction = 0.0;
    let c = cycle_position(
        fp,
        &rs,
        &reduced,
        &sweep,
        (first_torque, g.data.mesh_cycle()),
        study.position,
    )?;
    let (index, choice) = (c.index, c.choice.clone());
    let pos = StudyPosition::new(scene, index)?;
    let torques = all_torques(&sc.pinion_torque_nm);
    let (fe, fe_skipped) = fe_levels_solved(scene, meshes, out, study, &pos, &torques)?;
    // Our LTCA at the position per level with stiffness files.
    let at = solver::ltca::Sweep {
        start: pos.phi,
        positions: 1,
        ..sweep
    };
    let (ltca, ltca_skipped) = ltca_levels(&levels, &mut set, (fp, &rs), &reduced, &at, &torques)?;
    for l in &fe {
        for (m, sha) in [Which::Pinion, Which::Wheel].iter().zip(&l.mesh_sha256) {
            let stem = formats::paths::stem_named(*m, Blank::Standard, &l.level);
            set.record_input(&format!("mesh:{stem}"), sha)?;
        }
    }
    let mut rows = Vec::new();
    for &t in &sc.pinion_torque_nm {
        rows.push(torque_row(t, sc, &torques, &fe, &ltca)?);
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
    let summary = MeshStiffnessSummary {
        scene: sc.name.clone(),
        design: scene.pair.name.clone(),
        teeth: [g.data.members[0].teeth, g.data.members[1].teeth],
        position_index: index,
        pinion_rotation_deg: (pos.step * index as f64).to_degrees(),
        position_choice: choice,
        pairs_in_contact: c.pairs,
        cycle_tangent_n_per_m: c.cycle_tangent,
        torques: rows,
        fe_levels: fe_level_costs(&fe),
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

/// Mesh levels left out, each with why.
type Skipped = Vec<(String, String)>;

/// The stiffness files of the scene's standard blanks at each mesh level.
struct LevelFiles<'a> {
    scene: &'a LoadedScene,
    pos: &'a StudyPosition,
    scene_meshes: &'a Path,
}

impl LevelFiles<'_> {
    /// The pair compliance of `level`'s stiffness files, recorded as inputs
    /// of `set`.
    fn compliance(
        &self,
        level: MeshLevel,
        set: &mut ResultSet,
    ) -> anyhow::Result<solver::element::compliance::PairCompliance> {
        let (scene, g, scene_meshes) = (self.scene, &self.pos.g, self.scene_meshes);
        let load = |m| {
            solver::stage::context::member_compliance_at(
                scene,
                g,
                scene_meshes,
                m,
                Blank::Standard,
                self.pos.side,
                level,
            )
        };
        let (pinion, wheel) = (load(Which::Pinion)?, load(Which::Wheel)?);
        for plan in [&pinion.1, &wheel.1] {
            for (key, sha) in formats::stiffness_plan::inputs_of(scene_meshes, plan)? {
                set.record_input(&key, &sha)?;
            }
        }
        Ok(solver::element::compliance::PairCompliance {
            pinion: pinion.0,
            wheel: wheel.0,
        })
    }
}

/// Our LTCA over one mesh cycle at the first torque: the tooth pairs in
/// contact per position, the tangent k's minimum, mean and maximum, and
/// the study's position with why it was chosen.
struct CyclePosition {
    pairs: Vec<usize>,
    cycle_tangent: [f64; 3],
    index: usize,
    choice: String,
}

/// The LTCA over the mesh cycle `sweep` on the reduced level's compliance
/// at the first torque (with the pair's mesh cycle, rad), and the position:
/// `given`, else the middle of the longest run with the fewest pairs in
/// contact.
fn cycle_position(
    fp: &geometry::pair::FlankPair,
    rs: &geometry::utca::RollSurface,
    reduced: &solver::element::compliance::PairCompliance,
    sweep: &solver::ltca::Sweep,
    (first_torque, mesh_cycle): (f64, f64),
    given: Option<usize>,
) -> anyhow::Result<CyclePosition> {
    let cycle = solver::ltca::run(fp, rs, reduced, sweep, &tangent_torques(first_torque))
        .context("LTCA over the mesh cycle")?;
    let samples = mesh_samples(&cycle, first_torque, 1.0, mesh_cycle)?;
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
    let (index, choice) = match given {
        Some(i) => (i, "given on the command line".to_string()),
        None => (
            middle_of_fewest(&pairs),
            format!(
                "the middle of the longest run of positions with the fewest tooth pairs in contact ({}) in our LTCA over one mesh cycle at {first_torque} N·m",
                pairs.iter().min().copied().unwrap_or(0)
            ),
        ),
    };
    Ok(CyclePosition {
        pairs,
        cycle_tangent,
        index,
        choice,
    })
}

/// Every torque solved: each operating torque's three tangent torques,
/// ascending, without repeats.
fn all_torques(operating: &[f64]) -> Vec<f64> {
    let mut torques: Vec<f64> = operating.iter().flat_map(|&t| tangent_torques(t)).collect();
    torques.sort_by(f64::total_cmp);
    torques.dedup();
    torques
}

/// The FE reference at the position per level of the study (coarsest
/// first), and the levels left out because their factors would not fit.
fn fe_levels_solved(
    scene: &LoadedScene,
    meshes: &Path,
    out: &Path,
    study: &StiffnessStudy,
    pos: &StudyPosition,
    torques: &[f64],
) -> anyhow::Result<(Vec<LevelResult>, Skipped)> {
    let sc = &scene.scene;
    let lock = RunLock::shared(
        &out.join(&sc.name).join("reference"),
        &format!("validate mesh-stiffness {}", sc.name),
    )?;
    let solve = LevelSolve {
        scene,
        meshes,
        position: pos,
        torques_nm: torques,
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
    Ok((fe, fe_skipped))
}

/// Our LTCA at the position (`at`) per mesh level with stiffness files,
/// coarsest first (the reduced level's compliance given), and the levels
/// without them.
fn ltca_levels(
    levels: &LevelFiles,
    set: &mut ResultSet,
    (fp, rs): (&geometry::pair::FlankPair, &geometry::utca::RollSurface),
    reduced: &solver::element::compliance::PairCompliance,
    at: &solver::ltca::Sweep,
    torques: &[f64],
) -> anyhow::Result<(Vec<(MeshLevel, PositionResult)>, Skipped)> {
    let mut ltca = Vec::new();
    let mut ltca_skipped = Vec::new();
    for level in MeshLevel::FINEST_FIRST.iter().rev().copied() {
        let pc = match level {
            MeshLevel::Reduced => Ok(reduced.clone()),
            l => levels.compliance(l, set),
        };
        match pc {
            Ok(pc) => {
                let r = solver::ltca::run(fp, rs, &pc, at, torques)
                    .with_context(|| format!("LTCA at the position, level {}", level.name()))?;
                ltca.push((level, r.into_iter().next().context("one position")?));
            }
            Err(e) => ltca_skipped.push((level.name().to_string(), format!("{e:#}"))),
        }
    }
    Ok((ltca, ltca_skipped))
}
