//! Invalid meshes, materials and boundary conditions give typed errors, never panics.

use bem_core::{
    BemError, BoundaryCondition, Control, Material, MeshError, ResponseBasis, SolveParams,
    SurfaceMesh, shapes, solve,
};
use glam::DVec3;

fn tetra() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let v = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
    ];
    let t = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    (v, t)
}

#[test]
fn valid_tetrahedron_is_accepted_with_correct_geometry() {
    let (v, t) = tetra();
    let mesh = SurfaceMesh::new(v, t).expect("valid");
    assert!((mesh.volume() - 1.0 / 6.0).abs() < 1e-15);
    assert!((mesh.area(0) - 0.5).abs() < 1e-15);
    assert!((mesh.normal(0) - DVec3::new(0.0, 0.0, -1.0)).length() < 1e-15);
    assert!((mesh.centroid(3) - DVec3::splat(1.0 / 3.0)).length() < 1e-15);
    assert!((mesh.longest_edge(3) - 2f64.sqrt()).abs() < 1e-15);
}

#[test]
fn open_mesh_names_the_boundary_edge() {
    let (v, mut t) = tetra();
    t.pop();
    let err = SurfaceMesh::new(v, t).unwrap_err();
    assert!(matches!(err, MeshError::OpenEdge { .. }), "{err}");
    if let MeshError::OpenEdge { a, b, .. } = err {
        // the removed face was (1, 2, 3): its edges are the open ones
        assert!(
            [(1, 2), (2, 3), (1, 3)].contains(&(a.min(b), a.max(b))),
            "{a} {b}"
        );
    }
}

#[test]
fn non_manifold_edge_is_reported() {
    // two tetrahedra sharing edge (0, 1) plus a third face on it
    let (mut v, mut t) = tetra();
    v.push(DVec3::new(0.5, -1.0, 0.3));
    t.extend([[0, 1, 4], [1, 0, 4]]);
    let err = SurfaceMesh::new(v, t).unwrap_err();
    assert!(
        matches!(err, MeshError::NonManifoldEdge { a: 0, b: 1, .. }),
        "{err}"
    );
}

#[test]
fn flipped_triangle_is_inconsistent_orientation() {
    let (v, mut t) = tetra();
    t[3] = [1, 3, 2];
    let err = SurfaceMesh::new(v, t).unwrap_err();
    assert!(
        matches!(err, MeshError::InconsistentOrientation { .. }),
        "{err}"
    );
}

#[test]
fn inward_mesh_is_rejected() {
    let (v, t) = tetra();
    let t = t.into_iter().map(|[a, b, c]| [a, c, b]).collect();
    let err = SurfaceMesh::new(v, t).unwrap_err();
    assert!(
        matches!(err, MeshError::NotOutward { volume } if volume < 0.0),
        "{err}"
    );
}

#[test]
fn zero_area_triangle_is_degenerate() {
    let (mut v, t) = tetra();
    v[3] = DVec3::new(0.5, 0.5, 0.0); // on the hypotenuse of face (0, 2, 1)... makes face (1,2,3) flat
    let err = SurfaceMesh::new(v, t).unwrap_err();
    assert!(
        matches!(err, MeshError::DegenerateTriangle { triangle: 3, .. }),
        "{err}"
    );
    let (v, mut t) = tetra();
    t[0] = [0, 0, 1];
    let err = SurfaceMesh::new(v, t).unwrap_err();
    assert!(
        matches!(err, MeshError::DegenerateTriangle { triangle: 0, .. }),
        "{err}"
    );
}

#[test]
fn nan_coordinate_and_bad_index_are_reported() {
    let (mut v, t) = tetra();
    v[2].y = f64::NAN;
    let err = SurfaceMesh::new(v, t).unwrap_err();
    assert!(
        matches!(err, MeshError::NonFiniteVertex { vertex: 2, .. }),
        "{err}"
    );
    let (v, mut t) = tetra();
    t[1][2] = 9;
    let err = SurfaceMesh::new(v, t).unwrap_err();
    assert!(
        matches!(
            err,
            MeshError::IndexOutOfRange {
                triangle: 1,
                index: 9,
                vertex_count: 4
            }
        ),
        "{err}"
    );
    assert_eq!(
        SurfaceMesh::new(vec![], vec![]).unwrap_err(),
        MeshError::Empty
    );
}

#[test]
fn material_is_validated() {
    assert_eq!(
        Material::new(0.5, 1.0).unwrap_err(),
        BemError::InvalidPoisson(0.5)
    );
    assert!(matches!(
        Material::new(0.7, 1.0),
        Err(BemError::InvalidPoisson(_))
    ));
    assert!(matches!(
        Material::new(-0.1, 1.0),
        Err(BemError::InvalidPoisson(_))
    ));
    assert!(matches!(
        Material::new(f64::NAN, 1.0),
        Err(BemError::InvalidPoisson(_))
    ));
    assert!(matches!(
        Material::new(0.3, 0.0),
        Err(BemError::InvalidShearModulus(_))
    ));
    assert!(matches!(
        Material::new(0.3, f64::INFINITY),
        Err(BemError::InvalidShearModulus(_))
    ));
    assert!(Material::new(0.0, 1.0).is_ok() && Material::new(0.499, 1.0).is_ok());
}

