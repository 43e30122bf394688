//! The calibrated variant's committed files (written by `make calibrate`):
//! the design and the scene load and pass their checks, they are the very
//! files the calibration record hashed (a hand edit fails here), and the
//! design differs from the default one only by what the record says was
//! fitted.

use std::path::{Path, PathBuf};
use validate::studies::calibration::write::sha256;
use validate::studies::calibration::CalibrationRecord;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn record() -> CalibrationRecord {
    let p = root().join("reference/white_paper_20x43_calibration.json");
    serde_json::from_str(&std::fs::read_to_string(&p).expect("calibration record committed"))
        .expect("calibration record parses")
}

#[test]
fn calibrated_design_and_scene_are_the_files_the_record_hashed() {
    let r = record();
    assert_eq!(
        r.schema_version,
        validate::studies::calibration::SCHEMA_VERSION
    );
    for (f, h) in [
        (&r.design_file, &r.design_sha256),
        (&r.scene_file, &r.scene_sha256),
    ] {
        let bytes = std::fs::read(root().join(f)).unwrap_or_else(|e| panic!("{f}: {e}"));
        assert_eq!(&sha256(&bytes), h, "{f} changed since the calibration");
    }
}

#[test]
fn calibrated_scene_loads_with_the_fitted_ease_off_and_web() {
    let r = record();
    let s =
        geometry::scene::Scene::load(&root().join(&r.scene_file)).expect("calibrated scene loads");
    let e = &s.pair.ease_off;
    let got = [
        e.motion_error_urad,
        e.lengthwise_crowning_um,
        e.profile_crowning_um,
        e.bias_um,
    ];
    for (v, g) in r.ease_off.iter().zip(got) {
        assert!(
            (v.calibrated - g).abs() < 1e-9,
            "{}: record {} design {g}",
            v.name,
            v.calibrated
        );
    }
    assert_eq!(
        s.scene.blank_dimensions.wheel_lightweight_web_thickness_mm,
        Some(r.web.calibrated)
    );
    // Everything else is the default design's: same teeth, angles, module.
    let d = geometry::scene::Scene::load(&root().join(&r.base_scene)).expect("base scene loads");
    assert_eq!(
        (
            s.pair.members[0].teeth,
            s.pair.members[1].teeth,
            s.pair.normal_module,
            s.pair.face_width
        ),
        (
            d.pair.members[0].teeth,
            d.pair.members[1].teeth,
            d.pair.normal_module,
            d.pair.face_width
        )
    );
    assert_eq!(s.scene.pinion_torque_nm, d.scene.pinion_torque_nm);
}

#[test]
fn calibration_without_the_standard_blanks_is_refused_before_any_work() {
    let mut s =
        geometry::scene::Scene::load(&root().join("reference/scenes/default.toml")).unwrap();
    s.scene.blanks.wheel = vec![geometry::scene::Blank::Lightweight];
    let d = tempfile::tempdir().unwrap();
    let err = validate::studies::calibration::run(
        &s,
        d.path(),
        d.path(),
        &validate::studies::calibration::Targets {
            design: &d.path().join("design.toml"),
            scene: &d.path().join("scene.toml"),
            record: &d.path().join("record.json"),
        },
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("[blanks]") && err.contains("standard"),
        "{err}"
    );
    assert!(
        std::fs::read_dir(d.path()).unwrap().next().is_none(),
        "nothing written"
    );
}
