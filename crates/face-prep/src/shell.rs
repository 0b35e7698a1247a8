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

/// Outcome of [`repair_front_intersections`]: how far the shell's front surface departs from
/// the input face.
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
    /// ([`repair_front_intersections`]); 0 keeps the front exactly as the input.
    pub front_repair_rounds: usize,
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
    /// Builds the shell from the face (canonical frame) and its classified loops: front repair,
    /// back face, rim and local repair (see the module docs).
    pub fn build(
        input: &[DVec3],
        triangles: &[[u32; 3]],
        loops: &FaceLoops,
        dims: ShellDims,
    ) -> Shell {
        let mut front = input.to_vec();
        let front_repair =
            repair_front_intersections(&mut front, triangles, dims.front_repair_rounds);
        let vertices: &[DVec3] = &front;
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
        let taper = |d: f64| knife_edge_taper(d, dims.taper);
        // Offset directions, smoothed: start from the full inward offset everywhere (the eye and
        // mouth contours included, so that their neighbours' directions are not biased), then
        // Laplacian-smooth the interior vertices. This irons out folds where vertex normals turn
        // fast (mouth corners, nostril rims, lips). Only the direction is kept: the magnitude
        // is set afterwards from the taper, so smoothing cannot thin the tissue next to a knife
        // edge (smoothing magnitudes pinned at zero on the contours made the back face tangent
        // to the front there: a zero-angle wedge, on which the BEM system is near-singular).
        let mut disp: Vec<DVec3> = (0..n)
            .map(|v| match kind[v] {
                2 => -normals[v] * dims.thickness,
                _ => -normals[v] * dims.offset,
            })
            .collect();
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
        // Target inward displacement: the full offset away from the eyes and mouth, tapered to
        // zero at their knife edges, the thickness at the outer contour.
        for v in 0..n {
            match kind[v] {
                1 => disp[v] = DVec3::ZERO,
                0 => {
                    let dir = disp[v].try_normalize().unwrap_or(-normals[v]);
                    disp[v] = dir * dims.offset * taper(dist[v]);
                }
                _ => {}
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
            front_repair,
        };
        shell.repair_back_intersections(n, &anchor, &robust_dir, dims.repair_rounds);
        shell
    }

    /// Where back or rim elements intersect another element, their moved vertices first switch
    /// to the robust offset direction (`robust_dir`, outward) and then have their offset scaled
    /// by [`REPAIR_SHRINK`] per round (toward their anchors on the front face), for at most
    /// `rounds` rounds.
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
                    scale[v] *= REPAIR_SHRINK;
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
        let mut stuck: Vec<usize> = stuck.into_iter().map(|v| v as usize).collect();
        stuck.sort_unstable();
        for &v in &stuck {
            self.vertices[v] = anchor[v] + disp[v];
        }
        self.relocate_stuck(&stuck, anchor, &disp, robust_dir);
    }

    /// Last resort for back vertices still in an intersection after the repair rounds (tight
    /// folds such as the corners of pressed-together lips, where no single direction is behind
    /// every incident front triangle): a few sweeps of a local search that moves each such
    /// vertex to the candidate position with the fewest intersections of its incident elements.
    /// Candidates: the current position; along its repair direction, its robust direction and
    /// the mean of its neighbours' offsets at 1, 1/2, …, 1/1024 of its offset; along the 26
    /// axis and diagonal directions at 1, 1/2, …, 1/32 of it; the mean of its neighbours.
    /// Positions that would make an incident element a sliver are skipped. Ties keep the
    /// earlier candidate (the current one first), so a vertex only moves when that removes
    /// intersections; a shell without intersections is never touched.
    fn relocate_stuck(
        &mut self,
        stuck: &[usize],
        anchor: &[DVec3],
        disp: &[DVec3],
        robust_dir: &[DVec3],
    ) {
        if stuck.is_empty() {
            return;
        }
        let nv = self.vertices.len();
        let mut incident: Vec<Vec<usize>> = vec![Vec::new(); nv];
        for (e, t) in self.triangles.iter().enumerate() {
            for &v in t {
                incident[v as usize].push(e);
            }
        }
        let adjacency = vertex_adjacency(nv, &self.triangles);
        // Work bound: element-pair tests in proportion to the shell's size, so scrambled
        // geometry (long elements overlapping the whole face, many stuck vertices) cannot make
        // this quadratic. When it runs out, the remaining intersections stay (and are reported
        // as the rig's shell self-intersections).
        let budget = std::cell::Cell::new(RELOCATE_TESTS_PER_ELEMENT * self.triangles.len());
        let spend = |n: usize| budget.set(budget.get().saturating_sub(n));
        // The BVH of the current corners, rebuilt only after a vertex actually moved (the
        // same hierarchy as rebuilding it for every vertex, without the repeated builds).
        let mut tris: Vec<[DVec3; 3]> = Vec::new();
        let mut bvh = TriangleBvh::new(&[]);
        let mut stale = true;
        for _ in 0..12 {
            let mut changed = false;
            for &v in stuck {
                let elems = &incident[v];
                if stale {
                    tris = (0..self.triangles.len()).map(|e| self.corners(e)).collect();
                    bvh = TriangleBvh::new(&tris);
                    stale = false;
                }
                let (tris, bvh) = (&tris, &bvh);
                let cost = |shell: &Shell, p: DVec3| -> usize {
                    let corners = |e: usize| {
                        shell.triangles[e].map(|i| {
                            if i as usize == v {
                                p
                            } else {
                                shell.vertices[i as usize]
                            }
                        })
                    };
                    let mut hits = 0;
                    for (k, &e) in elems.iter().enumerate() {
                        let a = corners(e);
                        let longest = (0..3)
                            .map(|i| a[i].distance_squared(a[(i + 1) % 3]))
                            .fold(0.0, f64::max);
                        if (a[1] - a[0]).cross(a[2] - a[0]).length() <= 1e-4 * longest {
                            return usize::MAX;
                        }
                        let lo = a[0].min(a[1]).min(a[2]);
                        let hi = a[0].max(a[1]).max(a[2]);
                        let near = bvh.overlapping(lo, hi);
                        spend(near.len() + elems.len());
                        for f in near {
                            let f = f as usize;
                            if elems.contains(&f) {
                                continue;
                            }
                            if triangles_intersect(
                                shell.triangles[e],
                                &a,
                                shell.triangles[f],
                                &tris[f],
                            ) {
                                hits += 1;
                            }
                        }
                        for &f in &elems[k + 1..] {
                            if triangles_intersect(
                                shell.triangles[e],
                                &a,
                                shell.triangles[f],
                                &corners(f),
                            ) {
                                hits += 1;
                            }
                        }
                    }
                    hits
                };
                let len = disp[v].length();
                let neighbours: Vec<usize> = adjacency[v].iter().map(|&u| u as usize).collect();
                let mean_offset = neighbours
                    .iter()
                    .map(|&u| self.vertices[u] - anchor[u])
                    .sum::<DVec3>();
                let mut candidates = vec![self.vertices[v]];
                for dir in [
                    disp[v].try_normalize(),
                    Some(-robust_dir[v]),
                    mean_offset.try_normalize(),
                ]
                .into_iter()
                .flatten()
                {
                    for k in 0..11 {
                        candidates.push(anchor[v] + dir * len / f64::from(1u32 << k));
                    }
                }
                for x in [-1.0, 0.0, 1.0] {
                    for y in [-1.0, 0.0, 1.0] {
                        for z in [-1.0, 0.0, 1.0] {
                            if let Some(dir) = DVec3::new(x, y, z).try_normalize() {
                                for k in 0..6 {
                                    candidates.push(anchor[v] + dir * len / f64::from(1u32 << k));
                                }
                            }
                        }
                    }
                }
                if !neighbours.is_empty() {
                    candidates.push(
                        neighbours.iter().map(|&u| self.vertices[u]).sum::<DVec3>()
                            / neighbours.len() as f64,
                    );
                }
                if budget.get() == 0 {
                    return;
                }
                let mut best = (cost(self, candidates[0]), 0);
                if best.0 == 0 {
                    continue;
                }
                for (i, &c) in candidates.iter().enumerate().skip(1) {
                    let h = cost(self, c);
                    if h < best.0 {
                        best = (h, i);
                    }
                }
                if best.1 != 0 {
                    self.vertices[v] = candidates[best.1];
                    changed = true;
                    stale = true;
                }
            }
            if !changed {
                break;
            }
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

    /// Pairs of elements that intersect each other (BVH-accelerated, see
    /// [`intersecting_pairs`]). Empty for a valid shell.
    pub fn self_intersections(&self) -> Vec<[u32; 2]> {
        intersecting_pairs(&self.vertices, &self.triangles)
    }
}

/// Pairs `[i, j]`, `i < j`, sorted, of triangles of an indexed mesh that intersect each other
/// (BVH-accelerated). Pairs sharing an edge are not tested; pairs sharing one vertex are tested
/// with their edges opposite to it; touching within a relative tolerance of 1e-9 does not count
/// (see [`segment_crosses_triangle`]).
pub fn intersecting_pairs(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Vec<[u32; 2]> {
    let tris: Vec<[DVec3; 3]> = triangles
        .iter()
        .map(|t| t.map(|i| vertices[i as usize]))
        .collect();
    let bvh = TriangleBvh::new(&tris);
    let mut pairs: Vec<[u32; 2]> = (0..tris.len())
        .into_par_iter()
        .flat_map_iter(|i| {
            let a = &tris[i];
            let lo = a[0].min(a[1]).min(a[2]);
            let hi = a[0].max(a[1]).max(a[2]);
            let ta = triangles[i];
            let mut found = Vec::new();
            for j in bvh.overlapping(lo, hi) {
                let j = j as usize;
                if j <= i {
                    continue;
                }
                if triangles_intersect(ta, a, triangles[j], &tris[j]) {
                    found.push([i as u32, j as u32]);
                }
            }
            found
        })
        .collect();
    pairs.sort_unstable();
    pairs
}

/// The triangle in the most of `pairs` (as from [`intersecting_pairs`] over `triangle_count`
/// triangles) and in how many; `None` without pairs. Ties give the lowest index.
///
/// ```
/// use face_prep::shell::most_crossed;
/// assert_eq!(most_crossed(&[[0, 2], [1, 2], [2, 3]], 4), Some((2, 3)));
/// assert_eq!(most_crossed(&[], 4), None);
/// ```
pub fn most_crossed(pairs: &[[u32; 2]], triangle_count: usize) -> Option<(usize, usize)> {
    let mut crossings = vec![0usize; triangle_count];
    for &[a, b] in pairs {
        for t in [a, b] {
            if let Some(c) = crossings.get_mut(t as usize) {
                *c += 1;
            }
        }
    }
    let (t, c) = crossings
        .iter()
        .enumerate()
        .max_by_key(|&(t, &c)| (c, std::cmp::Reverse(t)))?;
    (*c > 0).then_some((t, *c))
}

/// Whether two triangles of one indexed mesh (indices `ta`, `tb`, corners `a`, `b`) intersect:
/// never when they share an edge; with their edges opposite to a shared vertex; else any edge
/// of one crossing the other.
fn triangles_intersect(ta: [u32; 3], a: &[DVec3; 3], tb: [u32; 3], b: &[DVec3; 3]) -> bool {
    let mut shared = ta.iter().copied().filter(|v| tb.contains(v));
    match (shared.next(), shared.next()) {
        (None, _) => (0..3).any(|k| {
            segment_crosses_triangle(a[k], a[(k + 1) % 3], b)
                || segment_crosses_triangle(b[k], b[(k + 1) % 3], a)
        }),
        (Some(v), None) => {
            let ka = ta.iter().position(|&u| u == v).unwrap_or(0);
            let kb = tb.iter().position(|&u| u == v).unwrap_or(0);
            segment_crosses_triangle(a[(ka + 1) % 3], a[(ka + 2) % 3], b)
                || segment_crosses_triangle(b[(kb + 1) % 3], b[(kb + 2) % 3], a)
        }
        _ => false,
    }
}

/// Element-pair tests [`Shell`]'s last-resort relocation of stuck back vertices may make per
/// shell element: bounds its time by the shell's size on scrambled input (a `v` line swapped:
/// elements spanning the whole face), far above what the bundled faces use.
pub const RELOCATE_TESTS_PER_ELEMENT: usize = 500;

/// Factor applied per repair round to the offset of back/rim vertices of intersecting elements.
/// Gentler than halving: with the full offset kept up to the knife-edge taper, halving thinned
/// concave creases (Lee Perry-Smith's alar groove) to a quarter of the offset, where 0.7 resolves
/// the same intersections at 0.4 or more of it.
pub const REPAIR_SHRINK: f64 = 0.7;

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

pub use crate::closest_point::closest_point_on_triangle;

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

/// Fraction of the full back-face offset at distance `d` (along mesh edges) from an eye or
/// mouth contour, for a taper length `taper`: `s (2 − s)` with `s = min(d / taper, 1)`.
///
/// It starts with a finite slope, so front and back meet at a knife edge with a real wedge
/// angle (the slope is `2 offset / taper`: about 31° at the default settings) instead of
/// tangentially, and it reaches the full offset with zero slope, so the back face has no crease
/// where the taper ends. A `taper` of 0 gives the full offset everywhere.
///
/// ```
/// use face_prep::shell::knife_edge_taper;
/// assert_eq!(knife_edge_taper(0.0, 2.0), 0.0);
/// assert_eq!(knife_edge_taper(1.0, 2.0), 0.75);
/// assert_eq!(knife_edge_taper(5.0, 2.0), 1.0);
/// // Finite slope at the contour: 2 / taper.
/// assert!((knife_edge_taper(1e-6, 2.0) / 1e-6 - 1.0).abs() < 1e-5);
/// ```
pub fn knife_edge_taper(d: f64, taper: f64) -> f64 {
    let s = if taper > 0.0 {
        (d / taper).clamp(0.0, 1.0)
    } else {
        1.0
    };
    s * (2.0 - s)
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
