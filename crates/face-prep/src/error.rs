//! Typed errors of face preparation.

use glam::DVec3;
use std::fmt;
use std::path::PathBuf;

/// Size and bounding box of one boundary loop, reported when the loop count is wrong.
#[derive(Clone, Debug, PartialEq)]
pub struct LoopSummary {
    /// Number of vertices (= boundary edges) of the loop.
    pub size: usize,
    /// Minimum corner of the loop's bounding box (input frame).
    pub min: DVec3,
    /// Maximum corner of the loop's bounding box (input frame).
    pub max: DVec3,
}

impl fmt::Display for LoopSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} edges, bbox {}..{}",
            self.size,
            fmt_p(&self.min),
            fmt_p(&self.max)
        )
    }
}

fn list_loops(loops: &[LoopSummary]) -> String {
    let shown: Vec<String> = loops
        .iter()
        .take(LIST_CAP)
        .enumerate()
        .map(|(i, l)| format!("loop {i}: {l}"))
        .collect();
    let more = loops.len().saturating_sub(LIST_CAP);
    if loops.is_empty() {
        return String::new();
    }
    let mut s = format!(": {}", shown.join("; "));
    if more > 0 {
        s.push_str(&format!("; and {more} more"));
    }
    s
}

/// Lists in messages show at most this many items, then "and N more".
pub const LIST_CAP: usize = 10;

/// `[a, b, …]` with at most [`LIST_CAP`] items, then "and N more".
///
/// ```
/// use face_prep::error::capped_list;
/// assert_eq!(capped_list(&[1, 2]), "[1, 2]");
/// assert_eq!(capped_list(&(0..25).collect::<Vec<_>>()), "[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, and 15 more]");
/// ```
pub fn capped_list<T: fmt::Debug>(items: &[T]) -> String {
    let mut s = String::from("[");
    for (i, x) in items.iter().take(LIST_CAP).enumerate() {
        if i > 0 {
            s.push_str(", ");
        }
        s.push_str(&format!("{x:?}"));
    }
    if items.len() > LIST_CAP {
        s.push_str(&format!(", and {} more", items.len() - LIST_CAP));
    }
    s.push(']');
    s
}

/// A file's text shortened for a message (at most 80 characters, quoted).
pub(crate) fn short_text(text: &str) -> String {
    const MAX: usize = 80;
    let mut s: String = text.chars().take(MAX).collect();
    if text.chars().nth(MAX).is_some() {
        s.push('…');
    }
    format!("{s:?}")
}

/// A number to 6 significant digits (plain notation between 1e-4 and 1e6, scientific outside),
/// so messages never echo a file's bytes at full precision.
///
/// ```
/// use face_prep::error::sig6;
/// assert_eq!(sig6(12.345678901), "12.3457");
/// assert_eq!(sig6(-0.5), "-0.5");
/// assert_eq!(sig6(1e300), "1.00000e300");
/// assert_eq!(sig6(f64::NAN), "NaN");
/// ```
pub fn sig6(x: f64) -> String {
    if !x.is_finite() || x == 0.0 {
        return format!("{x}");
    }
    let a = x.abs();
    if !(1e-4..1e6).contains(&a) {
        return format!("{x:.5e}");
    }
    let decimals = (5 - a.log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        s
    }
}

/// A point to 6 significant digits per coordinate.
pub(crate) fn fmt_p(p: &DVec3) -> String {
    format!("({}, {}, {})", sig6(p.x), sig6(p.y), sig6(p.z))
}

/// Largest absolute coordinate accepted in a face mesh (any unit: a face is about 2·10⁸
/// nanometres across). Larger values are not a face and overflow the geometry's squared
/// lengths ([`PrepError::CoordinateTooLarge`]).
pub const MAX_COORDINATE: f64 = 1e9;

