//! The gearbox's natural modes about a loaded state, and where they meet
//! the excitation orders (Campbell diagram).
//!
//! The contact element is linearized at the quasi-static state: its
//! tangent on the first 12 coordinates (Lᵀ ∂F/∂c L, [`crate::multibody::
//! compliant::CompliantMesh::stiffness`]) is added to the structure's K,
//! symmetrized (its asymmetry, the virtual-work term of the unloaded
//! shift's slope, is of relative size s′·m). A member whose speed the
//! drive imposes is held. The modes solve the dense generalized problem
//! (K + K_m) φ = ω² M φ (Cholesky of M, then the symmetric eigenproblem).
//! Each mode's kinetic energy φᵀ M φ = 1 is split by part as
//! Σ_{i ∈ part} φᵢ (M φ)ᵢ: what moves in it.

use super::structure::{GearboxStructure, Part};
use nalgebra::{DVector, SMatrix};

/// One natural mode of the loaded gearbox.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SystemMode {
    pub frequency_hz: f64,
    /// Share of the mode's kinetic energy in: pinion turn, wheel turn,
    /// pinion body, wheel body, pinion shaft, wheel shaft, housing.
    pub energy_share: [f64; 7],
}

/// Names of [`SystemMode::energy_share`]'s entries.
pub const ENERGY_PARTS: [&str; 7] = [
    "pinion turn",
    "wheel turn",
    "pinion body",
    "wheel body",
    "pinion shaft",
    "wheel shaft",
    "housing",
];

fn part_index(p: Part) -> usize {
    match p {
        Part::Spin(k) => k,
        Part::Body(k) => 2 + k,
        Part::Shaft(k) => 4 + k,
        Part::Housing => 6,
    }
}

/// The modes of `s` with the mesh tangent `mesh` (on q₁, q₂, d₁, d₂),
/// members with `held[k]` held, ascending (all of them, rigid ones at 0 Hz).
pub fn system_modes(
    s: &GearboxStructure,
    mesh: &SMatrix<f64, 12, 12>,
    held: [bool; 2],
) -> Option<Vec<SystemMode>> {
    let n = s.parts.len();
    let mut k = s.stiffness.clone();
    for i in 0..12 {
        for j in 0..12 {
            k[(i, j)] += 0.5 * (mesh[(i, j)] + mesh[(j, i)]);
        }
    }
    let keep: Vec<usize> = (0..n).filter(|&i| !(i < 2 && held[i])).collect();
    let k = k.select_rows(&keep).select_columns(&keep);
    let m = s.mass.select_rows(&keep).select_columns(&keep);
    let l = m.clone().cholesky()?.l();
    let li = l.try_inverse()?;
    let c = &li * k * li.transpose();
    let c = (&c + c.transpose()) * 0.5;
    let e = c.symmetric_eigen();
    let mut modes: Vec<SystemMode> = (0..keep.len())
        .map(|j| {
            // φ = L⁻ᵀ y, M-normalized.
            let phi: DVector<f64> = li.transpose() * e.eigenvectors.column(j);
            let mphi = &m * &phi;
            let mut share = [0.0; 7];
            for (r, &i) in keep.iter().enumerate() {
                share[part_index(s.parts[i])] += phi[r] * mphi[r];
            }
            let w2 = e.eigenvalues[j];
            SystemMode {
                frequency_hz: w2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI),
                energy_share: share,
            }
        })
        .collect();
    modes.sort_by(|a, b| a.frequency_hz.total_cmp(&b.frequency_hz));
    Some(modes)
}

/// A mode met by an excitation order within a speed range.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Crossing {
    pub mode: usize,
    pub order: f64,
    /// Pinion speed at which order × speed is the mode's frequency, rpm.
    pub pinion_rpm: f64,
}

/// Where the order lines f = order · n/60 (n the pinion speed, rpm) cross
/// the modes' frequencies for n in (0, `max_rpm`]: n = 60 f / order.
pub fn campbell_crossings(modes: &[SystemMode], orders: &[f64], max_rpm: f64) -> Vec<Crossing> {
    let mut out = Vec::new();
    for (i, m) in modes.iter().enumerate() {
        for &o in orders {
            if o > 0.0 && m.frequency_hz > 0.0 {
                let rpm = 60.0 * m.frequency_hz / o;
                if rpm <= max_rpm {
                    out.push(Crossing {
                        mode: i,
                        order: o,
                        pinion_rpm: rpm,
                    });
                }
            }
        }
    }
    out.sort_by(|a, b| a.pinion_rpm.total_cmp(&b.pinion_rpm));
    out
}
