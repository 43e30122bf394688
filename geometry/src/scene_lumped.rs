//! `[lumped]` scene section: the 8-degree-of-freedom lumped dynamic model
//! (`solver lumped`), driven by the scene's LTCA. SI units or the unit in
//! the field name; every field is read.

use crate::error::InputError;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// How the meshing impact enters the model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ImpactModel {
    /// No added pulse: the engagement of the entering pair acts only
    /// through k(t) and e(t) of our contact element.
    Engagement,
    /// Seed 004's pulse: peak F_s = v_s √(k_s mₑ′) at the entering pair's
    /// first loaded position, half-sine of `impact_pulse_of_mesh_period`.
    Seed004,
}

/// Where the mesh normal's direction cosines (a₁, a₂, a₃) come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DirectionSource {
    /// Seed 004's formula from αₙ, β₂, δ₂ and the wheel's hand.
    Seed004,
    /// Our LTCA's force-weighted flank normal over the mesh cycle at the
    /// operating torque (each component's sign as seed 004's: with
    /// diagonal bearings an axis's sign convention does not change the
    /// response).
    Ltca,
}

/// Settings of the lumped run.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct LumpedSettings {
    /// Pinion speed, rpm.
    pub pinion_speed_rpm: f64,
    /// Operating pinion torque, N·m (the LTCA runs at it and ±5 % for the
    /// tangent stiffness).
    pub pinion_torque_nm: f64,
    /// Mesh cycles integrated, and the first ones dropped from the statistics.
    pub mesh_cycles: f64,
    pub dropped_mesh_cycles: f64,
    /// Output samples per mesh cycle.
    pub samples_per_mesh_cycle: usize,
    /// Relative tolerance of the Dormand–Prince 5(4) steps.
    pub relative_tolerance: f64,
    /// Harmonic count of k(t), e(t): the fewest whose largest residual at the
    /// LTCA positions is within this share of the samples' peak-to-peak.
    pub fourier_tolerance_of_ptp: f64,
    /// Mesh damping ratio ζ: cₙ = 2ζ√(kₘ mₑ).
    pub mesh_damping_ratio: f64,
    /// Bearing stiffness in X, Y, Z, N/m.
    pub pinion_bearing_stiffness_n_per_m: [f64; 3],
    pub wheel_bearing_stiffness_n_per_m: [f64; 3],
    /// Bearing damping ratio per direction: c = 2ζ√(k m).
    pub bearing_damping_ratio: f64,
    /// Masses and polar moments; absent: from the reduced mesh (volume ×
    /// density, ∫ρr²dV) in the mesh folder's manifest.
    pub pinion_mass_kg: Option<f64>,
    pub wheel_mass_kg: Option<f64>,
    pub pinion_inertia_kgm2: Option<f64>,
    pub wheel_inertia_kgm2: Option<f64>,
    pub impact: ImpactModel,
    /// Impact pulse length over the mesh period (seed 004: 0.05).
    pub impact_pulse_of_mesh_period: f64,
    /// Source of the direction cosines.
    pub direction_cosines: DirectionSource,
    /// Further operating pinion torques, N·m, each its own run (LTCA at
    /// T(1 ± 5 %) and the model), beside `pinion_torque_nm`.
    pub more_pinion_torques_nm: Vec<f64>,
    /// Friction in the model (seed 003's μ = μ₀ + μ_r R); absent: none.
    pub friction: Option<LumpedFriction>,
    /// W–M roughness grades added to the pinion flank, each its own run
    /// beside the smooth flank; absent: smooth only.
    pub roughness: Option<LumpedRoughness>,
    /// Ease-off variants of the design, each its own run at every torque
    /// (seed 004's TE-slope and contact-ratio studies). They reuse the
    /// design's FE meshes and stiffness files: an ease-off is a few µm,
    /// far below the meshes' element size.
    pub design_variants: Vec<DesignVariant>,
    /// Order map: instead of the one-mesh-cycle run, the excitation over a
    /// whole wheel revolution (the lightweight wheel's web holes make it
    /// repeat only once per wheel turn) and runs at several speeds.
    pub order_map: Option<OrderMapSettings>,
}

