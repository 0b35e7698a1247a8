//! Large faces: simulate on a simplified copy of the front mesh, carry the result to every vertex.
//!
//! A dense BEM solve grows as (3N)² in memory and (3N)³ in time, so a face above
//! [`LargeFaceParams::max_triangles`] is first simplified with meshoptimizer (every border
//! vertex locked, so the face contour, eyes and mouth stay exactly where they were) to about
//! [`LargeFaceParams::target_triangles`]. Vertex normals enter the simplifier's error as
//! attributes ([`LargeFaceParams::normal_weight`]), so it keeps vertices where the surface
//! turns sharply (rolled lips, eyelids) instead of flattening those folds into pleats whose
//! offset back face crosses the front. After the solve, each vertex of the full mesh takes the
//! displacement of the closest point on the simplified front surface, interpolated with that
//! point's barycentric coordinates ([`Transfer`]).

use glam::DVec3;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// When and how far to simplify a face before the BEM solve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LargeFaceParams {
    /// Faces with more front triangles than this are simplified.
    pub max_triangles: usize,
    /// Triangle count to simplify to (meshoptimizer stops near it; borders are never touched,
    /// so a face with long contours may keep a few more).
    pub target_triangles: usize,
    /// Largest geometric deviation simplification may introduce, relative to the mesh's
    /// extent; simplification stops before the target count rather than exceed it.
    pub max_error: f32,
    /// Weight of the unit vertex normal in the simplifier's error (meshoptimizer attribute
    /// weight; 0 simplifies by position only). Regression: by position only, the 1500-triangle
    /// copies of both ICT faces folded the rolled lips at a mouth corner into a pleat (adjacent
    /// normals at cos −0.993) and the shell crossed itself there; over a sweep of targets
    /// 1400/1500/1600 and offsets ±10 % on both ICT faces (18 shells), 11 crossed themselves by
    /// position only, 1 with weight 1, none with weight 2. Default 2.
    pub normal_weight: f32,
}

impl Default for LargeFaceParams {
    /// 1500 front triangles (the thesis' face size): a shell of about 3.2k elements, 9.6k DOFs,
    /// a 0.75 GB matrix and a precompute of well under a minute on 2 cores.
    fn default() -> Self {
        LargeFaceParams {
            max_triangles: 1500,
            target_triangles: 1500,
            max_error: 1.0,
            normal_weight: 2.0,
        }
    }
}

/// Errors from simplification.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SimplifyError {
    /// The target triangle count is too small to be a face.
    #[error("target of {0} triangles is too small (need at least 16)")]
    TargetTooSmall(usize),
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle {triangle} refers to vertex {vertex}, but there are only {count} vertices")]
    IndexOutOfRange {
        /// Triangle index.
        triangle: usize,
        /// Offending vertex.
        vertex: u32,
        /// Vertex count.
        count: usize,
    },
    /// meshoptimizer returned no triangles.
    #[error("simplification of {0} triangles produced an empty mesh")]
    Empty(usize),
}

/// A simplified copy of a mesh; its vertices are a subset of the original ones.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Simplified {
    /// Vertex positions (copies of original positions).
    pub vertices: Vec<DVec3>,
    /// Triangles indexing [`Simplified::vertices`].
    pub triangles: Vec<[u32; 3]>,
    /// For each simplified vertex, its index in the original mesh.
    pub original_vertex: Vec<u32>,
}

