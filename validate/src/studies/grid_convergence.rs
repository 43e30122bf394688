//! `validate grid-convergence <scene>`: the reduced model against its own
//! discretization limit. The scene's quasi-static LTCA (standard blanks,
//! its sweep and loads) is run on its own stiffness files and on those of
//! a family of scenes of the same design at refined contact grids (each
//! with its reduced-order mesh refined to the same grid), and the family's
//! mean and peak-to-peak TE per load are extrapolated to the grid's limit
//! (Richardson over three grids, element size h = 1/√(profile · face)).
//! The report sets that limit beside the reference FE: the part of the
//! reduced model's difference that its own grid makes, and the part that
//! stays (the element's physics).
//!
//! Written to `<out>/<scene>/grid_convergence/summary.json` as a result set
//! recording the stiffness files it read.

use crate::studies::grid_scenes::GridScene;
use anyhow::Context;
use formats::output::write_json;
use formats::paths::MeshLevel;
use formats::result_set::ResultSet;
use formats::stiffness_plan;
use geometry::design::Member;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene};
use geometry::utca::roll_surface;
use serde::{Deserialize, Serialize};
use solver::element::compliance::PairCompliance;
use solver::ltca::{run as run_sweep, Sweep};
use solver::stage::context::{record_stiffness_inputs, LoadedPair};
use solver::stage::ltca::load_summaries;
use std::path::Path;

/// One grid's LTCA.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct GridRun {
    /// Contact grid (profile × face) and its element size 1/√(profile · face).
    pub grid: [u32; 2],
    pub h: f64,
    /// Whether this is the scene's own stiffness files (else a member of
    /// the refined family).
    pub is_scene: bool,
    /// Mean and peak-to-peak TE per load, µrad: (torque N·m, mean, ptp).
    pub loads: Vec<(f64, f64, f64)>,
    /// Thread CPU of the sweep per position, all loads, s.
    pub cpu_s_per_position: f64,
}

/// The study's result.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct GridConvergence {
    pub scene: String,
    /// Coarse to fine.
    pub runs: Vec<GridRun>,
}

fn grid_run(
    fp: &geometry::pair::FlankPair,
    rs: &geometry::utca::RollSurface,
    pc: &PairCompliance,
    sweep: &Sweep,
    torques: &[f64],
    grid: [u32; 2],
    is_scene: bool,
) -> anyhow::Result<GridRun> {
    let res = run_sweep(fp, rs, pc, sweep, torques)?;
    let loads = load_summaries(&res, torques)
        .iter()
        .map(|l| (l.torque_nm, l.te_mean_urad, l.te_ptp_urad))
        .collect();
    let cpu: f64 = res
        .iter()
        .map(|p| p.geometry_s + p.assembly_s + p.loads.iter().map(|l| l.solve_s).sum::<f64>())
        .sum();
    Ok(GridRun {
        grid,
        h: 1.0 / ((grid[0] * grid[1]) as f64).sqrt(),
        is_scene,
        loads,
        cpu_s_per_position: cpu / res.len().max(1) as f64,
    })
}

/// Runs the study on the scene's standard blanks and the `grids` scenes of
/// the same design (a scene of another design is refused by name).
pub fn run(
    scene: &LoadedScene,
    meshes: &Path,
    out: &Path,
    grids: &[std::path::PathBuf],
) -> anyhow::Result<GridConvergence> {
    let sc = &scene.scene;
    let others: Vec<GridScene> = grids
        .iter()
        .map(|p| GridScene::load(p, meshes))
        .collect::<anyhow::Result<_>>()?;
    if let Some(o) = others.iter().find(|o| !o.same_design(scene)) {
        anyhow::bail!(
            "grid scene {}: its design is not scene {}'s; the study compares grids of one design",
            o.scene.scene.name,
            sc.name
        );
    }
    let mut set = ResultSet::begin(
        &out.join(&sc.name).join("grid_convergence"),
        &format!("validate grid-convergence {}", scene.path.display()),
    )?;
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let dir = meshes.join(&sc.name);
    let blanks = [Blank::Standard; 2];
    record_stiffness_inputs(&mut set, scene, &g, &dir, blanks, false)?;
    let own = LoadedPair::load(scene, &g, &dir, blanks)
        .with_context(|| format!("scene {}: standard blanks' stiffness files", sc.name))?;
    let fp = g.side(sc.loaded_flank);
    let rs = roll_surface(fp, &sc.utca)?;
    let torques = &sc.pinion_torque_nm;
    // The scene's stiffness grid: its `[stiffness]` grid, else its mesh's.
    let o = sc.mesh.reduced_order;
    let st = &sc.stiffness;
    let own_grid = if st.grid_profile > 0 && st.grid_face > 0 {
        [st.grid_profile as u32, st.grid_face as u32]
    } else {
        [o.profile, o.face]
    };
    let mut runs = vec![grid_run(
        fp, &rs, &own.pc, &own.sweep, torques, own_grid, true,
    )?];
    for gs in &others {
        let label = format!("grid {}", gs.label());
        for m in [Member::Pinion, Member::Wheel] {
            let p = stiffness_plan::plan(
                &gs.scene,
                &gs.g,
                &gs.dir,
                m,
                Blank::Standard,
                MeshLevel::Reduced,
                gs.scene.scene.loaded_flank,
            )?;
            for (key, sha) in stiffness_plan::inputs_of(&gs.dir, &p)? {
                set.record_input(&format!("{label}:{key}"), &sha)?;
            }
        }
        let pc = gs
            .compliance()
            .with_context(|| format!("{label}: stiffness files in {}", gs.dir.display()))?;
        runs.push(grid_run(fp, &rs, &pc, &own.sweep, torques, gs.grid, false)?);
    }
    runs.sort_by(|a, b| b.h.total_cmp(&a.h));
    let result = GridConvergence {
        scene: sc.name.clone(),
        runs,
    };
    write_json(&set.path().join("summary.json"), &result)?;
    set.commit()?;
    Ok(result)
}
