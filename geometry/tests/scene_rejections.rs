//! Scene files with a setting out of range are rejected with the field, the
//! value and the limit named.

mod common;

use geometry::scene::{LoadedScene, Scene};

/// The default scene with its design path made absolute and `extra` appended.
fn scene_with(extra: &str) -> Result<LoadedScene, String> {
    scene_edited(&[], extra)
}

/// The default scene with each `(from, to)` of `edits` replaced in its
/// text, its design path made absolute and `extra` appended.
fn scene_edited(edits: &[(&str, &str)], extra: &str) -> Result<LoadedScene, String> {
    let mut text = std::fs::read_to_string(common::reference("scenes/default.toml")).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from} not in the scene");
        text = text.replace(from, to);
    }
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

#[test]
fn multibody_root_stress_without_coefficients_or_with_the_impact_law_is_rejected() {
    let s = scene_with("[multibody]\nroot_stress = true").unwrap();
    assert!(s.scene.multibody.root_stress);
    for (edits, extra) in [
        (
            &[("[stiffness]", "[stiffness]\nroot_stress = false")][..],
            "[multibody]\nroot_stress = true",
        ),
        (
            &[],
            "[multibody]\nroot_stress = true\nforce_law = \"impact\"",
        ),
    ] {
        let e = scene_edited(edits, extra).unwrap_err();
        assert!(
            e.contains("multibody.root_stress") && e.contains("stiffness.root_stress"),
            "{extra}: {e}"
        );
    }
}

#[test]
fn impact_law_settings_out_of_range_or_unknown_are_rejected_naming_the_field() {
    let law = "[multibody]\nforce_law = \"impact\"\n[multibody.impact]\n";
    let s = scene_with(&format!("{law}exponent = 2.2\ndamping_n_s_per_mm = 100.0")).unwrap();
    let mb = &s.scene.multibody;
    assert_eq!(mb.force_law, geometry::scene::ForceLaw::Impact);
    assert_eq!(
        (mb.impact.exponent, mb.impact.damping_n_s_per_mm),
        (2.2, 100.0)
    );
    for (extra, field, limit) in [
        ("exponent = 0.5", "multibody.impact.exponent", "[1, 3]"),
        (
            "stiffness_n_per_mm_e = -1.0",
            "multibody.impact.stiffness_n_per_mm_e",
            "(0, 1e15]",
        ),
        (
            "penetration_depth_mm = 0.0",
            "multibody.impact.penetration_depth_mm",
            "(0, 1e6]",
        ),
        (
            "stiction_speed_mm_s = 500.0\nfriction_transition_speed_mm_s = 400.0",
            "multibody.impact.friction_transition_speed_mm_s",
            "stiction_speed_mm_s = 500",
        ),
        (
            "static_friction = 3.0",
            "multibody.impact.static_friction",
            "[0, 2]",
        ),
    ] {
        let e = scene_with(&format!("{law}{extra}")).unwrap_err();
        assert!(e.contains(field) && e.contains(limit), "{extra}: {e}");
    }
    let e = scene_with(&format!("{law}stiffness = 1.0")).unwrap_err();
    assert!(e.contains("stiffness"), "{e}");
    // The impact law's table holds the drive flanks only.
    let e = scene_with("[multibody]\nforce_law = \"impact\"\ncoast_contact = true").unwrap_err();
    assert!(
        e.contains("multibody.force_law") && e.contains("coast_contact"),
        "{e}"
    );
}

