//! Closed, outward-oriented triangle surface: the boundary of the elastic body.

use std::collections::HashMap;

use glam::DVec3;

use crate::MeshError;

/// Relative area below which a triangle counts as degenerate: area ≤ this × (longest edge)².
const DEGENERATE_RELATIVE_AREA: f64 = 1e-10;

/// A closed, edge-manifold, consistently and outward-oriented triangle surface with f64 vertices.
///
/// Each triangle is one constant boundary element whose collocation node is its centroid.
/// Several closed components are allowed (a hollow sphere is an outer sphere plus an
/// inward-facing inner sphere); what is checked is that every edge is shared by exactly two
/// triangles traversing it in opposite directions and that the total enclosed volume is positive.
#[derive(Debug, Clone)]
pub struct SurfaceMesh {
    vertices: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    centroids: Vec<DVec3>,
    normals: Vec<DVec3>,
    areas: Vec<f64>,
    longest_edges: Vec<f64>,
    /// Centre of the bounding box: the solver works in coordinates relative to it
    /// ([`SurfaceMesh::recentred`]), so that translating a problem changes nothing.
    origin: DVec3,
    /// Body of each element ([`SurfaceMesh::body`]).
    body: Vec<u32>,
}

/// Centre of the axis-aligned bounding box of `vertices` (zero when there is none).
fn bounding_box_centre(vertices: &[DVec3]) -> DVec3 {
    let Some(first) = vertices.first() else {
        return DVec3::ZERO;
    };
    let (lo, hi) = vertices
        .iter()
        .fold((*first, *first), |(lo, hi), v| (lo.min(*v), hi.max(*v)));
    0.5 * (lo + hi)
}

impl SurfaceMesh {
    /// Validates and builds a surface mesh.
    ///
    /// ```
    /// use bem_core::{shapes, SurfaceMesh};
    /// let (v, t) = shapes::icosphere(1, 1.0);
    /// let mesh = SurfaceMesh::new(v, t).unwrap();
    /// assert_eq!(mesh.element_count(), 80);
    /// ```
    pub fn new(vertices: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<Self, MeshError> {
        if triangles.is_empty() {
            return Err(MeshError::Empty);
        }
        if let Some((vertex, v)) = vertices.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(MeshError::NonFiniteVertex {
                vertex,
                x: v.x,
                y: v.y,
                z: v.z,
            });
        }
        let n = triangles.len();
        // every geometric check below works relative to the bounding-box centre: a mesh far from
        // the coordinate origin (e.g. translated by 1e7) is validated like the same mesh at 0
        let origin = bounding_box_centre(&vertices);
        let local: Vec<DVec3> = vertices.iter().map(|v| *v - origin).collect();
        let mut centroids = Vec::with_capacity(n);
        let mut normals = Vec::with_capacity(n);
        let mut areas = Vec::with_capacity(n);
        let mut longest_edges = Vec::with_capacity(n);
        for (t, tri) in triangles.iter().enumerate() {
            for &index in tri {
                if index as usize >= vertices.len() {
                    return Err(MeshError::IndexOutOfRange {
                        triangle: t,
                        index,
                        vertex_count: vertices.len(),
                    });
                }
            }
            let [a, b, c] = tri.map(|i| vertices[i as usize]);
            let cross = (b - a).cross(c - a);
            let area = 0.5 * cross.length();
            let longest = (b - a).length().max((c - b).length()).max((a - c).length());
            if tri[0] == tri[1]
                || tri[1] == tri[2]
                || tri[0] == tri[2]
                || area.is_nan()
                || area <= DEGENERATE_RELATIVE_AREA * longest * longest
            {
                return Err(MeshError::DegenerateTriangle {
                    triangle: t,
                    area,
                    longest_edge: longest,
                });
            }
            centroids.push((a + b + c) / 3.0);
            normals.push(cross / (2.0 * area));
            areas.push(area);
            longest_edges.push(longest);
        }
        check_closed_manifold_oriented(&triangles)?;
        let volume = signed_volume(&local, &triangles);
        if volume.is_nan() || volume <= 0.0 {
            return Err(MeshError::NotOutward { volume });
        }
        let local_centroids: Vec<DVec3> = centroids.iter().map(|c| *c - origin).collect();
        let component = crate::bodies::components(vertices.len(), &triangles);
        check_components_outward(
            &local,
            &triangles,
            &component,
            &local_centroids,
            &normals,
            &areas,
            &longest_edges,
        )?;
        let body = crate::bodies::bodies(&local, &triangles, &component, &local_centroids, &areas);
        Ok(Self {
            vertices,
            triangles,
            centroids,
            normals,
            areas,
            longest_edges,
            origin,
            body,
        })
    }

