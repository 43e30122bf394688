//! Time stepping of the multibody model ([`crate::multibody::model::Model`]): the
//! two implicit one-step schemes (generalized-α; the energy-conserving
//! midpoint rule with a discrete gradient), both solved by Newton with the
//! contact element's tangent, and the step control around them.

use crate::multibody::model::{Contact, Model, State};
use crate::SolverError;

/// Integrates from `s` to `t_end`, calling `record` with the start and after
/// every accepted step; returns the final state and the number of steps.
pub fn integrate(
    m: &Model,
    s: State,
    integ: &mut Integrator,
    t_end: f64,
    mut record: impl FnMut(&State) -> Result<(), SolverError>,
) -> Result<(State, usize), SolverError> {
    let mut s = s;
    record(&s)?;
    let mut steps = 0;
    while s.t < t_end * (1.0 - 1e-12) {
        s = integ.step(m, &s, t_end)?;
        record(&s)?;
        steps += 1;
    }
    Ok((s, steps))
}

/// The time integration scheme.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scheme {
    /// Generalized-α with spectral radius at infinity ρ∞ ∈ [0, 1].
    GeneralizedAlpha { rho_inf: f64 },
    /// Energy-conserving midpoint rule with a discrete gradient.
    EnergyConserving,
}

/// Step control.
#[derive(Debug, Clone, Copy)]
pub struct StepControl {
    /// Largest and smallest step, s.
    pub max_step: f64,
    pub min_step: f64,
    /// Local error tolerance on the wheel lag, rad.
    pub tolerance: f64,
}

/// Integrator state carried from step to step.
#[derive(Debug, Clone, Copy)]
pub struct Integrator {
    pub scheme: Scheme,
    pub control: StepControl,
    /// Step to try next, s.
    pub h: f64,
    pub rejected: usize,
    pub newton_iterations: usize,
    pub history: StepHistory,
}

impl Integrator {
    pub fn new(scheme: Scheme, control: StepControl) -> Self {
        Integrator {
            scheme,
            control,
            h: control.max_step,
            rejected: 0,
            newton_iterations: 0,
            history: StepHistory::default(),
        }
    }

    /// One accepted step from `s` (retrying smaller steps as needed), not
    /// past `t_end`.
    pub fn step(&mut self, m: &Model, s: &State, t_end: f64) -> Result<State, SolverError> {
        loop {
            let h = self.h.min(t_end - s.t).max(0.0);
            if h <= 0.0 {
                return Ok(*s);
            }
            let trial = match self.scheme {
                Scheme::GeneralizedAlpha { rho_inf } => alpha_step(m, s, h, rho_inf),
                Scheme::EnergyConserving => midpoint_step(m, s, h),
            };
            let r = m.table.ratio;
            // Local error: corrector − Taylor predictor, on θ.
            let judged = trial.map(|(next, iters)| {
                self.newton_iterations += iters;
                let ratio = lag_error_ratio(r, [s.q, s.v, s.a], next.q, h, self.control.tolerance);
                (next, ratio)
            });
            if let Some(next) = self.control.judge(
                &mut self.h,
                &mut self.rejected,
                &mut self.history,
                h,
                judged,
            )? {
                return Ok(next);
            }
        }
    }
}

/// What the step control remembers between trial steps.
#[derive(Debug, Clone, Copy, Default)]
pub struct StepHistory {
    /// Error ratio of the last accepted step (0: none yet).
    pub last_ratio: f64,
    /// Whether the last trial was rejected.
    pub after_reject: bool,
}

