//! Unloaded tooth contact analysis through the surface of roll angles.
//!
//! Each pinion flank point p carries the pinion roll angle φ(p) at which it is
//! on the conjugate contact line, its ease-off E(p) and the wheel's normal
//! lever λ₂(p) = |n · (a₂ × r)|. Pinion tooth j is in conjugate contact along
//! the level line φ(p) = φ₁ + j·2π/z₁; with the ease-off the wheel must lag by
//! E/λ₂ to touch at p, so the unloaded transmission error is
//!
//! TE(φ₁) = min_j min_{p on line j, p active} E(p) / λ₂(p)
//!
//! (wheel side, rad; positive = the wheel lags behind the conjugate position).
//! This is first-order exact in the ease-off; [`crate::direct`] checks it
//! against a direct geometric contact search.

use crate::error::GeometryError;
use crate::pair::FlankPair;
use serde::Serialize;

/// Discretisation of the contact lines.
#[derive(Debug, Clone, Copy)]
pub struct LineGrid {
    /// Columns across the face width (samples along a contact line).
    pub n_face: usize,
    /// Nodes along the profile used to bracket the contact line.
    pub n_profile: usize,
}

impl Default for LineGrid {
    fn default() -> Self {
        LineGrid {
            n_face: 41,
            n_profile: 41,
        }
    }
}

/// Pinion flank grid with generating parameters and roll angles: the
/// tabulated surface of roll angles.
#[derive(Debug, Clone, Serialize)]
pub struct RollSurface {
    pub n_face: usize,
    pub n_profile: usize,
    /// (ζ, s) at node (ξ_i, η_k), index i·n_profile + k.
    pub uv: Vec<[f64; 2]>,
    /// Pinion roll angle at the nodes, rad.
    pub roll: Vec<f64>,
}

/// The contact point of one tooth pair at one position.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ToothContact {
    /// Pinion tooth index j (meshing with wheel tooth −j).
    pub tooth: i32,
    /// Wheel lag needed for contact at this tooth, rad.
    pub te: f64,
    pub uv: [f64; 2],
    /// Axial-section coordinates on the pinion flank, m.
    pub l: f64,
    pub d: f64,
    /// Position on pinion tooth 0 (member frame), m.
    pub pos: [f64; 3],
}

/// UTCA result of one flank pair over a rotation sweep.
#[derive(Debug, Clone, Serialize)]
pub struct Utca {
    pub side: crate::generation::Side,
    /// Pinion angles of the sweep, rad.
    pub pinion_angle: Vec<f64>,
    /// Unloaded TE, wheel side, rad.
    pub te: Vec<f64>,
    /// Index into `teeth[k]` of the tooth in contact at each position.
    pub contact: Vec<usize>,
    /// All tooth pairs on their contact lines at each position.
    pub teeth: Vec<Vec<ToothContact>>,
    /// Conjugate contact ratio (active roll range / mesh cycle).
    pub contact_ratio: f64,
}

impl Utca {
    /// Peak-to-peak TE, rad.
    pub fn te_ptp(&self) -> f64 {
        let (lo, hi) = self
            .te
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &t| (a.min(t), b.max(t)));
        hi - lo
    }
}

impl RollSurface {
    pub fn new(fp: &FlankPair, grid: LineGrid) -> Result<Self, GeometryError> {
        let uv = fp.pinion_grid(grid.n_face, grid.n_profile)?;
        let roll = uv
            .iter()
            .map(|&[u, v]| fp.pinion.eval_uv(u, v).pinion_roll)
            .collect();
        Ok(RollSurface {
            n_face: grid.n_face,
            n_profile: grid.n_profile,
            uv,
            roll,
        })
    }
}

/// Contact-line search on one flank pair.
pub struct LineSearch<'a> {
    pub fp: &'a FlankPair,
    pub rs: &'a RollSurface,
    k1: f64,
}

impl<'a> LineSearch<'a> {
    pub fn new(fp: &'a FlankPair, rs: &'a RollSurface) -> Self {
        LineSearch {
            fp,
            rs,
            k1: fp.pinion.gen.frame.roll_ratio,
        }
    }

    fn roll(&self, uv: [f64; 2]) -> f64 {
        self.fp.pinion.gen.eval(uv[0], uv[1]).crown_roll * self.k1
    }

