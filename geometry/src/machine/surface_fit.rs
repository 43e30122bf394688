//! A smooth surface through a cut flank's deviation grid: a tensor product
//! of Chebyshev polynomials fitted by least squares.
//!
//! The contact's second order (transmission error parabola, path direction,
//! contact ellipse) reads the ease-off's second derivatives. A bicubic
//! Hermite patch with difference slopes (the imported topography's
//! interpolant, [`crate::ease_off::Bicubic`]) has second derivatives that
//! jump at every node; the deviation the machine settings cut is smooth
//! (analytic in the flank coordinates), so it is represented as
//!
//!   f(ξ, η) = Σᵢ Σⱼ cᵢⱼ Tᵢ(2η − 1) Tⱼ(2ξ − 1),   i, j ≤ [`DEGREE`],
//!
//! the cᵢⱼ minimizing Σ (f − f_node)² over the grid (the tensor grid's
//! least squares separate: C = A_η⁺ F A_ξ⁺ᵀ). Outside the unit
//! square it continues along its tangent plane at the nearest point of the
//! square (C¹), so that a polynomial is never extrapolated far.

use crate::Scalar;
use nalgebra::DMatrix;
use serde::Serialize;

/// Polynomial degree in each of ξ and η.
pub const DEGREE: usize = 8;

/// The fitted surface.
#[derive(Debug, Clone, Serialize)]
pub struct ChebyshevSurface {
    /// `c[i * (DEGREE + 1) + j]` multiplies Tᵢ(2η − 1) Tⱼ(2ξ − 1).
    c: Vec<f64>,
}

/// T₀ … T_DEGREE at `x`.
fn chebyshev<D: Scalar>(x: D) -> [D; DEGREE + 1] {
    let mut t = [D::one(); DEGREE + 1];
    t[1] = x;
    for k in 2..=DEGREE {
        t[k] = x * t[k - 1] * 2.0 - t[k - 2];
    }
    t
}

impl ChebyshevSurface {
    /// Fits values `f[i][j]` at (`profile[i]`, `face[j]`); returns the surface
    /// and its largest residual at the nodes. None where the grid has too
    /// few nodes for the degree.
    pub fn fit(profile: &[f64], face: &[f64], f: &[Vec<f64>]) -> Option<(Self, f64)> {
        let n = DEGREE + 1;
        if profile.len() < n || face.len() < n {
            return None;
        }
        // On a tensor grid the design matrix is A_η ⊗ A_ξ, whose
        // pseudo-inverse is A_η⁺ ⊗ A_ξ⁺: C = A_η⁺ F A_ξ⁺ᵀ.
        let basis = |x: &[f64]| DMatrix::from_fn(x.len(), n, |i, k| chebyshev(2.0 * x[i] - 1.0)[k]);
        let (ae, ax) = (basis(profile), basis(face));
        let values = DMatrix::from_fn(profile.len(), face.len(), |i, j| f[i][j]);
        let pe = ae.clone().pseudo_inverse(1e-14).ok()?;
        let px = ax.clone().pseudo_inverse(1e-14).ok()?;
        let c = &pe * &values * px.transpose();
        let residual = (&ae * &c * ax.transpose() - values).amax();
        Some((
            ChebyshevSurface {
                c: c.transpose().iter().copied().collect(),
            },
            residual,
        ))
    }

    /// The polynomial at (ξ, η).
    fn polynomial<D: Scalar>(&self, xi: D, eta: D) -> D {
        let n = DEGREE + 1;
        let te = chebyshev(eta * 2.0 - 1.0);
        let tx = chebyshev(xi * 2.0 - 1.0);
        let mut v = D::zero();
        for (tp, coefficients) in te.iter().zip(self.c.chunks_exact(n)) {
            let mut row = D::zero();
            for (tq, c) in tx.iter().zip(coefficients) {
                row += *tq * *c;
            }
            v += *tp * row;
        }
        v
    }

    /// The surface at (ξ, η): the polynomial inside the unit square, its
    /// tangent plane at the nearest point of the square outside.
    pub fn value<D: Scalar>(&self, xi: D, eta: D) -> D {
        let (x, y) = (xi.re(), eta.re());
        let (cx, cy) = (x.clamp(0.0, 1.0), y.clamp(0.0, 1.0));
        if cx == x && cy == y {
            return self.polynomial(xi, eta);
        }
        let h = 1e-6;
        let p = |a: f64, b: f64| self.polynomial(a, b);
        let dx = (p((cx + h).min(1.0), cy) - p((cx - h).max(0.0), cy))
            / ((cx + h).min(1.0) - (cx - h).max(0.0));
        let dy = (p(cx, (cy + h).min(1.0)) - p(cx, (cy - h).max(0.0)))
            / ((cy + h).min(1.0) - (cy - h).max(0.0));
        (xi - cx) * dx + (eta - cy) * dy + p(cx, cy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_polynomial_of_the_fits_degree_is_reproduced_with_its_curvatures() {
        let f = |x: f64, y: f64| 3.0 + x * x * y - 2.0 * y.powi(5) + x.powi(8) * 0.5;
        let profile: Vec<f64> = (0..15).map(|i| i as f64 / 14.0).collect();
        let face: Vec<f64> = (0..17).map(|j| j as f64 / 16.0).collect();
        let grid: Vec<Vec<f64>> = profile
            .iter()
            .map(|&y| face.iter().map(|&x| f(x, y)).collect())
            .collect();
        let (s, residual) = ChebyshevSurface::fit(&profile, &face, &grid).unwrap();
        assert!(residual < 1e-10, "{residual}");
        // Between nodes, with second derivatives by dual numbers.
        use num_dual::{second_derivative, Dual2};
        let (x0, y0) = (0.37, 0.61);
        let (v, _, fxx) = second_derivative(|x: Dual2<f64>| s.value(x, Dual2::from(y0)), x0);
        assert!((v - f(x0, y0)).abs() < 1e-10);
        let exact = 2.0 * y0 + 28.0 * x0.powi(6);
        assert!((fxx - exact).abs() < 1e-7, "{fxx} {exact}");
        // Outside: the tangent plane at the edge.
        let out = s.value(1.05, 0.5);
        let slope = 2.0 * 0.5 + 4.0;
        assert!((out - (f(1.0, 0.5) + 0.05 * slope)).abs() < 1e-6, "{out}");
    }
}
