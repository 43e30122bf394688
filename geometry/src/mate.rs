//! The contact of a pinion point with the wheel flank when the pair is
//! misaligned: the point is placed with the pair's pose
//! ([`crate::misalignment`]) and projected onto the wheel flank, and the
//! wheel lag that closes the gap follows from the wheel's normal lever at
//! the closest point. The aligned pair does not need it: there the
//! surface of roll angles gives the mate of every point in closed form
//! (the same generating parameters on both flanks, see [`crate::utca`]).
//!
//! The misaligned analyses use the pose's *change* to the contact,
//! [`pose_correction`]: the exact mate with the pose less the exact mate
//! without it, added to the aligned pair's surface-of-roll-angles model.
//! With the identity pose the correction is exactly zero, so the
//! misaligned path reproduces the aligned one bit for bit; with a pose it
//! carries the pose's whole effect exactly, and only the aligned model's
//! own error (second order in the distance from the contact line) remains.

use crate::misalignment::Pose;
use crate::pair::FlankPair;
use crate::placement::{pinion_in_wheel_with, project_point, Placement};
use nalgebra::Vector3;

/// A pinion point's closest wheel point at one pinion roll.
#[derive(Debug, Clone, Copy)]
pub struct Mate {
    /// Wheel lag (rad) that closes the gap.
    pub lag: f64,
    /// Signed normal gap with the wheel at the conjugate angle, m.
    pub gap: f64,
    /// Generating parameters of the closest wheel point at the lag.
    pub wheel_uv: [f64; 2],
    /// The wheel's normal lever |(e_z × w) · n| at the closest point w at the lag, m/rad.
    pub lever: f64,
}

/// The mate of the pinion point `pos` (tooth 0, member frame) when tooth 0
/// is at pinion roll `target` and the wheel at the conjugate angle, the
/// projection started from the wheel parameters `start`. The lag is the
/// root of the gap in the wheel's rotation, by Newton steps gap / λ₂ with
/// the gap re-measured at the turned wheel (a misalignment's lag reaches a
/// milliradian, where the first-order step alone is off by about 0.1 µrad);
/// the wheel point is the one touched at that lag. None where a projection
/// fails or the lever vanishes.
pub fn mate(fp: &FlankPair, pos: [f64; 3], target: f64, start: [f64; 2]) -> Option<Mate> {
    mate_with(fp, fp.pose.as_ref(), pos, target, start)
}

/// As [`mate`], with the pinion's pose `pose` in place of the pair's
/// (None: aligned).
pub fn mate_with(
    fp: &FlankPair,
    pose: Option<&Pose>,
    pos: [f64; 3],
    target: f64,
    start: [f64; 2],
) -> Option<Mate> {
    let conj = fp.conjugate_wheel_angle(target);
    let p = Vector3::from(pos);
    let foot = |wheel: f64, start: [f64; 2]| {
        let at = Placement {
            pinion: target,
            wheel,
        };
        let f = project_point(&fp.wheel, &pinion_in_wheel_with(fp, pose, at, 0, &p), start)?;
        // d(gap)/d(wheel angle) = −n · (e_z × w).
        let lever = f.pos[0] * f.normal[1] - f.pos[1] * f.normal[0];
        (lever != 0.0).then_some((f, lever))
    };
    let (f0, l0) = foot(conj, start)?;
    // The wheel turns the way that closes the gap.
    let s = l0.signum();
    let (mut lag, mut f, mut lever) = (0.0, f0, l0.abs());
    for _ in 0..MATE_ITERATIONS {
        lag += f.gap / lever;
        let (fi, li) = foot(conj + s * lag, f.uv)?;
        (f, lever) = (fi, li.abs());
        if f.gap.abs() < MATE_GAP_TOL {
            break;
        }
    }
    Some(Mate {
        lag: lag + f.gap / lever,
        gap: f0.gap,
        wheel_uv: f.uv,
        lever,
    })
}

/// What the pair's pose changes in the contact of a pinion point: the
/// exact mates ([`mate_with`]) with the pose (p) and without it (a), at
/// the same roll `target` and from the same start,
///
///   Δlag = lag_p − lag_a,  Δλ₂ = λ₂,p − λ₂,a,  Δ(L, d) = (L, d)_p − (L, d)_a
///
/// of the wheel point touched. The misaligned contact of the point is the
/// aligned model's (lag from the surface of roll angles, the conjugate
/// wheel point, its lever) plus these. Zero, exactly, for the identity
/// pose. None where either mate fails.
pub fn pose_correction(
    fp: &FlankPair,
    pose: &Pose,
    pos: [f64; 3],
    target: f64,
    start: [f64; 2],
) -> Option<PoseCorrection> {
    let a = mate_with(fp, None, pos, target, start)?;
    let p = mate_with(fp, Some(pose), pos, target, start)?;
    let (la, da) = fp.wheel.ld(a.wheel_uv[0], a.wheel_uv[1]);
    let (lp, dp) = fp.wheel.ld(p.wheel_uv[0], p.wheel_uv[1]);
    Some(PoseCorrection {
        lag: p.lag - a.lag,
        lever: p.lever - a.lever,
        wheel_ld: [lp - la, dp - da],
        aligned_wheel_uv: a.wheel_uv,
    })
}

/// The pose's change to a pinion point's contact ([`pose_correction`]).
#[derive(Debug, Clone, Copy)]
pub struct PoseCorrection {
    /// Wheel lag, rad.
    pub lag: f64,
    /// Wheel normal lever, m/rad.
    pub lever: f64,
    /// Axial-section coordinates (L, d) of the wheel point touched, m.
    pub wheel_ld: [f64; 2],
    /// Generating parameters of the wheel point the aligned mate touches: a
    /// start for the projections of a nearby point.
    pub aligned_wheel_uv: [f64; 2],
}

impl PoseCorrection {
    /// The wheel point touched, (L, d): the conjugate point `conjugate`
    /// (same generating parameters as the pinion point) moved by the pose.
    pub fn wheel_point(&self, conjugate: (f64, f64)) -> (f64, f64) {
        (
            conjugate.0 + self.wheel_ld[0],
            conjugate.1 + self.wheel_ld[1],
        )
    }
}

/// Newton steps of [`mate`] at most, and the gap (m) at which it stops:
/// far from its contact line a point needs a lag of milliradians, and the
/// wheel point it then touches lies millimetres from the closest one at
/// the conjugate angle.
const MATE_ITERATIONS: usize = 8;
const MATE_GAP_TOL: f64 = 1e-12;

/// Signed distance (m) of the wheel point at generating parameters `uv`
/// inside the wheel flank's blank bounds (negative outside).
pub fn wheel_margin(fp: &FlankPair, uv: [f64; 2]) -> f64 {
    let (l, d) = fp.wheel.ld(uv[0], uv[1]);
    fp.wheel.bounds.margin(l, d)
}

/// Whether the wheel point at `uv` lies on the wheel flank (within `tol`, m).
pub fn on_wheel(fp: &FlankPair, uv: [f64; 2], tol: f64) -> bool {
    let (l, d) = fp.wheel.ld(uv[0], uv[1]);
    fp.wheel.bounds.contains(l, d, tol)
}

/// Whether the pinion point at `uv` lies on the pinion flank (within `tol`, m).
pub fn on_pinion(fp: &FlankPair, uv: [f64; 2], tol: f64) -> bool {
    let (l, d) = fp.pinion.ld(uv[0], uv[1]);
    fp.pinion.bounds.contains(l, d, tol)
}
