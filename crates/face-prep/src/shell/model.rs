//! The shell's data: [`Shell`] and its element tags, the front repair's outcome, the
//! dimensions it is built with, and queries of a built shell.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::intersect::intersecting_pairs;

/// Which part of the shell an element belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[non_exhaustive]
pub enum ElementTag {
    /// A triangle of the user's face (normal toward +z).
    Front,
    /// A triangle of the offset back face (normal toward −z).
    Back,
    /// A triangle of the strip joining the outer contour to its thickened copy.
    Rim,
}

/// The closed, edge-manifold, outward-oriented shell, canonical frame.
///
/// Contract: vertices `0..n_face_vertices` are the face's vertices (canonical frame, same order;
/// exactly, unless the front repair moved some of them, see [`Shell::front_repair`]) and triangles `0..n_face_triangles` are the face's triangles (front element `i` = face
/// triangle `i`). Back and rim elements follow. Eye and mouth contours are knife edges shared
/// by front and back; the outer contour is joined to its copy by the rim, so the surface has
/// genus 3 (V − E + F = −4).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Shell {
    /// Vertex positions.
    pub vertices: Vec<DVec3>,
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// Tag of every element.
    pub tags: Vec<ElementTag>,
    /// For every element, the face triangle it derives from: itself for front elements, the
    /// mirrored front triangle for back elements, the front triangle owning the contour edge for
    /// rim elements.
    pub source_triangle: Vec<u32>,
    /// What the repair of the input's own self-intersections did to the front vertices
    /// (nothing, for an input that does not intersect itself).
    pub front_repair: FrontRepair,
}

/// Outcome of [`repair_front_intersections`](crate::shell::repair_front_intersections): how far
/// the shell's front surface departs from the input face.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FrontRepair {
    /// Intersecting front/front triangle pairs of the input (see [`intersecting_pairs`]).
    pub input_intersections: usize,
    /// Intersecting front/front pairs left after the repair (0 unless the rounds ran out).
    pub remaining_intersections: usize,
    /// Repair rounds run.
    pub rounds: usize,
    /// Front vertices that were moved.
    pub moved_vertices: usize,
    /// Largest distance between a shell front vertex and its input position (face units,
    /// canonical frame); 0 when nothing was moved.
    pub max_displacement: f64,
}

/// Absolute shell dimensions, in the face's units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShellDims {
    /// Back-face offset along the inward vertex normal.
    pub offset: f64,
    /// How far the outer contour's copy is moved along the inward normal.
    pub thickness: f64,
    /// Each back vertex moves at most this fraction of the distance, along its inward normal,
    /// to the front surface (keeps the back face inside deep concavities such as nostrils).
    pub clamp_fraction: f64,
    /// Distance (along mesh edges) from the eye and mouth contours over which the offset
    /// grows from zero to `offset` (smoothstep).
    pub taper: f64,
    /// Laplacian smoothing iterations applied to the back-face displacement field.
    pub smoothing_iterations: usize,
    /// Rounds of local repair: back/rim vertices of intersecting elements get half their
    /// offset per round.
    pub repair_rounds: usize,
    /// Rounds of repair of the input front surface's own self-intersections
    /// ([`repair_front_intersections`](crate::shell::repair_front_intersections)); 0 keeps the
    /// front exactly as the input.
    pub front_repair_rounds: usize,
}

impl Shell {
    /// Number of elements (triangles).
    pub fn element_count(&self) -> usize {
        self.triangles.len()
    }

    /// Corner positions of element `e`.
    pub fn corners(&self, e: usize) -> [DVec3; 3] {
        self.triangles[e].map(|i| self.vertices[i as usize])
    }

    /// Centroid (collocation point) of element `e`.
    pub fn centroid(&self, e: usize) -> DVec3 {
        let p = self.corners(e);
        (p[0] + p[1] + p[2]) / 3.0
    }

    /// Euler characteristic V − E + F (−4 for a correct face shell).
    pub fn euler_characteristic(&self) -> i64 {
        let mut edges = std::collections::HashSet::new();
        for t in &self.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                edges.insert((a.min(b), a.max(b)));
            }
        }
        self.vertices.len() as i64 - edges.len() as i64 + self.triangles.len() as i64
    }

    /// Signed enclosed volume (positive when the shell is outward oriented).
    pub fn signed_volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let p = t.map(|i| self.vertices[i as usize]);
                p[0].dot(p[1].cross(p[2])) / 6.0
            })
            .sum()
    }

    /// Pairs of elements that intersect each other (BVH-accelerated, see
    /// [`intersecting_pairs`]). Empty for a valid shell.
    pub fn self_intersections(&self) -> Vec<[u32; 2]> {
        intersecting_pairs(&self.vertices, &self.triangles)
    }
}
