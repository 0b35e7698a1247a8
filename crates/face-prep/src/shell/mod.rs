//! The closed elastic shell (thesis ch. 5): front face, offset back face, rim strip.
//!
//! Construction, all lengths absolute ([`ShellDims`], derived from [`crate::RigParams`]):
//!
//! 0. Front repair ([`repair_front_intersections`]): the shell's copy of the front surface must
//!    not intersect itself, nor press two of its parts together (a crack, on which the BEM
//!    system is near-singular). Where the input does (the ICT faces' lips roll inward, cross
//!    each other near the mouth corners and press together along the mouth), the vertices
//!    involved are pushed apart by small local moves until no triangle pair intersects and
//!    facing parts keep a clearance of [`FRONT_CLEARANCE`] × the local edge length. The input
//!    mesh itself is never changed, front vertex `i` stays input vertex `i`, and an input
//!    without such defects is used bit for bit; [`Shell::front_repair`] records how many
//!    vertices moved and how far.
//! 1. Offset direction per vertex: the area-weighted vertex normal, or, where an incident
//!    triangle disagrees with it (folds such as mouth corners), the candidate direction with the
//!    best worst-case agreement ([`offset_directions`]).
//! 2. A few Laplacian smoothing passes of the offset directions (interior vertices).
//! 3. Inward displacement along the smoothed direction: `offset` for interior vertices, tapered
//!    to zero toward the eye and mouth contours ([`knife_edge_taper`] over `taper`, measured
//!    along mesh edges), which stay fixed as knife edges with a finite wedge angle; `thickness`
//!    for the outer contour, whose back copy closes the rim. Any vertex whose displacement does
//!    not go behind all of its incident front triangles falls back to step 1's direction.
//! 4. Each displacement is clamped to `clamp_fraction` of the free distance to the front surface
//!    along it (nostrils, rolled lips).
//! 5. Back triangles are the front ones reversed; an interior edge joining two eye/mouth
//!    contour vertices (a "chord") would coincide with its front twin, so on the back it is split
//!    at a displaced mid-point. The rim joins each outer-contour edge to its back copy.
//! 6. Local repair: back/rim elements found intersecting anything (BVH triangle–triangle test)
//!    get their moved vertices redirected, then their offset shrunk by [`REPAIR_SHRINK`] per
//!    round, for a few rounds; vertices still intersecting afterwards get their full offset back
//!    and are then moved, one at a time, to whichever of a set of nearby candidate positions
//!    leaves the fewest intersections (tight folds where the lips meet at a mouth corner).
//!
//! Vertex layout: face vertices `0..n` (the input's, moved only by step 0), then back copies of
//! every vertex not on an eye or mouth contour (outer contour copies included) in face order,
//! then chord mid-points. Element layout: front triangles `0..f`, back triangles (in
//! face-triangle order, split ones contiguous), rim triangles (two per outer-contour edge, in
//! loop order).

mod back_repair;
mod build;
mod front_repair;
mod intersect;
mod model;
mod offset;

pub use crate::closest_point::closest_point_on_triangle;
pub use back_repair::REPAIR_SHRINK;
pub use front_repair::{
    FACING_COSINE, FRONT_CLEARANCE, FRONT_REPAIR_GAP, MAX_MOVE_EDGES, MAX_REPAIRABLE_CROSSINGS,
    repair_front_intersections,
};
pub use intersect::{intersecting_pairs, most_crossed};
pub use model::{ElementTag, FrontRepair, Shell, ShellDims};
pub use offset::{knife_edge_taper, offset_directions, vertex_adjacency, vertex_normals};
