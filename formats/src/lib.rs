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
//! - [`memory_estimate`]: the size of a body's Cholesky factor from its
//!   degrees of freedom, to refuse before work what cannot fit;
//! - [`stiffness_sense`]: the physical sense of a stiffness file's numbers;
//! - [`summaries`]: the solver's stage summaries, shared by writer and readers;
//! - [`lumped_summary`]: the 8-DOF lumped run's summary;
//! - [`output`]: the one atomic write (temporary file + rename) every stage uses;
//! - [`result_set`]: a stage's output directory written as one set (lock,
//!   staging sibling, commit by rename, `run.json`);
//! - [`added_files`]: files a later command adds in place to a committed
//!   set (the studies beside the reference sweep), with their checksums;
//! - [`interrupt`]: Ctrl-C and SIGTERM remove what the run began and did
//!   not finish (staging directories, locks, temporary files);
//! - [`stop_point`]: the named phases of a run where the signal tests stop it.

pub mod added_files;
pub mod columns;
pub mod housing_file;
pub mod interrupt;
pub mod lumped_summary;
pub mod manifest;
pub mod memory_estimate;
pub mod output;
pub mod paths;
pub mod result_set;
pub mod root_stress;
pub mod sensitivity_summary;
pub mod stiffness_file;
pub mod stiffness_plan;
pub mod stiffness_sense;
pub mod stop_point;
pub mod summaries;
