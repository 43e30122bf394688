//! Unloaded tooth contact analysis through the surface of roll angles.
//!
//! Each pinion flank point p carries the pinion roll angle φ(p) at which it is
//! on the conjugate contact line, its ease-off E(p), the wheel's normal lever
//! λ₂(p) = |n · (a₂ × r)| and the growth K(p) of the conjugate separation when
//! the pair turns away from that roll angle, s = ½ K (φ − φ(p))² (tabulated
//! once by the direct projection). Pinion tooth j is at roll φ₁ + j·2π/z₁, and
//! the wheel must lag by (E + s)/λ₂ to touch at p, so the unloaded
//! transmission error is
//!
//! TE(φ₁) = min_j min_p [E(p) + ½ K(p) (φ₁ + jτ − φ(p))²] / λ₂(p)
//!
//! (wheel side, rad; positive = the wheel lags behind the conjugate position),
//! minimised over the active flank: grid nodes first, then Newton. With
//! K = 0 this would be the minimum along the conjugate contact line, which
//! misses off-line contact where the ease-off slopes across the line.
//! [`crate::direct`] checks the result against a direct geometric contact search.

use crate::design::PairData;
use crate::error::GeometryError;
use crate::pair::pinion_direction;
use crate::pair::FlankPair;
use crate::scene::UtcaSettings;
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
    /// Ease-off at the nodes, m.
    pub ease_off: Vec<f64>,
    /// Wheel lever at the nodes, m/rad.
    pub lever: Vec<f64>,
    /// Conjugate separation growth K at the nodes, m/rad².
    pub k_sep: Vec<f64>,
    /// Node lies on both flanks.
    pub active: Vec<bool>,
    /// Misaligned pair only (empty otherwise): the pose's change to the
    /// node's lag ([`crate::mate::pose_correction`]) as the parabola
    /// [c₀, c₁, c₂] through its values at the node's own roll φ(p) and at
    /// φ(p) ± δ (rad, rad/rad, rad/rad²); the node's lag at roll φ is the
    /// aligned one plus c₀ + c₁ (φ − φ(p)) + ½ c₂ (φ − φ(p))². It starts the
    /// searches, which then use the exact correction. All the other fields
    /// are the aligned pair's.
    pub correction: Vec<[f64; 3]>,
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
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &t| {
                (a.min(t), b.max(t))
            });
        hi - lo
    }
}

impl RollSurface {
    pub fn new(fp: &FlankPair, grid: LineGrid) -> Result<Self, GeometryError> {
        let uv = fp.pinion_grid(grid.n_face, grid.n_profile)?;
        let pts: Vec<_> = uv.iter().map(|&[u, v]| fp.pinion.eval_uv(u, v)).collect();
        let mut rs = RollSurface {
            n_face: grid.n_face,
            n_profile: grid.n_profile,
            roll: pts.iter().map(|p| p.pinion_roll).collect(),
            ease_off: pts.iter().map(|p| p.ease_off).collect(),
            lever: pts.iter().map(|p| p.wheel_lever).collect(),
            active: Vec::new(),
            uv: Vec::new(),
            k_sep: Vec::new(),
            correction: Vec::new(),
        };
        rs.k_sep = uv
            .iter()
            .zip(&pts)
            .map(|(&uv, p)| separation_growth(fp, uv, p.pinion_roll))
            .collect();
        match &fp.pose {
            None => {
                rs.active = uv
                    .iter()
                    .map(|&[u, v]| fp.is_active(u, v, crate::pair::EDGE_TOL))
                    .collect();
            }
            Some(pose) => {
                for (&uv, p) in uv.iter().zip(&pts) {
                    let node = posed_node(fp, pose, uv, p.pos, p.pinion_roll);
                    rs.active.push(node.is_some_and(|q| q.active));
                    rs.correction.push(node.map_or([0.0; 3], |q| q.lag));
                }
            }
        }
        rs.uv = uv;
        Ok(rs)
    }

    /// Whether the surface was made for a misaligned pair.
    pub fn misaligned(&self) -> bool {
        !self.correction.is_empty()
    }

    /// The node model's lag of node `n` when its tooth is at roll `target`, rad.
    pub fn node_lag(&self, n: usize, target: f64) -> f64 {
        let d = target - self.roll[n];
        let aligned = (self.ease_off[n] + 0.5 * self.k_sep[n] * d * d) / self.lever[n];
        match self.correction.get(n) {
            Some(c) => aligned + correction_at(*c, d),
            None => aligned,
        }
    }

