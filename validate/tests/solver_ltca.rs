//! The contact element and the quasi-static LTCA on the white-paper pair with
//! FE influence fields computed here on coarse meshes (6 × 10 elements per
//! refined flank, both members, standard blanks): the unloaded limit against
//! the UTCA, torque balance and complementarity, slice convergence, and the
//! assembled compliance.

mod fe_fixtures;
use fe_fixtures as common;

use geometry::design::Member;
use geometry::generation::Side;
use geometry::pair::{pinion_direction, teeth_in_contact, PairGeometry};
use geometry::utca::{LineGrid, RollSurface};
use solver::element::compliance::PairCompliance;
use solver::element::slices::sliding_velocity;
use solver::ltca::{assemble, geometry, mean_ptp, run, solve, Sweep};
use std::sync::OnceLock;

struct Fixture {
    g: PairGeometry,
    rs: RollSurface,
    pc: PairCompliance,
}

fn member(
    g: &PairGeometry,
    m: Member,
    refined: Vec<usize>,
) -> solver::element::compliance::MemberCompliance {
    let body = common::mesh(g, m, &refined, &[], "drive");
    common::compliance(g, &body, m, Side::Drive, refined[refined.len() / 2])
}

fn fixture() -> &'static Fixture {
    static F: OnceLock<Fixture> = OnceLock::new();
    F.get_or_init(|| {
        let g = common::white_paper();
        let (pt, wt) = teeth_in_contact(&g, Side::Drive, 2.0, 0.5f64.to_radians());
        let pc = PairCompliance {
            pinion: member(&g, Member::Pinion, pt),
            wheel: member(&g, Member::Wheel, wt),
        };
        let rs = RollSurface::new(
            g.side(Side::Drive),
            LineGrid {
                n_face: 41,
                n_profile: 41,
            },
        )
        .unwrap();
        Fixture { g, rs, pc }
    })
}

/// One mesh cycle in `n` steps from the entry of tooth 0.
fn sweep(f: &Fixture, n: usize, slices: usize) -> Sweep {
    let tau = f.g.data.mesh_cycle();
    Sweep {
        start: f.g.side(Side::Drive).roll_range[0],
        step: tau / n as f64,
        direction: pinion_direction(&f.g.data, Side::Drive),
        positions: n,
        slices,
        friction: 0.0,
    }
}

#[test]
fn vanishing_torque_reproduces_the_unloaded_te() {
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let sw = sweep(f, 12, 30);
    let res = run(fp, &f.rs, &f.pc, &sw, &[1e-3]).unwrap();
    // The UTCA's own sweep over the same angles (preprocess, independent of the slices).
    let utca = geometry::utca::run(fp, &f.rs, sw.start, sw.step, sw.positions, sw.direction);
    let mut worst: f64 = 0.0;
    for (p, te0) in res.iter().zip(&utca.te) {
        assert!(
            (p.utca_te - te0).abs() < 1e-12,
            "slices' UTCA {} vs {}",
            p.utca_te,
            te0
        );
        worst = worst.max((p.loads[0].te - te0).abs());
    }
    eprintln!("largest |TE(1e-3 N m) - TE_UTCA| = {:.4} µrad", worst * 1e6);
    assert!(worst < 0.01e-6, "{} µrad", worst * 1e6);
}

