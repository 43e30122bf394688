//! The cells of the stress matrix: what a cell varies, its outcome and
//! measures, the per-design and whole-set summaries, and filling a cell
//! from an LTCA sweep.

use super::TE_DECREASE_TOL;
use anyhow::Context;
use formats::summaries::EdgeContact;
use geometry::design::{Member, PairData};
use serde::{Deserialize, Serialize};
use solver::ltca::PositionResult;
use solver::stage::ltca::first_edge_contact;
use solver::SolverError;
use std::path::{Path, PathBuf};

/// What a cell varies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Study {
    Load,
    Slices,
    Grid,
    Flank,
    MaxStep,
    Tolerance,
    Speed,
    MultibodyLoad,
}

impl Study {
    pub const ALL: [Study; 8] = [
        Study::Load,
        Study::Slices,
        Study::Grid,
        Study::Flank,
        Study::MaxStep,
        Study::Tolerance,
        Study::Speed,
        Study::MultibodyLoad,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Study::Load => "load",
            Study::Slices => "slices",
            Study::Grid => "stiffness grid",
            Study::Flank => "flank",
            Study::MaxStep => "multibody max step",
            Study::Tolerance => "multibody tolerance",
            Study::Speed => "pinion speed",
            Study::MultibodyLoad => "multibody load",
        }
    }
}

/// A cell's outcome.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", content = "message", rename_all = "snake_case")]
pub enum Outcome {
    Converged,
    /// Refused by a check of the input, naming field, value and limit.
    Refused(String),
    /// An error in the run itself (no convergence, a singular system, ...).
    Failed(String),
    /// Not run: its inputs (meshes, stiffness files) are not cached.
    Skipped(String),
}

impl Outcome {
    pub fn class(&self) -> usize {
        match self {
            Outcome::Converged => 0,
            Outcome::Refused(_) => 1,
            Outcome::Failed(_) => 2,
            Outcome::Skipped(_) => 3,
        }
    }
    pub const CLASSES: [&'static str; 4] =
        ["converged", "refused", "failed", "skipped (not cached)"];
}

/// One cell of the matrix.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Cell {
    /// Scene name of the design.
    pub design: String,
    pub study: Study,
    /// The varied value, in `unit`.
    pub value: f64,
    pub unit: String,
    pub label: String,
    pub outcome: Outcome,
    /// LTCA: largest fixed-point iteration count over the positions;
    /// multibody: Newton iterations of the run.
    pub iterations: Option<usize>,
    /// LTCA: largest number of active-set changes over the positions.
    pub active_set_changes: Option<usize>,
    /// Multibody: accepted and rejected steps.
    pub steps: Option<usize>,
    pub rejected_steps: Option<usize>,
    /// Multibody: simulated time, s.
    #[serde(default)]
    pub sim_time_s: Option<f64>,
    /// A NaN or an infinity in any output of the cell.
    pub non_finite: bool,
    /// LTCA: largest |Σ λ₁F − T| / T over the positions (N·m at T = 0).
    pub torque_balance: Option<f64>,
    /// LTCA: every slice force ≥ 0.
    pub compressive_only: Option<bool>,
    /// Load study: TE at this load ≥ at the next lighter one, every
    /// position (None for the lightest).
    pub te_monotonic: Option<bool>,
    pub te_mean_urad: Option<f64>,
    /// Undamped multibody runs: largest |E(t) − E(0)| over the kinetic
    /// energy at the start plus the work the pinion torque does in the run.
    pub energy_drift: Option<f64>,
    /// LTCA: the first position whose contact reaches an edge of the flank.
    pub edge_contact: Option<EdgeContact>,
    /// Load study: the largest loaded deflection over the positions, as an
    /// arc at the wheel's mean pitch radius, (TE − unloaded TE) r₂ₘ, over
    /// the thinner member's mean normal tooth thickness (above
    /// [`DEFLECTION_LIMIT`]: implausible, see there).
    #[serde(default)]
    pub deflection_to_thickness: Option<f64>,
    /// CPU time of the cell, s (LTCA: all positions' threads).
    pub cpu_s: f64,
}

/// Per design.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DesignSummary {
    pub design: String,
    pub scene: PathBuf,
    /// Contact grid (profile × face) of its cached stiffness files.
    pub grid: [u32; 2],
    pub positions: usize,
    /// Smallest load of the load study with edge contact, and where.
    pub edge_contact_torque_nm: Option<f64>,
    pub edge_contact: Option<EdgeContact>,
    /// Largest load run.
    pub largest_load_nm: f64,
}

