//! Tet10 elements cut by a level set: stiffness of the part where φ ≥ 0,
//! and a penalty tie u = 0 on the cut surface φ = 0.
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

/// The element matrix of a model that keeps {φ ≥ 0} and ties u = 0 on
/// φ = 0 by a penalty α (Pa/m): the whole stiffness where every vertex is
/// inside; for a cut element, the inside part's stiffness, the tie, and
/// `ghost` × the whole element's stiffness (a small multiple, 1e-9 say: it
/// keeps the outside nodes of a barely cut element from being nearly free,
/// at a relative change of the order of `ghost`). `phi` are the vertex
/// values; an element with no vertex inside gets a zero matrix.
pub fn cut_stiffness(
    x: &[[f64; 3]; 10],
    lambda: f64,
    mu: f64,
    phi: [f64; 4],
    alpha: f64,
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
    let tie = surface_tie(x, &c, alpha);
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
}
