//! Studies that check one stage against something outside it:
//!
//! - [`utca_check`]: the surface of roll angles against the direct contact search;
//! - [`convergence`]: the reference at three mesh levels, Richardson extrapolation;
//! - [`line_load`]: the stiffness files' global field + Weber–Banaschek
//!   against fine-mesh FE under a line load;
//! - [`stress`]: issue 28's stress matrix on cached stiffness files;
//! - [`tradeoff`]: the reduced model's error to the reference against its run time.

pub mod convergence;
pub mod line_load;
pub mod stress;
pub mod tradeoff;
pub mod utca_check;
