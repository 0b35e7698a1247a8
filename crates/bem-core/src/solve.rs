//! Solving mixed problems: parameters, solutions, the general `solve`.

use glam::DVec3;

use crate::budget::SOLVE_BLOCK;
use crate::{
    BemError, BoundaryCondition, Control, DenseLu, ElementKind, LinearSystem, Loads,
    MAX_MIXED_CONDITION, Material, MixedLu, QuadratureParams, RigidModes, Stage, SurfaceMesh,
    tangent_frame,
};

/// Default of [`SolveParams::max_condition`]: solves whose estimated condition number (columns
/// scaled to unit 1-norm, [`crate::DenseLu::condition_estimate`]) exceeds 1e8 are refused.
///
/// Measured: healthy problems 3e2 (two held spheres) to 8e3 (the bundled faces: MediaPipe 2.5e3,
/// ICT 2500 7.8e3, Lee Perry-Smith 6.3e3); a paper-thin face shell (MediaPipe at offset 0.0005,
/// responses 27× the muscles' motion) 8.9e5; ICT simulated with its rolled-in lids and lips
/// 4.9e4; a sphere that nothing holds next to a fixed one 1.5e9 (at 80 elements each; the
/// finer the mesh the more exactly singular). At κ = 1e8 the LU alone may cost 8 of 16 digits
/// and the discretisation error is amplified accordingly.
pub const DEFAULT_MAX_CONDITION: f64 = 1e8;

/// Parameters of a solve.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SolveParams {
    /// Quadrature of the off-diagonal blocks.
    pub quadrature: QuadratureParams,
    /// Pure-traction problems: reject (default) or fix the rigid modes.
    pub rigid_modes: RigidModes,
    /// Largest accepted condition estimate ([`crate::DenseLu::condition_estimate`]) of K; above
    /// it the solve fails with [`BemError::IllConditioned`]. Default [`DEFAULT_MAX_CONDITION`];
    /// `f64::INFINITY` accepts anything.
    pub max_condition: f64,
    /// Memory the assembly and solve may use, in bytes ([`crate::MemoryEstimate`]); above it
    /// [`LinearSystem::assemble`] fails with [`BemError::OverBudget`] before allocating K.
    /// `None` (default): the memory the operating system reports available (Linux
    /// `MemAvailable`; unchecked where unknown).
    pub memory_budget_bytes: Option<u64>,
    /// Precision of the LU ([`Precision::Mixed`] by default).
    pub precision: Precision,
}

/// Precision of the dense LU.
///
/// ```
/// assert_eq!(bem_core::SolveParams::default().precision, bem_core::Precision::Mixed);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum Precision {
    /// The LU in f32 with the answer refined to f64 accuracy ([`crate::MixedLu`]), falling
    /// back to [`Precision::Double`] where that does not converge or the f32 copy does not fit
    /// the memory budget: about half the factorisation time, 1.5 times K's memory.
    #[default]
    Mixed,
    /// The LU in f64, in place ([`crate::DenseLu`]).
    Double,
}

impl Default for SolveParams {
    fn default() -> Self {
        Self {
            quadrature: QuadratureParams::default(),
            rigid_modes: RigidModes::default(),
            max_condition: DEFAULT_MAX_CONDITION,
            memory_budget_bytes: None,
            precision: Precision::Mixed,
        }
    }
}

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
                    rhs = original;
                } else {
                    used = Precision::Mixed;
                    condition_estimate = estimate;
                }
            }
            matrix = lu.into_matrix();
        }
        if used == Precision::Double {
            let lu = DenseLu::factor_with(matrix, control)?;
            control.check()?;
            condition_estimate = lu.condition_estimate()?;
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
        } else {
            drop(matrix);
        }
        control.report(Stage::Solve, count, count);
        let n = kinds.len();
        let solutions = (0..count)
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
            .collect();
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
