//! Input refused before work: every design or scene value that
//! can be checked at load is, and the refusal names the file, the field, the
//! value and the limit. Every checked-in design and scene still loads.

mod common;

use geometry::design::{DesignFile, TopographyDesign};
use geometry::design_file::load_pair;
use geometry::scene::Scene;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
}

fn toml_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    v.sort();
    v
}

/// Checks a design text fully (parse, field checks, derived checks).
fn design_text(text: &str) -> Result<(), String> {
    let path = Path::new("bad_design.toml");
    DesignFile::parse(text, path)
        .and_then(|d| d.to_pair(path))
        .map(|_| ())
        .map_err(|e| e.to_string())
}

fn white_paper_text() -> String {
    std::fs::read_to_string(common::white_paper_path()).unwrap()
}

/// The white-paper design with `from` replaced by `to` (which must occur).
fn design_with(from: &str, to: &str) -> Result<(), String> {
    let text = white_paper_text();
    assert!(text.contains(from), "{from} not in the design");
    design_text(&text.replacen(from, to, 1))
}

/// The default scene, its design path absolute, with `from` replaced by `to`
/// (which must occur), loaded from a temporary directory.
fn scene_with(from: &str, to: &str) -> Result<geometry::scene::LoadedScene, String> {
    scene_with_all(&[(from, to)])
}

/// [`scene_with`] for several replacements, in order.
fn scene_with_all(edits: &[(&str, &str)]) -> Result<geometry::scene::LoadedScene, String> {
    let mut text = std::fs::read_to_string(common::reference("scenes/default.toml")).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from} not in the scene");
        text = text.replacen(from, to, 1);
    }
    let text = text.replace(
        "design = \"../white_paper_20x43.toml\"",
        &format!(
            "design = {:?}",
            common::white_paper_path().display().to_string()
        ),
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, text).unwrap();
    Scene::load(&path).map_err(|e| e.to_string())
}

fn refused<T>(r: Result<T, String>, file: &str, words: &[&str]) -> String {
    let Err(msg) = r else {
        panic!("must be refused (expected {words:?})")
    };
    assert!(msg.contains(file), "file {file} not in: {msg}");
    for w in words {
        assert!(msg.contains(w), "'{w}' not in: {msg}");
    }
    msg
}

#[test]
fn every_checked_in_design_and_scene_loads() {
    let root = root();
    let mut n = 0;
    for p in toml_files(&root.join("reference")) {
        load_pair(&p).unwrap_or_else(|e| panic!("{e}"));
        n += 1;
    }
    let mut scenes = toml_files(&root.join("reference/scenes"));
    for e in std::fs::read_dir(root.join("examples")).unwrap() {
        let p = e.unwrap().path().join("scene.toml");
        if p.exists() {
            scenes.push(p);
        }
    }
    assert!(scenes.len() >= 11, "{scenes:?}");
    for p in scenes {
        Scene::load(&p).unwrap_or_else(|e| panic!("{e}"));
        n += 1;
    }
    assert!(n >= 16);
}

#[test]
fn nan_in_any_design_number_is_refused_by_field() {
    let text = white_paper_text();
    let mut tried = 0;
    for (i, line) in text.lines().enumerate() {
        let Some((key, value)) = line.split_once(" = ") else {
            continue;
        };
        if value.parse::<f64>().is_err() || key.trim() == "teeth" {
            continue;
        }
        for bad in ["nan", "inf", "-inf", "1e300", "-1e300"] {
            let mut lines: Vec<&str> = text.lines().collect();
            let changed = format!("{key} = {bad}");
            lines[i] = &changed;
            let msg = refused(design_text(&lines.join("\n")), "bad_design.toml", &[]);
            assert!(msg.contains(key.trim()), "{key} = {bad}: {msg}");
            tried += 1;
        }
    }
    // The material tables are inline: the pinion's comes first.
    for (key, good) in [
        ("youngs_modulus_gpa", "210.0"),
        ("poisson_ratio", "0.3"),
        ("density_kg_m3", "7850.0"),
    ] {
        for bad in ["nan", "inf", "-1.0"] {
            let text = text.replacen(&format!("{key} = {good}"), &format!("{key} = {bad}"), 1);
            refused(
                design_text(&text),
                "bad_design.toml",
                &[&format!("pinion.material.{key}")],
            );
            tried += 1;
        }
    }
    assert!(tried > 50, "{tried}");
}

