//! The multibody with compliant bearings ([`solver::multibody::compliant`])
//! on the checked-in example-02 stiffness fixture (no gmsh): the map of the
//! members' displacements onto the contact coordinates against finite poses,
//! the rigid-bearing limit against today's multibody, a slow run against the
//! quasi-static LTCA on the deflected poses ([`solver::bearings::system_deflection`]),
//! and the balance of bearing forces, mesh wrench and inertia every step.

#[path = "support/compliant.rs"]
mod compliant;
#[path = "support/fixture.rs"]
mod fixture;

use compliant::{bodies, supports, Compliant};
use geometry::misalignment::{BodyPoses, Misalignment, Pose};
use nalgebra::{Rotation3, Vector3, Vector6};
use solver::bearings::relative_twist::TwistMap;
use solver::bearings::system_deflection::{
    deflected_position, displacement_pose, DeflectionSettings,
};
use solver::multibody::compliant::{
    integrate as c_integrate, CState, CompliantIntegrator, CompliantModel,
};
use solver::multibody::model::{wheel_driven, Model};
use solver::multibody::time_step::{integrate, Integrator, Scheme, StepControl};
use std::f64::consts::PI;

const TORQUE_NM: f64 = 300.0;
/// The white paper's quasi-static wheel speed, rad/s.
const WHEEL_10_RPM: f64 = 10.0 * PI / 30.0;

fn rotation_about(axis: Vector3<f64>, angle: f64) -> Pose {
    Pose {
        rotation: *Rotation3::new(axis * angle).matrix(),
        translation: Vector3::zeros(),
    }
}

/// Largest difference of two poses: rotation entries, and translation over 0.1 m.
fn pose_gap(a: &Pose, b: &Pose) -> f64 {
    (a.rotation - b.rotation)
        .amax()
        .max((a.translation - b.translation).amax() / 0.1)
}

#[test]
fn small_displacements_map_onto_member_turns_and_misalignments_as_finite_poses_compose() {
    let f = fixture::Fixture::example_02();
    let g = &f.g;
    let (a1, a2) = (g.frames[0].axis(), g.frames[1].axis());
    let dir = f.sweep.direction;
    let hand = geometry::generation::trace_sign(g.data.members[0].hand);
    let map = TwistMap::new(a1, a2, dir, hand);
    // Arbitrary displacements of both members (translations m, rotations rad).
    let d1 = Vector6::new(3.0, -2.0, 1.5, 0.7, -1.1, 0.4);
    let d2 = Vector6::new(-1.0, 2.5, 0.5, -0.3, 0.9, -0.6);
    let mut gaps = Vec::new();
    for eps in [1e-5, 0.5e-5] {
        let (p, w) = (d1 * eps, d2 * eps);
        let c = map.of_displacements(&p, &w);
        let pose = |d: &Vector6<f64>| {
            displacement_pose(&solver::bearings::support::Displacement {
                translation: Vector3::new(d[0], d[1], d[2]),
                rotation: Vector3::new(d[3], d[4], d[5]),
            })
        };
        let moved = BodyPoses {
            pinion: pose(&p),
            wheel: pose(&w),
        }
        .relative();
        // The same relative pose from the contact coordinates: the pinion
        // turned by d δq₁ about a₁, placed by (E, P, G, ΔΣ), seen from the
        // wheel turned by −d δq₂ about a₂.
        let m = Misalignment {
            offset_mm: c[2] * 1e3,
            pinion_axial_mm: c[3] * 1e3,
            wheel_axial_mm: c[4] * 1e3,
            shaft_angle_deg: c[5].to_degrees(),
        };
        let from_c = rotation_about(a2, dir * c[1])
            .after(&m.poses(&g.data).relative())
            .after(&rotation_about(a1, dir * c[0]));
        let gap = pose_gap(&moved, &from_c);
        eprintln!(
            "displacement scale {eps:e}: pose difference {gap:.3e} (first order {:.3e})",
            eps * 3.0
        );
        gaps.push(gap);
    }
    // Second order: the difference is O(ε²), far below the O(ε) a sign or
    // axis error would leave, and quarters when ε halves.
    assert!(gaps[0] < 1e-3 * 1e-5, "{gaps:?}");
    let ratio = gaps[0] / gaps[1];
    assert!((3.0..5.0).contains(&ratio), "halving ratio {ratio}");
}

