//! Solving mixed problems: solutions, the solve of an assembled system, the general `solve`.

use faer::Mat;
use glam::DVec3;

use crate::assembly::LinearSystem;
use crate::budget::SOLVE_BLOCK;
use crate::params::Precision;
use crate::{
    BemError, BoundaryCondition, Control, DenseLu, DenseMatrix, ElementKind, Loads,
    MAX_MIXED_CONDITION, Material, MixedLu, SolveParams, Stage, SurfaceMesh, tangent_frame,
};

/// What the solver measured about the trustworthiness of its answer.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct SolveReport {
    /// Hager–Higham estimate of the 1-norm condition number of K with unit-1-norm columns
    /// ([`crate::DenseLu::condition_estimate`]).
    pub condition_estimate: f64,
    /// Quadrature accuracy of the assembly (unconverged blocks).
    pub quadrature: crate::AssemblyReport,
    /// The precision the LU ran in (a mixed solve that fell back reports `Double`).
    pub precision: Precision,
}

/// Displacement and traction on every element (at its centroid) for one load case.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Solution {
    /// Displacement per element.
    pub displacement: Vec<DVec3>,
    /// Traction per element.
    pub traction: Vec<DVec3>,
}

impl LinearSystem {
    /// Factorises K (consuming it) and solves all load cases together.
    ///
    /// Fails with [`BemError::IllConditioned`] when the condition estimate of K exceeds the
    /// limit the system was assembled with ([`SolveParams::max_condition`]).
    pub fn solve(self, control: &Control<'_>) -> Result<Vec<Solution>, BemError> {
        Ok(self.solve_with_report(control)?.0)
    }

    /// [`LinearSystem::solve`], also returning the condition estimate.
    pub fn solve_with_report(
        self,
        control: &Control<'_>,
    ) -> Result<(Vec<Solution>, SolveReport), BemError> {
        let LinearSystem {
            matrix,
            mut rhs,
            kinds,
            normals,
            loads,
            max_condition,
            quadrature,
            precision,
            ..
        } = self;
        control.check()?;
        let count = rhs.ncols();
        let mut matrix = matrix;
        let mut used = Precision::Double;
        let mut condition_estimate = f64::NAN;
        if precision == Precision::Mixed {
            let lu = MixedLu::factor_with(matrix, control)?;
            control.check()?;
            if let Some(estimate) = solve_mixed(&lu, &mut rhs, max_condition, control)? {
                used = Precision::Mixed;
                condition_estimate = estimate;
            }
            matrix = lu.into_matrix();
        }
        if used == Precision::Double {
            condition_estimate = solve_double(matrix, &mut rhs, max_condition, control)?;
        } else {
            drop(matrix);
        }
        control.report(Stage::Solve, count, count);
        let solutions = unpack_solutions(&rhs, &kinds, &normals, &loads);
        Ok((
            solutions,
            SolveReport {
                condition_estimate,
                quadrature,
                precision: used,
            },
        ))
    }
}

/// Solves all right-hand sides in place with the mixed-precision LU, block by block, when its
/// condition estimate is within both [`MAX_MIXED_CONDITION`] and `max_condition`: returns that
/// estimate, or `None` (with `rhs` unchanged) when the estimate is too large or the refinement
/// stalled, for the f64 LU to take over.
fn solve_mixed(
    lu: &MixedLu,
    rhs: &mut Mat<f64>,
    max_condition: f64,
    control: &Control<'_>,
) -> Result<Option<f64>, BemError> {
    let count = rhs.ncols();
    let estimate = if lu.is_usable() {
        lu.condition_estimate().unwrap_or(f64::INFINITY)
    } else {
        f64::INFINITY
    };
    if estimate <= MAX_MIXED_CONDITION && estimate <= max_condition {
        let original = rhs.clone();
        control.report(Stage::Solve, 0, count);
        let mut start = 0;
        let mut stalled = false;
        while start < count {
            let width = SOLVE_BLOCK.min(count - start);
            match lu.solve_in_place(rhs.as_mut().subcols_mut(start, width)) {
                Ok(_) => {}
                Err(BemError::RefinementStalled { .. }) => {
                    stalled = true;
                    break;
                }
                Err(e) => return Err(e),
            }
            start += width;
            control.report(Stage::Solve, start, count);
        }
        if stalled {
            *rhs = original;
            Ok(None)
        } else {
            Ok(Some(estimate))
        }
    } else {
        Ok(None)
    }
}

