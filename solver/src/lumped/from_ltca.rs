//! Mesh stiffness k(t) and static transmission error e(t) of the 8-DOF
//! model from our quasi-static LTCA at the operating torque.
//!
//! Stiffness: the tangent k = dF/dδ of the loaded mesh, not the secant F/δ
//! (seed 004's "ratio of the applied load to the resulting deflection").
//! The dynamic model moves about the loaded static state, and a small
//! motion there meets the slope of the load–deflection curve; the Hertzian
//! (Weber–Banaschek) flattening and the growing contact area make that
//! curve stiffen with load, so F/δ underestimates the stiffness the
//! vibration sees. The tangent is the central difference over pinion
//! torques T(1 ± ε) at every position (the contact problem is solved
//! exactly at each, active set included):
//!
//! ```text
//! κ = dT₁/dθ ≈ 2εT / (θ(T(1+ε)) − θ(T(1−ε)))     (N·m/rad, θ the wheel lag)
//! k = κ / (r₁ r₂)                                    (N/m along the normal)
//! ```
//!
//! with F = T₁/r₁ and δ = r₂θ. Transmission error: with the tangent, the
//! mesh force of the model is F = k(λ − e) about the loaded state, so e(t)
//! is the tangent's intercept
//!
//! ```text
//! e = r₂ θ(T) − (T/r₁)/k
//! ```
//!
//! which makes the model's quasi-static deflection at torque T equal the
//! LTCA's loaded TE at every position (with the secant instead, e is the
//! unloaded TE and k = T/(r₁r₂(θ − θ₀))). Levers: r₁ = T / ΣFₙ and
//! r₂ = T₂ / ΣFₙ, the mean over the positions of our contact solution's
//! own torque per total normal force (pinion and wheel).

use super::excitation::{fit_to_tolerance, FittedSeries};
use super::LumpedError;
use crate::ltca::PositionResult;
use serde::Serialize;

/// The relative torque step ε of the tangent.
pub const TANGENT_STEP: f64 = 0.05;

/// The torques to run the LTCA at for [`mesh_samples`]: T(1 − ε), T, T(1 + ε).
pub fn tangent_torques(torque_nm: f64) -> [f64; 3] {
    [
        torque_nm * (1.0 - TANGENT_STEP),
        torque_nm,
        torque_nm * (1.0 + TANGENT_STEP),
    ]
}

/// The tangent torsional mesh stiffness from the loaded TE at two torques:
///
/// ```text
/// κ = (T₊ − T₋) / (θ(T₊) − θ(T₋))     (N·m/rad: pinion torque per wheel lag)
/// ```
///
/// `torques_nm` = [T₋, T₊], `te_rad` = [θ(T₋), θ(T₊)]. None when θ does not
/// grow with the torque (or either is not finite).
pub fn torsional_tangent(torques_nm: [f64; 2], te_rad: [f64; 2]) -> Option<f64> {
    let dtheta = te_rad[1] - te_rad[0];
    let kappa = (torques_nm[1] - torques_nm[0]) / dtheta;
    (dtheta > 0.0 && kappa.is_finite() && kappa > 0.0).then_some(kappa)
}

/// The mesh over one mesh cycle, one entry per LTCA position.
#[derive(Debug, Clone, Serialize)]
pub struct MeshSamples {
    /// Time from the sweep start at the pinion speed, s.
    pub time_s: Vec<f64>,
    /// Tangent k, N/m.
    pub tangent_n_per_m: Vec<f64>,
    /// Secant F/(δ − δ₀), N/m (for comparison; δ₀ the unloaded TE).
    pub secant_n_per_m: Vec<f64>,
    /// e (intercept of the tangent), m along the normal.
    pub te_m: Vec<f64>,
    /// Loaded static deflection r₂θ(T), m along the normal.
    pub deflection_m: Vec<f64>,
    /// LTCA loaded TE θ(T), rad (wheel lag).
    pub loaded_te_rad: Vec<f64>,
    /// LTCA unloaded TE, rad.
    pub unloaded_te_rad: Vec<f64>,
    /// Levers r₁, r₂, m.
    pub levers_m: [f64; 2],
    /// Mesh period, s.
    pub period_s: f64,
    pub torque_nm: f64,
}

impl MeshSamples {
    /// No samples yet: levers (m), mesh period (s), torque (N·m).
    pub fn empty(levers_m: [f64; 2], period_s: f64, torque_nm: f64) -> Self {
        Self {
            time_s: Vec::new(),
            tangent_n_per_m: Vec::new(),
            secant_n_per_m: Vec::new(),
            te_m: Vec::new(),
            deflection_m: Vec::new(),
            loaded_te_rad: Vec::new(),
            unloaded_te_rad: Vec::new(),
            levers_m,
            period_s,
            torque_nm,
        }
    }
}

