//! The report's lumped-model section from a synthetic `solver lumped`
//! summary: our numbers formatted from it beside seed 004's, its charts
//! copied, and an absent summary stated in one line (and seed 003's part,
//! absent too, in its heading and one line).

use formats::lumped_summary::{Directions, ImpactSummary, LumpedSummary, SeriesSummary};
use geometry::gear_body::Blank;
use validate::report::sections::lumped::{section, LUMPED_SCENE};

fn directions(base: f64) -> Directions {
    Directions {
        pinion_x: base + 1.0,
        pinion_y: base + 2.0,
        pinion_z: base + 3.0,
        wheel_x: base + 4.0,
        wheel_y: base + 5.0,
        wheel_z: base + 6.0,
        mesh_normal: base + 7.0,
    }
}

fn series(mean: f64, harmonics: usize, residual: f64) -> SeriesSummary {
    SeriesSummary {
        mean,
        harmonics: vec![mean / 10.0; harmonics],
        max_residual_of_ptp: residual,
        tolerance_of_ptp: 0.1,
        met: residual <= 0.1,
    }
}

fn summary() -> LumpedSummary {
    LumpedSummary {
        pinion_blank: Blank::Standard,
        wheel_blank: Blank::Standard,
        pinion_speed_rpm: 5900.0,
        mesh_frequency_hz: 2261.67,
        pinion_torque_nm: 133.72,
        mesh_cycles: 50.0,
        dropped_mesh_cycles: 10.0,
        direction_cosines: [-0.48, 0.31, 0.82],
        levers_m: [0.04, 0.15],
        masses_kg: [2.0, 7.7],
        inertias_kgm2: [0.0018, 0.118],
        mesh_damping_ns_per_m: 2000.0,
        bearing_stiffness_n_per_m: [[1e9; 3], [1e9, 2e9, 1e9]],
        bearing_damping_ratio: 0.02,
        mesh_stiffness_n_per_m: series(7.2345e7, 8, 0.0983),
        secant_mesh_stiffness_mean_n_per_m: 6.7742e7,
        transmission_error_m: series(5.3e-6, 6, 0.0883),
        loaded_deflection_m: series(6.2e-5, 2, 0.125),
        natural_frequencies_hz: vec![1052.7, 1810.6],
        impact: ImpactSummary {
            model: "seed004".into(),
            seed004_force_n: 153.46,
            velocity_m_s: 0.0539,
            entering_pair_stiffness_n_per_m: 5.82e6,
            first_loaded_rotation_deg: 10.5,
            applied_peak_n: 153.46,
            pulse_s: 2.2e-5,
        },
        impact_force_n: 153.46,
        rms_acceleration_m_s2: directions(10.0),
        relative_normal_acceleration_rms_m_s2: 75.53,
        rms_acceleration_share_percent: directions(0.5),
        peak_to_peak_displacement_m: directions(0.0),
        mesh_force_mean_n: 3343.0,
        mesh_force_min_n: 3300.0,
        mesh_force_max_n: 3500.0,
        dynamic_factor: 1.047,
        pinion_bearing_force_rms_n: [1.0; 3],
        wheel_bearing_force_rms_n: [1.0; 3],
        bearing_force_peaks: vec![(1.0, 90.0)],
        steps: [4000, 0],
        evaluations: 24000,
        integration_wall_s: 0.01,
        variant: String::new(),
        roughness: None,
        friction_coefficient: 0.0,
        friction_normal_angle_deg: 0.9,
        ltca_normal_model_axes: [-0.49, 0.31, 0.81],
        rms_velocity_m_s: directions(0.0),
        member_velocity_rms_m_s: [1e-3, 2e-3],
        design_variant: None,
        loaded_contact_ratio: 1.625,
    }
}