#[test]
fn load_run_with_its_steady_window_past_its_end_is_rejected() {
    let run = "[multibody.load_run]\npinion_rpm = 150.0\npinion_ramp_s = 0.0\nwheel_torque_nm = 100.0\nwheel_torque_rise_s = 0.1\nmax_step_s = 1e-5\n";
    let s = scene_with(&format!("{run}time_s = 0.4\nsteady_from_s = 0.1")).unwrap();
    let r = s.scene.multibody.load_run.as_ref().unwrap();
    // 150 rpm for 0.4 s: one pinion turn.
    assert!((r.rotation() - 2.0 * std::f64::consts::PI).abs() < 1e-12);
    let e = scene_with(&format!("{run}time_s = 0.4\nsteady_from_s = 0.4")).unwrap_err();
    assert!(
        e.contains("multibody.load_run.steady_from_s") && e.contains("time_s = 0.4"),
        "{e}"
    );
    let e = scene_with(&format!("{run}time_s = 200.0\nsteady_from_s = 0.1")).unwrap_err();
    assert!(
        e.contains("multibody.load_run.time_s") && e.contains("[0.0001, 100]"),
        "{e}"
    );
}

#[test]
fn load_run_output_interval_outside_step_and_window_is_rejected() {
    let run = "[multibody.load_run]\npinion_rpm = 150.0\npinion_ramp_s = 0.0\nwheel_torque_nm = 100.0\nwheel_torque_rise_s = 0.1\nmax_step_s = 1e-5\ntime_s = 0.4\nsteady_from_s = 0.2\n";
    let s = scene_with(&format!("{run}output_interval_s = 0.002")).unwrap();
    assert_eq!(
        s.scene
            .multibody
            .load_run
            .as_ref()
            .unwrap()
            .output_interval_s,
        Some(0.002)
    );
    for bad in ["1e-6", "0.15"] {
        let e = scene_with(&format!("{run}output_interval_s = {bad}")).unwrap_err();
        assert!(
            e.contains("multibody.load_run.output_interval_s")
                && e.contains("max_step_s = 0.00001")
                && e.contains("half the steady window = 0.1"),
            "{e}"
        );
    }
}

#[test]
fn seed_scenes_load_with_both_force_laws() {
    for (name, law) in [
        ("seed001_impact", geometry::scene::ForceLaw::Impact),
        ("seed001_element", geometry::scene::ForceLaw::Element),
        (
            "seed001_impact_haversine",
            geometry::scene::ForceLaw::Impact,
        ),
        ("seed002_impact", geometry::scene::ForceLaw::Impact),
        ("seed002_element", geometry::scene::ForceLaw::Element),
    ] {
        let path = common::reference(&format!("scenes/{name}.toml"));
        let s = Scene::load(&path).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(s.scene.multibody.force_law, law, "{name}");
        assert!(s.scene.multibody.load_run.is_some(), "{name}");
        let haversine =
            s.scene.multibody.impact.damping_step == geometry::scene::StepShape::Haversine;
        assert_eq!(haversine, name.ends_with("_haversine"), "{name}");
    }
}

#[test]
fn misalignment_table_loads_and_defaults_to_zero() {
    let s = scene_with("").unwrap();
    assert!(s.scene.misalignment.is_zero());
    let s = scene_with(
        "[misalignment]\noffset_mm = 0.05\npinion_axial_mm = -0.03\nwheel_axial_mm = 0.02\nshaft_angle_deg = 0.01",
    )
    .unwrap();
    assert_eq!(s.scene.misalignment.offset_mm, 0.05);
    assert_eq!(s.scene.misalignment.pinion_axial_mm, -0.03);
    assert_eq!(s.scene.misalignment.wheel_axial_mm, 0.02);
    assert_eq!(s.scene.misalignment.shaft_angle_deg, 0.01);
}

#[test]
fn misalignment_beyond_its_limit_or_unknown_is_rejected_naming_the_field() {
    // 0.2 x the white-paper pair's 4.325 mm module = 0.865 mm; 0.5 deg.
    for (field, bad) in [
        ("offset_mm", "0.9"),
        ("pinion_axial_mm", "-1.0"),
        ("wheel_axial_mm", "nan"),
        ("shaft_angle_deg", "0.6"),
    ] {
        let e = scene_with(&format!("[misalignment]\n{field} = {bad}")).unwrap_err();
        assert!(
            e.contains(&format!("misalignment.{field}")) && e.contains("at most"),
            "{e}"
        );
    }
    let e = scene_with("[misalignment]\noffset = 0.1").unwrap_err();
    assert!(e.contains("unknown field") && e.contains("offset"), "{e}");
}