/// Factorises K in f64 and solves all right-hand sides in place, in blocks; fails with
/// [`BemError::IllConditioned`] above `max_condition`. Returns the condition estimate.
fn solve_double(
    matrix: DenseMatrix,
    rhs: &mut Mat<f64>,
    max_condition: f64,
    control: &Control<'_>,
) -> Result<f64, BemError> {
    let count = rhs.ncols();
    let lu = DenseLu::factor_with(matrix, control)?;
    control.check()?;
    let condition_estimate = lu.condition_estimate()?;
    if condition_estimate.is_nan() || condition_estimate > max_condition {
        return Err(BemError::IllConditioned {
            estimate: condition_estimate,
            limit: max_condition,
        });
    }
    control.report(Stage::Solve, 0, count);
    // in blocks of right-hand sides: the solve's scratch copy stays one block
    let mut start = 0;
    while start < count {
        let width = SOLVE_BLOCK.min(count - start);
        lu.solve_in_place(rhs.as_mut().subcols_mut(start, width))?;
        start += width;
        control.report(Stage::Solve, start, count);
    }
    Ok(condition_estimate)
}

/// Displacement and traction of every element for each load case, from the solved unknowns
/// (`rhs`, one column per load case) and the prescribed values.
fn unpack_solutions(
    rhs: &Mat<f64>,
    kinds: &[ElementKind],
    normals: &[DVec3],
    loads: &Loads,
) -> Vec<Solution> {
    let n = kinds.len();
    (0..rhs.ncols())
        .map(|r| {
            let mut displacement = Vec::with_capacity(n);
            let mut traction = Vec::with_capacity(n);
            for (e, &kind) in kinds.iter().enumerate() {
                let x = DVec3::new(rhs[(3 * e, r)], rhs[(3 * e + 1, r)], rhs[(3 * e + 2, r)]);
                let known = loads.get(e, r);
                match kind {
                    ElementKind::Displacement => {
                        displacement.push(known);
                        traction.push(x);
                    }
                    ElementKind::Traction => {
                        displacement.push(x);
                        traction.push(known);
                    }
                    ElementKind::Sliding => {
                        let normal = normals[e];
                        let (t1, t2) = tangent_frame(normal);
                        let un = normal * known.dot(normal);
                        displacement.push(un + t1 * x.y + t2 * x.z);
                        traction.push(normal * x.x + (known - un));
                    }
                }
            }
            Solution {
                displacement,
                traction,
            }
        })
        .collect()
}

/// Solves one mixed problem with a boundary condition per element.
///
/// ```
/// use bem_core::{shapes, solve, BoundaryCondition, Control, Material, SolveParams};
/// use glam::DVec3;
/// // solid sphere, rigid translation prescribed everywhere: tractions vanish
/// let mesh = shapes::sphere(1, 1.0).unwrap();
/// let bcs = vec![BoundaryCondition::Displacement(DVec3::X); mesh.element_count()];
/// let m = Material::new(0.3, 1.0).unwrap();
/// let s = solve(&mesh, &m, &bcs, &SolveParams::default(), &Control::default()).unwrap();
/// assert!(s.traction.iter().all(|t| t.length() < 1e-10));
/// ```
pub fn solve(
    mesh: &SurfaceMesh,
    material: &Material,
    bcs: &[BoundaryCondition],
    params: &SolveParams,
    control: &Control<'_>,
) -> Result<Solution, BemError> {
    let n = mesh.element_count();
    if bcs.len() != n {
        return Err(BemError::WrongLength {
            what: "boundary conditions",
            expected: n,
            got: bcs.len(),
        });
    }
    let prescribed: Vec<bool> = bcs.iter().map(|b| b.is_displacement()).collect();
    let mut loads = Loads::new(n, 1);
    for (e, bc) in bcs.iter().enumerate() {
        loads.set(e, 0, bc.value())?;
    }
    let system = LinearSystem::assemble(mesh, material, &prescribed, &loads, params, control)?;
    system.solve(control)?.pop().ok_or(BemError::Internal {
        what: "one load case solved but no solution returned",
    })
}
