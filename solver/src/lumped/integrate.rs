//! Time integration of the 8-DOF model as 16 first-order equations
//! y = (q, q̇), ẏ = (q̇, M⁻¹(f − K_b q − C_b q̇ − v Fₙ − μ max(Fₙ, 0) g(t))),
//! with the adaptive Dormand–Prince 5(4) pair and its dense output (g the
//! friction per unit normal force, [`super::friction`]; with friction the
//! wheel's load torque is the one that balances the mean friction moments,
//! [`Equations::new`]).
//!
//! Integrator: the `differential-equations` crate's
//! `ExplicitRungeKutta::dopri5` (Hairer's DOPRI5 step-size control, error
//! norm |errᵢ| / (atolᵢ + rtol max(|yᵢ|, |yᵢ′|)), 4th-order dense output).
//! Chosen over `ode_solvers` (also DOPRI5, maintained) because it builds
//! on the workspace's nalgebra 0.35 instead of pulling a second nalgebra,
//! takes a tolerance per component (the state mixes m, rad, m/s, rad/s)
//! and evaluates its dense output at even times (the time histories and
//! spectra need evenly spaced samples). Like DOPRI5 it stops with an error
//! after 15 stability-limited step checks ("stiffness detected"); at the
//! tolerances used here the steps are limited by accuracy, far below the
//! stability bound, and the error is reported as [`LumpedError::Integration`].

use super::excitation::MeshExcitation;
use super::model::{Model, Vec8};
use super::LumpedError;
use differential_equations::prelude::{ExplicitRungeKutta, IVP, ODE};

/// The right-hand side: the model and its excitation.
pub struct Equations<'a> {
    pub model: &'a Model,
    pub excitation: &'a MeshExcitation,
    v: [f64; 8],
    inv_mass: [f64; 8],
    kb: [f64; 8],
    cb: [f64; 8],
    f: [f64; 8],
}

/// The mesh at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshForce {
    /// λ (m) and λ̇ (m/s).
    pub lambda: [f64; 2],
    /// k(t), N/m.
    pub stiffness: f64,
    /// Fₙ = kλ + cλ̇ + F_imp, N.
    pub force: f64,
    /// F_imp, N.
    pub impact: f64,
}

impl<'a> Equations<'a> {
    /// With friction, the wheel's load torque T₂ is the mean over the
    /// friction samples of what the mesh gives the wheel in quasi-static
    /// balance: at each sample the pinion's balance T₁ = Fₖ(r₁ + μg₄ₖ)
    /// gives the mesh force Fₖ, and the wheel receives Fₖ(r₂ − μg₈ₖ);
    /// T₂ = mean of that (the mesh's efficiency below 1), so that the rigid
    /// rotation (θ₁, θ₂) ∝ (r₂, r₁) carries no mean generalized force.
    /// Without friction, T₂ = T₁ r₂/r₁.
    pub fn new(model: &'a Model, excitation: &'a MeshExcitation) -> Self {
        let v = model.mesh_vector();
        let mut f: [f64; 8] = std::array::from_fn(|i| model.torques()[i]);
        if let Some(fr) = &excitation.friction {
            let [r1, r2] = model.levers_m;
            let (mu, t1) = (fr.coefficient, model.pinion_torque_nm);
            let n = fr.per_unit_force.len() as f64;
            f[7] = -fr
                .per_unit_force
                .iter()
                .map(|g| t1 / (r1 + mu * g[3]) * (r2 - mu * g[7]))
                .sum::<f64>()
                / n;
        }
        let mut kb = [0.0; 8];
        let mut cb = [0.0; 8];
        for i in 0..2 {
            for d in 0..3 {
                kb[4 * i + d] = model.members[i].bearing_stiffness_n_per_m[d];
                cb[4 * i + d] = model.members[i].bearing_damping_ns_per_m[d];
            }
        }
        Self {
            model,
            excitation,
            v: std::array::from_fn(|i| v[i]),
            inv_mass: model.mass_diagonal().map(|m| 1.0 / m),
            kb,
            cb,
            f,
        }
    }

    /// Bearings made rigid: the translations keep their start values (their
    /// accelerations are zero), only θ₁, θ₂ move.
    pub fn rigid_bearings(mut self) -> Self {
        for i in [0, 1, 2, 4, 5, 6] {
            self.inv_mass[i] = 0.0;
        }
        self
    }

    /// The mesh force at time `t` for coordinates `q` and velocities `qd`.
    pub fn mesh(&self, t: f64, q: &[f64], qd: &[f64]) -> MeshForce {
        let [e, ed, _] = self.excitation.te(t);
        let k = self.excitation.stiffness.value(t);
        let lam = dot(&self.v, q) - e;
        let lamd = dot(&self.v, qd) - ed;
        let imp = self.excitation.impact.map_or(0.0, |p| p.force(t));
        MeshForce {
            lambda: [lam, lamd],
            stiffness: k,
            force: k * lam + self.model.mesh_damping_ns_per_m * lamd + imp,
            impact: imp,
        }
    }

    /// The external torques (0, 0, 0, T₁, 0, 0, 0, −T₂) the run uses.
    pub fn torques(&self) -> [f64; 8] {
        self.f
    }