/// `[lumped.order_map]`: the bearing-force spectrum over pinion orders at
/// several pinion speeds, the excitation k(t), δ(t) a series over one
/// wheel revolution sampled from the LTCA.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct OrderMapSettings {
    /// Pinion speeds of the runs, rpm (the map's rows).
    pub pinion_speeds_rpm: Vec<f64>,
    /// Simulated wheel revolutions per run.
    pub wheel_revolutions: f64,
    /// Wheel revolutions dropped before the spectrum (start transient).
    pub dropped_wheel_revolutions: f64,
    /// Highest pinion order of the map.
    pub max_pinion_order: f64,
}

/// One ease-off variant: the design's ease-off with these values replaced.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct DesignVariant {
    /// Name in the output (letters, digits, '_', '.', '-').
    pub name: String,
    /// Seed 004's first derivative of the transmission ratio m′₂₁ at the
    /// reference point (1/rad, ≤ 0): the parabolic motion error
    /// TE = ½ m′₂₁ (φ₁ − φ₀)², i.e. the design's motion error
    /// A = ½ |m′₂₁| (τ/2)² wheel radians at ±half a mesh cycle τ.
    pub te_slope_m21: Option<f64>,
    pub profile_crowning_um: Option<f64>,
    pub lengthwise_crowning_um: Option<f64>,
}

/// Seed 003's friction coefficient μ = μ₀ + μ_r R (its Eq. (30)), R the
/// effective roughness of the contact in µm.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LumpedFriction {
    /// μ₀.
    pub base_coefficient: f64,
    /// μ_r, per µm of R.
    pub roughness_coefficient_per_um: f64,
}

/// Seed 003's W–M roughness grades on the pinion flank.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LumpedRoughness {
    /// Ra of each grade, µm (D from seed 003's Eq. (41), G for the Ra).
    pub ra_um: Vec<f64>,
    /// Seed of the W–M phases (the same seed, the same flanks).
    pub seed: u64,
    /// Topography nodes along the profile and the face width.
    pub profile_nodes: usize,
    pub face_nodes: usize,
}

impl Default for LumpedSettings {
    fn default() -> Self {
        Self {
            pinion_speed_rpm: 1000.0,
            pinion_torque_nm: 100.0,
            mesh_cycles: 50.0,
            dropped_mesh_cycles: 10.0,
            samples_per_mesh_cycle: 256,
            relative_tolerance: 1e-6,
            fourier_tolerance_of_ptp: 0.1,
            mesh_damping_ratio: 0.1,
            pinion_bearing_stiffness_n_per_m: [1e9; 3],
            wheel_bearing_stiffness_n_per_m: [1e9; 3],
            bearing_damping_ratio: 0.05,
            pinion_mass_kg: None,
            wheel_mass_kg: None,
            pinion_inertia_kgm2: None,
            wheel_inertia_kgm2: None,
            impact: ImpactModel::Engagement,
            impact_pulse_of_mesh_period: 0.05,
            direction_cosines: DirectionSource::Seed004,
            more_pinion_torques_nm: Vec::new(),
            friction: None,
            roughness: None,
            design_variants: Vec::new(),
            order_map: None,
        }
    }
}

impl LumpedSettings {
    /// Checks every value against its limit; errors name field, value and limit.
    pub fn check(&self, path: &Path) -> Result<(), InputError> {
        let ck = LumpedCheck { path };
        self.check_run(&ck)?;
        self.check_model(&ck)?;
        self.check_friction_and_roughness(&ck)?;
        self.check_design_variants(&ck)?;
        self.check_order_map(&ck)
    }

