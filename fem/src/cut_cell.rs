//! Tet10 elements cut by a level set: stiffness of the part where φ ≥ 0,
//! and a tie u = 0 on the cut surface φ = 0, by a penalty or by Nitsche's
//! method.
//!
//! φ is linear over the element, interpolated from its four vertex values in
//! reference coordinates. The part {φ ≥ 0} of the reference tetrahedron is a
//! convex polyhedron with planar faces, split here into tetrahedra:
//! - one vertex a with φ ≥ 0: the corner tetrahedron (a, p_ab, p_ac, p_ad);
//! - two, a and b: the wedge between the triangles (a, p_ac, p_ad) and
//!   (b, p_bc, p_bd), three tetrahedra;
//! - three, a, b, c (d outside): the prism between (a, b, c) and
//!   (p_ad, p_bd, p_cd), three tetrahedra;
//!
//! with p_xy the zero of φ on edge xy. The cut surface is the triangle or
//! quadrilateral of these points (one or two triangles).
//!
//! Integrals map each piece's quadrature points into the element's reference
//! coordinates and use the element's own isoparametric map:
//!
//!   K = Σ_pieces Σ_q w_q det J(ξ_q) Bᵀ D B (ξ_q),
//!   P_ai,bj = α δ_ij ∫_Γ N_a N_b dA,   dA = |J t_s × J t_t| ds dt,
//!
//! with t_s, t_t the reference edge vectors of a surface triangle. A straight
//! element's integrand is a polynomial of degree 2 (stiffness) and 4 (tie),
//! which the 4-point tetrahedron and 6-point triangle rules integrate exactly.
//!
//! A penalty forces the quadratic field towards zero on a plane that runs
//! through the elements; the only quadratics that vanish there are φ times a
//! linear function, so a large α locks the cut elements (the held side grows
//! stiffer with every decade of α, by a share that depends on the mesh).
//! Nitsche's method adds the consistency terms
//!
//!   K_N = −∫_Γ (Nᵀ T + Tᵀ N) dA + α_T ∫_Γ Nᵀ N dA,
//!
//! with T the traction σ(u) n of the element's field on Γ (n the outward
//! normal of {φ ≥ 0}); the exact solution satisfies it for any α_T, so α_T
//! only has to keep K_N coercive: α_T = γ λ_T with λ_T = max_v ‖σ(v) n‖²_Γ /
//! a_T+(v, v), the largest eigenvalue of the element's traction matrix
//! ∫_Γ Tᵀ T dA against its inside stiffness, and γ > 2.

use crate::{tet10, tri6};

/// Reference coordinates (ξ, η, ζ).
pub type Xi = [f64; 3];

/// The part of the reference tetrahedron where φ ≥ 0 and its cut surface.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Clip {
    /// Tetrahedra (reference coordinates) filling {φ ≥ 0}.
    pub tets: Vec<[Xi; 4]>,
    /// Triangles (reference coordinates) covering {φ = 0}.
    pub surface: Vec<[Xi; 3]>,
}

fn lerp(a: Xi, b: Xi, t: f64) -> Xi {
    [0, 1, 2].map(|c| a[c] + t * (b[c] - a[c]))
}

/// The zero of φ on edge (a, b), φ linear with φ(a) = fa ≥ 0 > fb = φ(b).
fn zero(a: Xi, b: Xi, fa: f64, fb: f64) -> Xi {
    lerp(a, b, fa / (fa - fb))
}

