//! Parallel assembly of the free-dof stiffness (lower triangle, CSC).
//!
//! Fixed degrees of freedom are eliminated: the returned matrix is K_ff and
//! the lift vector is −K_fc u_c, so that K_ff u_f = f_f + lift.

use crate::{tet10, FemError, Material, TetMesh};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use rayon::prelude::*;

/// Numbering of the free degrees of freedom (dof = 3 · node + component).
#[derive(Debug, Clone)]
pub struct Dofs {
    /// Free index of each global dof, or `None` if fixed.
    free: Vec<Option<usize>>,
    /// Prescribed value of each global dof (used where fixed).
    value: Vec<f64>,
    n_free: usize,
}

impl Dofs {
    /// All dofs free except `fixed` (global dof, prescribed value) and the
    /// dofs of nodes that belong to no element (held at zero).
    pub fn new(mesh: &TetMesh, fixed: &[(usize, f64)]) -> Result<Dofs, FemError> {
        let n = 3 * mesh.nodes.len();
        let mut is_fixed = vec![true; n];
        for t in &mesh.tets {
            for &i in t {
                is_fixed[3 * i..3 * i + 3].fill(false);
            }
        }
        let mut value = vec![0.0; n];
        for &(d, v) in fixed {
            if d >= n {
                return Err(FemError::Invalid {
                    field: "fixed dof",
                    value: d.to_string(),
                    limit: format!("must be < 3 × nodes = {n}"),
                });
            }
            is_fixed[d] = true;
            value[d] = v;
        }
        let mut free = vec![None; n];
        let mut n_free = 0;
        for d in 0..n {
            if !is_fixed[d] {
                free[d] = Some(n_free);
                n_free += 1;
            }
        }
        Ok(Dofs {
            free,
            value,
            n_free,
        })
    }

    /// Number of free dofs.
    pub fn n_free(&self) -> usize {
        self.n_free
    }

    /// Free index of global dof `d`.
    pub fn free_index(&self, d: usize) -> Option<usize> {
        self.free[d]
    }

    /// Node of each free dof (nondecreasing), as [`crate::Factor::new`] takes it.
    pub fn node_of_free(&self) -> Vec<usize> {
        (0..self.free.len())
            .filter(|&d| self.free[d].is_some())
            .map(|d| d / 3)
            .collect()
    }

    /// Full displacement vector (3 per node) from the free solution.
    pub fn expand(&self, u_free: &[f64]) -> Vec<f64> {
        self.free
            .iter()
            .zip(&self.value)
            .map(|(f, v)| f.map_or(*v, |i| u_free[i]))
            .collect()
    }

    /// Gathers a full-length vector (3 per node) onto the free dofs.
    pub fn restrict(&self, full: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.n_free];
        for (d, f) in self.free.iter().enumerate() {
            if let Some(i) = f {
                out[*i] = full[d];
            }
        }
        out
    }
}

/// The assembled system.
pub struct Assembled {
    /// K_ff, lower triangle (row ≥ column), CSC.
    pub matrix: SparseColMat<usize, f64>,
    /// −K_fc u_c on the free dofs.
    pub lift: Vec<f64>,
}

/// Elements per parallel chunk (the element matrices of one chunk are held
/// in memory before they are scattered).
const CHUNK: usize = 2048;

/// Assembles K_ff (lower triangle) and the lift of the prescribed values.
pub fn assemble(mesh: &TetMesh, material: &Material, dofs: &Dofs) -> Result<Assembled, FemError> {
    material.validate()?;
    let (lambda, mu) = material.lame();
    assemble_with(mesh, dofs, |_, x| tet10::stiffness(x, lambda, mu))
}

