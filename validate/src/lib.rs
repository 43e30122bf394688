//! Validation: independent checks of each stage against reference methods,
//! and the report that puts them side by side. Three parts, apart:
//!
//! - [`reference`]: the reference FE (both bodies in penalty contact,
//!   condensed onto the contact nodes) and its `validate reference` stage;
//! - [`studies`]: the UTCA cross-check, mesh convergence, the line-load
//!   check and the run-time/error trade-off;
//! - [`deck`]: the reference as a CalculiX / Abaqus input deck, and a
//!   CalculiX run of it (the independent check of the reference);
//! - [`report`]: the comparison with the reduced model and the published
//!   values, the figures and the report files (`validate report`).

pub mod deck;
pub mod reference;
pub mod report;
pub mod studies;
