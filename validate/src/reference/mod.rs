//! The reference FE: both gear bodies meshed finely, in frictionless penalty
//! contact, solved by condensation onto the contact nodes — independent of
//! the reduced model it judges.
//!
//! - [`penalty`]: the penalty contact problem (active set, Newton);
//! - [`contact_surface`], [`contact_pairs`]: the flank surfaces and the
//!   node-to-surface pairs between them;
//! - [`body_compliance`] (full solves, the check) and [`path_compliance`]
//!   (forward solves on the contact nodes' factor paths): a body's
//!   condensed compliance;
//! - [`reference_root_stress`]: the fillets' stresses per load and position;
//! - [`reference_ltca`]: one position, all loads; [`reference_stage`]: the
//!   `validate reference` sweep with its cache, [`reference_blank_pair`] one
//!   blank pair of it.

pub mod body_compliance;
pub mod contact_pairs;
pub mod contact_surface;
pub mod path_compliance;
pub mod penalty;
pub mod position_cache;
pub mod reference_blank_pair;
pub mod reference_ltca;
pub mod reference_options;
pub mod reference_outputs;
pub mod reference_root_stress;
pub mod reference_stage;
pub mod reference_summary;
