//! Compliant supports: [`support`] (a member's shaft on compliant bearings:
//! reactions and displacement under a mesh force), [`relative_twist`] (the
//! two members' displacements as the contact sees them: extra rotation and
//! E, P, G, ΔΣ) and [`system_deflection`] (the quasi-static LTCA on the pose
//! the loaded bearings give); [`timoshenko`] and [`flexible_shaft`] (a
//! shaft as Timoshenko beam elements on its bearings, condensed onto the
//! gear's seat, which a [`support::Support`] can stand on instead of a
//! rigid shaft).

pub mod flexible_shaft;
pub mod relative_twist;
pub mod support;
pub mod system_deflection;
pub mod timoshenko;