    /// The same (already validated) mesh translated so that its bounding-box centre is at the
    /// origin, with centroids, normals, areas and edges recomputed from the shifted vertices.
    ///
    /// The solver assembles in these coordinates: subtracting the centre is exact for
    /// coordinates within a factor two of it (Sterbenz), so a problem translated far from the
    /// origin gives the same element geometry, and the same solution, as the original.
    pub(crate) fn recentred(&self) -> Self {
        let origin = self.origin;
        let vertices: Vec<DVec3> = self.vertices.iter().map(|v| *v - origin).collect();
        let n = self.triangles.len();
        let mut centroids = Vec::with_capacity(n);
        let mut normals = Vec::with_capacity(n);
        let mut areas = Vec::with_capacity(n);
        let mut longest_edges = Vec::with_capacity(n);
        for tri in &self.triangles {
            let [a, b, c] = tri.map(|i| vertices[i as usize]);
            let cross = (b - a).cross(c - a);
            let area = 0.5 * cross.length();
            centroids.push((a + b + c) / 3.0);
            normals.push(cross / (2.0 * area));
            areas.push(area);
            longest_edges.push((b - a).length().max((c - b).length()).max((a - c).length()));
        }
        Self {
            origin: bounding_box_centre(&vertices),
            body: self.body.clone(),
            vertices,
            triangles: self.triangles.clone(),
            centroids,
            normals,
            areas,
            longest_edges,
        }
    }

    /// Number of elements (triangles).
    pub fn element_count(&self) -> usize {
        self.triangles.len()
    }

    /// Vertices.
    pub fn vertices(&self) -> &[DVec3] {
        &self.vertices
    }

    /// Triangles (vertex indices, counter-clockwise seen from outside).
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Corner positions of element `e`.
    pub fn corners(&self, e: usize) -> [DVec3; 3] {
        self.triangles[e].map(|i| self.vertices[i as usize])
    }

    /// Centroid (collocation node) of element `e`.
    pub fn centroid(&self, e: usize) -> DVec3 {
        self.centroids[e]
    }

    /// All centroids.
    pub fn centroids(&self) -> &[DVec3] {
        &self.centroids
    }

    /// Outward unit normal of element `e`.
    pub fn normal(&self, e: usize) -> DVec3 {
        self.normals[e]
    }

    /// All outward unit normals.
    pub fn normals(&self) -> &[DVec3] {
        &self.normals
    }

    /// Area of element `e`.
    pub fn area(&self, e: usize) -> f64 {
        self.areas[e]
    }

    /// All areas.
    pub fn areas(&self) -> &[f64] {
        &self.areas
    }

    /// Longest edge of element `e`.
    pub fn longest_edge(&self, e: usize) -> f64 {
        self.longest_edges[e]
    }

    /// Number of separate elastic bodies: connected surface components, with each cavity (an
    /// inward-facing component) counted with the body whose outer surface encloses it.
    ///
    /// ```
    /// use bem_core::shapes;
    /// assert_eq!(shapes::hollow_sphere(1.0, 2.0, 1).unwrap().body_count(), 1);
    /// ```
    pub fn body_count(&self) -> usize {
        self.body.iter().map(|&b| b as usize + 1).max().unwrap_or(0)
    }

