//! A unit load's weights on the flank faces around a grid point (the bump
//! patch), and the mid-surface depth under a grid point (a ray to the
//! opposite flank).

use super::{dist, dot, Weights};
use fem::{tri6, TetMesh};

/// The bump's consistent nodal forces on `faces` (node → force) and their sum.
fn bump_forces(
    mesh: &TetMesh,
    faces: &[[usize; 6]],
    center: [f64; 3],
    radius: f64,
) -> (std::collections::BTreeMap<usize, f64>, f64) {
    let bump = |p: [f64; 3]| {
        let r2 = (0..3).map(|c| (p[c] - center[c]).powi(2)).sum::<f64>() / (radius * radius);
        if r2 < 1.0 {
            (1.0 - r2).powi(2)
        } else {
            0.0
        }
    };
    let mut acc: std::collections::BTreeMap<usize, f64> = Default::default();
    let mut total = 0.0;
    for f in faces {
        let x = f.map(|i| mesh.nodes[i]);
        let size = (1..6).map(|k| dist(x[0], x[k])).fold(0.0, f64::max);
        if dist(x[0], center) > radius + size {
            continue;
        }
        let fe = tri6::consistent_forces(&x, |p, _| [bump(p), 0.0, 0.0]);
        for (l, &node) in f.iter().enumerate() {
            if fe[l][0] != 0.0 {
                *acc.entry(node).or_default() += fe[l][0];
                total += fe[l][0];
            }
        }
    }
    (acc, total)
}

/// Weights of a unit force along `dir` at `center`, spread over `faces` by the
/// bump q(r) ∝ (1 − r²/ρ²)² (r < ρ) and integrated consistently (6-point rule
/// per tri6 face). The weights sum to `dir` (1 N).
///
/// Where the faces near `center` are so coarse that no quadrature point lies
/// within ρ (a fine contact grid's small patch on a tooth the mesh did not
/// refine: only its far-field response is used), ρ is widened to the
/// nearest face's size, the smallest patch that face's quadrature can carry.
pub fn patch_weights(
    mesh: &TetMesh,
    faces: &[[usize; 6]],
    center: [f64; 3],
    dir: [f64; 3],
    radius: f64,
) -> Option<Weights> {
    let (mut acc, mut total) = bump_forces(mesh, faces, center, radius);
    if total <= 0.0 {
        let nearest = faces
            .iter()
            .map(|f| {
                let x = f.map(|i| mesh.nodes[i]);
                let size = (1..6).map(|k| dist(x[0], x[k])).fold(0.0, f64::max);
                (dist(x[0], center), size)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))?;
        if nearest.0 <= radius + nearest.1 {
            (acc, total) = bump_forces(mesh, faces, center, radius.max(nearest.1));
        }
    }
    if total <= 0.0 {
        return None;
    }
    Some(
        acc.into_iter()
            .flat_map(|(node, w)| (0..3).map(move |c| (3 * node + c, w / total * dir[c])))
            .collect(),
    )
}

/// Half the tooth thickness along −n from `p`: the distance to the first hit
/// on the opposite flank's faces, halved (the mid-surface depth h).
pub fn mid_surface_depth(
    mesh: &TetMesh,
    opposite: &[[usize; 6]],
    p: [f64; 3],
    n: [f64; 3],
) -> Option<f64> {
    let d = n.map(|c| -c);
    let mut best: Option<f64> = None;
    const SUB: [[usize; 3]; 4] = [[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]];
    for f in opposite {
        for t in SUB {
            let [a, b, c] = t.map(|l| mesh.nodes[f[l]]);
            if let Some(s) = ray_triangle(p, d, a, b, c) {
                if s > 0.0 && best.is_none_or(|b| s < b) {
                    best = Some(s);
                }
            }
        }
    }
    best.map(|s| 0.5 * s)
}

/// Möller–Trumbore ray/triangle intersection: distance along `d` or None.
fn ray_triangle(o: [f64; 3], d: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Option<f64> {
    let sub = |x: [f64; 3], y: [f64; 3]| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
    let cross = |x: [f64; 3], y: [f64; 3]| {
        [
            x[1] * y[2] - x[2] * y[1],
            x[2] * y[0] - x[0] * y[2],
            x[0] * y[1] - x[1] * y[0],
        ]
    };
    let (e1, e2) = (sub(b, a), sub(c, a));
    let pv = cross(d, e2);
    let det = dot(e1, pv);
    if det.abs() < 1e-30 {
        return None;
    }
    let tv = sub(o, a);
    let u = dot(tv, pv) / det;
    if !(-1e-9..=1.0 + 1e-9).contains(&u) {
        return None;
    }
    let qv = cross(tv, e1);
    let v = dot(d, qv) / det;
    if v < -1e-9 || u + v > 1.0 + 1e-9 {
        return None;
    }
    Some(dot(e2, qv) / det)
}

#[cfg(test)]
mod patch_tests {
    use super::*;

    /// One flat tri6 face of 10 mm legs in z = 0 (corners, then mid-edges).
    fn coarse_face() -> (TetMesh, Vec<[usize; 6]>) {
        let h = 0.01;
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [h, 0.0, 0.0],
            [0.0, h, 0.0],
            [h / 2.0, 0.0, 0.0],
            [h / 2.0, h / 2.0, 0.0],
            [0.0, h / 2.0, 0.0],
        ];
        (
            TetMesh {
                nodes,
                tets: Vec::new(),
            },
            vec![[0, 1, 2, 3, 4, 5]],
        )
    }

    #[test]
    fn patch_smaller_than_a_coarse_face_is_widened_and_carries_one_newton() {
        let (mesh, faces) = coarse_face();
        let dir = [0.0, 0.0, -1.0];
        // 0.1 mm patch inside a 10 mm face: no quadrature point within it.
        let w = patch_weights(&mesh, &faces, [0.003, 0.003, 0.0], dir, 1e-4)
            .expect("widened to the face");
        let fz: f64 = w.iter().filter(|(d, _)| d % 3 == 2).map(|(_, v)| v).sum();
        assert!((fz + 1.0).abs() < 1e-12, "sum of weights {fz}");
        // Far from every face: still refused.
        assert!(patch_weights(&mesh, &faces, [0.5, 0.5, 0.0], dir, 1e-4).is_none());
    }
}
