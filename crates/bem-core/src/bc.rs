//! Boundary conditions and prescribed values.

use glam::DVec3;
use std::borrow::Cow;

use crate::BemError;

/// Boundary condition of one element.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
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

/// What is prescribed on an element in every load case of a [`crate::LinearSystem`] (the
/// split of the unknowns; the values come from [`Loads`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub enum ElementKind {
    /// The traction is prescribed (zero unless a load case sets it): u is unknown.
    Traction,
    /// The displacement is prescribed: t is unknown.
    Displacement,
    /// Frictionless contact with a rigid support along the element's own normal n (tissue
    /// sliding on bone or teeth): the normal displacement `u·n` and the tangential traction
    /// are prescribed, the normal traction and the tangential displacement are unknown. A load
    /// value `v` on such an element prescribes `u·n = v·n` and the tangential traction
    /// `v − (v·n) n` (zero by default: it stays on its support and slides freely).
    Sliding,
}

impl ElementKind {
    /// The kinds of a displacement/traction mask (`true` = displacement prescribed).
    ///
    /// ```
    /// use bem_core::ElementKind;
    /// assert_eq!(
    ///     ElementKind::from_mask(&[true, false]),
    ///     vec![ElementKind::Displacement, ElementKind::Traction]
    /// );
    /// ```
    pub fn from_mask(prescribed: &[bool]) -> Vec<ElementKind> {
        prescribed
            .iter()
            .map(|&p| {
                if p {
                    ElementKind::Displacement
                } else {
                    ElementKind::Traction
                }
            })
            .collect()
    }
}

/// The boundary condition of every element, given as an [`ElementKind`] per element or as a
/// prescribed mask (`true`: displacement prescribed, `false`: traction): what
/// [`crate::LinearSystem::assemble`] and [`crate::ResponseBasis::compute`] take.
///
/// ```
/// use bem_core::{ElementKind, ElementKinds};
/// let mask = vec![true, false];
/// assert_eq!(*mask.kinds(), [ElementKind::Displacement, ElementKind::Traction]);
/// assert_eq!(mask.argument_name(), "prescribed mask");
/// ```
pub trait ElementKinds {
    /// The kind of every element.
    fn kinds(&self) -> Cow<'_, [ElementKind]>;
    /// How a length error names the argument.
    fn argument_name(&self) -> &'static str;
    /// The kind of every element of a mesh of `n` elements ([`BemError::WrongLength`] when
    /// there are not `n`).
    fn kinds_of(&self, n: usize) -> Result<Cow<'_, [ElementKind]>, BemError> {
        let kinds = self.kinds();
        if kinds.len() != n {
            return Err(BemError::WrongLength {
                what: self.argument_name(),
                expected: n,
                got: kinds.len(),
            });
        }
        Ok(kinds)
    }
}

impl ElementKinds for [ElementKind] {
    fn kinds(&self) -> Cow<'_, [ElementKind]> {
        Cow::Borrowed(self)
    }
    fn argument_name(&self) -> &'static str {
        "element kinds"
    }
}

impl ElementKinds for [bool] {
    fn kinds(&self) -> Cow<'_, [ElementKind]> {
        Cow::Owned(ElementKind::from_mask(self))
    }
    fn argument_name(&self) -> &'static str {
        "prescribed mask"
    }
}

impl<T> ElementKinds for Vec<T>
where
    [T]: ElementKinds,
{
    fn kinds(&self) -> Cow<'_, [ElementKind]> {
        self.as_slice().kinds()
    }
    fn argument_name(&self) -> &'static str {
        self.as_slice().argument_name()
    }
}

/// An orthonormal tangent pair `(t1, t2)` of unit normal `n` with `t1 × t2 = n`, chosen
/// deterministically (t1 ⟂ the coordinate axis least aligned with n).
///
/// ```
/// use glam::DVec3;
/// let n = DVec3::new(0.0, 0.6, 0.8);
/// let (t1, t2) = bem_core::tangent_frame(n);
/// assert!(t1.dot(n).abs() < 1e-12 && t2.dot(n).abs() < 1e-12 && t1.dot(t2).abs() < 1e-12);
/// assert!((t1.cross(t2) - n).length() < 1e-12);
/// ```
pub fn tangent_frame(n: DVec3) -> (DVec3, DVec3) {
    let a = n.abs();
    let axis = if a.x <= a.y && a.x <= a.z {
        DVec3::X
    } else if a.y <= a.z {
        DVec3::Y
    } else {
        DVec3::Z
    };
    let t1 = n.cross(axis).normalize_or_zero();
    let t2 = n.cross(t1);
    (t1, t2)
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
