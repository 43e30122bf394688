//! Contact surfaces made of a mesh's own quadratic (tri6) faces: outward
//! orientation, lumped nodal areas, and the closest-point projection of a
//! slave node onto a master surface.

use fem::{tri6, TetMesh};
use std::collections::HashMap;

type V3 = [f64; 3];

pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub(crate) fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// Reorders `faces` so that their normals (right-hand rule of the vertex
/// order) point out of the tetrahedron each face belongs to. Returns the
/// number of faces that matched no element (left as they are).
pub fn orient_outward(mesh: &TetMesh, faces: &mut [[usize; 6]]) -> usize {
    let key = |a: usize, b: usize, c: usize| {
        let mut k = [a, b, c];
        k.sort_unstable();
        k
    };
    let mut want: HashMap<[usize; 3], Option<usize>> = faces
        .iter()
        .map(|f| (key(f[0], f[1], f[2]), None))
        .collect();
    for t in &mesh.tets {
        for skip in 0..4 {
            let v: Vec<usize> = (0..4).filter(|&i| i != skip).map(|i| t[i]).collect();
            if let Some(slot) = want.get_mut(&key(v[0], v[1], v[2])) {
                *slot = Some(t[skip]);
            }
        }
    }
    let mut unmatched = 0;
    for f in faces.iter_mut() {
        let Some(Some(opp)) = want.get(&key(f[0], f[1], f[2])) else {
            unmatched += 1;
            continue;
        };
        let x = |i: usize| mesh.nodes[i];
        let n = cross(sub(x(f[1]), x(f[0])), sub(x(f[2]), x(f[0])));
        if dot(n, sub(x(f[0]), x(*opp))) < 0.0 {
            // Swap vertices 1 and 2; edges (0,1),(1,2),(2,0) become (0,2),(2,1),(1,0).
            *f = [f[0], f[2], f[1], f[5], f[4], f[3]];
        }
    }
    unmatched
}

/// Lumped area of each node of `faces`: every tri6 is split into its four
/// straight sub-triangles (vertex–mid-edge), and each sub-triangle gives a
/// third of its area to each of its corners (so vertex nodes, whose
/// consistent load under uniform pressure is zero, still carry area), m².
pub fn lumped_areas(nodes: &[V3], faces: &[[usize; 6]]) -> HashMap<usize, f64> {
    let mut area: HashMap<usize, f64> = HashMap::new();
    for f in faces {
        for (&i, a) in f.iter().zip(face_shares(nodes, f)) {
            *area.entry(i).or_default() += a;
        }
    }
    area
}

/// Each node's share of one face's lumped area (see [`lumped_areas`]), m².
fn face_shares(nodes: &[V3], f: &[usize; 6]) -> [f64; 6] {
    const SUB: [[usize; 3]; 4] = [[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]];
    let mut share = [0.0; 6];
    for s in SUB {
        let [a, b, c] = s.map(|i| nodes[f[i]]);
        let ar = 0.5 * norm(cross(sub(b, a), sub(c, a)));
        for i in s {
            share[i] += ar / 3.0;
        }
    }
    share
}

/// The closest point of a master face to a slave node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// Index into the master's face list.
    pub face: usize,
    /// Face parameters (s, t).
    pub st: [f64; 2],
    pub point: V3,
    /// Unit outward normal of the master at the point.
    pub normal: V3,
    /// Signed gap (slave − point) · normal, m.
    pub gap: f64,
}

/// A master surface (faces oriented outward) with a uniform grid of cells
/// over its faces' bounding boxes for the search.
pub struct MasterSurface {
    pub faces: Vec<[usize; 6]>,
    /// Node coordinates in the frame where the projection happens.
    pub nodes: Vec<V3>,
    cell: f64,
    grid: HashMap<[i64; 3], Vec<usize>>,
    /// Per face: a box that holds the whole curved face ([`face_box`]) and
    /// its lowest grid cell.
    boxes: Vec<(V3, V3)>,
    first_cell: Vec<[i64; 3]>,
}

