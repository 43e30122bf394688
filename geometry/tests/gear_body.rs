//! Gear body geometry (blank polygons, slot sections) without a CAD kernel.

mod common;

use geometry::design::Member;
use geometry::gear_body::{
    blank_shape, revolution_volume, slot_sections, BlankDimensions, BlankDimensionsMm,
};
use geometry::scene::Blank;

#[test]
fn pappus_volume_of_a_rectangle_is_the_annular_cylinder() {
    // Rectangle z ∈ [0, 2], ρ ∈ [1, 3]: V = π (3² − 1²) 2 = 16π.
    let v = revolution_volume(&[[0.0, 1.0], [2.0, 1.0], [2.0, 3.0], [0.0, 3.0]]);
    assert!((v - 16.0 * std::f64::consts::PI).abs() < 1e-12);
    // A right triangle (cone): z ∈ [0, h], ρ from 0 to r at z = h: V = π r² h / 3.
    let v = revolution_volume(&[[0.0, 0.0], [3.0, 0.0], [3.0, 2.0]]);
    assert!((v - std::f64::consts::PI * 4.0 * 3.0 / 3.0).abs() < 1e-12);
}

#[test]
fn blank_polygons_are_simple_and_lightweight_web_is_thinner() {
    let p = common::white_paper();
    let dims = BlankDimensions::resolve(&BlankDimensionsMm::default(), &p);
    let std_w = blank_shape(&p, Member::Wheel, Blank::Standard, &dims);
    let light = blank_shape(&p, Member::Wheel, Blank::Lightweight, &dims);
    assert!(revolution_volume(&light.polygon) < revolution_volume(&std_w.polygon));
    assert!(std_w.holes.is_none());
    let h = light.holes.as_ref().unwrap();
    assert_eq!(h.count, 3);
    assert!(h.circle_radius - 0.5 * h.diameter > light.bore_radius);
    let pin = blank_shape(&p, Member::Pinion, Blank::Standard, &dims);
    for poly in [&std_w.polygon, &light.polygon, &pin.polygon] {
        assert!(poly.iter().all(|q| q[1] > 0.0), "polygon crosses the axis");
    }
}

#[test]
#[ignore = "writes /tmp/gear_body.json for CAD prototyping"]
fn dump_gear_body_json() {
    let p = common::white_paper();
    let g = common::geometry(&p);
    let dims = BlankDimensions::resolve(&BlankDimensionsMm::default(), &p);
    let mut out = serde_json::Map::new();
    for m in [Member::Pinion, Member::Wheel] {
        let s = slot_sections(&g, m, 12, 0.1 * p.face_width, 0.6 * p.normal_module).unwrap();
        out.insert(
            format!("{}_sections", m.name()),
            serde_json::to_value(&s).unwrap(),
        );
        out.insert(format!("{}_teeth", m.name()), p.member(m).teeth.into());
    }
    out.insert(
        "pinion_blank".into(),
        serde_json::to_value(blank_shape(&p, Member::Pinion, Blank::Standard, &dims)).unwrap(),
    );
    out.insert(
        "wheel_standard".into(),
        serde_json::to_value(blank_shape(&p, Member::Wheel, Blank::Standard, &dims)).unwrap(),
    );
    out.insert(
        "wheel_lightweight".into(),
        serde_json::to_value(blank_shape(&p, Member::Wheel, Blank::Lightweight, &dims)).unwrap(),
    );
    std::fs::write("/tmp/gear_body.json", serde_json::to_string(&out).unwrap()).unwrap();
}