#[test]
fn sensitivity_ranges_out_of_range_are_rejected_naming_the_field() {
    let e = scene_with("[sensitivity]\nvalues = 8").unwrap_err();
    assert!(e.contains("sensitivity.values") && e.contains("odd"), "{e}");
    let e = scene_with("[sensitivity]\noffset_mm = 0.0").unwrap_err();
    assert!(
        e.contains("sensitivity.offset_mm") && e.contains("(0,"),
        "{e}"
    );
    // The scene's own misalignment leaves less room for the sweep.
    let e =
        scene_with("[misalignment]\nshaft_angle_deg = 0.45\n[sensitivity]\nshaft_angle_deg = 0.1")
            .unwrap_err();
    assert!(
        e.contains("sensitivity.shaft_angle_deg") && e.contains("0.05"),
        "{e}"
    );
}

#[test]
fn bearings_that_cannot_hold_the_shaft_or_out_of_range_are_rejected_naming_the_field() {
    let b = |pos: &str, kr: &str, ka: &str| {
        format!("{{ axial_position_mm = {pos}, radial_stiffness_n_per_m = {kr}, axial_stiffness_n_per_m = {ka} }}")
    };
    let good = format!(
        "[{}, {}]",
        b("90.0", "5e8", "5e8"),
        b("150.0", "5e8", "0.0")
    );
    let table = |pinion: &str, extra: &str| {
        format!("[bearings]\npinion = {pinion}\nwheel = {good}\n{extra}")
    };
    let s = scene_with(&table(&good, "")).unwrap();
    let bs = s.scene.bearings.unwrap();
    assert_eq!(
        (bs.pinion.len(), bs.tolerance_nm, bs.max_iterations),
        (2, 1.0, 60)
    );
    for (pinion, field, words) in [
        (
            format!("[{}]", b("90.0", "5e8", "5e8")),
            "bearings.pinion",
            "tilt",
        ),
        (
            format!("[{}, {}]", b("90.0", "5e8", "5e8"), b("90.0", "5e8", "0.0")),
            "bearings.pinion",
            "tilt",
        ),
        (
            format!(
                "[{}, {}]",
                b("90.0", "5e8", "0.0"),
                b("150.0", "5e8", "0.0")
            ),
            "bearings.pinion",
            "axial",
        ),
        (
            format!(
                "[{}, {}]",
                b("90.0", "-5e8", "5e8"),
                b("150.0", "5e8", "0.0")
            ),
            "bearings.pinion[0].radial_stiffness_n_per_m",
            "[0, 1e14]",
        ),
        (
            format!("[{}, {}]", b("nan", "5e8", "5e8"), b("150.0", "5e8", "0.0")),
            "bearings.pinion[0].axial_position_mm",
            "finite",
        ),
    ] {
        let e = scene_with(&table(&pinion, "")).unwrap_err();
        assert!(e.contains(field) && e.contains(words), "{e}");
    }
    let e = scene_with(&table(&good, "tolerance_nm = 0.0")).unwrap_err();
    assert!(e.contains("bearings.tolerance_nm"), "{e}");
    let e = scene_with(&table(&good, "stiffness = 1.0")).unwrap_err();
    assert!(
        e.contains("unknown field") && e.contains("stiffness"),
        "{e}"
    );
}

