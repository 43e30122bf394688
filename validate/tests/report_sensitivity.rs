//! The report's misalignment-sensitivity section from a synthetic
//! `solver sensitivity` output: the tables are formatted from the summary,
//! the charts are copied next to the report, and an absent summary is one
//! line of text.

use formats::sensitivity_summary::{
    SensitivityCurve, SensitivityLoad, SensitivityPoint, SensitivitySummary,
};
use geometry::misalignment::{Component, Misalignment};
use geometry::scene::Blank;
use validate::report::sections::sensitivity::section;

fn summary() -> SensitivitySummary {
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
    let s = summary();
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
