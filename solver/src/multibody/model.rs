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

use crate::multibody::backlash::Coast;
use crate::multibody::mesh_table::{MeshState, MeshTable};
use crate::SolverError;

/// A speed ramp: linear from `from` to `to` (rad/s) over `duration` (s), then constant.
#[derive(Debug, Clone, Copy)]
pub struct Ramp {
    pub from: f64,
    pub to: f64,
    pub duration: f64,
}

impl Ramp {
    /// (angle from t = 0, speed, acceleration) at time t.
    pub fn at(&self, t: f64) -> [f64; 3] {
        let acc = if self.duration > 0.0 {
            (self.to - self.from) / self.duration
        } else {
            0.0
        };
        if t <= self.duration {
            [self.from * t + 0.5 * acc * t * t, self.from + acc * t, acc]
        } else {
            let d = self.duration;
            let a0 = self.from * d + 0.5 * acc * d * d;
            [a0 + self.to * (t - d), self.to, 0.0]
        }
    }
}

/// A speed fluctuating about its mean: ω(t) = ω̄ (1 + a sin Ωt), as an
/// engine's speed ripple drives gear rattle.
#[derive(Debug, Clone, Copy)]
pub struct Fluctuation {
    /// Mean speed ω̄, rad/s; relative amplitude a; circular frequency Ω, rad/s.
    pub mean: f64,
    pub amplitude: f64,
    pub omega: f64,
}

impl Fluctuation {
    /// (angle from t = 0, speed, acceleration) at time t.
    pub fn at(&self, t: f64) -> [f64; 3] {
        let (w, a, o) = (self.mean, self.amplitude, self.omega);
        if o == 0.0 {
            return [w * t, w, 0.0];
        }
        let (s, c) = (o * t).sin_cos();
        [
            w * t + w * a * (1.0 - c) / o,
            w * (1.0 + a * s),
            w * a * o * c,
        ]
    }
}

/// How the pair is driven. Torques in N·m, positive in the drive sense.
#[derive(Debug, Clone, Copy)]
pub enum Drive {
    /// The wheel follows a speed ramp (the white paper's quasi-static 10 rpm
    /// run); the pinion carries the driving torque.
    WheelSpeed { speed: Ramp, pinion_torque: f64 },
    /// The pinion follows a speed ramp (the run-up); the wheel carries a
    /// resisting torque.
    PinionSpeed { speed: Ramp, wheel_torque: f64 },
    /// The pinion follows a fluctuating speed (rattle); the wheel carries a
    /// resisting (drag) torque.
    PinionFluctuating {
        speed: Fluctuation,
        wheel_torque: f64,
    },
    /// The pinion follows a speed ramp; the wheel's resisting torque rises
    /// from 0 to `wheel_torque` over `rise_s` by ADAMS's cubic STEP,
    /// STEP(t, 0, 0, rise_s, T) ([`crate::multibody::impact_law::step`]; constant for
    /// rise_s = 0): the drives of seeds 001 and 002.
    PinionSpeedLoadStep {
        speed: Ramp,
        wheel_torque: f64,
        rise_s: f64,
    },
    /// Both free: a driving pinion torque and a resisting wheel torque.
    Free {
        pinion_torque: f64,
        wheel_torque: f64,
    },
}

impl Drive {
    /// STEP(t, 0, 0, rise, T): T for rise ≤ 0.
    fn load_step(torque: f64, rise: f64, t: f64) -> f64 {
        if rise > 0.0 {
            crate::multibody::impact_law::step(t, 0.0, 0.0, rise, torque)
        } else {
            torque
        }
    }

    /// Which coordinates are free.
    pub(crate) fn free(&self) -> [bool; 2] {
        match self {
            Drive::WheelSpeed { .. } => [true, false],
            Drive::PinionSpeed { .. }
            | Drive::PinionFluctuating { .. }
            | Drive::PinionSpeedLoadStep { .. } => [false, true],
            Drive::Free { .. } => [true, true],
        }
    }

