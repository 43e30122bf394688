//! Flank slicing: the potential contact of each tooth pair at one position,
//! cut into slices across the face width.
//!
//! The unloaded contact comes from the surface of roll angles (see
//! [`preprocess::utca`]): a pinion point p of tooth pair j touches when the
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

use crate::weber_banaschek::{Elastic, LineContact};
use preprocess::flank::Flank;
use preprocess::pair::FlankPair;
use preprocess::utca::{LineSearch, RollSurface};
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
    /// Pinion tooth-0 position and outward normal, member frame.
    pub pos: [f64; 3],
    pub normal: [f64; 3],
    /// Contact-line length of the slice, m.
    pub length: f64,
    /// Relative radius of curvature across the contact line, m.
    pub rho: f64,
}

impl Slice {
    /// Weber–Banaschek line contact of this slice with depths `h` (pinion, wheel).
    pub fn line_contact(&self, h: [f64; 2], bodies: [Elastic; 2]) -> LineContact {
        LineContact {
            rho: self.rho,
            length: self.length,
            h,
            bodies,
        }
    }
}

/// Largest relative radius of curvature used (a flatter contact is treated as this one), m.
pub const RHO_MAX: f64 = 1.0;

struct Column<'a> {
    fp: &'a FlankPair,
    rs: &'a RollSurface,
    target: f64,
    xi: f64,
}

impl Column<'_> {
    /// lag at profile parameter η, with the flank point; None where inactive.
    fn eval(&self, eta: f64) -> Option<(f64, preprocess::flank::FlankPoint)> {
        if !(0.0..=1.0).contains(&eta) {
            return None;
        }
        let p = self.fp.pinion.at_unit(self.xi, eta).ok()?;
        let (lw, dw) = self.fp.wheel.ld(p.uv[0], p.uv[1]);
        if !self.fp.wheel.bounds.contains(lw, dw, 1e-12) {
            return None;
        }
        let k = self.rs.interpolate(&self.rs.k_sep, self.xi, eta);
        let d = self.target - p.pinion_roll;
        Some(((p.ease_off + 0.5 * k * d * d) / p.wheel_lever, p))
    }

    fn value(&self, eta: f64) -> f64 {
        self.eval(eta).map_or(f64::INFINITY, |v| v.0)
    }

    /// Minimum of lag along the column, from `start`: damped Newton with
    /// finite-difference derivatives; stops at the edge of the active region.
    fn minimum(&self, start: f64) -> Option<(f64, preprocess::flank::FlankPoint)> {
        let mut x = start.clamp(0.0, 1.0);
        let mut fx = self.value(x);
        if !fx.is_finite() {
            let (best, fb) = (0..=32)
                .map(|k| k as f64 / 32.0)
                .map(|e| (e, self.value(e)))
                .min_by(|a, b| a.1.total_cmp(&b.1))?;
            if !fb.is_finite() {
                return None;
            }
            (x, fx) = (best, fb);
        }
        let d = 1e-5;
        for _ in 0..40 {
            let (fm, fpl) = (self.value(x - d), self.value(x + d));
            let step = match (fm.is_finite(), fpl.is_finite()) {
                (true, true) => {
                    let g1 = (fpl - fm) / (2.0 * d);
                    let g2 = (fpl + fm - 2.0 * fx) / (d * d);
                    if g2 > 0.0 {
                        -g1 / g2
                    } else {
                        -0.02 * g1.signum()
                    }
                }
                (false, true) => -0.02 * ((fpl - fx) / d).signum(),
                (true, false) => -0.02 * ((fx - fm) / d).signum(),
                (false, false) => break,
            }
            .clamp(-0.1, 0.1);
            let mut s = step;
            let mut moved = false;
            while s.abs() > 1e-13 {
                let fnew = self.value(x + s);
                if fnew < fx {
                    x += s;
                    fx = fnew;
                    moved = true;
                    break;
                }
                s *= 0.5;
            }
            if !moved || s.abs() < 1e-10 {
                break;
            }
        }
        self.eval(x)
    }
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

