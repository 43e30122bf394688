//! How far the flanks a pair's machine settings cut lie from the design's
//! conjugate flanks, as a topography of the pinion's ease-off.
//!
//! At each node (ξ, η) of a grid over the pinion's flank (the ease-off's
//! normalised coordinates, [`crate::flank::Bounds`]) the conjugate pinion
//! point P with outward normal n is found, and the wheel point W it
//! touches in the conjugate pair (the same generating parameters,
//! [`crate::mate`]). The flank the settings cut is met along each normal,
//! G(ζ, θ) = P + t n (cone parameters ζ, θ of [`Machine::cut`] and t by
//! Newton on the three coordinates), and the member's deviation is −t
//! (material removed is positive, as the ease-off counts it).
//!
//! Each member's deviation is taken with the cut flank turned by δ about
//! the member's axis, δ such that the deviation vanishes at the mean node
//! (ξ = η = ½): Newton on δ, whose step is the deviation there over the
//! normal lever λ = n · (e_z × P) (turning the flank by δ removes λ δ to
//! first order). The ease-off topography is the sum of both members'
//! deviations at mating points: the relative deviation that opens the gap.

use crate::design::Member;
use crate::design::TopographyDesign;
use crate::error::GeometryError;
use crate::flank::Flank;
use crate::generation::{RawPoint, Side};
use crate::machine::kinematics::Machine;
use crate::machine::settings::{FlankSettings, MachineSettings};
use crate::machine::surface_fit::ChebyshevSurface;
use crate::pair::FlankPair;
use nalgebra::{Matrix3, Rotation3, Vector3};
use serde::Serialize;

/// Nodes of the deviation grid along the profile (odd: one at η = ½).
pub const PROFILE_NODES: usize = 21;
/// Nodes along the face width (odd: one at ξ = ½).
pub const FACE_NODES: usize = 33;
/// Largest relative deviation the settings may cut from the design's
/// flanks, µm: beyond it they describe another gear.
pub const MAX_DEVIATION_UM: f64 = 200.0;

/// Largest miss of the smooth surface at a grid node, µm.
pub const MAX_FIT_RESIDUAL_UM: f64 = 0.01;

/// Convergence of the normal projection, m.
const PROJECTION_TOL: f64 = 1e-13;
/// Difference steps of the projection's Jacobian: height (m) and angle (rad).
const STEP_ZETA: f64 = 1e-7;
const STEP_THETA: f64 = 1e-6;

/// One member's deviation on the grid.
#[derive(Debug, Clone, Serialize)]
pub struct MemberDeviation {
    /// `deviation_um[i][j]` at (`profile[i]`, `face[j]`), after the rotation
    /// is removed, µm.
    pub deviation_um: Vec<Vec<f64>>,
    /// The rotation about the member's axis removed, µrad.
    pub removed_rotation_urad: f64,
}

/// Both members' deviations and their sum on one side of the pair.
#[derive(Debug, Clone, Serialize)]
pub struct SettingsDeviation {
    pub side: Side,
    pub pinion: MemberDeviation,
    pub wheel: MemberDeviation,
    /// The relative deviation (pinion + wheel) as the pinion's ease-off
    /// topography.
    pub topography: TopographyDesign,
}

/// `n` equally spaced nodes over [0, 1] (n ≥ 2).
pub fn unit_nodes(n: usize) -> Vec<f64> {
    (0..n).map(|i| i as f64 / (n - 1) as f64).collect()
}

/// The settings' deviation on the side of `fp`.
pub fn deviation(
    fp: &FlankPair,
    settings: &MachineSettings,
) -> Result<SettingsDeviation, GeometryError> {
    let (profile, face) = (unit_nodes(PROFILE_NODES), unit_nodes(FACE_NODES));
    let flanks = [&fp.pinion, &fp.wheel];
    // The conjugate points of both members at every node, row-major.
    let mut points: [Vec<RawPoint<f64>>; 2] = Default::default();
    for &eta in &profile {
        for &xi in &face {
            let (l, d) = fp.pinion.bounds.from_unit(xi, eta);
            let uv = fp.pinion.solve_ld(l, d)?;
            for (k, f) in flanks.iter().enumerate() {
                points[k].push(f.gen.eval(uv[0], uv[1]));
            }
        }
    }
    let mean = (PROFILE_NODES / 2) * FACE_NODES + FACE_NODES / 2;
    let mut members = Vec::with_capacity(2);
    for (k, m) in [Member::Pinion, Member::Wheel].into_iter().enumerate() {
        let base = Machine::new(settings.flank(m, fp.side), m, fp.side);
        members.push(member_deviation(
            &base,
            &points[k][mean],
            &points[k],
            (&profile, &face),
        )?);
    }
    let wheel = members.pop().expect("two members");
    let pinion = members.pop().expect("two members");
    let total: Vec<Vec<f64>> = pinion
        .deviation_um
        .iter()
        .zip(&wheel.deviation_um)
        .map(|(p, w)| p.iter().zip(w).map(|(a, b)| a + b).collect())
        .collect();
    for (i, row) in total.iter().enumerate() {
        for (j, &v) in row.iter().enumerate() {
            if v.abs() > MAX_DEVIATION_UM || !v.is_finite() {
                return Err(GeometryError::SettingsDeviation {
                    flank: fp.side.flank_name(Member::Pinion),
                    deviation_um: v,
                    xi: face[j],
                    eta: profile[i],
                    limit_um: MAX_DEVIATION_UM,
                });
            }
        }
    }
    Ok(SettingsDeviation {
        side: fp.side,
        pinion,
        wheel,
        topography: TopographyDesign {
            profile,
            face,
            deviation_um: total,
        },
    })
}

