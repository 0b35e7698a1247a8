//! Typed errors of the solver.

use thiserror::Error;

/// Why a surface mesh was rejected by [`crate::SurfaceMesh::new`].
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum MeshError {
    /// The mesh has no triangle.
    #[error("the surface mesh has no triangles")]
    Empty,
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate ({x}, {y}, {z})")]
    NonFiniteVertex {
        /// Index of the vertex.
        vertex: usize,
        /// x coordinate as read.
        x: f64,
        /// y coordinate as read.
        y: f64,
        /// z coordinate as read.
        z: f64,
    },
    /// A triangle refers to a vertex that does not exist.
    #[error(
        "triangle {triangle} refers to vertex {index}, but the mesh has only {vertex_count} vertices"
    )]
    IndexOutOfRange {
        /// Index of the triangle.
        triangle: usize,
        /// The offending vertex index.
        index: u32,
        /// Number of vertices in the mesh.
        vertex_count: usize,
    },
    /// A triangle has (numerically) zero area or repeats a vertex.
    #[error("triangle {triangle} is degenerate: area {area:e} for longest edge {longest_edge:e}")]
    DegenerateTriangle {
        /// Index of the triangle.
        triangle: usize,
        /// Its area.
        area: f64,
        /// Its longest edge.
        longest_edge: f64,
    },
    /// An edge belongs to only one triangle: the surface is not closed.
    #[error("edge ({a}, {b}) of triangle {triangle} is a boundary edge: the surface is not closed")]
    OpenEdge {
        /// First vertex of the edge.
        a: u32,
        /// Second vertex of the edge.
        b: u32,
        /// The only triangle using it.
        triangle: usize,
    },
    /// An edge is shared by more than two triangles.
    #[error(
        "edge ({a}, {b}) is shared by {count} triangles (first: {triangle}): the surface is not edge-manifold"
    )]
    NonManifoldEdge {
        /// First vertex of the edge.
        a: u32,
        /// Second vertex of the edge.
        b: u32,
        /// How many triangles use it.
        count: usize,
        /// One of these triangles.
        triangle: usize,
    },
    /// Two triangles traverse a shared edge in the same direction.
    #[error(
        "triangles {first} and {second} both traverse edge ({a} -> {b}): orientation is inconsistent"
    )]
    InconsistentOrientation {
        /// First vertex of the directed edge.
        a: u32,
        /// Second vertex of the directed edge.
        b: u32,
        /// First triangle.
        first: usize,
        /// Second triangle.
        second: usize,
    },
    /// A connected component's normals point into the body (e.g. an inner cavity oriented like
    /// the outer surface): just outside it along its normal the winding number is ≈ 1, not 0.
    #[error(
        "the component containing triangle {triangle} faces into the body (winding number {winding:.3} just outside it)"
    )]
    ComponentInward {
        /// Largest triangle of the offending component.
        triangle: usize,
        /// Winding number of the whole surface at a point just off that triangle along its normal.
        winding: f64,
    },
    /// The enclosed volume is not positive: normals point inward.
    #[error("the enclosed volume is {volume:e} (must be positive): the surface is oriented inward")]
    NotOutward {
        /// Signed enclosed volume.
        volume: f64,
    },
}

