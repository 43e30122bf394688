use super::*;
use crate::reference::contact_surface::MasterSurface;
use fem::structured::{faces_where, mapped_block};

fn straight_line(y: f64, z: f64, len: f64) -> LoadLine {
    let pts: Vec<[f64; 3]> = (0..=40).map(|i| [len * i as f64 / 40.0, y, z]).collect();
    let nrm = vec![[0.0, 0.0, 1.0]; pts.len()];
    LoadLine::new(pts, nrm, [0.0, 1.0, 0.0])
}

/// Force balance: the consistent forces of the Hertz strip on a flat
/// face add up to q · L along the inward normal, with no tangential
/// resultant and the centre of pressure on the line.
#[test]
fn hertz_strip_resultant_equals_line_load_times_length() {
    let block = mapped_block([8, 8, 2], |p| [p[0] * 0.02, p[1] * 0.01, p[2] * 0.004]);
    let top = faces_where(&block, |p| p[2] > 1.0 - 1e-12);
    let line = straight_line(0.0043, 0.004, 0.015);
    let (q, b) = (2.0e5, 0.9e-3);
    let (f, applied) = strip_forces(&block.mesh, &top, &line, q, b, 8);
    assert!((applied / (q * 0.015) - 1.0).abs() < 2e-3, "{applied}");
    let mut res = [0.0; 3];
    let mut moment_y = 0.0;
    for &(d, v) in &f {
        res[d % 3] += v;
        if d % 3 == 2 {
            moment_y += v * block.mesh.nodes[d / 3][1];
        }
    }
    let expected = -q * 0.015;
    assert!(
        (res[2] / expected - 1.0).abs() < 2e-3,
        "{res:?} vs {expected}"
    );
    assert!(res[0].abs() < 1e-9 * q && res[1].abs() < 1e-9 * q);
    let y_c = moment_y / res[2];
    assert!((y_c - 0.0043).abs() < 1e-3 * b, "centre {y_c}");
}

/// A rigid translation read back at a surface point of a curved
/// (mid-node displaced) quadratic face gives the translation.
#[test]
fn surface_value_reads_an_affine_field_exactly() {
    let block = mapped_block([3, 3, 2], |p| {
        [
            p[0] * 0.01,
            p[1] * 0.01,
            p[2] * 0.005 + 1e-4 * (3.0 * p[0]).sin(),
        ]
    });
    let top = faces_where(&block, |p| p[2] > 1.0 - 1e-12);
    let u: Vec<f64> = block
        .mesh
        .nodes
        .iter()
        .flat_map(|x| [1e-6, -2e-6, 3e-6 + 1e-4 * x[0]])
        .collect();
    let x: f64 = 0.0043;
    let p = [x, 0.0061, 0.005 + 1e-4 * (3.0 * x / 0.01).sin()];
    let surface = MasterSurface::new(block.mesh.nodes.clone(), top);
    let v = surface_value(&surface, &u, p, [0.0, 0.0, 1.0]);
    let v = v.expect("point on the top face");
    assert!((v - (3e-6 + 1e-4 * x)).abs() < 1e-9, "{v}");
}

/// Summation of the reduced model: global field times forces plus WB.
#[test]
fn reduced_prediction_adds_global_response_and_weber_banaschek() {
    let g = |k: usize, j: usize| 1.0 / (1.0 + (k as f64 - j as f64).abs());
    let (glob, tot) = reduced_prediction(g, &[1.0, 2.0], &[0.5, 0.25]);
    assert_eq!(glob, vec![1.0 + 1.0, 0.5 + 2.0]);
    assert_eq!(tot, vec![2.5, 2.75]);
}

/// The standard pinion's study keeps the file the report reads; another
/// body's goes beside it under its own name, so neither replaces the other.
#[test]
fn each_body_writes_its_own_file_and_the_standard_pinion_the_reports() {
    use geometry::design::Member;
    use geometry::scene::Blank;
    assert_eq!(
        file_name(Member::Pinion, Blank::Standard, 0),
        "line_load.json"
    );
    assert_eq!(
        file_name(Member::Wheel, Blank::Lightweight, 0),
        "line_load_wheel_lightweight.json"
    );
    assert_eq!(
        file_name(Member::Wheel, Blank::Standard, 0),
        "line_load_wheel_standard.json"
    );
    assert_eq!(
        file_name(Member::Pinion, Blank::Standard, -1),
        "line_load_pinion_standard_tooth-1.json"
    );
    assert_eq!(
        file_name(Member::Wheel, Blank::Lightweight, 1),
        "line_load_wheel_lightweight_tooth+1.json"
    );
}

/// A result written before the study named its blank was the standard
/// pinion's, and reads as such.
#[test]
fn a_result_without_a_blank_reads_as_the_standard_pinions() {
    let json = r#"{"member": "pinion", "flank": "concave", "stiffness_file": "f",
        "stiffness_mesh_sha256": "x", "line_load_n_per_m": 1e5, "profile_row": 6,
        "eta": 0.5, "line_length_mm": 30.0, "compared_columns": [2], "levels": []}"#;
    let r: LineLoad = serde_json::from_str(json).unwrap();
    assert_eq!(r.member, geometry::design::Member::Pinion);
    assert_eq!(r.blank, geometry::scene::Blank::Standard);
    assert_eq!(r.response_offset, 0);
    let mut s = String::new();
    r.markdown(&mut s);
    assert!(s.contains("pinion tooth 0 (standard blank)"), "{s}");
    assert!(s.contains("over the whole face width") && s.contains("Weber–Banaschek approach"));
    // A partial line on the wheel, compared on the neighbouring tooth, says so.
    let r = LineLoad {
        member: geometry::design::Member::Wheel,
        blank: geometry::scene::Blank::Lightweight,
        response_offset: 1,
        loaded_columns: Some((33, 39)),
        ..r
    };
    let mut s = String::new();
    r.markdown(&mut s);
    assert!(s.contains("wheel tooth 0 (lightweight blank)"), "{s}");
    assert!(s.contains("over grid columns 33..=39 only"), "{s}");
    assert!(s.contains("tooth +1") && s.contains("no local term"), "{s}");
    assert!(!s.contains("whole face width"), "{s}");
}
