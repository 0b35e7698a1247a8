//! Simplification of a large face that does not depend on how its file is written.
//!
//! [`crate::copy::simplify`](fn@crate::copy::simplify) hands the mesh to meshoptimizer as it comes: the collapses it
//! picks depend on the vertex and triangle order, and its float32 input on the rotation and
//! scale, so the same face written differently was simulated on a different copy (issue 10
//! measured 3–13 % RMS differences in the happy field), and a mirror-symmetric face on an
//! asymmetric copy (ICT 13k's left and right smiles differed by up to 90 %).
//!
//! [`simplify_face`] first moves the face into its canonical frame
//! ([`face_prep::orient::canonical_frame`], from the eyes and the mouth) in interocular units,
//! rounds the coordinates to a 2⁻²⁰ grid (exact in float32, so a rotated or rescaled copy gives
//! the simplifier bit-identical numbers), and sorts vertices and triangles by position. When the
//! face is mirror-symmetric about its midplane (every vertex has a mirror image within
//! [`MIRROR_TOLERANCE_IOD`] and every triangle a mirrored triangle, as on the ICT-FaceKit mesh),
//! only the left half is simplified and the right half is its mirror image, so the simulated
//! copy is symmetric too. The midline stays a chain of midline vertices: its vertices only
//! collapse along it and the points where it meets a contour are locked.

use crate::copy::{LargeFaceParams, Simplified, SimplifyError, simplify_anchored};
use glam::DVec3;
use std::collections::HashMap;

/// Largest distance, in interocular distances, between a vertex and the mirror image of its
/// partner for a face to count as mirror-symmetric: 2·10⁻³ (0.13 mm on an adult face). The ICT
/// mesh's partners lie within 0.05 mm (8·10⁻⁴); scans and decimated copies are off by 0.1–8 mm.
pub const MIRROR_TOLERANCE_IOD: f64 = 2e-3;

/// Quantum of the canonical coordinates, in interocular distances (2⁻²⁰ ≈ 0.06 µm).
const QUANTUM: f64 = 1.0 / (1u64 << 20) as f64;

/// How a face was simplified by [`simplify_face`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub enum SimplifyPath {
    /// Left half simplified and mirrored (a mirror-symmetric face).
    Mirrored,
    /// Whole face simplified in canonical order (not mirror-symmetric).
    Canonical,
    /// The face has no canonical frame (not four loops, say): simplified as written.
    AsWritten,
    /// Remeshed as the left half of the mirror-symmetric face, mirrored.
    RemeshedMirrored,
    /// Remeshed in the face's canonical frame and order (not mirror-symmetric).
    Remeshed,
    /// Remeshed as written, without a canonical frame.
    RemeshedAsWritten,
    /// [`SimplifyPath::Mirrored`] of the mirror-meshed stand-in of a face that is
    /// mirror-symmetric in shape but not in its triangles ([`crate::copy::symmetrize`]).
    SymmetrizedMirrored,
    /// [`SimplifyPath::RemeshedMirrored`] of that stand-in.
    RemeshedSymmetrized,
    /// Not reduced, only made mirror-meshed: the cut left half and its mirror image (a face
    /// below the simplification threshold, symmetric in shape but not in its triangles).
    Symmetrized,
}

impl SimplifyPath {
    /// Whether the copy was made by edge collapses (rather than remeshed, or not reduced).
    ///
    /// ```
    /// use facebem::copy::simplify::SimplifyPath;
    /// assert!(SimplifyPath::SymmetrizedMirrored.is_collapse());
    /// assert!(!SimplifyPath::Remeshed.is_collapse());
    /// assert!(!SimplifyPath::Symmetrized.is_collapse());
    /// ```
    pub fn is_collapse(self) -> bool {
        matches!(
            self,
            SimplifyPath::Mirrored
                | SimplifyPath::Canonical
                | SimplifyPath::AsWritten
                | SimplifyPath::SymmetrizedMirrored
        )
    }

