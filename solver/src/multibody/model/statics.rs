//! The model's quasi-static balance: the static lag and state at a pinion
//! angle, the torque that holds the pair in contact, the damping for a
//! ratio and the initial speeds.

use super::{Drive, Model, State};
use crate::SolverError;

impl Model<'_> {
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