#[test]
fn slice_forces_balance_the_pinion_torque_and_are_complementary_to_the_gaps() {
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let tau = f.g.data.mesh_cycle();
    let sw = sweep(f, 6, 30);
    for k in 0..sw.positions {
        let phi = sw.start + sw.direction * sw.step * k as f64;
        let g = geometry(fp, &f.rs, phi, tau, 30);
        let a = assemble(&g, &f.pc, 0.0).unwrap();
        for torque in [100.0, 700.0] {
            let s = solve(&a, torque, None).unwrap();
            // Levers recomputed from the slice points: |(r × n)·z|.
            let moment: f64 = g
                .slices
                .iter()
                .zip(&s.force)
                .map(|(sl, &fk)| fk * (sl.pos[0] * sl.normal[1] - sl.pos[1] * sl.normal[0]).abs())
                .sum();
            assert!(
                ((moment - torque) / torque).abs() < 1e-9,
                "position {k}: {moment} vs {torque}"
            );
            let n = g.slices.len();
            let fmax = s.force.iter().copied().fold(0.0, f64::max);
            for i in 0..n {
                assert!(s.force[i] >= 0.0);
                let gap = g.slices[i].lever_wheel * (g.slices[i].lag - s.theta)
                    + (0..n)
                        .map(|j| a.compliance[i * n + j] * s.force[j])
                        .sum::<f64>()
                    + a.line[i].approach(s.force[i]);
                assert!(gap > -1e-12, "position {k}, slice {i}: gap {gap:e}");
                if s.force[i] > 1e-9 * fmax {
                    assert!(gap.abs() < 1e-11, "loaded slice {i} open by {gap:e}");
                }
            }
        }
    }
}

#[test]
fn mean_te_changes_less_than_half_a_percent_when_the_slices_double() {
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let torques = [100.0, 300.0, 700.0];
    let te = |slices: usize| {
        let res = run(fp, &f.rs, &f.pc, &sweep(f, 18, slices), &torques).unwrap();
        (0..torques.len())
            .map(|i| mean_ptp(&res.iter().map(|p| p.loads[i].te).collect::<Vec<_>>()))
            .collect::<Vec<_>>()
    };
    let (a, b) = (te(30), te(60));
    for (i, t) in torques.iter().enumerate() {
        let rel = (a[i].0 - b[i].0).abs() / b[i].0;
        eprintln!(
            "{t} N m: mean TE {:.3} / {:.3} µrad ({:.3} %), ptp {:.3} / {:.3} µrad",
            a[i].0 * 1e6,
            b[i].0 * 1e6,
            rel * 100.0,
            a[i].1 * 1e6,
            b[i].1 * 1e6
        );
        assert!(rel < 0.005, "{t} N m: {:.3} %", rel * 100.0);
    }
}

#[test]
fn slice_compliance_is_symmetric_positive_definite_and_load_sharing_adds_up() {
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let tau = f.g.data.mesh_cycle();
    let phi = fp.roll_range[0] + 0.3 * tau * pinion_direction(&f.g.data, Side::Drive);
    let g = geometry(fp, &f.rs, phi, tau, 30);
    let a = assemble(&g, &f.pc, 0.0).unwrap();
    let n = g.slices.len();
    let pairs: std::collections::BTreeSet<i32> = g.slices.iter().map(|s| s.pair).collect();
    assert!(pairs.len() >= 2, "pairs {pairs:?}");
    let m = nalgebra::DMatrix::from_row_slice(n, n, &a.compliance);
    assert!((&m - m.transpose()).norm() <= 1e-14 * m.norm());
    assert!(
        m.clone().cholesky().is_some(),
        "C of {n} slices is not positive definite"
    );
    let s = solve(&a, 300.0, None).unwrap();
    let res = run(fp, &f.rs, &f.pc, &sweep(f, 6, 30), &[300.0]).unwrap();
    for p in &res {
        let share: f64 = p.loads[0].pair_share.iter().sum();
        assert!((share - 1.0).abs() < 1e-9, "shares add to {share}");
    }
    assert!(s.theta > g.utca_te);
}

