//! A line contact cut by a sharp edge: the local approach of a slice whose
//! contact strip reaches a tooth's tip edge.
//!
//! Plane strain across the contact line, both bodies as half-planes (the
//! classical approximation; the cut body is really a wedge, which is softer
//! still), the cut body ending at the edge X = 0 and the contact strip
//! [−a, 0] ending there. The gap between the unloaded surfaces, inward from
//! the edge (X ≤ 0), is
//!
//!   g(X) = s (−X) + X² / (2ρ) − g₀,
//!
//! s the gap's slope at the edge (s ≥ 0 where the unloaded contact point is
//! the edge itself, s = −d/ρ where it lies a distance d inside) and ρ the
//! relative radius of curvature. The surfaces' slopes in the strip give the
//! singular integral equation (1/π) PV∫ p(τ)/(τ − t) dτ = −(E*/2) g′ on the
//! strip mapped to τ ∈ [−1, 1], X = (a/2)(τ − 1). Its solution bounded at
//! the free end and singular at the edge is
//!
//!   p(τ) = (A + Bτ) √((1 + τ)/(1 − τ)),
//!   A = E* s / 2 + E* a / (2ρ),  B = −E* a / (4ρ),
//!
//! (from (1/π) PV∫ √((1+τ)/(1−τ)) τᵏ/(τ − t) dτ = 1, 1 + t for k = 0, 1), and
//! its line load q = ∫ p dX = (πa/2)(A + B/2):
//!
//!   q = π E* a s / 4 + 3π E* a² / (16ρ).
//!
//! The edge carries load (A + B ≥ 0) once a ≥ 2d: at a = 2d the solution is
//! exactly the Hertz strip of half width b = d touching the edge, so the law
//! joins the uncut line contact continuously.
//!
//! The approach of one body's surface at the contact point x₀ to its point
//! at depth h below, from Flamant's line load (σ_z, σ_x integrated along
//! the vertical as in [`crate::element::weber_banaschek`]), is
//!
//!   w = (1 − ν²)/(πE) ∫ p(X) [ln(1 + h²/u²) − h² / ((1 − ν)(u² + h²))] dX,
//!   u = X − x₀.
//!
//! Its logarithmic part −2∫ p ln|u| dX is closed: with
//! L(t₀) = ∫ p(τ) ln|τ − t₀| dτ, L(1) = π[A(−1 − ln 2) + B(−5/4 − ½ ln 2)]
//! and L′(t₀) = −π(A + B(1 + t₀)) inside the strip; the rest is smooth and
//! integrated by the midpoint rule in θ (τ = cos θ turns
//! √((1+τ)/(1−τ)) dτ into (1 + cos θ) dθ).

use crate::element::weber_banaschek::plane_strain_compliance;
use geometry::Material;
use std::f64::consts::{LN_2, PI};

/// Midpoint-rule points of the approach's smooth part.
const SMOOTH_POINTS: usize = 8;

/// The midpoint rule's nodes τ = cos θ, θ = (k + ½)π/n.
fn smooth_nodes() -> &'static [f64; SMOOTH_POINTS] {
    static NODES: std::sync::OnceLock<[f64; SMOOTH_POINTS]> = std::sync::OnceLock::new();
    NODES.get_or_init(|| {
        std::array::from_fn(|k| ((k as f64 + 0.5) * PI / SMOOTH_POINTS as f64).cos())
    })
}

/// Where a slice's unloaded contact lies relative to the nearest tip edge,
/// measured across the contact line.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct EdgeCut {
    /// Distance d ≥ 0 of the contact point from the edge, m.
    pub distance_m: f64,
    /// Gap slope s ≥ 0 at the edge, inward, where the contact point is the
    /// edge itself (d = 0); 0 otherwise.
    pub slope: f64,
}

impl EdgeCut {
    /// The gap's slope at the edge for relative radius `rho`: s − d/ρ.
    pub fn slope_at_edge(&self, rho: f64) -> f64 {
        self.slope - self.distance_m / rho
    }
}

/// Line load (N/m) at which the uncut Hertz strip of an interior contact
/// point at distance d reaches the edge (b = d): π E* d² / (4ρ).
pub fn threshold_line_load(distance: f64, rho: f64, e_star: f64) -> f64 {
    PI * e_star * distance * distance / (4.0 * rho)
}

