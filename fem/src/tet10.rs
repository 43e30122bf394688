//! The 10-node quadratic tetrahedron (gmsh node order).
//!
//! Volume coordinates L0 = 1 − ξ − η − ζ, L1 = ξ, L2 = η, L3 = ζ.
//! Vertex i: Nᵢ = Lᵢ(2Lᵢ − 1); mid-edge node on edge (a, b): N = 4 L_a L_b.

/// Mid-edge nodes 4..9 sit on these vertex pairs (gmsh order).
pub const EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [3, 0], [3, 2], [3, 1]];

/// Reference coordinates (ξ, η, ζ) of the ten nodes.
pub fn reference_nodes() -> [[f64; 3]; 10] {
    let v = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let mut out = [[0.0; 3]; 10];
    out[..4].copy_from_slice(&v);
    for (k, [a, b]) in EDGES.iter().enumerate() {
        for c in 0..3 {
            out[4 + k][c] = 0.5 * (v[*a][c] + v[*b][c]);
        }
    }
    out
}

/// The 4-point Gauss rule on the reference tetrahedron (degree 2):
/// points (a, b, b), … with a = (5 + 3√5)/20, b = (5 − √5)/20, weights 1/24.
pub fn gauss4() -> [([f64; 3], f64); 4] {
    let a = (5.0 + 3.0 * 5f64.sqrt()) / 20.0;
    let b = (5.0 - 5f64.sqrt()) / 20.0;
    let w = 1.0 / 24.0;
    [
        ([b, b, b], w),
        ([a, b, b], w),
        ([b, a, b], w),
        ([b, b, a], w),
    ]
}

fn volume_coordinates(xi: [f64; 3]) -> [f64; 4] {
    [1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]]
}

/// Shape functions N(ξ).
pub fn shape(xi: [f64; 3]) -> [f64; 10] {
    let l = volume_coordinates(xi);
    let mut n = [0.0; 10];
    for i in 0..4 {
        n[i] = l[i] * (2.0 * l[i] - 1.0);
    }
    for (k, [a, b]) in EDGES.iter().enumerate() {
        n[4 + k] = 4.0 * l[*a] * l[*b];
    }
    n
}

/// Shape-function derivatives ∂Nᵢ/∂ξ_c, from ∂N/∂L by the chain rule
/// ∂/∂ξ_c = ∂/∂L_c − ∂/∂L_0.
pub fn shape_derivatives(xi: [f64; 3]) -> [[f64; 3]; 10] {
    let l = volume_coordinates(xi);
    // dN/dL (4 volume coordinates)
    let mut dl = [[0.0; 4]; 10];
    for i in 0..4 {
        dl[i][i] = 4.0 * l[i] - 1.0;
    }
    for (k, [a, b]) in EDGES.iter().enumerate() {
        dl[4 + k][*a] = 4.0 * l[*b];
        dl[4 + k][*b] = 4.0 * l[*a];
    }
    let mut d = [[0.0; 3]; 10];
    for i in 0..10 {
        for c in 0..3 {
            d[i][c] = dl[i][c + 1] - dl[i][0];
        }
    }
    d
}

/// Jacobian J_rc = Σᵢ xᵢ_r ∂Nᵢ/∂ξ_c and its determinant.
pub fn jacobian(x: &[[f64; 3]; 10], dn: &[[f64; 3]; 10]) -> ([[f64; 3]; 3], f64) {
    let mut j = [[0.0; 3]; 3];
    for i in 0..10 {
        for r in 0..3 {
            for c in 0..3 {
                j[r][c] += x[i][r] * dn[i][c];
            }
        }
    }
    (j, det3(&j))
}

/// Determinant of a 3×3 matrix.
pub fn det3(a: &[[f64; 3]; 3]) -> f64 {
    a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
        - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
        + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
}

/// Inverse of a 3×3 matrix with known determinant.
pub fn inv3(a: &[[f64; 3]; 3], det: f64) -> [[f64; 3]; 3] {
    let c =
        |r0: usize, r1: usize, c0: usize, c1: usize| a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0];
    let s = 1.0 / det;
    [
        [c(1, 2, 1, 2) * s, -c(0, 2, 1, 2) * s, c(0, 1, 1, 2) * s],
        [-c(1, 2, 0, 2) * s, c(0, 2, 0, 2) * s, -c(0, 1, 0, 2) * s],
        [c(1, 2, 0, 1) * s, -c(0, 2, 0, 1) * s, c(0, 1, 0, 1) * s],
    ]
}

