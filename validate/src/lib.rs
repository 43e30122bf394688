//! Validation: independent checks of each stage against reference methods,
//! and the reports that put them side by side.
//!
//! - The unloaded TCA (surface of roll angles, [`geometry::utca`]) against
//!   the direct geometric contact search ([`geometry::direct`]), and the
//!   unloaded TE against the white paper's 1 N·m value.
//! - The reference loaded TCA: both FE bodies in penalty contact
//!   ([`reference_ltca`], [`reference_stage`]), and its comparison with the
//!   reduced model ([`comparison`], [`figures`], [`report`]).

pub mod body_compliance;
pub mod comparison;
pub mod comparison_row;
pub mod contact_pairs;
pub mod contact_surface;
pub mod convergence;
pub mod differences;
pub mod figures;
pub mod line_load;
pub mod path_compliance;
pub mod penalty;
pub mod published;
pub mod reference_ltca;
pub mod reference_stage;
pub mod report;
pub mod tradeoff;
pub mod utca_check;
