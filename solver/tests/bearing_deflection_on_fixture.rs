//! Quasi-static LTCA with compliant bearings ([`solver::bearings::system_deflection`])
//! on the checked-in example-02 stiffness fixture (no gmsh): stiff bearings
//! give the rigid-bearing TE, the bearing reactions balance the contact's
//! wrench and the contact torque is the applied torque, and the TE added by
//! soft bearings scales with their compliance; on flexible shafts
//! (Timoshenko beams condensed onto the gear seat) a very stiff shaft gives
//! the rigid shaft's TE and a steel one adds its own bending.

#[path = "support/fixture.rs"]
mod fixture;

use fixture::{supports, supports_on_shafts, Fixture};
use solver::bearings::system_deflection::{
    deflected_position, DeflectedPosition, DeflectionSettings,
};

const TORQUE_NM: f64 = 300.0;

fn solve_with(k: f64) -> DeflectedPosition {
    deflect(k).unwrap()
}

/// The fixture's position 3 at [`TORQUE_NM`] on bearings of stiffness `k`.
fn deflect(k: f64) -> Result<DeflectedPosition, solver::SolverError> {
    let f = Fixture::example_02();
    let sup = supports(&f.g, k);
    deflect_on(f, &sup)
}

/// The fixture's position 3 at [`TORQUE_NM`] on the supports `sup`.
fn deflect_on(
    mut f: Fixture,
    sup: &solver::bearings::system_deflection::Supports,
) -> Result<DeflectedPosition, solver::SolverError> {
    let phi = f.sweep.start + f.sweep.direction * 3.0 * f.sweep.step;
    deflected_position(
        &mut f.g,
        f.scene.scene.loaded_flank,
        &f.scene.scene.utca,
        &f.pc,
        sup,
        None,
        phi,
        TORQUE_NM,
        DeflectionSettings {
            slices: f.scene.scene.ltca.slices,
            tolerance_m: 1e-9,
            max_iterations: 60,
        },
    )
}

#[test]
fn very_stiff_bearings_give_the_rigid_bearing_te() {
    let r = solve_with(1e16);
    assert!(
        (r.te - r.te_rigid_bearings).abs() < 1e-9,
        "TE {} against rigid {} rad",
        r.te,
        r.te_rigid_bearings
    );
}

#[test]
fn bearing_reactions_balance_the_contact_wrench_and_the_contact_torque_is_the_applied_torque() {
    let k = 5e8;
    let r = solve_with(k);
    let sup = supports(&Fixture::example_02().g, k);
    assert!(r.iterations >= 2 && r.iterations < 60, "{}", r.iterations);
    let w = r.pinion_wrench;
    let scale = nalgebra::Vector3::new(w[0], w[1], w[2]).norm();
    for (s, g, d) in [(&sup.pinion, w, &r.pinion), (&sup.wheel, -w, &r.wheel)] {
        let (f, m) = s.residual(&g, d);
        assert!(f.norm() < 1e-9 * scale, "force residual {f}");
        assert!(m.norm() < 1e-9 * scale * 0.2, "moment residual {m}");
    }
    // The contact's torque about the moved pinion axis against the LTCA's
    // applied torque: the wrench built from points and normals against the
    // LTCA's levers.
    assert!(
        (r.pinion_contact_torque_nm.abs() - TORQUE_NM).abs() < 1e-9 * TORQUE_NM,
        "{} N·m",
        r.pinion_contact_torque_nm
    );
    // Reactions add up to the mesh force on each member.
    let sum: nalgebra::Vector3<f64> = r.pinion_reactions.iter().sum();
    assert!((sum + nalgebra::Vector3::new(w[0], w[1], w[2])).norm() < 1e-9 * scale);
}

#[test]
fn te_added_by_soft_bearings_scales_with_their_compliance() {
    let soft = solve_with(2e8);
    let stiffer = solve_with(4e8);
    let d_soft = soft.te - soft.te_rigid_bearings;
    let d_stiff = stiffer.te - stiffer.te_rigid_bearings;
    assert!(d_soft.abs() > 1e-7, "ΔTE {d_soft} rad");
    let ratio = d_soft / d_stiff;
    eprintln!(
        "300 N·m: TE rigid {:.3} µrad; k 2e8: +{:.3} µrad ({} iterations, pinion apex moved {:.2} µm); k 4e8: +{:.3} µrad ({} iterations)",
        soft.te_rigid_bearings * 1e6,
        d_soft * 1e6,
        soft.iterations,
        soft.pinion.translation.norm() * 1e6,
        d_stiff * 1e6,
        stiffer.iterations
    );
    assert!(
        (ratio - 2.0).abs() < 0.2,
        "ΔTE ratio {ratio} (soft {d_soft}, stiffer {d_stiff})"
    );
}

