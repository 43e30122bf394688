//! Direct geometric contact search, independent of the surface of roll angles:
//! both flanks are placed at their rotations, each pinion point is projected
//! onto the wheel flank (Gauss–Newton on the wheel's generating parameters)
//! and the signed normal gap is measured. Used to verify the UTCA (conjugacy,
//! separation map) and to find contact ellipses.

use crate::flank::Flank;
use crate::pair::FlankPair;
use crate::utca::RollSurface;
use nalgebra::{Matrix2, Matrix3x2, Vector2, Vector3};
use serde::Serialize;

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
    let gap = (q - Vector3::from(raw.pos)).dot(&Vector3::from(raw.normal));
    Some(([u, v], gap))
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
    let f1 = &fp.pinion.gen.frame;
    let f2 = &fp.wheel.gen.frame;
    let p = Vector3::from(fp.pinion.eval_uv(uv[0], uv[1]).pos);
    let x = f1.to_fixed(&p, at.pinion + j as f64 * f1.pitch());
    let q = f2.to_member(&x, at.wheel - j as f64 * f2.pitch());
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

/// Result of a direct contact search at one pinion angle.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct DirectContact {
    /// Wheel lag for first contact, rad.
    pub te: f64,
    pub tooth: i32,
    pub uv: [f64; 2],
    /// Smallest gap over the sampled active nodes at that lag (≥ 0 up to round-off), m.
    pub min_node_gap: f64,
}

/// Direct TCA at pinion angle `phi1`: the smallest wheel lag that closes
/// the gap somewhere on the active flanks, found by sampling the roll-surface
/// nodes and refining the best one with Newton on gap/λ₂.
pub fn direct_te(
    fp: &FlankPair,
    rs: &RollSurface,
    phi1: f64,
    direction: f64,
) -> Option<DirectContact> {
    let tau = fp.pinion.gen.frame.pitch();
    let [r0, r1] = fp.roll_range;
    let jmin = ((r0 - phi1) / tau).floor() as i32 - 1;
    let jmax = ((r1 - phi1) / tau).ceil() as i32 + 1;
    let conj = fp.placement(phi1, 0.0, direction);
    let ratio = |uv: [f64; 2], j: i32| -> Option<f64> {
        if !fp.is_active(uv[0], uv[1], 1e-12) {
            return None;
        }
        let (g, _) = gap_on_flank(fp, conj, j, uv, uv)?;
        Some(g / fp.pinion.eval_uv(uv[0], uv[1]).wheel_lever)
    };
    // Per tooth pair: best node, refined by Newton on f(u, v) = gap/λ₂; then the smallest.
    let mut best: Option<(f64, i32, [f64; 2])> = None;
    for j in jmin..=jmax {
        let node = rs
            .uv
            .iter()
            .filter_map(|&uv| ratio(uv, j).map(|r| (r, uv)))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((r, uv)) = node {
            let (uv, r) = crate::minimize::newton_2d(|c| ratio(c, j), uv, r, 2e-5, 20);
            if best.is_none_or(|b| r < b.0) {
                best = Some((r, j, uv));
            }
        }
    }
    let (val, j, uv) = best?;
    // One correction for the nonlinearity of the rotation.
    let at = fp.placement(phi1, val, direction);
    let (g, _) = gap(fp, at, j, uv, uv)?;
    let te = val + g / fp.pinion.eval_uv(uv[0], uv[1]).wheel_lever;
    let at = fp.placement(phi1, te, direction);
    let mut min_node_gap = f64::INFINITY;
    for jj in jmin..=jmax {
        for &n in &rs.uv {
            if fp.is_active(n[0], n[1], 1e-12) {
                if let Some((g, _)) = gap_on_flank(fp, at, jj, n, n) {
                    min_node_gap = min_node_gap.min(g);
                }
            }
        }
    }
    Some(DirectContact {
        te,
        tooth: j,
        uv,
        min_node_gap,
    })
}

/// Contact ellipse for a separation δ (marking compound) around a contact
/// point: the gap is fitted by a quadratic in the tangent plane, and the
/// semi-axes are a = √(2δ/λ) for the eigenvalues λ of its Hessian.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ContactEllipse {
    /// Semi-axes (major, minor), m; infinite where the separation does not grow.
    pub semi_axes: [f64; 2],
    /// Major-axis direction in the axial projection plane (dL, dd), unit.
    pub major_dir_ld: [f64; 2],
    /// Unit major-axis direction in the pinion member frame.
    pub major_dir: [f64; 3],
}

pub fn contact_ellipse(
    fp: &FlankPair,
    at: Placement,
    j: i32,
    uv: [f64; 2],
    separation: f64,
) -> Option<ContactEllipse> {
    let h = 2e-4;
    let g = |du: f64, dv: f64| gap(fp, at, j, [uv[0] + du, uv[1] + dv], uv).map(|x| x.0);
    let g0 = g(0.0, 0.0)?;
    let (gpu, gmu, gpv, gmv) = (g(h, 0.0)?, g(-h, 0.0)?, g(0.0, h)?, g(0.0, -h)?);
    let guv = g(h, h)? - g(h, -h)? - g(-h, h)? + g(-h, -h)?;
    let huv = Matrix2::new(
        (gpu - 2.0 * g0 + gmu) / (h * h),
        guv / (4.0 * h * h),
        guv / (4.0 * h * h),
        (gpv - 2.0 * g0 + gmv) / (h * h),
    );
    // Metric of the pinion surface: x = J (du, dv), J = [r_u r_v].
    let e = 1e-7;
    let p = |du: f64, dv: f64| Vector3::from(fp.pinion.eval_uv(uv[0] + du, uv[1] + dv).pos);
    let p0 = p(0.0, 0.0);
    let ru = (p(e, 0.0) - p0) / e;
    let rv = (p(0.0, e) - p0) / e;
    let first = Matrix2::new(ru.dot(&ru), ru.dot(&rv), ru.dot(&rv), rv.dot(&rv));
    let c = first.cholesky()?.l();
    let ci = c.try_inverse()?;
    let hx = ci * huv * ci.transpose();
    let eig = hx.symmetric_eigen();
    let (imaj, imin) = if eig.eigenvalues[0] <= eig.eigenvalues[1] {
        (0, 1)
    } else {
        (1, 0)
    };
    let axis = |i: usize| {
        let lam = eig.eigenvalues[i];
        if lam > 0.0 {
            (2.0 * separation / lam).sqrt()
        } else {
            f64::INFINITY
        }
    };
    let w = ci.transpose() * eig.eigenvectors.column(imaj);
    let t = (ru * w[0] + rv * w[1]).normalize();
    let ld0 = fp.pinion.ld(uv[0], uv[1]);
    let ld1 = fp.pinion.ld(uv[0] + e * w[0], uv[1] + e * w[1]);
    let dl = Vector2::new(ld1.0 - ld0.0, ld1.1 - ld0.1).normalize();
    Some(ContactEllipse {
        semi_axes: [axis(imaj), axis(imin)],
        major_dir_ld: [dl[0], dl[1]],
        major_dir: [t[0], t[1], t[2]],
    })
}
