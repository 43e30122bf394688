//! The flexible gearbox ([`solver::gearbox`]) on the checked-in example-02
//! stiffness fixture (no gmsh): with rigid shafts and housing it runs as
//! the compliant-bearing multibody; with flexible shafts its quasi-static
//! start is the compliant model's on the statically condensed shafts, and
//! a slow run stays there while a fast one shows the shafts' inertia.

#[path = "support/compliant.rs"]
mod compliant;
#[path = "support/fixture.rs"]
mod fixture;

use compliant::{bodies, fixed, parts, supports, Compliant};
use fixture::supports_on_shafts;
use geometry::pair::PairGeometry;
use solver::bearings::flexible_shaft::Shaft;
use solver::gearbox::assemble;
use solver::gearbox::dynamics::{integrate, GState, GearboxIntegrator, GearboxModel};
use solver::gearbox::system_modes::system_modes;
use solver::multibody::compliant::{
    integrate as c_integrate, CState, CompliantIntegrator, CompliantModel, MemberBody,
};
use solver::multibody::time_step::{integrate as r_integrate, Integrator, Scheme};
use std::f64::consts::PI;

const TORQUE_NM: f64 = 300.0;
const DIAMETER_M: f64 = 0.03;

/// The shafts of `supports_on_shafts`: each gear at its mean point, a
/// solid shaft from there to its far bearing.
fn shafts(g: &PairGeometry, s: &[MemberBody; 2]) -> [Shaft; 2] {
    compliant::shafts_from_mean_points(g, s, DIAMETER_M)
}

/// The pinion at `rpm` against 300 N·m, mesh damping ratio 0.05.
fn pinion_at(c: &Compliant, rpm: f64) -> solver::multibody::model::Model<'_> {
    compliant::pinion_at(c, rpm, TORQUE_NM)
}

#[test]
fn rigid_shafts_on_a_rigid_housing_run_as_the_compliant_bearing_model() {
    let c = Compliant::example_02(24, 900.0);
    let sup = supports(&c.f.g, 5e8);
    let b = bodies(&c.f.g, &sup, 2e3);
    let cm = CompliantModel::new(pinion_at(&c, 3000.0), &c.shift, b.clone(), c.hand).unwrap();
    let s = assemble(parts(&b, c.inertia, None, 0.0), None, 0.01).unwrap();
    let gm = GearboxModel::new(&cm, &s).unwrap();
    let t_end = 1.5 * c.table.span() / (3000.0 * PI / 30.0);
    let h = 2e-6;
    let mut a: Vec<CState> = Vec::new();
    c_integrate(
        &cm,
        cm.static_state(0.0).unwrap(),
        &mut CompliantIntegrator::new(0.8, fixed(h)),
        t_end,
        |s, _| {
            a.push(*s);
            Ok(())
        },
    )
    .unwrap();
    let mut g: Vec<GState> = Vec::new();
    integrate(
        &gm,
        gm.static_state(0.0).unwrap(),
        &mut GearboxIntegrator::new(0.8, fixed(h)),
        t_end,
        |s, _| {
            g.push(s.clone());
            Ok(())
        },
    )
    .unwrap();
    assert_eq!(a.len(), g.len());
    let (mut worst_x, mut worst_f): (f64, f64) = (0.0, 0.0);
    for (sa, sg) in a.iter().zip(&g) {
        for i in 0..12 {
            let scale = if i < 2 { 1.0 } else { 1e-5 };
            worst_x = worst_x.max((sa.x[i] - sg.x[i]).abs() / scale);
        }
        let fa: Vec<_> = (0..2)
            .flat_map(|k| cm.bearing_forces(&sa.x, &sa.v, k))
            .collect();
        let fg = gm.bearing_forces(&sg.x, &sg.v);
        for (p, q) in fa.iter().zip(&fg) {
            // The compliant model gives the force on the member, the
            // gearbox the force on the seat.
            worst_f = worst_f.max((p + q).norm() / p.norm().max(1.0));
        }
    }
    eprintln!(
        "{} steps: largest coordinate difference {worst_x:.2e}, bearing force {worst_f:.2e}",
        a.len()
    );
    // Rounding: the two integrators sum in other orders (turns ~0.1 rad,
    // bearing coordinates ~1e-5 m, both to ~1e-8 of their size).
    assert!(worst_x < 1e-8 && worst_f < 1e-8, "{worst_x} {worst_f}");
}

/// With rigid shafts on a rigid housing and bearings of 1e14 N/m (the
/// scene's stiffest), the gearbox runs as the rigid-bearing multibody:
/// the same TE at every step (fixed steps, 1.5 mesh cycles at 3,000 rpm).
#[test]
fn very_stiff_bearings_give_the_rigid_bearing_multibody_te() {
    let c = Compliant::example_02(24, 900.0);
    let rigid = pinion_at(&c, 3000.0);
    let b = bodies(&c.f.g, &supports(&c.f.g, 1e14), 0.0);
    let cm = CompliantModel::new(rigid, &c.shift, b.clone(), c.hand).unwrap();
    let s = assemble(parts(&b, c.inertia, None, 0.0), None, 0.01).unwrap();
    let gm = GearboxModel::new(&cm, &s).unwrap();
    let t_end = 1.5 * c.table.span() / (3000.0 * PI / 30.0);
    let h = 2e-6;
    let r = c.ratio;
    let mut te_rigid = Vec::new();
    let mut ri = Integrator::new(Scheme::GeneralizedAlpha { rho_inf: 0.8 }, fixed(h));
    r_integrate(
        &rigid,
        rigid.static_state(0.0).unwrap(),
        &mut ri,
        t_end,
        |s| {
            te_rigid.push(r * s.q[0] - s.q[1]);
            Ok(())
        },
    )
    .unwrap();
    let mut te = Vec::new();
    integrate(
        &gm,
        gm.static_state(0.0).unwrap(),
        &mut GearboxIntegrator::new(0.8, fixed(h)),
        t_end,
        |s, _| {
            te.push(r * s.x[0] - s.x[1]);
            Ok(())
        },
    )
    .unwrap();
    assert_eq!(te.len(), te_rigid.len());
    let worst = te
        .iter()
        .zip(&te_rigid)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let size = te_rigid.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    eprintln!(
        "{} steps: largest TE difference {:.3e} µrad of {:.1} µrad",
        te.len(),
        worst * 1e6,
        size * 1e6
    );
    assert!(
        worst < 1e-4 * size,
        "largest TE difference {worst} rad of {size}"
    );
}

