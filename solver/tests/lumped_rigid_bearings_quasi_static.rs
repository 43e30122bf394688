//! The lumped model's first verification: with the bearings rigid and no impact, the
//! 8-DOF model turning at 10 rpm has the transmission error of the
//! quasi-static LTCA, within 1 % of its peak-to-peak, at every LTCA
//! position (example 02's fixture: white-paper pair, standard blanks,
//! 300 N·m). TE of the model: (r₁θ₁ − r₂θ₂)/r₂, the wheel lag (rad).
//! The loaded-deflection series is fitted to 0.5 % of its peak-to-peak;
//! the second of two mesh cycles is compared (the first lets the start
//! transient of the torsional mode decay).

#[path = "support/fixture.rs"]
mod fixture;

use fixture::Fixture;

use solver::lumped::excitation::{MeshExcitation, StaticError};
use solver::lumped::from_ltca::{fit_series, mesh_samples, tangent_torques};
use solver::lumped::integrate::{integrate, Equations, Settings};
use solver::lumped::model::{direction_cosines, mesh_damping_for_ratio, Member, Model, WheelHand};

#[test]
fn lumped_rigid_bearings_at_10_rpm_give_the_quasi_static_ltca_te_within_1_percent_of_ptp() {
    let f = Fixture::example_02();
    let g = &f.g;
    let torque = 300.0;
    let res = f.ltca(&tangent_torques(torque));
    let omega = 10.0 * std::f64::consts::PI / 30.0;
    let s = mesh_samples(&res, torque, omega, g.data.mesh_cycle()).unwrap();
    let [k, _, d] = fit_series(&s, 0.005).unwrap();
    assert!(d.met, "deflection series: {:?}", d.max_residual_of_ptp);
    let member = |m: f64, j: f64| Member {
        mass_kg: m,
        inertia_kgm2: j,
        bearing_stiffness_n_per_m: [1e9; 3],
        bearing_damping_ns_per_m: [0.0; 3],
    };
    let mut model = Model {
        members: [member(2.0, 2e-3), member(10.0, 0.1)],
        direction: direction_cosines(
            g.data.pressure_angle[0],
            g.data.spiral_angle,
            g.data.members[1].pitch_angle,
            WheelHand::Left,
            geometry::generation::Side::Drive,
        ),
        levers_m: s.levers_m,
        mesh_damping_ns_per_m: 0.0,
        pinion_torque_nm: torque,
    };
    model.mesh_damping_ns_per_m =
        mesh_damping_for_ratio(0.1, k.series.mean, model.equivalent_mass());
    let exc = MeshExcitation {
        stiffness: k.series.clone(),
        transmission_error: StaticError::LoadedDeflection {
            deflection: d.series.clone(),
            force_n: model.mean_mesh_force(),
        },
        impact: None,
        friction: None,
    };
    let eq = Equations::new(&model, &exc).rigid_bearings();
    let [r1, r2] = s.levers_m;
    let lambda0 = model.mean_mesh_force() / exc.stiffness.value(0.0);
    let mut y0 = [0.0; 16];
    y0[3] = (lambda0 + exc.te(0.0)[0]) / r1;
    let period = s.period_s;
    let w = (k.series.mean / model.equivalent_mass()).sqrt();
    let mut atol = [1e-9 * 1e-6; 16];
    for a in atol.iter_mut().skip(8) {
        *a = 1e-9 * 1e-6 * w;
    }
    let times: Vec<f64> = s.time_s.iter().map(|t| period + t).collect();
    let sol = integrate(
        &eq,
        y0,
        &Settings {
            t_span_s: [0.0, 2.0 * period],
            output_step_s: period / 720.0,
            rtol: 1e-9,
            atol,
            max_step_s: 1.0 / w,
            max_steps: 10_000_000,
        },
    )
    .unwrap();
    let te_model = |t: f64| {
        // Samples every period/720; the LTCA positions fall on them (1° of an 18° cycle = 40 samples).
        let i = sol
            .t
            .iter()
            .position(|x| (x - t).abs() < 1e-9 * period)
            .unwrap_or_else(|| panic!("no sample at {t}"));
        let q = &sol.q[i];
        assert!(q[0] == 0.0 && q[5] == 0.0, "translations moved");
        (r1 * q[3] - r2 * q[7]) / r2
    };
    let (lo, hi) = s
        .loaded_te_rad
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let worst = times
        .iter()
        .zip(&s.loaded_te_rad)
        .map(|(t, te)| (te_model(*t) - te).abs())
        .fold(0.0f64, f64::max);
    eprintln!(
        "LTCA TE ptp {:.3} µrad, largest difference {:.4} µrad = {:.3} % of ptp ({} deflection harmonics)",
        (hi - lo) * 1e6,
        worst * 1e6,
        100.0 * worst / (hi - lo),
        d.series.harmonics()
    );
    assert!(worst < 0.01 * (hi - lo), "{worst:e} rad of {:e}", hi - lo);
}
