//! The copy stage: the front mesh that is simulated when it is not the user's mesh as written —
//! rolled-in eyelids and lips peeled off ([`rolled_in`]), a large face simplified
//! ([`simplify`](mod@simplify)) or remeshed ([`remesh_face`], [`remesh`]); [`crate::transfer`] carries the
//! copy's responses back to every input vertex.
//!
//! Large faces: simulate on a simplified copy of the front mesh, carry the result to every vertex.
//!
//! A dense BEM solve grows as (3N)² in memory and (3N)³ in time, so a face above
//! [`LargeFaceParams::max_triangles`] is first simplified with meshoptimizer to about
//! [`LargeFaceParams::target_triangles`]. The borders (face contour, eyes, mouth) are kept: a
//! border vertex only ever collapses along its border, and border vertices about
//! [`LargeFaceParams::border_spacing`] target edge lengths apart are locked, so the contours are
//! resampled to the resolution of the rest of the copy instead of keeping every input vertex
//! (which left slivers along dense contours). Vertex normals enter the simplifier's error as
//! attributes ([`LargeFaceParams::normal_weight`]), so it keeps vertices where the surface turns
//! sharply instead of flattening folds into pleats whose offset back face crosses the front.
//! After the solve, each vertex of the full mesh takes the displacement of the closest point on
//! the simplified front surface, interpolated with that point's barycentric coordinates
//! ([`Transfer`](crate::transfer::Transfer)).

pub mod flips;
pub(crate) mod reduce;
pub mod remesh;
pub mod remesh_face;
pub mod rolled_in;
pub mod simplify;
pub mod symmetrize;

use glam::DVec3;
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
    /// 1400/1500/1600 and offsets ±10 % on both ICT faces (18 shells, rolled-in lips still
    /// simulated then), 11 crossed themselves by position only, 1 with weight 1, none with
    /// weight 2. Default 2.
    pub normal_weight: f32,
    /// Spacing of the locked border vertices, in edge lengths of an equilateral triangle of the
    /// target size (the other border vertices may collapse along their border); 0 locks every
    /// border vertex. Regression: with every border vertex locked, the peeled ICT 13k face's
    /// contours (edges of 0.14–0.4 against 0.66 inside) left slivers along the eyes and mouth
    /// whose back copies formed near-zero wedges: largest responses 8–428 times the muscles'
    /// own motion over targets 1400/1500/1600 × offsets ±10 %; 1.0–1.1 resampled at 0.5.
    /// Default 0.5.
    pub border_spacing: f64,
    /// How the copy is made: edge collapses that keep input vertices (default), or isotropic
    /// remeshing ([`crate::copy::remesh_face::remesh_face`]).
    #[serde(default)]
    pub method: CopyMethod,
}

/// How a large face's simulated copy is made ([`LargeFaceParams::method`]).
///
/// ```
/// use facebem::copy::CopyMethod;
/// assert_eq!(CopyMethod::parse("remesh"), Some(CopyMethod::Remesh));
/// assert_eq!(CopyMethod::default(), CopyMethod::Collapse);
/// assert_eq!(CopyMethod::parse("decimate"), None);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[non_exhaustive]
pub enum CopyMethod {
    /// meshoptimizer's edge collapses; the copy's vertices are input vertices.
    #[default]
    Collapse,
    /// Isotropic remeshing, finer at the mouth and the eyes ([`crate::copy::remesh`]).
    Remesh,
}

impl CopyMethod {
    /// `collapse` or `remesh`.
    pub fn parse(s: &str) -> Option<CopyMethod> {
        match s {
            "collapse" => Some(CopyMethod::Collapse),
            "remesh" => Some(CopyMethod::Remesh),
            _ => None,
        }
    }
}

impl LargeFaceParams {
    /// Documented range of [`LargeFaceParams::max_triangles`] and
    /// [`LargeFaceParams::target_triangles`]. At 6000 front triangles the shell has about
    /// 13 000 elements and the dense solve needs about 12 GB and tens of minutes on 2 cores;
    /// below 100 triangles a face has no room for its features.
    pub const TRIANGLES_RANGE: std::ops::RangeInclusive<usize> = 100..=6000;