    /// External generalized forces on (q₁, q₂) at time t.
    pub fn torques(&self, t: f64) -> [f64; 2] {
        match *self {
            Drive::PinionSpeedLoadStep {
                wheel_torque,
                rise_s,
                ..
            } => [0.0, -Self::load_step(wheel_torque, rise_s, t)],
            Drive::WheelSpeed { pinion_torque, .. } => [pinion_torque, 0.0],
            Drive::PinionSpeed { wheel_torque, .. }
            | Drive::PinionFluctuating { wheel_torque, .. } => [0.0, -wheel_torque],
            Drive::Free {
                pinion_torque,
                wheel_torque,
            } => [pinion_torque, -wheel_torque],
        }
    }
}

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
}

impl Touching {
    /// Slot in a [drive, coast, neither] triple.
    pub fn slot(self) -> usize {
        match self {
            Touching::Drive => 0,
            Touching::Coast => 1,
            Touching::Neither => 2,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Touching::Drive => "drive",
            Touching::Coast => "coast",
            Touching::Neither => "none",
        }
    }
}

impl Contact {
    /// The pair in contact: the drive flanks while they push the wheel
    /// forward, the coast flanks while they push it back.
    pub fn touching(&self) -> Touching {
        let coast_u = self.coast.map_or(f64::NEG_INFINITY, |c| c.u);
        if self.mesh.u > 0.0 && self.mesh.grad[0] > 0.0 {
            Touching::Drive
        } else if coast_u > 0.0 && self.mesh.grad[0] < 0.0 {
            Touching::Coast
        } else {
            Touching::Neither
        }
    }
}

/// Contacts begun on each flank pair (impacts), counted along a run.
#[derive(Debug, Clone, Copy, Default)]
pub struct Impacts {
    pub drive: usize,
    pub coast: usize,
    last: Touching,
}