/// `summary.json` of the stress set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StressSummary {
    pub scene: String,
    pub designs: Vec<DesignSummary>,
    pub cells: Vec<Cell>,
    pub wall_s: f64,
}

impl StressSummary {
    /// Reads `<out>/<scene>/stress/summary.json`; None where absent.
    pub fn read(out: &Path, scene: &str) -> anyhow::Result<Option<StressSummary>> {
        let p = out.join(scene).join("stress").join("summary.json");
        match std::fs::read_to_string(&p) {
            Ok(t) => Ok(Some(
                serde_json::from_str(&t).with_context(|| format!("reading {}", p.display()))?,
            )),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
            Err(e) => Err(e).with_context(|| format!("reading {}", p.display())),
        }
    }
}

/// A refusal (a check of the input) or a failure of the run.
pub fn classify(e: &SolverError) -> Outcome {
    match e {
        SolverError::Torque(_) | SolverError::Table(_) | SolverError::ToothNotSolved { .. } => {
            Outcome::Refused(e.to_string())
        }
        _ => Outcome::Failed(e.to_string()),
    }
}

/// A converged cell of `design` with nothing measured yet.
pub fn cell(design: &str, study: Study, value: f64, unit: &str, label: String) -> Cell {
    Cell {
        design: design.to_string(),
        study,
        value,
        unit: unit.to_string(),
        label,
        outcome: Outcome::Converged,
        iterations: None,
        active_set_changes: None,
        steps: None,
        rejected_steps: None,
        sim_time_s: None,
        non_finite: false,
        torque_balance: None,
        compressive_only: None,
        te_monotonic: None,
        te_mean_urad: None,
        energy_drift: None,
        edge_contact: None,
        deflection_to_thickness: None,
        cpu_s: 0.0,
    }
}

/// Fills `c` from the sweep `res` at torque index `i` (torque `t`).
pub fn ltca_record(c: &mut Cell, res: &[PositionResult], i: usize, t: f64) {
    let loads = res.iter().map(|p| &p.loads[i]);
    c.iterations = loads.clone().map(|l| l.iterations).max();
    c.active_set_changes = loads.clone().map(|l| l.active_set_changes).max();
    c.non_finite = loads.clone().any(|l| {
        !l.finite
            || !l.max_pressure_pa.is_finite()
            || !l.wheel_torque_nm.is_finite()
            || l.slices.iter().any(|s| !s.half_width_m.is_finite())
    });
    let scale = if t > 0.0 { t } else { 1.0 };
    c.torque_balance = Some(
        loads
            .clone()
            .map(|l| l.torque_residual_nm.abs() / scale)
            .fold(
                0.0,
                |a: f64, b| if b.is_nan() { f64::NAN } else { a.max(b) },
            ),
    );
    c.compressive_only = Some(loads.clone().all(|l| l.min_force_n >= 0.0));
    c.te_mean_urad = Some(loads.clone().map(|l| l.te).sum::<f64>() / res.len().max(1) as f64 * 1e6);
    c.edge_contact = first_edge_contact(res, i);
    let n_t = res.first().map_or(1, |p| p.loads.len()) as f64;
    c.cpu_s = res
        .iter()
        .map(|p| p.loads[i].solve_s + (p.geometry_s + p.assembly_s) / n_t)
        .sum();
}

/// The largest loaded deflection at torque index `i` over the thinner
/// member's normal tooth thickness (see [`Cell::deflection_to_thickness`]).
pub fn deflection_to_thickness(res: &[PositionResult], i: usize, pair: &PairData) -> f64 {
    let r2 = pair.mean_cone_distance * pair.members[1].pitch_angle.sin();
    let s = pair
        .normal_thickness(Member::Pinion)
        .min(pair.normal_thickness(Member::Wheel));
    res.iter()
        .map(|p| (p.loads[i].te - p.utca_te) * r2)
        .fold(0.0, f64::max)
        / s
}

/// Where TE at torque index `i` < TE at `i − 1` anywhere (beyond rounding).
pub(super) fn te_decreases(res: &[PositionResult], i: usize) -> bool {
    res.iter()
        .any(|p| p.loads[i].te < p.loads[i - 1].te - TE_DECREASE_TOL)
}

/// Row label of a design's study.
pub fn row_label(design: &str, study: Study) -> String {
    format!("{design} · {}", study.name())
}