impl StepControl {
    /// The step control's verdict on a trial step of size `h`: `trial` is
    /// the step's result with its local error over the tolerance. A failed
    /// Newton retries a quarter step (the error returned once at the
    /// smallest step); an error ratio ρ above 1 retries the step scaled by
    /// 0.9 ρ^(−1/3) (at least 0.2). An accepted step sets the next by the
    /// PI rule (Gustafsson) 0.85 ρₙ^(−0.7/3) ρₙ₋₁^(0.4/3), within [0.2, 1.5]
    /// times this one and the largest step, and not above this one right
    /// after a rejection. The error estimate of a slow, nearly quasi-static
    /// run is noisy (ratios of 0.05 and 3.7 a few steps apart at the same
    /// h in the 10 rpm runs). Measured 2026-11-28 in the compliant-bearing
    /// bench: with the plain rule 0.9 ρ^(−1/3), up to 2 ×, the 10 rpm runs
    /// rejected 424 of 1,375 trials (rigid bearings) and 418 of 1,657
    /// (compliant); with this rule 32 of 1,312 and 23 of 1,820, the run-ups
    /// 3 and 8 of about 15,300 (were 3 and 55).
    /// Returns the accepted step, or None to retry with `*next_h`.
    pub fn judge<T>(
        &self,
        next_h: &mut f64,
        rejected: &mut usize,
        history: &mut StepHistory,
        h: f64,
        trial: Result<(T, f64), SolverError>,
    ) -> Result<Option<T>, SolverError> {
        let (next, ratio) = match trial {
            Ok(x) => x,
            Err(e) => {
                if h <= self.min_step {
                    return Err(e);
                }
                *rejected += 1;
                history.after_reject = true;
                *next_h = (0.25 * h).max(self.min_step);
                return Ok(None);
            }
        };
        if ratio > 1.0 && h > self.min_step {
            *rejected += 1;
            history.after_reject = true;
            *next_h = (h * (0.9 * ratio.powf(-1.0 / 3.0)).max(0.2)).max(self.min_step);
            return Ok(None);
        }
        // A zero error (nothing moves) grows the step as far as allowed.
        let rho = ratio.max(1e-10);
        let mut grow = 0.85 * rho.powf(-0.7 / 3.0);
        if history.last_ratio > 0.0 {
            grow *= history.last_ratio.powf(0.4 / 3.0);
        }
        let mut grow = grow.clamp(0.2, 1.5);
        if history.after_reject {
            grow = grow.min(1.0);
        }
        history.last_ratio = rho;
        history.after_reject = false;
        *next_h = (h * grow).min(self.max_step);
        Ok(Some(next))
    }
}

/// Smallest local error on the lag θ = r q₁ − q₂ that a step can resolve,
/// rad: Newton stops at updates of 1e-15 (1 + |q|) and θ is a difference of
/// rotations that grow along a run, so the corrector − predictor difference
/// has a floor of rounding noise of about (1 + r) 1e-15 (1 + |q|). A
/// tolerance below it rejected every step down to the smallest step, where
/// a run of millions of steps never ended (`te_tolerance_urad` = 1e-9 µrad
/// in a run-up); the step control takes this floor, 16 times over, as the
/// least tolerance (the scene checks refuse tolerances near it).
pub fn lag_resolution(r: f64, s: &State) -> f64 {
    lag_resolution_at(r, s.q[0].abs().max(s.q[1].abs()))
}

/// The local error ratio of a step of `h` from turns `q`, speeds `v` and
/// accelerations `a` to turns `next`: the lag θ = r q₁ − q₂'s corrector
/// minus its Taylor predictor q + h q̇ + h²/2 q̈, over the larger of
/// `tolerance` and [`lag_resolution_at`]. Shared by the rigid, compliant
/// and gearbox integrators.
pub fn lag_error_ratio(
    r: f64,
    [q, v, a]: [[f64; 2]; 3],
    next: [f64; 2],
    h: f64,
    tolerance: f64,
) -> f64 {
    let pred = |i: usize| q[i] + h * v[i] + 0.5 * h * h * a[i];
    let err = (r * (next[0] - pred(0)) - (next[1] - pred(1))).abs();
    err / tolerance.max(lag_resolution_at(r, next[0].abs().max(next[1].abs())))
}

/// Steps from `s` to `t_end` by `step` (the next state and its α-point),
/// calling `record` with the start (its own α-point) and after every
/// accepted step; the final state and the number of steps. `time` reads a
/// state's time.
pub fn run_until<S: Clone>(
    s: S,
    time: impl Fn(&S) -> f64,
    t_end: f64,
    mut step: impl FnMut(&S) -> Result<(S, S), SolverError>,
    mut record: impl FnMut(&S, &S) -> Result<(), SolverError>,
) -> Result<(S, usize), SolverError> {
    let mut s = s;
    record(&s, &s)?;
    let mut steps = 0;
    while time(&s) < t_end * (1.0 - 1e-12) {
        let (next, mid) = step(&s)?;
        s = next;
        record(&s, &mid)?;
        steps += 1;
    }
    Ok((s, steps))
}

/// [`lag_resolution`] for rotations up to `q_max` (rad) in magnitude.
pub fn lag_resolution_at(r: f64, q_max: f64) -> f64 {
    16.0 * (1.0 + r) * 1e-15 * (1.0 + q_max)
}

