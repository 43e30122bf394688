//! The load of the line-load check on the fine mesh: the load line on the
//! flank, the Hertz strip's consistent nodal forces along it, and the
//! displacement read back at a point of the flank faces.

use crate::reference::contact_surface::{cross, dot, norm, sub, MasterSurface};
use fem::{tri6, TetMesh};

/// The load line: points C(ξ) along the flank at fixed η₀ with their
/// outward normals and the unit profile direction in the tangent plane.
#[derive(Debug, Clone)]
pub struct LoadLine {
    pub points: Vec<[f64; 3]>,
    pub normals: Vec<[f64; 3]>,
    /// Unit vector in the tangent plane, normal to the line (towards
    /// increasing η).
    pub across: Vec<[f64; 3]>,
}

impl LoadLine {
    /// The part of a line sampled at `per_column` points per grid column
    /// that covers columns `first..=last`.
    pub fn columns(&self, first: usize, last: usize, per_column: usize) -> LoadLine {
        let range = first * per_column..=((last + 1) * per_column).min(self.points.len() - 1);
        LoadLine {
            points: self.points[range.clone()].to_vec(),
            normals: self.normals[range.clone()].to_vec(),
            across: self.across[range].to_vec(),
        }
    }
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = norm(a);
    [a[0] / n, a[1] / n, a[2] / n]
}

impl LoadLine {
    /// A line through `points` (at least two, ordered along it) on a surface
    /// with outward `normals`; the across direction is n × t, flipped to
    /// point along `towards` (e.g. the surface's ∂x/∂η).
    pub fn new(points: Vec<[f64; 3]>, normals: Vec<[f64; 3]>, towards: [f64; 3]) -> LoadLine {
        let n = points.len();
        assert!(n >= 2 && normals.len() == n, "a load line needs two points");
        let across = (0..n)
            .map(|i| {
                let t = sub(points[(i + 1).min(n - 1)], points[i.saturating_sub(1)]);
                let a = unit(cross(normals[i], unit(t)));
                if dot(a, towards) < 0.0 {
                    a.map(|c| -c)
                } else {
                    a
                }
            })
            .collect();
        LoadLine {
            points,
            normals,
            across,
        }
    }

    /// Arc length of the line.
    pub fn length(&self) -> f64 {
        self.points.windows(2).map(|w| norm(sub(w[1], w[0]))).sum()
    }

    /// Signed distance s of `x` from the line across it, and the inward
    /// normal there; None beyond the line's ends.
    pub fn across_distance(&self, x: [f64; 3]) -> Option<(f64, [f64; 3])> {
        // (distance², segment, raw parameter, across distance, inward normal)
        let mut best: Option<(f64, usize, f64, f64, [f64; 3])> = None;
        for (k, w) in self.points.windows(2).enumerate() {
            let d = sub(w[1], w[0]);
            let raw = dot(sub(x, w[0]), d) / dot(d, d);
            let t = raw.clamp(0.0, 1.0);
            let p = [w[0][0] + t * d[0], w[0][1] + t * d[1], w[0][2] + t * d[2]];
            let r = sub(x, p);
            let dist2 = dot(r, r);
            if best.is_none_or(|b| dist2 < b.0) {
                let mix = |a: [f64; 3], b: [f64; 3]| {
                    unit([
                        a[0] + t * (b[0] - a[0]),
                        a[1] + t * (b[1] - a[1]),
                        a[2] + t * (b[2] - a[2]),
                    ])
                };
                let across = mix(self.across[k], self.across[k + 1]);
                let normal = mix(self.normals[k], self.normals[k + 1]);
                best = Some((dist2, k, raw, dot(r, across), normal.map(|c| -c)));
            }
        }
        let (_, k, raw, s, inward) = best?;
        let last = self.points.len() - 2;
        if (k == 0 && raw < 0.0) || (k == last && raw > 1.0) {
            return None; // beyond the toe or heel end
        }
        Some((s, inward))
    }
}

/// Hertz pressure of line load `q` and half-width `b` at distance `s`.
pub fn hertz_pressure(q: f64, b: f64, s: f64) -> f64 {
    let r = 1.0 - (s / b).powi(2);
    if r <= 0.0 {
        0.0
    } else {
        2.0 * q / (std::f64::consts::PI * b) * r.sqrt()
    }
}

