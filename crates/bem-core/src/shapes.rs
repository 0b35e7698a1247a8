//! Closed test shapes: icospheres and hollow spheres (used by tests, docs and the benchmark).

use std::collections::HashMap;

use glam::DVec3;

use crate::{MeshError, SurfaceMesh};

/// Icosphere of `20·4^subdivisions` triangles on a sphere of `radius` about the origin, outward
/// oriented: returns (vertices, triangles).
pub fn icosphere(subdivisions: u32, radius: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut vertices: Vec<DVec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z).normalize())
    .collect();
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
        let mut mid = |a: u32, b: u32, vertices: &mut Vec<DVec3>| -> u32 {
            *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                vertices.push((vertices[a as usize] + vertices[b as usize]).normalize());
                (vertices.len() - 1) as u32
            })
        };
        let mut next = Vec::with_capacity(triangles.len() * 4);
        for [a, b, c] in triangles {
            let ab = mid(a, b, &mut vertices);
            let bc = mid(b, c, &mut vertices);
            let ca = mid(c, a, &mut vertices);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        triangles = next;
    }
    for v in &mut vertices {
        *v *= radius;
    }
    (vertices, triangles)
}

/// Solid sphere surface (icosphere) as a validated mesh.
pub fn sphere(subdivisions: u32, radius: f64) -> Result<SurfaceMesh, MeshError> {
    let (v, t) = icosphere(subdivisions, radius);
    SurfaceMesh::new(v, t)
}

/// Hollow sphere `inner < |x| < outer`: an inward-oriented inner icosphere (elements
/// `0..element_count()/2`) followed by the outward outer one, both with `20·4^subdivisions`
/// triangles, so 640 elements for `subdivisions = 2` and 2560 for 3.
pub fn hollow_sphere(inner: f64, outer: f64, subdivisions: u32) -> Result<SurfaceMesh, MeshError> {
    let (vi, ti) = icosphere(subdivisions, inner);
    let (vo, to) = icosphere(subdivisions, outer);
    let offset = vi.len() as u32;
    let mut vertices = vi;
    vertices.extend(vo);
    let mut triangles: Vec<[u32; 3]> = ti.into_iter().map(|[a, b, c]| [a, c, b]).collect();
    triangles.extend(to.into_iter().map(|t| t.map(|i| i + offset)));
    SurfaceMesh::new(vertices, triangles)
}

/// Torus about the z axis (major radius `major`, tube radius `minor`) with `2·around·tube`
/// triangles, outward oriented: a closed surface of any element count (used by the benchmark).
pub fn torus(major: f64, minor: f64, around: u32, tube: u32) -> Result<SurfaceMesh, MeshError> {
    use std::f64::consts::TAU;
    let mut vertices = Vec::with_capacity((around * tube) as usize);
    for i in 0..around {
        let phi = TAU * i as f64 / around as f64;
        for j in 0..tube {
            let theta = TAU * j as f64 / tube as f64;
            let rr = major + minor * theta.cos();
            vertices.push(DVec3::new(
                rr * phi.cos(),
                rr * phi.sin(),
                minor * theta.sin(),
            ));
        }
    }
    let id = |i: u32, j: u32| (i % around) * tube + (j % tube);
    let mut triangles = Vec::with_capacity((2 * around * tube) as usize);
    for i in 0..around {
        for j in 0..tube {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    SurfaceMesh::new(vertices, triangles)
}
