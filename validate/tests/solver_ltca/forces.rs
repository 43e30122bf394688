//! The mesh forces on the bearings, the sliding velocity, and friction in
//! the LTCA and the multibody runs.

use crate::common;
use crate::fixture::{fixture, quasi_static_run, sweep, table_fine, table_sweep, INERTIA};
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use solver::element::slices::sliding_velocity;
use solver::ltca::{mean_ptp, run, Sweep};
use solver::multibody::mesh_table::MeshTable;
use solver::multibody::model::{interpolate, wheel_driven, Drive, Model};
use solver::multibody::time_step::Scheme;

/// The textbook mesh forces of a spiral bevel pair at the mean point
/// (e.g. ISO 10300 / Gleason): tangential F_t = T₁/r_m1 with r_m1 = R_m sin δ₁,
/// total normal force F_t/(cos α_n cos β_m), and axial thrusts
/// F_t/cos β_m · |tan α_n sin δ₁ ± sin β_m cos δ₁| on the pinion and
/// F_t/cos β_m · |tan α_n cos δ₁ ∓ sin β_m sin δ₁| on the wheel (shaft angle
/// 90°; the sign pair follows hand and sense of rotation). The rigid
/// bearings' force of the multibody element (the tabulated contact force),
/// averaged over a mesh cycle of quasi-static states, must match magnitude
/// and both thrusts of one sign pair within 5 % (the contact wanders about
/// the mean point).
#[test]
fn wheel_bearing_force_matches_the_textbook_bevel_gear_mesh_forces() {
    let f = fixture();
    let t = table_fine();
    let d = &f.g.data;
    let torque = 300.0;
    let (m, _) = wheel_driven(t, INERTIA, 1.0, torque, 0.1, 0.0).unwrap();
    let n = 48;
    let mut mean = [0.0; 3];
    for k in 0..n {
        let q1 = t.span() * k as f64 / n as f64;
        let theta = m.static_lag(q1).unwrap();
        let s = t.state(q1, t.ratio * q1 - theta).unwrap();
        for (m, f) in mean.iter_mut().zip(s.force) {
            *m += f / n as f64;
        }
    }
    let fv = nalgebra::Vector3::from(mean);
    let (delta1, beta) = (d.members[0].pitch_angle, d.spiral_angle);
    let alpha = d.pressure_angle[Side::Drive.index()];
    let ft = torque / (d.mean_cone_distance * delta1.sin());
    let normal = ft / (alpha.cos() * beta.cos());
    let (ta, sb) = (alpha.tan(), beta.sin());
    let variants = [1.0, -1.0].map(|s| {
        [
            ft / beta.cos() * (ta * delta1.sin() + s * sb * delta1.cos()).abs(),
            ft / beta.cos() * (ta * delta1.cos() - s * sb * delta1.sin()).abs(),
        ]
    });
    let thrust = [
        fv.dot(&f.g.frames[0].axis()).abs(),
        fv.dot(&f.g.frames[1].axis()).abs(),
    ];
    eprintln!(
        "|F| {:.1} N (textbook {normal:.1}); thrust pinion {:.1}, wheel {:.1} N (textbook {:.1}/{:.1} or {:.1}/{:.1})",
        fv.norm(),
        thrust[0],
        thrust[1],
        variants[0][0],
        variants[0][1],
        variants[1][0],
        variants[1][1]
    );
    assert!((fv.norm() / normal - 1.0).abs() < 0.05);
    let close = |v: [f64; 2]| (0..2).all(|i| (thrust[i] - v[i]).abs() < 0.05 * normal);
    assert!(
        variants.iter().any(|&v| close(v)),
        "thrusts {thrust:?} match neither sign pair {variants:?}"
    );
}

/// The pitch cones roll on each other: a flank point on the pitch cone
/// (d = 0) in conjugate contact lies on their line of tangency, where the
/// flanks do not slide. Everywhere else the sliding velocity lies in the
/// common tangent plane (the equation of meshing: equal normal velocities)
/// and grows with the distance from the pitch line.
#[test]
fn sliding_vanishes_on_the_pitch_line_and_lies_in_the_tangent_plane() {
    let mut p = common::white_paper().data;
    p.ease_off = Default::default();
    let g = PairGeometry::new(&p).unwrap();
    let fp = g.side(Side::Drive);
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    for l in [0.95, 1.0, 1.05].map(|f| f * g.data.mean_cone_distance) {
        let q = fp.pinion.at(l, 0.0).unwrap();
        let vs = sliding_velocity(fp, q.pos, q.pinion_roll);
        let rolling = q.pos[0].hypot(q.pos[1]);
        assert!(
            norm(vs) < 1e-9 * rolling,
            "L = {l}: sliding {:.3e} of the rolling speed",
            norm(vs) / rolling
        );
    }
    for i in 0..=6 {
        for k in 0..=6 {
            let q = fp.pinion.at_unit(i as f64 / 6.0, k as f64 / 6.0).unwrap();
            let vs = sliding_velocity(fp, q.pos, q.pinion_roll);
            let rolling = q.pos[0].hypot(q.pos[1]);
            let vn: f64 = (0..3).map(|c| vs[c] * q.normal[c]).sum();
            assert!(vn.abs() < 1e-9 * rolling, "normal sliding {vn:e}");
            if q.d.abs() > 1e-3 {
                assert!(norm(vs) > 0.02 * rolling, "d = {} m", q.d);
            }
        }
    }
}

