//! The stress matrix, the regression subset run by `make test`: the
//! load extremes (0 N·m and the matrix's largest listed load, 5,000 N·m)
//! and the coarsest and finest slices (5 and 160 per pair, at 300 N·m) on
//! the white-paper pair (the example-02 stiffness fixture, no gmsh) and on
//! seed 003 (16 × 27; meshes and stiffness files made once under the
//! target's tmp folder, reused by the seed-pair chain test and later runs).
//! Every cell: converged, no NaN or infinity, compressive slice forces
//! only, torque balance ≤ 1e-9 relative (absolute N·m at 0 N·m).

use geometry::design::Member;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene, Scene};
use geometry::utca::roll_surface;
use solver::element::compliance::PairCompliance;
use solver::ltca::{run, Sweep};
use solver::stage::context::{member_compliance, scene_sweep};
use std::path::{Path, PathBuf};
use validate::studies::stress::{cell, ltca_record, Outcome, Study, LOADS_NM, PROBE_NM, SLICES};

const BALANCE: f64 = 1e-9;

fn check(name: &str, scene: &LoadedScene, meshes: &Path) {
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let dir = meshes.join(&scene.scene.name);
    let m = |m| {
        member_compliance(scene, &g, &dir, m, Blank::Standard)
            .unwrap_or_else(|e| panic!("{name}: {e:#}"))
            .0
    };
    let pc = PairCompliance {
        pinion: m(Member::Pinion),
        wheel: m(Member::Wheel),
    };
    let fp = g.side(scene.scene.loaded_flank);
    let rs = roll_surface(fp, &scene.scene.utca).unwrap();
    let sweep = scene_sweep(scene, &g, Blank::Standard);
    let loads = [LOADS_NM[0], LOADS_NM[LOADS_NM.len() - 1]];
    assert_eq!(loads, [0.0, 5000.0]);
    let slices = [SLICES[0], SLICES[SLICES.len() - 1]];
    assert_eq!(slices, [5, 160]);
    let mut cells = Vec::new();
    let res = run(fp, &rs, &pc, &sweep, &loads).unwrap_or_else(|e| panic!("{name}: {e}"));
    for (i, &t) in loads.iter().enumerate() {
        let mut c = cell(name, Study::Load, t, "", t.to_string());
        ltca_record(&mut c, &res, i, t);
        cells.push(c);
    }
    for n in slices {
        let res = run(fp, &rs, &pc, &Sweep { slices: n, ..sweep }, &[PROBE_NM])
            .unwrap_or_else(|e| panic!("{name}, {n} slices: {e}"));
        let mut c = cell(name, Study::Slices, n as f64, "", (n as f64).to_string());
        ltca_record(&mut c, &res, 0, PROBE_NM);
        cells.push(c);
    }
    for c in &cells {
        let what = format!("{name}, {:?} {}", c.study, c.value);
        println!(
            "{what}: balance {:?}, iterations {:?}, active-set changes {:?}, TE mean {:?} µrad, edge {:?}",
            c.torque_balance, c.iterations, c.active_set_changes, c.te_mean_urad, c.edge_contact
        );
        assert_eq!(c.outcome, Outcome::Converged, "{what}");
        assert!(!c.non_finite, "{what}: NaN or infinity");
        assert_eq!(c.compressive_only, Some(true), "{what}");
        let b = c.torque_balance.unwrap();
        assert!(b <= BALANCE, "{what}: torque balance {b:e}");
        assert!(c.te_mean_urad.unwrap().is_finite(), "{what}");
    }
    // The heavier load lags more at every position.
    assert!(res.iter().all(|p| p.loads[1].te > p.loads[0].te), "{name}");
}

#[test]
fn stress_subset_white_paper_pair_on_the_example_02_fixture_converges_with_torque_balance() {
    let dir = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/02_ltca_fixture"
    ));
    let scene = Scene::load(&dir.join("scene.toml")).unwrap();
    check("white paper (fixture)", &scene, &dir.join("meshes"));
}

#[test]
fn stress_subset_seed003_converges_with_torque_balance() {
    let path = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../reference/scenes/seed003_16x27.toml"
    ));
    let scene = Scene::load(&path).unwrap();
    // The seed-pair chain test's folder: whichever runs first makes the
    // meshes and stiffness files, the other finds them current.
    let root = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("seed_pairs");
    preprocess::mesh_stage::run(&scene, &root, preprocess::mesh_stage::Level::Reduced)
        .unwrap_or_else(|e| panic!("seed003, meshes: {e:#}"));
    preprocess::stiffness_stage::run(&scene, &root)
        .unwrap_or_else(|e| panic!("seed003, stiffness files: {e:#}"));
    check("seed003_16x27", &scene, &root);
}
