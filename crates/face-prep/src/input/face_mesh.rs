//! The validated, welded input face mesh and its loaders (OBJ through tobj, glTF/GLB through gltf).

use crate::error::PrepError;
use crate::frame::contact::{self, ContactLine};
use crate::frame::topology;
use crate::input::gltf_face::gltf_face_data;
use crate::input::limits::{InputLimits, check_coordinates, read_input_file};
use crate::input::obj_text;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::io::BufRead;
use std::path::Path;

/// One front-face triangle mesh in the user's INPUT frame: welded (positions within
/// [`WELD_RELATIVE_TOLERANCE`] of the diagonal merged), triangulated, unused vertices dropped, and validated (one connected, edge-manifold,
/// consistently wound surface with exactly four boundary loops).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FaceMesh {
    /// Welded vertex positions, input frame, in order of first appearance in the input.
    pub vertices: Vec<DVec3>,
    /// Triangles indexing [`FaceMesh::vertices`], counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// For every input position (OBJ `v` line order, or glTF POSITION accessor order concatenated
    /// over the mesh's primitives) the welded vertex it became, or `None` if no face used it.
    /// Exports use this to write poses in the user's own vertex order. An input position on a
    /// closed mouth's (eye's) contact line maps to the upper lip's (lid's) vertex; which side a
    /// face corner there belongs to follows from [`FaceMesh::triangles`] (see
    /// [`FaceMesh::lip_line`]). An input position of a mouth bag that was taken off
    /// ([`crate::frame::contact::bag`]) maps to the entrance vertex it follows.
    pub input_to_vertex: Vec<Option<u32>>,
    /// The lips' contact line when the mouth came closed (three loops: the lips share vertices
    /// or touch at coincident ones) and was cut open ([`crate::frame::contact`]): the lower
    /// lip's copies are appended after the welded input vertices.
    pub lip_line: Option<ContactLine>,
    /// The lids' contact lines when the eyes came closed (two loops) and were cut open, the
    /// lower lids' copies appended like the lips'. The rig's lid controls leave a closed eye
    /// alone.
    pub lid_lines: Vec<ContactLine>,
    /// How many vertices of a closed mouth bag behind the lips were taken off the simulated
    /// face ([`crate::frame::contact::bag`]); 0 when the mouth opens onto nothing.
    #[serde(default)]
    pub mouth_bag_vertices: usize,
}

/// Positions closer than this fraction of the used positions' bounding-box diagonal are one
/// vertex (0.2 nm on a 20 cm face: far below any modelled feature, far above rounding).
/// Regression (issue 36): vertices 1e-12 apart (a mesh exported with a float round trip
/// between its parts) were not welded and the face was refused as "non-manifold vertex".
pub const WELD_RELATIVE_TOLERANCE: f64 = 1e-9;

/// A uniform grid of welded vertices with cells of the weld tolerance: a position's welded
/// vertex, if any, is within the tolerance and so in its cell or a neighbouring one.
struct WeldGrid {
    tolerance: f64,
    cells: HashMap<[i64; 3], Vec<u32>>,
}

impl WeldGrid {
    fn cell(&self, p: DVec3) -> [i64; 3] {
        // `as` saturates: on a degenerate scale every position shares a cell, still correct.
        (p / self.tolerance).floor().to_array().map(|c| c as i64)
    }

    /// The first welded vertex within the tolerance of `p`.
    fn find(&self, vertices: &[DVec3], p: DVec3) -> Option<u32> {
        let c = self.cell(p);
        let mut best: Option<(f64, u32)> = None;
        for dx in -1..=1i64 {
            for dy in -1..=1i64 {
                for dz in -1..=1i64 {
                    let key = [
                        c[0].wrapping_add(dx),
                        c[1].wrapping_add(dy),
                        c[2].wrapping_add(dz),
                    ];
                    for &v in self.cells.get(&key).into_iter().flatten() {
                        let d = vertices[v as usize].distance(p);
                        if d <= self.tolerance && best.is_none_or(|(bd, bv)| (d, v) < (bd, bv)) {
                            best = Some((d, v));
                        }
                    }
                }
            }
        }
        best.map(|(_, v)| v)
    }

    fn insert(&mut self, p: DVec3, v: u32) {
        let c = self.cell(p);
        self.cells.entry(c).or_default().push(v);
    }
}

struct Welded {
    vertices: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    grid: WeldGrid,
}

impl Welded {
    /// The welded vertex an input position became (`None`: no used position within the
    /// tolerance).
    fn vertex_of(&self, p: DVec3) -> Option<u32> {
        self.grid.find(&self.vertices, p)
    }
}