/// Splits the reference tetrahedron by the vertex values `phi` (vertex
/// order 0–3 of [`tet10`]); a vertex with φ = 0 counts as inside.
pub fn clip(phi: [f64; 4]) -> Clip {
    let v: [Xi; 4] = std::array::from_fn(|i| tet10::reference_nodes()[i]);
    let inside: Vec<usize> = (0..4).filter(|&i| phi[i] >= 0.0).collect();
    let outside: Vec<usize> = (0..4).filter(|&i| phi[i] < 0.0).collect();
    let p = |a: usize, b: usize| zero(v[a], v[b], phi[a], phi[b]);
    // Prism (A, B, C) – (A', B', C') with planar quadrilateral sides.
    let prism = |a: Xi, b: Xi, c: Xi, a2: Xi, b2: Xi, c2: Xi| {
        vec![[a, b, c, c2], [a, b, b2, c2], [a, a2, b2, c2]]
    };
    match (inside.as_slice(), outside.as_slice()) {
        (_, []) => Clip {
            tets: vec![v],
            surface: Vec::new(),
        },
        ([], _) => Clip::default(),
        (&[a], &[b, c, d]) => {
            let (pb, pc, pd) = (p(a, b), p(a, c), p(a, d));
            Clip {
                tets: vec![[v[a], pb, pc, pd]],
                surface: vec![[pb, pc, pd]],
            }
        }
        (&[a, b], &[c, d]) => {
            let (ac, ad, bc, bd) = (p(a, c), p(a, d), p(b, c), p(b, d));
            Clip {
                tets: prism(v[a], ac, ad, v[b], bc, bd),
                surface: vec![[ac, bc, bd], [ac, bd, ad]],
            }
        }
        (&[a, b, c], &[d]) => {
            let (ad, bd, cd) = (p(a, d), p(b, d), p(c, d));
            Clip {
                tets: prism(v[a], v[b], v[c], ad, bd, cd),
                surface: vec![[ad, bd, cd]],
            }
        }
        _ => unreachable!("four vertices split into inside and outside"),
    }
}

fn sub(a: Xi, b: Xi) -> Xi {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: Xi, b: Xi) -> Xi {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: Xi) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// The 4-point Gauss rule mapped onto the reference-space tetrahedron `t`:
/// points in the element's reference coordinates, weights summing to its
/// reference volume.
pub fn tet_rule(t: &[Xi; 4]) -> [(Xi, f64); 4] {
    let (e1, e2, e3) = (sub(t[1], t[0]), sub(t[2], t[0]), sub(t[3], t[0]));
    let det = tet10::det3(&[e1, e2, e3]).abs();
    tet10::gauss4().map(|(r, w)| {
        let xi = [0, 1, 2].map(|c| t[0][c] + r[0] * e1[c] + r[1] * e2[c] + r[2] * e3[c]);
        (xi, w * det)
    })
}

/// Volume of the element's part {φ ≥ 0}: Σ_pieces Σ_q w_q det J(ξ_q)
/// (exact for straight elements).
pub fn inside_volume(x: &[[f64; 3]; 10], c: &Clip) -> f64 {
    c.tets
        .iter()
        .flat_map(tet_rule)
        .map(|(xi, w)| w * tet10::jacobian(x, &tet10::shape_derivatives(xi)).1)
        .sum()
}

/// Stiffness of the element's part {φ ≥ 0} (30 × 30 row-major, dof
/// 3 · node + component); `Err(det J)` at a non-positive det J.
pub fn inside_stiffness(
    x: &[[f64; 3]; 10],
    lambda: f64,
    mu: f64,
    c: &Clip,
) -> Result<[f64; 900], f64> {
    let rule: Vec<(Xi, f64)> = c.tets.iter().flat_map(tet_rule).collect();
    tet10::stiffness_with(x, lambda, mu, &rule)
}

/// Physical area of the cut surface: Σ_q w_q |J t_s × J t_t|.
pub fn surface_area(x: &[[f64; 3]; 10], c: &Clip) -> f64 {
    surface_rule(x, c).iter().map(|(_, w)| w).sum()
}

/// Points (reference coordinates) and physical area weights of the cut
/// surface (6-point rule per triangle).
fn surface_rule(x: &[[f64; 3]; 10], c: &Clip) -> Vec<(Xi, f64)> {
    let mut out = Vec::with_capacity(6 * c.surface.len());
    for t in &c.surface {
        let (ts, tt) = (sub(t[1], t[0]), sub(t[2], t[0]));
        for (st, w) in tri6::dunavant6() {
            let xi = [0, 1, 2].map(|k| t[0][k] + st[0] * ts[k] + st[1] * tt[k]);
            let (j, _) = tet10::jacobian(x, &tet10::shape_derivatives(xi));
            let map = |v: Xi| [0, 1, 2].map(|r| (0..3).map(|k| j[r][k] * v[k]).sum::<f64>());
            out.push((xi, w * norm(cross(map(ts), map(tt)))));
        }
    }
    out
}

