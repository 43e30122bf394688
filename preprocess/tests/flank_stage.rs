//! The `preprocess flanks` stage end to end on the small scene.

#[path = "../../geometry/tests/common/mod.rs"]
mod common;

use preprocess::flank_stage::{load_input, run_stage};

#[test]
fn small_scene_writes_grids_utca_plots_and_summary() {
    let input = load_input(&common::reference("scenes/small.toml")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("flanks");
    run_stage(&input, &out).unwrap();
    for f in [
        "flanks.json",
        "utca.json",
        "summary.json",
        "te.svg",
        "ease_off.svg",
        "roll_angles.svg",
        "contact_path.svg",
        "tooth_section.svg",
        "machine_settings.toml",
        "machine_settings_pinion.toml",
        "machine_settings_wheel.toml",
    ] {
        let p = out.join(f);
        assert!(
            p.metadata().map(|m| m.len() > 100).unwrap_or(false),
            "{f} missing or empty"
        );
    }
    let leftovers: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| !e.file_name().to_string_lossy().contains('.'))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
    // One set: run.json names the design and lists every file written.
    let info = formats::result_set::verify_files(&out)
        .unwrap()
        .expect("run.json");
    assert!(info.inputs.contains_key("design"), "{:?}", info.inputs);
    for f in ["flanks.json", "utca.json", "summary.json", "te.svg"] {
        assert!(
            info.files.contains_key(f),
            "{f} not in {:?}",
            info.files.keys()
        );
    }
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["mesh_cycle_deg"].as_f64().unwrap(), 18.0);
    for (m, f) in [
        ("pinion", "concave"),
        ("pinion", "convex"),
        ("wheel", "concave"),
        ("wheel", "convex"),
    ] {
        let b = s["mean_point"][m][f]["spiral_angle_deg"].as_f64().unwrap();
        let a = s["mean_point"][m][f]["normal_pressure_angle_deg"]
            .as_f64()
            .unwrap();
        assert!(
            (b - 32.0).abs() < 0.01 && (a - 20.0).abs() < 0.01,
            "{m} {f}: {b} {a}"
        );
    }
    // One mesh cycle at 0.5°: the unloaded TE of the white-paper pair, coarser sampling.
    let ptp = s["utca"]["te_ptp_urad"].as_f64().unwrap();
    assert!((ptp - 37.0).abs() < 3.7, "te ptp {ptp}");
    let cr = s["utca"]["contact_ratio"].as_f64().unwrap();
    assert!(cr > 2.0 && cr < 3.5, "contact ratio {cr}");
    let u: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("utca.json")).unwrap()).unwrap();
    assert_eq!(u["te_urad"].as_array().unwrap().len(), 37);
}

#[test]
fn unwritable_output_directory_is_an_error_naming_it() {
    let input = load_input(&common::reference("scenes/small.toml")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let blocker = dir.path().join("file");
    std::fs::write(&blocker, b"x").unwrap();
    let err = run_stage(&input, &blocker.join("out"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("file/out") || err.contains("file"), "{err}");
}

#[test]
fn scene_with_bad_setting_names_the_field() {
    let text = std::fs::read_to_string(common::reference("scenes/small.toml"))
        .unwrap()
        .replace("step_deg = 0.5", "step_deg = -0.5");
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        common::white_paper_path(),
        dir.path().join("white_paper_20x43.toml"),
    )
    .unwrap();
    let scenes = dir.path().join("scenes");
    std::fs::create_dir_all(&scenes).unwrap();
    let p = scenes.join("bad.toml");
    std::fs::write(&p, text).unwrap();
    let err = load_input(&p).unwrap_err().to_string();
    assert!(
        err.contains("bad.toml") && err.contains("utca.step_deg") && err.contains("-0.5"),
        "{err}"
    );
}

/// A design without settings whose ease-off no settings cut (500 µm
/// lengthwise and 300 µm profile crowning: the synthesis fails) still gets
/// its flanks and UTCA; no settings files are written and the summary says
/// why.
#[test]
fn a_design_whose_ease_off_no_settings_cut_gets_none_and_the_summary_says_why() {
    let mut input = load_input(&common::reference("scenes/small.toml")).unwrap();
    input.pair.ease_off.lengthwise_crowning_um = 500.0;
    input.pair.ease_off.profile_crowning_um = 300.0;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("flanks");
    let summary = run_stage(&input, &out).unwrap();
    assert!(summary.machine_settings.source.is_none());
    let why = summary.machine_settings.not_synthesized.unwrap();
    assert!(why.contains("pinion"), "{why}");
    assert!(!out.join("machine_settings.toml").exists());
    assert!(out.join("utca.json").is_file());
}
