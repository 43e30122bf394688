//! The mesh normal's direction cosines (a₁, a₂, a₃): a unit vector for both
//! hands; for seed 004's left-hand wheel a₁ as printed there,
//! −(sin αₙ cos δ₂ + cos αₙ sin β₂ sin δ₂), and a₃ = +cos αₙ cos β₂; a
//! right-hand wheel mirrors the spiral term and the tangential component.

use solver::lumped::model::{direction_cosines, WheelHand};

#[test]
fn lumped_direction_cosines_are_a_unit_normal_with_seed_004_signs() {
    let (an, b, d2) = (
        25f64.to_radians(),
        25f64.to_radians(),
        75.027f64.to_radians(),
    );
    let l = direction_cosines(an, b, d2, WheelHand::Left);
    let r = direction_cosines(an, b, d2, WheelHand::Right);
    for a in [l, r] {
        let n: f64 = a.iter().map(|x| x * x).sum();
        assert!((n - 1.0).abs() < 1e-14, "{a:?}");
    }
    let a1 = -(an.sin() * d2.cos() + an.cos() * b.sin() * d2.sin());
    assert!((l[0] - a1).abs() < 1e-15, "{l:?}");
    assert!((l[2] - an.cos() * b.cos()).abs() < 1e-15);
    assert!((r[2] + an.cos() * b.cos()).abs() < 1e-15);
    // The axial-plane part sin αₙ (across the pitch line) is hand-independent.
    let across = |a: [f64; 3]| -a[0] * d2.cos() + a[1] * d2.sin();
    assert!((across(l) - an.sin()).abs() < 1e-14);
    assert!((across(r) - an.sin()).abs() < 1e-14);
}
