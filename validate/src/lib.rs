//! Validation: independent checks of each stage against reference methods,
//! and the report that puts them side by side. Three parts, apart:
//!
//! - [`reference`]: the reference FE (both bodies in penalty contact,
//!   condensed onto the contact nodes) and its `validate reference` stage;
//! - [`studies`]: the UTCA cross-check, mesh convergence, the line-load
//!   check and the run-time/error trade-off;
//! - [`report`]: the comparison with the reduced model and the published
//!   values, the figures and the report files (`validate report`).
//!
//! The modules are also re-exported at the crate root (`validate::reference_stage`, ...).

pub mod reference;
pub mod report;
pub mod studies;

pub use reference::{
    body_compliance, contact_pairs, contact_surface, path_compliance, penalty, reference_ltca,
    reference_stage,
};
pub use report::{comparison, comparison_row, differences, figures, published};
pub use studies::{
    asperity_resolution, convergence, line_load, mesh_stiffness, stage_tradeoffs, stress, tradeoff,
    utca_check,
};
