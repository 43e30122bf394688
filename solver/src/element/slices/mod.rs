//! Flank slicing: the potential contact of each tooth pair at one position,
//! cut into slices across the face width.
//!
//! The unloaded contact comes from the surface of roll angles (see
//! [`geometry::utca`]): a pinion point p of tooth pair j touches when the
//! wheel lags the conjugate position by
//!
//!   lag(p) = [E(p) + ½ K(p) (φ₁ + jτ − φ(p))²] / λ₂(p),
//!
//! E the ease-off, φ(p) the roll angle at which p is on the conjugate contact
//! line, K the separation growth off that line, λ₂ the wheel's normal lever.
//! A slice is a band ξ ∈ [ξ_a, ξ_b] of the pinion's normalised face width;
//! its contact point is the minimum of lag along the profile at the band's
//! centre ξ_c (the point that touches first), and at wheel lag θ its
//! penetration is δ = λ₂ (θ − lag). The slice centres of a pair are anchored
//! at the pair's closest point (the UTCA minimum), ξ_c = ξ* + kΔ, so that
//! with vanishing load the element reproduces the UTCA exactly.

mod column;
mod curvature;
mod sliding;
#[cfg(test)]
mod tests;

pub use curvature::geometric_curvature;
pub use sliding::{friction_direction, friction_levers, sliding_velocity};

use crate::element::edge_cut::EdgeCut;
use crate::element::weber_banaschek::LineContact;
use column::{tabulated_minimum, Column};
use curvature::separation_curvature;
use geometry::pair::FlankPair;
use geometry::utca::{LineSearch, RollSurface};
use geometry::Material;
use serde::Serialize;

/// One slice of one tooth pair.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Slice {
    /// Tooth pair j: pinion tooth j with wheel tooth −j.
    pub pair: i32,
    /// Band of the pinion's normalised face width, and its centre.
    pub band: [f64; 2],
    pub xi: f64,
    /// Contact point: pinion normalised profile parameter, generating parameters.
    pub eta: f64,
    pub uv: [f64; 2],
    /// Contact point on the wheel flank, normalised (ξ, η).
    pub wheel_xi_eta: [f64; 2],
    /// Wheel lag (rad) at which the slice touches.
    pub lag: f64,
    /// Wheel normal lever λ₂ (m/rad) and pinion normal lever λ₁ (m).
    pub lever_wheel: f64,
    pub lever_pinion: f64,
    /// Distance of the contact point from the wheel axis, m: a normal force
    /// F here has the tangential (circumferential) component F λ₂ / ρ₂ on
    /// the wheel ([`Slice::wheel_tangential`]).
    pub wheel_radius: f64,
    /// Pinion tooth-0 position and outward normal, member frame.
    pub pos: [f64; 3],
    pub normal: [f64; 3],
    /// Contact-line length of the slice, m.
    pub length: f64,
    /// Relative radius of curvature across the contact line, m.
    pub rho: f64,
    /// Friction levers (ℓ₁, ℓ₂), m: with the pinion turning forward, a
    /// normal force F with friction coefficient μ adds the generalized forces
    /// −μ F ℓ₁ on the pinion rotation and +μ F ℓ₂ on the wheel rotation
    /// (see [`friction_levers`]).
    pub friction_lever: [f64; 2],
    /// The tip edge (pinion's or wheel's) that can cut this slice's contact
    /// strip under load; None where the contact lies far from both tips.
    pub edge: Option<EdgeCut>,
}

impl Slice {
    /// Tangential (circumferential) component on the wheel of a normal
    /// force `f` (N) at this slice, N: the wheel moment f λ₂ over the
    /// contact point's distance ρ₂ from the wheel axis,
    ///
    /// F_t = f λ₂ / ρ₂,
    ///
    /// since the moment about the axis of a force at radius ρ₂ is ρ₂ times
    /// its circumferential component. Summed over the contact it equals
    /// 2T₂/d only when every contact point lies on the circle of diameter d.
    pub fn wheel_tangential(&self, f: f64) -> f64 {
        f * self.lever_wheel / self.wheel_radius
    }

    /// Weber–Banaschek line contact of this slice with depths `h` (pinion, wheel).
    pub fn line_contact(&self, h: [f64; 2], bodies: [Material; 2]) -> LineContact {
        LineContact {
            rho: self.rho,
            length: self.length,
            h,
            bodies,
            edge: self.edge,
        }
    }
}

