//! The closed elastic shell (thesis ch. 5): front face, offset back face, rim strip.
//!
//! Construction, all lengths absolute ([`ShellDims`], derived from [`crate::RigParams`]):
//!
//! 1. Offset direction per vertex: the area-weighted vertex normal, or, where an incident
//!    triangle disagrees with it (folds such as mouth corners), the candidate direction with the
//!    best worst-case agreement ([`offset_directions`]).
//! 2. Target inward displacement: `offset` for interior vertices, tapered to zero (smoothstep
//!    over `taper`, measured along mesh edges) toward the eye and mouth contours, which stay
//!    fixed as knife edges; `thickness` for the outer contour, whose back copy closes the rim.
//! 3. A few Laplacian smoothing passes of the displacement field; any vertex whose displacement
//!    no longer goes behind all of its incident front triangles falls back to step 1's direction.
//! 4. Each displacement is clamped to `clamp_fraction` of the free distance to the front surface
//!    along it (nostrils, rolled lips).
//! 5. Back triangles are the front ones reversed; an interior edge joining two eye/mouth
//!    contour vertices (a "chord") would coincide with its front twin, so on the back it is split
//!    at a displaced mid-point. The rim joins each outer-contour edge to its back copy.
//! 6. Local repair: back/rim elements found intersecting anything (BVH triangle–triangle test)
//!    get their moved vertices redirected, then their offset halved, for a few rounds; vertices
//!    still intersecting afterwards sit where the input itself overlaps and keep their offset.
//!
//! Vertex layout: face vertices `0..n`, then back copies of every vertex not on an eye or mouth
//! contour (outer contour copies included) in face order, then chord mid-points. Element
//! layout: front triangles `0..f`, back triangles (in face-triangle order, split ones
//! contiguous), rim triangles (two per outer-contour edge, in loop order).

use crate::bvh::{TriangleBvh, segment_crosses_triangle};
use crate::orient::FaceLoops;
use glam::DVec3;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// Which part of the shell an element belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
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
/// Contract: vertices `0..n_face_vertices` are exactly the face's vertices (canonical frame, same
/// order) and triangles `0..n_face_triangles` are the face's triangles (front element `i` = face
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
}