    /// The path of a face simulated as its mirror-meshed stand-in, from the stand-in's own
    /// (`None` when the stand-in was not reduced).
    ///
    /// ```
    /// use facebem::copy::simplify::SimplifyPath;
    /// assert_eq!(SimplifyPath::of_stand_in(None), SimplifyPath::Symmetrized);
    /// assert_eq!(
    ///     SimplifyPath::of_stand_in(Some(SimplifyPath::Mirrored)),
    ///     SimplifyPath::SymmetrizedMirrored
    /// );
    /// ```
    pub fn of_stand_in(inner: Option<SimplifyPath>) -> SimplifyPath {
        match inner {
            None => SimplifyPath::Symmetrized,
            Some(SimplifyPath::Mirrored) => SimplifyPath::SymmetrizedMirrored,
            Some(SimplifyPath::RemeshedMirrored) => SimplifyPath::RemeshedSymmetrized,
            Some(other) => other,
        }
    }

    /// A few words for reports, to follow "simplified".
    ///
    /// ```
    /// use facebem::copy::simplify::SimplifyPath;
    /// assert_eq!(SimplifyPath::Canonical.describe(), "in the face's canonical frame and order");
    /// ```
    pub fn describe(self) -> &'static str {
        match self {
            SimplifyPath::Mirrored => "as a mirrored half of the mirror-symmetric face",
            SimplifyPath::Canonical => "in the face's canonical frame and order",
            SimplifyPath::AsWritten => "as written, without a canonical frame",
            SimplifyPath::RemeshedMirrored => {
                "by remeshing the left half of the mirror-symmetric face and mirroring it"
            }
            SimplifyPath::Remeshed => "by remeshing in the face's canonical frame and order",
            SimplifyPath::RemeshedAsWritten => "by remeshing as written, without a canonical frame",
            SimplifyPath::SymmetrizedMirrored => {
                "as a mirrored half, cut along the midplane (symmetric in shape, not in its triangles)"
            }
            SimplifyPath::RemeshedSymmetrized => {
                "by remeshing a half cut along the midplane and mirroring it (symmetric in shape, not in its triangles)"
            }
            SimplifyPath::Symmetrized => {
                "only by mirroring a half cut along the midplane (symmetric in shape, not in its triangles)"
            }
        }
    }
}

/// Simplifies a face (a valid front-face mesh with four loops) independently of its vertex
/// order, rotation, translation and scale, and mirror-symmetrically when the face is
/// mirror-symmetric. Falls back to [`crate::copy::simplify`](fn@crate::copy::simplify) of the mesh as written when
/// it has no canonical frame. The copy's vertices are vertices of the input.
///
/// The vertices `keep` (indices into `vertices`; out-of-range ones are ignored) stay in the
/// copy. Kept border vertices anchor the border's resampling
/// ([`crate::copy::border_locks_anchored`]). On a mirror-symmetric face a kept vertex keeps its
/// mirror image too.
///
/// ```
/// use facebem::copy::simplify::{SimplifyPath, simplify_face};
/// use facebem::copy::LargeFaceParams;
/// let mesh = facebem::input::default_face().unwrap();
/// let params = LargeFaceParams { target_triangles: 400, ..LargeFaceParams::default() };
/// let (copy, path) = simplify_face(&mesh.vertices, &mesh.triangles, &params, &[7]).unwrap();
/// // MediaPipe's canonical face is exactly mirror-symmetric.
/// assert_eq!(path, SimplifyPath::Mirrored);
/// assert!(copy.triangles.len() < 600);
/// assert!(copy.original_vertex.contains(&7));
/// ```
pub fn simplify_face(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    params: &LargeFaceParams,
    keep: &[u32],
) -> Result<(Simplified, SimplifyPath), SimplifyError> {
    let flags = |count: usize, index_of: &dyn Fn(u32) -> u32| {
        let mut flags = vec![false; count];
        for &v in keep.iter().filter(|&&v| (v as usize) < vertices.len()) {
            if let Some(f) = flags.get_mut(index_of(v) as usize) {
                *f = true;
            }
        }
        flags
    };
    let Some(canon) = Canonical::of(vertices, triangles) else {
        let s = simplify_anchored(
            vertices,
            triangles,
            params,
            &[],
            &flags(vertices.len(), &|v| v),
        )?;
        return Ok((s, SimplifyPath::AsWritten));
    };
    let mut canonical_of = vec![0u32; vertices.len()];
    for (c, &v) in canon.input_vertex.iter().enumerate() {
        canonical_of[v as usize] = c as u32;
    }
    let kept = flags(canon.positions.len(), &|v| canonical_of[v as usize]);
    let mirrored = mirror_map(&canon.positions, &canon.triangles)
        .and_then(|mirror| simplify_mirrored(&canon, &mirror, params, &kept));
    let (s, path) = match mirrored {
        Some(s) => (s, SimplifyPath::Mirrored),
        None => {
            let s = simplify_anchored(&canon.positions, &canon.triangles, params, &[], &kept)?;
            (s, SimplifyPath::Canonical)
        }
    };
    let original_vertex: Vec<u32> = s
        .original_vertex
        .iter()
        .map(|&c| canon.input_vertex[c as usize])
        .collect();
    Ok((
        Simplified {
            vertices: original_vertex
                .iter()
                .map(|&v| vertices[v as usize])
                .collect(),
            triangles: s.triangles,
            original_vertex,
        },
        path,
    ))
}