#[test]
fn present_summary_gives_table3_rows_beside_seed004_and_the_charts() {
    let out = tempfile::tempdir().unwrap();
    let reports = tempfile::tempdir().unwrap();
    let dir = out.path().join(LUMPED_SCENE).join("lumped");
    std::fs::create_dir_all(dir.join("standard_standard")).unwrap();
    std::fs::write(
        dir.join("summary.json"),
        serde_json::to_string(&vec![summary()]).unwrap(),
    )
    .unwrap();
    std::fs::write(dir.join("standard_standard/mesh_force.svg"), "<svg>F</svg>").unwrap();
    let s = section(Some(out.path()), reports.path());
    let md = &s.markdown;
    assert!(md.starts_with("## Lumped 8-DOF model (seeds 004/003)"));
    // Ours from the summary, seed 004's Table 3 beside.
    for row in [
        "| Pinion X (axial) | 11.00 | 1.50 | 14.56 | 63.82 | 21.28 |",
        "| Pinion Z (bending) | 13.00 | 3.50 | 17.21 | 112.02 | 37.35 |",
        "| Wheel Y (axial) | 15.00 | 5.50 | 19.86 | 24.97 | 8.33 |",
        "| Mesh normal | 17.00 | 7.50 | — | 299.89 | 100.00 |",
    ] {
        assert!(md.contains(row), "row {row} missing in\n{md}");
    }
    assert!(
        md.contains("| mean mesh stiffness, tangent (N/m) | 7.234e7 (secant 6.774e7) | 3.50e8 |")
    );
    assert!(md.contains("| meshing-impact force (N) | 153 (seed004) | 27660 |"));
    assert!(md.contains("| stiffness harmonics | 8 | up to order 5 |"));
    assert!(md.contains("| stiffness k(t): harmonics, largest residual / bound (% of peak-to-peak) | 8, 9.8 / 10.0 |"));
    assert!(md.contains("| loaded deflection δ(t): harmonics, largest residual / bound (% of peak-to-peak) | 2, 12.5 / 10.0 (bound not met) |"));
    assert!(md.contains("75.53 m/s²"));
    // 27,660 N against T1/r1 = 133.72 / 0.04 = 3343 N: 8.3 times.
    assert!(md.contains("3343 N"));
    assert!(md.contains("8.3 times"));
    // The bearings as the run used them, not as a text assumed them.
    assert!(
        md.contains("pinion 1.000e9 / 1.000e9 / 1.000e9 N/m and wheel 1.000e9 / 2.000e9 / 1.000e9 N/m (X / Y / Z) with 2 % damping"),
        "{md}"
    );
    assert!(md.contains("4.8 times our tangent mean"));
    assert!(
        md.contains("natural frequencies are 1053, 1811 Hz against the mesh frequency 2261.7 Hz")
    );
    // The one chart present is copied and linked; the missing ones are left out.
    assert_eq!(s.figures.len(), 1);
    assert_eq!(s.figures[0].file, "lumped_standard_standard_mesh_force.svg");
    assert!(reports
        .path()
        .join("lumped_standard_standard_mesh_force.svg")
        .is_file());
    assert!(md.contains("(lumped_standard_standard_mesh_force.svg)"));
}

#[test]
fn absent_summary_is_one_line_without_numbers() {
    let out = tempfile::tempdir().unwrap();
    let reports = tempfile::tempdir().unwrap();
    let s = section(Some(out.path()), reports.path());
    let body: Vec<&str> = s
        .markdown
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .collect();
    // Seed 004's line, seed 003's heading and its line, the FE mesh
    // stiffness heading, its note and one line per seed study, the order
    // map's heading and its line, the whole revolution's heading and its line.
    assert_eq!(body.len(), 11, "{}", s.markdown);
    assert!(body[0].starts_with("No lumped run:"));
    assert!(body[1].starts_with("### Seed 003"));
    assert!(body[2].starts_with("No seed 003 run:"));
    assert!(body[3].starts_with("### Mesh stiffness at one position"));
    assert!(body[5].starts_with("No study of `seed003_fe_stiffness`"));
    assert!(body[6].starts_with("No study of `seed004_fe_stiffness`"));
    assert!(body[7].starts_with("### White-paper pair, lightweight wheel"));
    assert!(body[8].starts_with("No order map:"));
    assert!(
        body[9].starts_with("### White-paper pair, lightweight wheel over its whole revolution")
    );
    assert!(body[10].starts_with("No whole-revolution order map:"));
    assert!(!s.markdown.contains('|') && !s.markdown.contains("0.00"));
    assert!(s.figures.is_empty());
    let none = section(None, reports.path());
    assert!(none.markdown.contains("No lumped run"));
}
