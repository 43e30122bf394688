//! Penalty contact between linear elastic bodies, condensed exactly onto the
//! contact nodes.
//!
//! Constraint c ties a slave node to the point of a master face it projects
//! on, along the master's outward normal n. Its gap (m) is
//!
//!   g_c = g⁰_c + ρ_c ψ + Σ_b B_cb u_b,   B_cb u_b = Σ_i v_ciᵀ u_i,
//!
//! with v = +n on the slave node and −Nᵢ n on the master face's nodes (Nᵢ
//! its shape functions at the projection), ψ a rigid coordinate (the
//! pinion's rotation; a translation in tests) and ρ_c = ∂g_c/∂ψ. The penalty
//! force is λ_c = k_c ⟨−g_c⟩; it acts on body b as B_cbᵀ λ_c, so that with
//! each body's compliance C_b = K_b⁻¹ (supports clamped)
//!
//!   g = g⁰ + ρ ψ + W λ,   W = Σ_b B_b C_b B_bᵀ,
//!
//! and the rigid coordinate is in equilibrium with its load Q when
//! Σ_c λ_c (−ρ_c) = Q. On the active set A (penetrating constraints)
//! g_A = −λ_A / k_A, so
//!
//!   (W_AA + K_A⁻¹) λ_A + ρ_A ψ = −g⁰_A,   ρ_Aᵀ λ_A = −Q,
//!
//! solved through the Cholesky factor of M = W_AA + K_A⁻¹:
//! ψ = (Q − ρᵀM⁻¹g⁰)/(ρᵀM⁻¹ρ), λ = −M⁻¹(g⁰ + ρψ). The active set is updated
//! (drop tensile constraints, add penetrating ones) until neither is left.
//! This is the minimum of the convex, piecewise quadratic potential energy,
//! so the condensation gives the same answer as the assembled FE system.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use rayon::prelude::*;
use thiserror::Error;

/// Errors of the contact solve.
#[derive(Debug, Error)]
pub enum ContactError {
    #[error("no constraint can close under the load (every ∂g/∂ψ ≥ 0)")]
    NothingCloses,
    #[error("active-set iteration did not settle in {0} iterations")]
    NotConverged(usize),
    #[error("condensed contact matrix is not positive definite ({0} active constraints)")]
    NotPositiveDefinite(usize),
    #[error("compliance at node {node} is not available (column not computed, or node outside the kept responses)")]
    MissingColumn { node: usize },
    #[error("FE: {0}")]
    Fem(#[from] fem::FemError),
}

/// One node's share of a constraint: gap change = dir · u(node).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Term {
    pub body: usize,
    pub node: usize,
    pub dir: [f64; 3],
}

/// A slave node against a master face.
#[derive(Debug, Clone, PartialEq)]
pub struct Constraint {
    pub terms: Vec<Term>,
    /// Gap with the bodies undeformed and ψ = 0, m (negative = penetration).
    pub gap0: f64,
    /// ∂g/∂ψ (m per unit of ψ).
    pub rigid: f64,
    /// Penalty stiffness k_c = ε A_c, N/m.
    pub stiffness: f64,
}

/// A body's compliance between nodes: C_ij = ∂u_i/∂f_j (3 × 3 blocks).
pub trait Compliance {
    /// C_ij (row: response at i, column: load at j), m/N. Errors if the
    /// column of `j` or the row of `i` is not available.
    fn block(&self, i: usize, j: usize) -> Result<[[f64; 3]; 3], ContactError>;
    /// Where the responses at `nodes` are stored (for [`Compliance::response`]).
    fn slots(&self, nodes: &[usize]) -> Result<Vec<usize>, ContactError>;
    /// Displacements at the nodes behind `slots` under a unit load along
    /// `dir` at node `j`, m/N.
    fn response(
        &self,
        j: usize,
        dir: [f64; 3],
        slots: &[usize],
    ) -> Result<Vec<[f64; 3]>, ContactError>;
}

/// The solution of one load.
#[derive(Debug, Clone)]
pub struct Solution {
    /// Penalty force of each constraint, N (≥ 0).
    pub force: Vec<f64>,
    /// Gap of each constraint after loading, m.
    pub gap: Vec<f64>,
    /// Rigid coordinate ψ.
    pub psi: f64,
    pub active: Vec<bool>,
    /// Active-set updates.
    pub iterations: usize,
}