/// A face in its canonical frame: positions in interocular units on the 2⁻²⁰ grid, vertices
/// sorted by (y, x, z), each triangle rotated to start at its smallest index, triangles sorted.
pub(crate) struct Canonical {
    pub(crate) positions: Vec<DVec3>,
    pub(crate) triangles: Vec<[u32; 3]>,
    /// Input vertex of each canonical vertex.
    pub(crate) input_vertex: Vec<u32>,
    /// Number of boundary loops (four for a face).
    pub(crate) loop_count: usize,
    /// The mouth loop (canonical vertices).
    pub(crate) mouth: Vec<u32>,
    /// The eye loops (canonical vertices).
    pub(crate) eyes: [Vec<u32>; 2],
    /// Input frame from canonical interocular units.
    pub(crate) input_from_grid: glam::DAffine3,
}

impl Canonical {
    /// A copy of this canonical mesh (`s`, its vertices indexing this one's) in the input's
    /// frame, its vertices mapped to the input's.
    pub(crate) fn to_input(&self, s: &Simplified) -> Simplified {
        Simplified {
            vertices: s
                .vertices
                .iter()
                .map(|&p| self.input_from_grid.transform_point3(p))
                .collect(),
            triangles: s.triangles.clone(),
            original_vertex: s
                .original_vertex
                .iter()
                .map(|&c| self.input_vertex[c as usize])
                .collect(),
        }
    }