    /// Node column i at or before face parameter ξ (clamped to the grid)
    /// and ξ's weight w ∈ [0, 1] towards column i + 1.
    pub fn face_cell(&self, xi: f64) -> (usize, f64) {
        let nf = self.n_face;
        let x = (xi * (nf - 1) as f64).clamp(0.0, (nf - 1) as f64);
        let i = (x as usize).min(nf - 2);
        (i, x - i as f64)
    }

    /// Bilinear interpolation of a node field at normalised (ξ, η).
    pub fn interpolate(&self, field: &[f64], xi: f64, eta: f64) -> f64 {
        let np = self.n_profile;
        let (i, a) = self.face_cell(xi);
        let y = (eta * (np - 1) as f64).clamp(0.0, (np - 1) as f64);
        let k = (y as usize).min(np - 2);
        let b = y - k as f64;
        let f = |i: usize, k: usize| field[i * np + k];
        (1.0 - a) * ((1.0 - b) * f(i, k) + b * f(i, k + 1))
            + a * ((1.0 - b) * f(i + 1, k) + b * f(i + 1, k + 1))
    }
}

/// Roll step δ of the separation growth's differences.
const GROWTH_STEP_DEG: f64 = 0.05;

/// K = (g(+δ) + g(−δ) − 2 g(0)) / δ²: conjugate separation growth of the
/// pinion point at `uv` when the pair turns by ±δ from its contact roll angle.
fn separation_growth(fp: &FlankPair, uv: [f64; 2], roll: f64) -> f64 {
    let delta = GROWTH_STEP_DEG.to_radians();
    let g = |d: f64| {
        let phi = roll + d;
        let at = crate::placement::Placement {
            pinion: phi,
            wheel: fp.conjugate_wheel_angle(phi),
        };
        crate::placement::gap(fp, at, 0, uv, uv).map_or(f64::NAN, |x| x.0)
    };
    let k = (g(delta) + g(-delta) - 2.0 * g(0.0)) / (delta * delta);
    if k.is_finite() {
        k.max(0.0)
    } else {
        0.0
    }
}

/// The pose correction's lag parabola [c₀, c₁, c₂] at roll offset `d`
/// (rad): c₀ + c₁ d + ½ c₂ d².
pub fn correction_at(c: [f64; 3], d: f64) -> f64 {
    c[0] + c[1] * d + 0.5 * c[2] * d * d
}

/// A node of a misaligned pair: the pose correction's lag parabola in the
/// roll about the node's own roll angle, and whether the node can touch.
#[derive(Clone, Copy)]
struct PosedNode {
    lag: [f64; 3],
    active: bool,
}

/// The pose corrections ([`crate::mate::pose_correction`]) of the pinion
/// point `pos` (at `uv`) at rolls φ(p) and φ(p) ± δ: value, slope and
/// curvature of their parabola. The node is active when it lies on the
/// pinion flank and the wheel point it touches at φ(p) (its conjugate
/// point moved by the correction) on the wheel flank, the aligned pair's
/// test ([`FlankPair::is_active`]) with the pose. None where a projection
/// fails.
fn posed_node(
    fp: &FlankPair,
    pose: &crate::misalignment::Pose,
    uv: [f64; 2],
    pos: [f64; 3],
    roll: f64,
) -> Option<PosedNode> {
    let delta = GROWTH_STEP_DEG.to_radians();
    let c = |d: f64| crate::mate::pose_correction(fp, pose, pos, roll + d, uv);
    let c0 = c(0.0)?;
    let (cp, cm) = (c(delta)?.lag, c(-delta)?.lag);
    let tol = crate::pair::EDGE_TOL;
    let (l, d) = fp.pinion.ld(uv[0], uv[1]);
    let (lw, dw) = c0.wheel_point(fp.wheel.ld(uv[0], uv[1]));
    Some(PosedNode {
        lag: [
            c0.lag,
            (cp - cm) / (2.0 * delta),
            (cp + cm - 2.0 * c0.lag) / (delta * delta),
        ],
        active: fp.pinion.bounds.contains(l, d, tol) && fp.wheel.bounds.contains(lw, dw, tol),
    })
}

/// Contact-line search on one flank pair.
pub struct LineSearch<'a> {
    pub fp: &'a FlankPair,
    pub rs: &'a RollSurface,
    k1: f64,
    /// Misaligned: the last pose correction, whose mates start those of the
    /// next point ([`crate::mate::pose_correction_near`]).
    near: std::cell::Cell<Option<crate::mate::PoseCorrection>>,
}