/// What is wrong with a glTF/GLB file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GltfError {
    /// The GLB container is malformed.
    #[error("GLB container: {0}")]
    Glb(String),
    /// The JSON does not parse as a glTF document.
    #[error("glTF JSON: {0}")]
    Json(String),
    /// A buffer cannot be loaded.
    #[error("buffer {index} (uri {uri}): {reason}")]
    Buffer {
        /// Buffer index.
        index: usize,
        /// Its URI, shortened for display (`<GLB binary chunk>` when it has none).
        uri: String,
        /// What is wrong.
        reason: String,
    },
    /// An accessor of a mesh attribute holds a NaN or infinite number.
    #[error("accessor {accessor} ({attribute}): element {element} is not finite")]
    NonFinite {
        /// Accessor index.
        accessor: usize,
        /// The attribute it is read as (`POSITION`, `NORMAL`, `TEXCOORD_0`).
        attribute: &'static str,
        /// The first element with a non-finite component (0-based).
        element: usize,
    },
    /// An object of the document is invalid (index out of range, bad type, out of bounds...).
    #[error("{what} {index}: {reason}")]
    Invalid {
        /// Kind of object (`accessor`, `bufferView`, `node`, `scene`, `mesh`).
        what: &'static str,
        /// Its index.
        index: usize,
        /// What is wrong.
        reason: String,
    },
}

/// What is wrong with a line of an OBJ file ([`crate::obj_text`]). Line numbers are 1-based.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ObjLineError {
    /// A `v`, `vt` or `vn` line holds a NaN or infinite number (or a position that overflows
    /// once divided by its w).
    #[error(
        "OBJ line {line}: {} holds a number that is not finite",
        short_text(text)
    )]
    NonFinite {
        /// Line number.
        line: usize,
        /// The line's text.
        text: String,
    },
    /// A `vt` line holds a number beyond the 32-bit float range (glTF stores texture
    /// coordinates as 32-bit floats).
    #[error(
        "OBJ line {line}: {} holds a texture coordinate beyond ±3.4e38",
        short_text(text)
    )]
    TexcoordOutOfRange {
        /// Line number.
        line: usize,
        /// The line's text.
        text: String,
    },
    /// A `v` line's w is zero (its position would be divided by zero).
    #[error("OBJ line {line}: {} has w = 0", short_text(text))]
    ZeroW {
        /// Line number.
        line: usize,
        /// The line's text.
        text: String,
    },
    /// A `v`, `vt` or `vn` line without the numbers it needs.
    #[error("OBJ line {line}: {} is not {expected}", short_text(text))]
    Malformed {
        /// Line number.
        line: usize,
        /// The line's text.
        text: String,
        /// What the line should be.
        expected: &'static str,
    },
    /// A face corner that is not `v`, `v/vt`, `v//vn` or `v/vt/vn` with non-zero integers.
    #[error(
        "OBJ line {line}: face corner {} is not v, v/vt, v//vn or v/vt/vn",
        short_text(corner)
    )]
    BadCorner {
        /// Line number.
        line: usize,
        /// The corner as written.
        corner: String,
    },
    /// A face corner refers to a `v`, `vt` or `vn` line that does not come before the face
    /// (OBJ indices count the lines above the face; a later line cannot be referred to).
    #[error(
        "OBJ line {line}: face corner {} refers to a `{statement}` line that does not come \
         before the face (there are {defined} above it)",
        short_text(corner)
    )]
    UndefinedCorner {
        /// Line number.
        line: usize,
        /// The corner as written.
        corner: String,
        /// `v`, `vt` or `vn`.
        statement: &'static str,
        /// How many such lines come before the face.
        defined: usize,
    },
}

