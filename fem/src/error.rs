//! Typed errors of the FE core.

use thiserror::Error;

/// What can go wrong when building or solving an FE model.
#[derive(Debug, Error)]
pub enum FemError {
    /// An input value outside its valid range.
    #[error("{field} = {value} is invalid: {limit}")]
    Invalid {
        field: &'static str,
        value: String,
        limit: String,
    },
    /// An element whose Jacobian determinant is not positive at a quadrature point.
    #[error(
        "element {element} is inverted or degenerate (det J = {det_j:e} at a quadrature point)"
    )]
    InvertedElement { element: usize, det_j: f64 },
    /// The stiffness is not positive definite (a rigid-body mode is not restrained).
    #[error("stiffness matrix is not positive definite: {0}")]
    NotPositiveDefinite(String),
    /// METIS failed to order the graph.
    #[error("METIS ordering failed: {0}")]
    Ordering(String),
    /// faer failed (symbolic analysis or memory).
    #[error("sparse factorization failed: {0}")]
    Factorization(String),
    /// The factor would not fit in the memory this machine has free:
    /// refused after the symbolic analysis, before allocating it.
    #[error("the Cholesky factor of {dofs} dofs needs {needed_gb:.2} GB (factor and scratch), this machine has {available_gb:.2} GB available; use a coarser mesh level or a machine with more memory")]
    OutOfMemory {
        dofs: usize,
        needed_gb: f64,
        available_gb: f64,
    },
    /// An iterative eigen-solver did not converge within its steps.
    #[error("eigenvalue iteration did not converge: {0}")]
    NotConverged(String),
}
