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
    /// Generating parameters of the closest wheel point at the lag.
    pub wheel_uv: [f64; 2],
    /// The wheel's normal lever |(e_z × w) · n| at the closest point w at the lag, m/rad.
    pub lever: f64,
    /// The sign of the wheel's turn that closes the gap (±1).
    pub sign: f64,
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
    let foot = Foot::new(fp, pose, pos, target);
    let (f0, l0) = foot.at(0.0, start)?;
    // The wheel turns the way that closes the gap.
    foot.close(l0.signum(), 0.0, f0, l0)
}

/// As [`mate_with`], Newton started from the mate `near` of a nearby point
/// (its wheel point, lag and turn): one projection fewer where the lags
/// are close (the one at the conjugate angle). Falls back to the cold
/// start where the turn's sign differs there.
pub fn mate_near(
    fp: &FlankPair,
    pose: Option<&Pose>,
    pos: [f64; 3],
    target: f64,
    near: &Mate,
) -> Option<Mate> {
    let foot = Foot::new(fp, pose, pos, target);
    let (f, l) = foot.at(near.sign * near.lag, near.wheel_uv)?;
    if l.signum() != near.sign {
        return mate_with(fp, pose, pos, target, near.wheel_uv);
    }
    foot.close(near.sign, near.lag, f, l)
}

/// The closest wheel point of one pinion point at one pinion roll, as the
/// wheel turns from the conjugate angle.
struct Foot<'a> {
    fp: &'a FlankPair,
    pose: Option<&'a Pose>,
    p: Vector3<f64>,
    target: f64,
    conj: f64,
}

impl<'a> Foot<'a> {
    fn new(fp: &'a FlankPair, pose: Option<&'a Pose>, pos: [f64; 3], target: f64) -> Self {
        Foot {
            fp,
            pose,
            p: Vector3::from(pos),
            target,
            conj: fp.conjugate_wheel_angle(target),
        }
    }

    /// The foot with the wheel turned by `turn` from the conjugate angle,
    /// projected from `start`, and d(gap)/d(wheel angle) = −n · (e_z × w)
    /// there (non-zero).
    fn at(&self, turn: f64, start: [f64; 2]) -> Option<(crate::placement::Foot, f64)> {
        let at = Placement {
            pinion: self.target,
            wheel: self.conj + turn,
        };
        let q = pinion_in_wheel_with(self.fp, self.pose, at, 0, &self.p);
        let f = project_point(&self.fp.wheel, &q, start)?;
        let lever = f.pos[0] * f.normal[1] - f.pos[1] * f.normal[0];
        (lever != 0.0).then_some((f, lever))
    }

    /// Newton on the gap in the lag from `lag` (turn sign `s`), where the
    /// foot is `f` with lever `l`.
    fn close(&self, s: f64, lag: f64, f: crate::placement::Foot, l: f64) -> Option<Mate> {
        let (mut lag, mut f, mut lever) = (lag, f, l.abs());
        for _ in 0..MATE_ITERATIONS {
            lag += f.gap / lever;
            let (fi, li) = self.at(s * lag, f.uv)?;
            (f, lever) = (fi, li.abs());
            if f.gap.abs() < MATE_GAP_TOL {
                break;
            }
        }
        Some(Mate {
            lag: lag + f.gap / lever,
            wheel_uv: f.uv,
            lever,
            sign: s,
        })
    }
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
    Some(PoseCorrection::of(fp, a, p))
}

/// As [`pose_correction`], each mate started from its own in `near`, the
/// correction of a nearby point ([`mate_near`]). With the identity pose
/// both mates still see the same point from the same start, and the
/// correction stays exactly zero.
pub fn pose_correction_near(
    fp: &FlankPair,
    pose: &Pose,
    pos: [f64; 3],
    target: f64,
    near: &PoseCorrection,
) -> Option<PoseCorrection> {
    let a = mate_near(fp, None, pos, target, &near.mates[0])?;
    let p = mate_near(fp, Some(pose), pos, target, &near.mates[1])?;
    Some(PoseCorrection::of(fp, a, p))
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
    /// The two mates (aligned, with the pose): starts for a nearby point
    /// ([`pose_correction_near`]).
    pub mates: [Mate; 2],
}

impl PoseCorrection {
    /// The correction from the aligned mate `a` and the posed mate `p`.
    fn of(fp: &FlankPair, a: Mate, p: Mate) -> Self {
        let (la, da) = fp.wheel.ld(a.wheel_uv[0], a.wheel_uv[1]);
        let (lp, dp) = fp.wheel.ld(p.wheel_uv[0], p.wheel_uv[1]);
        PoseCorrection {
            lag: p.lag - a.lag,
            lever: p.lever - a.lever,
            wheel_ld: [lp - la, dp - da],
            mates: [a, p],
        }
    }

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

/// Whether the pinion point at `uv` lies on the pinion flank (within `tol`, m).
pub fn on_pinion(fp: &FlankPair, uv: [f64; 2], tol: f64) -> bool {
    let (l, d) = fp.pinion.ld(uv[0], uv[1]);
    fp.pinion.bounds.contains(l, d, tol)
}
