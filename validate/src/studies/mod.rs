//! Studies that check one stage against something outside it:
//!
//! - [`utca_check`]: the surface of roll angles against the direct contact search;
//! - [`convergence`]: the reference at three mesh levels, Richardson extrapolation;
//! - [`line_load`]: the stiffness files' global field + Weber–Banaschek
//!   against fine-mesh FE under a line load;
//! - [`stress`]: the stress matrix on cached stiffness files;
//! - [`tradeoff`]: the reduced model's error to the reference against its run time;
//! - [`stage_tradeoffs`]: run time against error for every stage (one
//!   module per stage, `tradeoff_*`, the shared point type in
//!   [`tradeoff_stage`], other contact grids' scenes in [`grid_scenes`]).

pub mod asperity_resolution;
pub mod calibration;
pub mod convergence;
pub mod grid_convergence;
pub mod grid_scenes;
pub mod line_load;
pub mod mesh_stiffness;
pub mod stage_tradeoffs;
pub mod stress;
pub mod tradeoff;
pub mod tradeoff_fields;
pub mod tradeoff_ltca;
pub mod tradeoff_multibody;
pub mod tradeoff_reference;
pub mod tradeoff_stage;
pub mod tradeoff_utca;
pub mod utca_check;