#[test]
fn bearing_damping_and_member_masses_are_read_and_out_of_range_rejected_naming_the_field() {
    let b = |pos: &str, ka: &str, damping: &str| {
        format!("{{ axial_position_mm = {pos}, radial_stiffness_n_per_m = 5e8, axial_stiffness_n_per_m = {ka}{damping} }}")
    };
    let shaft =
        |damping: &str| format!("[{}, {}]", b("90.0", "5e8", damping), b("150.0", "0.0", ""));
    let table = |damping: &str, extra: &str| {
        format!(
            "[bearings]\npinion = {}\nwheel = {}\n{extra}",
            shaft(damping),
            shaft("")
        )
    };
    let damped = ", radial_damping_n_s_per_m = 2e3, axial_damping_n_s_per_m = 1e3";
    let body =
        "pinion_body = { mass_kg = 1.5, centroid_mm = 110.0, transverse_inertia_kgm2 = 2e-3 }";
    let s = scene_with(&table(damped, body)).unwrap();
    let bs = s.scene.bearings.unwrap();
    assert_eq!(
        (
            bs.pinion[0].radial_damping_n_s_per_m,
            bs.pinion[0].axial_damping_n_s_per_m
        ),
        (2e3, 1e3)
    );
    assert_eq!(
        (bs.pinion[1].radial_damping_n_s_per_m, bs.wheel_body),
        (0.0, None)
    );
    let pb = bs.pinion_body.unwrap();
    assert_eq!(
        (pb.mass_kg, pb.centroid_mm, pb.transverse_inertia_kgm2),
        (1.5, 110.0, 2e-3)
    );
    let e = scene_with(&table(", radial_damping_n_s_per_m = -1.0", "")).unwrap_err();
    assert!(
        e.contains("bearings.pinion[0].radial_damping_n_s_per_m") && e.contains("[0, 1e9]"),
        "{e}"
    );
    let e = scene_with(&table(
        "",
        "wheel_body = { mass_kg = 0.0, centroid_mm = 50.0, transverse_inertia_kgm2 = 0.1 }",
    ))
    .unwrap_err();
    assert!(e.contains("bearings.wheel_body.mass_kg"), "{e}");
    let e = scene_with(&table(
        "",
        "pinion_body = { mass_kg = 1.0, centroid_mm = 50.0 }",
    ))
    .unwrap_err();
    assert!(e.contains("transverse_inertia_kgm2"), "{e}");
}

#[test]
fn misalignment_at_its_limit_loads_without_a_sensitivity_table() {
    // |E| just under 0.2 m_n = 0.865 mm and |ΔΣ| = 0.5°: valid. The
    // default sensitivity ranges have no room left there, but the scene
    // never wrote them: they are checked only when the study runs.
    let s = scene_with("[misalignment]\noffset_mm = 0.8649\nshaft_angle_deg = 0.5").unwrap();
    assert!(s.scene.sensitivity.is_none());
    let study = s.scene.sensitivity_settings();
    let e = study
        .check(&s.path, &s.scene.misalignment, &s.pair)
        .unwrap_err()
        .to_string();
    assert!(e.contains("sensitivity.offset_mm"), "{e}");
    // A [sensitivity] table the scene writes is checked on loading.
    let e = scene_with(
        "[misalignment]\noffset_mm = 0.8649\nshaft_angle_deg = 0.5\n[sensitivity]\noffset_mm = 0.05",
    )
    .unwrap_err();
    assert!(e.contains("sensitivity.offset_mm"), "{e}");
}

#[test]
fn a_static_against_dynamic_te_blank_the_scene_does_not_analyse_is_refused_naming_it() {
    let ste_dte = "[multibody.ste_dte]\nwheel_blanks = [\"lightweight\"]\npinion_torque_nm = 300.0\nrpm = [10.0, 1000.0]\nacceleration_end_deg = 30.0\ntime_s = 0.15\nmax_step_s = 1e-5\ncompared_revolutions = 1.0";
    // With both wheel blanks analysed the section loads.
    assert!(scene_with(ste_dte).is_ok());
    // With the standard wheel only, the lightweight comparison is refused.
    let e = scene_edited(
        &[(
            "wheel = [\"standard\", \"lightweight\"]",
            "wheel = [\"standard\"]",
        )],
        ste_dte,
    )
    .err()
    .unwrap_or_default();
    assert!(
        e.contains("multibody.ste_dte.wheel_blanks[0]") && e.contains("blanks.wheel"),
        "{e}"
    );
}