/// With friction μ the pinion torque balance is Σ F (λ₁ + μ ℓ₁) = T₁, the
/// pair shares still add up to one, and the mesh loses power: efficiency
/// wheel torque · (z₁/z₂) / T₁ is one without friction (to the ease-off's
/// departure from conjugate levers) and 97–99.9 % at μ = 0.05, as measured
/// on spiral bevel gears.
#[test]
fn friction_enters_the_torque_balance_and_costs_efficiency() {
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let ratio = f.g.data.members[0].teeth as f64 / f.g.data.members[1].teeth as f64;
    let efficiency = |mu: f64| {
        let sw = Sweep {
            friction: mu,
            ..sweep(f, 12, 30)
        };
        let res = run(fp, &f.rs, &f.pc, &sw, &[300.0]).unwrap();
        let mut eta = Vec::new();
        for p in &res {
            let l = &p.loads[0];
            let share: f64 = l.pair_share.iter().sum();
            assert!((share - 1.0).abs() < 1e-9, "shares add up to {share}");
            eta.push(l.wheel_torque_nm * ratio / 300.0);
        }
        (eta, res)
    };
    let (eta0, dry) = efficiency(0.0);
    let (eta, wet) = efficiency(0.05);
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    eprintln!(
        "efficiency: {:.5} frictionless, {:.5} at mu = 0.05; mean TE {:.3} vs {:.3} urad",
        mean(&eta0),
        mean(&eta),
        mean(&dry.iter().map(|p| p.loads[0].te).collect::<Vec<_>>()) * 1e6,
        mean(&wet.iter().map(|p| p.loads[0].te).collect::<Vec<_>>()) * 1e6,
    );
    for e in &eta0 {
        assert!((e - 1.0).abs() < 2e-3, "frictionless efficiency {e}");
    }
    assert!(mean(&eta) > 0.97 && mean(&eta) < 0.999);
    // Position by position.
    for (a, b) in eta0.iter().zip(&eta) {
        assert!(b < a, "friction cannot raise the efficiency: {b} vs {a}");
    }
}

/// The fine table, μ = 0.05, the LTCA with that friction at 300 N·m over
/// the table's sweep and its TE peak-to-peak.
fn ltca_with_friction() -> (
    &'static MeshTable,
    f64,
    Vec<solver::ltca::PositionResult>,
    f64,
) {
    let f = fixture();
    let t = table_fine();
    let mu = 0.05;
    let ltca = run(
        f.g.side(Side::Drive),
        &f.rs,
        &f.pc,
        &table_sweep(t, mu),
        &[300.0],
    )
    .unwrap();
    let te: Vec<f64> = ltca.iter().map(|p| p.loads[0].te).collect();
    let (_, ptp) = mean_ptp(&te);
    (t, mu, ltca, ptp)
}

/// The 10 rpm multibody run with friction (tabulated friction moments,
/// smoothed sign of the pinion speed) against the quasi-static LTCA with
/// the same friction coefficient: TE within 1 % of its peak-to-peak.
#[test]
fn ten_rpm_multibody_with_friction_matches_the_ltca_with_friction() {
    let (t, mu, ltca, ptp) = ltca_with_friction();
    let mb = quasi_static_run(t, 300.0, 1.0, Scheme::GeneralizedAlpha { rho_inf: 0.8 }, mu);
    let worst = ltca
        .iter()
        .map(|p| (interpolate(&mb[0], &mb[1], p.rotation) - p.loads[0].te).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "mu = {mu}: |TE_MB - TE_LTCA| <= {:.4} urad, {:.2} % of ptp {:.3} urad",
        worst * 1e6,
        100.0 * worst / ptp,
        ptp * 1e6
    );
    assert!(worst < 0.01 * ptp);
}

/// The run-up's quasi-static reference (pinion speed imposed, the wheel
/// loaded): with friction, the lag that balances the wheel's load is the
/// LTCA's at the pinion torque that delivers that wheel torque (the LTCA
/// at 300 N·m gives both). Within 1 % of the TE's peak-to-peak, as the
/// 10 rpm runs.
#[test]
fn wheel_loaded_quasi_static_lag_with_friction_is_the_ltcas() {
    let (t, mu, ltca, ptp) = ltca_with_friction();
    let mut worst: f64 = 0.0;
    for p in &ltca {
        let m = Model {
            table: t,
            coast: None,
            inertia: INERTIA,
            damping: 0.0,
            friction: mu,
            drive: Drive::PinionSpeed {
                speed: solver::multibody::model::Ramp {
                    from: 1.0,
                    to: 1.0,
                    duration: 0.0,
                },
                wheel_torque: p.loads[0].wheel_torque_nm,
            },
        };
        let theta = m.static_lag(p.rotation).unwrap();
        worst = worst.max((theta - p.loads[0].te).abs());
    }
    eprintln!(
        "wheel-loaded static lag vs LTCA: {:.4} urad, {:.2} % of ptp",
        worst * 1e6,
        100.0 * worst / ptp
    );
    assert!(worst < 0.01 * ptp);
}