/// [`assemble`] with the element matrices of `kernel` (element index, node
/// coordinates → 30 × 30 row-major, or `Err(det J)` for an inverted
/// element): for models whose elements are not all integrated whole
/// ([`crate::cut_cell`]).
pub fn assemble_with<F>(mesh: &TetMesh, dofs: &Dofs, kernel: F) -> Result<Assembled, FemError>
where
    F: Fn(usize, &[[f64; 3]; 10]) -> Result<[f64; 900], f64> + Sync,
{
    mesh.validate()?;
    let (col_ptr, row_idx) = pattern(mesh, dofs);
    let mut values = vec![0.0; row_idx.len()];
    let mut lift = vec![0.0; dofs.n_free];
    for (c, chunk) in mesh.tets.chunks(CHUNK).enumerate() {
        let ks: Vec<Result<[f64; 900], FemError>> = chunk
            .par_iter()
            .enumerate()
            .map(|(k, t)| {
                let x = t.map(|i| mesh.nodes[i]);
                let element = c * CHUNK + k;
                kernel(element, &x).map_err(|det_j| FemError::InvertedElement { element, det_j })
            })
            .collect();
        for (t, k) in chunk.iter().zip(ks) {
            let k = k?;
            let g: [usize; 30] = std::array::from_fn(|l| 3 * t[l / 3] + l % 3);
            for (lc, &gc) in g.iter().enumerate() {
                match dofs.free[gc] {
                    Some(jc) => {
                        let rows = &row_idx[col_ptr[jc]..col_ptr[jc + 1]];
                        for (lr, &gr) in g.iter().enumerate() {
                            if let Some(ir) = dofs.free[gr] {
                                if ir >= jc {
                                    let p = rows.binary_search(&ir).expect("pattern");
                                    values[col_ptr[jc] + p] += k[lr * 30 + lc];
                                }
                            }
                        }
                    }
                    None => {
                        let u = dofs.value[gc];
                        if u != 0.0 {
                            for (lr, &gr) in g.iter().enumerate() {
                                if let Some(ir) = dofs.free[gr] {
                                    lift[ir] -= k[lr * 30 + lc] * u;
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    let n = dofs.n_free;
    let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
    Ok(Assembled {
        matrix: SparseColMat::new(symbolic, values),
        lift,
    })
}

/// Lower-triangle CSC pattern of K_ff from the node adjacency.
fn pattern(mesh: &TetMesh, dofs: &Dofs) -> (Vec<usize>, Vec<usize>) {
    let adj = mesh.node_adjacency();
    let mut col_ptr = Vec::with_capacity(dofs.n_free + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0);
    for (node, nbrs) in adj.iter().enumerate() {
        for c in 0..3 {
            let Some(j) = dofs.free[3 * node + c] else {
                continue;
            };
            for &m in nbrs {
                for r in 0..3 {
                    if let Some(i) = dofs.free[3 * m as usize + r] {
                        if i >= j {
                            row_idx.push(i);
                        }
                    }
                }
            }
            col_ptr.push(row_idx.len());
        }
    }
    (col_ptr, row_idx)
}

/// y = K x for the full symmetric matrix stored as its lower triangle.
pub fn sym_lower_mul(k: &SparseColMat<usize, f64>, x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; x.len()];
    let (cp, ri, v) = (k.col_ptr(), k.row_idx(), k.val());
    for j in 0..k.ncols() {
        for p in cp[j]..cp[j + 1] {
            let i = ri[p];
            y[i] += v[p] * x[j];
            if i != j {
                y[j] += v[p] * x[i];
            }
        }
    }
    y
}

/// Assembles the consistent mass M_ff (lower triangle, same pattern as
/// [`assemble`]'s K_ff for the same `dofs`) of density ρ (kg/m³).
pub fn assemble_mass(
    mesh: &TetMesh,
    density: f64,
    dofs: &Dofs,
) -> Result<SparseColMat<usize, f64>, FemError> {
    if !(density > 0.0 && density.is_finite()) {
        return Err(FemError::Invalid {
            field: "density_kg_m3",
            value: density.to_string(),
            limit: "must be finite and > 0".into(),
        });
    }
    Ok(assemble_with(mesh, dofs, |_, x| tet10::mass(x, density))?.matrix)
}