#[test]
fn web_holes_wider_than_the_lightweight_web_are_refused_naming_the_field() {
    let e = scene_with("[blank_dimensions]\nwheel_hole_diameter_mm = 80.0")
        .err()
        .unwrap_or_default();
    assert!(
        e.contains("blank_dimensions.wheel_hole_diameter_mm") && e.contains("radial height"),
        "{e}"
    );
    // The default holes (85 % of the web's height) load.
    assert!(scene_with("").is_ok());
}

#[test]
fn a_run_up_blank_the_scene_does_not_analyse_is_refused_where_the_scene_names_it() {
    let wheel_only = (
        "wheel = [\"standard\", \"lightweight\"]",
        "wheel = [\"lightweight\"]",
    );
    // The default list (the standard wheel) is not checked: a scene of the
    // lightweight wheel alone loads and runs no run-up.
    assert!(scene_edited(&[wheel_only], "").is_ok());
    // Named by the scene, it is refused.
    let e = scene_edited(
        &[wheel_only],
        "[multibody]\nrunup_wheel_blanks = [\"standard\"]",
    )
    .err()
    .unwrap_or_default();
    assert!(
        e.contains("multibody.runup_wheel_blanks[0]") && e.contains("blanks.wheel"),
        "{e}"
    );
}

#[test]
fn flexible_shafts_are_read_and_bad_segments_rejected_naming_the_field() {
    let b = |pos: &str, ka: &str| {
        format!("{{ axial_position_mm = {pos}, radial_stiffness_n_per_m = 5e8, axial_stiffness_n_per_m = {ka} }}")
    };
    let list = format!("[{}, {}]", b("90.0", "5e8"), b("150.0", "0.0"));
    let with_shaft = |shaft: &str| {
        format!("[bearings]\npinion = {list}\nwheel = {list}\n[bearings.pinion_shaft]\n{shaft}")
    };
    let good = "seat_mm = 60.0\nsegments = [ { from_mm = 50.0, to_mm = 100.0, outer_diameter_mm = 45.0 }, { from_mm = 100.0, to_mm = 160.0, outer_diameter_mm = 40.0, inner_diameter_mm = 10.0 } ]";
    let s = scene_with(&with_shaft(good)).unwrap();
    let sh = s.scene.bearings.unwrap().pinion_shaft.unwrap();
    assert_eq!(
        (
            sh.seat_mm,
            sh.segments.len(),
            sh.segments[1].inner_diameter_mm
        ),
        (60.0, 2, 10.0)
    );
    for (text, field, words) in [
        (
            good.replace("to_mm = 100.0, outer", "to_mm = 95.0, outer"),
            "segments[1].from_mm",
            "contiguous",
        ),
        (
            good.replace("inner_diameter_mm = 10.0", "inner_diameter_mm = 40.0"),
            "segments[1].inner_diameter_mm",
            "below outer",
        ),
        (
            good.replace("seat_mm = 60.0", "seat_mm = 20.0"),
            "bearings.pinion_shaft.seat_mm",
            "on the shaft",
        ),
        (
            good.replace("to_mm = 160.0", "to_mm = 140.0"),
            "bearings.pinion[1].axial_position_mm",
            "on the pinion_shaft",
        ),
        (
            good.replace("outer_diameter_mm = 45.0", "outer_diameter_mm = 0.0"),
            "segments[0].outer_diameter_mm",
            "(0, 2000]",
        ),
        (
            "seat_mm = 60.0\nsegments = []".to_string(),
            "bearings.pinion_shaft.segments",
            "1 to 50",
        ),
    ] {
        let e = scene_with(&with_shaft(&text)).unwrap_err();
        assert!(e.contains(field) && e.contains(words), "{field}: {e}");
    }
}
