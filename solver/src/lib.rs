//! Solver: the FE-analytical gear contact element, the quasi-static loaded
//! tooth contact analysis (LTCA), multibody time integration and the
//! 8-DOF lumped model.
//!
//! The folders depend one way: [`stage`] → [`multibody`] → [`bearings`] →
//! [`ltca`] → [`element`]; [`stage`] → [`lumped`] → [`ltca`]; [`signal`]
//! and [`cpu_clock`] are leaves. Nothing below [`stage`] reads a scene file
//! or writes a result.
//!
//! - [`element`]: the contact element of one position (slices, compliance
//!   from the stiffness files, Weber–Banaschek, the contact problem, edge
//!   contact);
//! - [`ltca`]: the element over a sweep of positions;
//! - [`bearings`]: compliant supports and the LTCA on the pose they give;
//! - [`multibody`]: the element tabulated as a force element, the Hertz
//!   impact law, the equations of motion and their time stepping, on rigid
//!   or compliant bearings;
//! - [`lumped`]: the 8-DOF lumped model of seeds 003 and 004 driven by our
//!   LTCA;
//! - [`signal`]: spectrogram and run-up order analysis;
//! - [`stage`]: `solver plan | ltca | dynamic | lumped | sensitivity`, with
//!   [`stage::context`] loading what every stage shares.

pub mod bearings;
pub mod cpu_clock;
pub mod element;
pub mod gearbox;
pub mod ltca;
pub mod lumped;
pub mod multibody;
pub mod signal;
pub mod stage;

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
    #[error("at {torque_nm} N·m the compliant bearings move the members apart until no tooth pair can touch (after {iterations} iteration(s) of the bearing deflection the pinion has moved {pinion_um:.1} µm and the wheel {wheel_um:.1} µm): the bearings are too soft for this load; stiffen `[bearings]` or lower the torque")]
    BearingsSeparate {
        torque_nm: f64,
        iterations: usize,
        pinion_um: f64,
        wheel_um: f64,
    },
    #[error("{member} tooth {tooth} is loaded but the stiffness file holds only teeth {solved:?}: the run turns the gears past the rotation the meshes and stiffness files were planned for (the scene's [rotation] mesh cycles of this blank, and the multibody run-up or rattle); lengthen `rotation.mesh_cycles_<blank>`, then run `preprocess mesh` and `preprocess stiffness` again")]
    ToothNotSolved {
        member: String,
        tooth: usize,
        solved: Vec<usize>,
    },
}
