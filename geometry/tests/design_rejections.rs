//! Every kind of inconsistent design input is rejected with an error that
//! names the file, the field, the value and the limit.

mod common;

use geometry::design::{pinion_pitch_angle, DesignFile, Hand};
use geometry::pair::PairGeometry;
use std::path::{Path, PathBuf};

/// Writes a design file into a temp dir and runs the full load + tooth checks.
fn check(d: &DesignFile) -> Result<(), String> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("design.toml");
    std::fs::write(&path, toml::to_string(d).unwrap()).unwrap();
    PairGeometry::from_design_file(&path)
        .map(|_| ())
        .map_err(|e| e.to_string())
}

fn check_text(text: &str) -> Result<(), String> {
    DesignFile::parse(text, Path::new("bad.toml"))
        .and_then(|d| d.to_pair(Path::new("bad.toml")))
        .map(|_| ())
        .map_err(|e| e.to_string())
}

/// Asserts the error names the field and carries the given words.
fn rejected(r: Result<(), String>, field: &str, words: &[&str]) {
    let msg = r.expect_err("must be rejected");
    assert!(
        msg.contains("design.toml") || msg.contains("bad.toml"),
        "no file in: {msg}"
    );
    assert!(msg.contains(field), "field {field} not in: {msg}");
    for w in words {
        assert!(msg.contains(w), "'{w}' not in: {msg}");
    }
}

#[test]
fn white_paper_design_passes_every_check() {
    let d = common::white_paper_file();
    check(&d).unwrap();
}

#[test]
fn pitch_angle_that_does_not_match_tooth_numbers_is_rejected() {
    let mut d = common::white_paper_file();
    d.pinion.pitch_angle_deg = 26.0;
    rejected(check(&d), "pinion.pitch_angle_deg", &["26", "24.94"]);
    let mut d = common::white_paper_file();
    d.wheel.pitch_angle_deg = 64.0;
    rejected(check(&d), "wheel.pitch_angle_deg", &["64"]);
}

#[test]
fn zero_or_negative_sizes_are_rejected() {
    let mut d = common::white_paper_file();
    d.pair.face_width_mm = 0.0;
    rejected(check(&d), "pair.face_width_mm", &["= 0", "> 0"]);
    let mut d = common::white_paper_file();
    d.pair.mean_normal_module_mm = -4.325;
    rejected(check(&d), "pair.mean_normal_module_mm", &["-4.325", "> 0"]);
    let mut d = common::white_paper_file();
    d.wheel.mean_dedendum_mm = 0.0;
    rejected(check(&d), "wheel.mean_dedendum_mm", &["> 0"]);
}

#[test]
fn face_width_beyond_a_third_of_the_outer_cone_distance_is_rejected() {
    let mut d = common::white_paper_file();
    d.pair.face_width_mm = 50.0;
    rejected(
        check(&d),
        "pair.face_width_mm",
        &["50", "outer cone distance / 3"],
    );
}

#[test]
fn spiral_angle_out_of_range_is_rejected() {
    let mut d = common::white_paper_file();
    d.pair.mean_spiral_angle_deg = 60.0;
    rejected(check(&d), "pair.mean_spiral_angle_deg", &["60", "[0, 50]"]);
}

#[test]
fn module_inconsistent_with_cone_distance_is_rejected() {
    let mut d = common::white_paper_file();
    d.pair.mean_normal_module_mm = 4.5;
    rejected(check(&d), "pair.mean_normal_module_mm", &["4.5", "4.325"]);
}

#[test]
fn equal_hands_are_rejected() {
    let mut d = common::white_paper_file();
    d.wheel.hand = Hand::Right;
    rejected(check(&d), "wheel.hand", &["right", "opposite"]);
}

#[test]
fn pointed_teeth_are_rejected() {
    // A wide pinion cutter point leaves a thin pinion tooth that comes to a point.
    let mut d = common::white_paper_file();
    d.pinion.point_width_mm = 7.5;
    d.wheel.point_width_mm = 1.6;
    rejected(
        check(&d),
        "pinion.mean_addendum_mm",
        &["pointed teeth", "top land"],
    );
}

#[test]
fn small_cutter_radius_pointing_the_heel_is_blamed_on_the_cutter() {
    // 0.45 R_m is inside the allowed cutter range, but face milling with a
    // constant slot width thins the tooth toward the heel until it points:
    // the error names the cutter radius and the smallest one that works.
    let mut d = common::white_paper_file();
    d.cutter.radius_mm = 0.45 * d.pair.mean_cone_distance_mm;
    let msg = check(&d).expect_err("pointed at the heel");
    rejected(
        Err(msg.clone()),
        "cutter.radius_mm",
        &["pointed teeth", "heel", "smallest cutter radius"],
    );
    let r_min: f64 = msg
        .rsplit("is ")
        .next()
        .and_then(|t| t.trim_end_matches(" mm").parse().ok())
        .expect("radius in the message");
    // The radius named works, and one 1 % smaller does not.
    d.cutter.radius_mm = r_min + 0.1;
    check(&d).expect("the named cutter radius gives positive top lands");
    d.cutter.radius_mm = 0.99 * r_min;
    rejected(check(&d), "cutter.radius_mm", &["pointed teeth"]);
}

