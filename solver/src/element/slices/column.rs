//! The column search: along one column of the pinion flank (fixed ξ), the
//! profile point of least lag, Newton on the flank started from the
//! tabulated surface of roll angles, and the column's active interval.

use super::{sub, wheel_point};
use geometry::pair::FlankPair;
use geometry::utca::{correction_at, RollSurface};

/// Generating parameters and the Jacobian of (L, d) there.
type NewtonStart = ([f64; 2], Option<nalgebra::Matrix2<f64>>);
/// Last Newton step (in η) of the column search.
const NEWTON_STOP: f64 = 1e-3;

/// (d²lag/dη², ∂r/∂η) at an interior column minimum.
type Curvature = (f64, [f64; 3]);

/// A flank point and the Jacobian of (L, d) there.
type NewtonPoint = (geometry::flank::FlankPoint, Option<nalgebra::Matrix2<f64>>);

pub(super) struct Column<'a> {
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
    pub(super) fn new(fp: &'a FlankPair, rs: &'a RollSurface, target: f64, xi: f64) -> Self {
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

    pub(super) fn value(&self, eta: f64) -> f64 {
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
    pub(super) fn minimum(&self, start: f64) -> Option<ColumnMin> {
        let ((lo, lo_out), (hi, hi_out)) = self.active_interval()?;
        self.trusted.set(self.trusted_interval());
        let mut best = match self.descend(start, lo, hi) {
            Some(b) => b,
            // The start cannot be evaluated: misaligned, the node flags hold
            // at each node's own roll, and the wheel point touched at this
            // roll can lie past the wheel's edge; aligned, a row with one
            // active node can start beyond the wheel's edge. Start from the
            // best point of the column that can.
            None => self.descend(self.evaluable_start(lo, hi)?, lo, hi)?,
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

    /// At a minimum `lag` on an end of the column's active part: the lag's
    /// rise per unit η going inward (one-sided difference), ≥ 0. None where
    /// both neighbours are active (an interior minimum) or neither is.
    pub(super) fn inward_rise(&self, eta: f64, lag: f64) -> Option<f64> {
        const STEP: f64 = 1e-4;
        let below = self.eval(eta - STEP).map(|e| e.0);
        let above = self.eval(eta + STEP).map(|e| e.0);
        match (below, above) {
            (Some(l), None) => Some(((l - lag) / STEP).max(0.0)),
            (None, Some(u)) => Some(((u - lag) / STEP).max(0.0)),
            _ => None,
        }
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
    /// activity flags, a row counting where either neighbouring node column
    /// is active (next to the wheel's edge one of them can lie beyond it
    /// while the column itself does not): (last active node, first inactive
    /// node) at each end; the outer bound is None where the column is active
    /// to its end.
    fn active_interval(&self) -> Option<(End, End)> {
        let rs = self.rs;
        let np = rs.n_profile;
        let (i, _) = rs.face_cell(self.xi);
        let on = |k: usize| rs.active[i * np + k] || rs.active[(i + 1) * np + k];
        let eta = |k: usize| k as f64 / (np - 1) as f64;
        let first = (0..np).find(|&k| on(k))?;
        let last = (0..np).rev().find(|&k| on(k))?;
        Some((
            (eta(first), first.checked_sub(1).map(eta)),
            (eta(last), (last + 1 < np).then(|| eta(last + 1))),
        ))
    }

    /// The η interval where both neighbouring node columns are active, one
    /// node spacing in from either end: there the wheel's bounds need no
    /// check (the mate of a point between active nodes lies on the wheel
    /// flank). Empty where no row has both nodes active.
    fn trusted_interval(&self) -> (f64, f64) {
        let rs = self.rs;
        let np = rs.n_profile;
        let (i, _) = rs.face_cell(self.xi);
        let both = |k: usize| rs.active[i * np + k] && rs.active[(i + 1) * np + k];
        let cell = 1.0 / (np - 1) as f64;
        match ((0..np).find(|&k| both(k)), (0..np).rev().find(|&k| both(k))) {
            (Some(a), Some(b)) => (a as f64 * cell + cell, b as f64 * cell - cell),
            _ => (f64::INFINITY, f64::NEG_INFINITY),
        }
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

pub(super) struct ColumnMin {
    pub(super) eta: f64,
    pub(super) lag: f64,
    pub(super) point: geometry::flank::FlankPoint,
    pub(super) curvature: Option<Curvature>,
}

/// Start of the column search from the tabulated surface of roll angles:
/// the smallest lag (E + ½ K (φ − φ(p))²) / λ₂ over the column's active
/// nodes (linear between the two neighbouring node columns), refined by the
/// parabola through it and its neighbours. None without active nodes.
pub(super) fn tabulated_minimum(rs: &RollSurface, xi: f64, target: f64) -> Option<f64> {
    let np = rs.n_profile;
    let (i, w_cell) = rs.face_cell(xi);
    let lag = |k: usize| -> Option<f64> {
        // A row with one active node (the other's mate beyond the wheel's
        // edge) starts from that node's values: the column search checks the
        // wheel's bounds exactly there.
        let w = match (rs.active[i * np + k], rs.active[(i + 1) * np + k]) {
            (true, true) => w_cell,
            (true, false) => 0.0,
            (false, true) => 1.0,
            (false, false) => return None,
        };
        let lerp = |f: &[f64], k: usize| (1.0 - w) * f[i * np + k] + w * f[(i + 1) * np + k];
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