/// Consistent nodal forces (dof 3 · node + component, value) of the Hertz
/// strip along `line` on the faces `faces`, and the applied force ∫ p dA
/// (the sum of the force magnitudes; the vector sum is smaller on a twisted
/// flank, whose normal turns along the line). Each face that the strip
/// reaches is integrated on `sub`² sub-triangles with the 6-point rule, so
/// that the strip's square-root edges are resolved inside the element.
pub fn strip_forces(
    mesh: &TetMesh,
    faces: &[[usize; 6]],
    line: &LoadLine,
    q: f64,
    b: f64,
    sub_div: usize,
) -> (Vec<(usize, f64)>, f64) {
    let mut acc: std::collections::BTreeMap<usize, f64> = Default::default();
    let mut applied = 0.0;
    let rule = tri6::dunavant6();
    let n = sub_div.max(1);
    for f in faces {
        let x = f.map(|i| mesh.nodes[i]);
        let size = (1..6).map(|k| norm(sub(x[0], x[k]))).fold(0.0, f64::max);
        match line.across_distance(x[0]) {
            Some((s, _)) if s.abs() <= b + 2.0 * size => {}
            // Beyond an end: the face may still straddle it.
            None if line.across_distance(x[1]).is_some()
                || line.across_distance(x[2]).is_some() => {}
            _ => continue,
        }
        let mut fe = [[0.0; 3]; 6];
        // Sub-triangles of the reference triangle: n² of them, each mapped
        // affinely from the reference triangle (corners a, b, c).
        for i in 0..n {
            for j in 0..n - i {
                let h = 1.0 / n as f64;
                let (s0, t0) = (i as f64 * h, j as f64 * h);
                let mut tris = vec![[[s0, t0], [s0 + h, t0], [s0, t0 + h]]];
                if i + j + 1 < n {
                    tris.push([[s0 + h, t0], [s0 + h, t0 + h], [s0, t0 + h]]);
                }
                for [a, bb, c] in tris {
                    let jac =
                        ((bb[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (bb[1] - a[1])).abs();
                    for &(st, w) in &rule {
                        let p = [
                            a[0] + st[0] * (bb[0] - a[0]) + st[1] * (c[0] - a[0]),
                            a[1] + st[0] * (bb[1] - a[1]) + st[1] * (c[1] - a[1]),
                        ];
                        let (pt, nn) = tri6::point_and_normal(&x, p);
                        let Some((s, inward)) = line.across_distance(pt) else {
                            continue;
                        };
                        let pr = hertz_pressure(q, b, s);
                        if pr == 0.0 {
                            continue;
                        }
                        let da = norm(nn);
                        applied += w * jac * da * pr;
                        let nshape = tri6::shape(p);
                        for (k, fk) in fe.iter_mut().enumerate() {
                            for c in 0..3 {
                                fk[c] += w * jac * da * nshape[k] * pr * inward[c];
                            }
                        }
                    }
                }
            }
        }
        for (&node, fk) in f.iter().zip(&fe) {
            for (c, &v) in fk.iter().enumerate() {
                if v != 0.0 {
                    *acc.entry(3 * node + c).or_default() += v;
                }
            }
        }
    }
    (acc.into_iter().collect(), applied)
}

/// How far from the flank faces a point of the load line may lie (the
/// quadratic faces' departure from the generated flank, with margin), m.
pub(super) const ON_FACE_REACH: f64 = 1e-4;

/// The displacement `u` (3 per node) interpolated at the surface point
/// `p` of `surface` (its nearest face), projected on `dir`.
pub fn surface_value(
    surface: &MasterSurface,
    u: &[f64],
    p: [f64; 3],
    dir: [f64; 3],
) -> Option<f64> {
    let pr = surface.project(p, ON_FACE_REACH)?;
    let nsh = tri6::shape(pr.st);
    Some(
        surface.faces[pr.face]
            .iter()
            .zip(nsh)
            .map(|(&node, w)| w * (0..3).map(|c| dir[c] * u[3 * node + c]).sum::<f64>())
            .sum(),
    )
}
