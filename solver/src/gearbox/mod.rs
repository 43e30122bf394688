//! A flexible gearbox: the gear pair's contact element on a linear
//! structure of shafts (Timoshenko beam elements with mass), bearings and
//! a housing reduced onto its bearing seats.
//!
//! [`structure`] assembles M, C, K over the contact element's coordinates
//! and the structure's own; [`system_modes`] gives the loaded gearbox's
//! natural modes and where the excitation orders meet them.

pub mod dynamics;
pub mod structure;
pub mod system_modes;

pub use structure::{
    assemble, BearingLink, GearboxError, GearboxStructure, Housing, MemberParts, Part,
};
