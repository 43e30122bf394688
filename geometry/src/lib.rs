//! Geometry: design and scene files, face-milled spiral bevel flanks, ease-off,
//! unloaded tooth contact analysis (UTCA) with its surfaces of roll angles, the
//! blank's shape and the teeth in contact over a sweep.
//!
//! Data flow: design file → [`design::PairData`] → [`pair::PairGeometry`]
//! (generated flanks, ease-off) → [`utca::Utca`]. Nothing here meshes, solves
//! FE, reads HDF5 or plots: every stage builds on this crate.

pub mod contact_grid;
pub mod design;
pub mod design_file;
pub mod direct;
pub mod ease_off;
pub mod error;
pub mod flank;
pub mod gear_body;
pub mod generation;
pub mod housing_layout;
pub mod limits;
pub mod machine;
pub mod mate;
pub mod material;
pub mod minimize;
pub mod misalignment;
pub mod nominal_root_stress;
pub mod pair;
pub mod placement;
pub mod roughness;
pub mod scene;
pub mod scene_bearings;
pub mod scene_checks;
pub mod scene_contact_law;
pub mod scene_lumped;
pub mod scene_sensitivity;
pub mod scene_ste_dte;
pub mod teeth;
pub mod utca;

pub use material::Material;

/// Scalar type of the geometry kernels: `f64`, or a dual number for exact derivatives.
pub trait Scalar: num_dual::DualNum<Primitive = f64> + Copy {}
impl<T: num_dual::DualNum<Primitive = f64> + Copy> Scalar for T {}
