//! Solving mixed problems: parameters, solutions, the general `solve`.

use glam::DVec3;

use crate::{
    BemError, BoundaryCondition, Control, DenseLu, LinearSystem, Loads, Material, QuadratureParams,
    RigidModes, Stage, SurfaceMesh,
};

/// Parameters of a solve.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct SolveParams {
    /// Quadrature of the off-diagonal blocks.
    pub quadrature: QuadratureParams,
    /// Pure-traction problems: reject (default) or fix the rigid modes.
    pub rigid_modes: RigidModes,
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
    pub fn solve(self, control: &Control<'_>) -> Result<Vec<Solution>, BemError> {
        let LinearSystem {
            matrix,
            mut rhs,
            prescribed,
            loads,
            ..
        } = self;
        control.check()?;
        let lu = DenseLu::factor_with(matrix, control)?;
        control.check()?;
        let count = rhs.ncols();
        control.report(Stage::Solve, 0, count);
        lu.solve_in_place(rhs.as_mut())?;
        drop(lu);
        control.report(Stage::Solve, count, count);
        let n = prescribed.len();
        Ok((0..count)
            .map(|r| {
                let mut displacement = Vec::with_capacity(n);
                let mut traction = Vec::with_capacity(n);
                for (e, &p) in prescribed.iter().enumerate() {
                    let x = DVec3::new(rhs[(3 * e, r)], rhs[(3 * e + 1, r)], rhs[(3 * e + 2, r)]);
                    let known = loads.get(e, r);
                    if p {
                        displacement.push(known);
                        traction.push(x);
                    } else {
                        displacement.push(x);
                        traction.push(known);
                    }
                }
                Solution {
                    displacement,
                    traction,
                }
            })
            .collect())
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
