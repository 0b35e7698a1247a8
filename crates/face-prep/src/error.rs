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
            "{} edges, bbox ({:.4}, {:.4}, {:.4})..({:.4}, {:.4}, {:.4})",
            self.size, self.min.x, self.min.y, self.min.z, self.max.x, self.max.y, self.max.z
        )
    }
}

fn list_loops(loops: &[LoopSummary]) -> String {
    loops
        .iter()
        .enumerate()
        .map(|(i, l)| format!("loop {i}: {l}"))
        .collect::<Vec<_>>()
        .join("; ")
}

fn fmt_p(p: &DVec3) -> String {
    format!("({:.6}, {:.6}, {:.6})", p.x, p.y, p.z)
}

/// Everything that can go wrong turning a face mesh into a rig.
#[derive(Debug, thiserror::Error)]
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
    /// The gltf crate rejected the file.
    #[error("glTF error: {0}")]
    Gltf(#[from] gltf::Error),
    /// The glTF document has no mesh at all.
    #[error("the glTF file contains no mesh")]
    GltfNoMesh,
    /// No mesh of the requested name.
    #[error("no glTF mesh named {name:?} (meshes present: {available:?})")]
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
    #[error("input position {input_index} is not finite: {position:?}")]
    NonFiniteVertex {
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
    #[error("non-manifold edge {a}-{b} from {pa} to {pb}: shared by {} triangles {triangles:?}", triangles.len(), pa = fmt_p(pa), pb = fmt_p(pb))]
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
    #[error("non-manifold vertex {vertex} at {p}: {outgoing} boundary edges leave it", p = fmt_p(position))]
    NonManifoldVertex {
        /// Vertex index.
        vertex: u32,
        /// Its position.
        position: DVec3,
        /// Number of boundary edges leaving it.
        outgoing: usize,
    },
    /// The mesh falls apart into several pieces.
    #[error("the mesh has {} connected components (triangle counts {sizes:?}); expected one", sizes.len())]
    MultipleComponents {
        /// Triangle count of every component, largest first.
        sizes: Vec<usize>,
    },
    /// Not exactly four boundary loops (face contour, two eyes, mouth).
    #[error(
        "expected 4 boundary loops (face contour, 2 eyes, mouth), found {count}: {}",
        list_loops(loops)
    )]
    WrongLoopCount {
        /// Number of loops found.
        count: usize,
        /// Size and bounding box of each loop found.
        loops: Vec<LoopSummary>,
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
    #[error("feature box {name} is invalid: min {min:?} max {max:?}")]
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
pub enum MuscleFileError {
    /// I/O failure.
    #[error("muscle file I/O error: {0}")]
    Io(#[from] std::io::Error),
    /// A line that does not belong where it is.
    #[error("line {line}: unexpected {text:?} ({expected})")]
    Unexpected {
        /// Line number.
        line: usize,
        /// The line's text.
        text: String,
        /// What was expected there.
        expected: &'static str,
    },
    /// A number could not be parsed.
    #[error("line {line}: {text:?} is not a non-negative integer")]
    BadNumber {
        /// Line number.
        line: usize,
        /// The text.
        text: String,
    },
    /// The `[Size]` does not match the number of `[Data]` lines.
    #[error("line {line}: muscle {muscle:?} declares {declared} elements but lists {found}")]
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
        "line {line}: element {index} of muscle {muscle:?} is out of range (shell has {element_count} elements)"
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
    #[error("line {line}: element {index} appears twice in muscle {muscle:?}")]
    DuplicateElement {
        /// Line number.
        line: usize,
        /// Muscle name.
        muscle: String,
        /// The index.
        index: u32,
    },
    /// The file ends inside a block.
    #[error("line {line}: file ends inside muscle {muscle:?} (missing {missing})")]
    Truncated {
        /// Last line number.
        line: usize,
        /// Muscle name.
        muscle: String,
        /// Missing block.
        missing: &'static str,
    },
    /// A muscle name that cannot be written (empty, or containing a line break or `[`).
    #[error("muscle name {0:?} cannot be written (empty, multi-line or starting with '[')")]
    BadName(String),
}
