//! Step 0 of the shell construction: opening the input front surface's own
//! self-intersections and cracks by small local vertex moves.

use glam::DVec3;
use rayon::prelude::*;

use super::intersect::{intersecting_pairs, most_crossed};
use super::model::FrontRepair;
use super::offset::{vertex_adjacency, vertex_normals};
use crate::bvh::TriangleBvh;
use crate::closest_point::closest_point_on_triangle;

/// Separation left between two repaired front triangles, as a fraction of the longest edge of
/// the triangle a vertex is pushed out of.
pub const FRONT_REPAIR_GAP: f64 = 0.02;

/// Smallest clearance kept across an exterior gap of the front surface (two parts of it facing
/// each other, e.g. upper and lower lip), as a fraction of the mean edge length at the vertex.
/// The bundled MediaPipe and Lee Perry-Smith faces have at least 0.39 (at their mouth
/// corners); the ICT faces' pressed-together lips 0.01–0.1, a crack that makes the BEM system
/// near-singular.
pub const FRONT_CLEARANCE: f64 = 0.3;

/// Most intersecting front triangle pairs one triangle may be part of for
/// [`repair_front_intersections`] to try to open them. At a fold (pressed or rolled lips) a
/// triangle crosses a few neighbours of the other sheet (the bundled faces: at most 9, ICT 13k); a
/// triangle crossing dozens spans the surface: scrambled geometry (a swapped `v` line), which
/// local pushes cannot repair and on which every round costs O(triangles²). Such a surface is
/// left as it is after one intersection pass.
pub const MAX_REPAIRABLE_CROSSINGS: usize = 32;

/// No front vertex is moved further than this many of its mean edge lengths from the input.
pub const MAX_MOVE_EDGES: f64 = 1.0;

/// Two normals count as facing each other below this cosine.
pub const FACING_COSINE: f64 = -0.3;

/// Opens the self-intersections and cracks of a front surface (e.g. lips that roll inward and
/// cross or press against each other) by small local vertex moves, in place.
///
/// Each round:
/// 1. Intersecting triangle pairs ([`intersecting_pairs`]) each straddle the other's plane;
///    every vertex of one that lies behind the other (against its outward normal, i.e. inside
///    the other sheet's tissue) is pushed along the other triangle's normal by half its depth
///    plus half a gap of [`FRONT_REPAIR_GAP`] × that triangle's longest edge.
/// 2. A vertex that faces a triangle (normals opposite within [`FACING_COSINE`], each in front
///    of the other) not touching its one-ring at less than [`FRONT_CLEARANCE`] × its mean edge
///    length is pushed along that triangle's normal by half the shortfall.
///
/// A vertex pushed by several triangles takes the largest push; both sides move, so they meet
/// half-way; no vertex ends up further than [`MAX_MOVE_EDGES`] of its mean edge lengths from
/// where it started. Rounds repeat until nothing is left to do or `rounds` ran out; the result
/// is the latest state with the fewest intersecting pairs. A surface with a triangle in more
/// than [`MAX_REPAIRABLE_CROSSINGS`] intersecting pairs is scrambled, not folded, and is
/// returned unchanged. Vertices of no offending pair never
/// move, and a surface without any is left bit-for-bit unchanged.
pub fn repair_front_intersections(
    vertices: &mut [DVec3],
    triangles: &[[u32; 3]],
    rounds: usize,
) -> FrontRepair {
    let original = vertices.to_vec();
    let n = vertices.len();
    let adjacency = vertex_adjacency(n, triangles);
    let mean_edge: Vec<f64> = (0..n)
        .map(|v| {
            let a = &adjacency[v];
            a.iter()
                .map(|&u| vertices[u as usize].distance(vertices[v]))
                .sum::<f64>()
                / a.len().max(1) as f64
        })
        .collect();
    let mut pairs = intersecting_pairs(vertices, triangles);
    let input_intersections = pairs.len();
    if most_crossed(&pairs, triangles.len()).is_some_and(|(_, c)| c > MAX_REPAIRABLE_CROSSINGS) {
        return FrontRepair {
            input_intersections,
            remaining_intersections: input_intersections,
            rounds: 0,
            moved_vertices: 0,
            max_displacement: 0.0,
        };
    }
    // The state with the fewest intersecting pairs so far (the latest among equals).
    let mut best = (pairs.clone(), vertices.to_vec());
    let mut done = 0;
    while done < rounds {
        let mut push: Vec<Option<DVec3>> = vec![None; n];
        let mut propose = |v: u32, d: DVec3| {
            let slot = &mut push[v as usize];
            if slot.is_none_or(|p| p.length_squared() < d.length_squared()) {
                *slot = Some(d);
            }
        };
        for &[a, b] in &pairs {
            for (x, y) in [(a, b), (b, a)] {
                let tx = triangles[x as usize];
                let ty = triangles[y as usize];
                let py = ty.map(|i| vertices[i as usize]);
                let Some(normal) = (py[1] - py[0]).cross(py[2] - py[0]).try_normalize() else {
                    continue;
                };
                let longest = (0..3)
                    .map(|k| py[k].distance(py[(k + 1) % 3]))
                    .fold(0.0, f64::max);
                let gap = FRONT_REPAIR_GAP * longest;
                for &v in &tx {
                    if ty.contains(&v) {
                        continue;
                    }
                    let depth = -normal.dot(vertices[v as usize] - py[0]);
                    if depth > 0.0 {
                        propose(v, normal * 0.5 * (depth + gap));
                    }
                }
            }
        }
        for (v, d) in clearance_pushes(vertices, triangles, &adjacency, &mean_edge) {
            propose(v, d);
        }
        if push.iter().all(Option::is_none) {
            break;
        }
        done += 1;
        for (v, d) in push.iter().enumerate() {
            if let Some(d) = d {
                // Never further than MAX_MOVE_EDGES mean edge lengths from the input.
                let limit = MAX_MOVE_EDGES * mean_edge[v];
                let total = vertices[v] + *d - original[v];
                vertices[v] = original[v] + total.clamp_length_max(limit);
            }
        }
        pairs = intersecting_pairs(vertices, triangles);
        if pairs.len() <= best.0.len() {
            best = (pairs.clone(), vertices.to_vec());
        }
    }
    if pairs.len() > best.0.len() {
        vertices.copy_from_slice(&best.1);
        pairs = best.0;
    }
    let moves: Vec<f64> = vertices
        .iter()
        .zip(&original)
        .map(|(p, q)| p.distance(*q))
        .collect();
    FrontRepair {
        input_intersections,
        remaining_intersections: pairs.len(),
        rounds: done,
        moved_vertices: moves.iter().filter(|&&m| m > 0.0).count(),
        max_displacement: moves.iter().copied().fold(0.0, f64::max),
    }
}

