//! The report's seed 003 part from synthetic `solver lumped` summaries (the
//! smooth pair and one roughness grade at both loads): our velocities
//! formatted beside the test rig's measured 4.195 / 4.384 mm/s and seed
//! 003's simulated 4.06 / 4.116, the runs matched to the loads by the
//! pinion torque T₂ × 16/27, the stiffness change against the smooth
//! flanks, the roughness the model carries; an absent summary in one line.

use formats::lumped_summary::{
    Directions, ImpactSummary, LumpedSummary, RoughnessSummary, SeriesSummary,
};
use geometry::gear_body::Blank;
use validate::report::lumped_seed003::{markdown, SEED003_SCENE};

fn directions(v: f64) -> Directions {
    Directions {
        pinion_x: v,
        pinion_y: v,
        pinion_z: v,
        wheel_x: v,
        wheel_y: v,
        wheel_z: v,
        mesh_normal: v,
    }
}

fn series(mean: f64) -> SeriesSummary {
    SeriesSummary {
        mean,
        harmonics: vec![mean / 10.0; 3],
        max_residual_of_ptp: 0.05,
        tolerance_of_ptp: 0.1,
        met: true,
    }
}

fn run(wheel_torque: f64, ra: Option<f64>, k: f64, velocity_mm_s: f64) -> LumpedSummary {
    LumpedSummary {
        pinion_blank: Blank::Standard,
        wheel_blank: Blank::Standard,
        pinion_speed_rpm: 1200.0,
        mesh_frequency_hz: 320.0,
        pinion_torque_nm: wheel_torque * 16.0 / 27.0,
        mesh_cycles: 50.0,
        dropped_mesh_cycles: 10.0,
        direction_cosines: [-0.61, 0.03, -0.79],
        levers_m: [0.0252, 0.0426],
        masses_kg: [0.38, 0.53],
        inertias_kgm2: [2.1e-4, 9.7e-4],
        mesh_damping_ns_per_m: 300.0,
        bearing_stiffness_n_per_m: [[1e9; 3]; 2],
        bearing_damping_ratio: 0.02,
        mesh_stiffness_n_per_m: series(k),
        secant_mesh_stiffness_mean_n_per_m: 0.9 * k,
        transmission_error_m: series(1e-6),
        loaded_deflection_m: series(3e-5),
        natural_frequencies_hz: vec![2565.0],
        impact: ImpactSummary {
            model: "engagement".into(),
            seed004_force_n: 0.0,
            velocity_m_s: 0.0,
            entering_pair_stiffness_n_per_m: 0.0,
            first_loaded_rotation_deg: 0.0,
            applied_peak_n: 0.0,
            pulse_s: 0.0,
        },
        impact_force_n: 0.0,
        rms_acceleration_m_s2: directions(150.0),
        relative_normal_acceleration_rms_m_s2: 140.0,
        rms_acceleration_share_percent: directions(50.0),
        peak_to_peak_displacement_m: directions(1e-6),
        mesh_force_mean_n: 1800.0,
        mesh_force_min_n: 1700.0,
        mesh_force_max_n: 1900.0,
        dynamic_factor: 1.05,
        pinion_bearing_force_rms_n: [1.0; 3],
        wheel_bearing_force_rms_n: [1.0; 3],
        bearing_force_peaks: vec![],
        steps: [11000, 0],
        evaluations: 66000,
        integration_wall_s: 0.03,
        variant: "synthetic".into(),
        roughness: ra.map(|ra| RoughnessSummary {
            ra_um: ra,
            composite_ra_um: ra * std::f64::consts::SQRT_2,
            dimension: 1.545,
            scale_m: 4.5e-9,
            terms: 15,
            terms_resolved: 2,
            rq_m: 1.4e-6,
            rq_resolved_m: 1.0e-6,
            shortest_resolved_wavelength_m: 5.33e-4,
            node_spacing_m: 1.89e-4,
            profile_length_m: 7.55e-3,
            mesh_element_profile_m: 1.258e-3,
            hertz_half_width_m: 2.41e-4,
        }),
        friction_coefficient: 0.6 + ra.map_or(0.0, |r| 0.01 * r * std::f64::consts::SQRT_2),
        friction_normal_angle_deg: 3.0,
        ltca_normal_model_axes: [-0.61, 0.03, -0.79],
        rms_velocity_m_s: directions(1e-3),
        member_velocity_rms_m_s: [velocity_mm_s * 1e-3, 1e-3],
    }
}

#[test]
fn seed003_part_puts_our_velocities_beside_the_test_rig_and_says_what_the_roughness_is() {
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().join(SEED003_SCENE).join("lumped");
    std::fs::create_dir_all(&dir).unwrap();
    let runs = vec![
        run(77.0, None, 6.0e7, 1.5),
        run(105.0, None, 6.2e7, 1.8),
        run(77.0, Some(0.8), 6.03e7, 2.1),
        run(105.0, Some(0.8), 6.31e7, 2.4),
    ];
    std::fs::write(
        dir.join("summary.json"),
        serde_json::to_string(&runs).unwrap(),
    )
    .unwrap();
    let md = markdown(out.path());
    for row in [
        "| 77 | 45.63 | 1.500 | 2.100 | 4.195 | 4.060 |",
        "| 105 | 62.22 | 1.800 | 2.400 | 4.384 | 4.116 |",
        "| 45.63 | smooth | 0.600 | 6.0000e7 | +0.00 | 1.500 / 1.000 | 150.0 |",
        "| 45.63 | Ra 0.8 µm | 0.611 | 6.0300e7 | +0.50 | 2.100 / 1.000 | 150.0 |",
        "| 62.22 | Ra 0.8 µm | 0.611 | 6.3100e7 | +1.77 | 2.400 / 1.000 | 150.0 |",
        "| 0.8 | 1.131 | 1.545 | 4.50e-9 | 2 / 15 | 1.000 / 1.400 (71 %) | 0.533 | 0.189 | 1.258 | 0.241 |",
    ] {
        assert!(md.contains(row), "row {row} missing in\n{md}");
    }
    // 1.5 / 4.195 = 36 %, 2.4 / 4.384 = 55 %; smooth rise 1.8 / 1.5 = +20 %, measured +4.5 %.
    assert!(
        md.contains("Ours are 36–55 % of the measured values"),
        "{md}"
    );
    assert!(md.contains("ours +20 % from 77 to 105 N·m"));
    assert!(md.contains("measured +4.5 %"));
    assert!(md.contains("neither a calibration nor a validation"));
    assert!(md.contains("1200 rpm (mesh frequency 320.0 Hz)"));
}

#[test]
fn absent_seed003_summary_is_one_line() {
    let out = tempfile::tempdir().unwrap();
    let md = markdown(out.path());
    let body: Vec<&str> = md
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .collect();
    assert_eq!(body.len(), 1, "{md}");
    assert!(body[0].starts_with("No seed 003 run:"));
    assert!(!md.contains('|'));
}
