//! The 10-node tetrahedron as CalculiX and Abaqus number it (C3D10), from
//! the meshes' gmsh order: node order, orientation and face labels.
//!
//! gmsh puts the mid-edge nodes 4..9 on the vertex pairs (0,1), (1,2),
//! (2,0), (3,0), (3,2), (3,1); C3D10 on (0,1), (1,2), (2,0), (0,3), (1,3),
//! (2,3). The two orders differ by the last two nodes.
//!
//! C3D10's faces (0-based vertices): S1 = (0,1,2), S2 = (0,3,1),
//! S3 = (1,3,2), S4 = (2,3,0), numbered so that their right-hand normal
//! points into a positive element (the solver knows the outward side from
//! the label alone).

type V3 = [f64; 3];

/// C3D10 node k is gmsh node `GMSH_OF_C3D10[k]`.
pub const GMSH_OF_C3D10: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8];

/// The element's nodes in C3D10 order.
pub fn c3d10_order(gmsh: &[usize; 10]) -> [usize; 10] {
    GMSH_OF_C3D10.map(|k| gmsh[k])
}

/// Mid-edge node 4..9 of C3D10 on these vertex pairs.
const C3D10_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];

/// The mid-edge node of element `el` (C3D10 order) between its vertices
/// `p` and `q` (0..4, p ≠ q).
pub fn mid_edge(el: &[usize; 10], p: usize, q: usize) -> usize {
    let k = C3D10_EDGES
        .iter()
        .position(|e| (e[0] == p && e[1] == q) || (e[0] == q && e[1] == p))
        .expect("two vertices of a tetrahedron share an edge");
    el[4 + k]
}

/// Derivatives ∂Nₖ/∂(ξ, η, ζ) of the C3D10 shape functions at a point of
/// the reference element (L0 = 1 − ξ − η − ζ, L1 = ξ, L2 = η, L3 = ζ;
/// vertex Nᵢ = Lᵢ(2Lᵢ − 1), mid-edge N = 4 L_a L_b).
fn shape_derivatives(p: V3) -> [V3; 10] {
    let l = [1.0 - p[0] - p[1] - p[2], p[0], p[1], p[2]];
    // ∂Lᵢ/∂(ξ, η, ζ)
    let dl = [
        [-1.0, -1.0, -1.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let mut d = [[0.0; 3]; 10];
    for i in 0..4 {
        d[i] = dl[i].map(|c| (4.0 * l[i] - 1.0) * c);
    }
    for (k, [a, b]) in C3D10_EDGES.iter().enumerate() {
        for c in 0..3 {
            d[4 + k][c] = 4.0 * (dl[*a][c] * l[*b] + l[*a] * dl[*b][c]);
        }
    }
    d
}

/// det J at the reference point `p` of an element with nodes `x` in
/// C3D10 order.
pub fn jacobian_det(x: &[V3; 10], p: V3) -> f64 {
    let d = shape_derivatives(p);
    // J[i][j] = ∂x_i/∂ξ_j
    let mut j = [[0.0; 3]; 3];
    for k in 0..10 {
        for r in 0..3 {
            for c in 0..3 {
                j[r][c] += x[k][r] * d[k][c];
            }
        }
    }
    j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
        - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
        + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0])
}

/// Where an element's Jacobian is checked: its four vertices, the
/// centroid and the four points of the degree-2 Gauss rule CalculiX
/// integrates C3D10 with.
pub fn check_points() -> [V3; 9] {
    let a = (5.0 + 3.0 * 5f64.sqrt()) / 20.0;
    let b = (5.0 - 5f64.sqrt()) / 20.0;
    [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.25, 0.25, 0.25],
        [b, b, b],
        [a, b, b],
        [b, a, b],
        [b, b, a],
    ]
}

/// The smallest det J over [`check_points`] divided by six times the
/// straight-edged volume's magnitude: 1 for a straight-edged positive
/// element, negative where the element is inverted at a point.
pub fn min_scaled_jacobian(x: &[V3; 10]) -> f64 {
    let e = |i: usize| [0, 1, 2].map(|c| x[i][c] - x[0][c]);
    let (a, b, c) = (e(1), e(2), e(3));
    let vol6 = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0]);
    check_points()
        .iter()
        .map(|&p| jacobian_det(x, p) / vol6.abs())
        .fold(f64::INFINITY, f64::min)
}

