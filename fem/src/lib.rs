//! Linear elasticity with quadratic (10-node) tetrahedra.
//!
//! Data flows one way: a [`TetMesh`] and a [`Material`] go into
//! [`assembly::assemble`], which returns the stiffness of the free degrees of
//! freedom (fixed ones are eliminated); [`cholesky::Factor`] factors it once
//! and solves many right-hand sides. Element kernels ([`tet10`], [`tri6`]) are
//! small pure functions with their formulas in the doc comments.
//!
//! Node order is gmsh's: tetrahedron vertices 0–3, then mid-edge nodes on the
//! edges (0,1), (1,2), (2,0), (3,0), (3,2), (3,1); triangle vertices 0–2, then
//! (0,1), (1,2), (2,0).

pub mod assembly;
pub mod cholesky;
pub mod clamped;
pub mod craig_bampton;
pub mod cut_cell;
pub mod error;
pub mod material;
pub mod mesh;
pub mod modes;
pub mod ordering;
pub mod path_solve;
pub mod stress;
pub mod structured;
pub mod tet10;
pub mod tri6;

pub use assembly::{assemble, assemble_with, Assembled, Dofs};
pub use cholesky::Factor;
pub use clamped::{clamp_nodes, ClampedBody, Factorization};
pub use error::FemError;
pub use material::Material;
pub use mesh::TetMesh;