/// Everything that can go wrong turning a face mesh into a rig.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PrepError {
    /// The file could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// File that failed.
        path: PathBuf,
        /// Underlying I/O error.
        source: std::io::Error,
    },
    /// The file extension is not one of `.obj`, `.gltf`, `.glb`.
    #[error("unsupported face file {path}: extension {extension:?} (expected .obj, .gltf or .glb)")]
    UnsupportedExtension {
        /// Offending file.
        path: PathBuf,
        /// Its extension (empty if none).
        extension: String,
    },
    /// tobj rejected the OBJ text.
    #[error("OBJ parse error: {reason}")]
    Obj {
        /// tobj's description of the problem.
        reason: String,
    },
    /// A line of the OBJ is invalid (a non-finite number, a zero w, a face corner referring to
    /// a line that does not come before it).
    #[error(transparent)]
    ObjLine(#[from] ObjLineError),
    /// The glTF/GLB document is malformed, or a buffer cannot be read safely.
    #[error("glTF error: {0}")]
    Gltf(#[from] GltfError),
    /// The input path is not a regular file (a folder, FIFO or device is not opened).
    #[error("{path} is not a regular file")]
    NotAFile {
        /// The path.
        path: PathBuf,
    },
    /// An input exceeds an [`crate::InputLimits`] limit.
    #[error("input too large: {count} {what}, the limit is {limit}")]
    TooLarge {
        /// What was counted (`file bytes`, `positions`, `triangles`, `muscles`).
        what: &'static str,
        /// The count found or declared.
        count: u64,
        /// The limit.
        limit: u64,
    },
    /// The glTF document has no mesh at all.
    #[error("the glTF file contains no mesh")]
    GltfNoMesh,
    /// No mesh of the requested name.
    #[error(
        "no glTF mesh named {} (meshes present: {})",
        short_text(name),
        capped_list(available)
    )]
    GltfMeshNotFound {
        /// Requested name.
        name: String,
        /// Names of the meshes present (unnamed ones as `#index`).
        available: Vec<String>,
    },
    /// A primitive cannot be used (no positions, or points/lines).
    #[error("glTF mesh {mesh:?} primitive {primitive}: {reason}")]
    GltfPrimitive {
        /// Mesh name or `#index`.
        mesh: String,
        /// Primitive index within the mesh.
        primitive: usize,
        /// What is wrong.
        reason: String,
    },
    /// The mesh has no triangle.
    #[error("the mesh has no triangles")]
    EmptyMesh,
    /// A face refers to a vertex that does not exist.
    #[error(
        "triangle {triangle} refers to vertex {index} but there are only {vertex_count} vertices"
    )]
    IndexOutOfRange {
        /// Triangle index (after triangulation).
        triangle: usize,
        /// Offending index.
        index: u32,
        /// Number of vertices available.
        vertex_count: usize,
    },
    /// A used vertex has a NaN or infinite coordinate.
    #[error("input position {input_index} is not finite: {}", fmt_p(&DVec3::from(*position)))]
    NonFiniteVertex {
        /// Index of the position in the input (OBJ `v` order, 0-based).
        input_index: usize,
        /// Its coordinates.
        position: [f64; 3],
    },
    /// A vertex lies absurdly far from the origin (beyond [`MAX_COORDINATE`]).
    #[error(
        "input position {input_index} is absurdly far from the origin: {} (limit {:e} in any unit)",
        fmt_p(&DVec3::from(*position)),
        MAX_COORDINATE
    )]
    CoordinateTooLarge {
        /// Index of the position in the input (OBJ `v` order, 0-based).
        input_index: usize,
        /// Its coordinates.
        position: [f64; 3],
    },
    /// A triangle has (near) zero area or repeats a vertex.
    #[error("triangle {triangle} {vertices:?} is degenerate: area {area:e} at {p0}, {p1}, {p2}", p0 = fmt_p(&corners[0]), p1 = fmt_p(&corners[1]), p2 = fmt_p(&corners[2]))]
    DegenerateTriangle {
        /// Triangle index (after triangulation).
        triangle: usize,
        /// Its welded vertex indices.
        vertices: [u32; 3],
        /// Its area.
        area: f64,
        /// Its corner positions.
        corners: [DVec3; 3],
    },
    /// An edge is shared by more than two triangles.
    #[error("non-manifold edge {a}-{b} from {pa} to {pb}: shared by {} triangles {}", triangles.len(), capped_list(triangles), pa = fmt_p(pa), pb = fmt_p(pb))]
    NonManifoldEdge {
        /// First vertex.
        a: u32,
        /// Second vertex.
        b: u32,
        /// Position of `a`.
        pa: DVec3,
        /// Position of `b`.
        pb: DVec3,
        /// All triangles using the edge.
        triangles: Vec<usize>,
    },
    /// Two triangles traverse their shared edge in the same direction.
    #[error("inconsistent winding: triangles {triangles:?} both traverse edge {a}->{b} ({pa} -> {pb})", pa = fmt_p(pa), pb = fmt_p(pb))]
    InconsistentWinding {
        /// Edge start.
        a: u32,
        /// Edge end.
        b: u32,
        /// Position of `a`.
        pa: DVec3,
        /// Position of `b`.
        pb: DVec3,
        /// The two triangles.
        triangles: [usize; 2],
    },
    /// A vertex where two boundary loops touch (bow-tie), so loops are ambiguous.
    #[error("non-manifold vertex {vertex} at {p}: {outgoing} boundary edges leave it (two boundary loops touch there; an unwelded seam? vertices closer than 1e-9 of the face's size are welded, merge wider gaps by distance first)", p = fmt_p(position))]
    NonManifoldVertex {
        /// Vertex index.
        vertex: u32,
        /// Its position.
        position: DVec3,
        /// Number of boundary edges leaving it.
        outgoing: usize,
    },
    /// The mesh falls apart into several pieces.
    #[error("the mesh has {} connected components (triangle counts {}); expected one", sizes.len(), capped_list(sizes))]
    MultipleComponents {
        /// Triangle count of every component, largest first.
        sizes: Vec<usize>,
    },
    /// Not exactly four boundary loops (face contour, two eyes, mouth).
    #[error(
        "expected 4 boundary loops (face contour, 2 eyes, mouth), found {count}{}",
        list_loops(loops)
    )]
    WrongLoopCount {
        /// Number of loops found.
        count: usize,
        /// Size and bounding box of each loop found.
        loops: Vec<LoopSummary>,
    },
    /// Three boundary loops (the contour and two eyes) and no closed mouth found on the surface
    /// ([`crate::frame::contact::mouth`]).
    #[error(
        "expected 4 boundary loops (face contour, 2 eyes, mouth), found 3 and no closed mouth: \
         {reason}"
    )]
    NoMouth {
        /// Why no lip contact line was found.
        reason: String,
    },
    /// Two boundary loops (the contour and the mouth) and no closed eyes found on the surface
    /// ([`crate::frame::contact::lids`]).
    #[error(
        "expected 4 boundary loops (face contour, 2 eyes, mouth), found 2 (no eye openings) and \
         no closed eyes: {reason}"
    )]
    NoEyes {
        /// Why no lid contact lines were found.
        reason: String,
    },
    /// The mesh has four loops but is not a front face (e.g. a whole head cut at the neck).
    #[error(
        "not a front face: {reason}. The input must be the front of a face only: one sheet cut \
         along the face's outline (forehead, temples, jaw), open at both eyes and the mouth"
    )]
    NotAFrontFace {
        /// What the loops are and why they do not make a front face.
        reason: String,
    },
    /// The surface crosses itself far more than a fold can (a triangle crossing dozens of
    /// others): its vertex positions are out of order, e.g. a `v` line moved or swapped.
    #[error(
        "the face surface is scrambled: triangle {triangle} crosses {crossings} other triangles \
         (a fold such as pressed lips crosses at most a few); are the vertex positions out of \
         order (a `v` line moved or swapped)?"
    )]
    ScrambledSurface {
        /// The triangle crossing the most others (0-based).
        triangle: usize,
        /// How many triangles it crosses.
        crossings: usize,
    },
    /// A vertex lies far outside the rest of the surface ([`crate::input::stray`]).
    #[error(
        "vertex {vertex} at {position:?} lies {ratio:.0} times farther from the surface's median \
         position than 90 % of the vertices do: a stray vertex (a mistyped or corrupted \
         position?)"
    )]
    StrayVertex {
        /// The vertex: 1-based in the file's order when read from a file ([`crate::FaceMesh`]),
        /// 0-based among the vertices given to [`crate::input::stray::check_no_stray_vertex`].
        vertex: usize,
        /// Its position, in the file's units.
        position: [f64; 3],
        /// Its distance from the median position over the 90th-percentile distance.
        ratio: f64,
    },
    /// The canonical frame cannot be determined.
    #[error("cannot orient the face: {reason}")]
    Orientation {
        /// What went wrong.
        reason: String,
    },
    /// A rig parameter is out of range.
    #[error("rig parameter {name} = {value} is invalid: {reason}")]
    InvalidParam {
        /// Parameter name.
        name: &'static str,
        /// Its value.
        value: f64,
        /// Allowed range.
        reason: &'static str,
    },
    /// A feature box is empty or not finite.
    #[error("feature box {name} is invalid: min ({}, {}) max ({}, {})", sig6(min[0]), sig6(min[1]), sig6(max[0]), sig6(max[1]))]
    InvalidBox {
        /// Box name.
        name: &'static str,
        /// Its minimum corner.
        min: [f64; 2],
        /// Its maximum corner.
        max: [f64; 2],
    },
    /// A muscle refers to an element it cannot use.
    #[error("muscle {muscle:?}: element {element} {reason}")]
    InvalidMuscle {
        /// Muscle name.
        muscle: String,
        /// Offending element.
        element: u32,
        /// Why it is rejected.
        reason: &'static str,
    },
    /// Two muscles have the same id ([`crate::Muscle::id`]): their morph targets and sliders
    /// would share a name.
    #[error("two muscles are named {} (muscle names must be unique)", short_text(.0))]
    DuplicateMuscle(String),
    /// Muscle index out of range in [`crate::FaceRig::muscle_pattern`] callers.
    #[error("muscle index {index} out of range ({count} muscles)")]
    NoSuchMuscle {
        /// Requested index.
        index: usize,
        /// Number of muscles.
        count: usize,
    },
}

