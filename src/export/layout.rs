//! The user's own vertex layout for glTF exports.
//!
//! glTF stores one POSITION, TEXCOORD_0 and NORMAL per vertex, whereas an OBJ corner picks a
//! position (`v`), a texture coordinate (`vt`) and a normal (`vn`) independently. An
//! [`ExportLayout`] lists the glTF vertices of the user's mesh:
//!
//! - **OBJ input**: glTF vertex `i` is `v` line `i` (0-based, file order) for every `i` below the
//!   number of `v` lines `N`, with the `vt`/`vn` of the first face corner that uses it. A later
//!   corner that uses the same `v` with another `vt` or `vn` (a UV seam or a hard edge) gets a
//!   copy of that vertex appended after the `N` originals. The map back is
//!   [`ExportLayout::input_index`]: glTF vertex `j` is a copy of `v` line `input_index[j]`
//!   (`input_index[i] == i` for `i < N`); the export writes the tail `input_index[N..]` into
//!   the glTF as `meshes[0].extras.seamCopyOf`. `v` lines no face uses are still written, at
//!   their own position, with zero morph deltas.
//! - **any other input** (glTF, a rig file without its OBJ text): the welded vertices of the
//!   [`crate::MuscleBasis`] in their order ([`ExportLayout::welded`]).
//!
//! Texture coordinates are converted to glTF's convention (origin at the image's top left):
//! `TEXCOORD_0 = (u, 1 − v)` of the OBJ's `vt u v`.

use std::collections::HashMap;

use face_prep::ObjLineError;
use face_prep::obj_text::{self, ObjCorner as Corner};
use glam::DVec3;

/// Errors building an [`ExportLayout`] from an OBJ text.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum LayoutError {
    /// A line breaks the rules the face reader holds OBJ text to ([`face_prep::obj_text`]):
    /// a face corner refers to a `v`, `vt` or `vn` that does not come before it, a number is
    /// not finite.
    #[error(transparent)]
    Obj(#[from] ObjLineError),
    /// The OBJ has another number of `v` lines than the face mesh was loaded from.
    #[error("the OBJ has {found} `v` lines but the face mesh was loaded from {expected}")]
    VertexCount {
        /// Input positions of the face mesh.
        expected: usize,
        /// `v` lines in the text.
        found: usize,
    },
    /// A face uses a `v` line the face mesh did not keep.
    #[error("OBJ line {line}: `v` {vertex} is used by a face but not part of the face mesh")]
    UnusedVertex {
        /// 1-based line number of the face.
        line: usize,
        /// 1-based `v` index.
        vertex: usize,
    },
}

/// The glTF vertices of an export and where each one comes from (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct ExportLayout {
    /// Per glTF vertex: the welded vertex of the basis that gives its position and morph
    /// deltas, or `None` for an input position no face uses (written at
    /// [`ExportLayout::positions`], deltas 0).
    pub welded: Vec<Option<u32>>,
    /// Per glTF vertex: the input position (user frame, input units).
    pub positions: Vec<DVec3>,
    /// Per glTF vertex: the input position (OBJ `v` line, 0-based) it is a copy of.
    pub input_index: Vec<u32>,
    /// Number of input positions (`v` lines); glTF vertices from here on are seam copies.
    pub input_count: usize,
    /// Per glTF vertex: TEXCOORD_0 in glTF's convention, when the input has texture coordinates.
    pub uvs: Option<Vec<[f32; 2]>>,
    /// Per glTF vertex: the input's unit normal, when the input has normals (`None` entries:
    /// corners without one, or a zero `vn`; the export uses the computed normal there).
    pub normals: Option<Vec<Option<DVec3>>>,
    /// Triangles indexing the glTF vertices, in file order (polygons fan-triangulated as the
    /// importer does).
    pub triangles: Vec<[u32; 3]>,
}

impl ExportLayout {
    /// The welded vertices of a basis, in order: no texture coordinates, no input normals.
    pub fn welded(neutral: &[DVec3], triangles: &[[u32; 3]]) -> ExportLayout {
        let n = neutral.len();
        ExportLayout {
            welded: (0..n as u32).map(Some).collect(),
            positions: neutral.to_vec(),
            input_index: (0..n as u32).collect(),
            input_count: n,
            uvs: None,
            normals: None,
            triangles: triangles.to_vec(),
        }
    }

