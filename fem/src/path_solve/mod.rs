//! Pruned triangular solves on a supernodal Cholesky factor L Lᵀ = P K Pᵀ.
//!
//! The compliance between two dofs is
//!
//!   C_ij = e_iᵀ K⁻¹ e_j = (L⁻¹ P e_i)ᵀ (L⁻¹ P e_j) = y_iᵀ y_j,
//!
//! and y_j = L⁻¹ P e_j is nonzero only on the supernodes of the elimination
//! tree's path from the supernode holding row (P e_j) to the root. So a
//! unit load needs only the forward half of a solve, and only along its path
//! ([`PathFactor::forward_units`]); a compliance is a dot product over the part
//! two paths share ([`gram`]). A displacement field u = K⁻¹ f is wanted at a
//! few dofs only: with z = L⁻¹ P f known on its paths, u at a dof needs the
//! backward solve x = L⁻ᵀ z on the path of that dof alone
//! ([`PathFactor::backward_at`]: a supernode's rows of x depend only on z there
//! and on x at its ancestors).
//!
//! A supernode's parent is the supernode holding the first row of its
//! off-diagonal pattern (faer does not expose the tree; its patterns give it).
//! Vectors on whole supernodes are [`PathVec`]s.
//!
//! Solves that start at a given set of dofs (a body's contact nodes) never
//! read the supernodes off their paths, so [`PathFactor`] keeps only those
//! of L's values (a supernodal factor of a gear body whose contact teeth are
//! a few of many keeps a fraction of them).

mod path_factor;
mod path_vec;
#[cfg(test)]
mod tests;
mod tree;

pub use path_factor::PathFactor;
pub use path_vec::{combine, gram, PathVec};
pub use tree::Tree;

/// No supernode: the parent of a root, the offset of one not kept.
const NONE: u32 = u32::MAX;
