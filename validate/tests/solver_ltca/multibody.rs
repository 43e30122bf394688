//! Multibody: the contact element as the force element between rigid
//! bodies (its potential, the quasi-static limit, energy).

use crate::fixture::{fixture, quasi_static_run, table_fine, table_sweep, INERTIA, TABLE_SLICES};
use geometry::generation::Side;
use geometry::pair::pinion_direction;
use solver::ltca::{assemble, geometry, mean_ptp, run, solve};
use solver::multibody::mesh_table::{MeshTable, TableSpec};
use solver::multibody::model::{interpolate, wheel_driven, Drive, Model, State};
use solver::multibody::time_step::{Integrator, Scheme, StepControl};

#[test]
fn mesh_potential_gradient_is_the_contact_elements_pinion_torque() {
    // Between the table's nodes: the pinion torque ∂V/∂q₁ of the potential
    // against the contact element solved directly under lag control.
    let f = fixture();
    let t = table_fine();
    let fp = f.g.side(Side::Drive);
    let tau = f.g.data.mesh_cycle();
    let (mut worst, mut sq, mut n): (f64, f64, usize) = (0.0, 0.0, 0);
    for k in 0..24 {
        let q1 = t.spec.step * (6.0 * k as f64 + 2.5);
        let phi = t.spec.start + t.spec.direction * q1;
        let g = geometry(fp, &f.rs, phi, tau, TABLE_SLICES);
        let a = assemble(&g, &f.pc, 0.0).unwrap();
        for target in [100.0, 300.0, 700.0] {
            let theta = solve(&a, target, None).unwrap().theta;
            let ms = t.state(q1, t.ratio * q1 - theta).unwrap();
            let e = (ms.grad[0] - target).abs() / target;
            worst = worst.max(e);
            sq += e * e;
            n += 1;
        }
    }
    let rms = (sq / n as f64).sqrt();
    eprintln!("|dV/dq1 - T1| / T1 between nodes: largest {worst:.3e}, rms {rms:.3e}");
    // Largest where a slice or tooth pair engages (a kink of T1 inside a cell).
    assert!(worst < 3e-3 && rms < 1e-3, "{worst} {rms}");
}

#[test]
fn wheel_torque_of_the_potential_is_the_pinion_torque_over_the_ratio() {
    // -dV/dq2 (the path integral of dT1/dθ) against T1/r within 1 %: the
    // torque ratio departs from r only by the TE's slope. The interpolated
    // fixed-frame force is non-zero and not purely axial.
    let f = fixture();
    let t = table_fine();
    let a2 = f.g.frames[1].axis();
    for k in [3usize, 40, 101] {
        let q1 = t.spec.step * k as f64;
        let theta = t.theta_lo() + 0.6 * (t.lags[t.lags.len() - 1] - t.theta_lo());
        let ms = t.state(q1, t.ratio * q1 - theta).unwrap();
        let fnorm = ms.force.iter().map(|c| c * c).sum::<f64>().sqrt();
        let axial = ms.force[0] * a2[0] + ms.force[1] * a2[1] + ms.force[2] * a2[2];
        assert!(fnorm > 0.0 && axial.abs() < fnorm);
        let wheel_torque = -ms.grad[1];
        let rel = (wheel_torque * t.ratio - ms.grad[0]).abs() / ms.grad[0];
        assert!(rel < 0.01, "torque ratio off by {rel}");
    }
}

#[test]
fn non_periodic_table_holds_the_potential_path_back_to_first_contact() {
    // A lightweight wheel's table is not periodic. At q₁ = 0 under a large
    // torque the potential's path starts (θ − θ_lo)/r before q₁, here many
    // steps: the table's lead-in must hold it, and ∂V/∂q₁ must still be the
    // contact element's pinion torque there.
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let tau = f.g.data.mesh_cycle();
    let ratio = f.g.data.members[0].teeth as f64 / f.g.data.members[1].teeth as f64;
    let spec = TableSpec {
        start: fp.roll_range[0] + 0.3 * tau,
        direction: pinion_direction(&f.g.data, Side::Drive),
        step: tau / 600.0,
        positions: 12,
        periodic: false,
        slices: TABLE_SLICES,
        lag_nodes: 48,
        torque_max_nm: 1000.0,
    };
    let t = MeshTable::build(fp, &f.rs, &f.pc, &f.g.frames[0], ratio, spec).unwrap();
    let reach = (t.lags[t.lags.len() - 1] - t.theta_lo()) / ratio / t.spec.step;
    eprintln!(
        "lead-in {} steps for a lag reach of {reach:.1} steps",
        t.lead
    );
    assert!(
        reach > 2.0 && t.lead as f64 >= reach,
        "{} < {reach}",
        t.lead
    );
    let (m, s) = wheel_driven(&t, INERTIA, 1.0, 900.0, 0.1, 0.0).unwrap();
    let g = geometry(fp, &f.rs, spec.start, tau, TABLE_SLICES);
    let a = assemble(&g, &f.pc, 0.0).unwrap();
    let theta = t.ratio * s.q[0] - s.q[1];
    let direct = solve(&a, 900.0, None).unwrap().theta;
    let ms = m.table.state(s.q[0], s.q[1]).unwrap();
    eprintln!(
        "q1 = 0 at 900 N m: lag {:.3} µrad (direct {:.3}), dV/dq1 {:.3} N m",
        theta * 1e6,
        direct * 1e6,
        ms.grad[0]
    );
    assert!((ms.grad[0] - 900.0).abs() < 1e-6 * 900.0);
    assert!(
        (theta - direct).abs() < 3e-3 * direct,
        "{theta} vs {direct}"
    );
}