/// Errors reading or writing a muscle file (thesis §7.6 format). Line numbers are 1-based.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MuscleFileError {
    /// I/O failure.
    #[error("muscle file I/O error: {0}")]
    Io(#[from] std::io::Error),
    /// A line that does not belong where it is.
    #[error("line {line}: unexpected {} ({expected})", short_text(text))]
    Unexpected {
        /// Line number.
        line: usize,
        /// The line's text.
        text: String,
        /// What was expected there.
        expected: &'static str,
    },
    /// A number could not be parsed.
    #[error("line {line}: {} is not a non-negative integer", short_text(text))]
    BadNumber {
        /// Line number.
        line: usize,
        /// The text.
        text: String,
    },
    /// The `[Size]` does not match the number of `[Data]` lines.
    #[error(
        "line {line}: muscle {} declares {declared} elements but lists {found}",
        short_text(muscle)
    )]
    SizeMismatch {
        /// Line of the block end.
        line: usize,
        /// Muscle name.
        muscle: String,
        /// Declared size.
        declared: usize,
        /// Number of indices found.
        found: usize,
    },
    /// An element index beyond the shell.
    #[error(
        "line {line}: element {index} of muscle {} is out of range (shell has {element_count} elements)",
        short_text(muscle)
    )]
    IndexOutOfRange {
        /// Line number.
        line: usize,
        /// Muscle name.
        muscle: String,
        /// The index.
        index: u32,
        /// Number of shell elements.
        element_count: usize,
    },
    /// An element listed twice in one chain.
    #[error(
        "line {line}: element {index} appears twice in muscle {}",
        short_text(muscle)
    )]
    DuplicateElement {
        /// Line number.
        line: usize,
        /// Muscle name.
        muscle: String,
        /// The index.
        index: u32,
    },
    /// The file ends inside a block.
    #[error(
        "line {line}: file ends inside muscle {} (missing {missing})",
        short_text(muscle)
    )]
    Truncated {
        /// Last line number.
        line: usize,
        /// Muscle name.
        muscle: String,
        /// Missing block.
        missing: &'static str,
    },
    /// Two muscles with the same id ([`crate::Muscle::id`]: a standard muscle's id, whatever
    /// name denotes it, else the name): their sliders and morph targets would share a name.
    #[error(
        "line {line}: muscle {} has the same name as the muscle at line {first_line} (both are \
         {}); muscle names must be unique",
        short_text(name),
        short_text(id)
    )]
    DuplicateName {
        /// Line of the second name.
        line: usize,
        /// The second name as written.
        name: String,
        /// The id both names denote.
        id: String,
        /// Line of the first name.
        first_line: usize,
    },
    /// More muscles than [`crate::InputLimits::max_muscles`].
    #[error("line {line}: more than {limit} muscles (input limit)")]
    TooManyMuscles {
        /// Line of the first muscle over the limit.
        line: usize,
        /// The limit.
        limit: usize,
    },
    /// A muscle name that cannot be written (empty, or containing a line break or `[`).
    #[error("muscle name {} cannot be written (empty, multi-line or starting with '[')", short_text(.0))]
    BadName(String),
}