    /// Point of the level line φ = `target` on the (fractional) column `t`.
    pub fn line_point(&self, t: f64, target: f64) -> Option<[f64; 2]> {
        let rs = self.rs;
        let np = rs.n_profile;
        let i0 = (t.floor() as usize).min(rs.n_face - 2);
        let w = t - i0 as f64;
        let node = |k: usize| {
            let a = rs.uv[i0 * np + k];
            let b = rs.uv[(i0 + 1) * np + k];
            let ra = rs.roll[i0 * np + k];
            let rb = rs.roll[(i0 + 1) * np + k];
            ([a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])], ra + w * (rb - ra))
        };
        let mut prev = node(0);
        for k in 1..np {
            let cur = node(k);
            let (f0, f1) = (prev.1 - target, cur.1 - target);
            if f0 == 0.0 || f0.signum() != f1.signum() {
                return Some(self.secant(prev.0, cur.0, f0 / (f0 - f1), target));
            }
            prev = cur;
        }
        None
    }

    /// Solves roll(a + s (b − a)) = target by Newton with a secant slope.
    fn secant(&self, a: [f64; 2], b: [f64; 2], s0: f64, target: f64) -> [f64; 2] {
        let at = |s: f64| [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
        let mut s = s0;
        let ds = 1e-6;
        for _ in 0..8 {
            let f = self.roll(at(s)) - target;
            if f.abs() < 1e-13 {
                break;
            }
            let g = (self.roll(at(s + ds)) - target - f) / ds;
            s -= f / g;
        }
        at(s)
    }

    /// Wheel lag E/λ₂ needed at the line point, if the point is active.
    fn value(&self, uv: [f64; 2], tol: f64) -> Option<f64> {
        let (p, ok) = self.fp.point(uv[0], uv[1], tol);
        ok.then(|| p.ease_off / p.wheel_lever)
    }

    fn value_at(&self, t: f64, target: f64) -> f64 {
        self.line_point(t, target)
            .and_then(|uv| self.value(uv, 1e-12))
            .unwrap_or(f64::INFINITY)
    }

    /// Minimum of E/λ₂ along the contact line of roll `target`: samples at
    /// every column, then a golden-section refinement around the best one.
    pub fn min_on_line(&self, target: f64) -> Option<(f64, [f64; 2])> {
        let n = self.rs.n_face;
        let mut best: Option<(usize, f64)> = None;
        for i in 0..n {
            let v = self.value_at(i as f64, target);
            if v.is_finite() && best.is_none_or(|(_, b)| v < b) {
                best = Some((i, v));
            }
        }
        let (i, _) = best?;
        let (mut a, mut b) = ((i as f64 - 1.0).max(0.0), (i as f64 + 1.0).min((n - 1) as f64));
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let mut c = b - g * (b - a);
        let mut d = a + g * (b - a);
        let (mut fc, mut fd) = (self.value_at(c, target), self.value_at(d, target));
        while b - a > 1e-5 {
            if fc <= fd {
                b = d;
                d = c;
                fd = fc;
                c = b - g * (b - a);
                fc = self.value_at(c, target);
            } else {
                a = c;
                c = d;
                fc = fd;
                d = a + g * (b - a);
                fd = self.value_at(d, target);
            }
        }
        let mut cands = vec![i as f64, c, d];
        cands.retain(|t| self.value_at(*t, target).is_finite());
        let t = cands
            .into_iter()
            .min_by(|x, y| self.value_at(*x, target).total_cmp(&self.value_at(*y, target)))?;
        let uv = self.line_point(t, target)?;
        Some((self.value(uv, 1e-12)?, uv))
    }
}

/// Runs the UTCA for pinion angles `start + σ k step`, k = 0..n, σ the
/// driving direction of the side.
pub fn run(
    fp: &FlankPair,
    rs: &RollSurface,
    start: f64,
    step: f64,
    n: usize,
    direction: f64,
) -> Utca {
    let ls = LineSearch::new(fp, rs);
    let tau = fp.pinion.gen.frame.pitch();
    let [r0, r1] = fp.roll_range;
    let mut out = Utca {
        side: fp.side,
        pinion_angle: Vec::with_capacity(n),
        te: Vec::with_capacity(n),
        contact: Vec::with_capacity(n),
        teeth: Vec::with_capacity(n),
        contact_ratio: (r1 - r0) / tau,
    };
    for k in 0..n {
        let phi = start + direction * step * k as f64;
        let jmin = ((r0 - phi) / tau).ceil() as i32;
        let jmax = ((r1 - phi) / tau).floor() as i32;
        let mut teeth = Vec::new();
        for j in jmin..=jmax {
            let target = phi + j as f64 * tau;
            if let Some((te, uv)) = ls.min_on_line(target) {
                let p = fp.pinion.eval_uv(uv[0], uv[1]);
                teeth.push(ToothContact {
                    tooth: j,
                    te,
                    uv,
                    l: p.l,
                    d: p.d,
                    pos: p.pos,
                });
            }
        }
        let (ci, te) = teeth
            .iter()
            .enumerate()
            .map(|(i, t)| (i, t.te))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((usize::MAX, f64::NAN));
        out.pinion_angle.push(phi);
        out.te.push(te);
        out.contact.push(ci);
        out.teeth.push(teeth);
    }
    out
}
