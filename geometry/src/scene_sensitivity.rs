//! The scene's `[sensitivity]` table: the ranges of `solver sensitivity`,
//! which sweeps each misalignment E, P, G, ΔΣ alone over `values` equally
//! spaced values in [−range, +range] (on top of the scene's own
//! `[misalignment]`) at the scene's loads.

use crate::design::PairData;
use crate::error::InputError;
use crate::limits::scene as lim;
use crate::misalignment::{Component, Misalignment};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Ranges of the sensitivity study.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SensitivitySettings {
    /// Values per misalignment (odd, so that the middle one is the scene's own).
    pub values: usize,
    /// Half ranges: E, P, G in mm, ΔΣ in deg.
    pub offset_mm: f64,
    pub pinion_axial_mm: f64,
    pub wheel_axial_mm: f64,
    pub shaft_angle_deg: f64,
}

impl Default for SensitivitySettings {
    fn default() -> Self {
        SensitivitySettings {
            values: 9,
            offset_mm: 0.05,
            pinion_axial_mm: 0.05,
            wheel_axial_mm: 0.05,
            shaft_angle_deg: 0.02,
        }
    }
}

impl SensitivitySettings {
    /// The half range of one misalignment, in its unit.
    pub fn range(&self, c: Component) -> f64 {
        let as_misalignment = Misalignment {
            offset_mm: self.offset_mm,
            pinion_axial_mm: self.pinion_axial_mm,
            wheel_axial_mm: self.wheel_axial_mm,
            shaft_angle_deg: self.shaft_angle_deg,
        };
        as_misalignment.get(c)
    }

    /// The swept values of `c`: `values` equally spaced in [−range, range].
    pub fn sweep(&self, c: Component) -> Vec<f64> {
        let r = self.range(c);
        let n = self.values;
        (0..n)
            .map(|k| -r + 2.0 * r * k as f64 / (n - 1) as f64)
            .collect()
    }

    /// `values` odd in [3, 41]; every range positive, and with the scene's
    /// own misalignment `base` added, within the misalignment's limits.
    pub fn check(
        &self,
        path: &Path,
        base: &Misalignment,
        pair: &PairData,
    ) -> Result<(), InputError> {
        let l = &lim::SENSITIVITY_VALUES;
        l.check_integer(path, l.field, self.values)?;
        for c in Component::ALL {
            let r = self.range(c);
            let room = Misalignment::limit(c, pair) - base.get(c).abs();
            let l = match c {
                Component::Offset => &lim::SENSITIVITY_OFFSET,
                Component::PinionAxial => &lim::SENSITIVITY_PINION_AXIAL,
                Component::WheelAxial => &lim::SENSITIVITY_WHEEL_AXIAL,
                Component::ShaftAngle => &lim::SENSITIVITY_SHAFT_ANGLE,
            };
            l.check_with(path, l.field, r, &[room], || {
                format!(
                    "must lie in (0, {room:.4}] {}: the limit of |{}| less the scene's own misalignment",
                    c.unit(),
                    c.symbol()
                )
            })?;
        }
        Ok(())
    }
}
