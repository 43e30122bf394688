//! One blank × load row of the loaded-TE comparison (reduced model against
//! the reference and the published values), as the report and
//! `reports/summary.json` carry it.

use serde::Serialize;

/// One blank × load row.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Row {
    pub pinion_blank: String,
    pub wheel_blank: String,
    pub torque_nm: f64,
    pub multibody_te_mean_urad: f64,
    pub multibody_te_ptp_urad: f64,
    pub reference_te_mean_urad: f64,
    pub reference_te_ptp_urad: f64,
    /// The multibody TE sampled at the reference's positions (linear
    /// interpolation in pinion rotation): its mean and peak-to-peak, µrad.
    /// None when a file is missing.
    pub multibody_at_reference_mean_urad: Option<f64>,
    pub multibody_at_reference_ptp_urad: Option<f64>,
    /// (multibody − reference) / reference, %: from the samples at the
    /// reference's positions when available (a sparse reference would
    /// otherwise miss peaks the full run has), else from the full run.
    pub te_mean_difference_pct: f64,
    pub te_ptp_difference_pct: f64,
    pub reference_penalty_difference_pct: f64,
    pub reference_max_pressure_mpa: f64,
    pub multibody_steps: usize,
    pub multibody_cpu_s_per_step: f64,
    pub multibody_cpu_s: f64,
    /// CPU of the contact-element table the run integrates on, s: built
    /// once per blank pair for all its loads (CPU per position × positions).
    pub multibody_table_cpu_s: f64,
    pub reference_positions: usize,
    pub reference_cpu_s_per_position: f64,
    pub reference_cpu_s: f64,
    pub reference_level: String,
    /// When the reference above is finer than the reduced level: the
    /// reference on the reduced model's own (reduced-level) meshes, its
    /// mean and peak-to-peak TE (µrad) and the reduced model's differences
    /// to it (%), as a second column.
    pub reduced_level_reference_te_mean_urad: Option<f64>,
    pub reduced_level_reference_te_ptp_urad: Option<f64>,
    pub reduced_level_te_mean_difference_pct: Option<f64>,
    pub reduced_level_te_ptp_difference_pct: Option<f64>,
    pub published_multibody_te_mean_urad: Option<f64>,
    pub published_nlfea_te_mean_urad: Option<f64>,
    pub published_multibody_te_ptp_urad: Option<f64>,
    pub published_nlfea_te_ptp_urad: Option<f64>,
    pub published_multibody_cpu_s_per_step: Option<f64>,
    pub published_nlfea_cpu_s_per_step: Option<f64>,
    /// The white paper's total CPU of the multibody run and of the NLFEA
    /// sweep at this blank and load (Table 5), s.
    pub published_multibody_cpu_total_s: Option<f64>,
    pub published_nlfea_cpu_total_s: Option<f64>,
}