/// Simplifies a triangle mesh to about `params.target_triangles` with every border vertex
/// locked, within `params.max_error`, with vertex normals weighted by `params.normal_weight`.
///
/// ```
/// use facebem::large_face::{LargeFaceParams, simplify};
/// use glam::DVec3;
/// // A 20 x 20 grid of quads: 800 triangles, 84 border vertices.
/// let n = 21;
/// let vertices: Vec<DVec3> =
///     (0..n * n).map(|i| DVec3::new((i % n) as f64, (i / n) as f64, 0.0)).collect();
/// let mut triangles = vec![];
/// for y in 0..n - 1 {
///     for x in 0..n - 1 {
///         let v = (y * n + x) as u32;
///         triangles.push([v, v + 1, v + n as u32 + 1]);
///         triangles.push([v, v + n as u32 + 1, v + n as u32]);
///     }
/// }
/// let params = LargeFaceParams { target_triangles: 200, ..LargeFaceParams::default() };
/// let s = simplify(&vertices, &triangles, &params).unwrap();
/// assert!(s.triangles.len() <= 300);
/// ```
pub fn simplify(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    params: &LargeFaceParams,
) -> Result<Simplified, SimplifyError> {
    let target_triangles = params.target_triangles;
    if target_triangles < 16 {
        return Err(SimplifyError::TargetTooSmall(target_triangles));
    }
    for (t, tri) in triangles.iter().enumerate() {
        if let Some(&v) = tri.iter().find(|&&v| v as usize >= vertices.len()) {
            return Err(SimplifyError::IndexOutOfRange {
                triangle: t,
                vertex: v,
                count: vertices.len(),
            });
        }
    }
    let positions: Vec<[f32; 3]> = vertices.iter().map(|v| v.as_vec3().to_array()).collect();
    let bytes: Vec<u8> = positions
        .iter()
        .flatten()
        .flat_map(|c| c.to_le_bytes())
        .collect();
    let indices: Vec<u32> = triangles.iter().flatten().copied().collect();
    let normals: Vec<f32> = face_prep::shell::vertex_normals(vertices, triangles)
        .iter()
        .flat_map(|n| n.as_vec3().to_array())
        .collect();
    let weight = params.normal_weight.max(0.0);
    let result = match meshopt::VertexDataAdapter::new(&bytes, 12, 0) {
        Ok(adapter) => meshopt::simplify_with_attributes_and_locks(
            &indices,
            &adapter,
            &normals,
            &[weight; 3],
            12,
            // The wrapper passes the slice's pointer to C, which reads one flag per vertex.
            &vec![false; vertices.len()],
            target_triangles * 3,
            params.max_error,
            meshopt::SimplifyOptions::LockBorder,
            None,
        ),
        // Unreachable for 12-byte f32 triples; fall back to the unsimplified mesh.
        Err(_) => indices,
    };
    if result.is_empty() {
        return Err(SimplifyError::Empty(triangles.len()));
    }
    let mut new_index = vec![u32::MAX; vertices.len()];
    let mut original_vertex = Vec::new();
    let mut out_triangles = Vec::with_capacity(result.len() / 3);
    for tri in result.chunks_exact(3) {
        let mut t = [0u32; 3];
        for (k, &v) in tri.iter().enumerate() {
            if new_index[v as usize] == u32::MAX {
                new_index[v as usize] = original_vertex.len() as u32;
                original_vertex.push(v);
            }
            t[k] = new_index[v as usize];
        }
        out_triangles.push(t);
    }
    Ok(Simplified {
        vertices: original_vertex
            .iter()
            .map(|&v| vertices[v as usize])
            .collect(),
        triangles: out_triangles,
        original_vertex,
    })
}

/// For every vertex of a full mesh: the simplified triangle holding its closest point and that
/// point's barycentric coordinates, so fields on the simplified mesh can be carried over.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Transfer {
    /// Per full vertex: (simplified triangle index, barycentric weights).
    pub samples: Vec<(u32, [f64; 3])>,
}

