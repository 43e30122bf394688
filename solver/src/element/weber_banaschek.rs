//! Weber–Banaschek approach of a line contact: the local (near-contact)
//! flattening of two elastic bodies, measured from their surfaces down to a
//! reference depth h in each body.
//!
//! Plane strain, Hertz pressure p(x) = p₀ √(1 − x²/b²) over a strip of half
//! width b on a half-plane. On the load axis the stresses are
//! σ_z = −p₀ b / √(b² + z²) and σ_x = −(p₀/b) [(b² + 2z²)/√(b² + z²) − 2z]
//! (Johnson, Contact Mechanics, §2.8), and the surface centre approaches the
//! point at depth h by w = −∫₀ʰ ε_z dz, ε_z = (1 − ν²)/E · [σ_z − ν/(1 − ν) σ_x]:
//!
//!   w(h) = 2q(1 − ν²)/(πE) · [asinh(h/b) − ν/(1 − ν) · (h√(h² + b²) − h²)/b²]
//!
//! with q = π p₀ b / 2 the line load. For h ≫ b this is the Weber–Banaschek
//! formula 2q(1 − ν²)/(πE) · [ln(2h/b) − ν/(2(1 − ν))]; unlike that formula it
//! stays positive and finite when b approaches or exceeds h. Two bodies add:
//! w = w₁(h₁) + w₂(h₂), with b = √(4qρ/(πE*)), 1/E* = Σ (1 − νᵢ²)/Eᵢ and ρ the
//! relative radius of curvature across the contact line.

use crate::element::edge_cut::{self, EdgeCut};
use geometry::Material;

/// Plane-strain compliance (1 − ν²)/E of a body, 1/Pa.
pub fn plane_strain_compliance(m: Material) -> f64 {
    (1.0 - m.poisson_ratio.powi(2)) / m.youngs_modulus_pa
}

/// Contact modulus E* of two bodies: 1/E* = Σ (1 − νᵢ²)/Eᵢ.
pub fn contact_modulus(a: Material, b: Material) -> f64 {
    1.0 / (plane_strain_compliance(a) + plane_strain_compliance(b))
}

/// Hertz half-width of a line contact: b = √(4 q ρ / (π E*)).
pub fn half_width(q: f64, rho: f64, e_star: f64) -> f64 {
    (4.0 * q * rho / (std::f64::consts::PI * e_star)).sqrt()
}

/// Approach (m) of one body's surface to depth `h` under line load `q` (N/m)
/// with Hertz half-width `b`: the exact half-plane form of the module doc,
/// with x = h/b, asinh x = ln s and (h√(h² + b²) − h²)/b² = x/s for
/// s = x + √(1 + x²) (no cancellation for x ≥ 0, → 1/2 for large x).
///
/// Deep below a narrow contact (h ≫ b) it is the classical
/// Weber–Banaschek formula [`body_approach_log`]:
///
/// ```
/// use geometry::Material;
/// use solver::element::weber_banaschek::{body_approach, body_approach_log};
/// let (q, b, h) = (500e3, 0.2e-3, 0.2); // 500 N/mm, b = 0.2 mm, h = 200 mm
/// let exact = body_approach(q, b, h, Material::STEEL);
/// let classical = body_approach_log(q, b, h, Material::STEEL);
/// assert!((exact / classical - 1.0).abs() < 1e-6);
/// ```
pub fn body_approach(q: f64, b: f64, h: f64, m: Material) -> f64 {
    if q <= 0.0 {
        return 0.0;
    }
    let nu = m.poisson_ratio;
    let x = h / b;
    let s = (1.0 + x * x).sqrt() + x;
    2.0 * q * plane_strain_compliance(m) / std::f64::consts::PI
        * (s.ln() - nu / (1.0 - nu) * (x / s))
}

/// The classical Weber–Banaschek formula for one body (valid for h ≫ b):
/// 2q(1 − ν²)/(πE) · [ln(2h/b) − ν/(2(1 − ν))].
pub fn body_approach_log(q: f64, b: f64, h: f64, m: Material) -> f64 {
    let nu = m.poisson_ratio;
    2.0 * q * plane_strain_compliance(m) / std::f64::consts::PI
        * ((2.0 * h / b).ln() - nu / (2.0 * (1.0 - nu)))
}

/// A line-contact slice: relative radius of curvature, length, the two
/// bodies' reference depths and materials, and the tip edge near it if any.
#[derive(Debug, Clone, Copy)]
pub struct LineContact {
    /// Relative radius of curvature across the contact line, m.
    pub rho: f64,
    /// Slice length along the contact line, m.
    pub length: f64,
    pub h: [f64; 2],
    pub bodies: [Material; 2],
    /// The tip edge that can cut this slice's strip
    /// ([`crate::element::edge_cut`]); None far from any.
    pub edge: Option<EdgeCut>,
}

impl LineContact {
    /// Approach (m) of the two bodies under the slice force `f` (N):
    /// w₁(h₁) + w₂(h₂) at q = f/length, of the Hertz strip or, where the
    /// strip reaches a tip edge (the contact point on the edge, or the
    /// half-width b past the distance to it), of the cut strip.
    pub fn approach(&self, f: f64) -> f64 {
        if f <= 0.0 {
            return 0.0;
        }
        let q = f / self.length;
        let e_star = contact_modulus(self.bodies[0], self.bodies[1]);
        let b = half_width(q, self.rho, e_star);
        match self.edge {
            Some(cut) if cut.distance_m == 0.0 || b > cut.distance_m => (0..2)
                .map(|i| {
                    edge_cut::body_approach(q, cut, self.rho, e_star, self.h[i], self.bodies[i])
                })
                .sum(),
            _ => {
                body_approach(q, b, self.h[0], self.bodies[0])
                    + body_approach(q, b, self.h[1], self.bodies[1])
            }
        }
    }

