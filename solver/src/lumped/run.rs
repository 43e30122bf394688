//! A loaded run of the model: its static start and integration settings.

use super::excitation::MeshExcitation;
use super::integrate::{integrate, Equations, History, Settings};
use super::model::Model;
use super::LumpedError;

/// Static equilibrium at t = 0 with k(0), e(0): the mesh carries
/// F₀ = T₁/r₁ (with friction T₁/(r₁ + μg₄(0)), the pinion's balance), the
/// bearings the mesh and friction forces (−a F₀ − μF₀ g)/k_b on the pinion
/// and (+a F₀ − μF₀ g)/k_b on the wheel, λ = F₀/k(0), θ₂ = 0 and θ₁ from λ;
/// velocities zero.
pub fn static_start(model: &Model, exc: &MeshExcitation) -> Result<[f64; 16], LumpedError> {
    let (mu, g) = exc
        .friction
        .as_ref()
        .map_or((0.0, [0.0; 8]), |f| (f.coefficient, f.at(0.0)));
    let f0 = model.pinion_torque_nm / (model.levers_m[0] + mu * g[3]);
    let k0 = exc.stiffness.value(0.0);
    if k0.is_nan() || k0 <= 0.0 {
        return Err(LumpedError::Input(format!(
            "mesh stiffness at t = 0 is {k0} N/m: must be > 0"
        )));
    }
    let mut y = [0.0; 16];
    let a = model.direction;
    let mut along = 0.0;
    for d in 0..3 {
        let kp = model.members[0].bearing_stiffness_n_per_m[d];
        let kw = model.members[1].bearing_stiffness_n_per_m[d];
        if !(kp > 0.0 && kw > 0.0) {
            return Err(LumpedError::Input(
                "a static start needs bearing stiffness > 0 in every direction".into(),
            ));
        }
        y[d] = (-a[d] - mu * g[d]) * f0 / kp;
        y[4 + d] = (a[d] - mu * g[4 + d]) * f0 / kw;
        along += a[d] * (y[d] - y[4 + d]);
    }
    let lambda = f0 / k0;
    y[3] = (lambda + exc.te(0.0)[0] - along) / model.levers_m[0];
    Ok(y)
}

/// Settings for `mesh_cycles` at `mesh_hz` with `samples` per cycle and
/// relative tolerance `rtol`; absolute tolerances rtol × the scale of each
/// component (the static mesh deflection δ = F₀/kₘ, 1 µm at no load, over
/// the levers for the rotations, times 2π f_mesh for the velocities). The
/// step is kept below a quarter of an impact pulse and below 1/ω_max (ω_max
/// the highest natural frequency at the largest k): Dormand–Prince's
/// stability bound is h ω ≈ 3.3, and steps held at that bound by an
/// unexcited fast mode would end the run as "stiff".
pub fn settings(
    model: &Model,
    exc: &MeshExcitation,
    mesh_hz: f64,
    mesh_cycles: f64,
    samples: usize,
    rtol: f64,
) -> Settings {
    let period = 1.0 / mesh_hz;
    let d = match model.mean_mesh_force() / exc.stiffness.mean {
        x if x > 0.0 && x.is_finite() => x,
        _ => 1e-6,
    };
    let w = 2.0 * std::f64::consts::PI * mesh_hz;
    let mut atol = [0.0; 16];
    for i in 0..8 {
        let s = match i {
            3 => d / model.levers_m[0],
            7 => d / model.levers_m[1],
            _ => d,
        };
        atol[i] = rtol * s;
        atol[8 + i] = rtol * s * w;
    }
    let k_max = exc.stiffness.mean + exc.stiffness.amplitudes().iter().sum::<f64>();
    let w_max = model
        .natural_frequencies(k_max)
        .last()
        .map_or(0.0, |f| 2.0 * std::f64::consts::PI * f);
    let mut max_step = match exc.impact {
        Some(p) => 0.25 * p.duration_s,
        None => 0.05 * period,
    };
    if w_max > 0.0 {
        max_step = max_step.min(1.0 / w_max);
    }
    Settings {
        t_span_s: [0.0, mesh_cycles * period],
        output_step_s: period / samples as f64,
        rtol,
        atol,
        max_step_s: max_step,
        max_steps: 50_000_000,
    }
}

/// Integrates `mesh_cycles` from the static start.
pub fn simulate(
    model: &Model,
    exc: &MeshExcitation,
    mesh_hz: f64,
    mesh_cycles: f64,
    samples: usize,
    rtol: f64,
) -> Result<History, LumpedError> {
    model.check()?;
    let s = settings(model, exc, mesh_hz, mesh_cycles, samples, rtol);
    check_step_budget(&s, mesh_hz, mesh_cycles)?;
    let y0 = static_start(model, exc)?;
    let eq = Equations::new(model, exc);
    integrate(&eq, y0, &s)
}

/// Refuses, before integrating, a run that cannot finish within its step
/// budget: the span over the largest step (set by the mesh period, the
/// impact pulse and the highest natural frequency) is a lower bound on the
/// steps. A very low speed stretches the span while the stiff bearing and
/// mesh modes keep the step small.
pub fn check_step_budget(s: &Settings, mesh_hz: f64, mesh_cycles: f64) -> Result<(), LumpedError> {
    let span = s.t_span_s[1] - s.t_span_s[0];
    let fewest = span / s.max_step_s;
    if fewest > s.max_steps as f64 {
        return Err(LumpedError::Input(format!(
            "{mesh_cycles} mesh cycles at {mesh_hz:.4} Hz span {span:.4e} s, and the largest step is {:.3e} s (the highest natural frequency, mesh period and impact pulse allow no more): at least {fewest:.3e} steps, beyond the budget of {:e}; raise the pinion speed or integrate fewer mesh cycles",
            s.max_step_s, s.max_steps as f64
        )));
    }
    Ok(())
}
