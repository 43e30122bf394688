//! The relative normal curvature across a slice's contact line: from the
//! separation field, or from the two flanks' principal curvatures.

use super::{cross, dot, norm, sub};
use geometry::flank::Flank;
use geometry::pair::FlankPair;

/// Normal curvature (convex positive) of `flank` at `uv` across the line `line`.
fn curvature_across(flank: &Flank, uv: [f64; 2], normal: [f64; 3], line: [f64; 3]) -> f64 {
    let c = flank.curvature_uv(uv[0], uv[1]);
    let t = cross(normal, line);
    let t = t.map(|x| x / norm(t));
    c.k[0] * dot(t, c.dir[0]).powi(2) + c.k[1] * dot(t, c.dir[1]).powi(2)
}

/// Relative normal curvature across the contact line from the separation
/// field itself: along the column the gap λ₂·lag has second derivative
/// λ₂ H per dη², i.e. λ₂ H / |∂r/∂η|² per arc length² (λ₂ taken as constant
/// over the short distance); the column crosses the
/// contact line `line` at angle γ, so across the line κ = that / sin²γ.
pub(super) fn separation_curvature(
    p: &geometry::flank::FlankPoint,
    h: f64,
    dr: [f64; 3],
    line: [f64; 3],
) -> f64 {
    let cos = dot(dr, line) / (norm(dr) * norm(line));
    let sin2 = (1.0 - cos * cos).max(1e-6);
    p.wheel_lever * h / dot(dr, dr) / sin2
}

/// Relative normal curvature across the contact line `line` from the two
/// flanks' principal curvatures (convex positive): κ₁(t₁) + κ₂(t₂), t = n × line.
pub fn geometric_curvature(fp: &FlankPair, p: &geometry::flank::FlankPoint, line: [f64; 3]) -> f64 {
    let w = fp.wheel.eval_uv(p.uv[0], p.uv[1]);
    let q = fp.wheel.eval_uv(p.uv[0] + 1e-6, p.uv[1]);
    let r = fp.pinion.eval_uv(p.uv[0] + 1e-6, p.uv[1]);
    // The wheel's image of `line`: map the pinion tangent through the common (u, v) parametrisation.
    let du_p = sub(r.pos, p.pos);
    let du_w = sub(q.pos, w.pos);
    let dv_p = sub(fp.pinion.eval_uv(p.uv[0], p.uv[1] + 1e-6).pos, p.pos);
    let dv_w = sub(fp.wheel.eval_uv(p.uv[0], p.uv[1] + 1e-6).pos, w.pos);
    // line = a du_p + b dv_p (least squares in the tangent plane).
    let (g11, g12, g22) = (dot(du_p, du_p), dot(du_p, dv_p), dot(dv_p, dv_p));
    let (r1, r2) = (dot(line, du_p), dot(line, dv_p));
    let det = g11 * g22 - g12 * g12;
    let (a, b) = ((r1 * g22 - r2 * g12) / det, (r2 * g11 - r1 * g12) / det);
    let line_w = [
        a * du_w[0] + b * dv_w[0],
        a * du_w[1] + b * dv_w[1],
        a * du_w[2] + b * dv_w[2],
    ];
    curvature_across(&fp.pinion, p.uv, p.normal, line)
        + curvature_across(&fp.wheel, p.uv, w.normal, line_w)
}
