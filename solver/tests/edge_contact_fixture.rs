//! Edge-contact detection on the example-02 stiffness fixture
//! (the white-paper pair, standard blanks, 6 × 10 contact grid; no gmsh):
//! none at 30 N·m, the pinion's tip named from 100 N·m (at the sweep's
//! first position the leaving pair's loaded contact line ends at the
//! pinion's tip: 0.07 mm of Hertz half-width past it at 100 N·m, 0.29 mm at
//! 300 N·m), and the detection's threshold against a hand-computed profile
//! distance.
use solver::stage::context::LoadedPair;

use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene, Scene};
use geometry::utca::roll_surface;
use solver::element::compliance::PairCompliance;
use solver::element::edge_contact::{profile_length_per_eta, slice_edges};
use solver::ltca::{geometry as slice_geometry, run, PositionResult};
use solver::stage::context::scene_sweep;
use solver::stage::ltca::{first_edge_contact, Edge};
use std::path::{Path, PathBuf};

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/02_ltca_fixture")
}

struct Setup {
    scene: LoadedScene,
    g: PairGeometry,
    pc: PairCompliance,
}

fn setup() -> Setup {
    let dir = fixture();
    let scene = Scene::load(&dir.join("scene.toml")).unwrap();
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let meshes = dir.join("meshes").join(&scene.scene.name);
    let pc = LoadedPair::load(&scene, &g, &meshes, [Blank::Standard; 2])
        .unwrap()
        .pc;
    Setup { scene, g, pc }
}

fn sweep_at(s: &Setup, torques: &[f64]) -> Vec<PositionResult> {
    let fp = s.g.side(s.scene.scene.loaded_flank);
    let rs = roll_surface(fp, &s.scene.scene.utca).unwrap();
    run(
        fp,
        &rs,
        &s.pc,
        &scene_sweep(&s.scene, &s.g, Blank::Standard),
        torques,
    )
    .unwrap()
}

#[test]
fn edge_contact_is_absent_at_30_nm_and_the_pinion_tip_is_named_from_100_nm() {
    let s = setup();
    let torques = [10.0, 30.0, 100.0, 300.0, 3000.0];
    let res = sweep_at(&s, &torques);
    let found: Vec<_> = (0..torques.len())
        .map(|i| first_edge_contact(&res, i))
        .collect();
    for (t, e) in torques.iter().zip(&found) {
        println!("{t} N·m: {e:?}");
    }
    assert!(found[..2].iter().all(|e| e.is_none()), "{found:?}");
    let e = found[2].expect("no edge contact at 100 N·m");
    assert_eq!(e.edge, Edge::PinionTip, "{e:?}");
    assert!(e.overshoot_mm > 0.0 && e.overshoot_mm < 0.2, "{e:?}");
    let e300 = found[3].unwrap();
    assert!(e300.overshoot_mm > e.overshoot_mm, "{e300:?}");
    // Once reached, an edge stays reached at higher loads.
    let first = found.iter().position(|e| e.is_some()).unwrap();
    assert!(found[first..].iter().all(|e| e.is_some()), "{found:?}");
    // The named edge is where the loaded slice really is.
    let p = res
        .iter()
        .find(|p| p.loads[3].edge.is_some())
        .expect("a position with edge contact");
    let hit = p.loads[3].edge.unwrap();
    let on_edge = p.loads[3]
        .slices
        .iter()
        .filter(|l| l.pair == hit.pair)
        .any(|l| match hit.edge {
            Edge::Toe => l.xi < 0.1,
            Edge::Heel => l.xi > 0.9,
            Edge::PinionTip => l.eta > 0.5,
            Edge::PinionRootFillet => l.eta < 0.5,
            // The wheel's tip meets the pinion's lower flank, its fillet
            // limit the pinion's upper flank.
            Edge::WheelTip => l.eta < 0.5,
            Edge::WheelRootFillet => l.eta > 0.5,
        });
    assert!(on_edge, "{hit:?} at {}", p.rotation.to_degrees());
}

#[test]
fn profile_edge_threshold_matches_the_hand_computed_distance_to_the_pinion_tip() {
    let s = setup();
    let fp = s.g.side(s.scene.scene.loaded_flank);
    let rs = roll_surface(fp, &s.scene.scene.utca).unwrap();
    let sweep = scene_sweep(&s.scene, &s.g, Blank::Standard);
    let tau = fp.pinion.gen.frame.pitch();
    let geo = slice_geometry(fp, &rs, sweep.start, tau, 10);
    // A mid-face slice moved up the profile to η = 0.9.
    let mut slice = *geo
        .slices
        .iter()
        .min_by(|a, b| (a.xi - 0.5).abs().total_cmp(&(b.xi - 0.5).abs()))
        .unwrap();
    slice.eta = 0.9;
    slice.band = [slice.xi - 0.05, slice.xi + 0.05];
    slice.wheel_xi_eta = [0.5, 0.5];
    // By hand: the chord from the point to the tip along the profile, in
    // ten pieces (the profile is nearly straight over 10 % of its height).
    let at = |eta: f64| fp.pinion.at_unit(slice.xi, eta).unwrap().pos;
    let mut to_tip = 0.0;
    for k in 0..10 {
        let (a, b) = (at(0.9 + 0.01 * k as f64), at(0.9 + 0.01 * (k + 1) as f64));
        to_tip += (0..3).map(|i| (b[i] - a[i]).powi(2)).sum::<f64>().sqrt();
    }
    assert!(to_tip > 0.2e-3 && to_tip < 5e-3, "{to_tip} m");
    let g = profile_length_per_eta(&fp.pinion, slice.xi, 0.9).unwrap();
    assert!(
        (0.1 * g / to_tip - 1.0).abs() < 0.02,
        "{} vs {to_tip}",
        0.1 * g
    );
    let tip = |b: f64| {
        slice_edges(fp, &slice, b)
            .into_iter()
            .find(|h| h.edge == Edge::PinionTip)
    };
    assert!(tip(0.97 * to_tip).is_none());
    let h = tip(1.03 * to_tip).expect("tip not reached at 1.03 × the distance");
    assert!(
        (h.overshoot_m - 0.03 * to_tip).abs() < 0.02 * to_tip,
        "{} vs {}",
        h.overshoot_m,
        0.03 * to_tip
    );
    // Nothing else at a mid-face band and mid-profile wheel point.
    assert!(slice_edges(fp, &slice, 0.97 * to_tip).is_empty());
    // A band cut at the toe reaches it, with any half-width.
    slice.band = [0.0, 0.05];
    assert!(slice_edges(fp, &slice, 1e-6)
        .iter()
        .any(|h| h.edge == Edge::Toe && h.overshoot_m == 0.0));
}