    pub(crate) fn of(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Option<Canonical> {
        let loops = face_prep::topology::validate(vertices, triangles).ok()?;
        let (canonical_from_input, face_loops) =
            face_prep::orient::canonical_frame(vertices, triangles, &loops).ok()?;
        let iod = face_prep::orient::loop_centroid(vertices, &face_loops.eye_l).distance(
            face_prep::orient::loop_centroid(vertices, &face_loops.eye_r),
        );
        if !(iod.is_finite() && iod > 0.0) {
            return None;
        }
        let grid: Vec<[i64; 3]> = vertices
            .iter()
            .map(|&p| {
                let q = canonical_from_input.transform_point3(p) / iod / QUANTUM;
                [q.x.round() as i64, q.y.round() as i64, q.z.round() as i64]
            })
            .collect();
        let mut input_vertex: Vec<u32> = (0..vertices.len() as u32).collect();
        input_vertex.sort_by_key(|&v| {
            let g = grid[v as usize];
            (g[1], g[0], g[2], v)
        });
        let mut canonical_of = vec![0u32; vertices.len()];
        for (c, &v) in input_vertex.iter().enumerate() {
            canonical_of[v as usize] = c as u32;
        }
        let mut tris: Vec<[u32; 3]> = triangles
            .iter()
            .map(|t| rotate_to_smallest(t.map(|v| canonical_of[v as usize])))
            .collect();
        tris.sort_unstable();
        let positions = input_vertex
            .iter()
            .map(|&v| {
                let g = grid[v as usize];
                DVec3::new(g[0] as f64, g[1] as f64, g[2] as f64) * QUANTUM
            })
            .collect();
        Some(Canonical {
            positions,
            triangles: tris,
            input_vertex,
            loop_count: loops.len(),
            mouth: face_loops
                .mouth
                .iter()
                .map(|&v| canonical_of[v as usize])
                .collect(),
            eyes: [&face_loops.eye_l, &face_loops.eye_r]
                .map(|lp| lp.iter().map(|&v| canonical_of[v as usize]).collect()),
            input_from_grid: canonical_from_input.inverse()
                * glam::DAffine3::from_scale(glam::DVec3::splat(iod)),
        })
    }
}

/// The triangle with the same winding, starting at its smallest index.
fn rotate_to_smallest(t: [u32; 3]) -> [u32; 3] {
    let k = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
    [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
}

/// For a face in canonical interocular units, each vertex's mirror image about x = 0, if the
/// face is mirror-symmetric: every vertex has a partner within [`MIRROR_TOLERANCE_IOD`] of its
/// mirrored position, the pairing is an involution, vertices that are their own partner lie on
/// the midplane, every triangle's mirror image is a triangle, and no triangle reaches across the
/// midplane. `None` otherwise.
///
/// ```
/// use facebem::copy::simplify::mirror_map;
/// use glam::DVec3;
/// // Two triangles mirrored about x = 0, sharing the midline edge 0–1.
/// let v = [DVec3::new(0.0, 0.0, 0.0), DVec3::new(0.0, 1.0, 0.0),
///          DVec3::new(1.0, 0.5, 0.0), DVec3::new(-1.0, 0.5, 0.0)];
/// let m = mirror_map(&v, &[[0, 2, 1], [0, 1, 3]]).unwrap();
/// assert_eq!(m, vec![0, 1, 3, 2]);
/// assert!(mirror_map(&v, &[[0, 2, 1]]).is_none());
/// ```
pub fn mirror_map(positions: &[DVec3], triangles: &[[u32; 3]]) -> Option<Vec<u32>> {
    let tol = MIRROR_TOLERANCE_IOD;
    let cell = |p: DVec3| {
        [
            (p.x / tol).floor() as i64,
            (p.y / tol).floor() as i64,
            (p.z / tol).floor() as i64,
        ]
    };
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    for (v, &p) in positions.iter().enumerate() {
        grid.entry(cell(p)).or_default().push(v as u32);
    }
    let mut mirror = Vec::with_capacity(positions.len());
    for &p in positions {
        let q = DVec3::new(-p.x, p.y, p.z);
        let c = cell(q);
        let mut best: Option<(f64, u32)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(list) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) else {
                        continue;
                    };
                    for &w in list {
                        let d = positions[w as usize].distance(q);
                        if d <= tol && best.is_none_or(|(bd, _)| d < bd) {
                            best = Some((d, w));
                        }
                    }
                }
            }
        }
        mirror.push(best?.1);
    }
    for (v, &m) in mirror.iter().enumerate() {
        if mirror[m as usize] != v as u32 {
            return None;
        }
        if m == v as u32 && positions[v].x.abs() > tol {
            return None;
        }
    }
    let key = |t: [u32; 3]| {
        let mut s = t;
        s.sort_unstable();
        s
    };
    let set: std::collections::HashSet<[u32; 3]> = triangles.iter().map(|&t| key(t)).collect();
    for &t in triangles {
        if !set.contains(&key(t.map(|v| mirror[v as usize]))) {
            return None;
        }
        side(t, &mirror, positions)?;
    }
    Some(mirror)
}

/// +1 for a triangle on the left (+x) of the midplane, −1 on the right; `None` for a triangle
/// that reaches across the midplane or lies in it.
fn side(t: [u32; 3], mirror: &[u32], positions: &[DVec3]) -> Option<i8> {
    let mut s = 0i8;
    for v in t {
        if mirror[v as usize] == v {
            continue;
        }
        let sv = if positions[v as usize].x > 0.0 { 1 } else { -1 };
        if s != 0 && s != sv {
            return None;
        }
        s = sv;
    }
    (s != 0).then_some(s)
}

/// How often [`simplify_mirrored`] locks more vertices after an interior midline edge.
const MAX_MIDLINE_RETRIES: usize = 8;

/// Ends of the edges of `half` that join two midline vertices through the half's interior (held
/// by two triangles, where a midline edge is a border held by one).
fn midline_chords(half: &Simplified, on_midline: &dyn Fn(u32) -> bool) -> Vec<u32> {
    let mut count: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &half.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if on_midline(a) && on_midline(b) {
                *count.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
    }
    let mut ends: Vec<u32> = count
        .into_iter()
        .filter(|&(_, c)| c > 1)
        .flat_map(|((a, b), _)| [a, b])
        .collect();
    ends.sort_unstable();
    ends.dedup();
    ends
}