impl<'a> LineSearch<'a> {
    pub fn new(fp: &'a FlankPair, rs: &'a RollSurface) -> Self {
        LineSearch {
            fp,
            rs,
            k1: fp.pinion.gen.frame.roll_ratio,
            near: Default::default(),
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
            (
                [a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])],
                ra + w * (rb - ra),
            )
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

    /// Wheel lag needed for contact at pinion point `uv` of the tooth at
    /// roll `target`: from the surface of roll angles, plus the pose's
    /// exact change ([`crate::mate::pose_correction`]) for a misaligned
    /// pair.
    pub fn lag(&self, uv: [f64; 2], target: f64) -> Option<f64> {
        let fp = self.fp;
        let aligned = |p: &crate::flank::FlankPoint| {
            let (xi, eta) = fp.pinion.bounds.to_unit(p.l, p.d);
            let k = self.rs.interpolate(&self.rs.k_sep, xi, eta);
            let dphi = target - p.pinion_roll;
            (p.ease_off + 0.5 * k * dphi * dphi) / p.wheel_lever
        };
        if let Some(pose) = &fp.pose {
            // The aligned model plus the pose's exact change, the touched
            // wheel point (the conjugate one moved by it) on the wheel.
            let p = fp.pinion.eval_uv(uv[0], uv[1]);
            if !fp.pinion.bounds.contains(p.l, p.d, 1e-12) {
                return None;
            }
            let c = match self.near.get() {
                Some(near) => crate::mate::pose_correction_near(fp, pose, p.pos, target, &near),
                None => crate::mate::pose_correction(fp, pose, p.pos, target, uv),
            }?;
            self.near.set(Some(c));
            let (lw, dw) = c.wheel_point(fp.wheel.ld(uv[0], uv[1]));
            return fp
                .wheel
                .bounds
                .contains(lw, dw, 1e-12)
                .then(|| aligned(&p) + c.lag);
        }
        let (p, ok) = fp.point(uv[0], uv[1], 1e-12);
        if !ok {
            return None;
        }
        Some(aligned(&p))
    }

    /// Smallest wheel lag for contact of the tooth at roll `target`, and where:
    /// the best grid node, refined by damped Newton on the active flank. A
    /// misaligned pair's node activity holds at the node's own roll, so the
    /// best node may not be able to touch at `target`; then the next best
    /// that can starts the search (the aligned pair keeps its old rule:
    /// the best node or nothing).
    pub fn min_contact(&self, target: f64) -> Option<(f64, [f64; 2])> {
        let rs = self.rs;
        let nodes = (0..rs.uv.len())
            .filter(|&n| rs.active[n])
            .map(|n| (rs.node_lag(n, target), n));
        // A node's generating parameters and its lag, where it can touch.
        let start = |n: usize| self.lag(rs.uv[n], target).map(|v| (rs.uv[n], v));
        let (uv, val) = if self.fp.pose.is_some() {
            let mut nodes: Vec<(f64, usize)> = nodes.collect();
            // Stable: of equal lags the first node, as a plain scan for the minimum.
            nodes.sort_by(|a, b| a.0.total_cmp(&b.0));
            nodes.iter().find_map(|&(_, n)| start(n))?
        } else {
            // The best node (the first of equal lags) or nothing: a scan,
            // no sort.
            start(nodes.min_by(|a, b| a.0.total_cmp(&b.0))?.1)?
        };
        let (uv, val) = crate::minimize::newton_2d(|c| self.lag(c, target), uv, val, 1e-5, 25);
        Some((val, uv))
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
            if let Some((te, uv)) = ls.min_contact(target) {
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

/// Tabulated surface of roll angles of a flank pair at the scene's sampling.
pub fn roll_surface(fp: &FlankPair, s: &UtcaSettings) -> Result<RollSurface, GeometryError> {
    RollSurface::new(
        fp,
        LineGrid {
            n_face: s.face_samples,
            n_profile: s.profile_samples,
        },
    )
}

/// UTCA over the scene's sweep, starting where tooth 0 enters the active region.
pub fn sweep(fp: &FlankPair, pair: &PairData, rs: &RollSurface, s: &UtcaSettings) -> Utca {
    let step = s.step_deg.to_radians();
    let n = (s.mesh_cycles * pair.mesh_cycle() / step).round() as usize + 1;
    run(
        fp,
        rs,
        fp.roll_range[0],
        step,
        n,
        pinion_direction(pair, fp.side),
    )
}
