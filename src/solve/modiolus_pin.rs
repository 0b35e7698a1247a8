//! The modiolus pins ([`face_prep::modiolus`]) in the one-LU solve.
//!
//! The modiolus elements stay traction-type in the shared system, so every other response
//! leaves them free. For each side, three extra load cases per modiolus element (a unit
//! traction along x, y and z on that element alone) give the responses `Z`; a pinned muscle's
//! response is the combination `Σ c Z` whose modiolus elements move exactly by the pin's
//! displacement: `M c = d` with `M` the modiolus elements' displacements in those responses
//! (3m × 3m for m elements, solved by LU). This is the Schur complement of switching the
//! modiolus elements to displacement-prescribed in that response alone, at the cost of 3m
//! right-hand sides per side (about 150 on the bundled faces) instead of a second LU.

use bem_core::faer::Mat;
use bem_core::{DenseLu, DisplacementGroup, ElementKind};
use face_prep::{FaceRig, Side};
use glam::DVec3;

use super::SolveError;

/// The unit axes each modiolus element is loaded along, in load-case order.
const AXES: [DVec3; 3] = [DVec3::X, DVec3::Y, DVec3::Z];

/// One side's modiolus: its traction-type elements and where its unit load cases start.
struct SideCases {
    side: Side,
    elements: Vec<usize>,
    first_case: usize,
}

/// The extra load cases of both modioli and the controls pinned to them.
pub(crate) struct ModiolusCases {
    sides: Vec<SideCases>,
    /// Per control: its pin (side and displacement at slider = +1), if any.
    pins: Vec<Option<face_prep::modiolus::ModiolusPin>>,
    /// Load cases before the modiolus ones (one per control).
    first_case: usize,
}

impl ModiolusCases {
    /// Plans the modiolus load cases after `first_case` existing ones. Modiolus elements that
    /// are not traction-type in `kinds` (none on the bundled faces) are left out; a side with
    /// no element left pins nothing, its muscles stay force-scaled.
    pub(crate) fn plan(rig: &FaceRig, kinds: &[ElementKind], first_case: usize) -> Self {
        let pins: Vec<_> = (0..rig.muscles.len())
            .map(|k| rig.modiolus_pin(k))
            .collect();
        let mut sides = Vec::new();
        let mut next = first_case;
        for side in [Side::Left, Side::Right] {
            if !pins.iter().flatten().any(|p| p.side == side) {
                continue;
            }
            let elements: Vec<usize> = rig
                .modiolus_elements(side)
                .into_iter()
                .map(|e| e as usize)
                .filter(|&e| kinds.get(e) == Some(&ElementKind::Traction))
                .collect();
            if elements.is_empty() {
                continue;
            }
            let count = AXES.len() * elements.len();
            sides.push(SideCases {
                side,
                elements,
                first_case: next,
            });
            next += count;
        }
        let pins = pins
            .into_iter()
            .map(|p| p.filter(|p| sides.iter().any(|s| s.side == p.side)))
            .collect();
        ModiolusCases {
            sides,
            pins,
            first_case,
        }
    }

    /// Whether control `k`'s response is pinned (its own load case can stay empty).
    pub(crate) fn is_pinned(&self, k: usize) -> bool {
        self.pins.get(k).is_some_and(Option::is_some)
    }

    /// The unit-traction load cases, in the planned order.
    pub(crate) fn load_cases(&self) -> Vec<DisplacementGroup> {
        self.sides
            .iter()
            .flat_map(|s| {
                s.elements
                    .iter()
                    .flat_map(|&e| AXES.iter().map(move |&axis| vec![(e, axis)]))
            })
            .collect()
    }

    /// Replaces each pinned control's response in `element` (one displacement field per load
    /// case, the modiolus cases included) by its pinned combination, then drops the modiolus
    /// cases.
    pub(crate) fn apply(&self, element: &mut Vec<Vec<DVec3>>) -> Result<(), SolveError> {
        for side in &self.sides {
            let m = AXES.len() * side.elements.len();
            let Some(unit) = element.get(side.first_case..side.first_case + m) else {
                return Err(SolveError::Bem(bem_core::BemError::Internal {
                    what: "the modiolus load cases are missing from the solve",
                }));
            };
            // M[(i, a), (j, b)]: element i's displacement along axis a under unit load j, b.
            let matrix = Mat::<f64>::from_fn(m, m, |row, col| {
                let e = side.elements[row / 3];
                unit[col].get(e).map_or(0.0, |u| u.dot(AXES[row % 3]))
            });
            let lu = DenseLu::factor(matrix)?;
            // Never empty: a side is planned only when a control pins it.
            let pinned: Vec<usize> = (0..self.pins.len())
                .filter(|&k| self.pins[k].is_some_and(|p| p.side == side.side))
                .collect();
            let mut rhs = Mat::<f64>::from_fn(m, pinned.len(), |row, col| {
                let d = self.pins[pinned[col]].map_or(DVec3::ZERO, |p| p.displacement);
                d.dot(AXES[row % 3])
            });
            lu.solve_in_place(rhs.as_mut())?;
            let len = unit.first().map_or(0, Vec::len);
            let fields: Vec<Vec<DVec3>> = (0..pinned.len())
                .map(|col| {
                    let mut field = vec![DVec3::ZERO; len];
                    for (j, z) in unit.iter().enumerate() {
                        let c = rhs[(j, col)];
                        for (u, zu) in field.iter_mut().zip(z) {
                            *u += *zu * c;
                        }
                    }
                    field
                })
                .collect();
            for (k, field) in pinned.into_iter().zip(fields) {
                element[k] = field;
            }
        }
        element.truncate(self.first_case);
        Ok(())
    }
}