/// The 10 rpm drive's rigid model of `c` at `torque`.
fn ten_rpm<'a>(c: &'a Compliant, zeta: f64) -> Model<'a> {
    wheel_driven(&c.table, c.inertia, WHEEL_10_RPM, TORQUE_NM, zeta, 0.0)
        .unwrap()
        .0
}

#[test]
fn very_stiff_bearings_give_the_rigid_bearing_multibody_te() {
    let c = Compliant::example_02(24, 600.0);
    let rigid = ten_rpm(&c, 0.05);
    let sup = supports(&c.f.g, 1e16);
    let cm = CompliantModel::new(rigid, &c.shift, bodies(&c.f.g, &sup, 0.0), c.hand).unwrap();
    // Fixed steps, the same in both runs, over half a mesh cycle.
    let h = 2e-4;
    let control = StepControl {
        max_step: h,
        min_step: h,
        tolerance: 1.0,
    };
    let t_end = 0.5 * c.table.span() / (WHEEL_10_RPM / c.ratio);
    let r = c.ratio;
    let mut te_rigid = Vec::new();
    let s0 = rigid.static_state(0.0).unwrap();
    let mut integ = Integrator::new(Scheme::GeneralizedAlpha { rho_inf: 0.8 }, control);
    integrate(&rigid, s0, &mut integ, t_end, |s| {
        te_rigid.push(r * s.q[0] - s.q[1]);
        Ok(())
    })
    .unwrap();
    let mut te = Vec::new();
    let mut most_d: f64 = 0.0;
    let cs0 = cm.static_state(0.0).unwrap();
    let mut ci = CompliantIntegrator::new(0.8, control);
    c_integrate(&cm, cs0, &mut ci, t_end, |s, _| {
        te.push(r * s.x[0] - s.x[1]);
        most_d = most_d.max(s.x.rows(2, 10).amax());
        Ok(())
    })
    .unwrap();
    assert_eq!(te.len(), te_rigid.len());
    let worst = te
        .iter()
        .zip(&te_rigid)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "{} steps: largest TE difference {:.3e} µrad, largest bearing coordinate {most_d:.3e}, TE {:.3}..{:.3} µrad",
        te.len(),
        worst * 1e6,
        te.iter().cloned().fold(f64::INFINITY, f64::min) * 1e6,
        te.iter().cloned().fold(f64::NEG_INFINITY, f64::max) * 1e6
    );
    assert!(worst < 1e-9, "largest TE difference {worst} rad");
}

/// A run of `cm` from its quasi-static start to `t_end` with step control;
/// the states and their α-points.
fn run(cm: &CompliantModel, t_end: f64, max_step: f64) -> Vec<(CState, CState)> {
    let s0 = cm.static_state(0.0).unwrap();
    let mut ci = CompliantIntegrator::new(
        0.8,
        StepControl {
            max_step,
            min_step: 1e-9,
            tolerance: 1e-9,
        },
    );
    let mut out = Vec::new();
    c_integrate(cm, s0, &mut ci, t_end, |s, mid| {
        out.push((*s, *mid));
        Ok(())
    })
    .unwrap();
    out
}