/// The C3D10 face label (1..=4) of the face whose three vertices are
/// `face` (any order), if they are three of the element's vertices.
pub fn face_label(element: &[usize; 10], face: [usize; 3]) -> Option<u8> {
    let has = |v: usize| face.contains(&element[v]);
    match (has(0), has(1), has(2), has(3)) {
        (true, true, true, false) => Some(1),
        (true, true, false, true) => Some(2),
        (false, true, true, true) => Some(3),
        (true, false, true, true) => Some(4),
        _ => None,
    }
}

/// The vertices of C3D10 face `label` (1..=4), ordered so that their
/// right-hand normal points out of a positive element (the reverse of the
/// label's own numbering).
pub fn face_vertices(label: u8) -> [usize; 3] {
    match label {
        1 => [0, 2, 1],
        2 => [0, 1, 3],
        3 => [1, 2, 3],
        _ => [2, 0, 3],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The straight unit tetrahedron in C3D10 order.
    fn unit() -> [V3; 10] {
        let v = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let mut x = [[0.0; 3]; 10];
        x[..4].copy_from_slice(&v);
        for (k, [a, b]) in C3D10_EDGES.iter().enumerate() {
            x[4 + k] = [0, 1, 2].map(|c| 0.5 * (v[*a][c] + v[*b][c]));
        }
        x
    }

    #[test]
    fn straight_unit_tetrahedron_has_unit_scaled_jacobian_everywhere() {
        let x = unit();
        for p in check_points() {
            assert!((jacobian_det(&x, p) - 1.0).abs() < 1e-14);
        }
        assert!((min_scaled_jacobian(&x) - 1.0).abs() < 1e-14);
    }

    #[test]
    fn gmsh_order_of_the_last_two_mid_edge_nodes_inverts_a_c3d10_element() {
        // The gmsh order read as C3D10 puts nodes 8 and 9 on the wrong
        // edges: the element is then inverted somewhere; the map repairs it.
        let x = unit();
        let as_gmsh: [V3; 10] = std::array::from_fn(|k| x[GMSH_OF_C3D10[k]]);
        assert!(min_scaled_jacobian(&as_gmsh) < 0.0);
        let back: [V3; 10] = std::array::from_fn(|k| as_gmsh[GMSH_OF_C3D10[k]]);
        assert_eq!(back, x);
        // gmsh's edges (fem::tet10::EDGES) are C3D10's with 8 and 9 swapped.
        for k in 0..6 {
            let g = fem::tet10::EDGES[GMSH_OF_C3D10[4 + k] - 4];
            let mut a = g;
            let mut b = C3D10_EDGES[k];
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b, "C3D10 mid-edge node {}", 4 + k);
        }
    }

    #[test]
    fn swapped_vertices_give_a_negative_jacobian() {
        // Vertices 1 and 2 swapped with their edges: (0,1) <-> (2,0) and
        // (1,3) <-> (2,3); (1,2) stays. A straight element inside out.
        let mut x = unit();
        x.swap(1, 2);
        x.swap(4, 6);
        x.swap(8, 9);
        assert!((min_scaled_jacobian(&x) + 1.0).abs() < 1e-14);
    }

    #[test]
    fn face_labels_point_outward_of_the_unit_tetrahedron() {
        let x = unit();
        let ids: [usize; 10] = std::array::from_fn(|k| k);
        let centroid = [0.25; 3];
        for label in 1..=4u8 {
            let f = face_vertices(label);
            assert_eq!(face_label(&ids, f), Some(label));
            let (a, b, c) = (x[f[0]], x[f[1]], x[f[2]]);
            let u = [0, 1, 2].map(|i| b[i] - a[i]);
            let v = [0, 1, 2].map(|i| c[i] - a[i]);
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let out: f64 = (0..3).map(|i| n[i] * (a[i] - centroid[i])).sum();
            assert!(out > 0.0, "face S{label}");
        }
        assert_eq!(face_label(&ids, [0, 1, 7]), None);
    }
}
