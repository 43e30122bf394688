//! The solver's stages: the only part of the crate that reads scenes,
//! opens result sets and writes files. Each `run` takes a scene, the mesh
//! folder and the output folder; [`context`] loads what they share (the
//! pair's geometry, the stiffness files checked against their manifest,
//! the pair compliance, the sweep).
//!
//! [`plan`] (`solver plan`), [`ltca`] (`solver ltca`), [`dynamic`] and
//! [`compliant`] (`solver dynamic`: rigid and compliant bearings),
//! [`lumped`] and [`lumped_order_map`] with [`lumped_plots`] (`solver
//! lumped`), [`sensitivity`] (`solver sensitivity`).

pub mod compliant;
pub mod context;
pub mod dynamic;
pub mod gearbox;
pub mod ltca;
pub mod lumped;
pub mod lumped_order_map;
pub mod lumped_plots;
pub mod lumped_run;
pub mod plan;
pub mod rattle;
pub mod runup;
pub mod sensitivity;
pub mod ste_dte;
pub mod trace;
