//! Misalignments in the loaded TCA and the multibody element, on the
//! checked-in example-02 stiffness fixture (no gmsh): a zero misalignment
//! gives today's TE, and a misaligned pair's element reproduces its UTCA at
//! vanishing load, with the same (body-fixed) stiffness files.
use solver::stage::context::LoadedPair;

use geometry::misalignment::{Component, Misalignment};
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene, Scene};
use geometry::utca::{roll_surface, sweep as utca_sweep};
use solver::element::compliance::PairCompliance;
use solver::ltca::{run, PositionResult};
use solver::multibody::mesh_table::{MeshTable, TableSpec};
use solver::stage::context::scene_sweep;
use std::path::{Path, PathBuf};

fn fixture() -> (LoadedScene, PathBuf) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/02_ltca_fixture");
    let scene = Scene::load(&dir.join("scene.toml")).unwrap();
    let meshes = dir.join("meshes").join(&scene.scene.name);
    (scene, meshes)
}

fn compliance(scene: &LoadedScene, g: &PairGeometry, meshes: &Path) -> PairCompliance {
    LoadedPair::load(scene, g, meshes, [Blank::Standard; 2])
        .unwrap()
        .pc
}

/// The fixture's LTCA sweep with the pair placed by `m` (None: as built).
fn ltca(m: Option<Misalignment>, torques: &[f64]) -> Vec<PositionResult> {
    let (scene, meshes) = fixture();
    let mut g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    // The stiffness files are read for the aligned geometry: they are body-fixed.
    let pc = compliance(&scene, &g, &meshes);
    if let Some(m) = m {
        g.misalign(&m);
    }
    let fp = g.side(scene.scene.loaded_flank);
    let rs = roll_surface(fp, &scene.scene.utca).unwrap();
    run(
        fp,
        &rs,
        &pc,
        &scene_sweep(&scene, &g, Blank::Standard),
        torques,
    )
    .unwrap()
}

fn table(m: Option<Misalignment>) -> MeshTable {
    let (scene, meshes) = fixture();
    let mut g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let pc = compliance(&scene, &g, &meshes);
    if let Some(m) = m {
        g.misalign(&m);
    }
    let fp = g.side(scene.scene.loaded_flank);
    let rs = roll_surface(fp, &scene.scene.utca).unwrap();
    let sweep = scene_sweep(&scene, &g, Blank::Standard);
    let tau = g.data.mesh_cycle();
    let per = (tau / 1f64.to_radians()).round() as usize;
    let spec = TableSpec {
        start: sweep.start,
        direction: sweep.direction,
        step: tau / per as f64,
        positions: per,
        periodic: true,
        slices: scene.scene.ltca.slices,
        lag_nodes: 24,
        torque_max_nm: 600.0,
    };
    let ratio = g.data.members[0].teeth as f64 / g.data.members[1].teeth as f64;
    MeshTable::build(fp, &rs, &pc, &g.frames[0], ratio, spec).unwrap()
}

#[test]
fn zero_misalignment_gives_todays_te_in_ltca_and_multibody_element() {
    let torques = [100.0, 300.0];
    let (a, b) = (
        ltca(None, &torques),
        ltca(Some(Misalignment::default()), &torques),
    );
    assert_eq!(a.len(), b.len());
    let mut worst: f64 = 0.0;
    for (p, q) in a.iter().zip(&b) {
        worst = worst.max((p.utca_te - q.utca_te).abs());
        for (l, m) in p.loads.iter().zip(&q.loads) {
            worst = worst.max((l.te - m.te).abs());
        }
    }
    assert!(
        worst * 1e6 <= 1e-3,
        "LTCA TE differs by {:.3e} urad",
        worst * 1e6
    );
    // The multibody element is the table over (pinion rotation, lag).
    let (ta, tb) = (table(None), table(Some(Misalignment::default())));
    let q1s: Vec<f64> = (0..12).map(|k| k as f64 * 0.01).collect();
    for &q1 in &q1s {
        let (ua, ub) = (ta.unloaded(q1).unwrap()[0], tb.unloaded(q1).unwrap()[0]);
        assert!(
            (ua - ub).abs() * 1e6 <= 1e-3,
            "q1 {q1}: unloaded {ua} vs {ub}"
        );
        for lag in [0.5, 1.0, 2.0].map(|f| ua + f * 50e-6) {
            let r = ta.ratio;
            let (sa, sb) = (
                ta.state(q1, r * q1 - lag).unwrap(),
                tb.state(q1, r * q1 - lag).unwrap(),
            );
            assert_eq!(format!("{sa:?}"), format!("{sb:?}"), "q1 {q1}, lag {lag}");
        }
    }
}

