//! `out/<scene>/lumped/<pinion>_<wheel>/summary.json` of `solver lumped`
//! (the 8-DOF lumped model): written by the solver, read by the report
//! with this one definition.

use geometry::gear_body::Blank;
use serde::{Deserialize, Serialize};

/// A Fourier series of the excitation over the mesh cycle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SeriesSummary {
    pub mean: f64,
    /// Amplitude √(aₗ² + bₗ²) of harmonics l = 1..N.
    pub harmonics: Vec<f64>,
    /// Largest residual at the LTCA positions over their peak-to-peak, and
    /// the bound asked for; `met` false: the most harmonics the samples allow.
    pub max_residual_of_ptp: f64,
    pub tolerance_of_ptp: f64,
    pub met: bool,
}

/// Per direction of both members and along the mesh normal.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Directions {
    pub pinion_x: f64,
    pub pinion_y: f64,
    pub pinion_z: f64,
    pub wheel_x: f64,
    pub wheel_y: f64,
    pub wheel_z: f64,
    pub mesh_normal: f64,
}

/// The meshing impact.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ImpactSummary {
    /// `engagement` or `seed004`.
    pub model: String,
    /// Seed 004's F_s, N (also listed with `engagement`, where no pulse is applied).
    pub seed004_force_n: f64,
    /// Impact velocity v_s, m/s, and the entering pair's tangent stiffness k_s, N/m.
    pub velocity_m_s: f64,
    pub entering_pair_stiffness_n_per_m: f64,
    /// Pinion rotation of the entering pair's first loaded position from the sweep start, deg.
    pub first_loaded_rotation_deg: f64,
    /// The pulse applied (0 with `engagement`), N, and its length, s.
    pub applied_peak_n: f64,
    pub pulse_s: f64,
}

/// The W–M roughness of a run and how much of it the LTCA can see.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoughnessSummary {
    /// Ra of each flank, µm, and of the pair's relative topography (√2 Ra:
    /// two independent flanks carried on the pinion), µm.
    pub ra_um: f64,
    pub composite_ra_um: f64,
    /// Fractal dimension D (seed 003's Eq. (41)) and the scale G set for the composite Ra, m.
    pub dimension: f64,
    pub scale_m: f64,
    /// W–M terms between λ_s = 2.5 µm and λ_c = 0.8 mm, and those the
    /// topography grid carries (λ ≥ 2 node spacings).
    pub terms: usize,
    pub terms_resolved: usize,
    /// Rq of the whole profile and of the carried terms, m.
    pub rq_m: f64,
    pub rq_resolved_m: f64,
    /// Shortest carried wavelength, m; topography node spacing along the
    /// profile, m; profile length, m.
    pub shortest_resolved_wavelength_m: f64,
    pub node_spacing_m: f64,
    pub profile_length_m: f64,
    /// The FE mesh's flank element length along the profile, m (the
    /// compliance comes from the smooth flanks' meshes).
    pub mesh_element_profile_m: f64,
    /// Hertz half-width of the loaded slices at the operating torque,
    /// force-weighted mean over slices and positions, m.
    pub hertz_half_width_m: f64,
}

/// An ease-off variant of the design as the run used it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DesignVariantSummary {
    pub name: String,
    /// Seed 004's m′₂₁ (1/rad), if the variant gave one.
    pub te_slope_m21: Option<f64>,
    /// The ease-off used: motion error (wheel µrad at ±half a mesh cycle)
    /// and crownings (µm).
    pub motion_error_urad: f64,
    pub profile_crowning_um: f64,
    pub lengthwise_crowning_um: f64,
}

