//! The report's order-map subsection (issue 31): a present
//! `order_map.json` gives one row per wheel blank, one per speed and blank
//! with the amplitudes at the marked orders as the summary holds them, the
//! order maps copied beside the multibody run-up spectrogram where the
//! multibody run has one, and a line saying so where it has not.

use formats::lumped_summary::{MarkedOrder, OrderMapSpeed, OrderMapSummary};
use geometry::gear_body::Blank;
use validate::report::lumped_order_map::{subsection, MULTIBODY_SCENE, ORDER_MAP_SCENE};

fn map(wheel: Blank, lobe_line_n: f64) -> OrderMapSummary {
    OrderMapSummary {
        pinion_blank: Blank::Standard,
        wheel_blank: wheel,
        pinion_teeth: 20,
        wheel_teeth: 43,
        lobes: if wheel == Blank::Lightweight { 3 } else { 0 },
        wheel_solved_teeth: if wheel == Blank::Lightweight {
            vec![0, 1, 2, 3, 4, 5, 41, 42]
        } else {
            vec![2]
        },
        ltca_span_mesh_cycles: 5,
        cycle_mean_stiffness_n_per_m: vec![9.2e7, 9.0e7],
        cycle_wheel_tooth: vec![-0.98, 0.02],
        stiffness_lobe: [0.03, -0.02, -0.04],
        deflection_lobe_m: [0.0; 3],
        stiffness_lobe_ptp_relative: 0.1093,
        stiffness_lobe_minimum_wheel_tooth: (wheel == Blank::Lightweight).then_some(2.49),
        span_fit_residual_of_ptp: [0.086, 0.109],
        mesh_harmonics: 14,
        revolution_harmonics: 623,
        revolution_series_residual_of_ptp: [0.016, 0.007],
        ltca_wall_s: 0.21,
        speeds: vec![OrderMapSpeed {
            pinion_speed_rpm: 3000.0,
            mesh_frequency_hz: 1000.0,
            integration_wall_s: 0.29,
            run_wall_s: 0.56,
            order_resolution: 20.0 / 86.0,
            marked: vec![
                MarkedOrder {
                    label: "3·20/43".into(),
                    pinion_order: 60.0 / 43.0,
                    wheel_bearing_force_n: lobe_line_n,
                },
                MarkedOrder {
                    label: "20".into(),
                    pinion_order: 20.0,
                    wheel_bearing_force_n: 448.6,
                },
            ],
        }],
    }
}

#[test]
fn present_order_map_gives_rows_from_the_summary_and_the_maps_beside_the_multibody_spectrogram() {
    let out = tempfile::tempdir().unwrap();
    let reports = tempfile::tempdir().unwrap();
    let dir = out.path().join(ORDER_MAP_SCENE).join("lumped");
    std::fs::create_dir_all(&dir).unwrap();
    let maps = vec![map(Blank::Standard, 5.3e-6), map(Blank::Lightweight, 1.502)];
    std::fs::write(
        dir.join("order_map.json"),
        serde_json::to_string(&maps).unwrap(),
    )
    .unwrap();
    let svg = "<svg xmlns=\"http://www.w3.org/2000/svg\"/>";
    for b in ["standard", "lightweight"] {
        std::fs::write(dir.join(format!("order_map_standard_{b}.svg")), svg).unwrap();
    }
    let mb = out
        .path()
        .join(MULTIBODY_SCENE)
        .join("multibody")
        .join("standard_standard");
    std::fs::create_dir_all(&mb).unwrap();
    std::fs::write(mb.join("runup_spectrogram.svg"), svg).unwrap();
    let (md, figs) = subsection(out.path(), reports.path());
    assert!(
        md.contains("| Lightweight | 0, 1, 2, 3, 4, 5, 41, 42 | 5 |"),
        "{md}"
    );
    assert!(md.contains("2.49 (of 14.33 per lobe)"), "{md}");
    assert!(
        md.contains("| 3000 | Lightweight | 1.502e0 | 4.486e2 |"),
        "{md}"
    );
    assert!(
        md.contains("| 3000 | Standard | 5.300e-6 | 4.486e2 |"),
        "{md}"
    );
    let files: Vec<&str> = figs.iter().map(|f| f.file.as_str()).collect();
    assert_eq!(
        files,
        [
            "lumped_order_map_standard_standard.svg",
            "lumped_order_map_standard_lightweight.svg",
            "multibody_standard_standard_runup_spectrogram.svg"
        ]
    );
    assert!(reports
        .path()
        .join("multibody_standard_standard_runup_spectrogram.svg")
        .is_file());
    // The lightweight wheel has no run-up in the multibody set: said so.
    assert!(md.contains("no run-up spectrogram for the Standard pinion / Lightweight wheel"));
}
