//! A synthetic `solver lumped` summary for the report's lumped tests:
//! seed 003's 16/27 case at 1,200 rpm by default; the tests set what they
//! check.

#![allow(dead_code)]

use formats::lumped_summary::{
    DesignVariantSummary, Directions, ImpactSummary, LumpedSummary, RoughnessSummary, SeriesSummary,
};
use geometry::gear_body::Blank;

pub fn directions(v: f64) -> Directions {
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

pub fn series(mean: f64) -> SeriesSummary {
    SeriesSummary {
        mean,
        harmonics: vec![mean / 10.0; 3],
        max_residual_of_ptp: 0.05,
        tolerance_of_ptp: 0.1,
        met: true,
    }
}

pub fn run(wheel_torque: f64, ra: Option<f64>, k: f64, velocity_mm_s: f64) -> LumpedSummary {
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
        design_variant: None,
        loaded_contact_ratio: 1.8,
    }
}

/// `base` as an ease-off variant with seed 004's m′₂₁ and a lengthwise
/// crowning, its measured contact ratio, impact force and RMS values.
pub fn variant(
    base: LumpedSummary,
    m21: f64,
    crowning_um: f64,
    contact_ratio: f64,
    impact_n: f64,
    rms: [f64; 2],
) -> LumpedSummary {
    let mut r = base;
    r.design_variant = Some(DesignVariantSummary {
        name: format!("m{m21}_c{crowning_um}"),
        te_slope_m21: Some(m21),
        motion_error_urad: 0.5 * m21.abs() * 0.01866 * 1e6,
        profile_crowning_um: 4.0,
        lengthwise_crowning_um: crowning_um,
    });
    r.variant = format!("v{m21}_{crowning_um}");
    r.loaded_contact_ratio = contact_ratio;
    r.impact.seed004_force_n = impact_n;
    r.rms_acceleration_m_s2.mesh_normal = rms[0];
    r.relative_normal_acceleration_rms_m_s2 = rms[1];
    r
}