    /// Body of element `e` (0-based, numbered in order of their first element).
    pub fn body(&self, e: usize) -> usize {
        self.body[e] as usize
    }

    /// Enclosed volume (positive for a valid mesh), computed relative to the bounding-box centre
    /// so that it does not depend on where the mesh is.
    pub fn volume(&self) -> f64 {
        let local: Vec<DVec3> = self.vertices.iter().map(|v| *v - self.origin).collect();
        signed_volume(&local, &self.triangles)
    }
}

/// Signed enclosed volume (sum of tetrahedra with the coordinate origin).
fn signed_volume(vertices: &[DVec3], triangles: &[[u32; 3]]) -> f64 {
    triangles
        .iter()
        .map(|tri| {
            let [a, b, c] = tri.map(|i| vertices[i as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// Every undirected edge must be used exactly twice, once in each direction.
fn check_closed_manifold_oriented(triangles: &[[u32; 3]]) -> Result<(), MeshError> {
    // directed edge -> triangle
    let mut directed: HashMap<(u32, u32), usize> = HashMap::with_capacity(triangles.len() * 3);
    let mut undirected: HashMap<(u32, u32), (usize, usize)> =
        HashMap::with_capacity(triangles.len() * 3 / 2);
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let key = (a.min(b), a.max(b));
            let entry = undirected.entry(key).or_insert((0, t));
            entry.0 += 1;
            if entry.0 > 2 {
                return Err(MeshError::NonManifoldEdge {
                    a: key.0,
                    b: key.1,
                    count: entry.0,
                    triangle: entry.1,
                });
            }
            if let Some(&first) = directed.get(&(a, b)) {
                // counted later as non-manifold if a third use appears; here two uses in the same direction
                let count = undirected.get(&key).map_or(0, |e| e.0);
                if count <= 2 {
                    // keep scanning for a third use first, to report the more fundamental problem
                    let third = triangles.iter().enumerate().skip(t + 1).any(|(_, o)| {
                        (0..3).any(|m| {
                            let (p, q) = (o[m], o[(m + 1) % 3]);
                            (p.min(q), p.max(q)) == key
                        })
                    });
                    if third {
                        return Err(MeshError::NonManifoldEdge {
                            a: key.0,
                            b: key.1,
                            count: 3,
                            triangle: first,
                        });
                    }
                }
                return Err(MeshError::InconsistentOrientation {
                    a,
                    b,
                    first,
                    second: t,
                });
            }
            directed.insert((a, b), t);
        }
    }
    let mut open: Vec<(u32, u32, usize)> = undirected
        .iter()
        .filter(|(_, (count, _))| *count == 1)
        .map(|(&(a, b), &(_, t))| (a, b, t))
        .collect();
    open.sort_unstable();
    if let Some(&(a, b, triangle)) = open.first() {
        return Err(MeshError::OpenEdge { a, b, triangle });
    }
    Ok(())
}

/// Each connected component must face outward from the body, not only the total volume be
/// positive: a point just off its largest triangle along the normal must be outside the body.
/// (Catches e.g. a hollow sphere whose inner sphere is oriented like the outer one.)
fn check_components_outward(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    component: &[u32],
    centroids: &[DVec3],
    normals: &[DVec3],
    areas: &[f64],
    longest: &[f64],
) -> Result<(), MeshError> {
    let picks = crate::bodies::largest_triangles(component, areas);
    if picks.len() < 2 {
        return Ok(()); // one component: the positive volume already decides
    }
    for t in picks {
        // 1% of the triangle's size off its centroid: its own solid angle is ≈ 2π on the near side
        let p = centroids[t] + normals[t] * (0.01 * (2.0 * areas[t]).sqrt().min(longest[t]));
        let winding = crate::bodies::winding_number(vertices, triangles, p);
        if winding > 0.5 {
            return Err(MeshError::ComponentInward {
                triangle: t,
                winding,
            });
        }
    }
    Ok(())
}