/// The machine with its cut flank turned about the work axis so that it
/// passes through the conjugate point `mean` (Newton on the rotation,
/// steps −t / λ), None where the flank is not met there.
pub fn indexed_at(base: &Machine, mean: &RawPoint<f64>) -> Option<Machine> {
    let mut index = 0.0;
    for _ in 0..8 {
        let t = normal_offset(&base.indexed(index), mean)?;
        index -= t / lever(mean);
        if t.abs() < 1e-14 {
            break;
        }
    }
    Some(base.indexed(index))
}

/// One member's deviation on its own flank's grid (`profile` × `face`
/// nodes of its normalised (ξ, η)), with the rotation that zeroes it at
/// its mean point (ξ = η = ½) removed: what the settings `s` cut on
/// `flank` relative to its conjugate flank.
pub fn member_grid(
    flank: &Flank,
    s: &FlankSettings,
    profile: &[f64],
    face: &[f64],
) -> Result<MemberDeviation, GeometryError> {
    let (m, side) = (flank.gen.member, flank.gen.side);
    let point = |xi: f64, eta: f64| -> Result<RawPoint<f64>, GeometryError> {
        let (l, d) = flank.bounds.from_unit(xi, eta);
        let uv = flank.solve_ld(l, d)?;
        Ok(flank.gen.eval(uv[0], uv[1]))
    };
    let mut points = Vec::with_capacity(profile.len() * face.len());
    for &eta in profile {
        for &xi in face {
            points.push(point(xi, eta)?);
        }
    }
    member_deviation(
        &Machine::new(s, m, side),
        &point(0.5, 0.5)?,
        &points,
        (profile, face),
    )
}

/// The deviation of the flank `base` cuts at the conjugate `points`
/// (row-major on the `(profile, face)` grid), the cut flank turned so that
/// it passes through `mean`; an error naming the member, the flank and the
/// grid node where it is not met.
fn member_deviation(
    base: &Machine,
    mean: &RawPoint<f64>,
    points: &[RawPoint<f64>],
    (profile, face): (&[f64], &[f64]),
) -> Result<MemberDeviation, GeometryError> {
    let error = |xi: f64, eta: f64| GeometryError::SettingsCut {
        member: base.member().name(),
        flank: base.side().flank_name(base.member()),
        xi,
        eta,
    };
    let machine = indexed_at(base, mean).ok_or_else(|| error(0.5, 0.5))?;
    let mut rows = vec![Vec::with_capacity(face.len()); profile.len()];
    for (n, p) in points.iter().enumerate() {
        let (i, j) = (n / face.len(), n % face.len());
        let t = normal_offset(&machine, p).ok_or_else(|| error(face[j], profile[i]))?;
        rows[i].push(-t * 1e6);
    }
    Ok(MemberDeviation {
        deviation_um: rows,
        removed_rotation_urad: -machine.index() * 1e6,
    })
}

impl SettingsDeviation {
    /// The relative deviation as a smooth surface ([`ChebyshevSurface`]),
    /// refused where the fit misses a node by more than
    /// [`MAX_FIT_RESIDUAL_UM`] (a deviation too rough for the settings
    /// to have cut it).
    pub fn surface(&self) -> Result<ChebyshevSurface, GeometryError> {
        let t = &self.topography;
        let flank = self.side.flank_name(Member::Pinion);
        match ChebyshevSurface::fit(&t.profile, &t.face, &t.deviation_um) {
            Some((s, r)) if r <= MAX_FIT_RESIDUAL_UM => Ok(s),
            other => Err(GeometryError::SettingsFit {
                flank,
                residual_um: other.map_or(f64::NAN, |(_, r)| r),
                limit_um: MAX_FIT_RESIDUAL_UM,
            }),
        }
    }
}

/// Normal lever n · (e_z × P) of a member point about its axis, m.
pub fn lever(p: &RawPoint<f64>) -> f64 {
    let (pos, n) = (Vector3::from(p.pos), Vector3::from(p.normal));
    n.dot(&Vector3::z().cross(&pos))
}

/// The distance t along the outward normal of the conjugate point `p` to
/// the flank the machine cuts (G = P + t n), None where Newton fails.
/// Newton starts from the cone point nearest the generating crown's point
/// of `p` and its crown roll.
pub fn normal_offset(machine: &Machine, p: &RawPoint<f64>) -> Option<f64> {
    let crown =
        Rotation3::from_axis_angle(&Vector3::z_axis(), -p.crown_roll) * Vector3::from(p.pos_fixed);
    let (mut zeta, mut theta) = machine.tool_parameters(&crown);
    let (pos, n) = (Vector3::from(p.pos), Vector3::from(p.normal));
    let mut roll = p.crown_roll;
    let mut t = 0.0;
    for _ in 0..30 {
        let c = machine.cut(zeta, theta, roll)?;
        roll = c.cradle_roll;
        let r = c.pos - pos - n * t;
        let at = |z: f64, th: f64| machine.cut(z, th, roll).map(|c| c.pos);
        let gz = (at(zeta + STEP_ZETA, theta)? - at(zeta - STEP_ZETA, theta)?) / (2.0 * STEP_ZETA);
        let gt =
            (at(zeta, theta + STEP_THETA)? - at(zeta, theta - STEP_THETA)?) / (2.0 * STEP_THETA);
        let step = Matrix3::from_columns(&[gz, gt, -n]).lu().solve(&(-r))?;
        zeta += step[0];
        theta += step[1];
        t += step[2];
        if (gz * step[0] + gt * step[1]).norm() < PROJECTION_TOL && step[2].abs() < PROJECTION_TOL {
            return Some(t);
        }
    }
    None
}