    /// Speed, torque, mesh cycles, samples and the tolerances.
    fn check_run(&self, ck: &LumpedCheck) -> Result<(), InputError> {
        ck.range(
            "pinion_speed_rpm",
            self.pinion_speed_rpm,
            0.0,
            1e5,
            "must lie in (0, 100000]",
        )?;
        ck.range(
            "pinion_torque_nm",
            self.pinion_torque_nm,
            0.0,
            1e6,
            "must lie in (0, 1e6]",
        )?;
        ck.range(
            "mesh_cycles",
            self.mesh_cycles,
            0.0,
            1e4,
            "must lie in (0, 10000]",
        )?;
        if !(self.dropped_mesh_cycles >= 0.0 && self.dropped_mesh_cycles < self.mesh_cycles) {
            return Err(ck.fail(
                "dropped_mesh_cycles",
                self.dropped_mesh_cycles.to_string(),
                "must lie in [0, mesh_cycles)",
            ));
        }
        if !(16..=4096).contains(&self.samples_per_mesh_cycle) {
            return Err(ck.fail(
                "samples_per_mesh_cycle",
                self.samples_per_mesh_cycle.to_string(),
                "must lie in [16, 4096]",
            ));
        }
        ck.range(
            "relative_tolerance",
            self.relative_tolerance,
            1e-13,
            1e-2,
            "must lie in (1e-13, 1e-2]",
        )?;
        ck.range(
            "fourier_tolerance_of_ptp",
            self.fourier_tolerance_of_ptp,
            0.0,
            1.0,
            "must lie in (0, 1]",
        )?;
        Ok(())
    }

    /// Damping ratios, bearing stiffnesses, masses and inertias, the impact
    /// pulse and the further torques.
    fn check_model(&self, ck: &LumpedCheck) -> Result<(), InputError> {
        for (f, v) in [
            ("mesh_damping_ratio", self.mesh_damping_ratio),
            ("bearing_damping_ratio", self.bearing_damping_ratio),
        ] {
            if !(v.is_finite() && (0.0..=1.0).contains(&v)) {
                return Err(ck.fail(f, v.to_string(), "must lie in [0, 1]"));
            }
        }
        for (f, k) in [
            (
                "pinion_bearing_stiffness_n_per_m",
                self.pinion_bearing_stiffness_n_per_m,
            ),
            (
                "wheel_bearing_stiffness_n_per_m",
                self.wheel_bearing_stiffness_n_per_m,
            ),
        ] {
            if k.iter().any(|v| !(v.is_finite() && *v > 0.0 && *v <= 1e13)) {
                return Err(ck.fail(f, format!("{k:?}"), "each must lie in (0, 1e13]"));
            }
        }
        for (f, v) in [
            ("pinion_mass_kg", self.pinion_mass_kg),
            ("wheel_mass_kg", self.wheel_mass_kg),
            ("pinion_inertia_kgm2", self.pinion_inertia_kgm2),
            ("wheel_inertia_kgm2", self.wheel_inertia_kgm2),
        ] {
            if let Some(v) = v {
                if !(v.is_finite() && v > 0.0) {
                    return Err(ck.fail(f, v.to_string(), "must be finite and > 0"));
                }
            }
        }
        ck.range(
            "impact_pulse_of_mesh_period",
            self.impact_pulse_of_mesh_period,
            0.0,
            0.5,
            "must lie in (0, 0.5]",
        )?;
        for t in &self.more_pinion_torques_nm {
            ck.range(
                "more_pinion_torques_nm",
                *t,
                0.0,
                1e6,
                "each must lie in (0, 1e6]",
            )?;
        }
        Ok(())
    }

    /// `[lumped.friction]` and `[lumped.roughness]`.
    fn check_friction_and_roughness(&self, ck: &LumpedCheck) -> Result<(), InputError> {
        if let Some(f) = &self.friction {
            for (field, v) in [
                ("friction.base_coefficient", f.base_coefficient),
                (
                    "friction.roughness_coefficient_per_um",
                    f.roughness_coefficient_per_um,
                ),
            ] {
                if !(v.is_finite() && (0.0..=2.0).contains(&v)) {
                    return Err(ck.fail(field, v.to_string(), "must lie in [0, 2]"));
                }
            }
        }
        if let Some(r) = &self.roughness {
            if r.ra_um.is_empty() {
                return Err(ck.fail("roughness.ra_um", "[]".into(), "needs at least one grade"));
            }
            for ra in &r.ra_um {
                ck.range(
                    "roughness.ra_um",
                    *ra,
                    0.0,
                    10.0,
                    "each must lie in (0, 10] µm",
                )?;
            }
            for (field, n) in [
                ("roughness.profile_nodes", r.profile_nodes),
                ("roughness.face_nodes", r.face_nodes),
            ] {
                if !(2..=crate::design_file::MAX_TOPOGRAPHY_NODES).contains(&n) {
                    return Err(ck.fail(field, n.to_string(), "must lie in [2, 200]"));
                }
            }
        }
        Ok(())
    }

