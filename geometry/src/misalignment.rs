//! Static misalignments of the pair (E, P, G, ΔΣ) and the rigid poses of
//! the two bodies they give; see `docs/misalignment.md` for the sketch.
//!
//! Conventions (fixed frame of [`crate::generation`]: origin at the pitch
//! apex, which is the crossing point of the aligned axes; the pitch plane is
//! z = 0; the pinion axis a₁ = (cos γ₁, 0, −sin γ₁), the wheel axis
//! a₂ = (cos γ₂, 0, sin γ₂), both in the plane y = 0):
//!
//! - ΔΣ (deg) turns the pinion about the y axis through the apex so that
//!   the shaft angle γ₁ + γ₂ grows by ΔΣ (positive opens the shaft angle):
//!   a₁ → (cos(γ₁ + ΔΣ), 0, −sin(γ₁ + ΔΣ)).
//! - P (mm) then moves the pinion along its (turned) axis, positive away
//!   from the apex (the pinion withdrawn from mesh).
//! - E (mm) moves the pinion along h·y, perpendicular to the plane of the
//!   aligned axes, with h the tooth-trace sign of the pinion's hand
//!   ([`crate::generation::trace_sign`]: −1 right hand, +1 left hand):
//!   positive E is the direction of a conventional hypoid offset for the
//!   pinion's hand, the one that makes the pinion's spiral angle larger than
//!   the wheel's (the pinion generatrix through the mean point turns by
//!   −E/R_m in the pitch plane, so β₁ = β + E/R_m to first order).
//! - G (mm) moves the wheel along its axis, positive away from the apex.
//!
//! Only the relative pose of the pinion with respect to the wheel enters the
//! contact: [`BodyPoses::relative`].

use crate::design::PairData;
use crate::error::InputError;
use crate::generation::{trace_sign, MemberFrame};
use crate::limits::scene as scene_limits;
use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The scene's `[misalignment]` table (all zero when absent).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Misalignment {
    /// E: offset of the pinion axis, mm (sign: see the module docs).
    pub offset_mm: f64,
    /// P: pinion axial, mm, positive away from the apex.
    pub pinion_axial_mm: f64,
    /// G: wheel axial, mm, positive away from the apex.
    pub wheel_axial_mm: f64,
    /// ΔΣ: shaft-angle change, deg, positive opens the shaft angle.
    pub shaft_angle_deg: f64,
}

/// Largest |E|, |P|, |G| as a fraction of the mean normal module: beyond a
/// fifth of a module the contact leaves the flanks of a localized bearing.
pub const MAX_SHIFT_PER_MODULE: f64 = 0.2;
/// Largest |ΔΣ|, deg.
pub const MAX_SHAFT_ANGLE_DEG: f64 = 0.5;

/// The four misalignments by name (scene field, symbol, unit).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Component {
    Offset,
    PinionAxial,
    WheelAxial,
    ShaftAngle,
}

impl Component {
    pub const ALL: [Component; 4] = [
        Component::Offset,
        Component::PinionAxial,
        Component::WheelAxial,
        Component::ShaftAngle,
    ];
    /// The field name in `[misalignment]`.
    pub fn field(self) -> &'static str {
        match self {
            Component::Offset => "offset_mm",
            Component::PinionAxial => "pinion_axial_mm",
            Component::WheelAxial => "wheel_axial_mm",
            Component::ShaftAngle => "shaft_angle_deg",
        }
    }
    /// The usual symbol (E, P, G, ΔΣ).
    pub fn symbol(self) -> &'static str {
        match self {
            Component::Offset => "E",
            Component::PinionAxial => "P",
            Component::WheelAxial => "G",
            Component::ShaftAngle => "ΔΣ",
        }
    }
    /// Unit of the field.
    pub fn unit(self) -> &'static str {
        match self {
            Component::ShaftAngle => "deg",
            _ => "mm",
        }
    }
}

impl Misalignment {
    /// The value of one component.
    pub fn get(&self, c: Component) -> f64 {
        match c {
            Component::Offset => self.offset_mm,
            Component::PinionAxial => self.pinion_axial_mm,
            Component::WheelAxial => self.wheel_axial_mm,
            Component::ShaftAngle => self.shaft_angle_deg,
        }
    }

    /// A copy with one component set.
    pub fn with(mut self, c: Component, v: f64) -> Self {
        match c {
            Component::Offset => self.offset_mm = v,
            Component::PinionAxial => self.pinion_axial_mm = v,
            Component::WheelAxial => self.wheel_axial_mm = v,
            Component::ShaftAngle => self.shaft_angle_deg = v,
        }
        self
    }