#[test]
fn relative_curvature_from_the_separation_field_matches_the_flanks_principal_curvatures() {
    // The slices take ρ from the second derivative of the model's own gap
    // along the profile; compare with κ₁(t) + κ₂(t) from the two generated
    // flanks' principal curvatures across the contact line.
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let tau = f.g.data.mesh_cycle();
    let phi = fp.roll_range[0] + 1.4 * tau * pinion_direction(&f.g.data, Side::Drive);
    let g = geometry(fp, &f.rs, phi, tau, 30);
    let lag_min = g.slices.iter().map(|s| s.lag).fold(f64::INFINITY, f64::min);
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    for w in g.slices.windows(3) {
        let [a, s, b] = [&w[0], &w[1], &w[2]];
        // Slices of one pair near its contact (within 60 µrad of touching).
        if a.pair != s.pair || b.pair != s.pair || s.lag > lag_min + 60e-6 || s.rho >= 0.999 {
            continue;
        }
        let line = [
            b.pos[0] - a.pos[0],
            b.pos[1] - a.pos[1],
            b.pos[2] - a.pos[2],
        ];
        let p = fp.pinion.eval_uv(s.uv[0], s.uv[1]);
        let k_geo = solver::element::slices::geometric_curvature(fp, &p, line);
        let rel = (1.0 / s.rho - k_geo).abs() / k_geo;
        worst = worst.max(rel);
        checked += 1;
    }
    eprintln!(
        "{checked} slices, largest relative difference {:.2} %",
        worst * 100.0
    );
    assert!(checked >= 8, "only {checked} slices near contact");
    assert!(worst < 0.05, "{:.2} %", worst * 100.0);
}

// ---------------------------------------------------------------------------
// Multibody: the contact element as the force element between rigid bodies.

use solver::multibody::mesh_table::{MeshTable, TableSpec};
use solver::multibody::model::{interpolate, wheel_driven, Drive, Model, State};
use solver::multibody::time_step::{integrate, Integrator, Scheme, StepControl};

const TABLE_SLICES: usize = 20;
/// Polar moments of inertia of the test bodies, kg·m² (test values; the
/// stage computes the real ones from the body meshes).
const INERTIA: [f64; 2] = [2e-3, 2.5e-2];

/// One mesh cycle, periodic, `per_cycle` positions.
fn table(per_cycle: usize) -> MeshTable {
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let tau = f.g.data.mesh_cycle();
    let ratio = f.g.data.members[0].teeth as f64 / f.g.data.members[1].teeth as f64;
    MeshTable::build(
        fp,
        &f.rs,
        &f.pc,
        &f.g.frames[0],
        ratio,
        TableSpec {
            start: fp.roll_range[0],
            direction: pinion_direction(&f.g.data, Side::Drive),
            step: tau / per_cycle as f64,
            positions: per_cycle,
            periodic: true,
            slices: TABLE_SLICES,
            lag_nodes: 96,
            torque_max_nm: 1000.0,
        },
    )
    .unwrap()
}

/// 0.125° steps in q₁.
fn table_fine() -> &'static MeshTable {
    static T: OnceLock<MeshTable> = OnceLock::new();
    T.get_or_init(|| table(144))
}

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

/// TE (rad) against pinion rotation of a quasi-static run.
/// Pinion rotations and TE (rad) of a quasi-static run.
fn quasi_static_run(
    t: &MeshTable,
    torque: f64,
    cycles: f64,
    scheme: Scheme,
    friction: f64,
) -> [Vec<f64>; 2] {
    let wheel = 10.0 * std::f64::consts::PI / 30.0;
    let (m, s) = wheel_driven(t, INERTIA, wheel, torque, 0.1, friction).unwrap();
    let mut integ = Integrator::new(
        scheme,
        StepControl {
            max_step: 1e-3,
            min_step: 1e-9,
            tolerance: 1e-9,
        },
    );
    let t_end = cycles * t.span() / (wheel / t.ratio);
    let (mut q1, mut te) = (Vec::new(), Vec::new());
    integrate(&m, s, &mut integ, t_end, |s| {
        q1.push(s.q[0]);
        te.push(t.ratio * s.q[0] - s.q[1]);
        Ok(())
    })
    .unwrap();
    [q1, te]
}

/// The LTCA at 24 positions over the table's mesh cycle, with its slices.
fn table_sweep(t: &MeshTable, friction: f64) -> Sweep {
    Sweep {
        start: t.spec.start,
        step: t.span() / 24.0,
        direction: t.spec.direction,
        positions: 24,
        slices: TABLE_SLICES,
        friction,
    }
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