    /// The layout of an OBJ text whose face mesh mapped its `v` lines to welded vertices by
    /// `input_to_vertex` ([`face_prep::FaceMesh::input_to_vertex`]).
    ///
    /// ```
    /// use facebem::export::layout::ExportLayout;
    /// // Two triangles sharing the edge 1-3, with a UV seam at v 3.
    /// let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0.5 1\n\
    ///            f 1/1 2/2 3/3\nf 1/1 3/4 4/4\n";
    /// let map = [Some(0), Some(1), Some(2), Some(3)];
    /// let layout = ExportLayout::from_obj(obj, &map).unwrap();
    /// assert_eq!(layout.input_index, [0, 1, 2, 3, 2]); // glTF vertex 4 is a copy of v 3
    /// assert_eq!(layout.triangles, [[0, 1, 2], [0, 4, 3]]);
    /// assert_eq!(layout.uvs.unwrap()[4], [0.5, 0.0]); // (u, 1 - v)
    /// ```
    pub fn from_obj(text: &str, input_to_vertex: &[Option<u32>]) -> Result<Self, LayoutError> {
        Self::build_from_obj(text, input_to_vertex, None)
    }

    /// The layout of an OBJ text for the face mesh `mesh` loaded from it: as
    /// [`ExportLayout::from_obj`], and where the mouth or the eyes came closed and were cut
    /// open ([`face_prep::FaceMesh::lip_line`], [`face_prep::FaceMesh::lid_lines`]) each face
    /// corner on a cut line takes its own side's vertex. A `v` line only the lower lip (lid)
    /// uses becomes the lower side's vertex; one both sides share (a slit) stays the upper
    /// side's, and the lower side's corners get a copy appended, so the exported mouth can open.
    pub fn from_obj_for(text: &str, mesh: &face_prep::FaceMesh) -> Result<Self, LayoutError> {
        let lines: Vec<_> = mesh.lip_line.iter().chain(&mesh.lid_lines).collect();
        let sides = (!lines.is_empty()).then(|| CutSides::new(mesh, &lines));
        Self::build_from_obj(text, &mesh.input_to_vertex, sides.as_ref())
    }

    fn build_from_obj(
        text: &str,
        input_to_vertex: &[Option<u32>],
        sides: Option<&CutSides>,
    ) -> Result<Self, LayoutError> {
        // The reader's own rules: what it accepted parses here the same way.
        let obj = obj_text::parse(text)?;
        let positions = obj.positions;
        let tex = obj.texcoords;
        let nor: Vec<Option<DVec3>> = obj.normals.iter().map(|n| n.try_normalize()).collect();
        let faces: Vec<(usize, Vec<Corner>)> = obj
            .faces
            .into_iter()
            .filter(|f| f.corners.len() >= 3)
            .map(|f| (f.line, f.corners))
            .collect();
        if positions.len() != input_to_vertex.len() {
            return Err(LayoutError::VertexCount {
                expected: input_to_vertex.len(),
                found: positions.len(),
            });
        }
        let n = positions.len();
        let any_vt = faces.iter().flat_map(|f| &f.1).any(|c| c.vt.is_some());
        let any_vn = faces.iter().flat_map(|f| &f.1).any(|c| c.vn.is_some());
        let mut layout = ExportLayout {
            welded: input_to_vertex.to_vec(),
            positions: positions.clone(),
            input_index: (0..n as u32).collect(),
            input_count: n,
            uvs: any_vt.then(|| vec![[0.0; 2]; n]),
            normals: any_vn.then(|| vec![None; n]),
            triangles: Vec::new(),
        };
        // Each polygon's welded vertices, its own side's where a contact line was cut.
        let mut resolved: Vec<Vec<u32>> = Vec::with_capacity(faces.len());
        for (line, corners) in &faces {
            let mut welded = Vec::with_capacity(corners.len());
            for c in corners {
                match input_to_vertex[c.v] {
                    Some(w) => welded.push(w),
                    None => {
                        return Err(LayoutError::UnusedVertex {
                            line: *line,
                            vertex: c.v + 1,
                        });
                    }
                }
            }
            if let Some(sides) = sides {
                sides.resolve(&mut welded);
            }
            resolved.push(welded);
        }
        // A `v` line keeps its own welded vertex when any face uses it so; one that only the
        // lower side of a cut line uses takes the lower side's.
        let mut keeps = vec![false; n];
        let mut other = vec![None; n];
        for ((_, corners), welded) in faces.iter().zip(&resolved) {
            for (c, &w) in corners.iter().zip(welded) {
                if Some(w) == input_to_vertex[c.v] {
                    keeps[c.v] = true;
                } else {
                    other[c.v].get_or_insert(w);
                }
            }
        }
        for v in 0..n {
            if !keeps[v] && other[v].is_some() {
                layout.welded[v] = other[v];
            }
        }
        // The (vt, vn) each `v` was first used with, and the copies made for other pairs or for
        // the other side of a cut line.
        let mut first_use: Vec<Option<(Option<usize>, Option<usize>)>> = vec![None; n];
        let mut copies: HashMap<(Corner, u32), u32> = HashMap::new();
        for ((_, corners), welded) in faces.iter().zip(&resolved) {
            let mut ids = Vec::with_capacity(corners.len());
            for (c, &w) in corners.iter().zip(welded) {
                let own = layout.welded[c.v] == Some(w);
                let id = match first_use[c.v] {
                    None if own => {
                        first_use[c.v] = Some((c.vt, c.vn));
                        layout.set_attributes(c.v, c, &tex, &nor);
                        c.v as u32
                    }
                    Some(pair) if own && pair == (c.vt, c.vn) => c.v as u32,
                    _ => *copies.entry((*c, w)).or_insert_with(|| {
                        let id = layout.welded.len();
                        layout.welded.push(Some(w));
                        layout.positions.push(positions[c.v]);
                        layout.input_index.push(c.v as u32);
                        if let Some(uvs) = &mut layout.uvs {
                            uvs.push([0.0; 2]);
                        }
                        if let Some(normals) = &mut layout.normals {
                            normals.push(None);
                        }
                        layout.set_attributes(id, c, &tex, &nor);
                        id as u32
                    }),
                };
                ids.push(id);
            }
            for k in 2..ids.len() {
                layout.triangles.push([ids[0], ids[k - 1], ids[k]]);
            }
        }
        Ok(layout)
    }

