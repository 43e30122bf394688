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

use crate::element::weber_banaschek::LineContact;
use geometry::flank::Flank;
use geometry::pair::FlankPair;
use geometry::utca::{correction_at, LineSearch, RollSurface};
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
        }
    }
}

/// Largest relative radius of curvature used (a flatter contact is treated as this one), m.
pub const RHO_MAX: f64 = 1.0;

/// Generating parameters and the Jacobian of (L, d) there.
type NewtonStart = ([f64; 2], Option<nalgebra::Matrix2<f64>>);
/// Last Newton step (in η) of the column search.
const NEWTON_STOP: f64 = 1e-3;

/// (d²lag/dη², ∂r/∂η) at an interior column minimum.
type Curvature = (f64, [f64; 3]);

/// A flank point and the Jacobian of (L, d) there.
type NewtonPoint = (geometry::flank::FlankPoint, Option<nalgebra::Matrix2<f64>>);

struct Column<'a> {
    fp: &'a FlankPair,
    rs: &'a RollSurface,
    target: f64,
    xi: f64,
    /// Generating parameters of the last point evaluated and the Jacobian
    /// of (L, d) there: Newton's start for the next point, which lies close
    /// by on the same column.
    last: std::cell::Cell<Option<NewtonStart>>,
    /// η interval between active surface-of-roll nodes (on both neighbouring
    /// node columns), where the wheel-bounds check is skipped: the mate of a
    /// point between active nodes lies on the wheel flank.
    trusted: std::cell::Cell<(f64, f64)>,
    /// Misaligned: the last pose correction, whose two mates start those of
    /// the next point ([`geometry::mate::pose_correction_near`]).
    near: std::cell::Cell<Option<geometry::mate::PoseCorrection>>,
}

impl<'a> Column<'a> {
    fn new(fp: &'a FlankPair, rs: &'a RollSurface, target: f64, xi: f64) -> Self {
        Column {
            fp,
            rs,
            target,
            xi,
            last: Default::default(),
            trusted: std::cell::Cell::new((f64::INFINITY, f64::NEG_INFINITY)),
            near: Default::default(),
        }
    }

    /// The pose's change to the contact of the pinion point `p` of this
    /// column ([`geometry::mate::pose_correction`]); None for the aligned
    /// pair, Some(None) where a projection fails.
    fn correction(
        &self,
        p: &geometry::flank::FlankPoint,
    ) -> Option<Option<geometry::mate::PoseCorrection>> {
        let pose = self.fp.pose.as_ref()?;
        let c = match self.near.get() {
            Some(near) => {
                geometry::mate::pose_correction_near(self.fp, pose, p.pos, self.target, &near)
            }
            None => geometry::mate::pose_correction(self.fp, pose, p.pos, self.target, p.uv),
        };
        if c.is_some() {
            self.near.set(c);
        }
        Some(c)
    }
}

