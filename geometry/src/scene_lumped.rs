//! `[lumped]` scene section: the 8-degree-of-freedom lumped dynamic model
//! (`solver lumped`), driven by the scene's LTCA. SI units or the unit in
//! the field name; every field is read.

use crate::error::InputError;
use crate::limits::lumped as lim;
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
        self.check_run(path)?;
        self.check_model(path)?;
        self.check_friction_and_roughness(path)?;
        self.check_design_variants(path)?;
        self.check_order_map(path)
    }

    /// Speed, torque, mesh cycles, samples and the tolerances.
    fn check_run(&self, path: &Path) -> Result<(), InputError> {
        lim::PINION_SPEED.check(path, self.pinion_speed_rpm)?;
        lim::PINION_TORQUE.check(path, self.pinion_torque_nm)?;
        lim::MESH_CYCLES.check(path, self.mesh_cycles)?;
        let l = &lim::DROPPED_MESH_CYCLES;
        l.check_ends(path, l.field, self.dropped_mesh_cycles, &[self.mesh_cycles])?;
        let l = &lim::SAMPLES;
        l.check_integer(path, l.field, self.samples_per_mesh_cycle)?;
        lim::RELATIVE_TOLERANCE.check(path, self.relative_tolerance)?;
        lim::FOURIER_TOLERANCE.check(path, self.fourier_tolerance_of_ptp)
    }

    /// Damping ratios, bearing stiffnesses, masses and inertias, the impact
    /// pulse and the further torques.
    fn check_model(&self, path: &Path) -> Result<(), InputError> {
        lim::MESH_DAMPING.check(path, self.mesh_damping_ratio)?;
        lim::BEARING_DAMPING.check(path, self.bearing_damping_ratio)?;
        for (l, k) in [
            (
                &lim::PINION_BEARING_STIFFNESS,
                self.pinion_bearing_stiffness_n_per_m,
            ),
            (
                &lim::WHEEL_BEARING_STIFFNESS,
                self.wheel_bearing_stiffness_n_per_m,
            ),
        ] {
            if k.iter().any(|v| !l.admits(*v, &[])) {
                return Err(l.refuse(path, l.field, format!("{k:?}"), l.text_of_refusal()));
            }
        }
        for (l, v) in [
            (&lim::PINION_MASS, self.pinion_mass_kg),
            (&lim::WHEEL_MASS, self.wheel_mass_kg),
            (&lim::PINION_INERTIA, self.pinion_inertia_kgm2),
            (&lim::WHEEL_INERTIA, self.wheel_inertia_kgm2),
        ] {
            if let Some(v) = v {
                l.check(path, v)?;
            }
        }
        lim::IMPACT_PULSE.check(path, self.impact_pulse_of_mesh_period)?;
        let l = &lim::MORE_PINION_TORQUE_COUNT;
        let n = self.more_pinion_torques_nm.len();
        if !l.admits(n as f64, &[]) {
            return Err(l.refuse(path, l.field, format!("{n} entries"), l.text_of_refusal()));
        }
        for t in &self.more_pinion_torques_nm {
            lim::MORE_PINION_TORQUES.check(path, *t)?;
        }
        Ok(())
    }

    /// `[lumped.friction]` and `[lumped.roughness]`.
    fn check_friction_and_roughness(&self, path: &Path) -> Result<(), InputError> {
        if let Some(f) = &self.friction {
            lim::FRICTION_BASE.check(path, f.base_coefficient)?;
            lim::FRICTION_ROUGHNESS.check(path, f.roughness_coefficient_per_um)?;
        }
        if let Some(r) = &self.roughness {
            let l = &lim::ROUGHNESS_GRADES;
            let n = r.ra_um.len();
            if !l.admits(n as f64, &[]) {
                return Err(l.refuse(path, l.field, format!("{n} entries"), l.text_of_refusal()));
            }
            for ra in &r.ra_um {
                lim::ROUGHNESS_RA.check(path, *ra)?;
            }
            for (l, n) in [
                (&lim::ROUGHNESS_PROFILE_NODES, r.profile_nodes),
                (&lim::ROUGHNESS_FACE_NODES, r.face_nodes),
            ] {
                l.check_integer(path, l.field, n)?;
            }
        }
        Ok(())
    }

    /// `[[lumped.design_variants]]`: names and ease-off values.
    fn check_design_variants(&self, path: &Path) -> Result<(), InputError> {
        let l = &lim::VARIANT_COUNT;
        let n = self.design_variants.len();
        if !l.admits(n as f64, &[]) {
            return Err(l.refuse(path, l.field, format!("{n} entries"), l.text_of_refusal()));
        }
        for (i, v) in self.design_variants.iter().enumerate() {
            if self.design_variants[..i].iter().any(|w| w.name == v.name) {
                let l = &lim::VARIANT_NAMES_UNIQUE;
                return Err(l.refuse(
                    path,
                    l.field,
                    format!("{:?}", v.name),
                    "each name once: the name names the variant's output files".into(),
                ));
            }
            let ok_name = !v.name.is_empty()
                && v.name.len() <= 100
                && v.name
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_.-".contains(c));
            if !ok_name {
                let l = &lim::VARIANT_NAME;
                return Err(l.refuse(
                    path,
                    l.field,
                    format!("{:?}", v.name),
                    "must be 1 to 100 letters, digits, '_', '.', '-'".into(),
                ));
            }
            for (l, value) in [
                (&lim::VARIANT_TE_SLOPE, v.te_slope_m21),
                (&lim::VARIANT_PROFILE_CROWNING, v.profile_crowning_um),
                (&lim::VARIANT_LENGTHWISE_CROWNING, v.lengthwise_crowning_um),
            ] {
                if let Some(value) = value {
                    l.check(path, value)?;
                }
            }
        }
        Ok(())
    }

    /// `[lumped.order_map]`.
    fn check_order_map(&self, path: &Path) -> Result<(), InputError> {
        if let Some(o) = &self.order_map {
            let l = &lim::ORDER_MAP_SPEED_COUNT;
            let n = o.pinion_speeds_rpm.len();
            if !l.admits(n as f64, &[]) {
                return Err(l.refuse(path, l.field, format!("{n} entries"), l.text_of_refusal()));
            }
            for &v in &o.pinion_speeds_rpm {
                lim::ORDER_MAP_SPEEDS.check(path, v)?;
            }
            lim::ORDER_MAP_REVOLUTIONS.check(path, o.wheel_revolutions)?;
            // At least one revolution kept: the entry's upper end.
            let d = o.dropped_wheel_revolutions;
            if !(d.is_finite() && d >= 0.0 && o.wheel_revolutions - d >= 1.0) {
                let l = &lim::ORDER_MAP_DROPPED;
                return Err(l.refuse(path, l.field, d.to_string(), l.text_of_refusal()));
            }
            lim::ORDER_MAP_MAX_ORDER.check(path, o.max_pinion_order)?;
        }
        Ok(())
    }
}