#[test]
fn slow_run_on_compliant_bearings_follows_the_quasi_static_ltca_on_the_deflected_poses() {
    let k = 1e9;
    let c = Compliant::example_02(32, 900.0);
    let rigid = ten_rpm(&c, 0.05);
    let sup = supports(&c.f.g, k);
    let mut cm = CompliantModel::new(rigid, &c.shift, bodies(&c.f.g, &sup, 5e3), c.hand).unwrap();
    if std::env::var("UNLOADED_SHIFT").is_ok() {
        cm.bearing_load = solver::multibody::compliant::BearingLoad::UnloadedShift;
    }
    let t_end = c.table.span() / (WHEEL_10_RPM / c.ratio);
    let states = run(&cm, t_end, 2e-4);
    let r = c.ratio;
    let mut g = c.f.g.clone();
    let mut worst_te: f64 = 0.0;
    let mut least_added = f64::INFINITY;
    let mut worst_force: f64 = 0.0;
    for deg in [2.0, 5.0, 8.0, 11.0, 14.0] {
        let q1 = f64::to_radians(deg);
        // The step nearest q₁ (steps of 2e-4 s are 0.026° of pinion rotation).
        let (s, _) = states
            .iter()
            .min_by(|a, b| (a.0.x[0] - q1).abs().total_cmp(&(b.0.x[0] - q1).abs()))
            .unwrap();
        let q1 = s.x[0];
        let te = r * s.x[0] - s.x[1];
        let phi = c.f.sweep.start + c.f.sweep.direction * q1;
        let sd = deflected_position(
            &mut g,
            c.f.scene.scene.loaded_flank,
            &c.f.scene.scene.utca,
            &c.f.pc,
            &sup,
            None,
            phi,
            TORQUE_NM,
            DeflectionSettings {
                slices: c.f.scene.scene.ltca.slices,
                tolerance_m: 1e-11,
                max_iterations: 100,
            },
        )
        .unwrap();
        let added = sd.te - sd.te_rigid_bearings;
        if std::env::var("DIAGNOSE").is_ok() {
            // The model's TE on the LTCA's converged displacements: the
            // rigid loaded lag + s·m − (r δq₁ − δq₂).
            let dv = |d: &solver::bearings::support::Displacement| {
                Vector6::new(
                    d.translation.x,
                    d.translation.y,
                    d.translation.z,
                    d.rotation.x,
                    d.rotation.y,
                    d.rotation.z,
                )
            };
            let cc = cm.twist().of_displacements(&dv(&sd.pinion), &dv(&sd.wheel));
            let (sh, _) = c.shift.at(&c.table, q1).unwrap();
            let sm: f64 = (0..4).map(|i| sh[i] * cc[2 + i]).sum();
            let mm = [cc[2], cc[3], cc[4], cc[5]];
            let model_te = sd.te_rigid_bearings + sm - (r * cc[0] - cc[1]);
            let cm_c = cm
                .twist()
                .of_displacements(&cm.displacement(&s.x, 0), &cm.displacement(&s.x, 1));
            eprintln!(
                "  on the LTCA's displacements the model's TE is {:.3} µrad (LTCA {:.3}); m LTCA (µm, µm, µm, µrad) {:.2?}, run {:.2?}; nonlinearity estimate {:.3} µrad",
                model_te * 1e6,
                sd.te * 1e6,
                mm.map(|x| x * 1e6),
                [cm_c[2], cm_c[3], cm_c[4], cm_c[5]].map(|x| x * 1e6),
                c.shift.nonlinearity(&c.table, q1, &mm) * 1e6
            );
        }
        let fb = [
            cm.bearing_forces(&s.x, &s.v, 0),
            cm.bearing_forces(&s.x, &s.v, 1),
        ];
        let reference = [&sd.pinion_reactions, &sd.wheel_reactions];
        let scale = reference[0].iter().map(|f| f.norm()).fold(0.0, f64::max);
        let mut force_gap: f64 = 0.0;
        for m in 0..2 {
            for (a, b) in fb[m].iter().zip(reference[m]) {
                force_gap = force_gap.max((a - b).norm());
            }
        }
        eprintln!(
            "q1 {:.3}°: TE run {:.3} µrad, quasi-static LTCA {:.3} µrad (rigid bearings {:.3}, added {:.3}), difference {:.3} µrad; bearing forces: largest difference {:.1} N of {:.1} N; pinion apex moved {:.2} µm",
            q1.to_degrees(),
            te * 1e6,
            sd.te * 1e6,
            sd.te_rigid_bearings * 1e6,
            added * 1e6,
            (te - sd.te) * 1e6,
            force_gap,
            scale,
            sd.pinion.translation.norm() * 1e6
        );
        worst_te = worst_te.max((te - sd.te).abs());
        least_added = least_added.min(added.abs());
        worst_force = worst_force.max(force_gap / scale);
    }
    eprintln!(
        "largest TE difference {:.3} µrad against at least {:.3} µrad added by the bearings; largest bearing-force difference {:.2} % of the largest reaction",
        worst_te * 1e6,
        least_added * 1e6,
        worst_force * 100.0
    );
    assert!(
        worst_te < 0.1 * least_added,
        "TE difference {worst_te} rad against {least_added} rad added"
    );
    assert!(
        worst_force < 0.1,
        "bearing forces off by {:.2} %",
        worst_force * 100.0
    );
}

