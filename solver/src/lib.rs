//! Solver: the FE-analytical gear contact element, loaded TCA and multibody
//! time integration (being built).
//!
//! Now: the contact-detection plan of a scene — for each pinion position,
//! which tooth pairs can touch on the loaded flank, from the active roll-angle
//! range of the surface of roll angles. The contact element will evaluate
//! slices only for these pairs.

pub mod plan;
