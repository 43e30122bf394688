//! Preprocess: the flank stage's files (grids, UTCA, plots), gmsh tet10 meshes
//! of the gear bodies, and the FE stiffness files of the reduced model.
//!
//! Data flow: scene ([`geometry::scene`]) → [`flank_stage`] (flanks, UTCA) →
//! [`mesh_stage`] (`.msh` + manifest) → [`stiffness_stage`]
//! (`.stiffness.h5`, [`formats::stiffness_file`]); a gearbox scene's housing
//! [`housing_stage`] (`housing.h5`, [`formats::housing_file`]).

pub mod body_mesh;
pub mod field_convergence;
pub mod fillet_nodes;
pub mod flank_stage;
pub mod housing_mesh;
pub mod housing_stage;
pub mod influence;
pub mod mesh;
pub mod mesh_stage;
pub mod periodic_sectors;
pub mod root_stress;
pub mod sibling_reuse;
pub mod solve_paths;
pub mod stiffness_stage;