#[test]
fn ten_rpm_multibody_te_matches_the_quasi_static_ltca() {
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let t = table_fine();
    let sw = table_sweep(t, 0.0);
    // 1 N·m: the light-load end, where the contact sits in the table's
    // fine band just above the unloaded TE.
    let torques = [1.0, 100.0, 300.0, 700.0];
    let ltca = run(fp, &f.rs, &f.pc, &sw, &torques).unwrap();
    for (i, &torque) in torques.iter().enumerate() {
        let mb = quasi_static_run(
            t,
            torque,
            1.0,
            Scheme::GeneralizedAlpha { rho_inf: 0.8 },
            0.0,
        );
        let te: Vec<f64> = ltca.iter().map(|p| p.loads[i].te).collect();
        let (_, ptp) = mean_ptp(&te);
        let worst = ltca
            .iter()
            .map(|p| (interpolate(&mb[0], &mb[1], p.rotation) - p.loads[i].te).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "{torque} N m: |TE_MB - TE_LTCA| <= {:.4} µrad, {:.2} % of the LTCA's ptp {:.3} µrad ({} steps)",
            worst * 1e6,
            100.0 * worst / ptp,
            ptp * 1e6,
            mb[0].len() - 1
        );
        assert!(
            worst < 0.01 * ptp,
            "{torque} N m: {:.2} % of ptp",
            100.0 * worst / ptp
        );
    }
}

#[test]
fn undamped_run_keeps_its_energy_over_ten_mesh_cycles() {
    // Both bodies free, constant pinion torque and the matching wheel torque,
    // started 20 % above the static lag at 300 rpm: the mesh vibrates while
    // the pair turns. Energy = kinetic + mesh potential − work of the torques.
    let t = table_fine();
    let m = Model {
        table: t,
        coast: None,
        inertia: INERTIA,
        damping: 0.0,
        friction: 0.0,
        drive: Drive::Free {
            pinion_torque: 300.0,
            wheel_torque: 300.0 / t.ratio,
        },
    };
    let mut s: State = m.static_state(0.0).unwrap();
    let w = 300.0 * std::f64::consts::PI / 30.0;
    let u0 = s.q[0] * t.ratio - s.q[1] - t.unloaded(0.0).unwrap()[0];
    s.q[1] -= 0.2 * u0;
    s.v = [w, w * t.ratio];
    let e0 = m.energy(&s).unwrap();
    let scale = 0.5 * (INERTIA[0] * w * w + INERTIA[1] * (w * t.ratio).powi(2))
        + t.state(s.q[0], s.q[1]).unwrap().potential;
    let mut integ = Integrator::new(
        Scheme::EnergyConserving,
        StepControl {
            max_step: 2e-5,
            min_step: 1e-10,
            tolerance: 1e-8,
        },
    );
    let t_end = 10.0 * t.span() / w;
    let mut worst: f64 = 0.0;
    let mut steps = 0;
    while s.t < t_end {
        s = integ.step(&m, &s, t_end).unwrap();
        worst = worst.max((m.energy(&s).unwrap() - e0).abs());
        steps += 1;
    }
    eprintln!(
        "energy drift {:.3e} of {:.4} J over {steps} steps ({} rejected)",
        worst / scale,
        scale,
        integ.rejected
    );
    assert!(s.q[0] > 9.0 * t.span());
    assert!(worst < 1e-6 * scale, "{:.3e}", worst / scale);
}