#[test]
fn bearing_forces_balance_the_mesh_wrench_and_the_inertia_forces_every_step() {
    let c = Compliant::example_02(24, 900.0);
    let sup = supports(&c.f.g, 5e8);
    // The pinion at 3,000 rpm against 300 N·m at the pinion (run-up speeds:
    // the bearings' inertia forces matter).
    let w1 = 3000.0 * PI / 30.0;
    let rigid = compliant::pinion_at(&c, 3000.0, TORQUE_NM);
    let cm = CompliantModel::new(rigid, &c.shift, bodies(&c.f.g, &sup, 2e3), c.hand).unwrap();
    let t_end = 1.5 * c.table.span() / w1;
    let states = run(&cm, t_end, 2e-6);
    let mut worst: f64 = 0.0;
    let mut inertia_share: f64 = 0.0;
    for (_, mid) in states.iter().skip(1) {
        let mesh = cm.mesh(&mid.x, &mid.v).unwrap();
        let w1 = cm.pinion_mesh_wrench(&mesh);
        for (k, wm) in [w1, -w1].into_iter().enumerate() {
            let mb = &cm.members[k];
            let m6 = mb.mass_matrix(cm.rigid.inertia[k]);
            let inertia = -(m6 * cm.displacement(&mid.a, k));
            let load = wm + inertia;
            let mut f = Vector3::new(load[0], load[1], load[2]);
            let mut m = Vector3::new(load[3], load[4], load[5]);
            for (b, r) in mb
                .support
                .bearings()
                .iter()
                .zip(cm.bearing_forces(&mid.x, &mid.v, k))
            {
                f += r;
                m += mb.support.arm_of(b).cross(&r);
            }
            // The moment about the shaft axis is the shaft's torque.
            let a = mb.support.axis();
            m -= a * a.dot(&m);
            let scale = Vector3::new(wm[0], wm[1], wm[2]).norm();
            let arm = mb
                .support
                .bearings()
                .iter()
                .fold(0.0_f64, |x, b| x.max(b.axial_position_m.abs()));
            worst = worst.max((f.norm() / scale).max(m.norm() / (scale * arm)));
            inertia_share =
                inertia_share.max(Vector3::new(inertia[0], inertia[1], inertia[2]).norm() / scale);
        }
    }
    eprintln!(
        "{} steps: largest relative imbalance {worst:.3e}; inertia forces up to {:.2} % of the mesh force",
        states.len(),
        inertia_share * 100.0
    );
    assert!(
        inertia_share > 1e-3,
        "the run does not exercise the inertia forces"
    );
    assert!(worst < 1e-9, "imbalance {worst}");
}

#[test]
fn tabulated_wrench_turns_the_pinion_with_the_tables_torque() {
    // The wrench on the wheel from the slices' points and normals, seen by
    // the twist map as a torque on the pinion's turn, against the torque
    // from the LTCA's levers (both interpolated alike).
    let c = Compliant::example_02(24, 600.0);
    let g = &c.f.g;
    let map = TwistMap::new(
        g.frames[0].axis(),
        g.frames[1].axis(),
        c.f.sweep.direction,
        c.hand,
    );
    let mut t = nalgebra::Matrix6::zeros();
    for k in 0..6 {
        let mut e = Vector6::zeros();
        e[k] = 1.0;
        t.set_column(k, &map.of_displacements(&e, &Vector6::zeros()));
    }
    let to_c = t.try_inverse().unwrap().transpose();
    let r = c.ratio;
    let mut worst: f64 = 0.0;
    for (q1_deg, load) in [
        (0.3, 0.2),
        (4.7, 0.5),
        (9.1, 0.9),
        (13.6, 0.35),
        (16.2, 0.7),
    ] {
        let q1 = f64::to_radians(q1_deg);
        let te0 = c.table.unloaded(q1).unwrap()[0];
        let top = c.table.lags[c.table.lags.len() - 1];
        let theta = te0 + load * (top - te0);
        let ms = c.table.state(q1, r * q1 - theta).unwrap();
        let w = c.table.wrench_state(q1, theta).unwrap();
        let fc = to_c * Vector6::from_fn(|k, _| w[k][0]);
        let rel = (fc[0] - ms.grad[0]).abs() / ms.grad[0].abs();
        eprintln!(
            "q1 {q1_deg}°, θ {:.1} µrad: pinion torque {:.6} N·m from the wrench, {:.6} N·m from the levers",
            theta * 1e6,
            fc[0],
            ms.grad[0]
        );
        assert!(ms.grad[0] > 10.0);
        worst = worst.max(rel);
    }
    assert!(worst < 1e-9, "relative difference {worst}");
}