/// Step 2 of [`repair_front_intersections`]: pushes of the vertices closer than
/// [`FRONT_CLEARANCE`] × their mean edge length to a facing triangle.
fn clearance_pushes(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    adjacency: &[Vec<u32>],
    mean_edge: &[f64],
) -> Vec<(u32, DVec3)> {
    let tris: Vec<[DVec3; 3]> = triangles
        .iter()
        .map(|t| t.map(|i| vertices[i as usize]))
        .collect();
    let bvh = TriangleBvh::new(&tris);
    let normals = vertex_normals(vertices, triangles);
    (0..vertices.len())
        .into_par_iter()
        .filter_map(|v| {
            let p = vertices[v];
            let want = FRONT_CLEARANCE * mean_edge[v];
            if adjacency[v].is_empty() || want <= 0.0 {
                return None;
            }
            let near = |t: &[u32; 3]| {
                t.iter()
                    .any(|&u| u as usize == v || adjacency[v].binary_search(&u).is_ok())
            };
            let mut best: Option<DVec3> = None;
            for t in bvh.overlapping(p - DVec3::splat(want), p + DVec3::splat(want)) {
                let t = t as usize;
                if near(&triangles[t]) {
                    continue;
                }
                let c = &tris[t];
                let Some(nt) = (c[1] - c[0]).cross(c[2] - c[0]).try_normalize() else {
                    continue;
                };
                if nt.dot(normals[v]) > FACING_COSINE {
                    continue;
                }
                let q = closest_point_on_triangle(p, c);
                let gap = p.distance(q);
                // Facing across an exterior gap: each in front of the other.
                if gap >= want || nt.dot(p - q) < 0.0 || normals[v].dot(q - p) < 0.0 {
                    continue;
                }
                let d = nt * 0.5 * (1.05 * want - gap);
                if best.is_none_or(|b| b.length_squared() < d.length_squared()) {
                    best = Some(d);
                }
            }
            best.map(|d| (v as u32, d))
        })
        .collect()
}
