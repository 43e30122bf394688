//! The reference stage's summaries (`<blank>/summary.json`, `summary.json`,
//! `compare_cache.json`): one type each, written by the stage and read by
//! the report.

use crate::reference::reference_ltca::PositionResult;
use formats::root_stress::RootStressSummary;
use serde::{Deserialize, Serialize};

/// The largest differences between positions solved now and their cached
/// results (`validate reference --compare-cache`), relative to the cached
/// value; torque balance (already relative) as an absolute difference.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct CacheComparison {
    pub positions_compared: usize,
    pub positions_without_cache: usize,
    pub unloaded_te: f64,
    pub te: f64,
    pub te_check: f64,
    pub max_pressure: f64,
    pub torque_balance_abs: f64,
    pub search_margin: f64,
    /// Positions whose working set or active-constraint counts differ.
    pub count_mismatches: usize,
    pub tolerance: f64,
}

impl CacheComparison {
    pub(crate) fn add(&mut self, new: &PositionResult, old: &PositionResult) {
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs().max(f64::MIN_POSITIVE);
        self.positions_compared += 1;
        self.unloaded_te = self.unloaded_te.max(rel(new.unloaded_te, old.unloaded_te));
        let mut counts_differ =
            new.constraints != old.constraints || new.loads.len() != old.loads.len();
        for (a, b) in new.loads.iter().zip(&old.loads) {
            self.te = self.te.max(rel(a.te, b.te));
            self.te_check = self.te_check.max(rel(a.te_check, b.te_check));
            self.max_pressure = self
                .max_pressure
                .max(rel(a.max_pressure_pa, b.max_pressure_pa));
            self.torque_balance_abs = self
                .torque_balance_abs
                .max((a.torque_balance - b.torque_balance).abs());
            if let (Some(x), Some(y)) = (a.search_margin_m, b.search_margin_m) {
                self.search_margin = self.search_margin.max(rel(x, y));
            }
            counts_differ |= a.active != b.active;
        }
        self.count_mismatches += usize::from(counts_differ);
    }

    /// The largest of the relative differences.
    pub fn worst(&self) -> f64 {
        [
            self.unloaded_te,
            self.te,
            self.te_check,
            self.max_pressure,
            self.torque_balance_abs,
            self.search_margin,
        ]
        .into_iter()
        .fold(0.0, f64::max)
    }
}

/// Per-torque statistics over the sweep.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct LoadSummary {
    pub torque_nm: f64,
    pub te_mean_urad: f64,
    pub te_ptp_urad: f64,
    /// Largest |TE(penalty) − TE(check penalty)| over the positions, % of
    /// the mean TE at this torque (at light loads the TE itself passes near
    /// zero, where a per-position percentage means nothing).
    pub penalty_difference_pct: f64,
    /// The same difference, µrad.
    pub penalty_difference_max_urad: f64,
    /// Mean and peak-to-peak TE at the check penalty factor, µrad, and of
    /// the TE extrapolated to the rigid limit per position: with a fixed
    /// active set the penalty springs act in series with the bodies, TE(p)
    /// = TE∞ + c/p, so TE∞ = (p TE(p) − p_c TE(p_c)) / (p − p_c). None in
    /// summaries written before they were recorded.
    #[serde(default)]
    pub te_check_mean_urad: Option<f64>,
    #[serde(default)]
    pub te_check_ptp_urad: Option<f64>,
    #[serde(default)]
    pub te_rigid_mean_urad: Option<f64>,
    #[serde(default)]
    pub te_rigid_ptp_urad: Option<f64>,
    pub max_pressure_mpa: f64,
    /// Largest |Σ forces × levers − torque| / torque over the positions.
    pub torque_balance_max: f64,
    /// Smallest loaded gap of the searched constraints left out of the
    /// solve in the outer half of the search range, µm (≥ 0 once settled).
    pub band_margin_min_um: f64,
    /// Smallest search margin over the positions (search gap − largest
    /// closure), µm; positive: nothing beyond the search range can have
    /// touched. None when a cached position predates it.
    pub search_margin_min_um: Option<f64>,
    /// Contact solves (both penalties) per position, s.
    pub cpu_s_per_position: f64,
    /// Each member's largest root (fillet) tension and compression over
    /// the positions, with where they sit; None when a position was solved
    /// without them (cached before they were computed).
    #[serde(default)]
    pub root_stress: Option<RootStressSummary>,
}

/// Summary of one pinion × wheel blank combination.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct BlankSummary {
    pub input_hash: String,
    pub pinion_blank: String,
    pub wheel_blank: String,
    pub level: String,
    pub penalty_factor: f64,
    pub penalty_factor_check: f64,
    pub positions: usize,
    pub step_deg: f64,
    pub mesh_cycles: f64,
    pub dofs: [usize; 2],
    pub factor_s: [f64; 2],
    /// Unit-load right-hand sides solved, and their time, per body.
    pub right_hand_sides: [usize; 2],
    pub solve_s: [f64; 2],
    /// Positions taken from the per-position cache of an earlier run.
    pub positions_reused: usize,
    /// Constraints searched per position (mean), and solved (mean).
    pub searched_mean: f64,
    pub constraints_mean: f64,
    /// Wall time of this run of the combination (factoring included), s.
    pub wall_s: f64,
    /// Wall time of this run's sweep (positions solved or reused), s.
    pub sweep_s: f64,
    /// Cost of the sweep from scratch: the positions' own times (when they
    /// were solved) plus factoring both bodies, s.
    pub total_cpu_s: f64,
    /// Wall time per position when it was solved (columns, condensation,
    /// all torques at both penalties; factoring excluded), s.
    pub cpu_s_per_position: f64,
    pub loads: Vec<LoadSummary>,
    pub unloaded: UnloadedCheck,
}

/// The meshed geometry's TE at a vanishing torque against the UTCA of the
/// generated flanks, at the same positions.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct UnloadedCheck {
    pub torque_nm: f64,
    /// Largest |TE(reference) − TE(UTCA)|, µrad.
    pub max_abs_difference_urad: f64,
    /// Mean of TE(reference) − TE(UTCA), µrad.
    pub mean_difference_urad: f64,
    pub utca_te_mean_urad: f64,
    pub utca_te_ptp_urad: f64,
    pub reference_te_mean_urad: f64,
    pub reference_te_ptp_urad: f64,
}