/// Solves the 1 × 1 or 2 × 2 system J x = b on the free coordinates.
fn solve_free(jac: [[f64; 2]; 2], b: [f64; 2], free: [bool; 2]) -> Option<[f64; 2]> {
    match free {
        [true, true] => {
            let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
            if det.abs() < f64::MIN_POSITIVE || !det.is_finite() {
                return None;
            }
            Some([
                (jac[1][1] * b[0] - jac[0][1] * b[1]) / det,
                (jac[0][0] * b[1] - jac[1][0] * b[0]) / det,
            ])
        }
        [true, false] => Some([b[0] / jac[0][0], 0.0]),
        [false, true] => Some([0.0, b[1] / jac[1][1]]),
        [false, false] => Some([0.0, 0.0]),
    }
}

/// Imposed coordinate of the driven member at t (absolute).
fn imposed_at(m: &Model, s0: &State, t: f64) -> Option<(usize, [f64; 3])> {
    m.imposed(t).map(|(i, [ang, w, a])| {
        let [ang_now, _, _] = m.imposed(s0.t).unwrap().1;
        (i, [s0.q[i] + ang - ang_now, w, a])
    })
}

const NEWTON_MAX: usize = 25;

/// Newton converges when the update is a few ulps of the coordinates.
fn converged(dx: [f64; 2], q: [f64; 2]) -> bool {
    dx[0].abs().max(dx[1].abs()) <= 1e-15 * (1.0 + q[0].abs().max(q[1].abs()))
}

/// Generalized-α step (Chung & Hulbert 1993): Newton on q_{n+1}.
fn alpha_step(m: &Model, s: &State, h: f64, rho: f64) -> Result<(State, usize), SolverError> {
    let am = (2.0 * rho - 1.0) / (rho + 1.0);
    let af = rho / (rho + 1.0);
    let gamma = 0.5 - am + af;
    let beta = 0.25 * (1.0 - am + af).powi(2);
    let free = m.drive.free();
    let t1 = s.t + h;
    // External torques at t_{n+1−α_f}.
    let ext = m.drive.torques(t1 - rho / (rho + 1.0) * h);
    let mut q = [0, 1].map(|i| s.q[i] + h * s.v[i] + 0.5 * h * h * s.a[i]);
    let fixed = imposed_at(m, s, t1);
    let kin = |q: [f64; 2]| -> ([f64; 2], [f64; 2]) {
        let mut a = [0.0; 2];
        let mut v = [0.0; 2];
        for i in 0..2 {
            a[i] = (q[i] - s.q[i] - h * s.v[i] - h * h * (0.5 - beta) * s.a[i]) / (beta * h * h);
            v[i] = s.v[i] + h * ((1.0 - gamma) * s.a[i] + gamma * a[i]);
        }
        if let Some((i, [_, w, acc])) = fixed {
            a[i] = acc;
            v[i] = w;
        }
        (v, a)
    };
    if let Some((i, [x, _, _])) = fixed {
        q[i] = x;
    }
    for it in 1..=NEWTON_MAX {
        let (v, a) = kin(q);
        let qm = [0, 1].map(|i| (1.0 - af) * q[i] + af * s.q[i]);
        let vm = [0, 1].map(|i| (1.0 - af) * v[i] + af * s.v[i]);
        let Contact {
            force: qc,
            stiffness: k,
            damping: d,
            ..
        } = m.contact(qm, vm)?;
        let mut res = [0.0; 2];
        let mut jac = [[0.0; 2]; 2];
        for i in 0..2 {
            let am_i = (1.0 - am) * a[i] + am * s.a[i];
            res[i] = m.inertia[i] * am_i - ext[i] - qc[i];
            for j in 0..2 {
                jac[i][j] = (1.0 - af) * (k[i][j] + d[i][j] * gamma / (beta * h));
            }
            jac[i][i] += m.inertia[i] * (1.0 - am) / (beta * h * h);
        }
        let dx =
            solve_free(jac, res.map(|x| -x), free).ok_or(SolverError::Singular { slices: 0 })?;
        for i in 0..2 {
            if free[i] {
                q[i] += dx[i];
            }
        }
        if converged(dx, q) {
            let (v, a) = kin(q);
            return Ok((State { t: t1, q, v, a }, it));
        }
    }
    Err(SolverError::NotConverged {
        what: "generalized-α Newton".into(),
        iterations: NEWTON_MAX,
    })
}