    /// Number of glTF vertices.
    pub fn len(&self) -> usize {
        self.welded.len()
    }

    /// Whether the layout has no vertices.
    pub fn is_empty(&self) -> bool {
        self.welded.is_empty()
    }

    fn set_attributes(&mut self, id: usize, c: &Corner, tex: &[[f64; 2]], nor: &[Option<DVec3>]) {
        if let (Some(uvs), Some(t)) = (&mut self.uvs, c.vt) {
            let [u, v] = tex[t];
            uvs[id] = [u as f32, (1.0 - v) as f32];
        }
        if let (Some(normals), Some(k)) = (&mut self.normals, c.vn) {
            normals[id] = nor[k];
        }
    }
}

/// An OBJ text with the vertices of a glTF face in the glTF's order: `v` = POSITION (world
/// frame), `vt` = TEXCOORD_0 converted to OBJ's convention `(u, 1 − v)`, `vn` = NORMAL, one
/// `f v/vt/vn` line per triangle. facebem keeps it as the layout of a glTF input
/// ([`crate::FaceModel::obj_source`]): glTF exports get the glTF's vertex order and
/// TEXCOORD_0 back (exactly: `1 − (1 − v)` is exact for an f32 `v` in [0, 1] in f64), and pose
/// exports are OBJ files with the glTF's texture coordinates.
///
/// ```
/// use face_prep::GltfFaceData;
/// use glam::DVec3;
/// let data = GltfFaceData {
///     positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
///     triangles: vec![[0, 1, 2]],
///     uvs: Some(vec![[0.0, 1.0], [1.0, 1.0], [0.0, 0.25]]),
///     normals: None,
///     triangle_material: vec![None],
/// };
/// let text = facebem::export::layout::obj_text_of_gltf(&data);
/// assert!(text.contains("vt 0 0.75\n"));
/// assert!(text.ends_with("f 1/1 2/2 3/3\n"));
/// ```
pub fn obj_text_of_gltf(data: &face_prep::GltfFaceData) -> String {
    use std::fmt::Write;
    let mut out = String::new();
    for p in &data.positions {
        let _ = writeln!(out, "v {} {} {}", p.x, p.y, p.z);
    }
    for [u, v] in data.uvs.iter().flatten() {
        let _ = writeln!(out, "vt {} {}", f64::from(*u), 1.0 - f64::from(*v));
    }
    for n in data.normals.iter().flatten() {
        let n = n.unwrap_or(DVec3::ZERO);
        let _ = writeln!(out, "vn {} {} {}", n.x, n.y, n.z);
    }
    for t in &data.triangles {
        out.push('f');
        for i in t.map(|i| i + 1) {
            let _ = match (data.uvs.is_some(), data.normals.is_some()) {
                (true, true) => write!(out, " {i}/{i}/{i}"),
                (true, false) => write!(out, " {i}/{i}"),
                (false, true) => write!(out, " {i}//{i}"),
                (false, false) => write!(out, " {i}"),
            };
        }
        out.push('\n');
    }
    out
}

