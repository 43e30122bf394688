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
}
