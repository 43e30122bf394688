//! The mesh normal's direction cosines (a₁, a₂, a₃): a unit vector for both
//! hands and both flanks; on the drive flank (pinion concave) a₁ as seed
//! 004 prints it, −(sin αₙ cos δ₂ + cos αₙ sin β₂ sin δ₂), whatever the
//! hand; the coast flank mirrors the spiral term; the hand sets only the
//! sign of the tangential component a₃ = ±cos αₙ cos β₂.

use geometry::generation::Side;
use solver::lumped::model::{direction_cosines, WheelHand};

#[test]
fn lumped_direction_cosines_are_a_unit_normal_with_the_spiral_sign_of_the_loaded_flank() {
    let (an, b, d2) = (
        25f64.to_radians(),
        25f64.to_radians(),
        75.027f64.to_radians(),
    );
    let a = |hand, side| direction_cosines(an, b, d2, hand, side);
    let (ld, rd) = (
        a(WheelHand::Left, Side::Drive),
        a(WheelHand::Right, Side::Drive),
    );
    let (lc, rc) = (
        a(WheelHand::Left, Side::Coast),
        a(WheelHand::Right, Side::Coast),
    );
    for v in [ld, rd, lc, rc] {
        let n: f64 = v.iter().map(|x| x * x).sum();
        assert!((n - 1.0).abs() < 1e-14, "{v:?}");
    }
    let a1 = -(an.sin() * d2.cos() + an.cos() * b.sin() * d2.sin());
    assert!((ld[0] - a1).abs() < 1e-15, "{ld:?}");
    assert_eq!((ld[0], ld[1]), (rd[0], rd[1]));
    assert!((ld[2] - an.cos() * b.cos()).abs() < 1e-15);
    assert!((rd[2] + an.cos() * b.cos()).abs() < 1e-15);
    let a1_coast = -(an.sin() * d2.cos() - an.cos() * b.sin() * d2.sin());
    assert!((lc[0] - a1_coast).abs() < 1e-15, "{lc:?}");
    // The axial-plane part sin αₙ (across the pitch line) is the same on every flank.
    let across = |a: [f64; 3]| -a[0] * d2.cos() + a[1] * d2.sin();
    for v in [ld, rd, lc, rc] {
        assert!((across(v) - an.sin()).abs() < 1e-14);
    }
}
