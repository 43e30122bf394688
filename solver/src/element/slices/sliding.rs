//! The members' rotation velocities at a contact point, the sliding velocity
//! and the friction levers and direction that follow from it.

use super::{cross, dot, norm, sub};
use geometry::pair::FlankPair;

/// The two members' rotation velocities at `pos` (pinion member frame,
/// tooth 0 at pinion angle `phi`) per unit pinion angular speed, e_z × r
/// and a₂ × r, with a₂ the wheel axis seen from the pinion, and the roll
/// ratio k = φ̇₂/φ̇₁ (both axes pass through the apex, the frames' common
/// origin).
fn rotation_velocities(fp: &FlankPair, pos: [f64; 3], phi: f64) -> ([f64; 3], [f64; 3], f64) {
    let (pf, wf) = (&fp.pinion.gen.frame, &fp.wheel.gen.frame);
    let k = wf.roll_ratio / pf.roll_ratio;
    let Some(pose) = &fp.pose else {
        let a2 = pf.to_member(&wf.axis(), phi);
        return (
            cross([0.0, 0.0, 1.0], pos),
            cross([a2[0], a2[1], a2[2]], pos),
            k,
        );
    };
    // Misaligned: the wheel axis through the fixed frame's origin, seen
    // from the pinion, which the pose has turned and moved.
    let back = pose.inverse();
    let a2 = pf.to_member(&(back.rotation * wf.axis()), phi);
    let c2 = pf.to_member(&back.translation, phi);
    let r = sub(pos, [c2[0], c2[1], c2[2]]);
    (
        cross([0.0, 0.0, 1.0], pos),
        cross([a2[0], a2[1], a2[2]], r),
        k,
    )
}

/// Sliding velocity of the pinion flank against the wheel's at `pos`
/// (pinion member frame, tooth 0 at pinion angle `phi`), per unit pinion
/// angular speed: v_s = e_z × r − k a₂ × r ([`rotation_velocities`]).
pub fn sliding_velocity(fp: &FlankPair, pos: [f64; 3], phi: f64) -> [f64; 3] {
    let (w1, w2, k) = rotation_velocities(fp, pos, phi);
    [0, 1, 2].map(|i| w1[i] - k * w2[i])
}

/// Friction levers (ℓ₁, ℓ₂) of a contact at `pos` with normal `normal`
/// (pinion member frame, tooth 0 at pinion angle `phi`). Friction opposes
/// sliding: on the pinion −μF û, on the wheel +μF û, û the unit sliding
/// direction in the tangent plane for forward rotation. By virtual power
/// the generalized forces are −μF ℓ₁ on q₁ and +μF ℓ₂ on q₂ with
///   ℓ₁ = û·(e_z × r),  ℓ₂ = sgn(k) û·(a₂ × r),
/// so that with q̇₂ = |k| q̇₁ the friction dissipates μF|v_s||q̇₁| (ℓ₁ − |k|ℓ₂
/// = |v_s|). Both vanish at a pure-rolling point (on the pitch line).
pub fn friction_levers(fp: &FlankPair, pos: [f64; 3], normal: [f64; 3], phi: f64) -> [f64; 2] {
    let (w1, w2, k) = rotation_velocities(fp, pos, phi);
    match friction_direction(fp, pos, normal, phi) {
        Some(u) => [dot(u, w1), k.signum() * dot(u, w2)],
        None => [0.0, 0.0],
    }
}

/// The unit sliding direction û of [`friction_levers`] (pinion member
/// frame, tangent to the flank at `pos`): friction pushes the pinion along
/// −û and the wheel along +û. `None` at a pure-rolling point.
pub fn friction_direction(
    fp: &FlankPair,
    pos: [f64; 3],
    normal: [f64; 3],
    phi: f64,
) -> Option<[f64; 3]> {
    let vs = sliding_velocity(fp, pos, phi);
    let vn = dot(vs, normal);
    let vt = [0, 1, 2].map(|i| vs[i] - vn * normal[i]);
    let speed = norm(vt);
    (speed > 1e-12 * norm(pos)).then(|| vt.map(|c| c / speed))
}
