//! Multibody time integration: pinion and wheel as rigid bodies on revolute
//! joints (rigid bearings), coupled by the tabulated contact element
//! ([`crate::multibody::mesh_table`]) with viscous mesh damping, driven as in the white
//! paper (an imposed speed on one member, a torque on the other) or by a
//! fluctuating pinion speed against a free wheel (rattle). With coast-side
//! contact the element holds both flank pairs across the backlash
//! ([`crate::multibody::backlash`]): V below is then the sum of both sides' potentials,
//! and the damping acts while either pair is in contact.
//!
//! Equations of motion in q = (q₁, q₂) (see [`crate::multibody::mesh_table`]):
//!
//!   J₁ q̈₁ = T₁ − ∂V/∂q₁ − c s(u) θ̇ r − μ σ(q̇₁) Φ₁
//!   J₂ q̈₂ = −T₂ − ∂V/∂q₂ + c s(u) θ̇ + μ σ(q̇₁) Φ₂,     θ = r q₁ − q₂,
//!
//! with s(u) a smooth step from 0 (open) to 1 over the first lag step of
//! the table, and optional Coulomb friction: μ the coefficient, Φᵢ the
//! tabulated friction moments, σ a smoothed sign of the pinion speed. A member with imposed speed follows its ramp. Two implicit one-step schemes, both solved by
//! Newton with the element's tangent (the Hessian of V):
//! - generalized-α (Chung & Hulbert 1993) with spectral radius ρ∞ (numerical
//!   damping of the high modes for ρ∞ < 1),
//! - the energy-conserving midpoint rule with the coordinate-wise discrete
//!   gradient of V (Itoh & Abe 1988), averaged over both coordinate orders
//!   so that it is the midpoint gradient to second order
//!   ([`crate::multibody::time_step::discrete_gradient`]): without damping, kinetic
//!   energy + V − work of the torques is constant to the Newton tolerance.
//!
//! With an impact-law table ([`crate::multibody::impact_table`]) V is that law's
//! stiffness term on the same grid; its damping and speed-dependent friction
//! replace c s(u) θ̇ and μ σ(q̇₁) Φ ([`Model::contact`]).
//!
//! Step control: the difference between the step's θ and its explicit
//! Taylor predictor estimates the local error; steps above the tolerance
//! are retried with a smaller step, and the step never exceeds the maximum.

mod drive;
mod forces;
mod statics;
#[cfg(test)]
mod tests;

pub use drive::{Drive, Fluctuation, Ramp};

use crate::multibody::backlash::Coast;
use crate::multibody::mesh_table::{MeshState, MeshTable};
use crate::SolverError;

/// The mechanical model.
#[derive(Debug, Clone, Copy)]
pub struct Model<'a> {
    pub table: &'a MeshTable,
    /// The coast flanks across the backlash, when the element has them.
    pub coast: Option<&'a Coast>,
    /// Polar moments of inertia of pinion and wheel, kg·m².
    pub inertia: [f64; 2],
    /// Mesh damping on the wheel lag, N·m·s/rad (pinion torque per lag rate).
    pub damping: f64,
    /// Coulomb friction coefficient μ of the flanks: generalized forces
    /// −μ s(q̇₁) Φ₁ on the pinion and +μ s(q̇₁) Φ₂ on the wheel
    /// ([`MeshTable::friction_state`]), s a smooth sign of the pinion speed.
    pub friction: f64,
    pub drive: Drive,
}

/// Pinion speed (rad/s) over which the friction force's sign is smoothed:
/// s(ω) = tanh(ω / FRICTION_SPEED).
pub const FRICTION_SPEED: f64 = 1e-2;

/// State of the pair at time t.
#[derive(Debug, Clone, Copy, Default)]
pub struct State {
    pub t: f64,
    pub q: [f64; 2],
    pub v: [f64; 2],
    pub a: [f64; 2],
}

/// Contact + damping forces of a state and their derivatives.
#[derive(Debug, Clone, Copy)]
pub struct Contact {
    /// Generalized forces on (q₁, q₂), N·m.
    pub force: [f64; 2],
    /// K = −∂force/∂q, N·m/rad, and D = −∂force/∂q̇, N·m·s/rad.
    pub stiffness: [[f64; 2]; 2],
    pub damping: [[f64; 2]; 2],
    /// Both flank pairs together (potential, gradient, Hessian and force
    /// summed; lag and u of the drive side).
    pub mesh: MeshState,
    /// The coast flanks' own state (their lag and distance into contact).
    pub coast: Option<MeshState>,
}

