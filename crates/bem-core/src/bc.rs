//! Boundary conditions and prescribed values.

use glam::DVec3;

use crate::BemError;

/// Boundary condition of one element.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum BoundaryCondition {
    /// Prescribed displacement (the traction is unknown).
    Displacement(DVec3),
    /// Prescribed traction (the displacement is unknown); `Traction(DVec3::ZERO)` is a free surface.
    Traction(DVec3),
}

impl BoundaryCondition {
    /// Traction-free surface.
    pub const FREE: Self = Self::Traction(DVec3::ZERO);

    /// Whether the displacement is prescribed.
    pub fn is_displacement(&self) -> bool {
        matches!(self, Self::Displacement(_))
    }

    /// The prescribed value (displacement or traction).
    pub fn value(&self) -> DVec3 {
        match *self {
            Self::Displacement(v) | Self::Traction(v) => v,
        }
    }
}

/// Prescribed values for several right-hand sides, stored sparsely per element: the displacement
/// of a displacement-prescribed element or the traction of a traction-prescribed one. Values not
/// set are zero.
#[derive(Debug, Clone, PartialEq)]
pub struct Loads {
    per_element: Vec<Vec<(u32, DVec3)>>,
    rhs_count: usize,
}

impl Loads {
    /// All-zero loads for `element_count` elements and `rhs_count` right-hand sides.
    pub fn new(element_count: usize, rhs_count: usize) -> Self {
        Self {
            per_element: vec![Vec::new(); element_count],
            rhs_count,
        }
    }

    /// Number of right-hand sides.
    pub fn rhs_count(&self) -> usize {
        self.rhs_count
    }

    /// Number of elements.
    pub fn element_count(&self) -> usize {
        self.per_element.len()
    }

    /// Sets the value of `element` in right-hand side `rhs` (replacing any previous value).
    pub fn set(&mut self, element: usize, rhs: usize, value: DVec3) -> Result<(), BemError> {
        if rhs >= self.rhs_count {
            return Err(BemError::WrongLength {
                what: "right-hand side index",
                expected: self.rhs_count,
                got: rhs + 1,
            });
        }
        if !value.is_finite() {
            return Err(BemError::NonFiniteValue { element });
        }
        let Some(list) = self.per_element.get_mut(element) else {
            return Err(BemError::WrongLength {
                what: "element index in loads",
                expected: self.per_element.len(),
                got: element + 1,
            });
        };
        list.retain(|(r, _)| *r as usize != rhs);
        if value != DVec3::ZERO {
            list.push((rhs as u32, value));
        }
        Ok(())
    }

    /// Value of `element` in right-hand side `rhs` (zero when unset).
    pub fn get(&self, element: usize, rhs: usize) -> DVec3 {
        self.per_element
            .get(element)
            .and_then(|l| l.iter().find(|(r, _)| *r as usize == rhs))
            .map_or(DVec3::ZERO, |(_, v)| *v)
    }

    /// Non-zero values of one element.
    pub(crate) fn of(&self, element: usize) -> &[(u32, DVec3)] {
        &self.per_element[element]
    }
}