/// Merges positions used by `triangles` that lie within [`WELD_RELATIVE_TOLERANCE`] of the
/// bounding-box diagonal of each other (the first in input order is kept) and drops unused
/// ones.
fn weld(positions: &[DVec3], triangles: &[[u32; 3]]) -> Result<Welded, PrepError> {
    let mut used = vec![false; positions.len()];
    for (t, tri) in triangles.iter().enumerate() {
        for &i in tri {
            match used.get_mut(i as usize) {
                Some(u) => *u = true,
                None => {
                    return Err(PrepError::IndexOutOfRange {
                        triangle: t,
                        index: i,
                        vertex_count: positions.len(),
                    });
                }
            }
        }
    }
    for (i, &p) in positions.iter().enumerate().filter(|(i, _)| used[*i]) {
        check_coordinates(i, p)?;
    }
    let (lo, hi) = topology::bounding_box(
        positions
            .iter()
            .enumerate()
            .filter(|(i, _)| used[*i])
            .map(|(_, &p)| p),
    );
    let diagonal = (hi - lo).length();
    let tolerance = if diagonal.is_finite() && diagonal > 0.0 {
        WELD_RELATIVE_TOLERANCE * diagonal
    } else {
        f64::MIN_POSITIVE
    };
    let mut grid = WeldGrid {
        tolerance,
        cells: HashMap::new(),
    };
    let mut vertices = Vec::new();
    let mut remap = vec![u32::MAX; positions.len()];
    for (i, &p) in positions.iter().enumerate() {
        if !used[i] {
            continue;
        }
        let id = match grid.find(&vertices, p) {
            Some(v) => v,
            None => {
                vertices.push(p);
                let v = (vertices.len() - 1) as u32;
                grid.insert(p, v);
                v
            }
        };
        remap[i] = id;
    }
    let triangles = triangles
        .iter()
        .map(|t| t.map(|i| remap[i as usize]))
        .collect();
    Ok(Welded {
        vertices,
        triangles,
        grid,
    })
}

impl FaceMesh {
    /// Builds a face mesh from raw positions and triangles (indices into `positions`), welding
    /// coincident positions, dropping unused ones and validating the result.
    ///
    /// ```
    /// use face_prep::{FaceMesh, PrepError};
    /// use glam::DVec3;
    /// // A single triangle has one boundary loop, not four.
    /// let err = FaceMesh::from_triangles(&[DVec3::ZERO, DVec3::X, DVec3::Y], &[[0, 1, 2]]);
    /// assert!(matches!(err, Err(PrepError::WrongLoopCount { count: 1, .. })));
    /// ```
    pub fn from_triangles(
        positions: &[DVec3],
        triangles: &[[u32; 3]],
    ) -> Result<FaceMesh, PrepError> {
        let limits = InputLimits::default();
        limits.check_count("positions", positions.len() as u64, limits.max_positions)?;
        limits.check_count("triangles", triangles.len() as u64, limits.max_triangles)?;
        let w = weld(positions, triangles)?;
        let input_to_vertex = positions.iter().map(|&p| w.vertex_of(p)).collect();
        FaceMesh::validated(w.vertices, w.triangles, input_to_vertex)
    }

    fn validated(
        vertices: Vec<DVec3>,
        triangles: Vec<[u32; 3]>,
        input_to_vertex: Vec<Option<u32>>,
    ) -> Result<FaceMesh, PrepError> {
        let loops = topology::validate(&vertices, &triangles)?;
        // Named by its place in the file (1-based, as OBJ counts), not after welding.
        crate::input::stray::check_no_stray_vertex(&vertices, &triangles).map_err(|e| match e {
            PrepError::StrayVertex {
                vertex,
                position,
                ratio,
            } => PrepError::StrayVertex {
                vertex: input_to_vertex
                    .iter()
                    .position(|v| *v == Some(vertex as u32))
                    .map_or(vertex, |i| i + 1),
                position,
                ratio,
            },
            other => other,
        })?;
        let mut input_to_vertex = input_to_vertex;
        let (vertices, triangles, loops, lip_line, lid_lines, mouth_bag_vertices) =
            match contact::open_closed_features(&vertices, &triangles, &loops)? {
                None => (vertices, triangles, loops, None, Vec::new(), 0),
                Some(mut opened) => {
                    let bag = drop_followers(&mut opened, &mut input_to_vertex);
                    let loops = topology::validate(&opened.vertices, &opened.triangles)?;
                    let (v, t) = (opened.vertices, opened.triangles);
                    (v, t, loops, opened.lips, opened.lids, bag)
                }
            };
        topology::check_four_loops(&vertices, &loops)?;
        Ok(FaceMesh {
            vertices,
            triangles,
            input_to_vertex,
            lip_line,
            lid_lines,
            mouth_bag_vertices,
        })
    }

