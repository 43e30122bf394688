//! The 8-degree-of-freedom lumped dynamic model of seeds 003 and 004
//! (bending, axial and torsional motion of both members on bearings),
//! driven by the mesh stiffness k(t) and static transmission error e(t)
//! of our own LTCA as Fourier series, with a meshing-impact pulse.
//!
//! [`model`] (matrices, direction cosines, sign conventions) →
//! [`excitation`] (Fourier series, impact) → [`integrate`] (adaptive
//! Dormand–Prince 5(4)); [`from_ltca`] and [`impact`] take k(t), e(t) and
//! the engagement from our LTCA, [`friction`] the sliding friction from its
//! load distribution, [`run`] starts a loaded run at static
//! equilibrium, [`response`] reduces it to RMS, peak-to-peak and spectra.

pub mod excitation;
pub mod friction;
pub mod from_ltca;
pub mod impact;
pub mod integrate;
pub mod model;
pub mod response;
pub mod revolution;
pub mod roughness;
pub mod run;

/// Errors of the lumped model.
#[derive(Debug, thiserror::Error)]
pub enum LumpedError {
    #[error("lumped model input: {0}")]
    Input(String),
    #[error("lumped model time integration failed: {0}")]
    Integration(String),
}