/// Largest relative radius of curvature used (a flatter contact is treated as this one), m.
pub const RHO_MAX: f64 = 1.0;

/// The wheel point (L, d) the pinion point `p` touches: its conjugate mate
/// (same generating parameters), moved by the pose's `correction` if any.
fn wheel_point(
    fp: &FlankPair,
    p: &geometry::flank::FlankPoint,
    correction: Option<&geometry::mate::PoseCorrection>,
) -> (f64, f64) {
    let conjugate = fp.wheel.ld(p.uv[0], p.uv[1]);
    correction.map_or(conjugate, |c| c.wheel_point(conjugate))
}

/// Pinion normal lever |(r × n)_z| about the pinion axis, m.
fn pinion_lever(pos: [f64; 3], n: [f64; 3]) -> f64 {
    (pos[0] * n[1] - pos[1] * n[0]).abs()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Profile parameter (of either member) beyond which a slice's contact is
/// checked for a tip edge that its loaded strip can reach.
const TIP_ZONE: f64 = 0.7;

/// The tip edge near a slice's contact point at (ξ, η) of the pinion and
/// `wheel` (ξ, η) of the wheel, measured across the contact line `line`
/// in the 2D model of [`crate::element::edge_cut`]. A contact point on an
/// end of its column's active part (`rise` = the lag's rise per unit η
/// inward) that is a member's tip is cut there, with gap slope
/// s = λ₂ rise / |∂r/∂η| / sin γ; otherwise the distance to the nearer tip,
/// (1 − η) |∂r/∂η| sin γ on the pinion, likewise on the wheel, γ the angle
/// between the pinion's profile direction and the contact line (the
/// wheel's profile is taken as crossing it at the same angle). None away
/// from both tips and at other ends (toe, heel, root limits).
#[allow(clippy::too_many_arguments)]
fn tip_cut(
    fp: &FlankPair,
    xi: f64,
    eta: f64,
    wheel: [f64; 2],
    line: [f64; 3],
    rise: Option<f64>,
    dr: Option<[f64; 3]>,
    lever_wheel: f64,
) -> Option<EdgeCut> {
    const STEP: f64 = 1e-3;
    if eta <= TIP_ZONE && wheel[1] <= TIP_ZONE {
        return None;
    }
    // ∂r/∂η: the column search's where it has one, else by differences.
    let dr = match dr {
        Some(dr) => dr,
        None => {
            let (lo, hi) = ((eta - STEP).max(0.0), (eta + STEP).min(1.0));
            sub(
                fp.pinion.at_unit(xi, hi).ok()?.pos,
                fp.pinion.at_unit(xi, lo).ok()?.pos,
            )
            .map(|x| x / (hi - lo))
        }
    };
    let per_eta = norm(dr);
    let cos = dot(dr, line) / (per_eta * norm(line));
    // Floor: a contact line almost along the profile is cut over a long
    // way; its distance across the line is then tiny but not zero.
    let sin = (1.0 - cos * cos).max(0.0).sqrt().max(0.05);
    if let Some(rise) = rise {
        let at_tip = eta >= 1.0 - 1e-9 || wheel[1] >= 1.0 - 1e-3;
        return at_tip.then(|| EdgeCut {
            distance_m: 0.0,
            slope: lever_wheel * rise / per_eta / sin,
        });
    }
    let pinion = (1.0 - eta) * per_eta * sin;
    let wheel_d = if wheel[1] > TIP_ZONE {
        let g = crate::element::edge_contact::profile_length_per_eta(
            &fp.wheel,
            wheel[0].clamp(0.0, 1.0),
            wheel[1].clamp(0.0, 1.0),
        )?;
        (1.0 - wheel[1]) * g * sin
    } else {
        f64::INFINITY
    };
    let d = if eta > TIP_ZONE {
        pinion
    } else {
        f64::INFINITY
    }
    .min(wheel_d);
    Some(EdgeCut {
        distance_m: d,
        slope: 0.0,
    })
}

/// A tooth pair's slices and its unloaded (UTCA) contact lag.
#[derive(Debug, Clone)]
pub struct PairSlices {
    pub utca_lag: f64,
    pub slices: Vec<Slice>,
}

/// The slices of tooth pair `pair` at pinion angle `phi`: `n` bands across
/// the face width, anchored at the pair's closest point. None when the pair
/// has no active point.
pub fn pair_slices(
    fp: &FlankPair,
    rs: &RollSurface,
    phi: f64,
    tau: f64,
    pair: i32,
    n: usize,
) -> Option<PairSlices> {
    let ls = LineSearch::new(fp, rs);
    let target = phi + pair as f64 * tau;
    let (utca_lag, uv_star) = ls.min_contact(target)?;
    let (l, d) = fp.pinion.ld(uv_star[0], uv_star[1]);
    let (xi_star, _) = fp.pinion.bounds.to_unit(l, d);
    let delta = 1.0 / n as f64;
    // Bands [c − Δ/2, c + Δ/2] ∩ [0, 1] around c = ξ* + kΔ. A band whose
    // centre lies outside the face keeps its clipped part, loaded at the
    // face edge: as ξ* moves with the pinion, an edge band grows from zero
    // length instead of appearing whole, so the element stays continuous in
    // the rotation.
    let k0 = ((-0.5 * delta - xi_star) / delta).ceil() as i64;
    let k1 = ((1.0 + 0.5 * delta - xi_star) / delta).floor() as i64;
    let mut raw = Vec::with_capacity((k1 - k0 + 1).max(0) as usize);
    for k in k0..=k1 {
        let c = xi_star + k as f64 * delta;
        let band = [(c - 0.5 * delta).max(0.0), (c + 0.5 * delta).min(1.0)];
        if band[1] - band[0] <= 1e-9 * delta {
            continue;
        }
        let xi = c.clamp(0.0, 1.0);
        let col = Column::new(fp, rs, target, xi);
        // No active node on the column: no contact there either.
        let Some(start) = tabulated_minimum(rs, xi, target) else {
            continue;
        };
        if let Some(c) = col.minimum(start) {
            // Only a minimum without interior curvature can sit on an end.
            let rise = match c.curvature {
                Some(_) => None,
                None => col.inward_rise(c.eta, c.lag),
            };
            raw.push((band, xi, c, rise));
        }
    }
    let m = raw.len();
    let slices = (0..m)
        .map(|i| {
            let (band, xi, ref c, rise) = raw[i];
            let p = c.point;
            // Contact-line tangent from the neighbouring contact points.
            let (a, b) = match m {
                1 => (i, i),
                _ if i == 0 => (0, 1),
                _ if i + 1 == m => (m - 2, m - 1),
                _ => (i - 1, i + 1),
            };
            let (dp, dxi) = if a == b {
                let q = fp.pinion.at_unit((xi + 1e-4).min(1.0), c.eta).ok();
                (q.map_or([1.0, 0.0, 0.0], |q| sub(q.pos, p.pos)), 1e-4)
            } else {
                (
                    sub(raw[b].2.point.pos, raw[a].2.point.pos),
                    raw[b].1 - raw[a].1,
                )
            };
            let length = norm(dp) / dxi.abs() * (band[1] - band[0]);
            let kappa = match c.curvature {
                Some((h, dr)) => separation_curvature(&p, h, dr, dp),
                None => geometric_curvature(fp, &p, dp),
            };
            // The wheel point the slice touches and the wheel's lever: the
            // conjugate mate (same generating parameters) for the aligned
            // pair, moved and changed by the pose for a misaligned one.
            let correction = fp
                .pose
                .as_ref()
                .and_then(|pose| geometry::mate::pose_correction(fp, pose, p.pos, target, p.uv));
            let lever_wheel = p.wheel_lever + correction.map_or(0.0, |c| c.lever);
            let (lw, dw) = wheel_point(fp, &p, correction.as_ref());
            let (xw, ew) = fp.wheel.bounds.to_unit(lw, dw);
            let wheel_radius = fp.wheel.gen.frame.radius_at(lw, dw);
            let friction_lever = friction_levers(fp, p.pos, p.normal, target);
            let dr = c.curvature.map(|(_, dr)| dr);
            let edge = tip_cut(fp, xi, c.eta, [xw, ew], dp, rise, dr, lever_wheel);
            Slice {
                pair,
                band,
                xi,
                eta: c.eta,
                uv: p.uv,
                wheel_xi_eta: [xw, ew],
                lag: c.lag,
                lever_wheel,
                lever_pinion: pinion_lever(p.pos, p.normal),
                wheel_radius,
                pos: p.pos,
                normal: p.normal,
                length,
                rho: 1.0 / kappa.max(1.0 / RHO_MAX),
                friction_lever,
                edge,
            }
        })
        .collect();
    Some(PairSlices { utca_lag, slices })
}
