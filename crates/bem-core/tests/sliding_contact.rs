//! Sliding contact (`ElementKind::Sliding`: normal displacement and tangential traction
//! prescribed) against exact solutions on a unit cube.

use bem_core::{
    Control, DisplacementGroup, ElementKind, Material, ResponseBasis, SolveParams, SurfaceMesh,
};
use glam::DVec3;

/// Closed unit cube [0, 1]³, each face split into `k × k` squares of two triangles, outward
/// normals.
fn cube(k: u32) -> SurfaceMesh {
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    // (origin, u axis, v axis) of each face, u × v outward
    let faces = [
        (DVec3::ZERO, DVec3::Y, DVec3::X), // z = 0, normal −z
        (DVec3::Z, DVec3::X, DVec3::Y),    // z = 1, normal +z
        (DVec3::ZERO, DVec3::Z, DVec3::Y), // x = 0, normal −x
        (DVec3::X, DVec3::Y, DVec3::Z),    // x = 1, normal +x
        (DVec3::ZERO, DVec3::X, DVec3::Z), // y = 0, normal −y
        (DVec3::Y, DVec3::Z, DVec3::X),    // y = 1, normal +y
    ];
    for (origin, u, v) in faces {
        let base = vertices.len() as u32;
        for j in 0..=k {
            for i in 0..=k {
                vertices.push(origin + u * (i as f64 / k as f64) + v * (j as f64 / k as f64));
            }
        }
        let id = |i: u32, j: u32| base + j * (k + 1) + i;
        for j in 0..k {
            for i in 0..k {
                triangles.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                triangles.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
    }
    // weld the shared edges
    let mut unique: Vec<DVec3> = Vec::new();
    let mut remap = Vec::with_capacity(vertices.len());
    for p in &vertices {
        let found = unique.iter().position(|q| q.distance(*p) < 1e-9);
        remap.push(match found {
            Some(i) => i as u32,
            None => {
                unique.push(*p);
                (unique.len() - 1) as u32
            }
        });
    }
    let triangles = triangles
        .into_iter()
        .map(|t| t.map(|v| remap[v as usize]))
        .collect();
    SurfaceMesh::new(unique, triangles).unwrap()
}

fn solve(
    mesh: &SurfaceMesh,
    kinds: &[ElementKind],
    group: DisplacementGroup,
) -> bem_core::Solution {
    let m = Material::new(0.3, 1.0).unwrap();
    ResponseBasis::compute(
        mesh,
        &m,
        kinds,
        &[group],
        &SolveParams::default(),
        &Control::default(),
    )
    .unwrap()
    .responses
    .remove(0)
}

/// Every face sliding with the normal displacement of a rigid translation v: the discrete
/// system is solved exactly by u = v, t = 0 (H annihilates rigid translations).
#[test]
fn all_faces_sliding_translate_rigidly() {
    let mesh = cube(3);
    let n = mesh.element_count();
    let v = DVec3::new(0.01, -0.02, 0.015);
    let kinds = vec![ElementKind::Sliding; n];
    let group = (0..n)
        .map(|e| (e, mesh.normal(e) * v.dot(mesh.normal(e))))
        .collect();
    let s = solve(&mesh, &kinds, group);
    for e in 0..n {
        assert!(
            (s.displacement[e] - v).length() < 1e-9,
            "element {e}: {:?}",
            s.displacement[e]
        );
        assert!(
            s.traction[e].length() < 1e-8,
            "element {e}: {:?}",
            s.traction[e]
        );
    }
}

/// Uniaxial compression of a cube octant: x = 0, y = 0, z = 0 are symmetry planes (sliding),
/// the top z = 1 is pushed down by δ while sliding freely, x = 1 and y = 1 are free. Exact:
/// u = (ν δ x, ν δ y, −δ z), σ_zz = −E δ, every other stress zero.
#[test]
fn octant_compression_matches_the_uniaxial_solution() {
    let mesh = cube(6);
    let n = mesh.element_count();
    let (nu, mu, delta) = (0.3, 1.0, 0.01);
    let e_modulus = 2.0 * mu * (1.0 + nu);
    let mut kinds = vec![ElementKind::Traction; n];
    let mut group = Vec::new();
    for (e, kind) in kinds.iter_mut().enumerate() {
        let normal = mesh.normal(e);
        if normal.x < -0.5 || normal.y < -0.5 || normal.z < -0.5 {
            *kind = ElementKind::Sliding;
        } else if normal.z > 0.5 {
            *kind = ElementKind::Sliding;
            group.push((e, DVec3::new(0.0, 0.0, -delta)));
        }
    }
    let s = solve(&mesh, &kinds, group);
    let mut worst_u: f64 = 0.0;
    let mut worst_t: f64 = 0.0;
    for (e, &kind) in kinds.iter().enumerate() {
        let (c, normal) = (mesh.centroid(e), mesh.normal(e));
        let exact_u = DVec3::new(nu * delta * c.x, nu * delta * c.y, -delta * c.z);
        worst_u = worst_u.max((s.displacement[e] - exact_u).length() / delta);
        let exact_t = DVec3::new(0.0, 0.0, -e_modulus * delta * normal.z);
        worst_t = worst_t.max((s.traction[e] - exact_t).length() / (e_modulus * delta));
        if kind == ElementKind::Sliding {
            // on its support exactly
            let want = if normal.z > 0.5 { -delta } else { 0.0 };
            assert!((s.displacement[e].dot(normal) - want).abs() < 1e-12);
        }
    }
    println!("worst displacement error {worst_u:.4} δ, worst traction error {worst_t:.4} E δ");
    assert!(worst_u < 0.02, "displacement error {worst_u:.4} δ");
    assert!(worst_t < 0.08, "traction error {worst_t:.4} E δ");
}

/// A body held only by sliding on one plane can still slide along it: refused (a singular or
/// ill-conditioned system) instead of returning a drifting answer.
#[test]
fn sliding_on_one_plane_alone_is_refused() {
    let mesh = cube(2);
    let n = mesh.element_count();
    let kinds: Vec<ElementKind> = (0..n)
        .map(|e| {
            if mesh.normal(e).z < -0.5 {
                ElementKind::Sliding
            } else {
                ElementKind::Traction
            }
        })
        .collect();
    let m = Material::new(0.3, 1.0).unwrap();
    let top: Vec<(usize, DVec3)> = (0..n)
        .filter(|&e| mesh.normal(e).z > 0.5)
        .map(|e| (e, DVec3::new(0.0, 0.0, -0.01)))
        .collect();
    let r = ResponseBasis::compute(
        &mesh,
        &m,
        &kinds,
        &[top],
        &SolveParams::default(),
        &Control::default(),
    );
    assert!(
        matches!(
            r,
            Err(bem_core::BemError::IllConditioned { .. } | bem_core::BemError::Singular { .. })
        ),
        "{r:?}"
    );
}