impl Transfer {
    /// Finds, for every point of `full`, the closest point on the triangles of `coarse`
    /// (brute force over the triangles, parallel over the points). `None` if `coarse` has no
    /// triangles.
    pub fn build(full: &[DVec3], coarse: &Simplified) -> Option<Transfer> {
        if coarse.triangles.is_empty() {
            return None;
        }
        let tris: Vec<[DVec3; 3]> = coarse
            .triangles
            .iter()
            .map(|t| t.map(|i| coarse.vertices[i as usize]))
            .collect();
        let samples = full
            .par_iter()
            .map(|&p| {
                let mut best = (f64::INFINITY, 0u32, [1.0, 0.0, 0.0]);
                for (t, &[a, b, c]) in tris.iter().enumerate() {
                    let w = face_prep::closest_point::closest_point_barycentric(p, a, b, c);
                    let q = a * w[0] + b * w[1] + c * w[2];
                    let d = q.distance_squared(p);
                    if d < best.0 {
                        best = (d, t as u32, w);
                    }
                }
                (best.1, best.2)
            })
            .collect();
        Some(Transfer { samples })
    }

    /// Interpolates a per-vertex field of the simplified mesh onto the full mesh's vertices.
    /// `coarse_field` must have one value per simplified vertex.
    pub fn apply(&self, coarse: &Simplified, coarse_field: &[DVec3]) -> Vec<DVec3> {
        self.samples
            .iter()
            .map(|(t, w)| {
                let tri = coarse.triangles[*t as usize];
                (0..3)
                    .map(|k| coarse_field[tri[k] as usize] * w[k])
                    .sum::<DVec3>()
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: usize) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let vertices = (0..n * n)
            .map(|i| {
                let (x, y) = ((i % n) as f64, (i / n) as f64);
                DVec3::new(x, y, 0.1 * (x * 0.3).sin() * (y * 0.2).cos())
            })
            .collect();
        let mut triangles = vec![];
        let m = n as u32;
        for y in 0..m - 1 {
            for x in 0..m - 1 {
                let v = y * m + x;
                triangles.push([v, v + 1, v + m + 1]);
                triangles.push([v, v + m + 1, v + m]);
            }
        }
        (vertices, triangles)
    }

    #[test]
    fn simplify_keeps_borders_and_transfer_reproduces_linear_fields() {
        let (vertices, triangles) = grid(31);
        let params = LargeFaceParams {
            target_triangles: 300,
            ..LargeFaceParams::default()
        };
        let s = simplify(&vertices, &triangles, &params).unwrap();
        assert!(s.triangles.len() < 600, "{} triangles", s.triangles.len());
        // Every border vertex survives.
        let border = (0..vertices.len()).filter(|&i| {
            let (x, y) = (i % 31, i / 31);
            x == 0 || y == 0 || x == 30 || y == 30
        });
        for v in border {
            assert!(
                s.original_vertex.contains(&(v as u32)),
                "border vertex {v} lost"
            );
        }
        // A field linear in x, y is carried exactly to vertices lying on the coarse surface
        // (the coarse vertices themselves) and to within the surface's deviation elsewhere.
        let field = |p: DVec3| DVec3::new(0.5 * p.x, -0.25 * p.y, 0.0);
        let coarse_field: Vec<DVec3> = s.vertices.iter().map(|&p| field(p)).collect();
        let t = Transfer::build(&vertices, &s).unwrap();
        let carried = t.apply(&s, &coarse_field);
        for (&orig, &c) in s.original_vertex.iter().zip(&coarse_field) {
            assert!(carried[orig as usize].distance(c) < 1e-12);
        }
        let max_err = vertices
            .iter()
            .zip(&carried)
            .map(|(&p, &c)| c.distance(field(p)))
            .fold(0.0, f64::max);
        assert!(max_err < 0.1, "max transfer error {max_err}");
    }

    #[test]
    fn bad_simplify_inputs() {
        let (v, t) = grid(3);
        let target = |n| LargeFaceParams {
            target_triangles: n,
            ..LargeFaceParams::default()
        };
        assert_eq!(
            simplify(&v, &t, &target(4)),
            Err(SimplifyError::TargetTooSmall(4))
        );
        assert!(matches!(
            simplify(&v[..4], &t, &target(100)),
            Err(SimplifyError::IndexOutOfRange { .. })
        ));
    }
}
