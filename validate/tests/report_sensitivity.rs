//! The report's misalignment-sensitivity section from a synthetic
//! `solver sensitivity` output: the tables are formatted from the summary,
//! the charts are copied next to the report, and an absent summary is one
//! line of text; the root-stress columns and charts appear exactly when
//! the summary holds root stress.

use formats::root_stress::{FilletPlace, RootStressExtreme, RootStressSummary};
use formats::sensitivity_summary::{
    SensitivityCurve, SensitivityLoad, SensitivityPoint, SensitivitySummary,
};
use geometry::misalignment::{Component, Misalignment};
use geometry::scene::Blank;
use validate::report::sections::sensitivity::section;

/// Root-stress extremes of one load: the pinion's tension grows with the
/// torque and moves toward the heel with the value.
fn root_stress(t: f64, value: f64) -> RootStressSummary {
    let place = |xi| FilletPlace {
        pinion_rotation_deg: 3.0,
        tooth: 1,
        xi,
        height: 0.3,
    };
    let member = |tension_mpa, xi| RootStressExtreme {
        tension_mpa,
        tension_at: place(xi),
        compression_mpa: -0.5 * tension_mpa,
        compression_at: place(0.5),
    };
    RootStressSummary {
        pinion: member(t, 0.5 + value),
        wheel: member(0.8 * t, 0.5 - value),
    }
}

fn summary(root: bool) -> SensitivitySummary {
    let curves = Component::ALL
        .iter()
        .enumerate()
        .map(|(k, &c)| SensitivityCurve {
            component: c,
            symbol: c.symbol().into(),
            unit: c.unit().into(),
            range: 0.05,
            points: (0..3)
                .map(|i| {
                    let value = 0.05 * (i as f64 - 1.0);
                    SensitivityPoint {
                        value,
                        misalignment: Misalignment::default().with(c, value),
                        loads: [100.0, 300.0]
                            .iter()
                            .map(|&t| SensitivityLoad {
                                torque_nm: t,
                                te_ptp_urad: 10.0 + k as f64 + i as f64 + t / 1000.0,
                                te_mean_urad: 100.0 * value + t,
                                pattern_centre_l_mm: 121.0 + value,
                                pattern_centre_d_mm: 1.0 - value,
                                pattern_length_mm: 20.0,
                                pattern_height_mm: 5.0,
                                max_pressure_mpa: 1234.0 + t,
                                root_stress: root.then(|| root_stress(t, value)),
                            })
                            .collect(),
                    }
                })
                .collect(),
        })
        .collect();
    SensitivitySummary {
        scene: "synthetic".into(),
        pinion_blank: Blank::Standard,
        wheel_blank: Blank::Standard,
        base: Misalignment::default(),
        torques_nm: vec![100.0, 300.0],
        positions: 19,
        step_deg: 1.0,
        curves,
        stiffness_files: vec![],
        wall_s: 2.5,
    }
}

#[test]
fn sensitivity_section_tabulates_the_summary_and_copies_its_charts() {
    let out = tempfile::tempdir().unwrap();
    let reports = tempfile::tempdir().unwrap();
    let dir = out.path().join("synthetic").join("sensitivity");
    std::fs::create_dir_all(&dir).unwrap();
    let s = summary(false);
    formats::output::write_json(&dir.join("summary.json"), &s).unwrap();
    solver::stage::sensitivity::write_charts(&dir, &s).unwrap();
    let sec = section(Some(out.path()), Some("synthetic"), reports.path());
    assert!(sec.markdown.starts_with("## Misalignment sensitivity"));
    for c in [
        "### E (offset_mm)",
        "### P (pinion_axial_mm)",
        "### G (wheel_axial_mm)",
        "### ΔΣ (shaft_angle_deg)",
    ] {
        assert!(sec.markdown.contains(c), "{c} missing:\n{}", sec.markdown);
    }
    // Rows at the largest torque: E at −0.05 has ptp 10 + 0 + 0 + 0.3.
    assert!(
        sec.markdown
            .contains("| -0.0500 | 10.30 | 295.00 | 120.95 | 1.05 | 20.00 | 5.00 | 1534 |"),
        "{}",
        sec.markdown
    );
    assert!(
        !sec.markdown.contains("| 10.10 |"),
        "a row of the smaller torque"
    );
    assert!(
        sec.markdown.contains("No root stress") && !sec.markdown.contains("σ_F pinion"),
        "{}",
        sec.markdown
    );
    assert_eq!(sec.figures.len(), 6);
    for f in &sec.figures {
        assert!(
            reports.path().join(&f.file).is_file(),
            "{} not copied",
            f.file
        );
        assert!(f.file.starts_with("sensitivity_"));
    }
    let none = section(Some(out.path()), Some("other"), reports.path());
    assert!(
        none.markdown.contains("No sensitivity study"),
        "{}",
        none.markdown
    );
    assert!(none.figures.is_empty());
}

/// With root stress in every load: its four columns (tension and ξ of
/// pinion and wheel at the largest torque) and its two charts.
#[test]
fn sensitivity_section_adds_the_root_stress_where_the_summary_has_it() {
    let out = tempfile::tempdir().unwrap();
    let reports = tempfile::tempdir().unwrap();
    let dir = out.path().join("synthetic").join("sensitivity");
    std::fs::create_dir_all(&dir).unwrap();
    let s = summary(true);
    formats::output::write_json(&dir.join("summary.json"), &s).unwrap();
    solver::stage::sensitivity::write_charts(&dir, &s).unwrap();
    let csv = solver::stage::sensitivity::summary_csv(&s).unwrap();
    assert!(
        csv.lines()
            .nth(1)
            .unwrap()
            .ends_with(",100.000,0.4500,80.000,0.5500"),
        "{csv}"
    );
    let sec = section(Some(out.path()), Some("synthetic"), reports.path());
    assert!(
        sec.markdown.contains("σ_F pinion (MPa)"),
        "{}",
        sec.markdown
    );
    // E at −0.05, 300 N·m: pinion 300 MPa at ξ 0.45, wheel 240 MPa at ξ 0.55.
    assert!(
        sec.markdown.contains(
            "| -0.0500 | 10.30 | 295.00 | 120.95 | 1.05 | 20.00 | 5.00 | 1534 | 300.0 | 0.45 | 240.0 | 0.55 |"
        ),
        "{}",
        sec.markdown
    );
    assert_eq!(sec.figures.len(), 8);
    assert!(sec
        .figures
        .iter()
        .any(|f| f.file == "sensitivity_wheel_root_stress.svg"));
}
