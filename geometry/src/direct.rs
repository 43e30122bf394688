//! Direct geometric contact search, independent of the surface of roll angles:
//! both flanks are placed at their rotations, each pinion point is projected
//! onto the wheel flank (Gauss–Newton on the wheel's generating parameters)
//! and the signed normal gap is measured. Used to verify the UTCA (conjugacy,
//! separation map) and to find contact ellipses.

use crate::pair::FlankPair;
use crate::utca::RollSurface;
use nalgebra::{Matrix2, Vector2, Vector3};
use serde::Serialize;

pub use crate::placement::{gap, gap_on_flank, project, Placement};

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
        if !candidate(fp, uv) {
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
            if candidate(fp, n) {
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

/// Whether the pinion point at `uv` can touch: for the aligned pair, when
/// it and its conjugate mate lie on their flanks; for a misaligned one, when
/// it lies on the pinion flank (its closest wheel point is checked by
/// [`gap_on_flank`]).
fn candidate(fp: &FlankPair, uv: [f64; 2]) -> bool {
    if fp.pose.is_some() {
        crate::mate::on_pinion(fp, uv, 1e-12)
    } else {
        fp.is_active(uv[0], uv[1], 1e-12)
    }
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
