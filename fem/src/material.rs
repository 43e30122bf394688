//! Isotropic linear-elastic material.

use crate::FemError;

/// Isotropic linear elasticity, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus E in Pa.
    pub youngs_modulus_pa: f64,
    /// Poisson's ratio ν.
    pub poisson_ratio: f64,
}

impl Material {
    /// Steel: E = 210 GPa, ν = 0.3.
    pub const STEEL: Material = Material {
        youngs_modulus_pa: 210e9,
        poisson_ratio: 0.3,
    };

    /// Checks E > 0 and −1 < ν < 0.5.
    pub fn validate(&self) -> Result<(), FemError> {
        if !(self.youngs_modulus_pa > 0.0 && self.youngs_modulus_pa.is_finite()) {
            return Err(FemError::Invalid {
                field: "youngs_modulus_pa",
                value: self.youngs_modulus_pa.to_string(),
                limit: "must be finite and > 0".into(),
            });
        }
        if !(self.poisson_ratio > -1.0 && self.poisson_ratio < 0.5) {
            return Err(FemError::Invalid {
                field: "poisson_ratio",
                value: self.poisson_ratio.to_string(),
                limit: "must lie in (-1, 0.5)".into(),
            });
        }
        Ok(())
    }

    /// Lamé constants (λ, μ): λ = Eν/((1+ν)(1−2ν)), μ = E/(2(1+ν)).
    pub fn lame(&self) -> (f64, f64) {
        let (e, nu) = (self.youngs_modulus_pa, self.poisson_ratio);
        (
            e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            e / (2.0 * (1.0 + nu)),
        )
    }

    /// Shear modulus G = μ.
    pub fn shear_modulus(&self) -> f64 {
        self.lame().1
    }
}
