//! The parametric gearbox housing (`geometry::housing_layout`) around the
//! white-paper pair of `white_paper_gearbox.toml`: its walls and floor keep
//! the clearance from both blanks and shafts, a wall moved into the wheel
//! is refused naming it, and a bore narrower than its shaft is refused.

use geometry::housing_layout::{layout, of_scene, polygon_distance, shaft_polygon};
use geometry::pair::PairGeometry;
use geometry::scene::Scene;
use nalgebra::Vector3;
use std::path::PathBuf;

fn scene() -> (geometry::scene::LoadedScene, PairGeometry) {
    let p = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../reference/scenes/white_paper_gearbox.toml"
    ));
    let s = Scene::load(&p).unwrap();
    let g = PairGeometry::build(&s.pair, Some(&s.design_path)).unwrap();
    (s, g)
}

#[test]
fn white_paper_housing_clears_both_blanks_and_shafts() {
    let (s, g) = scene();
    let l = of_scene(&s, &g).unwrap().expect("the scene has a housing");
    assert_eq!(l.walls.len(), 4);
    // The sampled least gap is the clearance (the floor under the wheel's
    // rim), within the sampling's tolerance.
    let c = 10e-3;
    assert!(
        l.least_gap >= c - l.sample_spacing,
        "{} {}",
        l.least_gap,
        l.least_gap_between
    );
    assert!(
        l.least_gap <= c + l.sample_spacing,
        "{} {}",
        l.least_gap,
        l.least_gap_between
    );
    // Frame: X the pinion's axis, Z normal to both axes.
    let x = Vector3::from(l.frame[0]);
    let z = Vector3::from(l.frame[2]);
    assert!((x - g.frames[0].axis()).norm() < 1e-12);
    assert!(z.dot(&g.frames[1].axis()).abs() < 1e-12);
    // A rib per member, on the floor, below its shaft, along it from the
    // first wall's centre to the last's.
    assert_eq!(l.ribs.len(), 2);
    for r in &l.ribs {
        let top = Vector3::from(r.solid.centre).dot(&z) + r.solid.half[2];
        assert!(top < -0.045, "rib top {top}");
        let a = Vector3::from(r.solid.axes[0]);
        assert!((a - g.frames[r.member].axis()).norm() < 1e-12);
        let span = [[0.175, 0.235], [0.095, 0.195]][r.member];
        let c = Vector3::from(r.solid.centre).dot(&a);
        assert!((c - r.solid.half[0] - span[0]).abs() < 1e-12);
        assert!((c + r.solid.half[0] - span[1]).abs() < 1e-12);
    }
    // Every wall stands on the floor's top and holds its bearing's centre.
    let floor_top = Vector3::from(l.floor.centre).dot(&z) + l.floor.half[2];
    for w in &l.walls {
        let bottom = Vector3::from(w.solid.centre).dot(&z) - w.solid.half[2];
        assert!((bottom - floor_top).abs() < 1e-12);
        assert!(w.solid.contains(&Vector3::from(w.seat), 0.0));
        let on = Vector3::from(w.seat) + z * w.bore_radius;
        assert!(w.on_bore(&on, 1e-12));
    }
}

#[test]
fn a_wall_moved_into_the_wheel_is_refused_naming_it() {
    let (s, g) = scene();
    let mut s2 = s.clone();
    let b = s2.scene.bearings.as_mut().unwrap();
    // The wheel's near bearing 20 mm closer to the apex: its wall cuts the
    // wheel's back.
    b.wheel[0].axial_position_mm -= 20.0;
    b.wheel_shaft.as_mut().unwrap().segments[0].from_mm -= 20.0;
    b.wheel_shaft.as_mut().unwrap().seat_mm -= 20.0;
    let e = of_scene(&s2, &g).unwrap_err().to_string();
    assert!(e.contains("the wall of bearings.wheel[0]"), "{e}");
    assert!(e.contains("wheel standard blank"), "{e}");
    assert!(e.contains("clearance_mm = 10 mm"), "{e}");
}

#[test]
fn a_bore_narrower_than_its_shaft_is_refused() {
    let (s, g) = scene();
    let mut s2 = s.clone();
    let h = s2
        .scene
        .bearings
        .as_mut()
        .unwrap()
        .gearbox
        .as_mut()
        .unwrap()
        .housing
        .as_mut()
        .unwrap();
    h.wheel_bore_diameter_mm = 45.0;
    let e = of_scene(&s2, &g).unwrap_err().to_string();
    assert!(e.contains("wheel_bore_diameter_mm = 45 mm"), "{e}");
    assert!(e.contains("70 mm"), "{e}");
}

#[test]
fn shaft_envelope_is_the_segments_cylinders() {
    let sh = geometry::scene_bearings::ShaftMm {
        seat_mm: 10.0,
        segments: vec![
            geometry::scene_bearings::ShaftSegmentMm {
                from_mm: 0.0,
                to_mm: 10.0,
                outer_diameter_mm: 20.0,
                inner_diameter_mm: 0.0,
            },
            geometry::scene_bearings::ShaftSegmentMm {
                from_mm: 10.0,
                to_mm: 30.0,
                outer_diameter_mm: 40.0,
                inner_diameter_mm: 0.0,
            },
        ],
    };
    let p = shaft_polygon(&sh);
    assert!((polygon_distance(&p, [5e-3, 15e-3]) - 5e-3).abs() < 1e-15);
    assert!((polygon_distance(&p, [20e-3, 25e-3]) - 5e-3).abs() < 1e-15);
    assert!((polygon_distance(&p, [20e-3, 10e-3]) + 10e-3).abs() < 1e-15);
    let _ = layout;
}