    /// Parses OBJ text (tobj, multi-index mode so seams are not split, n-gons fan-triangulated),
    /// welds, validates. The whole text is held to the rules of [`crate::obj_text`] too (finite
    /// numbers, non-zero w, face corners referring only to lines above the face), so the
    /// exports, which read the text again, accept whatever this accepts.
    ///
    /// ```
    /// let obj = std::fs::read_to_string(concat!(
    ///     env!("CARGO_MANIFEST_DIR"),
    ///     "/../../assets/mediapipe_canonical_4loop.obj"
    /// ))
    /// .unwrap();
    /// let face = face_prep::FaceMesh::from_obj_str(&obj).unwrap();
    /// assert_eq!((face.vertices.len(), face.triangles.len()), (468, 852));
    /// ```
    pub fn from_obj_str(text: &str) -> Result<FaceMesh, PrepError> {
        FaceMesh::from_obj_reader(&mut text.as_bytes())
    }

    /// Like [`FaceMesh::from_obj_str`], from a buffered reader (at most
    /// [`InputLimits::max_file_bytes`] bytes are read).
    pub(crate) fn from_obj_reader(reader: &mut impl BufRead) -> Result<FaceMesh, PrepError> {
        use std::io::Read;
        let limits = InputLimits::default();
        let mut bytes = Vec::new();
        reader
            .take(limits.max_file_bytes.saturating_add(1))
            .read_to_end(&mut bytes)
            .map_err(|e| PrepError::Io {
                path: "<reader>".into(),
                source: e,
            })?;
        limits.check_file_bytes(bytes.len() as u64)?;
        FaceMesh::from_obj_bytes(&bytes, &limits)
    }

    /// Parses OBJ bytes (see [`FaceMesh::from_obj_str`]) with explicit size limits.
    pub fn from_obj_bytes(bytes: &[u8], limits: &InputLimits) -> Result<FaceMesh, PrepError> {
        limits.check_file_bytes(bytes.len() as u64)?;
        let text = String::from_utf8_lossy(bytes);
        // First the rules the exports read the text by (their errors name the line); positions
        // in file order, parsed as tobj does.
        let file_positions = obj_text::checked_positions(&text, limits)?;
        let options = tobj::LoadOptions {
            single_index: false,
            triangulate: true,
            ignore_points: true,
            ignore_lines: true,
        };
        let (models, _materials) =
            tobj::load_obj_buf(&mut text.as_bytes(), &options, |_| Ok(Default::default()))
                .map_err(|e| PrepError::Obj {
                    reason: e.to_string(),
                })?;
        let position_count: usize = models.iter().map(|m| m.mesh.positions.len() / 3).sum();
        let index_count: usize = models.iter().map(|m| m.mesh.indices.len() / 3).sum();
        limits.check_count("positions", position_count as u64, limits.max_positions)?;
        limits.check_count("triangles", index_count as u64, limits.max_triangles)?;
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for m in &models {
            let base = (positions.len()) as u32;
            positions.extend(
                m.mesh
                    .positions
                    .chunks_exact(3)
                    .map(|c| DVec3::new(c[0], c[1], c[2])),
            );
            triangles.extend(
                m.mesh
                    .indices
                    .chunks_exact(3)
                    .map(|c| [c[0] + base, c[1] + base, c[2] + base]),
            );
        }
        for (i, p) in file_positions.iter().enumerate() {
            check_coordinates(i, *p)?;
        }
        let w = weld(&positions, &triangles)?;
        let input_to_vertex = file_positions.iter().map(|&p| w.vertex_of(p)).collect();
        FaceMesh::validated(w.vertices, w.triangles, input_to_vertex)
    }

    /// Loads the first mesh of a glTF/GLB document given as bytes (`.glb` or self-contained
    /// `.gltf` with data URIs), or the mesh named `mesh_name`. The transforms of the first node
    /// that instantiates the mesh (in scene order) are applied.
    pub fn from_gltf_slice(bytes: &[u8], mesh_name: Option<&str>) -> Result<FaceMesh, PrepError> {
        gltf_mesh(bytes, None, mesh_name, &InputLimits::default())
    }