/// The left half of a mirror-symmetric canonical face, ready to be reduced and mirrored.
pub(crate) struct LeftHalf {
    /// The half, its vertices mapped to the canonical face's.
    pub(crate) half: Simplified,
    /// Per half vertex: kept (it or its mirror image is flagged in `kept`).
    pub(crate) anchors: Vec<bool>,
    /// Per half vertex: where the midline meets a contour (a border edge of the half to a
    /// vertex off the midline); moving them would pull the cut off the midplane.
    pub(crate) locks: Vec<bool>,
}

/// The left half of `canon` (mirror images `mirror`, kept vertices `kept`); `None` when it is
/// not a valid surface.
pub(crate) fn left_half(canon: &Canonical, mirror: &[u32], kept: &[bool]) -> Option<LeftHalf> {
    let whole = Simplified::whole(&canon.positions, &canon.triangles);
    let left: Vec<[u32; 3]> = canon
        .triangles
        .iter()
        .copied()
        .filter(|&t| side(t, mirror, &canon.positions) == Some(1))
        .collect();
    let half = whole.subset(&left);
    let half_loops = face_prep::topology::validate(&half.vertices, &half.triangles).ok()?;
    let on_midline = |h: u32| {
        let c = half.original_vertex[h as usize];
        mirror[c as usize] == c
    };
    let is_kept = |c: u32| {
        kept.get(c as usize).copied().unwrap_or(false)
            || kept
                .get(mirror[c as usize] as usize)
                .copied()
                .unwrap_or(false)
    };
    let anchors: Vec<bool> = half.original_vertex.iter().map(|&c| is_kept(c)).collect();
    let mut locks = vec![false; half.vertices.len()];
    for lp in &half_loops {
        for i in 0..lp.len() {
            let (a, b) = (lp[i], lp[(i + 1) % lp.len()]);
            if on_midline(a) != on_midline(b) {
                let m = if on_midline(a) { a } else { b };
                locks[m as usize] = true;
            }
        }
    }
    Some(LeftHalf {
        half,
        anchors,
        locks,
    })
}

/// Simplifies the left half of a mirror-symmetric canonical face and mirrors it. `None` when the
/// half or the glued result is not a valid surface with the face's loop count.
fn simplify_mirrored(
    canon: &Canonical,
    mirror: &[u32],
    params: &LargeFaceParams,
    kept: &[bool],
) -> Option<Simplified> {
    let whole = Simplified::whole(&canon.positions, &canon.triangles);
    let LeftHalf {
        half,
        anchors,
        mut locks,
    } = left_half(canon, mirror, kept)?;
    let on_midline = |h: u32| {
        let c = half.original_vertex[h as usize];
        mirror[c as usize] == c
    };
    let half_params = LargeFaceParams {
        target_triangles: (params.target_triangles / 2).max(16),
        ..params.clone()
    };
    // A collapse onto a midline vertex can join two midline vertices by an edge through the
    // half's interior, which the mirror image would share (an edge of four triangles). Where
    // that happens, the vertices around both ends are locked and the half simplified again.
    let neighbours = face_prep::shell::vertex_adjacency(half.vertices.len(), &half.triangles);
    let mut kept = Vec::new();
    for _ in 0..MAX_MIDLINE_RETRIES {
        let s = simplify_anchored(
            &half.vertices,
            &half.triangles,
            &half_params,
            &locks,
            &anchors,
        )
        .ok()?;
        let across = midline_chords(&s, &|v| on_midline(s.original_vertex[v as usize]));
        kept = s
            .triangles
            .iter()
            .map(|t| t.map(|v| half.original_vertex[s.original_vertex[v as usize] as usize]))
            .collect();
        if across.is_empty() {
            break;
        }
        for v in across {
            let h = s.original_vertex[v as usize];
            for &w in &neighbours[h as usize] {
                if !on_midline(w) {
                    locks[w as usize] = true;
                }
            }
        }
    }
    let mut glued = kept.clone();
    glued.extend(
        kept.iter()
            .map(|t| [t[0], t[2], t[1]].map(|v| mirror[v as usize])),
    );
    let result = whole.subset(&glued);
    let loops = face_prep::topology::validate(&result.vertices, &result.triangles).ok()?;
    (loops.len() == canon.loop_count).then_some(result)
}