/// Penalty tie of all three displacement components to zero on the cut
/// surface: P_ai,bj = α δ_ij ∫_Γ N_a N_b dA (α in Pa/m).
pub fn surface_tie(x: &[[f64; 3]; 10], c: &Clip, alpha: f64) -> [f64; 900] {
    let mut k = [0.0; 900];
    for (xi, w) in surface_rule(x, c) {
        let n = tet10::shape(xi);
        for a in 0..10 {
            for b in 0..10 {
                let v = alpha * w * n[a] * n[b];
                for i in 0..3 {
                    k[(3 * a + i) * 30 + 3 * b + i] += v;
                }
            }
        }
    }
    k
}

/// Outward unit normal n = −∇φ/|∇φ| of {φ ≥ 0} at ξ (φ linear in the
/// reference coordinates: ∇_ξ φ = (φ1 − φ0, φ2 − φ0, φ3 − φ0); ∇_x φ =
/// J⁻ᵀ ∇_ξ φ).
fn outward_normal(x: &[[f64; 3]; 10], phi: [f64; 4], xi: Xi) -> Xi {
    let d = [phi[1] - phi[0], phi[2] - phi[0], phi[3] - phi[0]];
    let (j, det) = tet10::jacobian(x, &tet10::shape_derivatives(xi));
    let ji = tet10::inv3(&j, det);
    let g: Xi = [0, 1, 2].map(|r| (0..3).map(|c| ji[c][r] * d[c]).sum::<f64>());
    let l = norm(g);
    g.map(|v| -v / l)
}

/// Traction operator at ξ: t = T u (3 × 30, dof 3 · node + component),
///
///   T_j,ai = λ g_a,i n_j + μ (δ_ij (g_a · n) + n_i g_a,j),
///
/// the traction σ n of the field u = N_a e_i, g_a the physical gradient of
/// N_a.
fn traction_operator(x: &[[f64; 3]; 10], lambda: f64, mu: f64, n: Xi, xi: Xi) -> [[f64; 30]; 3] {
    let (g, _) = tet10::gradients(x, xi);
    let mut t = [[0.0; 30]; 3];
    for (a, ga) in g.iter().enumerate() {
        let gn = ga[0] * n[0] + ga[1] * n[1] + ga[2] * n[2];
        for i in 0..3 {
            for (j, tj) in t.iter_mut().enumerate() {
                let mut v = lambda * ga[i] * n[j] + mu * n[i] * ga[j];
                if i == j {
                    v += mu * gn;
                }
                tj[3 * a + i] = v;
            }
        }
    }
    t
}

/// A quadrature point of the cut surface: area weight, shape functions and
/// traction operator ([`traction_operator`]).
struct SurfacePoint {
    w: f64,
    n: [f64; 10],
    t: [[f64; 30]; 3],
}

/// The cut surface's quadrature points with what both Nitsche terms need.
fn surface_points(
    x: &[[f64; 3]; 10],
    c: &Clip,
    phi: [f64; 4],
    lambda: f64,
    mu: f64,
) -> Vec<SurfacePoint> {
    surface_rule(x, c)
        .into_iter()
        .map(|(xi, w)| SurfacePoint {
            w,
            n: tet10::shape(xi),
            t: traction_operator(x, lambda, mu, outward_normal(x, phi, xi), xi),
        })
        .collect()
}

/// Nitsche's tie u = 0 on the cut surface with the parameter `alpha` (Pa/m):
///
///   K_N,ai,bj = ∫_Γ (−N_a T_i,bj − T_j,ai N_b + α δ_ij N_a N_b) dA.
pub fn surface_nitsche(
    x: &[[f64; 3]; 10],
    c: &Clip,
    phi: [f64; 4],
    lambda: f64,
    mu: f64,
    alpha: f64,
) -> [f64; 900] {
    nitsche_matrix(&surface_points(x, c, phi, lambda, mu), alpha)
}