/// Area-weighted vertex normals of a triangle mesh (+z where undefined).
pub fn vertex_normals(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Vec<DVec3> {
    let mut n = vec![DVec3::ZERO; vertices.len()];
    for t in triangles {
        let p = t.map(|i| vertices[i as usize]);
        let c = (p[1] - p[0]).cross(p[2] - p[0]);
        for &i in t {
            n[i as usize] += c;
        }
    }
    n.into_iter()
        .map(|v| v.try_normalize().unwrap_or(DVec3::Z))
        .collect()
}

impl Shell {
    /// Builds the shell from the face (canonical frame) and its classified loops.
    pub fn build(
        vertices: &[DVec3],
        triangles: &[[u32; 3]],
        loops: &FaceLoops,
        dims: ShellDims,
    ) -> Shell {
        let n = vertices.len();
        let normals = offset_directions(vertices, triangles);
        let front_tris: Vec<[DVec3; 3]> = triangles
            .iter()
            .map(|t| t.map(|i| vertices[i as usize]))
            .collect();
        let front_bvh = TriangleBvh::new(&front_tris);
        // Inward move of a point, clamped by the distance to the front surface along −normal.
        let moved = |p: DVec3, normal: DVec3, distance: f64| -> DVec3 {
            let dir = -normal;
            let min_t = 1e-6 * distance;
            let free = front_bvh
                .ray_hits(p, dir)
                .into_iter()
                .find(|h| h.t > min_t)
                .map(|h| h.t)
                .unwrap_or(f64::INFINITY);
            p + dir * distance.min(dims.clamp_fraction * free)
        };
        let mut kind = vec![0u8; n]; // 0 interior, 1 inner contour, 2 outer contour
        for l in [&loops.eye_l, &loops.eye_r, &loops.mouth] {
            for &v in l.iter() {
                kind[v as usize] = 1;
            }
        }
        for &v in &loops.face {
            kind[v as usize] = 2;
        }
        let adjacency = vertex_adjacency(n, triangles);
        let dist = contour_distance(vertices, &adjacency, &kind);
        let taper = |d: f64| {
            let s = if dims.taper > 0.0 {
                (d / dims.taper).min(1.0)
            } else {
                1.0
            };
            s * s * (3.0 - 2.0 * s)
        };
        // Target inward displacement: the full offset away from the eyes and mouth, tapered to
        // zero at their knife edges (smoothstep over `taper`), the thickness at the outer contour.
        let mut disp: Vec<DVec3> = (0..n)
            .map(|v| match kind[v] {
                1 => DVec3::ZERO,
                2 => -normals[v] * dims.thickness,
                _ => -normals[v] * dims.offset * taper(dist[v]),
            })
            .collect();
        // Laplacian smoothing of the displacement of interior vertices: irons out folds where
        // vertex normals turn fast (mouth corners, nostril rims, lips).
        for _ in 0..dims.smoothing_iterations {
            let prev = disp.clone();
            for v in 0..n {
                if kind[v] == 0 && !adjacency[v].is_empty() {
                    let avg = adjacency[v]
                        .iter()
                        .map(|&u| prev[u as usize])
                        .sum::<DVec3>()
                        / adjacency[v].len() as f64;
                    disp[v] = 0.5 * (prev[v] + avg);
                }
            }
        }
        // Every moved vertex must go behind all of its incident front triangles; where the
        // smoothed field does not, fall back to the robust offset direction.
        let mut incident: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (ti, t) in triangles.iter().enumerate() {
            for &i in t {
                incident[i as usize].push(ti);
            }
        }
        let tri_normal = |ti: usize| {
            let p = front_tris[ti];
            (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero()
        };
        for v in 0..n {
            let len = disp[v].length();
            if kind[v] == 1 || len == 0.0 {
                continue;
            }
            let worst = incident[v]
                .iter()
                .map(|&t| tri_normal(t).dot(disp[v]) / len)
                .fold(f64::NEG_INFINITY, f64::max);
            if worst > -0.1 {
                disp[v] = -normals[v] * len;
            }
        }
        let mut out_v = vertices.to_vec();
        let mut anchor = vertices.to_vec();
        let mut robust_dir = normals.clone();
        let mut back_of = vec![u32::MAX; n];
        let new_back: Vec<(usize, DVec3)> = (0..n)
            .into_par_iter()
            .filter(|&v| kind[v] != 1)
            .map(|v| {
                let d = disp[v];
                let len = d.length();
                let dir = d.try_normalize().unwrap_or(-normals[v]);
                (v, moved(vertices[v], -dir, len))
            })
            .collect();
        for (v, p) in new_back {
            back_of[v] = out_v.len() as u32;
            out_v.push(p);
            anchor.push(vertices[v]);
            robust_dir.push(normals[v]);
        }
        for v in 0..n {
            if kind[v] == 1 {
                back_of[v] = v as u32;
            }
        }
        // Chords: interior edges joining two inner-contour vertices. On the back they would
        // coincide with the front edge, so the back side splits them at an offset mid-point.
        let mut boundary_edges = std::collections::HashSet::new();
        for l in [&loops.eye_l, &loops.eye_r, &loops.mouth] {
            for i in 0..l.len() {
                let (a, b) = (l[i], l[(i + 1) % l.len()]);
                boundary_edges.insert((a.min(b), a.max(b)));
            }
        }
        let mut chord_mid: HashMap<(u32, u32), u32> = HashMap::new();
        let mid_start = out_v.len() as u32;
        for t in triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let key = (a.min(b), a.max(b));
                if kind[a as usize] == 1 && kind[b as usize] == 1 && !boundary_edges.contains(&key)
                {
                    chord_mid.entry(key).or_insert_with(|| {
                        let m = 0.5 * (vertices[a as usize] + vertices[b as usize]);
                        let nm = (normals[a as usize] + normals[b as usize])
                            .try_normalize()
                            .unwrap_or(DVec3::Z);
                        out_v.push(moved(
                            m,
                            nm,
                            dims.offset
                                * taper(0.5 * vertices[a as usize].distance(vertices[b as usize])),
                        ));
                        anchor.push(m);
                        robust_dir.push(nm);
                        (out_v.len() - 1) as u32
                    });
                }
            }
        }
        let mut out_t = triangles.to_vec();
        let mut tags = vec![ElementTag::Front; triangles.len()];
        let mut source: Vec<u32> = (0..triangles.len() as u32).collect();
        for (ti, t) in triangles.iter().enumerate() {
            // Back polygon, reversed orientation: t0, t2, t1 with chord mid-points inserted.
            let rev = [t[0], t[2], t[1]];
            let mut poly = Vec::with_capacity(6);
            for k in 0..3 {
                let (a, b) = (rev[k], rev[(k + 1) % 3]);
                poly.push(back_of[a as usize]);
                if let Some(&m) = chord_mid.get(&(a.min(b), a.max(b))) {
                    poly.push(m);
                }
            }
            // Fan from a chord mid-point if any (never degenerate), else the plain triangle.
            let start = (0..poly.len()).find(|&i| poly[i] >= mid_start).unwrap_or(0);
            poly.rotate_left(start);
            for i in 1..poly.len() - 1 {
                out_t.push([poly[0], poly[i], poly[i + 1]]);
                tags.push(ElementTag::Back);
                source.push(ti as u32);
            }
        }
        // Rim: the front's outer boundary half-edge a→b is completed by (b, a, a'), (b, a', b').
        let mut owner: HashMap<(u32, u32), u32> = HashMap::new();
        for (ti, t) in triangles.iter().enumerate() {
            for k in 0..3 {
                owner.insert((t[k], t[(k + 1) % 3]), ti as u32);
            }
        }
        let f = &loops.face;
        for i in 0..f.len() {
            let (a, b) = (f[i], f[(i + 1) % f.len()]);
            let (a2, b2) = (back_of[a as usize], back_of[b as usize]);
            let src = owner.get(&(a, b)).copied().unwrap_or(0);
            out_t.push([b, a, a2]);
            out_t.push([b, a2, b2]);
            tags.extend([ElementTag::Rim, ElementTag::Rim]);
            source.extend([src, src]);
        }
        let mut shell = Shell {
            vertices: out_v,
            triangles: out_t,
            tags,
            source_triangle: source,
        };
        shell.repair_back_intersections(n, &anchor, &robust_dir, dims.repair_rounds);
        shell
    }

    /// Where back or rim elements intersect another element, their moved vertices first switch
    /// to the robust offset direction (`robust_dir`, outward) and then get half their offset
    /// per round (toward their anchors on the front face), for at most `rounds` rounds.
    /// Intersections between two front elements belong to the input and are left alone.
    fn repair_back_intersections(
        &mut self,
        n_front: usize,
        anchor: &[DVec3],
        robust_dir: &[DVec3],
        rounds: usize,
    ) {
        let mut disp: Vec<DVec3> = self
            .vertices
            .iter()
            .zip(anchor)
            .map(|(p, a)| *p - *a)
            .collect();
        let mut redirected = vec![false; self.vertices.len()];
        let mut scale = vec![1.0f64; self.vertices.len()];
        for _ in 0..rounds {
            let bad = self.self_intersections();
            let mut shrink = std::collections::HashSet::new();
            for pair in bad {
                for e in pair {
                    if self.tags[e as usize] != ElementTag::Front {
                        shrink.extend(
                            self.triangles[e as usize]
                                .iter()
                                .copied()
                                .filter(|&v| v as usize >= n_front),
                        );
                    }
                }
            }
            if shrink.is_empty() {
                return;
            }
            for v in shrink {
                let v = v as usize;
                if !redirected[v] {
                    redirected[v] = true;
                    disp[v] = -robust_dir[v] * disp[v].length();
                } else {
                    scale[v] *= 0.5;
                }
                self.vertices[v] = anchor[v] + disp[v] * scale[v];
            }
        }
        // Vertices still in an intersection after every round sit where the input itself
        // overlaps (e.g. interpenetrating lips): shrinking them gains nothing and only makes
        // the shell needlessly thin there, so they get their full (redirected) offset back.
        let stuck: std::collections::HashSet<u32> = self
            .self_intersections()
            .into_iter()
            .flatten()
            .filter(|&e| self.tags[e as usize] != ElementTag::Front)
            .flat_map(|e| self.triangles[e as usize])
            .filter(|&v| v as usize >= n_front)
            .collect();
        for v in stuck {
            let v = v as usize;
            self.vertices[v] = anchor[v] + disp[v];
        }
    }

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

    /// Pairs of elements that intersect each other (BVH-accelerated). Pairs sharing an edge
    /// are not tested; pairs sharing one vertex are tested with their edges opposite to it.
    /// Empty for a valid shell.
    pub fn self_intersections(&self) -> Vec<[u32; 2]> {
        let tris: Vec<[DVec3; 3]> = (0..self.triangles.len()).map(|e| self.corners(e)).collect();
        let bvh = TriangleBvh::new(&tris);
        let mut pairs: Vec<[u32; 2]> = (0..tris.len())
            .into_par_iter()
            .flat_map_iter(|i| {
                let a = &tris[i];
                let lo = a[0].min(a[1]).min(a[2]);
                let hi = a[0].max(a[1]).max(a[2]);
                let ta = self.triangles[i];
                let mut found = Vec::new();
                for j in bvh.overlapping(lo, hi) {
                    let j = j as usize;
                    if j <= i {
                        continue;
                    }
                    let tb = self.triangles[j];
                    let shared: Vec<u32> = ta.iter().copied().filter(|v| tb.contains(v)).collect();
                    let b = &tris[j];
                    let hit = match shared.len() {
                        0 => (0..3).any(|k| {
                            segment_crosses_triangle(a[k], a[(k + 1) % 3], b)
                                || segment_crosses_triangle(b[k], b[(k + 1) % 3], a)
                        }),
                        1 => {
                            let ka = ta.iter().position(|&v| v == shared[0]).unwrap_or(0);
                            let kb = tb.iter().position(|&v| v == shared[0]).unwrap_or(0);
                            segment_crosses_triangle(a[(ka + 1) % 3], a[(ka + 2) % 3], b)
                                || segment_crosses_triangle(b[(kb + 1) % 3], b[(kb + 2) % 3], a)
                        }
                        _ => false,
                    };
                    if hit {
                        found.push([i as u32, j as u32]);
                    }
                }
                found
            })
            .collect();
        pairs.sort_unstable();
        pairs
    }
}

