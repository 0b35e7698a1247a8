//! Near-singular systems are refused, not solved: bodies that nothing holds, and matrices whose
//! condition estimate is above the limit.

use bem_core::{
    BemError, BoundaryCondition, Control, DEFAULT_MAX_CONDITION, DenseMatrix, LinearSystem, Loads,
    Material, QuadratureParams, SolveParams, SurfaceMesh, assemble_h_g, shapes, solve,
};
use glam::DVec3;

/// Two unit spheres (80 elements each), the second 3 units along x: elements 0..80 and 80..160.
fn two_spheres() -> SurfaceMesh {
    let (va, ta) = shapes::icosphere(1, 1.0);
    let (vb, tb) = shapes::icosphere(1, 1.0);
    let offset = va.len() as u32;
    let mut v = va;
    v.extend(vb.into_iter().map(|p| p + DVec3::new(3.0, 0.0, 0.0)));
    let mut t = ta;
    t.extend(tb.into_iter().map(|tri| tri.map(|i| i + offset)));
    SurfaceMesh::new(v, t).expect("two disjoint spheres are a valid surface")
}

/// First sphere fixed (zero displacement on its lower half, pulled on top), second sphere loaded
/// by a traction and held by nothing: the "fixed + floating" case.
fn fixed_and_floating(mesh: &SurfaceMesh) -> Vec<BoundaryCondition> {
    (0..mesh.element_count())
        .map(|e| {
            let c = mesh.centroid(e);
            if e < 80 {
                BoundaryCondition::Displacement(if c.z > 0.5 {
                    DVec3::new(0.0, 0.0, 0.01)
                } else {
                    DVec3::ZERO
                })
            } else {
                BoundaryCondition::Traction(0.01 * mesh.normal(e) * (1.0 + c.y))
            }
        })
        .collect()
}

/// Regression (issue 14): a fixed sphere plus a separate unsupported sphere "solved" with a 3e4
/// rigid drift. Now it is a typed error naming the floating body.
#[test]
fn fixed_sphere_plus_floating_sphere_is_a_floating_body_error() {
    let mesh = two_spheres();
    assert_eq!(mesh.body_count(), 2);
    assert_eq!((mesh.body(0), mesh.body(80)), (0, 1));
    let m = Material::new(0.3, 1.0).expect("material");
    let bcs = fixed_and_floating(&mesh);
    let err = solve(
        &mesh,
        &m,
        &bcs,
        &SolveParams::default(),
        &Control::default(),
    )
    .unwrap_err();
    assert_eq!(
        err,
        BemError::FloatingBody {
            body: 1,
            element: 80,
            bodies: 2
        }
    );
    assert!(err.to_string().contains("element 80"), "{err}");

    // holding the second sphere by one element makes it a healthy problem
    let mut held = bcs.clone();
    held[100] = BoundaryCondition::Displacement(DVec3::ZERO);
    let system = LinearSystem::assemble(
        &mesh,
        &m,
        &held.iter().map(|b| b.is_displacement()).collect::<Vec<_>>(),
        &{
            let mut loads = Loads::new(mesh.element_count(), 1);
            for (e, b) in held.iter().enumerate() {
                loads.set(e, 0, b.value()).expect("finite");
            }
            loads
        },
        &SolveParams::default(),
        &Control::default(),
    )
    .expect("assemble");
    let (solutions, report) = system
        .solve_with_report(&Control::default())
        .expect("held spheres solve");
    eprintln!(
        "two held spheres: condition estimate {:.3e}",
        report.condition_estimate
    );
    assert!(report.condition_estimate > 1.0 && report.condition_estimate < 1e5);
    let drift = solutions[0]
        .displacement
        .iter()
        .map(|u| u.length())
        .fold(0.0, f64::max);
    assert!(drift < 0.1, "largest displacement {drift:e}");
}

/// A hollow sphere is one body with two surface components: its cavity belongs to it, so fixing
/// only the cavity holds the body; nested separate bodies are told apart.
#[test]
fn cavities_belong_to_the_body_around_them() {
    let hollow = shapes::hollow_sphere(1.0, 2.0, 1).expect("valid");
    assert_eq!(hollow.body_count(), 1);
    let m = Material::new(0.3, 1.0).expect("material");
    let n = hollow.element_count();
    let bcs: Vec<BoundaryCondition> = (0..n)
        .map(|e| {
            if e < n / 2 {
                BoundaryCondition::Displacement(0.01 * hollow.centroid(e))
            } else {
                BoundaryCondition::FREE
            }
        })
        .collect();
    solve(
        &hollow,
        &m,
        &bcs,
        &SolveParams::default(),
        &Control::default(),
    )
    .expect("inner surface fixed holds the hollow sphere");

    // a small solid sphere floating inside the cavity of the hollow one: a second body
    let (vs, ts) = shapes::icosphere(1, 0.5);
    let mut v = hollow.vertices().to_vec();
    let offset = v.len() as u32;
    v.extend(vs);
    let mut t = hollow.triangles().to_vec();
    t.extend(ts.into_iter().map(|tri| tri.map(|i| i + offset)));
    let nested = SurfaceMesh::new(v, t).expect("valid nested surface");
    assert_eq!(nested.body_count(), 2);
    assert_eq!(
        (nested.body(0), nested.body(n - 1), nested.body(n)),
        (0, 0, 1)
    );
    let mut bcs = bcs;
    bcs.extend(vec![BoundaryCondition::FREE; 80]);
    let err = solve(
        &nested,
        &m,
        &bcs,
        &SolveParams::default(),
        &Control::default(),
    )
    .unwrap_err();
    assert!(
        matches!(err, BemError::FloatingBody { body: 1, element, bodies: 2 } if element == n),
        "{err}"
    );
}