/// Which flank pair carries the contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Touching {
    #[default]
    Neither,
    Drive,
    Coast,
    /// Both flank pairs at once: the pair is wedged (the free play across
    /// the backlash closed, e.g. by a negative backlash).
    Both,
}

impl Touching {
    /// Slot in a [drive, coast, neither, both] quadruple.
    pub fn slot(self) -> usize {
        match self {
            Touching::Drive => 0,
            Touching::Coast => 1,
            Touching::Neither => 2,
            Touching::Both => 3,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Touching::Drive => "drive",
            Touching::Coast => "coast",
            Touching::Neither => "none",
            Touching::Both => "wedged",
        }
    }
}

impl Contact {
    /// The pair in contact: both flank pairs when each is into contact
    /// (u > 0 on both: wedged), else the drive flanks while they push the
    /// wheel forward, the coast flanks while they push it back.
    pub fn touching(&self) -> Touching {
        let coast_u = self.coast.map_or(f64::NEG_INFINITY, |c| c.u);
        if self.mesh.u > 0.0 && coast_u > 0.0 {
            Touching::Both
        } else if self.mesh.u > 0.0 && self.mesh.grad[0] > 0.0 {
            Touching::Drive
        } else if coast_u > 0.0 && self.mesh.grad[0] < 0.0 {
            Touching::Coast
        } else {
            Touching::Neither
        }
    }
}

/// Contacts begun on each flank pair (impacts) and wedging episodes
/// (both pairs at once), counted along a run.
#[derive(Debug, Clone, Copy, Default)]
pub struct Impacts {
    pub drive: usize,
    pub coast: usize,
    pub wedged: usize,
    last: Touching,
}

impl Impacts {
    /// Records the pair in contact now; returns the previous one.
    pub fn record(&mut self, now: Touching) -> Touching {
        if now != self.last {
            match now {
                Touching::Drive => self.drive += 1,
                Touching::Coast => self.coast += 1,
                Touching::Both => self.wedged += 1,
                Touching::Neither => {}
            }
        }
        std::mem::replace(&mut self.last, now)
    }
}

/// Smooth step 0 → 1 on [0, 1] (C¹).
pub(crate) fn smoothstep(x: f64) -> (f64, f64) {
    let x = x.clamp(0.0, 1.0);
    (x * x * (3.0 - 2.0 * x), 6.0 * x * (1.0 - x))
}

/// The white paper's quasi-static drive: constant wheel speed (rad/s), the
/// torque on the pinion, mesh damping ratio ζ, friction coefficient μ; with
/// its quasi-static start at q₁ = 0.
pub fn wheel_driven<'a>(
    table: &'a MeshTable,
    inertia: [f64; 2],
    wheel_speed: f64,
    pinion_torque: f64,
    zeta: f64,
    friction: f64,
) -> Result<(Model<'a>, State), SolverError> {
    let mut m = Model {
        table,
        coast: None,
        inertia,
        damping: 0.0,
        friction,
        drive: Drive::WheelSpeed {
            speed: Ramp {
                from: wheel_speed,
                to: wheel_speed,
                duration: 0.0,
            },
            pinion_torque,
        },
    };
    let holding = m.holding_torque()?;
    if pinion_torque < holding {
        return Err(SolverError::Table(format!(
            "pinion_torque_nm = {pinion_torque} N·m is below {holding:.3e} N·m, the torque the pinion's inertia ({:.4e} kg·m²) needs to follow the unloaded TE at the quasi-static wheel speed of {:.4} rpm (the flanks can only push it back: below this it leaves the wheel at the tooth changes and drifts across the backlash, and no quasi-static TE exists); raise the torque or lower multibody.quasi_static_wheel_rpm",
            inertia[0],
            wheel_speed * 30.0 / std::f64::consts::PI
        )));
    }
    let s = m.static_state(0.0)?;
    m.damping = m.damping_for_ratio(zeta, &s)?;
    Ok((m, s))
}

/// Linear interpolation of y(x) on increasing x (end segments extended).
pub fn interpolate(x: &[f64], y: &[f64], at: f64) -> f64 {
    let k = x.partition_point(|v| *v < at).clamp(1, x.len() - 1);
    let (a, b) = (k - 1, k);
    if x[b] == x[a] {
        return y[a];
    }
    y[a] + (y[b] - y[a]) * (at - x[a]) / (x[b] - x[a])
}