#[test]
fn soft_bearings_of_1e8_n_per_m_converge_and_keep_the_compliance_scaling() {
    // Soft but realistic bearings: the plain iteration overshoots there
    // (the fixed half step it once used did not converge at all). The TE
    // they add is twice that of 2e8 N/m bearings, as at 2e8 and 4e8.
    let soft = solve_with(1e8);
    let stiffer = solve_with(2e8);
    assert!(soft.iterations < 60, "{} iterations", soft.iterations);
    let ratio = (soft.te - soft.te_rigid_bearings) / (stiffer.te - stiffer.te_rigid_bearings);
    eprintln!(
        "k 1e8: {} iterations, +{:.3} µrad; k 2e8: {} iterations; ratio {ratio:.3}",
        soft.iterations,
        (soft.te - soft.te_rigid_bearings) * 1e6,
        stiffer.iterations
    );
    assert!((ratio - 2.0).abs() < 0.25, "ΔTE ratio {ratio}");
}

#[test]
fn bearings_too_soft_for_the_load_are_named_not_a_missing_contact() {
    // 1 N/m: the first deflection moves the members metres apart. The
    // error must say that the bearings did it, with the torque and how far
    // they moved the members, not that no pair can touch.
    let e = deflect(1.0).unwrap_err();
    assert!(
        matches!(e, solver::SolverError::BearingsSeparate { .. }),
        "{e}"
    );
    let msg = e.to_string();
    for w in ["bearings are too soft", "300 N·m", "stiffen `[bearings]`"] {
        assert!(msg.contains(w), "'{w}' not in: {msg}");
    }
}

/// A shaft a million times stiffer than steel carries the gear as the
/// rigid shaft does (the same TE within 1e-5 of the TE the bearings add);
/// a 30 mm steel shaft
/// bends under the mesh force and adds TE beyond the bearings' own, with
/// the reactions still balancing the contact's wrench.
#[test]
fn flexible_shafts_give_the_rigid_shaft_te_when_stiff_and_add_their_bending_when_steel() {
    let k = 5e8;
    let rigid = solve_with(k);
    let g = Fixture::example_02().g;
    let stiff = deflect_on(Fixture::example_02(), &supports_on_shafts(&g, k, 0.03, 1e6)).unwrap();
    // Within 1e-5 of what the bearings add (the iteration stops at 1 nm,
    // and the shaft keeps a millionth of a steel shaft's compliance).
    let added = rigid.te - rigid.te_rigid_bearings;
    assert!(
        (stiff.te - rigid.te).abs() < 1e-5 * added.abs(),
        "TE on a very stiff shaft {} against the rigid shaft {} rad",
        stiff.te,
        rigid.te
    );
    let steel_sup = supports_on_shafts(&g, k, 0.03, 1.0);
    let steel = deflect_on(Fixture::example_02(), &steel_sup).unwrap();
    let (d_bearings, d_shaft) = (added, steel.te - rigid.te);
    eprintln!(
        "300 N·m, bearings 5e8 N/m: TE rigid supports {:.3} µrad, + bearings {:+.3} µrad, + 30 mm steel shafts {:+.3} µrad; pinion apex moved {:.2} µm (rigid shaft {:.2} µm)",
        rigid.te_rigid_bearings * 1e6,
        d_bearings * 1e6,
        d_shaft * 1e6,
        steel.pinion.translation.norm() * 1e6,
        rigid.pinion.translation.norm() * 1e6
    );
    assert!(steel.pinion.translation.norm() > rigid.pinion.translation.norm());
    assert!(
        d_shaft.abs() > 1e-8,
        "the shaft's bending changes the TE: {d_shaft} rad"
    );
    let w = steel.pinion_wrench;
    let scale = nalgebra::Vector3::new(w[0], w[1], w[2]).norm();
    for (s, g, d) in [
        (&steel_sup.pinion, w, &steel.pinion),
        (&steel_sup.wheel, -w, &steel.wheel),
    ] {
        let (f, m) = s.residual(&g, d);
        assert!(f.norm() < 1e-9 * scale, "force residual {f}");
        assert!(m.norm() < 1e-9 * scale * 0.2, "moment residual {m}");
    }
}