/// Symmetrized coordinate-wise discrete gradient of V between q and q'
/// (Itoh & Abe 1988, averaged over both coordinate orders): with the
/// corners c₁ = (q₁', q₂) and c₂ = (q₁, q₂'),
///
///   ḡ₁ = ½ [(V(c₁) − V(q)) + (V(q') − V(c₂))] / (q₁' − q₁),
///   ḡ₂ = ½ [(V(c₂) − V(q)) + (V(q') − V(c₁))] / (q₂' − q₂),
///
/// so that ḡ · (q' − q) = V(q') − V(q) exactly (the scheme conserves
/// energy) and ḡ is the gradient at the midpoint to second order in the
/// step. One order alone (c₁ only) evaluates ḡ₂ at q₁' instead of the
/// midpoint: a torque error of ½ ∂²V/∂q₁∂q₂ Δq₁ that grows with step and
/// speed (11 % of the wheel torque at 300 N·m, 1,000 rpm and 1.4 µs steps
/// on the white-paper pair). A coordinate that does not move takes
/// `g_mid`, the gradient at the midpoint, and the other the rest of the
/// change of V, so that the identity stays exact.
pub fn discrete_gradient(
    m: &Model,
    q: [f64; 2],
    qn: [f64; 2],
    g_mid: [f64; 2],
) -> Result<[f64; 2], SolverError> {
    let v = |a: [f64; 2]| m.potential(a);
    let d = [qn[0] - q[0], qn[1] - q[1]];
    let moves = d.map(|x| x.abs() > 1e-10);
    if !moves[0] && !moves[1] {
        return Ok(g_mid);
    }
    let v0 = v(q)?;
    let change = v(qn)? - v0;
    // One coordinate (nearly) still: it takes the midpoint gradient and the
    // other the rest of the change, so that ḡ · Δq = ΔV stays exact.
    if !moves[0] {
        return Ok([g_mid[0], (change - g_mid[0] * d[0]) / d[1]]);
    }
    if !moves[1] {
        return Ok([(change - g_mid[1] * d[1]) / d[0], g_mid[1]]);
    }
    let (c1, c2) = (v([qn[0], q[1]])? - v0, v([q[0], qn[1]])? - v0);
    Ok([
        0.5 * (c1 + change - c2) / d[0],
        0.5 * (c2 + change - c1) / d[1],
    ])
}

/// Energy-conserving midpoint step: Newton on q_{n+1} with the midpoint tangent.
fn midpoint_step(m: &Model, s: &State, h: f64) -> Result<(State, usize), SolverError> {
    let free = m.drive.free();
    let t1 = s.t + h;
    // External torques at the midpoint.
    let ext = m.drive.torques(s.t + 0.5 * h);
    let fixed = imposed_at(m, s, t1);
    let mut q = [0, 1].map(|i| s.q[i] + h * s.v[i] + 0.5 * h * h * s.a[i]);
    if let Some((i, [x, _, _])) = fixed {
        q[i] = x;
    }
    let vel = |q: [f64; 2]| -> [f64; 2] {
        let mut v = [0, 1].map(|i| 2.0 * (q[i] - s.q[i]) / h - s.v[i]);
        if let Some((i, [_, w, _])) = fixed {
            v[i] = w;
        }
        v
    };
    for it in 1..=NEWTON_MAX {
        let v = vel(q);
        let qm = [0, 1].map(|i| 0.5 * (q[i] + s.q[i]));
        let vm = [0, 1].map(|i| 0.5 * (v[i] + s.v[i]));
        let Contact {
            force: qc,
            stiffness: k,
            damping: d,
            mesh,
            ..
        } = m.contact(qm, vm)?;
        let g = discrete_gradient(m, s.q, q, mesh.grad)?;
        let mut res = [0.0; 2];
        let mut jac = [[0.0; 2]; 2];
        for i in 0..2 {
            // Damping part of the midpoint forces, without the potential.
            let damp = qc[i] + mesh.grad[i];
            res[i] = m.inertia[i] * (v[i] - s.v[i]) / h - ext[i] + g[i] - damp;
            for j in 0..2 {
                jac[i][j] = 0.5 * k[i][j] + d[i][j] / h;
            }
            jac[i][i] += 2.0 * m.inertia[i] / (h * h);
        }
        let dx =
            solve_free(jac, res.map(|x| -x), free).ok_or(SolverError::Singular { slices: 0 })?;
        for i in 0..2 {
            if free[i] {
                q[i] += dx[i];
            }
        }
        if converged(dx, q) {
            let v = vel(q);
            let mut a = [0, 1].map(|i| (v[i] - s.v[i]) / h);
            if let Some((i, [_, _, acc])) = fixed {
                a[i] = acc;
            }
            return Ok((State { t: t1, q, v, a }, it));
        }
    }
    Err(SolverError::NotConverged {
        what: "energy-conserving midpoint Newton".into(),
        iterations: NEWTON_MAX,
    })
}
