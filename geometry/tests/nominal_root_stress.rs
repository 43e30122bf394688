//! The nominal root stress anchor (`geometry::nominal_root_stress`) on
//! design data: the white-paper pinion's virtual gear carries the profile
//! shift its design notes derive (x = 0.357), the virtual contact ratio of a
//! bevel pair whose cones flatten into spur gears tends to the spur pair's
//! (two 20-tooth gears, 20°: 1.557), and σ_F0 is linear in the torque.

mod common;

use geometry::design::Member;
use geometry::nominal_root_stress::{nominal_root_stress, virtual_contact_ratio, virtual_tooth};

#[test]
fn white_paper_pinion_virtual_gear_has_the_designed_profile_shift() {
    let p = common::white_paper();
    let t = virtual_tooth(&p, Member::Pinion, p.pressure_angle[0]);
    assert!((t.x - 0.357).abs() < 1e-3, "x_E {}", t.x);
    // Virtual teeth in the normal section: z / (cos δ cos² β_vb cos β_m).
    assert!(t.z > 20.0 / p.members[0].pitch_angle.cos(), "{}", t.z);
}

#[test]
fn flattened_straight_bevel_pair_has_the_spur_contact_ratio() {
    let mut p = common::white_paper();
    let m = 4e-3;
    let delta = 1e-6f64;
    p.spiral_angle = 0.0;
    p.normal_module = m;
    p.mean_cone_distance = 20.0 * m / (2.0 * delta.sin());
    for d in &mut p.members {
        d.teeth = 20;
        d.pitch_angle = delta;
        d.mean_addendum = m;
    }
    let eps = virtual_contact_ratio(&p, 20f64.to_radians());
    assert!((eps - 1.557).abs() < 1e-3, "ε_vα {eps}");
}

#[test]
fn nominal_root_stress_is_linear_in_the_torque() {
    let p = common::white_paper();
    let a = nominal_root_stress(&p, p.pressure_angle[0], 300.0);
    let b = nominal_root_stress(&p, p.pressure_angle[0], 600.0);
    for k in 0..2 {
        assert!((b.sigma_pa[k] / a.sigma_pa[k] - 2.0).abs() < 1e-12);
        assert!(a.sigma_pa[k] > 0.0);
    }
    assert!(a.contact_ratio > 1.0 && a.contact_ratio < 2.0, "{a:?}");
}