/// Contact length a (m) of the cut strip under line load `q` (N/m), gap
/// slope `s` at the edge: the positive root of
/// 3πE*/(16ρ) a² + πE* s/4 a − q = 0.
pub fn contact_length(q: f64, s: f64, rho: f64, e_star: f64) -> f64 {
    let alpha = 3.0 * PI * e_star / (16.0 * rho);
    let beta = PI * e_star * s / 4.0;
    let root = (beta * beta + 4.0 * alpha * q).sqrt();
    if beta >= 0.0 {
        2.0 * q / (beta + root)
    } else {
        (root - beta) / (2.0 * alpha)
    }
}

/// Pressure coefficients (A, B), Pa, of the cut strip of length `a`.
pub fn pressure_coefficients(a: f64, s: f64, rho: f64, e_star: f64) -> (f64, f64) {
    (
        0.5 * e_star * s + e_star * a / (2.0 * rho),
        -e_star * a / (4.0 * rho),
    )
}

/// Pressure (Pa) of the cut strip at X ∈ [−a, 0) (m, the edge at 0).
pub fn pressure(x: f64, a: f64, s: f64, rho: f64, e_star: f64) -> f64 {
    if !(x >= -a && x < 0.0) {
        return 0.0;
    }
    let (ca, cb) = pressure_coefficients(a, s, rho, e_star);
    let tau = 1.0 + 2.0 * x / a;
    (ca + cb * tau) * ((1.0 + tau) / (1.0 - tau)).sqrt()
}

