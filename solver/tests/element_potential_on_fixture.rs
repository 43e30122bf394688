//! The tabulated contact element is conservative by construction: its
//! generalized forces are the gradient of one potential V(q₁, q₂) (a path
//! integral of the tabulated pinion torque) and its tangent is the Hessian.
//! Checked on the example-02 fixture's table (white-paper pair, standard
//! blanks) against central differences of V itself, and through the
//! energy-conserving scheme's wheel impulse: the torque the scheme applies
//! (its discrete gradient) must be the element's pointwise torque.

#[path = "support/fixture.rs"]
mod fixture;

use fixture::Fixture;
use solver::multibody::mesh_table::MeshTable;
use solver::multibody::model::{Drive, Model, Ramp};
use solver::multibody::time_step::{discrete_gradient, integrate, Integrator, Scheme, StepControl};

/// The fixture's table over one mesh cycle in 0.5° steps, up to 600 N·m.
fn table(f: &Fixture) -> MeshTable {
    f.table(0.5, 48, 600.0)
}

#[test]
fn element_gradient_and_hessian_equal_central_differences_of_its_potential() {
    let f = Fixture::example_02();
    let table = table(&f);
    let (tau, r) = (f.g.data.mesh_cycle(), table.ratio);
    let top = *table.lags.last().unwrap();
    let h = 1e-9;
    let (mut worst_grad, mut worst_hess) = (0.0f64, 0.0f64);
    for k in 0..37 {
        let q1 = k as f64 * tau / 37.0;
        let te0 = table.unloaded(q1).unwrap()[0];
        for frac in [0.02, 0.1, 0.3, 0.6, 0.9] {
            let q2 = r * q1 - (te0 + frac * (top - te0));
            let s = table.state(q1, q2).unwrap();
            let at = |a: f64, b: f64| table.state(a, b).unwrap();
            let fd = [
                (at(q1 + h, q2).potential - at(q1 - h, q2).potential) / (2.0 * h),
                (at(q1, q2 + h).potential - at(q1, q2 - h).potential) / (2.0 * h),
            ];
            let scale = s.grad[0].abs().max(1.0);
            for (d, g) in fd.iter().zip(s.grad) {
                worst_grad = worst_grad.max((d - g).abs() / scale);
            }
            let h22 = (at(q1, q2 + h).grad[1] - at(q1, q2 - h).grad[1]) / (2.0 * h);
            let h12 = (at(q1, q2 + h).grad[0] - at(q1, q2 - h).grad[0]) / (2.0 * h);
            let kscale = s.hess[1][1].abs().max(1.0);
            worst_hess = worst_hess.max((h22 - s.hess[1][1]).abs() / kscale);
            worst_hess = worst_hess.max((h12 - s.hess[0][1]).abs() / kscale);
        }
    }
    eprintln!("largest relative difference: gradient {worst_grad:.2e}, Hessian {worst_hess:.2e}");
    assert!(
        worst_grad < 1e-6,
        "gradient against central differences of V: {worst_grad:e}"
    );
    assert!(
        worst_hess < 1e-6,
        "Hessian against central differences of ∇V: {worst_hess:e}"
    );
}

/// One mesh cycle at 300 N·m, the pinion at a constant 1,000 rpm, the wheel
/// free (inertia chosen, 0.05 kg·m²), undamped: the wheel's impulse from the
/// scheme's discrete gradient balances its momentum exactly, and the
/// element's pointwise torque −∂V/∂q₂ at the step ends, trapezoid-integrated,
/// gives the same impulse. With Itoh–Abe's one-order discrete gradient
/// (ḡ₂ taken at the step's end q₁) the scheme applied a wheel torque 11 %
/// off the element's here (½ ∂²V/∂q₁∂q₂ Δq₁ per step).
#[test]
fn energy_conserving_scheme_applies_the_elements_wheel_torque() {
    let f = Fixture::example_02();
    let table = table(&f);
    let (tau, r) = (f.g.data.mesh_cycle(), table.ratio);
    let w1 = 1000.0 * std::f64::consts::PI / 30.0;
    let wheel_torque = 300.0 / r;
    let inertia = [1.5e-3, 5.0e-2];
    let m = Model {
        table: &table,
        coast: None,
        inertia,
        damping: 0.0,
        friction: 0.0,
        drive: Drive::PinionSpeed {
            speed: Ramp {
                from: w1,
                to: w1,
                duration: 0.0,
            },
            wheel_torque,
        },
    };
    let s = m.static_state(0.0).unwrap();
    let w2_0 = s.v[1];
    let t_end = tau / w1;
    let mut integ = Integrator::new(
        Scheme::EnergyConserving,
        StepControl {
            max_step: 1e-5,
            min_step: 1e-11,
            tolerance: 1e-12,
        },
    );
    let (mut scheme, mut pointwise) = (0.0, 0.0);
    let mut last: Option<(f64, [f64; 2], f64)> = None;
    let (end, steps) = integrate(&m, s, &mut integ, t_end, |s| {
        let g = m.mesh(s.q)?.0.grad[1];
        if let Some((t0, q0, g0)) = last {
            let mid = [0.5 * (s.q[0] + q0[0]), 0.5 * (s.q[1] + q0[1])];
            scheme -= discrete_gradient(&m, q0, s.q, m.mesh(mid)?.0.grad)?[1] * (s.t - t0);
            pointwise -= 0.5 * (g + g0) * (s.t - t0);
        }
        last = Some((s.t, s.q, g));
        Ok(())
    })
    .unwrap();
    let momentum = inertia[1] * (end.v[1] - w2_0) + wheel_torque * t_end;
    let scale = wheel_torque * t_end;
    eprintln!(
        "{steps} steps: wheel impulse {scheme:.6e} (scheme), {pointwise:.6e} (pointwise), momentum {momentum:.6e} N·m·s"
    );
    assert!((scheme - momentum).abs() < 1e-9 * scale);
    assert!(
        (pointwise - momentum).abs() < 1e-3 * scale,
        "pointwise {pointwise} against momentum {momentum}"
    );
}
