//! The solver's stage summaries (`out/<scene>/{ltca,multibody}/summary.json`
//! and each blank pair's own `summary.json`): one type per file, written by
//! the solver and read by the report with the same definition, so a renamed
//! field fails to compile or fails to read, never drops a table silently.

use geometry::gear_body::Blank;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

// Loaded TCA (`solver ltca`).

/// Per-torque summary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LoadSummary {
    pub torque_nm: f64,
    pub te_mean_urad: f64,
    pub te_ptp_urad: f64,
    /// Geometry + compliance + contact solve of one position at this torque, s.
    pub cpu_s_per_position: f64,
    /// Contact solve alone, s per position.
    pub solve_s_per_position: f64,
    pub max_pressure_mpa: f64,
    pub mesh_stiffness_mean_nm_per_rad: f64,
    /// Largest torque share of one tooth pair over the sweep.
    pub max_pair_share: f64,
    /// Mean torque driving the wheel, N·m; the mesh efficiency is this ·
    /// z₁/z₂ / torque (one without friction, to the ease-off's departure
    /// from conjugate levers).
    pub wheel_torque_mean_nm: f64,
}

/// Summary of one pinion × wheel blank combination.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BlankSummary {
    pub pinion_blank: Blank,
    pub wheel_blank: Blank,
    pub positions: usize,
    pub step_deg: f64,
    pub mesh_cycles: f64,
    pub slices_per_pair: usize,
    /// Coulomb friction coefficient of the flanks.
    pub friction_coefficient: f64,
    pub utca_te_mean_urad: f64,
    pub utca_te_ptp_urad: f64,
    pub stiffness_files: Vec<PathBuf>,
    pub wall_s: f64,
    pub loads: Vec<LoadSummary>,
    pub dir: PathBuf,
    /// With coast-side contact (`multibody.coast_contact`): the same loads
    /// on the coast flanks.
    pub coast: Option<CoastSummary>,
}

/// The coast flanks under the scene's loads: the pinion driving the other
/// way over the same pinion angles (the sweep run backwards), each coast
/// flank with its own body tooth's compliance. TEs are the coast side's
/// lags (positive, as on the drive side); the drive side's lag at coast
/// contact is −backlash − TE.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CoastSummary {
    /// Angular backlash B of the conjugate flanks at the wheel, µrad.
    pub backlash_urad: f64,
    /// Body wheel tooth of the coast model's tooth k: k + this.
    pub wheel_tooth_shift: i64,
    pub utca_te_mean_urad: f64,
    pub utca_te_ptp_urad: f64,
    pub stiffness_files: Vec<PathBuf>,
    pub loads: Vec<LoadSummary>,
    pub dir: PathBuf,
}

// Multibody runs (`solver dynamic`).

/// One quasi-static run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QuasiStaticSummary {
    pub torque_nm: f64,
    /// TE sampled at the LTCA's positions.
    pub te_mean_urad: f64,
    pub te_ptp_urad: f64,
    pub steps: usize,
    pub rejected_steps: usize,
    pub cpu_s: f64,
    pub cpu_s_per_step: f64,
}

/// The run-up.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunupSummary {
    pub pinion_torque_nm: f64,
    pub rpm: [f64; 2],
    pub sim_time_s: f64,
    pub max_step_s: f64,
    pub steps: usize,
    pub rejected_steps: usize,
    pub cpu_s: f64,
    pub cpu_s_per_step: f64,
    /// Dynamic minus quasi-static TE: extremes over the run, µrad.
    pub te_dynamic_minus_static_urad: [f64; 2],
}

/// Summary of one pinion × wheel blank.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DynamicSummary {
    pub pinion_blank: Blank,
    pub wheel_blank: Blank,
    pub inertia_kgm2: [f64; 2],
    /// "scene" or "mesh" (∫ρr² dV over the body mesh).
    pub inertia_source: String,
    pub damping_nm_s_per_rad: f64,
    /// Coulomb friction coefficient of the flanks.
    pub friction_coefficient: f64,
    pub table_positions: usize,
    pub table_lag_nodes: usize,
    pub table_build_s: f64,
    pub table_cpu_s_per_position: f64,
    pub quasi_static: Vec<QuasiStaticSummary>,
    pub runup: Option<RunupSummary>,
    /// With coast-side contact: the conjugate flanks' angular backlash at
    /// the wheel and the free play between drive and coast contact over a
    /// mesh cycle (min, max), µrad, and the rattle run.
    pub backlash_urad: Option<f64>,
    pub free_play_urad: Option<[f64; 2]>,
    pub rattle: Option<RattleSummary>,
    pub dir: PathBuf,
}

/// The rattle run: fluctuating pinion speed, free wheel.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RattleSummary {
    pub pinion_rpm: f64,
    pub speed_fluctuation: f64,
    pub frequency_hz: f64,
    pub wheel_drag_nm: f64,
    pub sim_time_s: f64,
    pub steps: usize,
    pub rejected_steps: usize,
    pub cpu_s: f64,
    pub cpu_s_per_step: f64,
    /// Contacts begun on the drive and on the coast flanks.
    pub drive_impacts: usize,
    pub coast_impacts: usize,
    /// Share of the time in drive contact, coast contact and free flight.
    pub time_share_drive_coast_free: [f64; 3],
    /// Extremes of the pinion mesh torque, N·m (negative: coast side).
    pub mesh_torque_min_max_nm: [f64; 2],
    /// Extremes of the wheel lag, µrad, and of the wheel speed, rpm.
    pub te_min_max_urad: [f64; 2],
    pub wheel_rpm_min_max: [f64; 2],
}