/// Physical gradients gᵢ = ∂Nᵢ/∂x = J⁻ᵀ ∂Nᵢ/∂ξ at ξ, with det J.
pub fn gradients(x: &[[f64; 3]; 10], xi: [f64; 3]) -> ([[f64; 3]; 10], f64) {
    let dn = shape_derivatives(xi);
    let (j, det) = jacobian(x, &dn);
    let ji = inv3(&j, det);
    let mut g = [[0.0; 3]; 10];
    for i in 0..10 {
        for r in 0..3 {
            g[i][r] = (0..3).map(|c| ji[c][r] * dn[i][c]).sum();
        }
    }
    (g, det)
}

/// The 5-point rule on the reference tetrahedron (degree 3): centroid with
/// weight −2/15, and (1/2, 1/6, 1/6) with its permutations and (1/6, 1/6, 1/6),
/// weights 3/40.
pub fn degree3() -> [([f64; 3], f64); 5] {
    let (a, b) = (0.5, 1.0 / 6.0);
    [
        ([0.25, 0.25, 0.25], -2.0 / 15.0),
        ([a, b, b], 3.0 / 40.0),
        ([b, a, b], 3.0 / 40.0),
        ([b, b, a], 3.0 / 40.0),
        ([b, b, b], 3.0 / 40.0),
    ]
}

/// Element volume |∫ det J dξ|. det J of a tet10 is cubic in ξ, so the
/// degree-3 rule makes this exact for curved elements too.
pub fn volume(x: &[[f64; 3]; 10]) -> f64 {
    degree3()
        .iter()
        .map(|(xi, w)| w * jacobian(x, &shape_derivatives(*xi)).1)
        .sum::<f64>()
        .abs()
}

/// Isotropic element stiffness, 30×30 row-major with dof 3·node + component.
///
/// Block (a, b), components (i, j):
/// K_ai,bj = Σ_q w_q det J_q [λ g_a,i g_b,j + μ g_a,j g_b,i + μ δ_ij (g_a · g_b)],
/// with gᵢ the physical shape-function gradients at quadrature point q
/// (4-point Gauss). Returns `Err(det J)` if det J ≤ 0 at any point.
///
/// A rigid translation strains nothing, so it meets no nodal force, and
/// K is symmetric:
///
/// ```
/// use fem::tet10::{reference_nodes, stiffness};
/// let (lambda, mu) = (121.15e9, 80.77e9); // steel: E = 210 GPa, ν = 0.3
/// let k = stiffness(&reference_nodes(), lambda, mu).unwrap();
/// // u = (1, 0, 0) at every node.
/// let f: Vec<f64> = (0..30)
///     .map(|r| (0..10).map(|b| k[r * 30 + 3 * b]).sum::<f64>())
///     .collect();
/// assert!(f.iter().all(|x| x.abs() < 1e-6 * mu));
/// assert!((0..30).all(|i| (0..30).all(|j| (k[i * 30 + j] - k[j * 30 + i]).abs() < 1e-6 * mu)));
/// ```
pub fn stiffness(x: &[[f64; 3]; 10], lambda: f64, mu: f64) -> Result<[f64; 900], f64> {
    stiffness_with(x, lambda, mu, &gauss4())
}

/// [`stiffness`] with the quadrature rule `rule` (points ξ_q in reference
/// coordinates, weights w_q): for parts of the element ([`crate::cut_cell`]).
pub fn stiffness_with(
    x: &[[f64; 3]; 10],
    lambda: f64,
    mu: f64,
    rule: &[([f64; 3], f64)],
) -> Result<[f64; 900], f64> {
    let mut k = [0.0; 900];
    for &(xi, w) in rule {
        let (g, det) = gradients(x, xi);
        if det <= 0.0 || !det.is_finite() {
            return Err(det);
        }
        let s = w * det;
        for a in 0..10 {
            for b in 0..10 {
                let dot = g[a][0] * g[b][0] + g[a][1] * g[b][1] + g[a][2] * g[b][2];
                for i in 0..3 {
                    let row = (3 * a + i) * 30 + 3 * b;
                    for j in 0..3 {
                        let mut v = lambda * g[a][i] * g[b][j] + mu * g[a][j] * g[b][i];
                        if i == j {
                            v += mu * dot;
                        }
                        k[row + j] += s * v;
                    }
                }
            }
        }
    }
    Ok(k)
}