/// The side a face corner on a cut contact line (lips or lids) belongs to: every triangle of
/// the face mesh by its corners, with the lower side's copies read as the upper side's vertices.
struct CutSides {
    /// Sorted corners (copies read as their upper vertex) → the triangle's own corners.
    by_key: HashMap<[u32; 3], [u32; 3]>,
    /// Lower-side copy → upper-side vertex.
    upper_of: HashMap<u32, u32>,
}

impl CutSides {
    fn new(
        mesh: &face_prep::FaceMesh,
        lines: &[&face_prep::frame::contact::ContactLine],
    ) -> CutSides {
        let upper_of: HashMap<u32, u32> = lines
            .iter()
            .flat_map(|line| line.lower.iter().zip(line.upper.iter().skip(1)))
            .map(|(&l, &u)| (l, u))
            .collect();
        let by_key = mesh
            .triangles
            .iter()
            .filter(|t| t.iter().any(|v| upper_of.contains_key(v)))
            .map(|t| {
                let mut key = t.map(|v| upper_of.get(&v).copied().unwrap_or(v));
                key.sort_unstable();
                (key, *t)
            })
            .collect();
        CutSides { by_key, upper_of }
    }

    /// Replaces the welded vertices of one polygon's corners (upper-side vertices on a line)
    /// by the vertices its triangles use (fan-triangulated as the reader does).
    fn resolve(&self, welded: &mut [u32]) {
        let original = welded.to_vec();
        for k in 2..original.len() {
            let corners = [0, k - 1, k];
            let mut key = corners.map(|i| original[i]);
            key.sort_unstable();
            let Some(actual) = self.by_key.get(&key) else {
                continue;
            };
            for i in corners {
                if let Some(&v) = actual
                    .iter()
                    .find(|&&v| self.upper_of.get(&v).copied().unwrap_or(v) == original[i])
                {
                    welded[i] = v;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn negative_indices_normals_and_quads() {
        let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\nvn 0 0 2\nvn 0 1 0\n\
                   f -5//-2 -4//-2 -3//-2 -2//-2\nf 1//2 3//1 4//1\n";
        let map = [Some(0), Some(1), Some(2), Some(3), None];
        let l = ExportLayout::from_obj(obj, &map).unwrap();
        assert_eq!(l.triangles, [[0, 1, 2], [0, 2, 3], [5, 2, 3]]);
        assert_eq!(l.input_index, [0, 1, 2, 3, 4, 0]);
        assert_eq!(l.welded[4], None);
        let normals = l.normals.unwrap();
        assert_eq!(normals[0], Some(DVec3::Z));
        assert_eq!(normals[5], Some(DVec3::Y));
        assert_eq!(normals[4], None);
        assert!(l.uvs.is_none());
    }

    #[test]
    fn bad_corners_and_counts_are_errors() {
        let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 4\n";
        let map = [Some(0), Some(1), Some(2)];
        assert!(matches!(
            ExportLayout::from_obj(obj, &map),
            Err(LayoutError::Obj(ObjLineError::UndefinedCorner {
                line: 4,
                ..
            }))
        ));
        assert!(matches!(
            ExportLayout::from_obj("v 0 0 0\n", &map),
            Err(LayoutError::VertexCount {
                expected: 3,
                found: 1
            })
        ));
        let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n";
        assert!(matches!(
            ExportLayout::from_obj(obj, &[Some(0), None, Some(2)]),
            Err(LayoutError::UnusedVertex { line: 4, vertex: 2 })
        ));
    }
}
