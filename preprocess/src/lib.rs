//! Preprocess: design and scene files, face-milled spiral bevel flanks and
//! unloaded tooth contact analysis (UTCA).
//!
//! Data flow: design file → [`design::PairData`] → [`pair::PairGeometry`]
//! (generated flanks, ease-off) → [`utca::Utca`] → outputs.

pub mod body_mesh;
pub mod design;
pub mod direct;
pub mod ease_off;
pub mod error;
pub mod field_convergence;
pub mod flank;
pub mod flank_stage;
pub mod gear_body;
pub mod generation;
pub mod influence;
pub mod mesh;
pub mod mesh_stage;
pub mod minimize;
pub mod output;
pub mod pair;
pub mod periodic_sectors;
pub mod plots;
pub mod scene;
pub mod stiffness_file;
pub mod stiffness_stage;
pub mod utca;

/// Scalar type of the geometry kernels: `f64`, or a dual number for exact derivatives.
pub trait Scalar: num_dual::DualNum<Primitive = f64> + Copy {}
impl<T: num_dual::DualNum<Primitive = f64> + Copy> Scalar for T {}