    /// All four exactly zero: the aligned pair (the analyses then take the
    /// aligned code path, bit for bit today's).
    pub fn is_zero(&self) -> bool {
        Component::ALL.iter().all(|&c| self.get(c) == 0.0)
    }

    /// The limit of component `c` for `pair`, in its unit.
    pub fn limit(c: Component, pair: &PairData) -> f64 {
        match c {
            Component::ShaftAngle => MAX_SHAFT_ANGLE_DEG,
            _ => MAX_SHIFT_PER_MODULE * pair.normal_module * 1e3,
        }
    }

    /// Each component finite and within its limit; `table` is the TOML
    /// table the fields are in (for the messages).
    pub fn check(&self, path: &Path, table: &str, pair: &PairData) -> Result<(), InputError> {
        for c in Component::ALL {
            let v = self.get(c);
            let lim = Self::limit(c, pair);
            let field = format!("{table}.{}", c.field());
            match c {
                Component::ShaftAngle => scene_limits::SHAFT_ANGLE.check_at(path, &field, v)?,
                _ => {
                    let l = match c {
                        Component::Offset => &scene_limits::OFFSET,
                        Component::PinionAxial => &scene_limits::PINION_AXIAL,
                        _ => &scene_limits::WHEEL_AXIAL,
                    };
                    l.check_with(path, &field, v, &[-lim, lim], || {
                        format!(
                            "|{}| must be at most {lim:.4} mm ({MAX_SHIFT_PER_MODULE} x the mean normal module)",
                            c.symbol()
                        )
                    })?
                }
            }
        }
        Ok(())
    }

    /// The bodies' poses in the fixed frame: the wheel moved by G along its
    /// axis, the pinion turned by ΔΣ about the y axis through the apex, then
    /// moved by P along its turned axis and by E along h·y.
    pub fn poses(&self, pair: &PairData) -> BodyPoses {
        let a1 = MemberFrame::new(pair, crate::design::Member::Pinion).axis();
        let a2 = MemberFrame::new(pair, crate::design::Member::Wheel).axis();
        let h = trace_sign(pair.members[0].hand);
        let rotation = rot_y(self.shaft_angle_deg.to_radians());
        let pinion = Pose {
            translation: rotation * a1 * (self.pinion_axial_mm * 1e-3)
                + Vector3::new(0.0, h * self.offset_mm * 1e-3, 0.0),
            rotation,
        };
        let wheel = Pose {
            rotation: Matrix3::identity(),
            translation: a2 * (self.wheel_axial_mm * 1e-3),
        };
        BodyPoses { pinion, wheel }
    }
}

/// Rotation about y by `a` (rad).
pub fn rot_y(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)
}

/// A rigid pose x ↦ R x + t.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    pub rotation: Matrix3<f64>,
    pub translation: Vector3<f64>,
}

impl Pose {
    pub fn identity() -> Self {
        Pose {
            rotation: Matrix3::identity(),
            translation: Vector3::zeros(),
        }
    }
    /// The pose applied to a point.
    pub fn apply(&self, x: &Vector3<f64>) -> Vector3<f64> {
        self.rotation * x + self.translation
    }
    /// The inverse pose.
    pub fn inverse(&self) -> Pose {
        let rt = self.rotation.transpose();
        Pose {
            rotation: rt,
            translation: -(rt * self.translation),
        }
    }
    /// `self` after `first`: x ↦ self(first(x)).
    pub fn after(&self, first: &Pose) -> Pose {
        Pose {
            rotation: self.rotation * first.rotation,
            translation: self.rotation * first.translation + self.translation,
        }
    }
}

/// Poses of both bodies in a common frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyPoses {
    pub pinion: Pose,
    pub wheel: Pose,
}

impl BodyPoses {
    /// The pinion's pose seen from the wheel: wheel⁻¹ ∘ pinion, the only
    /// thing the contact depends on.
    pub fn relative(&self) -> Pose {
        self.wheel.inverse().after(&self.pinion)
    }
    /// Both bodies moved by the same rigid motion `common` (which leaves
    /// [`BodyPoses::relative`] unchanged).
    pub fn moved(&self, common: &Pose) -> BodyPoses {
        BodyPoses {
            pinion: common.after(&self.pinion),
            wheel: common.after(&self.wheel),
        }
    }
}