impl Column<'_> {
    /// lag at profile parameter η, with the flank point; None where inactive.
    /// The pinion flank point at η of this column and the Jacobian of
    /// (L, d) there, Newton started from the last point [`Column::eval`]
    /// kept.
    fn point(&self, eta: f64) -> Option<NewtonPoint> {
        match self.last.get() {
            Some((uv, jac)) => self.fp.pinion.at_unit_from(self.xi, eta, uv, jac),
            None => self.fp.pinion.at_unit(self.xi, eta).map(|p| (p, None)),
        }
        .ok()
    }

    fn eval(&self, eta: f64) -> Option<(f64, geometry::flank::FlankPoint)> {
        if !(0.0..=1.0).contains(&eta) {
            return None;
        }
        let (p, jac) = self.point(eta)?;
        self.last.set(Some((p.uv, jac)));
        // Misaligned: the pose's exact change to the aligned model
        // ([`geometry::mate::pose_correction`]); it moves the wheel point
        // touched, which is checked against the wheel's bounds in its place.
        let correction = match self.correction(&p) {
            Some(c) => Some(c?),
            None => None,
        };
        let (lo, hi) = self.trusted.get();
        if !(lo..=hi).contains(&eta) {
            let (lw, dw) = wheel_point(self.fp, &p, correction.as_ref());
            if !self.fp.wheel.bounds.contains(lw, dw, 1e-12) {
                return None;
            }
        }
        let k = self.rs.interpolate(&self.rs.k_sep, self.xi, eta);
        let d = self.target - p.pinion_roll;
        let lag = (p.ease_off + 0.5 * k * d * d) / p.wheel_lever;
        Some((lag + correction.map_or(0.0, |c| c.lag), p))
    }

    fn value(&self, eta: f64) -> f64 {
        self.eval(eta).map_or(f64::INFINITY, |v| v.0)
    }

    /// Minimum of lag along the column, from `start`: damped Newton with
    /// finite-difference derivatives inside the node-based active interval.
    /// Where that ends at an end of the interval with lag still falling
    /// beyond it, the active region's boundary is found and the descent goes
    /// on between it and the interval's end (the minimum may lie at the
    /// boundary or just inside it). Returns the minimum, its flank point and,
    /// where the minimum is interior, the second derivative d²lag/dη² and
    /// |∂r/∂η| there.
    fn minimum(&self, start: f64) -> Option<ColumnMin> {
        let ((lo, lo_out), (hi, hi_out)) = self.active_interval()?;
        // One node spacing in from either end: the wheel's bounds can cut
        // the cell between the last active nodes of the two node columns.
        let cell = 1.0 / (self.rs.n_profile - 1) as f64;
        self.trusted.set((lo + cell, hi - cell));
        let mut best = match self.descend(start, lo, hi) {
            Some(b) => b,
            // Misaligned: the node flags hold at each node's own roll, and
            // where the wheel point touched at this roll lies past the
            // wheel's edge the start cannot be evaluated; start from the
            // best point of the column that can.
            None if self.fp.pose.is_some() => {
                self.descend(self.evaluable_start(lo, hi)?, lo, hi)?
            }
            None => return None,
        };
        let beyond = |end: f64, out: Option<f64>, towards: f64| {
            let out = out?;
            (self.value(end + towards * 1e-5) < best.lag).then(|| self.boundary(end, out))
        };
        let extended = if best.eta <= lo + 1e-9 {
            beyond(lo, lo_out, -1.0).map(|b| (b, lo))
        } else if best.eta >= hi - 1e-9 {
            beyond(hi, hi_out, 1.0).map(|b| (hi, b))
        } else {
            None
        };
        if let Some((a, b)) = extended {
            if let Some(found) = self.descend(best.eta, a, b) {
                if found.lag <= best.lag {
                    best = found;
                }
            }
            // A minimum on the boundary has no interior curvature.
            if best.eta <= a + 1e-9 || best.eta >= b - 1e-9 {
                best.curvature = None;
            }
        }
        Some(best)
    }

    /// The smallest-lag point of [`START_SAMPLES`] equally spaced on
    /// [lo, hi] that can be evaluated; None if none can.
    fn evaluable_start(&self, lo: f64, hi: f64) -> Option<f64> {
        (0..=START_SAMPLES)
            .map(|k| lo + (hi - lo) * k as f64 / START_SAMPLES as f64)
            .filter_map(|eta| self.eval(eta).map(|e| (e.0, eta)))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|e| e.1)
    }

    /// Damped Newton for the smallest lag on [lo, hi] from `start`, with
    /// central differences of step 1e-5 in η; steps are projected onto the
    /// interval and halved until lag falls. The curvature is that of the
    /// last iterate where both neighbours were active. None where the start
    /// itself is inactive.
    fn descend(&self, start: f64, lo: f64, hi: f64) -> Option<ColumnMin> {
        let mut x = start.clamp(lo, hi);
        let (mut fx, mut point) = self.eval(x)?;
        let d = 1e-5;
        let mut curv = None;
        for _ in 0..40 {
            let (em, ep) = (self.eval(x - d), self.eval(x + d));
            let (fm, fpl) = (
                em.map_or(f64::INFINITY, |e| e.0),
                ep.map_or(f64::INFINITY, |e| e.0),
            );
            curv = None;
            let newton = match (em, ep) {
                (Some(m), Some(p)) => {
                    let g1 = (fpl - fm) / (2.0 * d);
                    let g2 = (fpl + fm - 2.0 * fx) / (d * d);
                    if g2 > 0.0 {
                        curv = Some((g2, sub(p.1.pos, m.1.pos).map(|c| c / (2.0 * d))));
                        -g1 / g2
                    } else {
                        -0.05 * g1.signum()
                    }
                }
                (None, Some(_)) => -0.05 * ((fpl - fx) / d).signum(),
                (Some(_), None) => -0.05 * ((fx - fm) / d).signum(),
                (None, None) => break,
            };
            // Projected onto the interval (the full step lands exactly on
            // an end of it).
            let full = (x + newton.clamp(-0.1, 0.1)).clamp(lo, hi);
            let step = full - x;
            if step.abs() < 1e-9 {
                break;
            }
            let mut s = step;
            let mut moved = false;
            while s.abs() > 1e-9 {
                let xn = if s == step {
                    full
                } else {
                    (x + s).clamp(lo, hi)
                };
                if let Some((fnew, pnew)) = self.eval(xn).filter(|e| e.0 < fx) {
                    (x, fx, point) = (xn, fnew, pnew);
                    moved = true;
                    break;
                }
                s *= 0.5;
            }
            if !moved {
                break;
            }
            // A full Newton step of less than STOP: the next one would move
            // η by about STOP × (relative error of the difference curvature,
            // ~1e-2), the point by well under a micrometre, and the lag,
            // stationary there, by nothing measurable.
            if step.abs() < NEWTON_STOP && s == step {
                break;
            }
        }
        Some(ColumnMin {
            eta: x,
            lag: fx,
            point,
            curvature: curv,
        })
    }

    /// The active part of the column from the surface of roll angles'
    /// activity flags: (last active node, first inactive node) at each end;
    /// the outer bound is None where the column is active to its end.
    fn active_interval(&self) -> Option<(End, End)> {
        let rs = self.rs;
        let np = rs.n_profile;
        let (i, _) = rs.face_cell(self.xi);
        let on = |k: usize| rs.active[i * np + k] && rs.active[(i + 1) * np + k];
        let eta = |k: usize| k as f64 / (np - 1) as f64;
        let first = (0..np).find(|&k| on(k))?;
        let last = (0..np).rev().find(|&k| on(k))?;
        Some((
            (eta(first), first.checked_sub(1).map(eta)),
            (eta(last), (last + 1 < np).then(|| eta(last + 1))),
        ))
    }

    /// Signed distance (m) of the conjugate wheel point at η inside the
    /// wheel flank's bounds (negative outside); None where the pinion point
    /// cannot be evaluated.
    fn margin(&self, eta: f64) -> Option<f64> {
        let p = self.point(eta)?.0;
        let correction = match self.correction(&p) {
            Some(c) => Some(c?),
            None => None,
        };
        let (l, d) = wheel_point(self.fp, &p, correction.as_ref());
        Some(self.fp.wheel.bounds.margin(l, d))
    }

    /// Boundary of the active region between an active and an inactive η:
    /// regula falsi (Illinois) on the wheel-bounds margin, bracketed, to
    /// 1e-9 in η; the last η with a non-negative margin is returned.
    fn boundary(&self, inside: f64, outside: f64) -> f64 {
        let (mut a, mut b) = (inside, outside);
        let (Some(mut fa), Some(mut fb)) = (self.margin(a), self.margin(b)) else {
            return self.bisect_boundary(a, b);
        };
        if !(fa >= -1e-12 && fb < -1e-12) {
            return self.bisect_boundary(a, b);
        }
        let mut side = 0;
        for _ in 0..40 {
            if (b - a).abs() < 1e-9 {
                break;
            }
            let m = (a * fb - b * fa) / (fb - fa);
            let m = if m.is_finite() && (m - a) * (m - b) < 0.0 {
                m
            } else {
                0.5 * (a + b)
            };
            let Some(fm) = self.margin(m) else {
                b = m;
                fb = -1.0;
                continue;
            };
            // Inside with no round-off slack: the returned η must pass
            // [`Column::eval`]'s bounds check from any Newton start.
            if fm >= 0.0 {
                a = m;
                fa = fm;
                if side == -1 {
                    fb *= 0.5;
                }
                side = -1;
            } else {
                b = m;
                fb = fm;
                if side == 1 {
                    fa *= 0.5;
                }
                side = 1;
            }
            if (0.0..1e-13).contains(&fm) {
                break;
            }
        }
        a
    }

    /// Bisection fallback of [`Column::boundary`] on activity alone.
    fn bisect_boundary(&self, inside: f64, outside: f64) -> f64 {
        let (mut a, mut b) = (inside, outside);
        for _ in 0..14 {
            let m = 0.5 * (a + b);
            if self.eval(m).is_some() {
                a = m;
            } else {
                b = m;
            }
        }
        a
    }
}