/// Summary of one pinion × wheel blank.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LumpedSummary {
    pub pinion_blank: Blank,
    pub wheel_blank: Blank,
    pub pinion_speed_rpm: f64,
    pub mesh_frequency_hz: f64,
    pub pinion_torque_nm: f64,
    pub mesh_cycles: f64,
    pub dropped_mesh_cycles: f64,
    /// (a₁, a₂, a₃) and the levers r₁, r₂ (m).
    pub direction_cosines: [f64; 3],
    pub levers_m: [f64; 2],
    pub masses_kg: [f64; 2],
    pub inertias_kgm2: [f64; 2],
    pub mesh_damping_ns_per_m: f64,
    /// Bearing stiffness of pinion and wheel per direction (X, Y, Z), N/m,
    /// and the bearings' damping ratio, as the run used them.
    #[serde(default)]
    pub bearing_stiffness_n_per_m: [[f64; 3]; 2],
    #[serde(default)]
    pub bearing_damping_ratio: f64,
    /// Tangent k(t) = dF/dδ; the secant F/δ mean beside it.
    pub mesh_stiffness_n_per_m: SeriesSummary,
    pub secant_mesh_stiffness_mean_n_per_m: f64,
    /// e(t) along the normal fitted as its own series, m (reported; the
    /// model takes e = δ − F/k from k and the loaded deflection δ).
    pub transmission_error_m: SeriesSummary,
    /// Loaded static deflection δ(t) = r₂θ(t), m.
    pub loaded_deflection_m: SeriesSummary,
    /// Natural frequencies of the linear model at the mean k, Hz (rigid mode left out).
    pub natural_frequencies_hz: Vec<f64>,
    pub impact: ImpactSummary,
    /// Seed 004's `impact_force_n`: the applied pulse peak (0 with `engagement`).
    pub impact_force_n: f64,
    /// RMS of the fluctuating accelerations, m/s² (mesh normal: λ̈).
    pub rms_acceleration_m_s2: Directions,
    /// RMS of the bodies' relative acceleration along the normal, v·q̈
    /// (λ̈ without ë: the static TE's own curvature left out), m/s².
    pub relative_normal_acceleration_rms_m_s2: f64,
    /// Each over the mesh normal's, %.
    pub rms_acceleration_share_percent: Directions,
    /// Peak-to-peak displacements, m (mesh normal: λ).
    pub peak_to_peak_displacement_m: Directions,
    /// Dynamic mesh force Fₙ: mean, min, max, N; max over the static F = T₁/r₁.
    pub mesh_force_mean_n: f64,
    pub mesh_force_min_n: f64,
    pub mesh_force_max_n: f64,
    pub dynamic_factor: f64,
    /// Bearing forces X, Y, Z: RMS of the fluctuation, N.
    pub pinion_bearing_force_rms_n: [f64; 3],
    pub wheel_bearing_force_rms_n: [f64; 3],
    /// Largest bearing-force spectrum lines (resultant fluctuation of both members): (mesh order, N amplitude).
    pub bearing_force_peaks: Vec<(f64, f64)>,
    /// Integration: accepted and rejected steps, right-hand-side evaluations, wall s.
    pub steps: [usize; 2],
    pub evaluations: usize,
    pub integration_wall_s: f64,
    /// The run's name within the blank pair ("" for a scene's only run;
    /// else torque and roughness).
    #[serde(default)]
    pub variant: String,
    /// The pinion flank's W–M roughness; absent: smooth.
    #[serde(default)]
    pub roughness: Option<RoughnessSummary>,
    /// Friction coefficient μ of the run (0: none), and the angle between
    /// our LTCA's force-weighted flank normal and seed 004's direction
    /// cosines, deg (0 in summaries written before it was computed).
    #[serde(default)]
    pub friction_coefficient: f64,
    #[serde(default)]
    pub friction_normal_angle_deg: f64,
    /// Our LTCA's force-weighted flank normal on the model's axes (unit),
    /// beside `direction_cosines` (the two equal when the scene takes
    /// `direction_cosines = "ltca"`).
    #[serde(default)]
    pub ltca_normal_model_axes: [f64; 3],
    /// RMS of the fluctuating velocities, m/s (mesh normal: λ̇), and of the
    /// resultant translational velocity of each member, m/s.
    #[serde(default = "zero_directions")]
    pub rms_velocity_m_s: Directions,
    #[serde(default)]
    pub member_velocity_rms_m_s: [f64; 2],
    /// The ease-off variant of the design, if the run is one.
    #[serde(default)]
    pub design_variant: Option<DesignVariantSummary>,
    /// Mean number of tooth pairs carrying load over the mesh cycle at the
    /// operating torque, from our LTCA.
    #[serde(default)]
    pub loaded_contact_ratio: f64,
}

fn zero_directions() -> Directions {
    Directions {
        pinion_x: 0.0,
        pinion_y: 0.0,
        pinion_z: 0.0,
        wheel_x: 0.0,
        wheel_y: 0.0,
        wheel_z: 0.0,
        mesh_normal: 0.0,
    }
}