    /// `[[lumped.design_variants]]`: names and ease-off values.
    fn check_design_variants(&self, ck: &LumpedCheck) -> Result<(), InputError> {
        for v in &self.design_variants {
            let ok_name = !v.name.is_empty()
                && v.name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_.-".contains(c));
            if !ok_name {
                return Err(ck.fail(
                    "design_variants.name",
                    format!("{:?}", v.name),
                    "must be non-empty letters, digits, '_', '.', '-'",
                ));
            }
            if let Some(m) = v.te_slope_m21 {
                if !(m.is_finite() && (-0.1..=0.0).contains(&m)) {
                    return Err(ck.fail(
                        "design_variants.te_slope_m21",
                        m.to_string(),
                        "must lie in [-0.1, 0] per rad",
                    ));
                }
            }
            for (field, c) in [
                ("design_variants.profile_crowning_um", v.profile_crowning_um),
                (
                    "design_variants.lengthwise_crowning_um",
                    v.lengthwise_crowning_um,
                ),
            ] {
                if let Some(c) = c {
                    if !(c.is_finite() && (0.0..=500.0).contains(&c)) {
                        return Err(ck.fail(field, c.to_string(), "must lie in [0, 500] µm"));
                    }
                }
            }
        }
        Ok(())
    }

    /// `[lumped.order_map]`.
    fn check_order_map(&self, ck: &LumpedCheck) -> Result<(), InputError> {
        if let Some(o) = &self.order_map {
            if o.pinion_speeds_rpm.is_empty() {
                return Err(ck.fail(
                    "order_map.pinion_speeds_rpm",
                    "[]".into(),
                    "must hold at least one speed",
                ));
            }
            for &v in &o.pinion_speeds_rpm {
                if !(v.is_finite() && v > 0.0 && v <= 100_000.0) {
                    return Err(ck.fail(
                        "order_map.pinion_speeds_rpm",
                        v.to_string(),
                        "must lie in (0, 100000] rpm",
                    ));
                }
            }
            if !(o.wheel_revolutions.is_finite() && (1.0..=20.0).contains(&o.wheel_revolutions)) {
                return Err(ck.fail(
                    "order_map.wheel_revolutions",
                    o.wheel_revolutions.to_string(),
                    "must lie in [1, 20]",
                ));
            }
            let d = o.dropped_wheel_revolutions;
            if !(d.is_finite() && d >= 0.0 && o.wheel_revolutions - d >= 1.0) {
                return Err(ck.fail(
                    "order_map.dropped_wheel_revolutions",
                    d.to_string(),
                    "must be >= 0 and leave at least one wheel revolution",
                ));
            }
            if !(o.max_pinion_order.is_finite() && o.max_pinion_order > 0.0) {
                return Err(ck.fail(
                    "order_map.max_pinion_order",
                    o.max_pinion_order.to_string(),
                    "must be finite and > 0",
                ));
            }
        }
        Ok(())
    }
}

/// The checks' error for a field of `[lumped]` in the scene at `path`.
struct LumpedCheck<'a> {
    path: &'a Path,
}

impl LumpedCheck<'_> {
    /// `lumped.<field>` = `value` outside `limit`.
    fn fail(&self, field: &str, value: String, limit: &str) -> InputError {
        InputError::Invalid {
            path: self.path.to_path_buf(),
            field: format!("lumped.{field}"),
            value,
            limit: limit.into(),
        }
    }

    /// `v` finite and in (lo, hi], else `limit`.
    fn range(&self, field: &str, v: f64, lo: f64, hi: f64, limit: &str) -> Result<(), InputError> {
        if v.is_finite() && v > lo && v <= hi {
            Ok(())
        } else {
            Err(self.fail(field, v.to_string(), limit))
        }
    }
}