/// K of the fixed + floating case assembled by hand from the full H and G (bypassing the body
/// check): the condition estimate sees the rigid modes of the floating sphere and the solve is
/// refused with a typed error instead of returning the drift.
#[test]
fn condition_estimate_refuses_the_floating_sphere_system() {
    let mesh = two_spheres();
    let m = Material::new(0.3, 1.0).expect("material");
    let bcs = fixed_and_floating(&mesh);
    let n = mesh.element_count();
    let (h, g) = assemble_h_g(&mesh, &m, &QuadratureParams::default()).expect("H and G");
    let dof = 3 * n;
    let mut k = faer::Mat::<f64>::zeros(dof, dof);
    let mut rhs = faer::Mat::<f64>::zeros(dof, 1);
    let mut loads = Loads::new(n, 1);
    for (j, bc) in bcs.iter().enumerate() {
        loads.set(j, 0, bc.value()).expect("finite");
        let value = bc.value().to_array();
        for (c, &v) in value.iter().enumerate() {
            let col = 3 * j + c;
            for r in 0..dof {
                if bc.is_displacement() {
                    k[(r, col)] = -g[(r, col)];
                    rhs[(r, 0)] -= h[(r, col)] * v;
                } else {
                    k[(r, col)] = h[(r, col)];
                    rhs[(r, 0)] += g[(r, col)] * v;
                }
            }
        }
    }
    let system = LinearSystem {
        matrix: DenseMatrix::from(&k),
        rhs,
        prescribed: bcs.iter().map(|b| b.is_displacement()).collect(),
        kinds: bem_core::ElementKind::from_mask(
            &bcs.iter().map(|b| b.is_displacement()).collect::<Vec<_>>(),
        ),
        normals: mesh.normals().to_vec(),
        loads,
        gauge_fixed: false,
        max_condition: DEFAULT_MAX_CONDITION,
        quadrature: Default::default(),
        precision: bem_core::Precision::Double,
    };
    let estimate = bem_core::DenseLu::factor(DenseMatrix::from(&k))
        .expect("the pivots alone do not reveal it")
        .condition_estimate()
        .expect("estimate");
    eprintln!("fixed + floating spheres: condition estimate {estimate:.3e}");
    assert!(estimate > DEFAULT_MAX_CONDITION, "{estimate:e}");
    match system.solve(&Control::default()) {
        Err(BemError::IllConditioned { estimate: e, limit }) => {
            assert_eq!(limit, DEFAULT_MAX_CONDITION);
            assert_eq!(e, estimate);
        }
        other => panic!("expected IllConditioned, got {other:?}"),
    }
}

/// The estimator itself: within a factor 3 of the exact κ₁ of small equilibrated matrices whose
/// inverse is known, and independent of column units.
#[test]
fn condition_estimate_matches_exact_kappa_and_ignores_column_units() {
    // upper bidiagonal with 1 on the diagonal and -2 above: inverse entries 2^(j-i), κ grows as 2^n
    let n = 12;
    let a = faer::Mat::<f64>::from_fn(n, n, |i, j| {
        if i == j {
            1.0
        } else if j == i + 1 {
            -2.0
        } else {
            0.0
        }
    });
    // exact: columns have 1-norm 3 (1 for the first); B = D⁻¹ A⁻¹ has entries norm_i 2^(j-i)
    let norms: Vec<f64> = (0..n).map(|j| if j == 0 { 1.0 } else { 3.0 }).collect();
    let exact = (0..n)
        .map(|j| {
            (0..=j)
                .map(|i| norms[i] * 2f64.powi((j - i) as i32))
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    let estimate = bem_core::DenseLu::factor(a.clone())
        .expect("factor")
        .condition_estimate()
        .expect("estimate");
    eprintln!("bidiagonal: estimate {estimate:.4e}, exact {exact:.4e}");
    assert!(estimate <= exact * (1.0 + 1e-12) && estimate >= exact / 3.0);
    // scaling columns by 1e-8 .. 1e8 does not change the equilibrated condition number
    let scaled = faer::Mat::<f64>::from_fn(n, n, |i, j| a[(i, j)] * 10f64.powi(j as i32 - 6));
    let again = bem_core::DenseLu::factor(scaled)
        .expect("factor")
        .condition_estimate()
        .expect("estimate");
    assert!(
        (again - estimate).abs() <= 1e-9 * estimate,
        "{again:e} vs {estimate:e}"
    );
}