    /// Like [`FaceMesh::from_gltf_slice`] for a document read from `folder` (relative buffer
    /// URIs are read from inside that folder only), with explicit size limits.
    pub fn from_gltf_bytes(
        bytes: &[u8],
        folder: Option<&Path>,
        mesh_name: Option<&str>,
        limits: &InputLimits,
    ) -> Result<FaceMesh, PrepError> {
        gltf_mesh(bytes, folder, mesh_name, limits)
    }
}

/// A glTF face: [`gltf_face_data`] welded and validated.
fn gltf_mesh(
    bytes: &[u8],
    base: Option<&Path>,
    mesh_name: Option<&str>,
    limits: &InputLimits,
) -> Result<FaceMesh, PrepError> {
    let data = gltf_face_data(bytes, base, mesh_name, limits)?;
    FaceMesh::from_triangles(&data.positions, &data.triangles)
}

/// Loads a face mesh, dispatching on the extension: `.obj` (tobj), `.gltf` or `.glb` (gltf,
/// first mesh), under the default [`InputLimits`]. See [`LoadOptions`] to pick a glTF mesh by
/// name or set other limits.
///
/// ```
/// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
///     .join("../../assets/mediapipe_canonical_4loop.obj");
/// let face = face_prep::load_face(&path).unwrap();
/// assert_eq!(face.triangles.len(), 852);
/// ```
pub fn load_face(path: &Path) -> Result<FaceMesh, PrepError> {
    LoadOptions::default().load(path)
}

/// How a face mesh file is read: which glTF/GLB mesh (`None`: the first; ignored for OBJ) and
/// the input size limits (file bytes, positions, triangles), checked before the data is
/// allocated. [`load_face`] uses the defaults.
///
/// ```
/// use face_prep::{InputLimits, LoadOptions, PrepError};
/// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
///     .join("../../assets/mediapipe_canonical_4loop.obj");
/// let small = LoadOptions {
///     limits: InputLimits { max_triangles: 100, ..InputLimits::default() },
///     ..LoadOptions::default()
/// };
/// let err = small.load(&path).unwrap_err();
/// assert!(matches!(err, PrepError::TooLarge { what: "triangles", .. }), "{err}");
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// The glTF/GLB mesh to read, by name (`None`: the first mesh).
    pub mesh_name: Option<String>,
    /// Size limits of the file and the mesh.
    pub limits: InputLimits,
}

impl LoadOptions {
    /// Loads the face mesh at `path`, dispatching on the extension.
    pub fn load(&self, path: &Path) -> Result<FaceMesh, PrepError> {
        let (mesh_name, limits) = (self.mesh_name.as_deref(), &self.limits);
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase();
        let read = || read_input_file(path, limits);
        match ext.as_str() {
            "obj" => FaceMesh::from_obj_bytes(&read()?, limits),
            "gltf" | "glb" => gltf_mesh(&read()?, path.parent(), mesh_name, limits),
            _ => Err(PrepError::UnsupportedExtension {
                path: path.to_owned(),
                extension: ext,
            }),
        }
    }
}

/// Takes the vertices no triangle uses out of an opened face (a mouth bag taken off,
/// [`contact::bag`]): the rest are renumbered in order, and the input lines of each follower
/// go to the vertex it follows. Returns how many followers were taken out.
fn drop_followers(opened: &mut contact::Opened, input_to_vertex: &mut [Option<u32>]) -> usize {
    let followers = opened.followers.len();
    if followers == 0 {
        return 0;
    }
    let n = opened.vertices.len();
    let mut used = vec![false; n];
    for &v in opened.triangles.iter().flatten() {
        used[v as usize] = true;
    }
    let mut index = vec![None; n];
    let mut kept = Vec::new();
    for v in 0..n {
        if used[v] {
            index[v] = Some(kept.len() as u32);
            kept.push(opened.vertices[v]);
        }
    }
    for &(follower, anchor) in &opened.followers {
        index[follower as usize] = index[anchor as usize];
    }
    let renumber = |v: u32| index[v as usize].unwrap_or(v);
    for t in &mut opened.triangles {
        *t = t.map(renumber);
    }
    for line in opened.lips.iter_mut().chain(&mut opened.lids) {
        for v in line.upper.iter_mut().chain(&mut line.lower) {
            *v = renumber(*v);
        }
    }
    for v in input_to_vertex.iter_mut() {
        *v = v.and_then(|v| index[v as usize]);
    }
    opened.vertices = kept;
    opened.followers.clear();
    followers
}