    /// Checks every field against its documented range: both triangle counts in
    /// [`LargeFaceParams::TRIANGLES_RANGE`] (a target at or above a face's own size leaves it
    /// whole), `max_error`
    /// finite and positive, `normal_weight` in [0, 100], `border_spacing` in [0, 10].
    /// Returns the first field outside as `(name, value, range)`.
    ///
    /// ```
    /// use facebem::copy::LargeFaceParams;
    /// assert!(LargeFaceParams::default().validate().is_ok());
    /// let p = LargeFaceParams { target_triangles: 1_000_000, ..LargeFaceParams::default() };
    /// let (name, _, range) = p.validate().unwrap_err();
    /// assert_eq!((name, range.as_str()), ("target_triangles", "[100, 6000]"));
    /// ```
    pub fn validate(&self) -> Result<(), (&'static str, String, String)> {
        let range = Self::TRIANGLES_RANGE;
        let bounds = format!("[{}, {}]", range.start(), range.end());
        if !range.contains(&self.max_triangles) {
            return Err(("max_triangles", self.max_triangles.to_string(), bounds));
        }
        if !range.contains(&self.target_triangles) {
            return Err((
                "target_triangles",
                self.target_triangles.to_string(),
                bounds,
            ));
        }
        if !(self.max_error.is_finite() && self.max_error > 0.0) {
            return Err((
                "max_error",
                format!("{:?}", self.max_error),
                "(0, inf)".into(),
            ));
        }
        if !(0.0..=100.0).contains(&self.normal_weight) {
            let value = format!("{:?}", self.normal_weight);
            return Err(("normal_weight", value, "[0, 100]".into()));
        }
        if !(0.0..=10.0).contains(&self.border_spacing) {
            let value = format!("{:?}", self.border_spacing);
            return Err(("border_spacing", value, "[0, 10]".into()));
        }
        Ok(())
    }
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
            border_spacing: 0.5,
            method: CopyMethod::Collapse,
        }
    }
}

/// Errors from simplification.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
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
    /// Remeshing failed ([`CopyMethod::Remesh`]).
    #[error(transparent)]
    Remesh(#[from] crate::copy::remesh::RemeshError),
}

/// A reduced copy of a mesh (simplified and/or with rolled-in parts peeled off); its vertices
/// are a subset of the original ones, except for a remeshed copy ([`CopyMethod::Remesh`]),
/// whose vertices are new points of the original surface.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Simplified {
    /// Vertex positions (copies of original positions; points of the original surface for a
    /// remeshed copy).
    pub vertices: Vec<DVec3>,
    /// Triangles indexing [`Simplified::vertices`].
    pub triangles: Vec<[u32; 3]>,
    /// For each simplified vertex, its index in the original mesh (for a remeshed copy: the
    /// original vertex closest to it, the vertex itself for a kept one).
    pub original_vertex: Vec<u32>,
}

impl Simplified {
    /// The whole mesh as a (trivial) copy of itself.
    pub fn whole(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Simplified {
        Simplified {
            vertices: vertices.to_vec(),
            triangles: triangles.to_vec(),
            original_vertex: (0..vertices.len() as u32).collect(),
        }
    }

    /// The copy made of `triangles` (indexing this copy's vertices), with only the vertices they
    /// use, mapped to the original mesh.
    ///
    /// ```
    /// use facebem::copy::Simplified;
    /// use glam::DVec3;
    /// let v = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE];
    /// let whole = Simplified::whole(&v, &[[0, 1, 2], [1, 3, 2]]);
    /// let part = whole.subset(&[[1, 3, 2]]);
    /// assert_eq!(part.triangles, vec![[0, 1, 2]]);
    /// assert_eq!(part.original_vertex, vec![1, 3, 2]);
    /// ```
    pub fn subset(&self, triangles: &[[u32; 3]]) -> Simplified {
        let mut new_index = vec![u32::MAX; self.vertices.len()];
        let mut kept: Vec<u32> = Vec::new();
        let triangles = triangles
            .iter()
            .map(|t| {
                t.map(|v| {
                    if new_index[v as usize] == u32::MAX {
                        new_index[v as usize] = kept.len() as u32;
                        kept.push(v);
                    }
                    new_index[v as usize]
                })
            })
            .collect();
        Simplified {
            vertices: kept.iter().map(|&v| self.vertices[v as usize]).collect(),
            triangles,
            original_vertex: kept
                .iter()
                .map(|&v| self.original_vertex[v as usize])
                .collect(),
        }
    }
}

/// Simplifies a triangle mesh to about `params.target_triangles` with every border vertex
/// locked, within `params.max_error`, with vertex normals weighted by `params.normal_weight`.
///
/// ```
/// use facebem::copy::{LargeFaceParams, simplify};
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
    simplify_anchored(vertices, triangles, params, &[], &[])
}

