//! The model's element state, contact and damping forces (with the
//! impact law's where its table is one) and energy at a state.

use super::{smoothstep, Contact, Drive, Model, State, FRICTION_SPEED};
use crate::multibody::mesh_table::MeshState;
use crate::SolverError;

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
            add_friction(&mut q_c, &mut k, &mut d, mu, dmu, phi, dphi);
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
            add_friction(q_c, k, d, mu, dmu, phi, dphi);
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
}

/// Adds the friction of coefficient μ (and ∂μ/∂θ̇₁ = `dmu`) on the friction
/// levers φ (with their Jacobian ∂φ/∂q) to the forces `q_c`, the
/// stiffness `k` and the damping `d`: Q₁ −= μφ₁, Q₂ += μφ₂,
/// K₁ⱼ += μ∂φ₁/∂qⱼ, K₂ⱼ −= μ∂φ₂/∂qⱼ, D₁₁ += μ′φ₁, D₂₁ −= μ′φ₂.
fn add_friction(
    q_c: &mut [f64; 2],
    k: &mut [[f64; 2]; 2],
    d: &mut [[f64; 2]; 2],
    mu: f64,
    dmu: f64,
    phi: [f64; 2],
    dphi: [[f64; 2]; 2],
) {
    q_c[0] -= mu * phi[0];
    q_c[1] += mu * phi[1];
    for j in 0..2 {
        k[0][j] += mu * dphi[0][j];
        k[1][j] -= mu * dphi[1][j];
    }
    d[0][0] += dmu * phi[0];
    d[1][0] -= dmu * phi[1];
}