/// Samples from an LTCA run at [`tangent_torques`]`(torque_nm)`, the
/// pinion turning at `pinion_speed_rad_s`; `mesh_cycle_rad` = 2π/z₁.
/// Positions at or past one mesh cycle from the first are left out (the
/// series is periodic).
pub fn mesh_samples(
    res: &[PositionResult],
    torque_nm: f64,
    pinion_speed_rad_s: f64,
    mesh_cycle_rad: f64,
) -> Result<MeshSamples, LumpedError> {
    span_samples(res, torque_nm, pinion_speed_rad_s, mesh_cycle_rad, 1.0)
}

/// As [`mesh_samples`], keeping the positions within `mesh_cycles` mesh
/// cycles of the first (`period_s` stays the mesh period).
pub fn span_samples(
    res: &[PositionResult],
    torque_nm: f64,
    pinion_speed_rad_s: f64,
    mesh_cycle_rad: f64,
    mesh_cycles: f64,
) -> Result<MeshSamples, LumpedError> {
    super::model::positive("torque", torque_nm, false)?;
    super::model::positive("pinion speed", pinion_speed_rad_s, false)?;
    let torques = tangent_torques(torque_nm);
    let mut s = MeshSamples::empty([0.0; 2], mesh_cycle_rad / pinion_speed_rad_s, torque_nm);
    let keep: Vec<&PositionResult> = res
        .iter()
        .filter(|p| p.rotation < mesh_cycles * mesh_cycle_rad - 1e-9 * mesh_cycle_rad)
        .collect();
    if keep.len() < 3 {
        return Err(LumpedError::Input(format!(
            "LTCA: {} positions inside one mesh cycle, need ≥ 3",
            keep.len()
        )));
    }
    let mut levers = [0.0; 2];
    for p in &keep {
        if p.loads.len() != 3 {
            return Err(LumpedError::Input(format!(
                "LTCA position at {} rad has {} torques, needs the 3 of tangent_torques",
                p.rotation,
                p.loads.len()
            )));
        }
        let total: f64 = p.loads[1].pair_force.iter().map(|f| f.1).sum();
        if total.is_nan() || total <= 0.0 {
            return Err(LumpedError::Input(format!(
                "LTCA position at {} rad carries no normal force",
                p.rotation
            )));
        }
        levers[0] += torque_nm / total;
        levers[1] += p.loads[1].wheel_torque_nm / total;
    }
    let r = levers.map(|l| l / keep.len() as f64);
    s.levers_m = r;
    for p in &keep {
        let Some(kappa) =
            torsional_tangent([torques[0], torques[2]], [p.loads[0].te, p.loads[2].te])
        else {
            return Err(LumpedError::Input(format!(
                "LTCA position at {} rad: loaded TE does not grow with torque ({} rad from {} to {} N·m)",
                p.rotation,
                p.loads[2].te - p.loads[0].te,
                torques[0],
                torques[2]
            )));
        };
        let k = kappa / (r[0] * r[1]);
        let theta = p.loads[1].te;
        s.time_s.push(p.rotation / pinion_speed_rad_s);
        s.tangent_n_per_m.push(k);
        s.secant_n_per_m
            .push(p.loads[1].mesh_stiffness / (r[0] * r[1]));
        s.te_m.push(r[1] * theta - torque_nm / r[0] / k);
        s.deflection_m.push(r[1] * theta);
        s.loaded_te_rad.push(theta);
        s.unloaded_te_rad.push(p.utca_te);
    }
    Ok(s)
}

/// k(t), e(t) and the loaded deflection δ(t) = r₂θ(t) fitted to
/// `samples`, each with the fewest harmonics whose largest residual is
/// ≤ `tolerance` × its samples' peak-to-peak. The model takes k and δ
/// ([`super::excitation::StaticError::LoadedDeflection`]): e = δ − F/k
/// inherits the position-to-position jitter of the tangent k (F/k is some
/// 30 times the TE's peak-to-peak), δ does not.
pub fn fit_series(samples: &MeshSamples, tolerance: f64) -> Result<[FittedSeries; 3], LumpedError> {
    Ok([
        fit_to_tolerance(
            &samples.time_s,
            &samples.tangent_n_per_m,
            samples.period_s,
            tolerance,
        )?,
        fit_to_tolerance(&samples.time_s, &samples.te_m, samples.period_s, tolerance)?,
        fit_to_tolerance(
            &samples.time_s,
            &samples.deflection_m,
            samples.period_s,
            tolerance,
        )?,
    ])
}