/// Samples of a misaligned column's start search ([`Column::evaluable_start`]).
const START_SAMPLES: usize = 20;

/// An end of a column's active interval: (last active η, first inactive η beyond it).
type End = (f64, Option<f64>);

struct ColumnMin {
    eta: f64,
    lag: f64,
    point: geometry::flank::FlankPoint,
    curvature: Option<Curvature>,
}

/// Start of the column search from the tabulated surface of roll angles:
/// the smallest lag (E + ½ K (φ − φ(p))²) / λ₂ over the column's active
/// nodes (linear between the two neighbouring node columns), refined by the
/// parabola through it and its neighbours. None without active nodes.
fn tabulated_minimum(rs: &RollSurface, xi: f64, target: f64) -> Option<f64> {
    let np = rs.n_profile;
    let (i, w) = rs.face_cell(xi);
    let lerp = |f: &[f64], k: usize| (1.0 - w) * f[i * np + k] + w * f[(i + 1) * np + k];
    let lag = |k: usize| -> Option<f64> {
        if !(rs.active[i * np + k] && rs.active[(i + 1) * np + k]) {
            return None;
        }
        let d = target - lerp(&rs.roll, k);
        let aligned =
            (lerp(&rs.ease_off, k) + 0.5 * lerp(&rs.k_sep, k) * d * d) / lerp(&rs.lever, k);
        if rs.misaligned() {
            let c = |m: usize| {
                (1.0 - w) * rs.correction[i * np + k][m] + w * rs.correction[(i + 1) * np + k][m]
            };
            return Some(aligned + correction_at([c(0), c(1), c(2)], d));
        }
        Some(aligned)
    };
    let values: Vec<Option<f64>> = (0..np).map(lag).collect();
    let (k, fk) = values
        .iter()
        .enumerate()
        .filter_map(|(k, v)| v.map(|v| (k, v)))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    let at = |k: usize| k as f64 / (np - 1) as f64;
    if k == 0 || k + 1 == np {
        return Some(at(k));
    }
    match (values[k - 1], values[k + 1]) {
        (Some(fm), Some(fp)) if fm + fp - 2.0 * fk > 0.0 => {
            let t = (0.5 * (fm - fp) / (fm + fp - 2.0 * fk)).clamp(-1.0, 1.0);
            Some((k as f64 + t) / (np - 1) as f64)
        }
        _ => Some(at(k)),
    }
}

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
            raw.push((band, xi, c));
        }
    }
    let m = raw.len();
    let slices = (0..m)
        .map(|i| {
            let (band, xi, ref c) = raw[i];
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
            }
        })
        .collect();
    Some(PairSlices { utca_lag, slices })
}

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

