//! The files between the stages, one typed format each, shared by the stage
//! that writes it and the stages that read it:
//!
//! - [`columns`]: CSV column names, shared by writers and readers;
//! - [`paths`]: the one rule for file names in a mesh folder;
//! - [`manifest`]: a mesh folder's manifest (mesh inputs, hashes, mass
//!   properties, stiffness files);
//! - [`stiffness_file`]: the HDF5 stiffness files (schema, config, input hash);
//! - [`stiffness_plan`]: what a scene asks of a stiffness file, and the
//!   readers' check of a file against it;
//! - [`summaries`]: the solver's stage summaries, shared by writer and readers;
//! - [`output`]: the one atomic write (temporary file + rename) every stage uses.

pub mod columns;
pub mod manifest;
pub mod output;
pub mod paths;
pub mod stiffness_file;
pub mod stiffness_plan;
pub mod summaries;
