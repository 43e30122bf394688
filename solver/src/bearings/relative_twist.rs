//! The small rigid displacements of the two members on their bearings as
//! the contact sees them: extra turning of each member about its own axis
//! and the four misalignments E, P, G, ΔΣ ([`geometry::misalignment`]).
//!
//! Fixed frame of the flank generation: origin at the pitch apex, pinion
//! axis a₁, wheel axis a₂ (both in the plane y = 0), ŷ = (0, 1, 0). A member
//! displaced by translation u and small rotation θ about the apex moves a
//! point x to x + u + θ × x. Only the pinion's pose relative to the wheel
//! enters the contact, to first order the twist
//!
//!   ω = θ₁ − θ₂,  t = u₁ − u₂.
//!
//! It splits uniquely (a₁, a₂, ŷ independent) into
//!
//!   ω = d (δq₁ a₁ + δq₂ a₂) + ΔΣ ŷ,
//!   t = P a₁ + E h ŷ − G a₂,
//!
//! with d the pinion's drive direction (±1, the table's
//! [`crate::multibody::mesh_table::TableSpec::direction`]: the pinion turns by d q₁
//! about a₁ and the wheel by −d q₂ about a₂, which the relative pose sees as
//! the pinion turning by d q₂ about a₂), h the tooth-trace sign of the
//! pinion's hand, and (E, P, G, ΔΣ) in m and rad with the signs of
//! [`geometry::misalignment::Misalignment`]: ΔΣ turns the pinion about ŷ,
//! P moves it along a₁, E along h ŷ, G moves the wheel along a₂ (the pinion
//! along −a₂ relative to it).

use nalgebra::{Matrix3, SMatrix, Vector3, Vector6};

/// Contact coordinates of a relative displacement: extra member rotations
/// (δq₁, δq₂) in the drive directions, rad, then E, P, G (m) and ΔΣ (rad).
pub type ContactCoordinates = Vector6<f64>;

/// The linear map from the members' small displacements to the contact
/// coordinates.
#[derive(Debug, Clone, Copy)]
pub struct TwistMap {
    /// Inverse of [d a₁ | d a₂ | ŷ]: ω ↦ (δq₁, δq₂, ΔΣ).
    rotation: Matrix3<f64>,
    /// Inverse of [a₁ | h ŷ | −a₂]: t ↦ (P, E, G).
    translation: Matrix3<f64>,
}

impl TwistMap {
    /// `a1`, `a2`: unit member axes; `direction`: the pinion's drive
    /// direction d; `hand`: the trace sign h of the pinion's hand.
    pub fn new(a1: Vector3<f64>, a2: Vector3<f64>, direction: f64, hand: f64) -> TwistMap {
        let y = Vector3::y();
        let r = Matrix3::from_columns(&[a1 * direction, a2 * direction, y]);
        let t = Matrix3::from_columns(&[a1, y * hand, -a2]);
        TwistMap {
            rotation: r
                .try_inverse()
                .expect("member axes and ŷ independent (shaft angle in (0, π))"),
            translation: t
                .try_inverse()
                .expect("member axes and ŷ independent (shaft angle in (0, π))"),
        }
    }

    /// (δq₁, δq₂, E, P, G, ΔΣ) of the relative twist (ω, t).
    pub fn split(&self, omega: &Vector3<f64>, t: &Vector3<f64>) -> ContactCoordinates {
        let r = self.rotation * omega;
        let p = self.translation * t;
        Vector6::new(r[0], r[1], p[1], p[0], p[2], r[2])
    }

    /// (δq₁, δq₂, E, P, G, ΔΣ) of the members' displacements [u₁; θ₁],
    /// [u₂; θ₂] about the apex.
    pub fn of_displacements(
        &self,
        pinion: &Vector6<f64>,
        wheel: &Vector6<f64>,
    ) -> ContactCoordinates {
        let d = pinion - wheel;
        self.split(
            &Vector3::new(d[3], d[4], d[5]),
            &Vector3::new(d[0], d[1], d[2]),
        )
    }

    /// The 6 × 10 matrix of the contact coordinates per the members'
    /// coordinates in their bearings' bases (`pinion`, `wheel`: 6 × 5, the
    /// columns [u; θ] of [`crate::bearings::support::Support::basis`]).
    pub fn matrix(
        &self,
        pinion: &SMatrix<f64, 6, 5>,
        wheel: &SMatrix<f64, 6, 5>,
    ) -> SMatrix<f64, 6, 10> {
        let mut out = SMatrix::<f64, 6, 10>::zeros();
        let zero = Vector6::zeros();
        for k in 0..5 {
            let col = pinion.column(k).into_owned();
            out.set_column(k, &self.of_displacements(&col, &zero));
            let col = wheel.column(k).into_owned();
            out.set_column(5 + k, &self.of_displacements(&zero, &col));
        }
        out
    }
}
