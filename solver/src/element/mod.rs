//! The FE-analytical contact element: what happens between one loaded
//! tooth pair at one position, independent of how the position is reached.
//!
//! [`slices`] (the potential contact of each tooth pair cut into slices
//! across the face width) → [`compliance`] (C = C_pinion + C_wheel from the
//! stiffness files' global fields, [`interp`] on their flank grids) +
//! [`weber_banaschek`] (the local, near-contact approach of a line
//! contact) → [`contact_problem`] (slice forces and loaded TE);
//! [`edge_cut`] is the local approach of a slice whose strip a tip edge
//! cuts; [`edge_contact`] tells when a slice's contact reaches a flank edge;
//! [`root_stress`] turns the slice forces into the loaded teeth's fillet
//! stresses.

pub mod compliance;
pub mod contact_problem;
pub mod edge_contact;
pub mod edge_cut;
pub mod interp;
pub mod root_stress;
pub mod slices;
pub mod weber_banaschek;
