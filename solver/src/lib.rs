//! Solver: the FE-analytical gear contact element, the quasi-static loaded
//! tooth contact analysis (LTCA) and multibody time integration.
//!
//! Data flow: scene → flank pair and surface of roll angles (preprocess) →
//! [`slices`] (contact geometry per position) → [`compliance`] (stiffness
//! files interpolated to the slices) + [`weber_banaschek`] (line-contact
//! approach) → [`contact_problem`] (forces and loaded TE) → [`ltca`] (sweep)
//! → [`ltca_stage`] (files). [`plan`] lists the tooth pairs that can touch.
//! Multibody: [`mesh_table`] (the element as a conservative force element
//! between rigid bodies) → [`multibody`] (equations of motion, time
//! integration) → [`dynamic_stage`] (10 rpm and run-up files, with
//! [`spectrum`] for the bearing-force spectrogram). [`bearings`]: a shaft
//! on compliant bearings (reactions and the member's displacement under a
//! mesh force), and [`system_deflection`]: the quasi-static LTCA on the
//! pose the loaded bearings give.

pub mod backlash;
pub mod bearings;
pub mod compliance;
pub mod compliant_multibody;
pub mod compliant_stage;
pub mod contact_problem;
pub mod cpu_clock;
pub mod dynamic_stage;
pub mod edge_contact;
pub mod impact_law;
pub mod impact_table;
pub mod interp;
pub mod lag_shift;
pub mod load_run;
pub mod ltca;
pub mod ltca_stage;
pub mod lumped;
pub mod lumped_order_map;
pub mod lumped_plots;
pub mod lumped_roughness;
pub mod lumped_stage;
pub mod mesh_table;
pub mod multibody;
pub mod plan;
pub mod relative_twist;
pub mod runup_orders;
pub mod sensitivity_stage;
pub mod slices;
pub mod spectrum;
pub mod system_deflection;
pub mod time_step;
pub mod weber_banaschek;

/// Errors of the contact element and the LTCA.
#[derive(Debug, thiserror::Error)]
pub enum SolverError {
    #[error("no tooth pair can touch at this position")]
    NoContact,
    #[error("pinion torque {0} N·m: must be finite and ≥ 0 (coast-side loading needs the coast flanks' stiffness files)")]
    Torque(f64),
    #[error("singular contact system with {slices} active slices")]
    Singular { slices: usize },
    #[error("{what} did not converge in {iterations} iterations")]
    NotConverged { what: String, iterations: usize },
    #[error("multibody mesh table: {0}")]
    Table(String),
    #[error("{member} tooth {tooth} is loaded but the stiffness file holds only teeth {solved:?}: the run turns the gears past the rotation the meshes and stiffness files were planned for (the scene's [rotation] mesh cycles of this blank, and the multibody run-up or rattle); lengthen `rotation.mesh_cycles_<blank>`, then run `preprocess mesh` and `preprocess stiffness` again")]
    ToothNotSolved {
        member: String,
        tooth: usize,
        solved: Vec<usize>,
    },
}
