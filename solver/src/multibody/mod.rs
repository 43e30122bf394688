//! Multibody time integration of the gear pair with the contact element as
//! its force element.
//!
//! [`mesh_table`] (the element tabulated over rotation and lag: a
//! conservative force element between rigid bodies; [`impact_law`] and
//! [`impact_table`] the Hertz impact law of general-purpose codes in the
//! same form; [`backlash`] both flank sides across the backlash) →
//! [`model`] (equations of motion on rigid bearings) → [`time_step`] (the
//! implicit one-step schemes with step control). [`compliant`] is the model
//! on compliant bearings, with [`lag_shift`] the unloaded TE's shift with
//! the misalignments; [`load_run`] the imposed-speed load run of seeds 001
//! and 002.

pub mod backlash;
pub mod compliant;
pub mod impact_law;
pub mod impact_table;
pub mod lag_shift;
pub mod load_run;
pub mod mesh_table;
pub mod model;
pub mod time_step;