/// Normal curvature (convex positive) of `flank` at `uv` across the line `line`.
fn curvature_across(flank: &Flank, uv: [f64; 2], normal: [f64; 3], line: [f64; 3]) -> f64 {
    let c = flank.curvature_uv(uv[0], uv[1]);
    let t = cross(normal, line);
    let t = t.map(|x| x / norm(t));
    c.k[0] * dot(t, c.dir[0]).powi(2) + c.k[1] * dot(t, c.dir[1]).powi(2)
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
    let k0 = -((xi_star / delta).floor() as i64);
    let k1 = ((1.0 - xi_star) / delta).floor() as i64;
    let centres: Vec<f64> = (k0..=k1)
        .map(|k| (xi_star + k as f64 * delta).clamp(0.0, 1.0))
        .collect();
    let m = centres.len();
    let mut raw = Vec::with_capacity(m);
    for (i, &xi) in centres.iter().enumerate() {
        let band = [
            if i == 0 { 0.0 } else { xi - 0.5 * delta },
            if i + 1 == m { 1.0 } else { xi + 0.5 * delta },
        ];
        let col = Column { fp, rs, target, xi };
        let start = ls
            .line_point(xi * (rs.n_face - 1) as f64, target)
            .map(|uv| {
                let (l, d) = fp.pinion.ld(uv[0], uv[1]);
                fp.pinion.bounds.to_unit(l, d).1
            })
            .unwrap_or_else(|| {
                if col.value(0.0) < col.value(1.0) {
                    0.0
                } else {
                    1.0
                }
            });
        if let Some((lag, p)) = col.minimum(start) {
            raw.push((band, xi, lag, p));
        }
    }
    // Contact-line tangent from neighbouring contact points (pinion and wheel
    // frames), slice length and relative curvature across the line.
    let wheel_pts: Vec<_> = raw
        .iter()
        .map(|r| fp.wheel.eval_uv(r.3.uv[0], r.3.uv[1]))
        .collect();
    let m = raw.len();
    let slices = (0..m)
        .map(|i| {
            let (band, xi, lag, p) = raw[i];
            let (a, b) = match m {
                1 => (i, i),
                _ if i == 0 => (0, 1),
                _ if i + 1 == m => (m - 2, m - 1),
                _ => (i - 1, i + 1),
            };
            let (dp, dw, dxi) = if a == b {
                let q = fp.pinion.at_unit((xi + 1e-4).min(1.0), p_eta(fp, &p)).ok();
                match q {
                    Some(q) => {
                        let w = fp.wheel.eval_uv(q.uv[0], q.uv[1]);
                        (sub(q.pos, p.pos), sub(w.pos, wheel_pts[i].pos), 1e-4)
                    }
                    None => ([1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1.0),
                }
            } else {
                (
                    sub(raw[b].3.pos, raw[a].3.pos),
                    sub(wheel_pts[b].pos, wheel_pts[a].pos),
                    raw[b].1 - raw[a].1,
                )
            };
            let length = norm(dp) / dxi.abs() * (band[1] - band[0]);
            let k1 = curvature_across(&fp.pinion, p.uv, p.normal, dp);
            let k2 = curvature_across(&fp.wheel, p.uv, wheel_pts[i].normal, dw);
            let (lw, dw_) = fp.wheel.ld(p.uv[0], p.uv[1]);
            let (xw, ew) = fp.wheel.bounds.to_unit(lw, dw_);
            Slice {
                pair,
                band,
                xi,
                eta: p_eta(fp, &p),
                uv: p.uv,
                wheel_xi_eta: [xw, ew],
                lag,
                lever_wheel: p.wheel_lever,
                lever_pinion: pinion_lever(p.pos, p.normal),
                pos: p.pos,
                normal: p.normal,
                length,
                rho: 1.0 / (k1 + k2).max(1.0 / RHO_MAX),
            }
        })
        .collect();
    Some(PairSlices { utca_lag, slices })
}

fn p_eta(fp: &FlankPair, p: &preprocess::flank::FlankPoint) -> f64 {
    fp.pinion.bounds.to_unit(p.l, p.d).1
}
