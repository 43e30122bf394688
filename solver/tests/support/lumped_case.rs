//! A representative 8-DOF model for the lumped-model tests: seed 004's
//! 23/86 pair (δ₂ = 75.027°, αₙ = βₘ = 25°, left-hand wheel), levers
//! rᵢ = r_mᵢ cos αₙ cos β with mean pitch radii 40.07 / 149.8 mm, masses and
//! moments of solid discs of about its size, bearings of 0.5–0.9 GN/m.

#![allow(dead_code)]

use solver::lumped::model::{direction_cosines, Member, Model, WheelHand};

/// Mean mesh stiffness of the case, N/m (seed 004's Table 1 value).
pub const K_MEAN: f64 = 3.5e8;
/// Seed 004's mesh frequency, Hz.
pub const MESH_HZ: f64 = 2260.0;

pub fn model() -> Model {
    let c = 25f64.to_radians().cos();
    Model {
        members: [
            Member {
                mass_kg: 1.5,
                inertia_kgm2: 1.2e-3,
                bearing_stiffness_n_per_m: [8e8, 5e8, 5.5e8],
                bearing_damping_ns_per_m: [0.0; 3],
            },
            Member {
                mass_kg: 8.0,
                inertia_kgm2: 9.0e-2,
                bearing_stiffness_n_per_m: [6e8, 9e8, 7e8],
                bearing_damping_ns_per_m: [0.0; 3],
            },
        ],
        direction: direction_cosines(
            25f64.to_radians(),
            25f64.to_radians(),
            75.027f64.to_radians(),
            WheelHand::Left,
            geometry::generation::Side::Drive,
        ),
        levers_m: [0.04007 * c * c, 0.1498 * c * c],
        mesh_damping_ns_per_m: 0.0,
        pinion_torque_nm: 0.0,
    }
}