fn nitsche_matrix(points: &[SurfacePoint], alpha: f64) -> [f64; 900] {
    let mut k = [0.0; 900];
    for SurfacePoint { w, n: nn, t } in points {
        for a in 0..10 {
            for i in 0..3 {
                let row = (3 * a + i) * 30;
                for b in 0..10 {
                    for j in 0..3 {
                        let mut v = -nn[a] * t[i][3 * b + j] - t[j][3 * a + i] * nn[b];
                        if i == j {
                            v += alpha * nn[a] * nn[b];
                        }
                        k[row + 3 * b + j] += w * v;
                    }
                }
            }
        }
    }
    k
}

/// λ_T = max_v ‖σ(v) n‖²_Γ / a_T+(v, v): the largest eigenvalue of the
/// traction matrix M = ∫_Γ Tᵀ T dA against the inside stiffness `k_inside`,
/// over the modes that strain the inside part (rigid motions leave both
/// zero). Pa/m.
pub fn nitsche_bound(
    x: &[[f64; 3]; 10],
    c: &Clip,
    phi: [f64; 4],
    lambda: f64,
    mu: f64,
    k_inside: &[f64; 900],
) -> f64 {
    bound_of(&surface_points(x, c, phi, lambda, mu), k_inside)
}

fn bound_of(points: &[SurfacePoint], k_inside: &[f64; 900]) -> f64 {
    use nalgebra::{DMatrix, SymmetricEigen};
    let mut m = DMatrix::<f64>::zeros(30, 30);
    for SurfacePoint { w, t, .. } in points {
        for p in 0..30 {
            for q in 0..30 {
                m[(p, q)] += w * (0..3).map(|k| t[k][p] * t[k][q]).sum::<f64>();
            }
        }
    }
    let k = DMatrix::from_row_slice(30, 30, k_inside);
    let k = SymmetricEigen::new(0.5 * (&k + k.transpose()));
    let top = k.eigenvalues.max();
    if top <= 0.0 || top.is_nan() {
        // No inside volume (φ = 0 at the only vertex not below it): no tie.
        return 0.0;
    }
    // Straining modes: K_+ = V Λ Vᵀ restricted to Λ > 0 (rigid ones are at
    // round-off), L = V Λ^{-1/2}; λ_T is the top eigenvalue of Lᵀ M L.
    let keep: Vec<usize> = (0..30)
        .filter(|&i| k.eigenvalues[i] > 1e-10 * top)
        .collect();
    let mut l = DMatrix::<f64>::zeros(30, keep.len());
    for (c, &i) in keep.iter().enumerate() {
        let s = k.eigenvalues[i].sqrt().recip();
        for r in 0..30 {
            l[(r, c)] = k.eigenvectors[(r, i)] * s;
        }
    }
    let a = l.transpose() * m * &l;
    SymmetricEigen::new(0.5 * (&a + a.transpose()))
        .eigenvalues
        .max()
}

/// How a cut element holds its cut surface at zero displacement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tie {
    /// The penalty P with α in Pa/m.
    Penalty { alpha: f64 },
    /// Nitsche's terms with α_T = γ λ_T ([`nitsche_bound`]); γ > 2 keeps
    /// the element's matrix coercive.
    Nitsche { gamma: f64 },
}

