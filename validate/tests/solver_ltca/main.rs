//! The contact element and the quasi-static LTCA on the white-paper pair with
//! FE influence fields computed here on coarse meshes (6 × 10 elements per
//! refined flank, both members, standard blanks): the unloaded limit against
//! the UTCA, torque balance and complementarity, slice convergence, and the
//! assembled compliance (`ltca`); the element as the multibody force element
//! (`multibody`); the mesh forces, sliding and friction (`forces`).
//!
//! One test binary in several files: the fixture's FE fields (meshing and
//! influence solves of both members) are computed once for all of them.

#[path = "../fe_fixtures/mod.rs"]
mod fe_fixtures;
use fe_fixtures as common;

mod fixture;
mod forces;
mod ltca;
mod multibody;
