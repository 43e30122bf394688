//! The scene's optional `[bearings]` table: each member's shaft on
//! compliant bearings, for the LTCA with bearing deflection
//! (`solver::system_deflection`). Positions are along the member's axis from
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
}

fn default_tolerance_nm() -> f64 {
    1.0
}

fn default_max_iterations() -> usize {
    60
}

/// Stiffer than this is rigid for any gear mesh, N/m.
pub const MAX_BEARING_STIFFNESS_N_PER_M: f64 = 1e14;
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