/// The element matrix of a model that keeps {φ ≥ 0} and ties u = 0 on
/// φ = 0 ([`Tie`]): the whole stiffness where every vertex is inside; for a
/// cut element, the inside part's stiffness, the tie, and `ghost` × the
/// whole element's stiffness (a small multiple, 1e-9 say: it keeps the
/// outside nodes of a barely cut element from being nearly free, at a
/// relative change of the order of `ghost`). `phi` are the vertex values;
/// an element with no vertex inside gets a zero matrix.
pub fn cut_stiffness(
    x: &[[f64; 3]; 10],
    lambda: f64,
    mu: f64,
    phi: [f64; 4],
    tie: Tie,
    ghost: f64,
) -> Result<[f64; 900], f64> {
    if phi.iter().all(|&p| p >= 0.0) {
        return tet10::stiffness(x, lambda, mu);
    }
    let c = clip(phi);
    if c.tets.is_empty() {
        return Ok([0.0; 900]);
    }
    let mut k = inside_stiffness(x, lambda, mu, &c)?;
    let tie = match tie {
        Tie::Penalty { alpha } => surface_tie(x, &c, alpha),
        Tie::Nitsche { gamma } => {
            let points = surface_points(x, &c, phi, lambda, mu);
            nitsche_matrix(&points, gamma * bound_of(&points, &k))
        }
    };
    let whole = tet10::stiffness(x, lambda, mu)?;
    for ((k, t), w) in k.iter_mut().zip(tie).zip(whole) {
        *k += t + ghost * w;
    }
    Ok(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> [[f64; 3]; 10] {
        tet10::reference_nodes()
    }

    /// Plane cuts of the reference tetrahedron in all three cases (one,
    /// two, three vertices inside): volumes and cut areas in closed form.
    #[test]
    fn plane_cut_volumes_and_areas_match_the_closed_form() {
        let x = unit();
        // φ = s − (ξ + η + ζ) · 1: the corner at vertex 0, a tet of volume s³/6
        // and a cut triangle of area √3 s²/2.
        for s in [0.2, 0.5, 0.9] {
            let c = clip([s, s - 1.0, s - 1.0, s - 1.0]);
            assert_eq!((c.tets.len(), c.surface.len()), (1, 1));
            assert!((inside_volume(&x, &c) - s.powi(3) / 6.0).abs() < 1e-14);
            assert!((surface_area(&x, &c) - 3f64.sqrt() * s * s / 2.0).abs() < 1e-14);
            // The complement: three inside, the prism case.
            let d = clip([-s, 1.0 - s, 1.0 - s, 1.0 - s]);
            assert_eq!((d.tets.len(), d.surface.len()), (3, 1));
            assert!((inside_volume(&x, &d) - (1.0 - s.powi(3)) / 6.0).abs() < 1e-14);
        }
        // φ = c − ξ: vertices 0, 2, 3 inside (ξ = 0), vertex 1 outside. The
        // part ξ ≤ c has volume (1 − (1 − c)³)/6; the cut, the triangle
        // ξ = c, η + ζ ≤ 1 − c, area (1 − c)²/2.
        for cv in [0.3, 0.7] {
            let c = clip([cv, cv - 1.0, cv, cv]);
            let vol = (1.0 - (1.0 - cv).powi(3)) / 6.0;
            assert!((inside_volume(&x, &c) - vol).abs() < 1e-14);
            assert!((surface_area(&x, &c) - (1.0 - cv).powi(2) / 2.0).abs() < 1e-14);
        }
        // Two inside, two outside: φ = c − ξ − η keeps vertices 0 and 3.
        // Volume of ξ + η ≤ c in the tet: ∫₀^c (1 − u) u du = c²/2 − c³/3.
        for cv in [0.25, 0.6] {
            let c = clip([cv, cv - 1.0, cv - 1.0, cv]);
            assert_eq!((c.tets.len(), c.surface.len()), (3, 2));
            let vol = cv * cv / 2.0 - cv.powi(3) / 3.0;
            assert!((inside_volume(&x, &c) - vol).abs() < 1e-14, "{cv}");
            // The cut: (ξ, c − ξ, ζ) with 0 ≤ ξ ≤ c, 0 ≤ ζ ≤ 1 − c, a
            // rectangle in (ξ, ζ) with area element |(1, −1, 0) × (0, 0, 1)| = √2.
            let area = std::f64::consts::SQRT_2 * cv * (1.0 - cv);
            assert!((surface_area(&x, &c) - area).abs() < 1e-14, "{cv}");
        }
    }

    /// Sub-tetrahedra never overlap: the inside and outside parts of any cut
    /// add up to the whole element, curved elements included.
    #[test]
    fn inside_and_outside_parts_add_up_to_the_element() {
        let mut x = unit();
        // Curve two mid-edge nodes (a curved face).
        x[4][1] += 0.05;
        x[7][0] -= 0.04;
        let whole = tet10::volume(&x);
        for phi in [
            [0.3, -0.2, 0.1, -0.5],
            [0.9, -0.1, -0.3, -0.2],
            [0.2, 0.4, 0.1, -0.7],
        ] {
            let neg = phi.map(|p: f64| -p);
            let (a, b) = (clip(phi), clip(neg));
            let sum = inside_volume(&x, &a) + inside_volume(&x, &b);
            // The 4-point rule is not exact on curved elements: 1e-4 here.
            assert!((sum - whole).abs() < 1e-4 * whole, "{sum} vs {whole}");
            assert!((surface_area(&x, &a) - surface_area(&x, &b)).abs() < 1e-14);
        }
    }

    /// Nitsche's element matrix (inside stiffness + tie) is symmetric and
    /// positive semi-definite (to round-off) at γ = 4 for cuts of every
    /// kind, slivers included (λ_T grows as the inside part shrinks, and α_T
    /// with it), while the tie's consistency terms alone, without α_T, leave
    /// it indefinite.
    #[test]
    fn nitsche_element_matrix_is_symmetric_and_coercive_for_slivers_and_full_cuts() {
        use nalgebra::{DMatrix, SymmetricEigen};
        let mut x = unit();
        x[4][1] += 0.05;
        x[7][0] -= 0.04;
        let (lambda, mu) = (1.2, 0.8);
        let min_eig = |k: &[f64; 900]| -> (f64, f64) {
            let m = DMatrix::from_row_slice(30, 30, k);
            let asym = (&m - m.transpose()).abs().max() / m.abs().max();
            let e = SymmetricEigen::new(m).eigenvalues;
            (e.min() / e.max(), asym)
        };
        for (phi, sliver) in [
            ([0.3, -0.2, 0.1, -0.5], false),
            ([0.9, -0.1, -0.3, -0.2], false),
            ([0.2, 0.4, 0.1, -0.7], false),
            ([1e-3, -1.0, -1.0, -1.0], true),
            ([1.0, 1.0, 1.0, -1e-3], true),
        ] {
            let c = clip(phi);
            let inside = inside_stiffness(&x, lambda, mu, &c).unwrap();
            let bound = nitsche_bound(&x, &c, phi, lambda, mu, &inside);
            let k = cut_stiffness(&x, lambda, mu, phi, Tie::Nitsche { gamma: 4.0 }, 0.0).unwrap();
            let (low, asym) = min_eig(&k);
            assert!(asym < 1e-12, "{phi:?}: asymmetry {asym:e}");
            // Rigid motions are held only by the tie on Γ: at round-off for
            // a tiny Γ, never below it.
            assert!(
                low > -1e-13,
                "{phi:?}: smallest / largest eigenvalue {low:e}"
            );
            let mut bare = inside;
            let tie = surface_nitsche(&x, &c, phi, lambda, mu, 0.0);
            bare.iter_mut().zip(tie).for_each(|(k, t)| *k += t);
            let (low0, _) = min_eig(&bare);
            // (A sliver's consistency terms are too small to show it.)
            assert!(
                sliver || low0 < -1e-6,
                "{phi:?}: no α, smallest / largest eigenvalue {low0:e}"
            );
            assert!(bound > 0.0 && bound.is_finite(), "{phi:?}: λ_T {bound:e}");
        }
        // φ = 0 at the one vertex not below it: nothing inside, no tie.
        let c = clip([0.0, -1.0, -1.0, -1.0]);
        let inside = inside_stiffness(&x, lambda, mu, &c).unwrap();
        assert_eq!(
            nitsche_bound(&x, &c, [0.0, -1.0, -1.0, -1.0], lambda, mu, &inside),
            0.0
        );
    }
}
