//! `out/<scene>/sensitivity/summary.json` of `solver sensitivity` (each
//! misalignment E, P, G, ΔΣ swept alone at the scene's loads): written by
//! the solver, read by the report with this one definition.

use crate::root_stress::RootStressSummary;
use geometry::gear_body::Blank;
use geometry::misalignment::{Component, Misalignment};
use serde::{Deserialize, Serialize};

/// The loaded contact at one misalignment and one torque, over the scene's sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SensitivityLoad {
    pub torque_nm: f64,
    pub te_ptp_urad: f64,
    pub te_mean_urad: f64,
    /// The loaded pattern on the pinion flank over the sweep (every slice
    /// that carries load): centre of its extent and the extent, along the
    /// face (cone distance L) and in height (d above the pitch cone), mm.
    pub pattern_centre_l_mm: f64,
    pub pattern_centre_d_mm: f64,
    pub pattern_length_mm: f64,
    pub pattern_height_mm: f64,
    /// Largest Hertz pressure over the sweep, MPa.
    pub max_pressure_mpa: f64,
    /// The tooth root (fillet) stress extremes of pinion and wheel over the
    /// sweep, with where each sits; None when the stiffness files hold no
    /// root-stress coefficients (`[stiffness] root_stress = false`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub root_stress: Option<RootStressSummary>,
}

/// One value of one swept misalignment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SensitivityPoint {
    /// The swept component's offset from the scene's own value, in its unit.
    pub value: f64,
    /// The whole misalignment analysed (scene's own plus the offset).
    pub misalignment: Misalignment,
    /// One entry per scene torque.
    pub loads: Vec<SensitivityLoad>,
}

/// The sweep of one misalignment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SensitivityCurve {
    pub component: Component,
    pub symbol: String,
    pub unit: String,
    /// Half range of the sweep, in the unit.
    pub range: f64,
    pub points: Vec<SensitivityPoint>,
}

/// The study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SensitivitySummary {
    pub scene: String,
    pub pinion_blank: Blank,
    pub wheel_blank: Blank,
    /// The scene's own misalignment, which the sweeps are centred on.
    pub base: Misalignment,
    pub torques_nm: Vec<f64>,
    pub positions: usize,
    pub step_deg: f64,
    pub curves: Vec<SensitivityCurve>,
    /// Stiffness files read (once, for every misalignment: they are body-fixed).
    pub stiffness_files: Vec<std::path::PathBuf>,
    /// Wall time of the study (stiffness files read, every LTCA), s.
    pub wall_s: f64,
}

impl SensitivitySummary {
    /// Whether every load of the study has the root stress (the stiffness
    /// files held root-stress coefficients).
    pub fn has_root_stress(&self) -> bool {
        self.curves
            .iter()
            .flat_map(|c| &c.points)
            .flat_map(|p| &p.loads)
            .all(|l| l.root_stress.is_some())
    }
}