/// A design with z₁ teeth on a wheel of 43, same cone distance and spiral
/// angle, pressure angle `alpha_deg` and pinion addendum coefficient `ha_coef`.
fn small_pinion(z1: u32, alpha_deg: f64, ha_coef: f64) -> DesignFile {
    let mut d = common::white_paper_file();
    let sigma = 90f64.to_radians();
    let g1 = pinion_pitch_angle(z1 as f64, 43.0, sigma);
    let rm = d.pair.mean_cone_distance_mm;
    let mn = 2.0 * rm * g1.sin() * d.pair.mean_spiral_angle_deg.to_radians().cos() / z1 as f64;
    let (ha1, ha2, c) = (ha_coef * mn, (2.0 - ha_coef) * mn, 0.25 * mn);
    let (hf1, hf2) = (ha2 + c, ha1 + c);
    d.pinion.teeth = z1;
    d.pair.mean_normal_module_mm = mn;
    d.pair.drive_pressure_angle_deg = alpha_deg;
    d.pair.coast_pressure_angle_deg = alpha_deg;
    let set = |m: &mut geometry::design::MemberDesign, g: f64, ha: f64, hf: f64, hf_mate: f64| {
        m.pitch_angle_deg = g.to_degrees();
        m.root_angle_deg = (g - (hf / rm).atan()).to_degrees();
        m.face_angle_deg = (g + (hf_mate / rm).atan()).to_degrees();
        m.mean_addendum_mm = ha;
        m.mean_dedendum_mm = hf;
    };
    set(&mut d.pinion, g1, ha1, hf1, hf2);
    set(&mut d.wheel, sigma - g1, ha2, hf2, hf1);
    let t = alpha_deg.to_radians().tan();
    let sn1 = mn * (std::f64::consts::PI / 2.0 + 2.0 * (ha_coef - 1.0) * t);
    let sn2 = std::f64::consts::PI * mn - sn1 - 0.1;
    d.pinion.point_width_mm = std::f64::consts::PI * mn - sn1 - 2.0 * hf1 * t;
    d.wheel.point_width_mm = std::f64::consts::PI * mn - sn2 - 2.0 * hf2 * t;
    d.cutter.edge_radius_mm = 0.2 * mn;
    d
}

#[test]
fn undercut_pinion_is_rejected() {
    // 8 teeth, 15° pressure angle, negative profile shift: the crown tooth tip
    // cuts into the pinion flank it has generated.
    let d = small_pinion(8, 15.0, 0.8);
    rejected(check(&d), "pinion.mean_dedendum_mm", &["undercut"]);
    // 20 teeth at 20° with the white paper's profile shift are not undercut.
    let ok = small_pinion(20, 20.0, 1.357);
    check(&ok).unwrap();
}

#[test]
fn cutter_radius_too_small_for_the_lengthwise_curvature_is_rejected() {
    let mut d = common::white_paper_file();
    d.cutter.radius_mm = 15.0;
    rejected(check(&d), "cutter.radius_mm", &["15", "minimum"]);
}

#[test]
fn unknown_fields_are_rejected() {
    let text = std::fs::read_to_string(common::white_paper_path())
        .unwrap()
        .replace("[cutter]\n", "[cutter]\nblade_angle_deg = 20.0\n");
    rejected(
        check_text(&text),
        "blade_angle_deg",
        &["unknown field", "line"],
    );
}

#[test]
fn malformed_toml_is_rejected_with_line_and_column() {
    let text = std::fs::read_to_string(common::white_paper_path())
        .unwrap()
        .replace("face_width_mm = 41.0", "face_width_mm = 41.0.0");
    let msg = check_text(&text).unwrap_err();
    let line = text.lines().position(|l| l.contains("41.0.0")).unwrap() + 1;
    assert!(msg.contains(&format!("line {line}, column")), "{msg}");
}

#[test]
fn missing_design_file_names_the_path() {
    let p = PathBuf::from("/nonexistent/design.toml");
    let msg = PairGeometry::from_design_file(&p)
        .err()
        .unwrap()
        .to_string();
    assert!(
        msg.contains("/nonexistent/design.toml") && msg.contains("cannot read"),
        "{msg}"
    );
}

/// The `[published]` table names files of results, not geometry: cutting it
/// gives back the design text it was appended to, byte for byte, and a
/// table after it is kept.
#[test]
fn published_table_is_not_part_of_the_geometry_text() {
    let base = "name = \"x\"\n\n[pair]\na = 1\n";
    let with = format!("{base}\n[published]\n# note\nloaded_te = \"t.toml\"\n");
    assert_eq!(geometry::design::geometry_text(&with), base);
    let middle = "name = \"x\"\n\n[published]\ncpu = \"c.toml\"\n\n[pair]\na = 1\n";
    assert_eq!(
        geometry::design::geometry_text(middle),
        "name = \"x\"\n\n[pair]\na = 1\n"
    );
    assert_eq!(geometry::design::geometry_text(base), base);
    let wp = std::fs::read_to_string(common::reference("white_paper_20x43.toml")).unwrap();
    assert!(wp.contains("[published]"));
    assert!(!geometry::design::geometry_text(&wp).contains("published/"));
}