impl Impacts {
    /// Records the pair in contact now; returns the previous one.
    pub fn record(&mut self, now: Touching) -> Touching {
        if now != self.last {
            match now {
                Touching::Drive => self.drive += 1,
                Touching::Coast => self.coast += 1,
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

impl Model<'_> {
    /// Imposed (angle, speed, acceleration) of the driven member, if any, at t,
    /// relative to its value at t = 0.
    pub(crate) fn imposed(&self, t: f64) -> Option<(usize, [f64; 3])> {
        match self.drive {
            Drive::WheelSpeed { speed, .. } => Some((1, speed.at(t))),
            Drive::PinionSpeed { speed, .. } | Drive::PinionSpeedLoadStep { speed, .. } => {
                Some((0, speed.at(t)))
            }
            Drive::PinionFluctuating { speed, .. } => Some((0, speed.at(t))),
            Drive::Free { .. } => None,
        }
    }

    /// The element's state at q: both flank pairs summed, and the coast
    /// flanks' own state when the element has them.
    pub fn mesh(&self, q: [f64; 2]) -> Result<(MeshState, Option<MeshState>), SolverError> {
        let mut ms = self.table.state(q[0], q[1])?;
        let Some(coast) = self.coast else {
            return Ok((ms, None));
        };
        let cs = coast.state(q)?;
        ms.potential += cs.potential;
        for i in 0..2 {
            ms.grad[i] += cs.grad[i];
            ms.force[i] += cs.force[i];
            for j in 0..2 {
                ms.hess[i][j] += cs.hess[i][j];
            }
        }
        ms.force[2] += cs.force[2];
        Ok((ms, Some(cs)))
    }

    /// Tangential (circumferential) component of the contact forces on the
    /// wheel at q, N ([`MeshTable::tangential_at`]): the drive flanks' in
    /// the direction of their wheel torque, the coast flanks' (which push
    /// the wheel the other way) subtracted.
    pub fn wheel_tangential_force(&self, q: [f64; 2]) -> Result<f64, SolverError> {
        let drive = self.table.tangential_at(q[0], q[1])?;
        let coast = match self.coast {
            Some(c) => {
                let [q1, q2] = c.coordinates(q);
                c.table.tangential_at(q1, q2)?
            }
            None => 0.0,
        };
        Ok(drive - coast)
    }

    /// Potential of both flank pairs at q, J.
    pub fn potential(&self, q: [f64; 2]) -> Result<f64, SolverError> {
        Ok(self.mesh(q)?.0.potential)
    }

    /// Contact and damping generalized forces at (q, v), their stiffness
    /// K = −∂Q/∂q (Hessian of V) and damping matrix D = −∂Q/∂v.
    pub fn contact(&self, q: [f64; 2], v: [f64; 2]) -> Result<Contact, SolverError> {
        let (ms, cs) = self.mesh(q)?;
        let r = self.table.ratio;
        // Damping acts on the lag rate while either flank pair is in contact
        // (θ̇ᶜ = −θ̇: the same force law on the coast side).
        let (mut s, _) = smoothstep(ms.u / self.table.du());
        if let (Some(cs), Some(coast)) = (cs, self.coast) {
            s = s.max(smoothstep(cs.u / coast.table.du()).0);
        }
        let rate = r * v[0] - v[1];
        let c = self.damping * s;
        let dir = [r, -1.0];
        let q_c = [
            -ms.grad[0] - c * rate * dir[0],
            -ms.grad[1] - c * rate * dir[1],
        ];
        let d = [
            [c * dir[0] * dir[0], c * dir[0] * dir[1]],
            [c * dir[1] * dir[0], c * dir[1] * dir[1]],
        ];
        let (mut q_c, mut k, mut d) = (q_c, ms.hess, d);
        if self.table.impact.is_some() {
            self.impact_forces(q, v, &ms, &mut q_c, &mut k, &mut d)?;
        } else if self.friction > 0.0 {
            let (mut phi, mut dphi) = self.table.friction_state(q[0], q[1])?;
            if let Some(coast) = self.coast {
                let (pc, dc) = coast.friction_state(q)?;
                for i in 0..2 {
                    phi[i] += pc[i];
                    for j in 0..2 {
                        dphi[i][j] += dc[i][j];
                    }
                }
            }
            let th = (v[0] / FRICTION_SPEED).tanh();
            let (mu, dmu) = (
                self.friction * th,
                self.friction * (1.0 - th * th) / FRICTION_SPEED,
            );
            q_c[0] -= mu * phi[0];
            q_c[1] += mu * phi[1];
            for j in 0..2 {
                k[0][j] += mu * dphi[0][j];
                k[1][j] -= mu * dphi[1][j];
            }
            d[0][0] += dmu * phi[0];
            d[1][0] -= dmu * phi[1];
        }
        Ok(Contact {
            force: q_c,
            stiffness: k,
            damping: d,
            mesh: ms,
            coast: cs,
        })
    }

    /// The impact law's damping and friction ([`crate::multibody::impact_table`]),
    /// added to the generalized forces `q_c` with their tangents: damping
    /// −C (A₁ θ̇ + E₁ q̇₁) on q₁ and +C (A₂ θ̇ + E₂ q̇₁) on q₂ (the normal
    /// approach speed at each pair's deepest point), the law's zero clamp on the mesh
    /// total (where the damping would pull the pinion, the mesh force is
    /// zero: forces and tangents vanish); friction −μ_e Φ₁ on q₁, +μ_e Φ₂
    /// on q₂ with μ_e = sgn(q̇₁) μ(ḡ |q̇₁|) (ḡ the mean slip speed per unit
    /// pinion speed, [`crate::multibody::impact_law::Friction`]), acting on the
    /// elastic normal force.
    fn impact_forces(
        &self,
        q: [f64; 2],
        v: [f64; 2],
        ms: &MeshState,
        q_c: &mut [f64; 2],
        k: &mut [[f64; 2]; 2],
        d: &mut [[f64; 2]; 2],
    ) -> Result<(), SolverError> {
        let (Some(imp), Some(is)) = (&self.table.impact, self.table.impact_state(q[0], q[1])?)
        else {
            return Ok(());
        };
        let r = self.table.ratio;
        let c = imp.law.damping;
        let rate = r * v[0] - v[1];
        let [a1, a2, e1, e2] = is.damping;
        let pinion_damping = c * (a1 * rate + e1 * v[0]);
        if ms.grad[0] - pinion_damping < 0.0 && ms.grad[0] > 0.0 {
            *q_c = [0.0; 2];
            *k = [[0.0; 2]; 2];
            *d = [[0.0; 2]; 2];
            return Ok(());
        }
        if ms.grad[0] > 0.0 {
            q_c[0] -= pinion_damping;
            q_c[1] += c * (a2 * rate + e2 * v[0]);
            d[0][0] += c * (a1 * r + e1);
            d[0][1] -= c * a1;
            d[1][0] -= c * (a2 * r + e2);
            d[1][1] += c * a2;
            let g = is.damping_grad;
            let dq = |j: usize, a: usize, e: usize| c * (rate * g[a][j] + v[0] * g[e][j]);
            *k = [
                [k[0][0] + dq(0, 0, 2), k[0][1] + dq(1, 0, 2)],
                [k[1][0] - dq(0, 1, 3), k[1][1] - dq(1, 1, 3)],
            ];
        }
        if let Some(fr) = imp.friction {
            let (phi, dphi) = self.table.friction_state(q[0], q[1])?;
            let g = is.slip;
            let (mu, dmu) = fr.coefficient(g * v[0].abs());
            let sgn = if v[0] > 0.0 {
                1.0
            } else if v[0] < 0.0 {
                -1.0
            } else {
                0.0
            };
            let (mu, dmu) = (sgn * mu, g * dmu);
            q_c[0] -= mu * phi[0];
            q_c[1] += mu * phi[1];
            for j in 0..2 {
                k[0][j] += mu * dphi[0][j];
                k[1][j] -= mu * dphi[1][j];
            }
            d[0][0] += dmu * phi[0];
            d[1][0] -= dmu * phi[1];
        }
        Ok(())
    }

    /// Kinetic + mesh potential energy − work of the constant torques, J
    /// (constant in a run without damping and with both members free).
    pub fn energy(&self, s: &State) -> Result<f64, SolverError> {
        let ext = self.drive.torques(s.t);
        Ok(0.5 * self.inertia[0] * s.v[0] * s.v[0]
            + 0.5 * self.inertia[1] * s.v[1] * s.v[1]
            + self.potential(s.q)?
            - ext[0] * s.q[0]
            - ext[1] * s.q[1])
    }

    /// Pinion torque of the drive's quasi-static balance, N·m.
    fn static_torque(&self) -> f64 {
        match self.drive {
            Drive::WheelSpeed { pinion_torque, .. } => pinion_torque,
            Drive::PinionSpeed { wheel_torque, .. }
            | Drive::PinionFluctuating { wheel_torque, .. } => wheel_torque * self.table.ratio,
            Drive::PinionSpeedLoadStep {
                wheel_torque,
                rise_s,
                ..
            } => Drive::load_step(wheel_torque, rise_s, 0.0) * self.table.ratio,
            Drive::Free { pinion_torque, .. } => pinion_torque,
        }
    }

    /// Quasi-static wheel lag at pinion rotation q₁ under the drive's
    /// torque, turning forward (the unloaded TE at zero torque): the
    /// smallest lag θ ≥ θ₀(q₁) at which the member that carries the torque
    /// is in balance, the pinion's ∂V/∂q₁ + μ Φ₁ = T₁, or with the pinion's
    /// speed imposed the wheel's −∂V/∂q₂ + μ Φ₂ = T₂ (with friction the two
    /// differ by the mesh efficiency).
    ///
    /// The root is bracketed first (from θ₀ upward) and then refined by
    /// Newton kept inside the bracket (bisection where Newton would leave
    /// it). Near θ₀ the tabulated torque is an interpolant through the
    /// contact's onset and not monotonic within about one lag step (it dips
    /// below zero and rises again): an unguarded Newton from there found
    /// roots below the unloaded TE at light loads, or none, and the start's
    /// speed taken from their slope was off by 0.4 % (the 10 rpm run at
    /// 1e-6 N·m then drifted away by hundreds of µrad). Where the
    /// interpolated torque already reaches the load at θ₀ the table cannot
    /// resolve the deflection and θ₀ is returned.
    pub fn static_lag(&self, q1: f64) -> Result<f64, SolverError> {
        let r = self.table.ratio;
        let torque = self.static_torque();
        let t0 = self.table.unloaded(q1)?[0];
        if torque <= 0.0 {
            return Ok(t0);
        }
        let wheel = self.drive.free() == [false, true];
        // Residual and its derivative in θ (d/dθ = −∂/∂q₂ at fixed q₁).
        let residual = |theta: f64| -> Result<(f64, f64), SolverError> {
            let q2 = r * q1 - theta;
            let ms = self.table.state(q1, q2)?;
            let (phi, dphi) = if self.friction > 0.0 {
                self.table.friction_state(q1, q2)?
            } else {
                Default::default()
            };
            Ok(if wheel {
                (
                    -ms.grad[1] + self.friction * phi[1] - torque / r,
                    ms.hess[1][1] - self.friction * dphi[1][1],
                )
            } else {
                (
                    ms.grad[0] + self.friction * phi[0] - torque,
                    -ms.hess[0][1] - self.friction * dphi[0][1],
                )
            })
        };
        let not_converged = |iterations| SolverError::NotConverged {
            what: "quasi-static lag".into(),
            iterations,
        };
        // Bracket [lo, hi] with f(lo) < 0 ≤ f(hi), marching up from θ₀ in
        // growing steps (the table ends at the largest lag it covers).
        let top = self.table.lags[self.table.lags.len() - 1];
        let mut lo = t0.max(self.table.theta_lo());
        let (f_lo, _) = residual(lo)?;
        if f_lo >= 0.0 {
            return Ok(lo);
        }
        let mut dx = self.table.du();
        let mut hi = lo;
        let mut found = false;
        for _ in 0..200 {
            let next = (hi + dx).min(top);
            if residual(next)?.0 >= 0.0 {
                hi = next;
                found = true;
                break;
            }
            lo = next;
            hi = next;
            if next >= top {
                break;
            }
            dx *= 1.5;
        }
        if !found {
            return Err(SolverError::Table(format!(
                "no quasi-static balance for {torque} N·m at pinion rotation {:.4} deg below the table's largest lag {:.3} µrad; raise the multibody table's torque",
                q1.to_degrees(),
                top * 1e6
            )));
        }
        // Safeguarded Newton in the bracket, from its upper end (the root
        // lies in the table's smooth part above the onset at most loads).
        let mut theta = hi;
        for _ in 0..100 {
            let (f, df) = residual(theta)?;
            if f < 0.0 {
                lo = theta;
            } else {
                hi = theta;
            }
            let newton = theta - f / df;
            let next = if df > 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            let step = next - theta;
            theta = next;
            if step.abs() < 1e-16 + 1e-12 * theta.abs() || hi - lo <= 4.0 * f64::EPSILON * hi.abs()
            {
                return Ok(theta);
            }
        }
        Err(not_converged(100))
    }

    /// Smallest pinion torque (N·m) that keeps the flanks in contact in
    /// the quasi-static drive (imposed wheel speed ω₂): the flanks can only
    /// push the pinion back, so wherever following the unloaded TE θ₀(q₁)
    /// needs the pinion to speed up, q̈₁ = θ₀″ q̇₁² / (r − θ₀′) with
    /// q̇₁ = ω₂ / (r − θ₀′), its torque must supply J₁ q̈₁; and where the
    /// contact passes to the next tooth pair (a kink of θ₀) the pinion's
    /// rebound must stay within the table's finest lag step. Below this the
    /// pinion leaves the wheel and drifts across the backlash or rattles:
    /// the run's TE is then no quasi-static TE. Zero for the other drives.
    ///
    /// The mirror image for the run-up (imposed pinion speed ω₁, resisting
    /// wheel torque): the flanks can only push the wheel forward, so where
    /// following θ₀ slows the wheel, q̈₂ = −θ₀″ ω₁² at steady speed, the
    /// wheel's resisting torque must supply J₂ θ₀″ ω₁²; at a tooth change
    /// the wheel runs ahead by J₂ (Δθ₀′ ω₁)² / (2 T₂), to be kept within the
    /// finest lag step. Returned as the pinion torque r T₂, at the ramp's
    /// top speed.
    pub fn holding_torque(&self) -> Result<f64, SolverError> {
        let (speed, member) = match self.drive {
            Drive::WheelSpeed { speed, .. } => (speed, 0),
            Drive::PinionSpeed { speed, .. } => (speed, 1),
            _ => return Ok(0.0),
        };
        let w = speed.from.abs().max(speed.to.abs());
        let r = self.table.ratio;
        let h = self.table.spec.step;
        let n = if self.table.spec.periodic {
            self.table.spec.positions
        } else {
            self.table.spec.positions - 1
        };
        // (at(n) wraps to the first node for a periodic table)
        // From the tabulated θ₀ by differences at the nodes: the interpolant
        // overshoots next to the kinks where the contact passes to the next
        // tooth pair (there the flanks decelerate the pinion, θ₀″ < 0), and
        // its θ₀″ there is no demand of the flanks' geometry.
        let te0 = &self.table.te0[self.table.lead..];
        let at = |k: usize| -> f64 {
            if k < te0.len() {
                te0[k]
            } else {
                te0[k - te0.len()]
            }
        };
        let mut need: f64 = 0.0;
        for k in 1..n {
            let (a, b, c) = (at(k - 1), at(k), at(k + 1));
            let d1 = (c - a) / (2.0 * h);
            let d2 = (a - 2.0 * b + c) / (h * h);
            if member == 1 {
                // Run-up: pinion speed imposed, the wheel held by T₂.
                need = need.max(r * self.inertia[1] * d2 * w * w);
                let drop = ((b - a) - (c - b)) / h;
                if drop > 0.0 {
                    let rate = drop * w;
                    need = need.max(r * self.inertia[1] * rate * rate / (2.0 * self.table.du()));
                }
                continue;
            }
            let v1 = w / (r - d1);
            need = need.max(self.inertia[0] * d2 * v1 * v1 / (r - d1));
            // Tooth change: the lag rate drops by Δθ̇ = (θ₀′₋ − θ₀′₊) q̇₁ at
            // once, an impact; the pinion rebounds (restitution up to 1) and
            // its torque brings it back after a separation of
            // J₁ Δθ̇² / (2 r T), to be kept within the table's finest lag step.
            let drop = ((b - a) - (c - b)) / h;
            if drop > 0.0 {
                let rate = drop * v1;
                need = need.max(self.inertia[0] * rate * rate / (2.0 * r * self.table.du()));
            }
        }
        Ok(need)
    }
    /// The quasi-static state at pinion rotation q₁, moving at the drive's
    /// initial speed with the static lag kept (θ̇ = θ'(q₁) q̇₁).
    pub fn static_state(&self, q1: f64) -> Result<State, SolverError> {
        let r = self.table.ratio;
        let theta = self.static_lag(q1)?;
        let d = 0.1 * self.table.spec.step;
        // Central difference, one-sided at the start of a non-periodic table.
        let slope = match self.static_lag(q1 - d) {
            Ok(before) => (self.static_lag(q1 + d)? - before) / (2.0 * d),
            Err(_) => (self.static_lag(q1 + d)? - theta) / d,
        };
        let w = self.initial_speed();
        let v = match self.drive {
            Drive::WheelSpeed { .. } => [w[1] / (r - slope), w[1]],
            _ => [w[0], (r - slope) * w[0]],
        };
        Ok(State {
            t: 0.0,
            q: [q1, r * q1 - theta],
            v,
            a: [0.0; 2],
        })
    }

    /// Mesh damping c (N·m·s/rad) that gives the torsional mesh mode the
    /// damping ratio ζ at state `s`: with k = ∂T₁/∂θ (pinion torque per lag),
    /// ω² = k (r/J₁ + 1/(r J₂)) and 2ζω = c (r²/J₁ + 1/J₂); a member with
    /// imposed speed counts as infinitely heavy.
    pub fn damping_for_ratio(&self, zeta: f64, s: &State) -> Result<f64, SolverError> {
        let ms = self.table.state(s.q[0], s.q[1])?;
        let r = self.table.ratio;
        let k = r * ms.hess[1][1];
        let free = self.drive.free();
        let inv = |i: usize| if free[i] { 1.0 / self.inertia[i] } else { 0.0 };
        let w2 = k * (r * inv(0) + inv(1) / r);
        Ok(2.0 * zeta * w2.max(0.0).sqrt() / (r * r * inv(0) + inv(1)))
    }

    fn initial_speed(&self) -> [f64; 2] {
        let r = self.table.ratio;
        match self.drive {
            Drive::WheelSpeed { speed, .. } => [speed.from / r, speed.from],
            Drive::PinionSpeed { speed, .. } | Drive::PinionSpeedLoadStep { speed, .. } => {
                [speed.from, speed.from * r]
            }
            Drive::PinionFluctuating { speed, .. } => [speed.mean, speed.mean * r],
            Drive::Free { .. } => [0.0, 0.0],
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speed_ramp_integrates_to_its_angle() {
        let r = Ramp {
            from: 1.0,
            to: 5.0,
            duration: 2.0,
        };
        // ∫₀² (1 + 2t) dt = 6, then 5 rad/s.
        assert!((r.at(2.0)[0] - 6.0).abs() < 1e-14);
        assert!((r.at(3.0)[0] - 11.0).abs() < 1e-14);
        assert_eq!(r.at(1.0)[2], 2.0);
        assert_eq!(r.at(2.5)[1], 5.0);
    }

    #[test]
    fn fluctuating_speed_is_the_derivative_of_its_angle() {
        let f = Fluctuation {
            mean: 30.0,
            amplitude: 0.05,
            omega: 2.0 * std::f64::consts::PI * 25.0,
        };
        assert_eq!(f.at(0.0)[0], 0.0);
        // One period: the mean speed times the period.
        let period = 2.0 * std::f64::consts::PI / f.omega;
        assert!((f.at(period)[0] - 30.0 * period).abs() < 1e-12);
        for t in [0.003, 0.011, 0.027] {
            let h = 1e-6;
            let [a0, w, acc] = f.at(t);
            let (ap, am) = (f.at(t + h), f.at(t - h));
            assert!(((ap[0] - am[0]) / (2.0 * h) - w).abs() < 1e-6 * w);
            assert!(((ap[1] - am[1]) / (2.0 * h) - acc).abs() < 1e-6 * (w * 0.05 * f.omega));
            assert!(a0 > 0.0);
        }
    }

    #[test]
    fn smoothstep_is_c1() {
        assert_eq!(smoothstep(-1.0), (0.0, 0.0));
        assert_eq!(smoothstep(2.0), (1.0, 0.0));
        assert!((smoothstep(0.5).0 - 0.5).abs() < 1e-15);
    }
}
