//! A body clamped on some of its nodes, assembled and factored once: the one
//! place every caller (stiffness files, reference contact, line-load check)
//! gets its K = LLᵀ from.
//!
//! The clamped dofs are held at zero (all three components of every clamped
//! node); [`crate::assemble`] eliminates them, and the stiffness of the free
//! dofs is factored with a METIS fill-reducing ordering on the node graph.

use crate::cholesky::{Factor, Ordering};
use crate::{assemble, Dofs, FemError, Material, TetMesh};
use std::time::Instant;

/// The dofs of `nodes`, all three components (3 · node + component): a
/// clamped support.
pub fn clamp_nodes(nodes: &[usize]) -> Vec<usize> {
    nodes
        .iter()
        .flat_map(|&n| (0..3).map(move |c| 3 * n + c))
        .collect()
}

/// How the factor is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Factorization {
    /// faer's choice of simplicial or supernodal.
    Auto,
    /// Always supernodal (what [`crate::path_solve`] works on).
    Supernodal,
}

/// A clamped body: its free dofs and the Cholesky factor of its stiffness.
pub struct ClampedBody {
    pub dofs: Dofs,
    pub factor: Factor,
    /// Wall time of the assembly and of the factorization, s.
    pub assemble_s: f64,
    pub factor_s: f64,
}

impl ClampedBody {
    /// Assembles `mesh` of `material` with the `fixed` dofs held at zero
    /// (see [`clamp_nodes`]) and factors it.
    pub fn new(
        mesh: &TetMesh,
        material: &Material,
        fixed: &[usize],
        factorization: Factorization,
    ) -> Result<ClampedBody, FemError> {
        let t = Instant::now();
        let fixed: Vec<(usize, f64)> = fixed.iter().map(|&d| (d, 0.0)).collect();
        let dofs = Dofs::new(mesh, &fixed)?;
        let sys = assemble(mesh, material, &dofs)?;
        let assemble_s = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let node_of = dofs.node_of_free();
        let factor = match factorization {
            Factorization::Auto => Factor::new(&sys.matrix, &node_of, Ordering::Metis)?,
            Factorization::Supernodal => {
                Factor::new_supernodal(&sys.matrix, &node_of, Ordering::Metis)?
            }
        };
        Ok(ClampedBody {
            dofs,
            factor,
            assemble_s,
            factor_s: t.elapsed().as_secs_f64(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamped_node_holds_its_three_components() {
        assert_eq!(clamp_nodes(&[2, 5]), vec![6, 7, 8, 15, 16, 17]);
    }
}
