//! Run time against error and the multibody load cells, on the
//! example-02 stiffness fixture (the white-paper pair, 6 × 10, no gmsh)
//! and the default scene's geometry.

use formats::paths::MeshLevel;
use geometry::design::Member;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene, Scene};
use geometry::utca::roll_surface;
use solver::element::compliance::PairCompliance;
use solver::stage::context::member_compliance;
use std::path::PathBuf;
use validate::studies::grid_scenes::{member_fields, GridScene};
use validate::studies::stress::{cell, loaded_run, probe_table, Outcome, Study, MB_LOADS_NM};
use validate::studies::tradeoff_fields::field_error_pct;
use validate::studies::tradeoff_stage::TARGET_PCT;
use validate::studies::tradeoff_utca;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn fixture() -> (LoadedScene, PathBuf) {
    let dir = root().join("examples/02_ltca_fixture");
    (
        Scene::load(&dir.join("scene.toml")).unwrap(),
        dir.join("meshes"),
    )
}

#[test]
fn stiffness_field_error_is_zero_against_itself_and_one_percent_for_a_field_scaled_by_1_01() {
    let (scene, meshes) = fixture();
    let gs = GridScene::load(&scene.path, &meshes).unwrap();
    let (d, cost) = member_fields(
        &gs.scene,
        &gs.g,
        &gs.dir,
        Member::Pinion,
        MeshLevel::Reduced,
    )
    .unwrap();
    // A checked-in fixture has no stage report: its cost is unknown.
    assert_eq!(cost, None);
    assert_eq!(field_error_pct(&d, &d).unwrap(), 0.0);
    let mut scaled = d.clone();
    scaled.global.iter_mut().for_each(|v| *v *= 1.01);
    // max |u − 1.01 u| / max |1.01 u| = 0.01 / 1.01.
    let e = field_error_pct(&d, &scaled).unwrap();
    assert!((e - 100.0 / 101.0).abs() < 1e-9, "{e} %");
}

#[test]
fn utca_tradeoff_default_is_within_one_percent_and_a_half_degree_step_is_worse_than_the_default() {
    let scene = Scene::load(&root().join("reference/scenes/default.toml")).unwrap();
    let st = tradeoff_utca::run(&scene).unwrap();
    assert!(st.not_run.is_empty(), "{:?}", st.not_run);
    for p in &st.points {
        assert!(p.cpu_s > 0.0 && p.error_pct.is_finite(), "{p:?}");
    }
    let d = st.default.as_ref().expect("default point");
    assert!(d.error_pct < TARGET_PCT, "default {d:?}");
    let coarse = st
        .points
        .iter()
        .find(|p| p.setting == "0.5°")
        .expect("0.5° point");
    assert!(coarse.error_pct > d.error_pct, "{coarse:?} against {d:?}");
    assert!(st.cheapest.is_some());
}

#[test]
fn multibody_at_0_nm_without_coast_flanks_is_refused_and_loaded_runs_balance_the_wheel_impulse() {
    let (scene, meshes) = fixture();
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let dir = meshes.join(&scene.scene.name);
    let (pin, pp) = member_compliance(&scene, &g, &dir, Member::Pinion, Blank::Standard).unwrap();
    let (whl, wp) = member_compliance(&scene, &g, &dir, Member::Wheel, Blank::Standard).unwrap();
    let j = [
        solver::stage::context::inertia(&scene, &g, &dir, &pp, Member::Pinion)
            .unwrap()
            .0,
        solver::stage::context::inertia(&scene, &g, &dir, &wp, Member::Wheel)
            .unwrap()
            .0,
    ];
    let pc = PairCompliance {
        pinion: pin,
        wheel: whl,
    };
    let fp = g.side(scene.scene.loaded_flank);
    let rs = roll_surface(fp, &scene.scene.utca).unwrap();
    let top = MB_LOADS_NM.iter().copied().fold(0.0, f64::max);
    let table = probe_table(&scene, &g, fp, &rs, &pc, top).unwrap();
    let mut c = cell("fixture", Study::MultibodyLoad, 0.0, "N·m", String::new());
    let e = loaded_run(&mut c, &table, j, g.data.mesh_cycle(), 0.0).expect_err("0 N·m refused");
    let msg = e.to_string();
    assert!(
        msg.contains("is below") && msg.contains("holding") || msg.contains("holds the wheel"),
        "{msg}"
    );
    assert!(matches!(
        validate::studies::stress::classify(&e),
        Outcome::Refused(_)
    ));
    for t in [300.0, 3000.0] {
        let mut c = cell("fixture", Study::MultibodyLoad, t, "N·m", String::new());
        loaded_run(&mut c, &table, j, g.data.mesh_cycle(), t).unwrap();
        let b = c.torque_balance.unwrap();
        println!(
            "{t} N·m: impulse balance {b:.3e}, {:?} steps, TE mean {:?} µrad",
            c.steps, c.te_mean_urad
        );
        assert!(!c.non_finite);
        assert!(b <= 1e-9, "{t} N·m: impulse balance {b}");
    }
}

#[test]
fn deflection_to_tooth_thickness_is_zero_unloaded_and_grows_5_to_12_fold_from_300_to_3000_nm() {
    let (scene, meshes) = fixture();
    let gs = GridScene::load(&scene.path, &meshes).unwrap();
    let pc = gs.compliance().unwrap();
    let fp = gs.g.side(scene.scene.loaded_flank);
    let rs = roll_surface(fp, &scene.scene.utca).unwrap();
    let sweep = solver::stage::context::scene_sweep(&scene, &gs.g, Blank::Standard);
    let loads = [0.0, 300.0, 3000.0];
    let res = solver::ltca::run(fp, &rs, &pc, &sweep, &loads).unwrap();
    let r: Vec<f64> = (0..3)
        .map(|i| validate::studies::stress::deflection_to_thickness(&res, i, &gs.g.data))
        .collect();
    println!("deflection / tooth thickness: {r:?}");
    assert!(r[0].abs() < 1e-9, "{r:?}");
    // Nearly linear above the light-load range (Hertzian softening aside).
    let growth = r[2] / r[1];
    assert!((5.0..12.0).contains(&growth), "{r:?}");
    assert!(
        r[2] < validate::studies::stress::DEFLECTION_LIMIT,
        "3000 N·m on the white-paper pair: {r:?}"
    );
}