/// Relative normal curvature across the contact line from the separation
/// field itself: along the column the gap λ₂·lag has second derivative
/// λ₂ H per dη², i.e. λ₂ H / |∂r/∂η|² per arc length² (λ₂ taken as constant
/// over the short distance); the column crosses the
/// contact line `line` at angle γ, so across the line κ = that / sin²γ.
fn separation_curvature(
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

#[cfg(test)]
mod tests {
    use super::*;
    use geometry::design_file::load_pair;
    use geometry::generation::Side;
    use geometry::pair::PairGeometry;
    use geometry::utca::LineGrid;

    /// The column search is a local method started from the tabulated
    /// surface of roll angles. Started instead from η = 0, 0.1, …, 1 on the
    /// same column, it must never find a smaller lag than from its own start
    /// (white-paper pair, drive flanks, one mesh cycle in 24 positions, five
    /// tooth pairs, 31 columns; lags up to 2.5 mrad, which covers every
    /// contact up to 700 N·m). Until the search went on past the node-based
    /// interval's end to the active region's boundary, it missed minima just
    /// inside the wheel's tip edge by up to 6 µrad.
    #[test]
    fn column_minimum_does_not_depend_on_the_newton_start() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../reference/white_paper_20x43.toml"
        );
        let g = PairGeometry::new(&load_pair(std::path::Path::new(path)).unwrap()).unwrap();
        let fp = g.side(Side::Drive);
        let grid = LineGrid {
            n_face: 41,
            n_profile: 41,
        };
        let rs = RollSurface::new(fp, grid).unwrap();
        let tau = g.data.mesh_cycle();
        let mut worst = (0.0f64, String::new());
        let mut columns = 0;
        for ip in 0..24 {
            let phi = fp.roll_range[0] + ip as f64 * tau / 24.0;
            for pair in -2..=2 {
                let target = phi + pair as f64 * tau;
                for ic in 0..=30 {
                    let xi = ic as f64 / 30.0;
                    let column = || Column::new(fp, &rs, target, xi);
                    let Some(own) = tabulated_minimum(&rs, xi, target) else {
                        continue;
                    };
                    let own = column().minimum(own).expect("active column has a minimum");
                    columns += 1;
                    for k in 0..=10 {
                        let Some(other) = column().minimum(k as f64 / 10.0) else {
                            continue;
                        };
                        let gain = own.lag - other.lag;
                        if other.lag < 2.5e-3 && gain > worst.0 {
                            worst = (
                                gain,
                                format!(
                                    "position {ip}, pair {pair}, ξ {xi:.3}: η {:.6} lag {:.4e} \
                                     from its own start, η {:.6} lag {:.4e} from {:.1}",
                                    own.eta,
                                    own.lag,
                                    other.eta,
                                    other.lag,
                                    k as f64 / 10.0
                                ),
                            );
                        }
                    }
                }
            }
        }
        assert!(columns > 1000, "{columns} active columns");
        assert!(
            worst.0 < 1e-6,
            "another start finds {:.3e} rad less: {}",
            worst.0,
            worst.1
        );
    }
}
