//! The scene's optional `[bearings]` table: each member's shaft on
//! compliant bearings, for the LTCA with bearing deflection
//! (`solver::bearings::system_deflection`). Positions are along the member's axis from
//! its pitch apex, positive toward (and beyond) the teeth.
//!
//! ```toml
//! [bearings]
//! pinion = [
//!   { axial_position_mm = 110.0, radial_stiffness_n_per_m = 5e8, axial_stiffness_n_per_m = 5e8 },
//!   { axial_position_mm = 170.0, radial_stiffness_n_per_m = 5e8, axial_stiffness_n_per_m = 0.0 },
//! ]
//! wheel = [ ... ]
//! ```

use crate::error::InputError;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// One bearing of a shaft.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BearingMm {
    /// Along the member's axis from its pitch apex, mm.
    pub axial_position_mm: f64,
    /// Radial stiffness, N/m (the same in every radial direction).
    pub radial_stiffness_n_per_m: f64,
    /// Axial stiffness, N/m (0: floating).
    pub axial_stiffness_n_per_m: f64,
    /// Viscous damping, radial and axial, N·s/m (multibody with compliant
    /// bearings only; the quasi-static LTCA has no speeds). Default 0.
    #[serde(default)]
    pub radial_damping_n_s_per_m: f64,
    #[serde(default)]
    pub axial_damping_n_s_per_m: f64,
}

/// A member's mass properties for the multibody with compliant bearings
/// (the translations and tilts on its bearings). Without it: the mass from
/// the mesh (volume × density, the folder's manifest), the centre of mass
/// at the mean point of the pitch cone's axis, and the transverse moment
/// half the polar moment (a thin disc's).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyMass {
    pub mass_kg: f64,
    /// Centre of mass along the member's axis from its pitch apex, mm.
    pub centroid_mm: f64,
    /// Moment of inertia about an axis ⊥ the shaft through the centre of
    /// mass, kg·m².
    pub transverse_inertia_kgm2: f64,
}

/// Both members' bearings and the iteration's settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BearingSettings {
    pub pinion: Vec<BearingMm>,
    pub wheel: Vec<BearingMm>,
    /// Convergence of the members' displacements, nm.
    #[serde(default = "default_tolerance_nm")]
    pub tolerance_nm: f64,
    /// Most iterations of contact and bearing deflection per position.
    #[serde(default = "default_max_iterations")]
    pub max_iterations: usize,
    /// Mass properties of the members (multibody; see [`BodyMass`]).
    #[serde(default)]
    pub pinion_body: Option<BodyMass>,
    #[serde(default)]
    pub wheel_body: Option<BodyMass>,
}

fn default_tolerance_nm() -> f64 {
    1.0
}

fn default_max_iterations() -> usize {
    60
}

/// Stiffer than this is rigid for any gear mesh, N/m.
pub const MAX_BEARING_STIFFNESS_N_PER_M: f64 = 1e14;
/// Largest bearing damping, N·s/m.
pub const MAX_BEARING_DAMPING_N_S_PER_M: f64 = 1e9;
/// Farthest bearing from the apex, mm.
pub const MAX_BEARING_POSITION_MM: f64 = 10_000.0;

impl BearingSettings {
    /// Every number finite and in range; each shaft held against tilt (two
    /// radial bearings at different positions) and along its axis (one
    /// axial bearing).
    pub fn check(&self, path: &Path) -> Result<(), InputError> {
        let fail = |field: String, value: String, limit: &str| InputError::Invalid {
            path: path.to_path_buf(),
            field,
            value,
            limit: limit.into(),
        };
        for (member, list) in [("pinion", &self.pinion), ("wheel", &self.wheel)] {
            for (i, b) in list.iter().enumerate() {
                let f = |name: &str| format!("bearings.{member}[{i}].{name}");
                if !(b.axial_position_mm.is_finite()
                    && b.axial_position_mm.abs() <= MAX_BEARING_POSITION_MM)
                {
                    return Err(fail(
                        f("axial_position_mm"),
                        b.axial_position_mm.to_string(),
                        "must be finite, within ±10,000 mm of the pitch apex",
                    ));
                }
                for (name, v) in [
                    ("radial_stiffness_n_per_m", b.radial_stiffness_n_per_m),
                    ("axial_stiffness_n_per_m", b.axial_stiffness_n_per_m),
                ] {
                    if !(v.is_finite() && (0.0..=MAX_BEARING_STIFFNESS_N_PER_M).contains(&v)) {
                        return Err(fail(f(name), v.to_string(), "must lie in [0, 1e14] N/m"));
                    }
                }
                for (name, v) in [
                    ("radial_damping_n_s_per_m", b.radial_damping_n_s_per_m),
                    ("axial_damping_n_s_per_m", b.axial_damping_n_s_per_m),
                ] {
                    if !(v.is_finite() && (0.0..=MAX_BEARING_DAMPING_N_S_PER_M).contains(&v)) {
                        return Err(fail(f(name), v.to_string(), "must lie in [0, 1e9] N·s/m"));
                    }
                }
            }
            let radial: Vec<f64> = list
                .iter()
                .filter(|b| b.radial_stiffness_n_per_m > 0.0)
                .map(|b| b.axial_position_mm)
                .collect();
            let distinct = radial.iter().any(|&a| radial.iter().any(|&b| a != b));
            if !distinct {
                return Err(fail(
                    format!("bearings.{member}"),
                    format!("{} bearings with radial stiffness", radial.len()),
                    "needs two bearings with radial stiffness at different axial positions (to hold tilt)",
                ));
            }
            if list.iter().all(|b| b.axial_stiffness_n_per_m <= 0.0) {
                return Err(fail(
                    format!("bearings.{member}"),
                    "no axial stiffness".into(),
                    "needs one bearing with axial_stiffness_n_per_m > 0 (else the shaft slides along its axis)",
                ));
            }
        }
        for (member, body) in [
            ("pinion_body", &self.pinion_body),
            ("wheel_body", &self.wheel_body),
        ] {
            let Some(b) = body else { continue };
            let f = |name: &str| format!("bearings.{member}.{name}");
            if !(b.mass_kg.is_finite() && b.mass_kg > 0.0 && b.mass_kg <= 1e5) {
                return Err(fail(
                    f("mass_kg"),
                    b.mass_kg.to_string(),
                    "must lie in (0, 1e5] kg",
                ));
            }
            if !(b.centroid_mm.is_finite() && b.centroid_mm.abs() <= MAX_BEARING_POSITION_MM) {
                return Err(fail(
                    f("centroid_mm"),
                    b.centroid_mm.to_string(),
                    "must be finite, within ±10,000 mm of the pitch apex",
                ));
            }
            let jt = b.transverse_inertia_kgm2;
            if !(jt.is_finite() && jt > 0.0 && jt <= 1e4) {
                return Err(fail(
                    f("transverse_inertia_kgm2"),
                    jt.to_string(),
                    "must lie in (0, 1e4] kg·m²",
                ));
            }
        }
        if !(self.tolerance_nm.is_finite() && (1e-3..=1e3).contains(&self.tolerance_nm)) {
            return Err(fail(
                "bearings.tolerance_nm".into(),
                self.tolerance_nm.to_string(),
                "must lie in [0.001, 1000] nm",
            ));
        }
        if !(2..=500).contains(&self.max_iterations) {
            return Err(fail(
                "bearings.max_iterations".into(),
                self.max_iterations.to_string(),
                "must lie in [2, 500]",
            ));
        }
        Ok(())
    }
}
