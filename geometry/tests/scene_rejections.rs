//! Scene files with a setting out of range are rejected with the field, the
//! value and the limit named.

mod common;

use geometry::scene::{LoadedScene, Scene};

/// The default scene with its design path made absolute and `extra` appended.
fn scene_with(extra: &str) -> Result<LoadedScene, String> {
    let text = std::fs::read_to_string(common::reference("scenes/default.toml")).unwrap();
    let design = common::white_paper_path();
    let text = text.replace(
        "design = \"../white_paper_20x43.toml\"",
        &format!("design = {:?}", design.display().to_string()),
    );
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, format!("{text}\n{extra}\n")).unwrap();
    Scene::load(&path).map_err(|e| e.to_string())
}

#[test]
fn default_scene_with_frictionless_flanks_loads() {
    let s = scene_with("[ltca]\nfriction_coefficient = 0.0").unwrap();
    assert_eq!(s.scene.ltca.friction_coefficient, 0.0);
    let s = scene_with("[ltca]\nfriction_coefficient = 0.08").unwrap();
    assert_eq!(s.scene.ltca.friction_coefficient, 0.08);
}

#[test]
fn friction_coefficient_out_of_range_is_rejected() {
    for bad in ["0.8", "-0.1", "nan"] {
        let e = scene_with(&format!("[ltca]\nfriction_coefficient = {bad}")).unwrap_err();
        assert!(
            e.contains("ltca.friction_coefficient") && e.contains("[0, 0.5]"),
            "{e}"
        );
    }
}

#[test]
fn rattle_without_coast_contact_or_with_a_fluctuation_beyond_1_is_rejected() {
    let e = scene_with("[multibody]\nrattle_time_s = 0.05").unwrap_err();
    assert!(
        e.contains("multibody.rattle_time_s") && e.contains("coast_contact"),
        "{e}"
    );
    // The default scene analyses the lightweight wheel too: its coast flanks
    // are mapped onto the body's teeth.
    let s = scene_with("[multibody]\ncoast_contact = true\nrattle_time_s = 0.05").unwrap();
    assert!(s.scene.multibody.coast_contact);
    let e = scene_with("[multibody]\nrattle_speed_fluctuation = 1.5").unwrap_err();
    assert!(
        e.contains("multibody.rattle_speed_fluctuation") && e.contains("[0, 1]"),
        "{e}"
    );
}