fn with_topography(t: TopographyDesign) -> Result<(), String> {
    let mut d = common::white_paper_file();
    d.ease_off.topography = Some(t);
    let text = toml::to_string(&d).unwrap();
    design_text(&text)
}

fn grid(deviation: f64) -> TopographyDesign {
    TopographyDesign {
        profile: vec![0.0, 0.5, 1.0],
        face: vec![0.0, 0.5, 1.0],
        deviation_um: vec![
            vec![0.0, 1.0, 0.0],
            vec![1.0, deviation, 1.0],
            vec![0.0, 1.0, 0.0],
        ],
    }
}

#[test]
fn nan_in_topography_grid_is_refused_by_field() {
    with_topography(grid(2.0)).unwrap();
    refused(
        with_topography(grid(f64::NAN)),
        "bad_design.toml",
        &["ease_off.topography.deviation_um[1][1]", "NaN", "finite"],
    );
    refused(
        with_topography(grid(f64::INFINITY)),
        "bad_design.toml",
        &["ease_off.topography.deviation_um[1][1]", "inf"],
    );
}

#[test]
fn huge_topography_is_refused_with_its_limit() {
    with_topography(grid(-999.0)).unwrap();
    refused(
        with_topography(grid(1e9)),
        "bad_design.toml",
        &[
            "ease_off.topography.deviation_um[1][1]",
            "1000000000",
            "1000 µm",
        ],
    );
}

#[test]
fn nan_topography_node_is_refused_by_index() {
    let mut t = grid(0.0);
    t.face[1] = f64::NAN;
    refused(
        with_topography(t),
        "bad_design.toml",
        &["ease_off.topography.face[1]", "NaN", "[0, 1]"],
    );
    let mut t = grid(0.0);
    t.profile = vec![0.0, 0.7, 0.5];
    refused(
        with_topography(t),
        "bad_design.toml",
        &["ease_off.topography.profile[2]", "strictly increasing"],
    );
}