    /// The friction's generalized force −μ max(Fₙ, 0) g(t) for the mesh
    /// force `fm` (zero without friction).
    pub fn friction(&self, t: f64, fm: f64) -> [f64; 8] {
        match &self.excitation.friction {
            Some(fr) => {
                let g = fr.at(t);
                let s = fr.coefficient * fm.max(0.0);
                g.map(|x| -s * x)
            }
            None => [0.0; 8],
        }
    }

    /// q̈ at time `t`.
    pub fn acceleration(&self, t: f64, q: &[f64], qd: &[f64]) -> [f64; 8] {
        let fm = self.mesh(t, q, qd).force;
        let ff = self.friction(t, fm);
        std::array::from_fn(|i| {
            (self.f[i] - self.kb[i] * q[i] - self.cb[i] * qd[i] - self.v[i] * fm + ff[i])
                * self.inv_mass[i]
        })
    }
}

fn dot(a: &[f64; 8], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

impl ODE<f64, [f64; 16]> for Equations<'_> {
    fn diff(&self, t: f64, y: &[f64; 16], dydt: &mut [f64; 16]) {
        let (q, qd) = y.split_at(8);
        let a = self.acceleration(t, q, qd);
        dydt[..8].copy_from_slice(qd);
        dydt[8..].copy_from_slice(&a);
    }
}

/// Integration settings.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Start and end time, s.
    pub t_span_s: [f64; 2],
    /// Spacing of the output samples, s.
    pub output_step_s: f64,
    /// Relative tolerance (seed 004: 1e-6).
    pub rtol: f64,
    /// Absolute tolerance per component of (q, q̇).
    pub atol: [f64; 16],
    /// Largest step, s (keeps a step from jumping over an impact pulse).
    pub max_step_s: f64,
    /// Step budget.
    pub max_steps: usize,
}

/// The run: samples at even times.
#[derive(Debug, Clone, Default)]
pub struct History {
    pub t: Vec<f64>,
    pub q: Vec<[f64; 8]>,
    pub qd: Vec<[f64; 8]>,
    pub qdd: Vec<[f64; 8]>,
    pub mesh: Vec<MeshForceSample>,
    /// Accepted and rejected steps, right-hand-side evaluations.
    pub steps: [usize; 2],
    pub evaluations: usize,
}

/// [`MeshForce`] at a sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshForceSample {
    pub lambda_m: f64,
    pub stiffness_n_per_m: f64,
    pub force_n: f64,
    pub impact_n: f64,
}

/// Integrates from `y0` = (q, q̇).
pub fn integrate(eq: &Equations, y0: [f64; 16], s: &Settings) -> Result<History, LumpedError> {
    let [t0, t1] = s.t_span_s;
    let ok = t0.is_finite()
        && t1 > t0
        && s.output_step_s > 0.0
        && s.rtol > 0.0
        && s.max_step_s > 0.0
        && s.atol.iter().all(|a| *a > 0.0 && a.is_finite())
        && y0.iter().all(|v| v.is_finite());
    if !ok {
        return Err(LumpedError::Input(format!(
            "integration settings: span {:?} s, output step {} s, rtol {}, max step {} s, atol {:?}: need t1 > t0, all > 0 and a finite start state",
            s.t_span_s, s.output_step_s, s.rtol, s.max_step_s, s.atol
        )));
    }
    let method = ExplicitRungeKutta::dopri5()
        .rtol(s.rtol)
        .atol(s.atol)
        .h_max(s.max_step_s)
        .max_steps(s.max_steps);
    let sol = IVP::ode(eq, t0, t1, y0)
        .even(s.output_step_s)
        .method(method)
        .solve()
        .map_err(|e| LumpedError::Integration(format!("{e:?}").chars().take(300).collect()))?;
    let mut h = History {
        steps: [sol.steps.accepted, sol.steps.rejected],
        evaluations: sol.evals.function,
        ..Default::default()
    };
    for (t, y) in sol.t.iter().zip(&sol.y) {
        let (q, qd) = y.split_at(8);
        let m = eq.mesh(*t, q, qd);
        h.t.push(*t);
        h.q.push(std::array::from_fn(|i| q[i]));
        h.qd.push(std::array::from_fn(|i| qd[i]));
        h.qdd.push(eq.acceleration(*t, q, qd));
        h.mesh.push(MeshForceSample {
            lambda_m: m.lambda[0],
            stiffness_n_per_m: m.stiffness,
            force_n: m.force,
            impact_n: m.impact,
        });
    }
    Ok(h)
}

/// Kinetic plus potential energy ½q̇ᵀMq̇ + ½qᵀKq of the undamped, unforced
/// model with constant mesh stiffness `k` (N/m), J.
pub fn energy(model: &Model, k: f64, q: &[f64; 8], qd: &[f64; 8]) -> f64 {
    let q = Vec8::from(*q);
    let qd = Vec8::from(*qd);
    0.5 * (qd.transpose() * model.mass() * qd)[0]
        + 0.5 * (q.transpose() * model.stiffness(k) * q)[0]
}