/// Errors of the boundary element solve.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum BemError {
    /// Poisson ratio outside [0, 0.5).
    #[error("Poisson ratio {0} is outside [0, 0.5)")]
    InvalidPoisson(f64),
    /// Shear modulus not a positive finite number.
    #[error("shear modulus {0} must be positive and finite")]
    InvalidShearModulus(f64),
    /// The number of boundary conditions (or values) does not match the number of elements.
    #[error("{what}: expected {expected} entries (one per element), got {got}")]
    WrongLength {
        /// Which input had the wrong length.
        what: &'static str,
        /// Number of elements.
        expected: usize,
        /// Number supplied.
        got: usize,
    },
    /// A load group refers to an element that does not exist.
    #[error("group {group} refers to element {element}, which {reason}")]
    BadGroupElement {
        /// Index of the group.
        group: usize,
        /// Offending element index.
        element: usize,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A prescribed value is NaN or infinite.
    #[error("boundary value on element {element} is not finite")]
    NonFiniteValue {
        /// Element index.
        element: usize,
    },
    /// No element has a prescribed displacement and the gauge was not fixed.
    #[error(
        "no element has a prescribed displacement: the pure-traction problem is singular (rigid-body modes); prescribe a displacement somewhere or set SolveParams::rigid_modes = RigidModes::Fix"
    )]
    PureTraction,
    /// A separate body (see [`crate::SurfaceMesh::body`]) has no displacement-prescribed element:
    /// nothing holds it, its rigid motions are free and the system is singular.
    #[error(
        "body {body} of {bodies} (the surface component containing element {element}) has no prescribed displacement: nothing holds it, so its rigid-body motion is undetermined; prescribe a displacement on it"
    )]
    FloatingBody {
        /// Index of the body.
        body: usize,
        /// Its first element.
        element: usize,
        /// Number of bodies in the mesh.
        bodies: usize,
    },
    /// The estimated condition number of the system matrix exceeds the accepted limit
    /// ([`crate::SolveParams::max_condition`]): the answer would be dominated by rounding.
    #[error(
        "the system is near-singular: estimated condition number {estimate:.2e} (columns scaled to unit 1-norm) is above the limit {limit:.1e}; e.g. surfaces nearly touching or a body barely held"
    )]
    IllConditioned {
        /// Hager–Higham estimate of κ₁ of the column-equilibrated matrix.
        estimate: f64,
        /// The limit it exceeded.
        limit: f64,
    },
    /// The system matrix is numerically singular.
    #[error(
        "the system matrix is numerically singular: pivot {index} has magnitude {pivot:e} against largest pivot {max_pivot:e}"
    )]
    Singular {
        /// Index of the smallest pivot.
        index: usize,
        /// Its magnitude.
        pivot: f64,
        /// Largest pivot magnitude.
        max_pivot: f64,
    },
    /// The mixed-precision solve's iterative refinement stopped converging
    /// ([`crate::MixedLu::solve_in_place`]); the f64 LU is the fallback.
    #[error("the mixed-precision refinement stalled after at most {rounds} rounds")]
    RefinementStalled {
        /// Most rounds allowed.
        rounds: usize,
    },
    /// The matrix contains NaN or infinite entries.
    #[error("the {what} contains non-finite entries")]
    NonFinite {
        /// Which matrix or vector.
        what: &'static str,
    },
    /// The dense matrix could not be allocated.
    #[error("cannot allocate a dense {rows}x{cols} matrix ({bytes} bytes)")]
    OutOfMemory {
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
        /// Bytes requested.
        bytes: usize,
    },
    /// The dense solve would need more memory than the budget
    /// ([`crate::SolveParams::memory_budget_bytes`], by default the memory available).
    #[error(
        "the dense solve needs {needed_bytes} bytes (K {matrix_bytes}, right-hand sides {rhs_bytes}, buffers the rest) but the memory budget is {budget_bytes} bytes; use fewer elements or load cases"
    )]
    OverBudget {
        /// Peak bytes the assembly and solve would hold ([`crate::MemoryEstimate::total`]).
        needed_bytes: u64,
        /// The budget.
        budget_bytes: u64,
        /// Of which K.
        matrix_bytes: u64,
        /// Of which the right-hand sides.
        rhs_bytes: u64,
    },
    /// An internal invariant failed (a bug in bem-core, please report it).
    #[error("internal error: {what}")]
    Internal {
        /// Which invariant.
        what: &'static str,
    },
    /// The computation was cancelled through [`crate::Control::cancel`].
    #[error("cancelled")]
    Cancelled,
}
