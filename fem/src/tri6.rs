//! The 6-node quadratic triangle on element faces (gmsh node order).
//!
//! Area coordinates L0 = 1 − s − t, L1 = s, L2 = t. Vertex i: Nᵢ = Lᵢ(2Lᵢ − 1);
//! mid-edge node on (a, b): N = 4 L_a L_b, edges (0,1), (1,2), (2,0).

const EDGES: [[usize; 2]; 3] = [[0, 1], [1, 2], [2, 0]];

/// Shape functions N(s, t).
pub fn shape(st: [f64; 2]) -> [f64; 6] {
    let l = [1.0 - st[0] - st[1], st[0], st[1]];
    let mut n = [0.0; 6];
    for i in 0..3 {
        n[i] = l[i] * (2.0 * l[i] - 1.0);
    }
    for (k, [a, b]) in EDGES.iter().enumerate() {
        n[3 + k] = 4.0 * l[*a] * l[*b];
    }
    n
}

/// Derivatives ∂Nᵢ/∂(s, t).
pub fn shape_derivatives(st: [f64; 2]) -> [[f64; 2]; 6] {
    let l = [1.0 - st[0] - st[1], st[0], st[1]];
    let mut dl = [[0.0; 3]; 6];
    for i in 0..3 {
        dl[i][i] = 4.0 * l[i] - 1.0;
    }
    for (k, [a, b]) in EDGES.iter().enumerate() {
        dl[3 + k][*a] = 4.0 * l[*b];
        dl[3 + k][*b] = 4.0 * l[*a];
    }
    let mut d = [[0.0; 2]; 6];
    for i in 0..6 {
        d[i] = [dl[i][1] - dl[i][0], dl[i][2] - dl[i][0]];
    }
    d
}

/// The 6-point Dunavant rule on the reference triangle (degree 4), weights
/// summing to the reference area 1/2.
pub fn dunavant6() -> [([f64; 2], f64); 6] {
    let (a1, b1, w1) = (
        0.445_948_490_915_965,
        0.108_103_018_168_070,
        0.223_381_589_678_011,
    );
    let (a2, b2, w2) = (
        0.091_576_213_509_771,
        0.816_847_572_980_459,
        0.109_951_743_655_322,
    );
    [
        ([a1, a1], 0.5 * w1),
        ([a1, b1], 0.5 * w1),
        ([b1, a1], 0.5 * w1),
        ([a2, a2], 0.5 * w2),
        ([a2, b2], 0.5 * w2),
        ([b2, a2], 0.5 * w2),
    ]
}

/// Point and area-weighted normal at (s, t): x = Σ Nᵢ xᵢ and
/// n dA = (∂x/∂s × ∂x/∂t) ds dt (right-hand rule of the node order).
pub fn point_and_normal(x: &[[f64; 3]; 6], st: [f64; 2]) -> ([f64; 3], [f64; 3]) {
    let n = shape(st);
    let d = shape_derivatives(st);
    let mut p = [0.0; 3];
    let mut xs = [0.0; 3];
    let mut xt = [0.0; 3];
    for i in 0..6 {
        for c in 0..3 {
            p[c] += n[i] * x[i][c];
            xs[c] += d[i][0] * x[i][c];
            xt[c] += d[i][1] * x[i][c];
        }
    }
    let nn = [
        xs[1] * xt[2] - xs[2] * xt[1],
        xs[2] * xt[0] - xs[0] * xt[2],
        xs[0] * xt[1] - xs[1] * xt[0],
    ];
    (p, nn)
}

/// Consistent nodal forces of a traction field t(x, n̂) on one face:
/// fᵢ = ∫ Nᵢ t dA (6-point rule). `traction` gets the point and the unit normal.
pub fn consistent_forces(
    x: &[[f64; 3]; 6],
    mut traction: impl FnMut([f64; 3], [f64; 3]) -> [f64; 3],
) -> [[f64; 3]; 6] {
    let mut f = [[0.0; 3]; 6];
    for (st, w) in dunavant6() {
        let (p, nn) = point_and_normal(x, st);
        let da = (nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]).sqrt();
        let unit = [nn[0] / da, nn[1] / da, nn[2] / da];
        let t = traction(p, unit);
        let n = shape(st);
        for i in 0..6 {
            for c in 0..3 {
                f[i][c] += w * da * n[i] * t[c];
            }
        }
    }
    f
}

/// Face area ∫ dA (6-point rule).
pub fn area(x: &[[f64; 3]; 6]) -> f64 {
    dunavant6()
        .iter()
        .map(|(st, w)| {
            let (_, nn) = point_and_normal(x, *st);
            w * (nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]).sqrt()
        })
        .sum()
}
