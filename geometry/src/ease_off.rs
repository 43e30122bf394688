//! The designed flank modification of the pinion (ease-off), as a normal
//! deviation from the conjugate flank (positive = material removed):
//!
//! E = c_p (2η − 1)² + c_l (2ξ − 1)² + c_b (2ξ − 1)(2η − 1)
//!   + A (2 (φ − φ₀) / Δφ)² · λ₂ + T(η, ξ)
//!
//! with ξ, η the normalised face and profile coordinates, φ the pinion roll
//! angle at which the point is on the conjugate contact line (surface of roll
//! angles), φ₀ the vertex and Δφ = 2π/z₁ the mesh cycle, λ₂ = |n · (a₂ × r)|
//! the wheel's normal lever at the contact, A the parabolic motion error in
//! wheel radians, and T a measured or imported topography.

use crate::design::{EaseOffDesign, TopographyDesign};
use crate::machine::surface_fit::ChebyshevSurface;
use crate::Scalar;
use serde::Serialize;

/// Ease-off in SI units, ready to evaluate.
#[derive(Debug, Clone, Serialize)]
pub struct EaseOff {
    pub profile_crowning: f64,
    pub lengthwise_crowning: f64,
    pub bias: f64,
    /// Wheel-side motion error at ±half a mesh cycle from the vertex, rad.
    pub motion_error: f64,
    /// Pinion roll angle of the parabola's vertex, rad.
    pub roll_vertex: f64,
    /// Mesh cycle (pinion), rad.
    pub mesh_cycle: f64,
    pub topography: Option<Bicubic>,
    /// The relative deviation of the flanks the machine settings cut
    /// ([`crate::machine::deviation`]), µm, a smooth fit of its grid.
    pub settings: Option<ChebyshevSurface>,
}

impl EaseOff {
    pub fn new(d: &EaseOffDesign, roll_vertex: f64, mesh_cycle: f64) -> Self {
        EaseOff {
            profile_crowning: d.profile_crowning_um * 1e-6,
            lengthwise_crowning: d.lengthwise_crowning_um * 1e-6,
            bias: d.bias_um * 1e-6,
            motion_error: d.motion_error_urad * 1e-6,
            roll_vertex,
            mesh_cycle,
            topography: d.topography.as_ref().map(Bicubic::new),
            settings: None,
        }
    }

    /// With the machine settings' deviation added (its fitted surface).
    pub fn with_settings(mut self, t: Option<ChebyshevSurface>) -> Self {
        self.settings = t;
        self
    }

    /// Normal deviation at normalised (ξ, η), roll angle φ and wheel lever λ₂, m.
    pub fn value<D: Scalar>(&self, xi: D, eta: D, roll: D, lever: D) -> D {
        let x = xi * 2.0 - 1.0;
        let y = eta * 2.0 - 1.0;
        let r = (roll - self.roll_vertex) * (2.0 / self.mesh_cycle);
        let mut e = y * y * self.profile_crowning
            + x * x * self.lengthwise_crowning
            + x * y * self.bias
            + r * r * lever * self.motion_error;
        if let Some(t) = &self.topography {
            e += t.value(eta, xi) * 1e-6;
        }
        if let Some(t) = &self.settings {
            e += t.value(xi, eta) * 1e-6;
        }
        e
    }
}

/// Bicubic Hermite interpolation on a rectangular, non-uniform grid, with
/// finite-difference slopes (C¹); constant extrapolation of the slopes'
/// cubic beyond the grid.
#[derive(Debug, Clone, Serialize)]
pub struct Bicubic {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<Vec<f64>>,
}

fn slopes(x: &[f64], f: &[f64]) -> Vec<f64> {
    let n = x.len();
    (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            (f[b] - f[a]) / (x[b] - x[a])
        })
        .collect()
}

fn hermite<D: Scalar>(x0: f64, x1: f64, f0: D, f1: D, m0: D, m1: D, x: D) -> D {
    let h = x1 - x0;
    let t = (x - x0) / h;
    let t2 = t * t;
    let t3 = t2 * t;
    f0 * (t3 * 2.0 - t2 * 3.0 + 1.0)
        + m0 * ((t3 - t2 * 2.0 + t) * h)
        + f1 * (t2 * 3.0 - t3 * 2.0)
        + m1 * ((t3 - t2) * h)
}

fn cell(x: &[f64], v: f64) -> usize {
    let i = x.partition_point(|&a| a <= v);
    i.clamp(1, x.len() - 1) - 1
}

impl Bicubic {
    pub fn new(t: &TopographyDesign) -> Self {
        Bicubic {
            x: t.profile.clone(),
            y: t.face.clone(),
            z: t.deviation_um.clone(),
        }
    }

    /// Whether the grid can be interpolated: at least 2 nodes each way and
    /// one row of values per x node with one value per y node (what the
    /// design checks ensure for a loaded design).
    fn is_grid(&self) -> bool {
        self.x.len() >= 2
            && self.y.len() >= 2
            && self.z.len() == self.x.len()
            && self.z.iter().all(|r| r.len() == self.y.len())
    }

    /// Interpolates along y in every row, then along x; NaN (not a panic)
    /// for a grid that [`Bicubic::is_grid`] refuses.
    pub fn value<D: Scalar>(&self, x: D, y: D) -> D {
        if !self.is_grid() {
            return D::from(f64::NAN);
        }
        let j = cell(&self.y, y.re());
        let col: Vec<D> = self
            .z
            .iter()
            .map(|row| {
                let m = slopes(&self.y, row);
                hermite(
                    self.y[j],
                    self.y[j + 1],
                    D::from(row[j]),
                    D::from(row[j + 1]),
                    D::from(m[j]),
                    D::from(m[j + 1]),
                    y,
                )
            })
            .collect();
        let i = cell(&self.x, x.re());
        // Slopes along x from the interpolated column (finite differences).
        let n = self.x.len();
        let slope = |k: usize| {
            let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
            (col[b] - col[a]) / (self.x[b] - self.x[a])
        };
        hermite(
            self.x[i],
            self.x[i + 1],
            col[i],
            col[i + 1],
            slope(i),
            slope(i + 1),
            x,
        )
    }
}