/// W = Σ_b B_b C_b B_bᵀ for the listed rows × columns of `constraints`
/// (row-major rows.len() × cols.len()). For each body and column
/// constraint, its load's displacement field at the row constraints' nodes
/// is summed from the node columns, then projected on each row.
pub fn condensed_matrix(
    constraints: &[Constraint],
    rows: &[usize],
    cols: &[usize],
    bodies: &[&(dyn Compliance + Sync)],
) -> Result<Vec<f64>, ContactError> {
    let (nr, nc) = (rows.len(), cols.len());
    let mut w = vec![0.0; nr * nc];
    for (b, body) in bodies.iter().enumerate() {
        let mut at: Vec<usize> = rows
            .iter()
            .flat_map(|&r| constraints[r].terms.iter())
            .filter(|t| t.body == b)
            .map(|t| t.node)
            .collect();
        at.sort_unstable();
        at.dedup();
        if at.is_empty() {
            continue;
        }
        let slots = body.slots(&at)?;
        let pos = |n: usize| at.binary_search(&n).expect("row node collected above");
        let row_terms: Vec<Vec<(usize, [f64; 3])>> = rows
            .iter()
            .map(|&r| {
                constraints[r]
                    .terms
                    .iter()
                    .filter(|t| t.body == b)
                    .map(|t| (pos(t.node), t.dir))
                    .collect()
            })
            .collect();
        let columns: Result<Vec<Vec<f64>>, ContactError> = cols
            .par_iter()
            .map(|&c| {
                let mut u = vec![[0.0; 3]; at.len()];
                for t in constraints[c].terms.iter().filter(|t| t.body == b) {
                    for (acc, v) in u.iter_mut().zip(body.response(t.node, t.dir, &slots)?) {
                        for k in 0..3 {
                            acc[k] += v[k];
                        }
                    }
                }
                Ok(row_terms
                    .iter()
                    .map(|rt| {
                        rt.iter()
                            .map(|(p, d)| d[0] * u[*p][0] + d[1] * u[*p][1] + d[2] * u[*p][2])
                            .sum()
                    })
                    .collect())
            })
            .collect();
        for (k, col) in columns?.into_iter().enumerate() {
            for (r, v) in col.into_iter().enumerate() {
                w[r * nc + k] += v;
            }
        }
    }
    Ok(w)
}

/// Gaps below −this are penetrations, forces below −this × k are tensile, m.
const GAP_TOL: f64 = 1e-14;
const MAX_ITERATIONS: usize = 200;

/// Solves the penalty contact of `constraints` under the load `q` on the
/// rigid coordinate. `w` is the full condensed matrix (row-major m × m);
/// `warm` a starting active set.
pub fn solve(
    constraints: &[Constraint],
    w: &[f64],
    q: f64,
    warm: Option<&[bool]>,
) -> Result<Solution, ContactError> {
    let m = constraints.len();
    let mut active: Vec<bool> = match warm {
        Some(a) if a.len() == m && a.iter().any(|&x| x) => a.to_vec(),
        _ => {
            // The first constraint to close as ψ grows.
            let first = (0..m)
                .filter(|&c| constraints[c].rigid < 0.0)
                .min_by(|&a, &b| {
                    let ta = constraints[a].gap0 / -constraints[a].rigid;
                    let tb = constraints[b].gap0 / -constraints[b].rigid;
                    ta.total_cmp(&tb)
                })
                .ok_or(ContactError::NothingCloses)?;
            let mut v = vec![false; m];
            v[first] = true;
            v
        }
    };
    for it in 0..MAX_ITERATIONS {
        let idx: Vec<usize> = (0..m).filter(|&c| active[c]).collect();
        let (lambda_a, psi) = solve_active(constraints, w, &idx, q)?;
        let mut force = vec![0.0; m];
        for (k, &c) in idx.iter().enumerate() {
            force[c] = lambda_a[k];
        }
        let gap: Vec<f64> = (0..m)
            .into_par_iter()
            .map(|c| {
                let row = &w[c * m..(c + 1) * m];
                constraints[c].gap0
                    + constraints[c].rigid * psi
                    + idx.iter().map(|&d| row[d] * force[d]).sum::<f64>()
            })
            .collect();
        let mut changed = false;
        for c in 0..m {
            if active[c] && force[c] < -GAP_TOL * constraints[c].stiffness {
                active[c] = false;
                changed = true;
            } else if !active[c] && gap[c] < -GAP_TOL {
                active[c] = true;
                changed = true;
            }
        }
        if !active.iter().any(|&a| a) {
            // Everything dropped: restart from the deepest penetration.
            let deepest = (0..m)
                .min_by(|&a, &b| gap[a].total_cmp(&gap[b]))
                .unwrap_or(0);
            active[deepest] = true;
        }
        if !changed {
            for f in &mut force {
                *f = f.max(0.0);
            }
            return Ok(Solution {
                force,
                gap,
                psi,
                active,
                iterations: it,
            });
        }
    }
    Err(ContactError::NotConverged(MAX_ITERATIONS))
}