/// `order_map.json` of `solver lumped` with `[lumped.order_map]`: per blank
/// pair, the per-revolution excitation and, per pinion speed, the wheel
/// bearing-force amplitude at the marked pinion orders.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OrderMapSummary {
    pub pinion_blank: Blank,
    pub wheel_blank: Blank,
    pub pinion_teeth: usize,
    pub wheel_teeth: usize,
    /// Lobes per wheel revolution fitted (0: axisymmetric wheel).
    pub lobes: usize,
    /// Wheel teeth whose influence data the wheel's stiffness file holds.
    pub wheel_solved_teeth: Vec<usize>,
    /// Whole mesh cycles of the LTCA span the revolution is derived from.
    pub ltca_span_mesh_cycles: usize,
    /// Per span cycle: mean tangent k (N/m) and force-weighted loaded wheel tooth.
    pub cycle_mean_stiffness_n_per_m: Vec<f64>,
    pub cycle_wheel_tooth: Vec<f64>,
    /// k lobe term c₀, a, b (relative) and δ's d₀, d_a, d_b (m).
    pub stiffness_lobe: [f64; 3],
    pub deflection_lobe_m: [f64; 3],
    /// 2√(a² + b²)/(1 + c₀): the lobe's peak-to-peak over k's revolution mean.
    pub stiffness_lobe_ptp_relative: f64,
    /// Wheel tooth (within one lobe, z₂/n teeth) where the fitted lobe of k
    /// is least; None for an axisymmetric wheel.
    pub stiffness_lobe_minimum_wheel_tooth: Option<f64>,
    /// The span model's largest residual at the LTCA positions over their
    /// peak-to-peak: stiffness, deflection.
    pub span_fit_residual_of_ptp: [f64; 2],
    /// Mesh harmonics of the one-cycle fit; harmonics of the revolution series.
    pub mesh_harmonics: usize,
    pub revolution_harmonics: usize,
    /// Revolution series' largest residual at its samples over their ptp: k, δ.
    pub revolution_series_residual_of_ptp: [f64; 2],
    /// LTCA wall time, s.
    pub ltca_wall_s: f64,
    pub speeds: Vec<OrderMapSpeed>,
    /// What drives the runs: "solved revolution" (the LTCA over a whole
    /// wheel revolution, every wheel tooth in the stiffness file) or "lobe
    /// fitted to the span" (the lowest hole harmonic fitted to the span
    /// and extrapolated over the revolution); "" in files from before.
    #[serde(default)]
    pub excitation: String,
    /// With a solved revolution: the lobe fitted to the scene's sweep
    /// alone (its first `mesh_cycles_lightweight` cycles), as a stiffness
    /// file of those teeth only would give it, for comparison.
    #[serde(default)]
    pub short_span_lobe: Option<LobeFit>,
    /// With a solved revolution: how far the per-cycle mean k is from
    /// repeating every z₂/n teeth (max, rms over its mean; `solver::lumped::
    /// revolution::lobe_repeat_mismatch`).
    #[serde(default)]
    pub lobe_repeat_mismatch_of_mean: Option<[f64; 2]>,
    /// Wheel teeth (fractional) whose loaded flank sits over a web hole's
    /// centre (`geometry::gear_body::hole_wheel_teeth`); empty for a standard wheel.
    #[serde(default)]
    pub hole_wheel_teeth: Vec<f64>,
}

/// A lobe fit over an LTCA span ([`OrderMapSummary::short_span_lobe`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LobeFit {
    pub span_mesh_cycles: usize,
    pub stiffness_lobe: [f64; 3],
    pub stiffness_lobe_ptp_relative: f64,
    pub stiffness_lobe_minimum_wheel_tooth: Option<f64>,
}

/// One row of the order map.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OrderMapSpeed {
    pub pinion_speed_rpm: f64,
    pub mesh_frequency_hz: f64,
    /// Integration and whole-run wall time, s.
    pub integration_wall_s: f64,
    pub run_wall_s: f64,
    /// Spectral line spacing, pinion orders.
    pub order_resolution: f64,
    /// (label, pinion order, wheel bearing-force amplitude N) at the marked orders.
    pub marked: Vec<MarkedOrder>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MarkedOrder {
    pub label: String,
    pub pinion_order: f64,
    pub wheel_bearing_force_n: f64,
}