/// The panic a NaN topography caused (the Cholesky factor of a NaN first
/// fundamental form) is gone from the curvature itself: it is NaN.
#[test]
fn curvature_of_non_finite_derivatives_is_nan_not_a_panic() {
    let n = nalgebra::Vector3::new(0.0, 0.0, 1.0);
    let k = geometry::flank::curvature_from_derivatives(
        [[f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]],
        [[0.0; 3]; 3],
        &n,
    );
    assert!(k.k.iter().all(|x| x.is_nan()));
    let k = geometry::flank::curvature_from_derivatives(
        [[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
        [[0.0; 3]; 3],
        &n,
    );
    assert!(k.k.iter().all(|x| x.is_nan()));
}

#[test]
fn inconsistent_pitch_angle_is_blamed_on_the_pitch_angle_not_the_face_angle() {
    // 30° is above the pinion's face angle (28.183°): before, the face angle
    // was refused as below the pitch angle.
    let msg = refused(
        design_with("pitch_angle_deg = 24.944", "pitch_angle_deg = 30.0"),
        "bad_design.toml",
        &["pinion.pitch_angle_deg", "30", "24.94", "tooth numbers"],
    );
    assert!(!msg.contains("face_angle"), "{msg}");
    let msg = refused(
        design_with("pitch_angle_deg = 65.056", "pitch_angle_deg = 60.0"),
        "bad_design.toml",
        &["wheel.pitch_angle_deg", "60"],
    );
    assert!(!msg.contains("root_angle"), "{msg}");
}

#[test]
fn absurd_cutter_radius_is_refused_with_its_bound_not_a_newton_failure() {
    // Before, 1e6 mm failed in Newton at the toe and 40 mm (0.33 R_m, above
    // the lengthwise-curvature minimum of 0.31 R_m) at the heel.
    for bad in ["1e6", "5000.0", "40.0", "inf", "nan", "-114.3"] {
        refused(
            design_with("radius_mm = 114.3", &format!("radius_mm = {bad}")),
            "bad_design.toml",
            &["cutter.radius_mm", "mean_cone_distance_mm = [48.4, 483.8]"],
        );
    }
    // At the bound the flanks are still generated (no Newton failure).
    let mut d = common::white_paper_file();
    d.cutter.radius_mm = 4.0 * d.pair.mean_cone_distance_mm;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("design.toml");
    std::fs::write(&path, toml::to_string(&d).unwrap()).unwrap();
    geometry::pair::PairGeometry::from_design_file(&path).unwrap();
}

#[test]
fn design_name_with_a_path_separator_is_refused() {
    refused(
        design_with("name = \"white_paper_20x43\"", "name = \"../x\""),
        "bad_design.toml",
        &["name", "../x", "plain name"],
    );
}

#[test]
fn addendum_far_beyond_the_module_is_refused() {
    refused(
        design_with("mean_addendum_mm = 5.871", "mean_addendum_mm = 500.0"),
        "bad_design.toml",
        &["pinion.mean_addendum_mm", "500", "3 m_n = 12.975"],
    );
}

#[test]
fn addendum_that_leaves_the_tip_below_the_pitch_cone_at_the_toe_is_refused() {
    // Positive at the mean point, but the face cone is inclined to the
    // pitch cone: 20.5 mm towards the toe the addendum is gone.
    refused(
        design_with("mean_addendum_mm = 5.871", "mean_addendum_mm = 1e-9"),
        "bad_design.toml",
        &[
            "pinion.mean_addendum_mm",
            "at the toe",
            "below the pitch cone",
        ],
    );
    // Just above the limit it loads.
    design_with("mean_addendum_mm = 5.871", "mean_addendum_mm = 1.3").unwrap();
}

#[test]
fn dedendum_that_lifts_the_root_above_the_pitch_cone_at_the_toe_is_refused() {
    // A root angle far below the pitch angle: the mean dedendum no longer
    // reaches the toe.
    refused(
        design_with("root_angle_deg = 61.817", "root_angle_deg = 40.0"),
        "bad_design.toml",
        &[
            "wheel.mean_dedendum_mm",
            "at the toe",
            "above the pitch cone",
        ],
    );
}

#[test]
fn tooth_number_beyond_the_bound_is_refused() {
    refused(
        design_with("teeth = 43", "teeth = 4000000000"),
        "bad_design.toml",
        &["wheel.teeth", "4000000000", "[5, 500]"],
    );
}

#[test]
fn scene_name_with_dotdot_is_refused() {
    for bad in ["..", "../outside", "a..b"] {
        refused(
            scene_with("name = \"default\"", &format!("name = {bad:?}")),
            "scene.toml",
            &["name", bad, ".."],
        );
    }
}

#[test]
fn scene_name_that_is_not_a_plain_name_is_refused() {
    for (bad, word) in [
        ("", "empty"),
        ("a/b", "'/'"),
        ("/abs", "'/'"),
        ("a\\\\b", "'\\'"),
        ("a\\nb", "control"),
        ("a\\u0000b", "control"),
        (".", "'.'"),
    ] {
        refused(
            scene_with("name = \"default\"", &format!("name = \"{bad}\"")),
            "scene.toml",
            &["name", word],
        );
    }
    scene_with("name = \"default\"", "name = \"run-2 (v1.5)\"").unwrap();
}

#[test]
fn tiny_roll_step_is_refused_with_the_position_estimate() {
    let msg = refused(
        scene_with("step_deg = 0.5", "step_deg = 1e-9"),
        "scene.toml",
        &[
            "rotation.step_deg",
            "0.000000001",
            "positions per blank",
            "at most 1e6",
            "rotation.mesh_cycles_standard",
        ],
    );
    // 2 mesh cycles of 18° in steps of 1e-9°: 3.6e10 positions.
    assert!(msg.contains("3.600e10"), "{msg}");
    refused(
        scene_with("step_deg = 0.1", "step_deg = 1e-7"),
        "scene.toml",
        &["utca.step_deg", "positions per blank"],
    );
    // Small but bounded steps still load: 5 cycles × 18° / 1e-4° = 9e5.
    scene_with("step_deg = 0.5", "step_deg = 1e-4").unwrap();
}

#[test]
fn tiny_multibody_steps_are_refused_with_the_estimate() {
    refused(
        scene_with(
            "[analyses]",
            "[multibody]\nrunup_time_s = 1.0\nrunup_max_step_s = 1e-8\n[analyses]",
        ),
        "scene.toml",
        &["multibody.runup_max_step_s", "time steps", "at most 1e7"],
    );
    refused(
        scene_with(
            "[analyses]",
            "[multibody]\nrunup_rpm = [0.0, 100000.0]\nrunup_time_s = 100.0\nrunup_max_step_s = 1e-3\ntable_step_deg = 0.001\n[analyses]",
        ),
        "scene.toml",
        &["multibody.table_step_deg", "table positions", "at most 1e6"],
    );
}

#[test]
fn empty_torque_list_is_refused() {
    refused(
        scene_with(
            "pinion_torque_nm = [1.0, 100.0, 300.0, 500.0, 700.0]",
            "pinion_torque_nm = []",
        ),
        "scene.toml",
        &["pinion_torque_nm", "0 values", "1 to 100"],
    );
}

#[test]
fn torque_that_is_not_finite_and_positive_is_refused() {
    for bad in ["nan", "inf", "-1.0", "0.0", "1e7"] {
        refused(
            scene_with("[1.0, 100.0,", &format!("[1.0, {bad},")),
            "scene.toml",
            &["pinion_torque_nm[1]", "(0, 1000000] N·m"],
        );
    }
}

#[test]
fn repeated_torque_is_refused_naming_both_entries() {
    refused(
        scene_with(
            "pinion_torque_nm = [1.0, 100.0, 300.0, 500.0, 700.0]",
            "pinion_torque_nm = [300.0, 300.0]",
        ),
        "scene.toml",
        &["pinion_torque_nm[1]", "repeats pinion_torque_nm[0] = 300"],
    );
}

#[test]
fn torques_out_of_order_are_refused_asking_for_increasing_loads() {
    refused(
        scene_with(
            "pinion_torque_nm = [1.0, 100.0, 300.0, 500.0, 700.0]",
            "pinion_torque_nm = [1.0, 700.0, 300.0]",
        ),
        "scene.toml",
        &["pinion_torque_nm[2]", "300", "increasing order"],
    );
}

#[test]
fn repeated_blank_is_refused_by_its_index() {
    refused(
        scene_with(
            "wheel = [\"standard\", \"lightweight\"]",
            "wheel = [\"lightweight\", \"lightweight\"]",
        ),
        "scene.toml",
        &["blanks.wheel[1]", "\"lightweight\"", "each blank once"],
    );
}

#[test]
fn mesh_level_beyond_the_element_bound_is_refused() {
    refused(
        scene_with(
            "reference = { profile = 35, face = 75 }",
            "reference = { profile = 35, face = 4000 }",
        ),
        "scene.toml",
        &["mesh.reference.face", "4000", "[1, 200]", "100 × 200"],
    );
    refused(
        scene_with(
            "reduced_order = { profile = 12, face = 20 }",
            "reduced_order = { profile = 101, face = 20 }",
        ),
        "scene.toml",
        &["mesh.reduced_order.profile", "101", "[1, 100]"],
    );
    scene_with(
        "reference = { profile = 35, face = 75 }",
        "reference = { profile = 100, face = 200 }",
    )
    .unwrap();
}

#[test]
fn stiffness_grid_beyond_the_point_bound_is_refused() {
    refused(
        scene_with(
            "grid_profile = 12\ngrid_face = 40",
            "grid_profile = 200\ngrid_face = 200",
        ),
        "scene.toml",
        &[
            "stiffness.grid_profile × stiffness.grid_face",
            "40000",
            "2500",
        ],
    );
}

#[test]
fn nan_in_scene_numbers_is_refused_by_field() {
    for (from, to, field) in [
        (
            "mesh_cycles_standard = 2.0",
            "mesh_cycles_standard = nan",
            "rotation.mesh_cycles_standard",
        ),
        ("step_deg = 0.5", "step_deg = nan", "rotation.step_deg"),
        ("step_deg = 0.1", "step_deg = inf", "utca.step_deg"),
        (
            "marking_compound_um = 6.3",
            "marking_compound_um = nan",
            "utca.marking_compound_um",
        ),
        (
            "[analyses]",
            "[blank_dimensions]\nwheel_bore_radius_mm = nan\n[analyses]",
            "blank_dimensions.wheel_bore_radius_mm",
        ),
        (
            "[analyses]",
            "[multibody]\ndamping_ratio = nan\n[analyses]",
            "multibody.damping_ratio",
        ),
        (
            "[stiffness]\n",
            "[stiffness]\nload_radius_factor = inf\n",
            "stiffness.load_radius_factor",
        ),
    ] {
        refused(scene_with(from, to), "scene.toml", &[field]);
    }
}

#[test]
fn a_grid_side_left_to_the_mesh_level_counts_at_the_mesh_level_s_size() {
    // 0 profile rows: the reduced-order level's 40; 40 × 200 = 8,000 points
    // (the written 0 × 200 is 0).
    let r = scene_with_all(&[
        (
            "reduced_order = { profile = 12,",
            "reduced_order = { profile = 40,",
        ),
        ("grid_profile = 12", "grid_profile = 0"),
        ("grid_face = 40", "grid_face = 200"),
    ]);
    refused(
        r,
        "scene.toml",
        &["stiffness.grid_profile", "40 × 200 = 8000"],
    );
    // Within the limit it loads.
    scene_with_all(&[("grid_profile = 12", "grid_profile = 0")]).unwrap();
}

#[test]
fn lumped_design_variants_with_the_same_name_are_refused() {
    let lumped = "\n[lumped]\n[[lumped.design_variants]]\nname = \"flat\"\nte_slope_m21 = -0.01\n[[lumped.design_variants]]\nname = \"flat\"\nte_slope_m21 = -0.02\n";
    let r = scene_with_all(&[("[analyses]", &format!("{lumped}\n[analyses]"))]);
    refused(
        r,
        "scene.toml",
        &["lumped.design_variants.name", "\"flat\"", "each name once"],
    );
}

#[test]
fn a_hub_inside_the_bore_is_refused_at_load_not_after_meshing() {
    // The default wheel bore is a quarter of the rim bottom radius at the
    // toe (about 21 mm here): a 10 mm hub lies inside it, and the wheel's
    // half-section crosses itself. The mesh stage found it only after
    // meshing the pinion (about 15 s).
    let r = scene_with_all(&[(
        "[rotation]",
        "[blank_dimensions]\nwheel_hub_radius_mm = 10.0\n\n[rotation]",
    )]);
    refused(
        r,
        "scene.toml",
        &[
            "blank_dimensions.wheel_hub_radius_mm",
            "crosses itself",
            "85.0 mm",
        ],
    );
    // A hub around the bore loads.
    scene_with_all(&[(
        "[rotation]",
        "[blank_dimensions]\nwheel_hub_radius_mm = 40.0\n\n[rotation]",
    )])
    .unwrap();
}