#[test]
fn misaligned_ltca_at_vanishing_load_is_its_utca_and_load_adds_deflection() {
    let m = Misalignment::default()
        .with(Component::PinionAxial, 0.03)
        .with(Component::ShaftAngle, 0.01);
    let res = ltca(Some(m), &[1e-3, 300.0]);
    let aligned = ltca(None, &[1e-3, 300.0]);
    // The UTCA over the same sweep, from geometry alone.
    let (scene, _) = fixture();
    let mut g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    g.misalign(&m);
    let fp = g.side(scene.scene.loaded_flank);
    let rs = roll_surface(fp, &scene.scene.utca).unwrap();
    let mut s = scene.scene.utca.clone();
    s.step_deg = scene.scene.rotation.step_deg;
    let u = utca_sweep(fp, &g.data, &rs, &s);
    let mut shifted: f64 = 0.0;
    for (k, p) in res.iter().enumerate() {
        assert!(
            (p.utca_te - u.te[k]).abs() * 1e6 < 1e-6,
            "position {k}: element's UTCA {} vs UTCA {} urad",
            p.utca_te * 1e6,
            u.te[k] * 1e6
        );
        // 1 mN·m adds well under a hundredth of a microradian.
        let light = p.loads[0].te - p.utca_te;
        assert!(
            (0.0..0.01e-6).contains(&light),
            "position {k}: {light:e} rad"
        );
        // 300 N·m deflects by tens of microradians, as the aligned pair.
        let defl = p.loads[1].te - p.utca_te;
        let defl0 = aligned[k].loads[1].te - aligned[k].utca_te;
        assert!(
            defl > 0.5 * defl0 && defl < 2.0 * defl0,
            "position {k}: {defl:e} vs {defl0:e}"
        );
        shifted = shifted.max((p.utca_te - aligned[k].utca_te).abs());
        assert!(p.loads[1].torque_residual_nm.abs() < 1e-6);
    }
    assert!(
        shifted > 1e-6,
        "the misalignment moved the TE by {shifted:e} rad only"
    );
}

#[test]
fn misaligned_multibody_element_follows_the_misaligned_ltca() {
    let m = Misalignment::default()
        .with(Component::Offset, -0.03)
        .with(Component::WheelAxial, 0.02);
    let t = table(Some(m));
    let res = ltca(Some(m), &[300.0]);
    let aligned = table(None);
    // The table's nodes lie every 1° from the sweep's start, as the fixture's LTCA.
    for (k, p) in res.iter().enumerate().take(18) {
        let q1 = k as f64 * 1f64.to_radians();
        let te0 = t.unloaded(q1).unwrap()[0];
        assert!(
            (te0 - p.utca_te).abs() * 1e6 < 1e-6,
            "node {k}: table {} vs LTCA {} urad",
            te0 * 1e6,
            p.utca_te * 1e6
        );
        let moved = (te0 - aligned.unloaded(q1).unwrap()[0]).abs();
        assert!(
            moved > 10e-6,
            "node {k}: the misalignment moved the element by {moved:e} rad"
        );
    }
}