/// Axis-aligned box holding a tri6 face: the nodes' box grown by 4/3 of
/// the largest mid-edge offset. The face is its linear triangle (inside
/// the corners' box) plus the edge bubbles 4 λₐ λ_b δₑ, δₑ the offset of
/// edge e's mid node from its chord's midpoint, and Σₑ 4 λₐ λ_b ≤ 4/3.
pub fn face_box(x: &[V3; 6]) -> (V3, V3) {
    let mut lo = x[0];
    let mut hi = x[0];
    for p in x {
        for c in 0..3 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    let edges = [(0, 1, 3), (1, 2, 4), (2, 0, 5)];
    let bulge = edges
        .iter()
        .map(|&(a, b, m)| norm([0, 1, 2].map(|c| x[m][c] - 0.5 * (x[a][c] + x[b][c]))))
        .fold(0.0, f64::max);
    let grow = 4.0 / 3.0 * bulge + 1e-12;
    (lo.map(|v| v - grow), hi.map(|v| v + grow))
}

/// Squared distance from `p` to the box `b` (zero inside).
fn box_distance2(p: V3, b: &(V3, V3)) -> f64 {
    (0..3)
        .map(|c| {
            let d = (b.0[c] - p[c]).max(p[c] - b.1[c]).max(0.0);
            d * d
        })
        .sum()
}

impl MasterSurface {
    /// Builds the search grid; `nodes` are all node coordinates (indexed by
    /// node number) in the common frame.
    pub fn new(nodes: Vec<V3>, faces: Vec<[usize; 6]>) -> MasterSurface {
        let mut size = 0.0f64;
        for f in &faces {
            size = size.max(norm(sub(nodes[f[1]], nodes[f[0]])));
            size = size.max(norm(sub(nodes[f[2]], nodes[f[0]])));
        }
        let cell = size.max(1e-9);
        let mut s = MasterSurface {
            faces,
            nodes,
            cell,
            grid: HashMap::new(),
            boxes: Vec::new(),
            first_cell: Vec::new(),
        };
        s.boxes = (0..s.faces.len()).map(|k| face_box(&s.face_x(k))).collect();
        for (k, f) in s.faces.iter().enumerate() {
            let (lo, hi) = s.cells_of(f);
            s.first_cell.push(lo);
            for i in lo[0]..=hi[0] {
                for j in lo[1]..=hi[1] {
                    for l in lo[2]..=hi[2] {
                        s.grid.entry([i, j, l]).or_default().push(k);
                    }
                }
            }
        }
        s
    }

    fn cell_of(&self, p: V3) -> [i64; 3] {
        p.map(|c| (c / self.cell).floor() as i64)
    }

    fn cells_of(&self, f: &[usize; 6]) -> ([i64; 3], [i64; 3]) {
        let mut lo = [i64::MAX; 3];
        let mut hi = [i64::MIN; 3];
        for &i in f {
            let c = self.cell_of(self.nodes[i]);
            for d in 0..3 {
                lo[d] = lo[d].min(c[d]);
                hi[d] = hi[d].max(c[d]);
            }
        }
        (lo, hi)
    }

    fn face_x(&self, k: usize) -> [V3; 6] {
        self.faces[k].map(|i| self.nodes[i])
    }

    /// Projects `p` onto the surface: among the faces near `p` (within
    /// `reach` m), the closest point that lies inside a face. None when `p`
    /// projects outside the surface. Faces whose box lies farther than the
    /// best point so far are skipped (they cannot hold a closer one).
    pub fn project(&self, p: V3, reach: f64) -> Option<Projection> {
        let c = self.cell_of(p);
        let r = (reach / self.cell).ceil() as i64 + 1;
        let mut best: Option<(f64, Projection)> = None;
        for i in -r..=r {
            for j in -r..=r {
                for l in -r..=r {
                    let here = [c[0] + i, c[1] + j, c[2] + l];
                    let Some(list) = self.grid.get(&here) else {
                        continue;
                    };
                    for &k in list {
                        // Each face once: in the first searched cell it is listed in.
                        let fc = &self.first_cell[k];
                        if (0..3).any(|d| here[d] != fc[d].max(c[d] - r)) {
                            continue;
                        }
                        let limit = best.as_ref().map_or(reach, |b| b.0.min(reach));
                        if box_distance2(p, &self.boxes[k]) > limit * limit {
                            continue;
                        }
                        if let Some(pr) = project_on_face(&self.face_x(k), p) {
                            let d = norm(sub(p, pr.0));
                            if d <= reach && best.as_ref().is_none_or(|b| d < b.0) {
                                best = Some((
                                    d,
                                    Projection {
                                        face: k,
                                        st: pr.1,
                                        point: pr.0,
                                        normal: pr.2,
                                        gap: dot(sub(p, pr.0), pr.2),
                                    },
                                ));
                            }
                        }
                    }
                }
            }
        }
        best.map(|b| b.1)
    }
}

/// Closest point of one tri6 face to `p` by Gauss–Newton on (s, t); None if
/// it falls outside the face (by more than 1e-9 in the parameters).
pub fn project_on_face(x: &[V3; 6], p: V3) -> Option<(V3, [f64; 2], V3)> {
    let mut st = [1.0 / 3.0, 1.0 / 3.0];
    for _ in 0..30 {
        let n = tri6::shape(st);
        let d = tri6::shape_derivatives(st);
        let mut q = [0.0; 3];
        let mut xs = [0.0; 3];
        let mut xt = [0.0; 3];
        for i in 0..6 {
            for c in 0..3 {
                q[c] += n[i] * x[i][c];
                xs[c] += d[i][0] * x[i][c];
                xt[c] += d[i][1] * x[i][c];
            }
        }
        let r = sub(p, q);
        let (a, b, cc) = (dot(xs, xs), dot(xs, xt), dot(xt, xt));
        let (f, g) = (dot(xs, r), dot(xt, r));
        let det = a * cc - b * b;
        if det <= 0.0 {
            return None;
        }
        let ds = (cc * f - b * g) / det;
        let dt = (a * g - b * f) / det;
        // Keep the iterate near the triangle so that Newton stays in the
        // face's own parametrization.
        st = [(st[0] + ds).clamp(-0.5, 1.5), (st[1] + dt).clamp(-0.5, 1.5)];
        if ds.abs() + dt.abs() < 1e-13 {
            break;
        }
    }
    let tol = 1e-9;
    if st[0] < -tol || st[1] < -tol || st[0] + st[1] > 1.0 + tol {
        return None;
    }
    let (q, nn) = tri6::point_and_normal(x, st);
    let l = norm(nn);
    Some((q, st, nn.map(|c| c / l)))
}

/// Parameters (s, t) of the tri6 nodes: vertices, then mid-edge nodes.
pub const TRI6_NODES: [[f64; 2]; 6] = [
    [0.0, 0.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [0.5, 0.0],
    [0.5, 0.5],
    [0.0, 0.5],
];

/// Outward unit normal of a surface at each of its nodes (mean of the
/// adjacent faces' normals at the node).
pub fn nodal_normals(nodes: &[V3], faces: &[[usize; 6]]) -> HashMap<usize, V3> {
    let mut out: HashMap<usize, V3> = HashMap::new();
    for f in faces {
        let x = f.map(|i| nodes[i]);
        for (k, &i) in f.iter().enumerate() {
            let (_, nn) = tri6::point_and_normal(&x, TRI6_NODES[k]);
            let l = norm(nn);
            let e = out.entry(i).or_default();
            for c in 0..3 {
                e[c] += nn[c] / l;
            }
        }
    }
    for v in out.values_mut() {
        let l = norm(*v);
        *v = v.map(|c| c / l);
    }
    out
}

/// Contact pressure at each node of `faces` (Pa) from the normal nodal
/// forces `f` (N, compressive positive). On quadratic faces a smooth
/// pressure loads vertex nodes about half as much as mid-edge nodes, so
/// force over a node's own lumped area alternates from node to node. Each
/// node's force is shared among its faces in proportion to the lumped area
/// it has in each; a face's pressure is its share of force over its area
/// (this balances the alternation exactly), and a node's pressure is the
/// area-weighted mean of its faces'.
pub fn smoothed_pressure(
    nodes: &[V3],
    faces: &[[usize; 6]],
    f: &HashMap<usize, f64>,
) -> HashMap<usize, f64> {
    let area = lumped_areas(nodes, faces);
    let mut sum: HashMap<usize, (f64, f64)> = HashMap::new();
    for fc in faces {
        let own = face_shares(nodes, fc);
        let a_face: f64 = own.iter().sum();
        let force: f64 = fc
            .iter()
            .zip(own)
            .map(|(i, a)| f.get(i).copied().unwrap_or(0.0) * a / area[i])
            .sum();
        for &i in fc {
            let e = sum.entry(i).or_default();
            e.0 += force;
            e.1 += a_face;
        }
    }
    sum.into_iter().map(|(i, (fs, a))| (i, fs / a)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat face in z = 0 projects a point straight down; a quadratic face
    /// bent into a parabola z = κ x² / 2 gives the exact closest point.
    #[test]
    fn projection_onto_flat_and_curved_faces_is_the_closest_point() {
        let flat: [V3; 6] = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.0, 0.0],
            [0.5, 0.5, 0.0],
            [0.0, 0.5, 0.0],
        ];
        let (q, st, n) = project_on_face(&flat, [0.2, 0.3, 0.7]).unwrap();
        assert!((q[0] - 0.2).abs() < 1e-14 && (q[1] - 0.3).abs() < 1e-14 && q[2].abs() < 1e-14);
        assert!((st[0] - 0.2).abs() < 1e-14 && (n[2] - 1.0).abs() < 1e-14);
        assert!(project_on_face(&flat, [0.8, 0.8, 0.1]).is_none());
        // z = x²/2 is exactly quadratic: the tri6 reproduces it.
        let k = 1.0;
        let z = |x: f64| 0.5 * k * x * x;
        let curved = flat.map(|p| [p[0], p[1], z(p[0])]);
        let p = [0.3, 0.2, 0.2];
        let (q, _, n) = project_on_face(&curved, p).unwrap();
        // At the closest point, p − q is along the normal (−z'(x), 0, 1).
        let r = sub(p, q);
        let t = [1.0, 0.0, k * q[0]];
        assert!(dot(r, t).abs() < 1e-12, "{}", dot(r, t));
        assert!((q[2] - z(q[0])).abs() < 1e-14);
        assert!(n[2] > 0.0);
    }

    /// The lumped areas of a face sum to its area, vertices get 1/12 and
    /// mid-edge nodes 1/4 of a straight face.
    #[test]
    fn lumped_areas_sum_to_the_face_area() {
        let nodes: Vec<V3> = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let a = lumped_areas(&nodes, &[[0, 1, 2, 3, 4, 5]]);
        assert!((a[&0] - 2.0 / 12.0).abs() < 1e-14);
        assert!((a[&3] - 2.0 / 4.0).abs() < 1e-14);
        assert!((a.values().sum::<f64>() - 2.0).abs() < 1e-14);
    }

    /// A wavy surface of curved tri6 faces (random mid-node offsets): every
    /// point of every face lies in its box, and the grid search with the box
    /// cut-off returns the closest point that trying every face returns.
    #[test]
    fn grid_search_with_face_boxes_matches_trying_every_face() {
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        // A 6 × 6 grid of vertices, spacing 1, two triangles per square,
        // mid-edge nodes off their chords by up to ±0.15.
        let n = 6;
        let mut nodes: Vec<V3> = Vec::new();
        let vid = |i: usize, j: usize| i * n + j;
        for i in 0..n {
            for j in 0..n {
                nodes.push([i as f64, j as f64, 0.2 * rnd()]);
            }
        }
        let mut mids: HashMap<(usize, usize), usize> = HashMap::new();
        let mut mid = |a: usize, b: usize, nodes: &mut Vec<V3>, rnd: &mut dyn FnMut() -> f64| {
            let key = (a.min(b), a.max(b));
            *mids.entry(key).or_insert_with(|| {
                let (p, q) = (nodes[a], nodes[b]);
                nodes.push([0, 1, 2].map(|c| 0.5 * (p[c] + q[c]) + 0.3 * rnd()));
                nodes.len() - 1
            })
        };
        let mut faces = Vec::new();
        for i in 0..n - 1 {
            for j in 0..n - 1 {
                for [a, b, c] in [
                    [vid(i, j), vid(i + 1, j), vid(i, j + 1)],
                    [vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)],
                ] {
                    let (m0, m1, m2) = (
                        mid(a, b, &mut nodes, &mut rnd),
                        mid(b, c, &mut nodes, &mut rnd),
                        mid(c, a, &mut nodes, &mut rnd),
                    );
                    faces.push([a, b, c, m0, m1, m2]);
                }
            }
        }
        let surface = MasterSurface::new(nodes.clone(), faces.clone());
        for (k, f) in faces.iter().enumerate() {
            let x = f.map(|i| nodes[i]);
            let b = &surface.boxes[k];
            for a in 0..=10 {
                for c in 0..=10 - a {
                    let st = [a as f64 / 10.0, c as f64 / 10.0];
                    let sh = tri6::shape(st);
                    let q = [0, 1, 2].map(|d| (0..6).map(|i| sh[i] * x[i][d]).sum::<f64>());
                    assert!(box_distance2(q, b) == 0.0, "face {k} at {st:?}");
                }
            }
        }
        let mut found = 0;
        for _ in 0..400 {
            let p = [
                0.5 + 4.0 * (rnd() + 0.5),
                0.5 + 4.0 * (rnd() + 0.5),
                0.6 * rnd(),
            ];
            let reach = 0.4;
            let brute = (0..faces.len())
                .filter_map(|k| project_on_face(&surface.face_x(k), p).map(|r| (k, r)))
                .map(|(k, r)| (norm(sub(p, r.0)), k))
                .filter(|&(d, _)| d <= reach)
                .min_by(|a, b| a.0.total_cmp(&b.0));
            let grid = surface.project(p, reach);
            match (brute, grid) {
                (Some((d, _)), Some(g)) => {
                    assert!((norm(sub(p, g.point)) - d).abs() < 1e-12, "{p:?}");
                    found += 1;
                }
                (None, None) => {}
                (b, g) => panic!("{p:?}: brute {b:?}, grid {:?}", g.map(|g| g.face)),
            }
        }
        assert!(found > 100, "{found}");
    }
}