/// [`simplify`](fn@simplify) with the vertices flagged in `extra_locks` locked besides the
/// resampled border, and the vertices flagged in `anchors` kept, the borders resampled from the
/// anchored border vertices ([`border_locks_anchored`]). One flag per vertex in each; a shorter
/// slice leaves the rest unflagged.
///
/// ```
/// use facebem::copy::{LargeFaceParams, simplify_anchored};
/// let mesh = facebem::input::default_face().unwrap();
/// let params = LargeFaceParams { target_triangles: 200, ..LargeFaceParams::default() };
/// let mut anchors = vec![false; mesh.vertices.len()];
/// anchors[61] = true;
/// let s = simplify_anchored(&mesh.vertices, &mesh.triangles, &params, &[], &anchors).unwrap();
/// assert!(s.original_vertex.contains(&61));
/// ```
pub fn simplify_anchored(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    params: &LargeFaceParams,
    extra_locks: &[bool],
    anchors: &[bool],
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
    // Nothing to remove. meshoptimizer asserts (an abort, not an error) on a target above the
    // mesh's own size: regression `a_target_above_the_face_size_does_not_abort` (issue 36).
    if target_triangles >= triangles.len() {
        return Ok(Simplified::whole(vertices, triangles));
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
    // Resampled borders need the boundary loops; a mesh that is not a valid surface (no
    // loops to walk) keeps every border vertex instead.
    let loops = (params.border_spacing > 0.0)
        .then(|| face_prep::topology::validate(vertices, triangles).ok())
        .flatten();
    let (mut locks, options) = match loops {
        Some(loops) => {
            let spacing =
                params.border_spacing * target_edge_length(vertices, triangles, target_triangles);
            (
                border_locks_anchored(vertices, &loops, spacing, anchors),
                meshopt::SimplifyOptions::None,
            )
        }
        None => (
            vec![false; vertices.len()],
            meshopt::SimplifyOptions::LockBorder,
        ),
    };
    for (lock, &extra) in locks.iter_mut().zip(extra_locks) {
        *lock |= extra;
    }
    for (lock, &anchor) in locks.iter_mut().zip(anchors) {
        *lock |= anchor;
    }
    let result = match meshopt::VertexDataAdapter::new(&bytes, 12, 0) {
        Ok(adapter) => meshopt::simplify_with_attributes_and_locks(
            &indices,
            &adapter,
            &normals,
            &[weight; 3],
            12,
            // The wrapper passes the slice's pointer to C, which reads one flag per vertex.
            &locks,
            target_triangles * 3,
            params.max_error,
            options,
            None,
        ),
        // Unreachable for 12-byte f32 triples; fall back to the unsimplified mesh.
        Err(_) => indices,
    };
    if result.is_empty() {
        return Err(SimplifyError::Empty(triangles.len()));
    }
    let result: Vec<[u32; 3]> = result.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    Ok(Simplified::whole(vertices, triangles).subset(&result))
}

/// Edge length of an equilateral triangle of the mesh's mean area at `target` triangles.
fn target_edge_length(vertices: &[DVec3], triangles: &[[u32; 3]], target: usize) -> f64 {
    let area: f64 = triangles
        .iter()
        .map(|t| face_prep::topology::triangle_area(t.map(|i| vertices[i as usize])))
        .sum();
    (4.0 * area / (3f64.sqrt() * target.max(1) as f64)).sqrt()
}

/// Border vertices to lock so that the contours keep a vertex about every `spacing` of arc
/// length: on each boundary loop (as [`face_prep::topology::validate`] returns them), its first
/// vertex and then each vertex at least `spacing` of arc length after the last locked one
/// (and at least half of it before the first).
pub fn border_locks(vertices: &[DVec3], loops: &[Vec<u32>], spacing: f64) -> Vec<bool> {
    border_locks_anchored(vertices, loops, spacing, &[])
}

/// [`border_locks`] resampled from anchors: every border vertex flagged in `anchors` (one flag
/// per vertex; a shorter slice leaves the rest unflagged) is locked, and each loop holding one
/// is resampled from its anchors, so no other lock falls within half a spacing of an anchor
/// (a lock beside a kept mouth corner would leave a sliver there). Loops without an anchor
/// are resampled as [`border_locks`] does.
///
/// ```
/// use facebem::copy::border_locks_anchored;
/// use glam::DVec3;
/// // A square loop of 8 vertices, 1 apart; vertex 3 anchored, spacing 2.
/// let v: Vec<DVec3> = [(0., 0.), (1., 0.), (2., 0.), (2., 1.), (2., 2.), (1., 2.), (0., 2.), (0., 1.)]
///     .iter().map(|&(x, y)| DVec3::new(x, y, 0.0)).collect();
/// let lp = vec![(0..8u32).collect::<Vec<_>>()];
/// let mut anchors = vec![false; 8];
/// anchors[3] = true;
/// let locks = border_locks_anchored(&v, &lp, 2.0, &anchors);
/// let locked: Vec<usize> = (0..8).filter(|&i| locks[i]).collect();
/// assert_eq!(locked, vec![1, 3, 5, 7]);
/// ```
pub fn border_locks_anchored(
    vertices: &[DVec3],
    loops: &[Vec<u32>],
    spacing: f64,
    anchors: &[bool],
) -> Vec<bool> {
    let mut locks = vec![false; vertices.len()];
    let p = |v: u32| vertices[v as usize];
    let anchored = |v: u32| anchors.get(v as usize).copied().unwrap_or(false);
    for lp in loops {
        let n = lp.len();
        let Some(first) = lp
            .iter()
            .position(|&v| anchored(v))
            .or((n > 0).then_some(0))
        else {
            continue;
        };
        // The loop from its first anchor (or first vertex), closed back onto it.
        let walk: Vec<u32> = (0..=n).map(|k| lp[(first + k) % n]).collect();
        // The next anchor ahead of each walk vertex (the closing start counts).
        let mut next_anchor = vec![walk[walk.len() - 1]; walk.len()];
        for k in (0..walk.len() - 1).rev() {
            let after = walk[k + 1];
            next_anchor[k] = if anchored(after) {
                after
            } else {
                next_anchor[k + 1]
            };
        }
        locks[walk[0] as usize] = true;
        let mut since = 0.0;
        for k in 1..walk.len() - 1 {
            since += p(walk[k - 1]).distance(p(walk[k]));
            let v = walk[k];
            if anchored(v)
                || (since >= spacing && p(v).distance(p(next_anchor[k])) >= 0.5 * spacing)
            {
                locks[v as usize] = true;
                since = 0.0;
            }
        }
    }
    locks
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::transfer::Transfer;

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
        let on_border = |i: usize| {
            let (x, y) = (i % 31, i / 31);
            x == 0 || y == 0 || x == 30 || y == 30
        };
        // Every border vertex locked.
        let all_locked = LargeFaceParams {
            target_triangles: 300,
            border_spacing: 0.0,
            ..LargeFaceParams::default()
        };
        let s = simplify(&vertices, &triangles, &all_locked).unwrap();
        for v in (0..vertices.len()).filter(|&v| on_border(v)) {
            assert!(
                s.original_vertex.contains(&(v as u32)),
                "border vertex {v} lost"
            );
        }
        // Resampled border (the default): the border keeps only original border vertices,
        // fewer of them, none of the locked ones lost, and no gap longer than about twice the
        // spacing (2 x 0.5 target edge lengths, ≈ 3.6 grid units at 300 triangles).
        let params = LargeFaceParams {
            target_triangles: 300,
            ..LargeFaceParams::default()
        };
        let s = simplify(&vertices, &triangles, &params).unwrap();
        assert!(s.triangles.len() < 600, "{} triangles", s.triangles.len());
        let spacing = params.border_spacing * target_edge_length(&vertices, &triangles, 300);
        let loops = face_prep::topology::validate(&vertices, &triangles).unwrap();
        let locks = border_locks(&vertices, &loops, spacing);
        let kept: Vec<usize> = s.original_vertex.iter().map(|&v| v as usize).collect();
        let kept_border: Vec<usize> = kept.iter().copied().filter(|&v| on_border(v)).collect();
        assert!(
            kept_border.len() < 120,
            "{} border vertices",
            kept_border.len()
        );
        for v in (0..vertices.len()).filter(|&v| locks[v]) {
            assert!(kept.contains(&v), "locked border vertex {v} lost");
        }
        let sb = face_prep::topology::validate(&s.vertices, &s.triangles).unwrap();
        assert_eq!(sb.len(), 1);
        for &v in &sb[0] {
            assert!(on_border(s.original_vertex[v as usize] as usize));
        }
        for v in (0..vertices.len()).filter(|&v| on_border(v)) {
            let gap = kept_border
                .iter()
                .map(|&k| vertices[k].distance(vertices[v]))
                .fold(f64::INFINITY, f64::min);
            assert!(
                gap <= 2.0 * spacing,
                "border vertex {v} is {gap} from the kept border"
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
