//! Isotropic linear elastic material.

use crate::BemError;

/// Isotropic linear elastic material: Poisson ratio ν ∈ [0, 0.5) and shear modulus μ > 0.
///
/// Deserialisation validates too (an invalid ν or μ in a file is an error, not a bad material).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "RawMaterial")]
pub struct Material {
    poisson: f64,
    shear_modulus: f64,
}

impl Material {
    /// Validates and builds a material.
    ///
    /// ```
    /// let m = bem_core::Material::new(0.45, 1.0).unwrap();
    /// assert_eq!(m.poisson(), 0.45);
    /// assert!(bem_core::Material::new(0.5, 1.0).is_err());
    /// ```
    pub fn new(poisson: f64, shear_modulus: f64) -> Result<Self, BemError> {
        if !(poisson.is_finite() && (0.0..0.5).contains(&poisson)) {
            return Err(BemError::InvalidPoisson(poisson));
        }
        if !(shear_modulus.is_finite() && shear_modulus > 0.0) {
            return Err(BemError::InvalidShearModulus(shear_modulus));
        }
        Ok(Self {
            poisson,
            shear_modulus,
        })
    }

    /// Builds a material from Young's modulus E and Poisson ratio ν (μ = E / (2(1+ν))).
    pub fn from_young(young: f64, poisson: f64) -> Result<Self, BemError> {
        Self::new(poisson, young / (2.0 * (1.0 + poisson)))
    }

    /// Poisson ratio ν.
    pub fn poisson(&self) -> f64 {
        self.poisson
    }

    /// Shear modulus μ.
    pub fn shear_modulus(&self) -> f64 {
        self.shear_modulus
    }

    /// Lamé's first parameter λ = 2μν / (1 − 2ν).
    pub fn lambda(&self) -> f64 {
        2.0 * self.shear_modulus * self.poisson / (1.0 - 2.0 * self.poisson)
    }
}

/// Unvalidated serialised form of [`Material`].
#[derive(serde::Deserialize)]
struct RawMaterial {
    poisson: f64,
    shear_modulus: f64,
}

impl TryFrom<RawMaterial> for Material {
    type Error = BemError;

    fn try_from(raw: RawMaterial) -> Result<Self, BemError> {
        Self::new(raw.poisson, raw.shear_modulus)
    }
}
