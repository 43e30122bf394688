//! Both flanks placed at their rotations, and the signed normal gap between
//! a pinion point and the wheel flank (closest point by Gauss–Newton on the
//! wheel's generating parameters). The UTCA's separation growth and the
//! direct contact search both measure gaps with these.

use crate::flank::Flank;
use crate::pair::FlankPair;
use nalgebra::{Matrix3x2, Vector3};

/// Pinion and wheel rotations, rad.
#[derive(Debug, Clone, Copy)]
pub struct Placement {
    pub pinion: f64,
    pub wheel: f64,
}

impl FlankPair {
    /// Wheel rotation of conjugate contact for pinion rotation `phi1`.
    pub fn conjugate_wheel_angle(&self, phi1: f64) -> f64 {
        let z1 = self.pinion.gen.frame.teeth as f64;
        let z2 = self.wheel.gen.frame.teeth as f64;
        -(z1 / z2) * phi1 + self.wheel_offset
    }

    /// Placement with the wheel lagging by `te` (wheel rad) when the pinion
    /// turns in direction `direction`.
    pub fn placement(&self, phi1: f64, te: f64, direction: f64) -> Placement {
        Placement {
            pinion: phi1,
            wheel: self.conjugate_wheel_angle(phi1) + direction * te,
        }
    }
}

/// Closest point of `flank` (unmodified, member frame) to `q`: generating
/// parameters and signed gap along the flank's outward normal.
pub fn project(flank: &Flank, q: &Vector3<f64>, start: [f64; 2]) -> Option<([f64; 2], f64)> {
    project_point(flank, q, start).map(|f| (f.uv, f.gap))
}

/// The closest point of a flank to a point, as [`project_point`] finds it.
#[derive(Debug, Clone, Copy)]
pub struct Foot {
    /// Generating parameters of the closest point.
    pub uv: [f64; 2],
    /// Signed gap along the flank's outward normal, m.
    pub gap: f64,
    /// The closest point and the outward unit normal there (member frame).
    pub pos: Vector3<f64>,
    pub normal: Vector3<f64>,
}

/// Closest point of `flank` (unmodified, member frame) to `q` by
/// Gauss–Newton on the generating parameters from `start`.
pub fn project_point(flank: &Flank, q: &Vector3<f64>, start: [f64; 2]) -> Option<Foot> {
    let [mut u, mut v] = start;
    let h = 1e-7;
    for _ in 0..30 {
        let w = Vector3::from(flank.gen.eval(u, v).pos);
        let wu = (Vector3::from(flank.gen.eval(u + h, v).pos) - w) / h;
        let wv = (Vector3::from(flank.gen.eval(u, v + h).pos) - w) / h;
        let j = Matrix3x2::from_columns(&[wu, wv]);
        let r = q - w;
        let step = (j.transpose() * j).try_inverse()? * (j.transpose() * r);
        u += step[0];
        v += step[1];
        if step.norm() < 1e-13 {
            break;
        }
    }
    let raw = flank.gen.eval(u, v);
    let pos = Vector3::from(raw.pos);
    let normal = Vector3::from(raw.normal);
    Some(Foot {
        uv: [u, v],
        gap: (q - pos).dot(&normal),
        pos,
        normal,
    })
}

/// Pinion tooth-`j` point `p` (member frame of tooth 0) at placement `at`,
/// in the member frame of wheel tooth −j: the pinion turned about its axis,
/// moved by the pair's pose (misalignment) if any, then seen from the
/// turned wheel.
pub fn pinion_in_wheel(fp: &FlankPair, at: Placement, j: i32, p: &Vector3<f64>) -> Vector3<f64> {
    pinion_in_wheel_with(fp, fp.pose.as_ref(), at, j, p)
}

/// As [`pinion_in_wheel`], with the pinion's pose `pose` in place of the
/// pair's (None: aligned).
pub fn pinion_in_wheel_with(
    fp: &FlankPair,
    pose: Option<&crate::misalignment::Pose>,
    at: Placement,
    j: i32,
    p: &Vector3<f64>,
) -> Vector3<f64> {
    let f1 = &fp.pinion.gen.frame;
    let f2 = &fp.wheel.gen.frame;
    let x = f1.to_fixed(p, at.pinion + j as f64 * f1.pitch());
    let x = match pose {
        Some(pose) => pose.apply(&x),
        None => x,
    };
    f2.to_member(&x, at.wheel - j as f64 * f2.pitch())
}

/// Signed gap between pinion tooth `j` at pinion parameters `uv` and wheel
/// tooth −j (positive = open), and the wheel parameters of the closest point.
pub fn gap(
    fp: &FlankPair,
    at: Placement,
    j: i32,
    uv: [f64; 2],
    start: [f64; 2],
) -> Option<(f64, [f64; 2])> {
    let p = Vector3::from(fp.pinion.eval_uv(uv[0], uv[1]).pos);
    let q = pinion_in_wheel(fp, at, j, &p);
    project(&fp.wheel, &q, start).map(|(w, g)| (g, w))
}

/// As [`gap`], but `None` unless the closest wheel point lies on the wheel
/// flank (within its blank bounds): other points cannot touch.
pub fn gap_on_flank(
    fp: &FlankPair,
    at: Placement,
    j: i32,
    uv: [f64; 2],
    start: [f64; 2],
) -> Option<(f64, [f64; 2])> {
    let (g, w) = gap(fp, at, j, uv, start)?;
    let (l, d) = fp.wheel.ld(w[0], w[1]);
    fp.wheel.bounds.contains(l, d, 1e-9).then_some((g, w))
}