/// Offset directions: per vertex, the unit outward direction that is most consistently
/// "outward" for all incident triangles. Starts from the area-weighted normal; where some incident
/// triangle disagrees with it (dot < 0.3, folds at mouth corners), the candidate among the
/// area-weighted normal, the unit-weighted normal and each incident triangle normal with the
/// largest minimum dot product over the incident triangles is taken instead.
pub fn offset_directions(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Vec<DVec3> {
    let area_weighted = vertex_normals(vertices, triangles);
    let mut incident: Vec<Vec<DVec3>> = vec![Vec::new(); vertices.len()];
    for t in triangles {
        let p = t.map(|i| vertices[i as usize]);
        if let Some(nt) = (p[1] - p[0]).cross(p[2] - p[0]).try_normalize() {
            for &i in t {
                incident[i as usize].push(nt);
            }
        }
    }
    area_weighted
        .into_iter()
        .zip(&incident)
        .map(|(n, faces)| {
            let worst = |c: DVec3| faces.iter().map(|f| f.dot(c)).fold(f64::INFINITY, f64::min);
            if faces.is_empty() || worst(n) >= 0.3 {
                return n;
            }
            let unit = faces
                .iter()
                .copied()
                .sum::<DVec3>()
                .try_normalize()
                .unwrap_or(n);
            std::iter::once(n)
                .chain(std::iter::once(unit))
                .chain(faces.iter().copied())
                .max_by(|a, b| worst(*a).total_cmp(&worst(*b)))
                .unwrap_or(n)
        })
        .collect()
}

/// Neighbouring vertices of every vertex (sorted, no repeats).
pub fn vertex_adjacency(n: usize, triangles: &[[u32; 3]]) -> Vec<Vec<u32>> {
    let mut adj = vec![Vec::new(); n];
    for t in triangles {
        for k in 0..3 {
            adj[t[k] as usize].push(t[(k + 1) % 3]);
            adj[t[(k + 1) % 3] as usize].push(t[k]);
        }
    }
    for a in &mut adj {
        a.sort_unstable();
        a.dedup();
    }
    adj
}

/// Shortest distance along mesh edges from every vertex to the nearest vertex with
/// `kind == 1` (eye or mouth contour); infinite where unreachable.
fn contour_distance(vertices: &[DVec3], adjacency: &[Vec<u32>], kind: &[u8]) -> Vec<f64> {
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;
    let mut dist = vec![f64::INFINITY; vertices.len()];
    let mut heap = BinaryHeap::new();
    for (v, &k) in kind.iter().enumerate() {
        if k == 1 {
            dist[v] = 0.0;
            heap.push(Reverse((0u64, v as u32)));
        }
    }
    // Non-negative f64 bit patterns order like the values.
    while let Some(Reverse((d_bits, v))) = heap.pop() {
        let d = f64::from_bits(d_bits);
        if d > dist[v as usize] {
            continue;
        }
        for &u in &adjacency[v as usize] {
            let nd = d + vertices[v as usize].distance(vertices[u as usize]);
            if nd < dist[u as usize] {
                dist[u as usize] = nd;
                heap.push(Reverse((nd.to_bits(), u)));
            }
        }
    }
    dist
}