/// λ_A and ψ of the active set `idx`.
fn solve_active(
    constraints: &[Constraint],
    w: &[f64],
    idx: &[usize],
    q: f64,
) -> Result<(Vec<f64>, f64), ContactError> {
    let m = constraints.len();
    let n = idx.len();
    let mm = Mat::<f64>::from_fn(n, n, |i, j| {
        let (a, b) = (idx[i], idx[j]);
        w[a * m + b]
            + if i == j {
                1.0 / constraints[a].stiffness
            } else {
                0.0
            }
    });
    let llt = mm
        .llt(Side::Lower)
        .map_err(|_| ContactError::NotPositiveDefinite(n))?;
    let g0 = Mat::<f64>::from_fn(n, 2, |i, j| {
        let c = &constraints[idx[i]];
        if j == 0 {
            c.gap0
        } else {
            c.rigid
        }
    });
    let x = llt.solve(&g0);
    let rho: Vec<f64> = idx.iter().map(|&c| constraints[c].rigid).collect();
    let rx: f64 = (0..n).map(|i| rho[i] * x[(i, 0)]).sum();
    let ry: f64 = (0..n).map(|i| rho[i] * x[(i, 1)]).sum();
    if ry <= 0.0 {
        return Err(ContactError::NothingCloses);
    }
    let psi = (q - rx) / ry;
    let lambda = (0..n).map(|i| -(x[(i, 0)] + psi * x[(i, 1)])).collect();
    Ok((lambda, psi))
}

/// Σ_c λ_c (−ρ_c): the load the contact forces carry on the rigid coordinate.
pub fn carried_load(constraints: &[Constraint], force: &[f64]) -> f64 {
    constraints
        .iter()
        .zip(force)
        .map(|(c, f)| -c.rigid * f)
        .sum()
}

/// Dense compliance of a small body, for tests and small models: the full
/// inverse of its stiffness, 3 rows per node (fixed dofs give zero rows).
pub struct DenseCompliance {
    pub n_nodes: usize,
    /// Row-major (3 n) × (3 n).
    pub c: Vec<f64>,
}

impl Compliance for DenseCompliance {
    fn block(&self, i: usize, j: usize) -> Result<[[f64; 3]; 3], ContactError> {
        let n = 3 * self.n_nodes;
        let mut m = [[0.0; 3]; 3];
        for (a, row) in m.iter_mut().enumerate() {
            for (b, v) in row.iter_mut().enumerate() {
                *v = self.c[(3 * i + a) * n + 3 * j + b];
            }
        }
        Ok(m)
    }

    fn slots(&self, nodes: &[usize]) -> Result<Vec<usize>, ContactError> {
        Ok(nodes.to_vec())
    }

    fn response(
        &self,
        j: usize,
        dir: [f64; 3],
        slots: &[usize],
    ) -> Result<Vec<[f64; 3]>, ContactError> {
        Ok(slots
            .iter()
            .map(|&i| {
                let m = self.block(i, j).expect("dense compliance has every block");
                [0, 1, 2].map(|a| m[a][0] * dir[0] + m[a][1] * dir[1] + m[a][2] * dir[2])
            })
            .collect())
    }
}

/// The normal contact force on each node of `body` (N, positive pressing
/// into the body): Σ_c λ_c v_ci · ν_i, with ν_i the inward unit normal of the
/// body at node i (body frame) from `inward`.
pub fn nodal_normal_forces(
    constraints: &[Constraint],
    force: &[f64],
    body: usize,
    inward: &std::collections::HashMap<usize, [f64; 3]>,
) -> std::collections::HashMap<usize, f64> {
    let mut out = std::collections::HashMap::new();
    for (c, &f) in constraints.iter().zip(force) {
        if f == 0.0 {
            continue;
        }
        for t in c.terms.iter().filter(|t| t.body == body) {
            if let Some(nu) = inward.get(&t.node) {
                let v = f * (t.dir[0] * nu[0] + t.dir[1] * nu[1] + t.dir[2] * nu[2]);
                *out.entry(t.node).or_insert(0.0) += v;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two unit springs (compliance 1 each, independent) under a rigid
    /// plate: the load splits equally, ψ = gap + load/2·(1 + 1/k).
    #[test]
    fn two_equal_springs_share_the_load_equally() {
        let c = DenseCompliance {
            n_nodes: 2,
            c: {
                let mut v = vec![0.0; 36];
                for d in 0..6 {
                    v[d * 6 + d] = 1.0;
                }
                v
            },
        };
        let k = 1e3;
        let con = |node: usize, g: f64| Constraint {
            terms: vec![Term {
                body: 0,
                node,
                dir: [0.0, 0.0, 1.0],
            }],
            gap0: g,
            rigid: -1.0,
            stiffness: k,
        };
        let cs = vec![con(0, 0.1), con(1, 0.1), con(0, 5.0)];
        let all: Vec<usize> = (0..3).collect();
        let w = condensed_matrix(&cs, &all, &all, &[&c]).unwrap();
        let s = solve(&cs, &w, 2.0, None).unwrap();
        assert!((s.force[0] - 1.0).abs() < 1e-12 && (s.force[1] - 1.0).abs() < 1e-12);
        assert_eq!(s.force[2], 0.0);
        assert!((s.psi - (0.1 + 1.0 + 1.0 / k)).abs() < 1e-12);
        assert!((carried_load(&cs, &s.force) - 2.0).abs() < 1e-12);
    }
}