    /// Secant compliance w(f)/f, m/N (finite for f > 0, growing like −ln f as f → 0).
    pub fn secant(&self, f: f64) -> f64 {
        self.approach(f) / f
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const STEEL: Material = Material::STEEL;

    #[test]
    fn deep_reference_point_gives_the_weber_banaschek_logarithm() {
        let (q, b) = (3e5, 1e-4);
        for h in [1e-2, 3e-2] {
            let exact = body_approach(q, b, h, STEEL);
            let log = body_approach_log(q, b, h, STEEL);
            // Next term of the expansion: O((b/h)²).
            assert!(
                ((exact - log) / log).abs() < 2.0 * (b / h).powi(2),
                "{exact} {log}"
            );
        }
    }

    #[test]
    fn approach_matches_numerical_integration_of_the_axis_strain() {
        // Independent check of the closed form: integrate ε_z of the Hertz
        // stresses along the axis by Simpson's rule.
        let (p0, b, h) = (1.2e9, 2e-4, 1.5e-4);
        let nu = STEEL.poisson_ratio;
        let strain = |z: f64| {
            let r = (b * b + z * z).sqrt();
            let sz = -p0 * b / r;
            let sx = -(p0 / b) * ((b * b + 2.0 * z * z) / r - 2.0 * z);
            plane_strain_compliance(STEEL) * (sz - nu / (1.0 - nu) * sx)
        };
        let n = 2000;
        let dz = h / n as f64;
        let mut integral = strain(0.0) + strain(h);
        for i in 1..n {
            integral += if i % 2 == 1 { 4.0 } else { 2.0 } * strain(i as f64 * dz);
        }
        let w_num = -integral * dz / 3.0;
        let q = std::f64::consts::PI * p0 * b / 2.0;
        let w = body_approach(q, b, h, STEEL);
        assert!(((w - w_num) / w_num).abs() < 1e-9, "{w} vs {w_num}");
    }

    #[test]
    fn approach_stays_positive_and_monotone_when_the_contact_is_wider_than_h() {
        let c = LineContact {
            rho: 0.02,
            length: 1e-3,
            h: [1e-4, 1e-4],
            bodies: [STEEL, STEEL],
            edge: None,
        };
        let mut last = 0.0;
        for k in 0..60 {
            let f = 1e-3 * 1.5f64.powi(k);
            let w = c.approach(f);
            assert!(w > last && w.is_finite(), "f = {f}: w = {w}");
            last = w;
        }
    }

    #[test]
    fn a_slice_near_a_tip_edge_is_hertz_until_its_strip_reaches_the_edge_then_cut() {
        // Interior contact point 0.1 mm from the edge: below the force at
        // which b = d the uncut approach, above it the cut strip's, and the
        // two meet there (the cut law starts from the Hertz strip).
        let d = 0.1e-3;
        let uncut = LineContact {
            rho: 0.01,
            length: 2e-3,
            h: [3e-3, 4e-3],
            bodies: [STEEL, STEEL],
            edge: None,
        };
        let cut = LineContact {
            edge: Some(EdgeCut {
                distance_m: d,
                slope: 0.0,
            }),
            ..uncut
        };
        let e_star = contact_modulus(STEEL, STEEL);
        let f0 = edge_cut::threshold_line_load(d, uncut.rho, e_star) * uncut.length;
        assert_eq!(cut.approach(0.9 * f0), uncut.approach(0.9 * f0));
        let (below, above) = (
            cut.approach(f0 * (1.0 - 1e-9)),
            cut.approach(f0 * (1.0 + 1e-9)),
        );
        assert!((above / below - 1.0).abs() < 1e-6, "{below} {above}");
        assert!(cut.approach(2.0 * f0) > uncut.approach(2.0 * f0));
    }

    #[test]
    fn different_materials_add_per_body() {
        let bronze = Material {
            youngs_modulus_pa: 110e9,
            poisson_ratio: 0.34,
        };
        let c = LineContact {
            rho: 0.015,
            length: 2e-3,
            h: [3e-3, 4e-3],
            bodies: [STEEL, bronze],
            edge: None,
        };
        let f = 500.0;
        let q = f / c.length;
        let b = half_width(q, c.rho, contact_modulus(STEEL, bronze));
        let expected = body_approach_log(q, b, 3e-3, STEEL) + body_approach_log(q, b, 4e-3, bronze);
        assert!(((c.approach(f) - expected) / expected).abs() < 1e-3);
        // Same material: the issue's two-body formula.
        let s = LineContact {
            bodies: [STEEL, STEEL],
            ..c
        };
        let b = half_width(q, c.rho, contact_modulus(STEEL, STEEL));
        let nu = STEEL.poisson_ratio;
        let wb = 2.0 * q * plane_strain_compliance(STEEL) / std::f64::consts::PI
            * ((2.0 * 3e-3 / b).ln() + (2.0 * 4e-3 / b).ln() - nu / (1.0 - nu));
        assert!(((s.approach(f) - wb) / wb).abs() < 1e-3);
    }
}