/// Approach (m) of one body's surface at the contact point to its point at
/// depth `h` below it, under the cut strip carrying line load `q` (N/m).
/// `cut` places the contact point and the edge; the strip's length and
/// pressure follow from `q`, `rho` and `e_star` (module doc).
pub fn body_approach(q: f64, cut: EdgeCut, rho: f64, e_star: f64, h: f64, m: Material) -> f64 {
    if q <= 0.0 {
        return 0.0;
    }
    let s = cut.slope_at_edge(rho);
    let a = contact_length(q, s, rho, e_star);
    let (ca, cb) = pressure_coefficients(a, s, rho, e_star);
    // Contact point in τ (inside the strip: a ≥ 2d wherever the cut applies).
    let t0 = (1.0 - 2.0 * cut.distance_m / a).clamp(-1.0, 1.0);
    let l1 = PI * (ca * (-1.0 - LN_2) + cb * (-1.25 - 0.5 * LN_2));
    let l_t0 = l1 - PI * (ca * (t0 - 1.0) + cb * ((1.0 + t0).powi(2) - 4.0) / 2.0);
    let log_part = -2.0 * q * (0.5 * a).ln() - a * l_t0;
    // Smooth part: ∫ p [ln(h² + u²) − h²/((1 − ν)(u² + h²))] dX, midpoint
    // rule in θ with a fixed number of points (a count that changed with a
    // would make the approach jump by its quadrature error, and the
    // multibody table's interpolant with it): within 1e-10 for a ≤ h.
    let nu = m.poisson_ratio;
    let n = SMOOTH_POINTS;
    let mut smooth = 0.0;
    for &tau in smooth_nodes() {
        let u = 0.5 * a * (tau - t0);
        let r2 = h * h + u * u;
        smooth += (ca + cb * tau) * (1.0 + tau) * (r2.ln() - h * h / ((1.0 - nu) * r2));
    }
    smooth *= 0.5 * a * PI / n as f64;
    plane_strain_compliance(m) / PI * (smooth + log_part)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::weber_banaschek::{self as wb, contact_modulus, half_width};

    const STEEL: Material = Material::STEEL;

    fn e_star() -> f64 {
        contact_modulus(STEEL, STEEL)
    }

    #[test]
    fn cut_strip_touching_the_edge_is_the_hertz_strip() {
        // Interior contact point at d: at q = πE*d²/(4ρ) the strip is
        // [−2d, 0], its pressure Hertz's with b = d, and its approach the
        // uncut closed form (weber_banaschek::body_approach).
        let (rho, d, h) = (0.012, 0.15e-3, 3e-3);
        let q = threshold_line_load(d, rho, e_star());
        assert!((half_width(q, rho, e_star()) - d).abs() < 1e-12);
        let cut = EdgeCut {
            distance_m: d,
            slope: 0.0,
        };
        let a = contact_length(q, cut.slope_at_edge(rho), rho, e_star());
        assert!((a - 2.0 * d).abs() < 1e-12 * d, "{a}");
        let (ca, cb) = pressure_coefficients(a, cut.slope_at_edge(rho), rho, e_star());
        assert!((ca + cb).abs() < 1e-9 * ca);
        let p0 = e_star() * d / (2.0 * rho);
        let x = -0.6 * d;
        let hertz = p0 * (1.0 - ((x + d) / d).powi(2)).sqrt();
        let cut_p = pressure(x, a, cut.slope_at_edge(rho), rho, e_star());
        assert!((cut_p - hertz).abs() < 1e-9 * p0, "{cut_p} {hertz}");
        let w = body_approach(q, cut, rho, e_star(), h, STEEL);
        let w_hertz = wb::body_approach(q, d, h, STEEL);
        assert!((w / w_hertz - 1.0).abs() < 1e-6, "{w} vs {w_hertz}");
    }

    #[test]
    fn smooth_part_is_converged_where_the_strip_is_as_long_as_h() {
        // A strip as long as the reference depth (far beyond the tooth's
        // contacts): the 8-point rule against 4000 points.
        let (rho, s) = (0.01, 1e-3);
        let q = 2e6;
        let a = contact_length(q, s, rho, e_star());
        let cut = EdgeCut {
            distance_m: 0.0,
            slope: s,
        };
        let w8 = body_approach(q, cut, rho, e_star(), a, STEEL);
        // Reference: the smooth part by a fine rule here.
        let (ca, cb) = pressure_coefficients(a, s, rho, e_star());
        let h = a;
        let nu = STEEL.poisson_ratio;
        let n = 4000;
        let mut smooth = 0.0;
        for k in 0..n {
            let tau = ((k as f64 + 0.5) * PI / n as f64).cos();
            let u = 0.5 * a * (tau - 1.0);
            let r2 = h * h + u * u;
            smooth += (ca + cb * tau) * (1.0 + tau) * (r2.ln() - h * h / ((1.0 - nu) * r2));
        }
        smooth *= 0.5 * a * PI / n as f64;
        let l1 = PI * (ca * (-1.0 - LN_2) + cb * (-1.25 - 0.5 * LN_2));
        let w_fine =
            plane_strain_compliance(STEEL) / PI * (smooth - 2.0 * q * (0.5 * a).ln() - a * l1);
        assert!((w8 / w_fine - 1.0).abs() < 1e-10, "{w8} {w_fine}");
    }

    #[test]
    fn line_load_is_the_integral_of_the_pressure() {
        let (rho, s) = (0.01, 2e-3);
        let q = 4e5;
        let a = contact_length(q, s, rho, e_star());
        // Midpoint rule in θ (exact for the polynomial part).
        let n = 64;
        let mut sum = 0.0;
        for k in 0..n {
            let tau = ((k as f64 + 0.5) * PI / n as f64).cos();
            let x = 0.5 * a * (tau - 1.0);
            let w = ((1.0 + tau) / (1.0 - tau)).sqrt();
            // ∫ p dX = (a/2) ∫ p dτ, dτ = sin θ dθ.
            sum += pressure(x, a, s, rho, e_star()) / w * (1.0 + tau);
        }
        let integral = sum * 0.5 * a * PI / n as f64;
        assert!((integral / q - 1.0).abs() < 1e-12, "{integral} {q}");
    }

    /// Surface displacement kernel of a uniform pressure on [x₁, x₂] of a
    /// half-plane pair with contact modulus E*, up to a constant:
    /// −(2/(πE*)) ∫ ln|x − ξ| dξ.
    fn strip_log(x: f64, x1: f64, x2: f64) -> f64 {
        let f = |u: f64| if u == 0.0 { 0.0 } else { u * u.abs().ln() - u };
        -(f(x - x1) - f(x - x2))
    }

    /// ∫ over [x₁, x₂] of ln(1 + h²/u²) − h²/((1 − ν)(u² + h²)), u = ξ − x₀.
    fn strip_depth_kernel(x0: f64, x1: f64, x2: f64, h: f64, nu: f64) -> f64 {
        let f = |u: f64| {
            let l = if u == 0.0 {
                0.0
            } else {
                u * (1.0 + h * h / (u * u)).ln()
            };
            l + 2.0 * h * (u / h).atan() - h / (1.0 - nu) * (u / h).atan()
        };
        f(x2 - x0) - f(x1 - x0)
    }

    /// Independent discrete solution: piecewise-constant pressure panels on
    /// [−L, 0] of two half-planes, rigid approach δ at the edge, active set
    /// on p ≥ 0. Returns (line load, contact length, approach at x₀ of one
    /// steel body to depth h).
    fn panels(delta: f64, s: f64, rho: f64, x0: f64, h: f64) -> (f64, f64, f64) {
        // Panels graded towards the edge (spacing ∝ distance^½ there),
        // where the pressure is singular.
        let n = 400;
        let len = 1.0e-3;
        let edges: Vec<f64> = (0..=n)
            .map(|i| -len * (1.0 - i as f64 / n as f64).powi(2))
            .collect();
        let mid: Vec<f64> = (0..n).map(|i| 0.5 * (edges[i] + edges[i + 1])).collect();
        let gap = |x: f64| s * (-x) + x * x / (2.0 * rho);
        let coef = 2.0 / (PI * e_star());
        let g = nalgebra::DMatrix::from_fn(n, n, |i, j| {
            coef * strip_log(mid[i], edges[j], edges[j + 1])
        });
        // Unknowns: the active panels' pressures and the surface constant
        // c (the log kernel's displacement is defined up to one): at the
        // edge's panel the closure is δ − g.
        let mut active = vec![true; n];
        let mut p = vec![0.0; n];
        for _ in 0..200 {
            let idx: Vec<usize> = (0..n).filter(|&k| active[k]).collect();
            let m = idx.len();
            let mut a = nalgebra::DMatrix::zeros(m, m);
            let mut r = nalgebra::DVector::zeros(m);
            for (ii, &i) in idx.iter().enumerate() {
                for (jj, &j) in idx.iter().enumerate() {
                    a[(ii, jj)] = g[(i, j)];
                }
                r[ii] = delta - gap(mid[i]);
            }
            let x = a.lu().solve(&r).unwrap();
            p = vec![0.0; n];
            for (ii, &i) in idx.iter().enumerate() {
                p[i] = x[ii];
            }
            let neg: Vec<usize> = idx.iter().copied().filter(|&k| p[k] < 0.0).collect();
            if neg.is_empty() {
                break;
            }
            for k in neg {
                active[k] = false;
            }
        }
        let q: f64 = (0..n).map(|j| p[j] * (edges[j + 1] - edges[j])).sum();
        let first = (0..n).find(|&k| p[k] > 0.0).unwrap();
        let a = -edges[first];
        let nu = STEEL.poisson_ratio;
        let w: f64 = (0..n)
            .map(|j| p[j] * strip_depth_kernel(x0, edges[j], edges[j + 1], h, nu))
            .sum::<f64>()
            * plane_strain_compliance(STEEL)
            / PI;
        (q, a, w)
    }

    #[test]
    fn edge_contact_matches_a_discrete_half_plane_solution() {
        // The discrete model's load, contact length and approach against
        // the closed form at the same load: a boundary contact point
        // (slope 3e-3) and an interior one 0.1 mm from the edge, both loaded
        // past the threshold. Panels graded towards the edge resolve its
        // square-root singularity (measured: 0.3 % and 2e-6 in the approach).
        let (rho, h) = (0.01, 2e-3);
        for (s, d, delta) in [(3e-3, 0.0, 2.0e-6), (0.0, 0.1e-3, 5e-6)] {
            let x0 = -d;
            let s_edge = s - d / rho;
            let (q, a_num, w_num) = panels(delta, s_edge, rho, x0, h);
            let cut = EdgeCut {
                distance_m: d,
                slope: s,
            };
            let a = contact_length(q, s_edge, rho, e_star());
            let w = body_approach(q, cut, rho, e_star(), h, STEEL);
            assert!((a_num / a - 1.0).abs() < 0.01, "a {a_num} vs {a}");
            assert!((w_num / w - 1.0).abs() < 0.005, "w {w_num} vs {w}");
            assert!(q > threshold_line_load(d, rho, e_star()));
        }
    }

    #[test]
    fn edge_makes_the_contact_softer_than_the_uncut_strip() {
        // Beyond the threshold the cut strip is shorter than the Hertz
        // strip of the same load and its approach larger.
        let (rho, d, h) = (0.01, 0.05e-3, 3e-3);
        let cut = EdgeCut {
            distance_m: d,
            slope: 0.0,
        };
        let q0 = threshold_line_load(d, rho, e_star());
        let mut last = 0.0;
        for k in 1..8 {
            let q = q0 * (1.0 + k as f64);
            let b = half_width(q, rho, e_star());
            let w_cut = body_approach(q, cut, rho, e_star(), h, STEEL);
            let w_hertz = wb::body_approach(q, b, h, STEEL);
            assert!(w_cut > w_hertz, "q {q}: {w_cut} vs {w_hertz}");
            assert!(w_cut > last);
            last = w_cut;
        }
    }
}