#[test]
fn flexible_shafts_start_where_the_condensed_shafts_support_the_gears() {
    let c = Compliant::example_02(24, 900.0);
    let flexible = supports_on_shafts(&c.f.g, 5e8, DIAMETER_M, 1.0);
    let condensed = bodies(&c.f.g, &flexible, 0.0);
    let cm_condensed =
        CompliantModel::new(pinion_at(&c, 10.0), &c.shift, condensed, c.hand).unwrap();
    let rigid = bodies(&c.f.g, &supports(&c.f.g, 5e8), 0.0);
    let sh = shafts(&c.f.g, &rigid);
    let cm = CompliantModel::new(pinion_at(&c, 10.0), &c.shift, rigid.clone(), c.hand).unwrap();
    let s = assemble(parts(&rigid, c.inertia, Some(&sh), 7850.0), None, 0.005).unwrap();
    let gm = GearboxModel::new(&cm, &s).unwrap();
    let want = cm_condensed.static_state(0.0).unwrap();
    let got = gm.static_state(0.0).unwrap();
    let mut worst: f64 = 0.0;
    for i in 0..12 {
        let scale = if i < 2 { 1.0 } else { 1e-5 };
        worst = worst.max((want.x[i] - got.x[i]).abs() / scale);
    }
    let te = |x: f64, y: f64| c.ratio * x - y;
    eprintln!(
        "static TE {:.4} against {:.4} µrad (rigid shafts {:.4}); largest coordinate difference {worst:.2e}",
        te(got.x[0], got.x[1]) * 1e6,
        te(want.x[0], want.x[1]) * 1e6,
        {
            let r = cm.static_state(0.0).unwrap();
            te(r.x[0], r.x[1]) * 1e6
        }
    );
    assert!(worst < 1e-9, "{worst}");

    // The loaded modes: the shafts' mass brings modes with shaft energy.
    let mesh = cm
        .mesh(
            &solver::multibody::compliant::X::from_fn(|i, _| got.x[i]),
            &Default::default(),
        )
        .unwrap();
    let modes = system_modes(&s, &mesh.stiffness, [true, false]).unwrap();
    assert!(modes[0].frequency_hz > 10.0, "{:?}", modes[0]);
    assert!(modes
        .iter()
        .any(|m| m.energy_share[4] + m.energy_share[5] > 0.5));

    // A slow run (bearing damping 5e3 N·s/m, fixed steps) follows the
    // compliant model on the condensed shafts: at 10 rpm the shafts' own
    // inertia hardly acts. Measured 2026-11-29: within 0.086 µrad of a TE
    // of 2,040 µrad (4e-5), the same at a quarter of the step (0.089), and
    // 0.041 µrad at 5 rpm: the shafts' mass, not the integration.
    let damped = |b: &[MemberBody; 2]| -> [MemberBody; 2] {
        std::array::from_fn(|k| MemberBody {
            damping: vec![(5e3, 5e3); b[k].support.bearings().len()],
            ..b[k].clone()
        })
    };
    let cm_condensed = CompliantModel::new(
        pinion_at(&c, 10.0),
        &c.shift,
        damped(&bodies(&c.f.g, &flexible, 0.0)),
        c.hand,
    )
    .unwrap();
    let rigid_damped = damped(&rigid);
    let cm =
        CompliantModel::new(pinion_at(&c, 10.0), &c.shift, rigid_damped.clone(), c.hand).unwrap();
    let s = assemble(
        parts(&rigid_damped, c.inertia, Some(&sh), 7850.0),
        None,
        0.005,
    )
    .unwrap();
    let gm = GearboxModel::new(&cm, &s).unwrap();
    let t_end = c.table.span() / (10.0 * PI / 30.0);
    let h = 2e-4;
    let mut want = Vec::new();
    c_integrate(
        &cm_condensed,
        cm_condensed.static_state(0.0).unwrap(),
        &mut CompliantIntegrator::new(0.8, fixed(h)),
        t_end,
        |st, _| {
            want.push(te(st.x[0], st.x[1]));
            Ok(())
        },
    )
    .unwrap();
    let mut got = Vec::new();
    let mut last = None;
    integrate(
        &gm,
        gm.static_state(0.0).unwrap(),
        &mut GearboxIntegrator::new(0.8, fixed(h)),
        t_end,
        |st, _| {
            got.push(te(st.x[0], st.x[1]));
            last = Some(st.clone());
            Ok(())
        },
    )
    .unwrap();
    assert_eq!(want.len(), got.len());
    let worst_te = want
        .iter()
        .zip(&got)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    eprintln!(
        "10 rpm over a mesh cycle ({} steps): TE within {:.4} µrad of the condensed shafts' run",
        got.len(),
        worst_te * 1e6
    );
    assert!(worst_te < 0.2e-6, "{worst_te}");
    let last: GState = last.unwrap();
    let forces = gm.bearing_forces(&last.x, &last.v);
    assert_eq!(forces.len(), 4);
    assert!(forces.iter().all(|f| f.norm() > 100.0));
}