#[test]
fn wrong_number_of_conditions_and_bad_values_are_reported() {
    let mesh = shapes::sphere(1, 1.0).expect("valid");
    let m = Material::new(0.3, 1.0).expect("material");
    let bcs = vec![BoundaryCondition::Displacement(DVec3::X); 79];
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
        BemError::WrongLength {
            what: "boundary conditions",
            expected: 80,
            got: 79
        }
    );
    let mut bcs = vec![BoundaryCondition::Displacement(DVec3::X); 80];
    bcs[7] = BoundaryCondition::Traction(DVec3::new(0.0, f64::NAN, 0.0));
    let err = solve(
        &mesh,
        &m,
        &bcs,
        &SolveParams::default(),
        &Control::default(),
    )
    .unwrap_err();
    assert_eq!(err, BemError::NonFiniteValue { element: 7 });
}

#[test]
fn response_groups_must_name_existing_elements_and_load_free_ones_with_tractions() {
    let mesh = shapes::sphere(1, 1.0).expect("valid");
    let m = Material::new(0.3, 1.0).expect("material");
    let prescribed: Vec<bool> = (0..80).map(|e| e < 40).collect();
    let p = SolveParams::default();
    let c = Control::default();
    // A group value on a free element is a traction (a force-driven muscle): it comes back as
    // that element's traction, the prescribed elements stay put, and the body moves.
    let basis = ResponseBasis::compute(&mesh, &m, &prescribed, &[vec![(50, DVec3::X)]], &p, &c)
        .expect("traction group");
    let r = &basis.responses[0];
    assert!(
        (r.traction[50] - DVec3::X).length() < 1e-12,
        "{}",
        r.traction[50]
    );
    for e in 40..80 {
        if e != 50 {
            assert!(
                r.traction[e].length() < 1e-12,
                "element {e}: {}",
                r.traction[e]
            );
        }
    }
    for e in 0..40 {
        assert_eq!(r.displacement[e], DVec3::ZERO, "element {e}");
    }
    assert!(r.displacement[50].x > 0.0, "{}", r.displacement[50]);
    let err = ResponseBasis::compute(
        &mesh,
        &m,
        &prescribed,
        &[vec![], vec![(80, DVec3::X)]],
        &p,
        &c,
    )
    .unwrap_err();
    assert!(
        matches!(
            err,
            BemError::BadGroupElement {
                group: 1,
                element: 80,
                ..
            }
        ),
        "{err}"
    );
    let err = ResponseBasis::compute(&mesh, &m, &prescribed[..10], &[], &p, &c).unwrap_err();
    assert!(
        matches!(
            err,
            BemError::WrongLength {
                expected: 80,
                got: 10,
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn material_from_a_file_is_validated() {
    let ok: Material =
        serde_json::from_str(r#"{"poisson":0.45,"shear_modulus":2.0}"#).expect("valid json");
    assert_eq!(ok, Material::new(0.45, 2.0).expect("valid"));
    let err = serde_json::from_str::<Material>(r#"{"poisson":0.5,"shear_modulus":2.0}"#)
        .expect_err("ν = 0.5 must be rejected");
    assert!(err.to_string().contains("Poisson ratio 0.5"), "{err}");
}

#[test]
fn cavity_oriented_like_the_outer_surface_is_rejected() {
    // hollow sphere whose inner sphere is (wrongly) outward-oriented: total volume is positive,
    // so only the per-component check catches it
    let (vi, ti) = shapes::icosphere(1, 1.0);
    let (vo, to) = shapes::icosphere(1, 2.0);
    let offset = vi.len() as u32;
    let mut v = vi;
    v.extend(vo);
    let mut t = ti;
    let inner_count = t.len();
    t.extend(to.into_iter().map(|tri| tri.map(|i| i + offset)));
    let err = SurfaceMesh::new(v, t).unwrap_err();
    match err {
        MeshError::ComponentInward { triangle, winding } => {
            assert!(
                triangle < inner_count,
                "blamed the outer sphere: {triangle}"
            );
            assert!((winding - 1.0).abs() < 0.05, "{winding}");
        }
        other => panic!("expected ComponentInward, got {other}"),
    }
    // the correctly oriented hollow sphere and two disjoint spheres are accepted
    assert!(shapes::hollow_sphere(1.0, 2.0, 1).is_ok());
    let (va, ta) = shapes::icosphere(1, 1.0);
    let n = va.len() as u32;
    let mut v: Vec<DVec3> = va.clone();
    v.extend(va.iter().map(|p| *p + DVec3::new(5.0, 0.0, 0.0)));
    let mut t = ta.clone();
    t.extend(ta.iter().map(|tri| tri.map(|i| i + n)));
    assert!(SurfaceMesh::new(v, t).is_ok());
}