/// Small-strain tensor ε = sym(∇u) at ξ for nodal displacements u.
pub fn strain(x: &[[f64; 3]; 10], u: &[[f64; 3]; 10], xi: [f64; 3]) -> [[f64; 3]; 3] {
    let (g, _) = gradients(x, xi);
    let mut e = [[0.0; 3]; 3];
    for a in 0..10 {
        for i in 0..3 {
            for j in 0..3 {
                e[i][j] += 0.5 * (u[a][i] * g[a][j] + u[a][j] * g[a][i]);
            }
        }
    }
    e
}

/// Position x(ξ) = Σ Nᵢ(ξ) xᵢ.
pub fn position(x: &[[f64; 3]; 10], xi: [f64; 3]) -> [f64; 3] {
    let n = shape(xi);
    let mut p = [0.0; 3];
    for i in 0..10 {
        for c in 0..3 {
            p[c] += n[i] * x[i][c];
        }
    }
    p
}

/// Gauss–Legendre rule of `n` points on [0, 1] (nodes, weights): the roots
/// of Pₙ(2t − 1) by Newton from Chebyshev's guesses, weights
/// 1 / ((1 − x²) Pₙ′(x)²) on [0, 1]. Exact for polynomials of degree 2n − 1.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                // P_n(x) and P_n'(x) by the three-term recurrence.
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                let p = if n == 0 { 1.0 } else { p1 };
                let pm1 = if n == 1 { 1.0 } else { p0 };
                dp = n as f64 * (x * p - pm1) / (x * x - 1.0);
                let dx = p / dp;
                x -= dx;
                if dx.abs() < 1e-15 {
                    break;
                }
            }
            ((1.0 - x) / 2.0, 1.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// Conical-product rule of n³ points on the reference tetrahedron:
/// Gauss–Legendre in u, v, w ∈ [0, 1] through Duffy's map ξ = u,
/// η = v(1 − u), ζ = w(1 − u)(1 − v), dξ dη dζ = (1 − u)²(1 − v) du dv dw.
/// Exact for polynomials of degree 2n − 3 in (ξ, η, ζ).
pub fn conical_rule(n: usize) -> Vec<([f64; 3], f64)> {
    let g = gauss_legendre(n);
    let mut rule = Vec::with_capacity(n * n * n);
    for &(u, wu) in &g {
        for &(v, wv) in &g {
            for &(w, ww) in &g {
                let xi = [u, v * (1.0 - u), w * (1.0 - u) * (1.0 - v)];
                rule.push((xi, wu * wv * ww * (1.0 - u).powi(2) * (1.0 - v)));
            }
        }
    }
    rule
}

/// Consistent mass, 30×30 row-major with dof 3·node + component:
///
///   M_ai,bj = δ_ij ρ ∫ N_a N_b dV = δ_ij ρ Σ_q w_q det J_q N_a(ξ_q) N_b(ξ_q),
///
/// by the 125-point conical rule, exact for N_a N_b det J of degree 7 (a
/// curved element). Σ_ab m_ab = ρ V: the mass moves whole under a rigid
/// translation. Returns `Err(det J)` if det J ≤ 0 at any point.
pub fn mass(x: &[[f64; 3]; 10], density: f64) -> Result<[f64; 900], f64> {
    static RULE: std::sync::OnceLock<Vec<([f64; 3], f64)>> = std::sync::OnceLock::new();
    let rule = RULE.get_or_init(|| conical_rule(5));
    let mut m = [[0.0; 10]; 10];
    for &(xi, w) in rule {
        let det = jacobian(x, &shape_derivatives(xi)).1;
        if det <= 0.0 || !det.is_finite() {
            return Err(det);
        }
        let n = shape(xi);
        let s = density * w * det;
        for a in 0..10 {
            for b in 0..10 {
                m[a][b] += s * n[a] * n[b];
            }
        }
    }
    let mut out = [0.0; 900];
    for a in 0..10 {
        for b in 0..10 {
            for i in 0..3 {
                out[(3 * a + i) * 30 + 3 * b + i] = m[a][b];
            }
        }
    }
    Ok(out)
}
