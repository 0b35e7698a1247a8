//! Steps 1–5 of the shell construction: offset directions, the tapered and clamped back face,
//! chord mid-points, back and rim triangles.

use std::collections::{HashMap, HashSet};

use glam::DVec3;
use rayon::prelude::*;

use super::front_repair::repair_front_intersections;
use super::model::{ElementTag, Shell, ShellDims};
use super::offset::{contour_distance, knife_edge_taper, offset_directions, vertex_adjacency};
use crate::bvh::TriangleBvh;
use crate::frame::orient::FaceLoops;

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
        let kind = vertex_kinds(n, loops);
        let surface = FrontSurface {
            vertices,
            triangles,
            front_tris: &front_tris,
            front_bvh: &front_bvh,
            normals: &normals,
            kind: &kind,
            dims: &dims,
        };
        let disp = surface.back_displacements();
        let mut back = surface.back_copies(&disp);
        let (chord_mid, mid_start) = surface.chord_midpoints(loops, &mut back);
        let mut elements = Elements {
            triangles: triangles.to_vec(),
            tags: vec![ElementTag::Front; triangles.len()],
            source: (0..triangles.len() as u32).collect(),
        };
        elements.push_back(triangles, &back.back_of, &chord_mid, mid_start);
        elements.push_rim(triangles, &loops.face, &back.back_of);
        let mut shell = Shell {
            vertices: back.vertices,
            triangles: elements.triangles,
            tags: elements.tags,
            source_triangle: elements.source,
            front_repair,
        };
        shell.repair_back_intersections(n, &back.anchor, &back.robust_dir, dims.repair_rounds);
        shell
    }
}

/// Kind of every face vertex: 0 interior, 1 on an eye or mouth contour (inner contour), 2 on the
/// outer contour.
fn vertex_kinds(n: usize, loops: &FaceLoops) -> Vec<u8> {
    let mut kind = vec![0u8; n]; // 0 interior, 1 inner contour, 2 outer contour
    for l in [&loops.eye_l, &loops.eye_r, &loops.mouth] {
        for &v in l.iter() {
            kind[v as usize] = 1;
        }
    }
    for &v in &loops.face {
        kind[v as usize] = 2;
    }
    kind
}

/// The (repaired) front surface the back face is built from.
struct FrontSurface<'a> {
    vertices: &'a [DVec3],
    triangles: &'a [[u32; 3]],
    /// Corners of every front triangle.
    front_tris: &'a [[DVec3; 3]],
    /// Hierarchy of `front_tris`, for the clamp of inward moves.
    front_bvh: &'a TriangleBvh,
    /// Robust offset direction of every vertex (outward, [`offset_directions`]).
    normals: &'a [DVec3],
    /// [`vertex_kinds`].
    kind: &'a [u8],
    dims: &'a ShellDims,
}

/// The shell's vertices while it is built: the front vertices, then back copies and chord
/// mid-points, each with its anchor on the front and its robust offset direction.
struct BackVertices {
    vertices: Vec<DVec3>,
    anchor: Vec<DVec3>,
    robust_dir: Vec<DVec3>,
    /// Back copy of every front vertex (itself on the eye and mouth contours).
    back_of: Vec<u32>,
}

impl FrontSurface<'_> {
    /// Inward move of a point, clamped by the distance to the front surface along −normal.
    fn moved(&self, p: DVec3, normal: DVec3, distance: f64) -> DVec3 {
        let dir = -normal;
        let min_t = 1e-6 * distance;
        let free = self
            .front_bvh
            .ray_hits(p, dir)
            .into_iter()
            .find(|h| h.t > min_t)
            .map(|h| h.t)
            .unwrap_or(f64::INFINITY);
        p + dir * distance.min(self.dims.clamp_fraction * free)
    }

    /// Inward displacement of every vertex (steps 2 and 3 of the module docs), before the clamp.
    fn back_displacements(&self) -> Vec<DVec3> {
        let n = self.vertices.len();
        let adjacency = vertex_adjacency(n, self.triangles);
        let dist = contour_distance(self.vertices, &adjacency, self.kind);
        let mut disp = self.smoothed_directions(&adjacency);
        let (normals, kind, dims) = (self.normals, self.kind, self.dims);
        let taper = |d: f64| knife_edge_taper(d, dims.taper);
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
        self.keep_behind_front(&mut disp);
        disp
    }

    /// Offset directions, smoothed: start from the full inward offset everywhere (the eye and
    /// mouth contours included, so that their neighbours' directions are not biased), then
    /// Laplacian-smooth the interior vertices. This irons out folds where vertex normals turn
    /// fast (mouth corners, nostril rims, lips). Only the direction is kept: the magnitude
    /// is set afterwards from the taper, so smoothing cannot thin the tissue next to a knife
    /// edge (smoothing magnitudes pinned at zero on the contours made the back face tangent
    /// to the front there: a zero-angle wedge, on which the BEM system is near-singular).
    fn smoothed_directions(&self, adjacency: &[Vec<u32>]) -> Vec<DVec3> {
        let n = self.vertices.len();
        let (normals, kind, dims) = (self.normals, self.kind, self.dims);
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
        disp
    }

    /// Every moved vertex must go behind all of its incident front triangles; where the
    /// smoothed field does not, fall back to the robust offset direction.
    fn keep_behind_front(&self, disp: &mut [DVec3]) {
        let n = self.vertices.len();
        let (normals, kind) = (self.normals, self.kind);
        let mut incident: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (ti, t) in self.triangles.iter().enumerate() {
            for &i in t {
                incident[i as usize].push(ti);
            }
        }
        let tri_normal = |ti: usize| {
            let p = self.front_tris[ti];
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
    }

    /// The front vertices followed by the clamped back copy of every vertex not on an eye or
    /// mouth contour (step 4 of the module docs), in face order.
    fn back_copies(&self, disp: &[DVec3]) -> BackVertices {
        let (vertices, normals, kind) = (self.vertices, self.normals, self.kind);
        let n = vertices.len();
        let mut out_v = vertices.to_vec();
        let mut anchor = vertices.to_vec();
        let mut robust_dir = normals.to_vec();
        let mut back_of = vec![u32::MAX; n];
        let new_back: Vec<(usize, DVec3)> = (0..n)
            .into_par_iter()
            .filter(|&v| kind[v] != 1)
            .map(|v| {
                let d = disp[v];
                let len = d.length();
                let dir = d.try_normalize().unwrap_or(-normals[v]);
                (v, self.moved(vertices[v], -dir, len))
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
        BackVertices {
            vertices: out_v,
            anchor,
            robust_dir,
            back_of,
        }
    }

    /// Chords: interior edges joining two inner-contour vertices. On the back they would
    /// coincide with the front edge, so the back side splits them at an offset mid-point,
    /// appended to `back`. Returns the mid-point of every chord (by sorted end points) and the
    /// index of the first one.
    fn chord_midpoints(
        &self,
        loops: &FaceLoops,
        back: &mut BackVertices,
    ) -> (HashMap<(u32, u32), u32>, u32) {
        let (vertices, normals, kind) = (self.vertices, self.normals, self.kind);
        let taper = |d: f64| knife_edge_taper(d, self.dims.taper);
        let mut boundary_edges = HashSet::new();
        for l in [&loops.eye_l, &loops.eye_r, &loops.mouth] {
            for i in 0..l.len() {
                let (a, b) = (l[i], l[(i + 1) % l.len()]);
                boundary_edges.insert((a.min(b), a.max(b)));
            }
        }
        let mut chord_mid: HashMap<(u32, u32), u32> = HashMap::new();
        let mid_start = back.vertices.len() as u32;
        for t in self.triangles {
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
                        back.vertices.push(self.moved(
                            m,
                            nm,
                            self.dims.offset
                                * taper(0.5 * vertices[a as usize].distance(vertices[b as usize])),
                        ));
                        back.anchor.push(m);
                        back.robust_dir.push(nm);
                        (back.vertices.len() - 1) as u32
                    });
                }
            }
        }
        (chord_mid, mid_start)
    }
}

/// The shell's elements while it is built: triangles, tags and source face triangles.
struct Elements {
    triangles: Vec<[u32; 3]>,
    tags: Vec<ElementTag>,
    source: Vec<u32>,
}

impl Elements {
    /// Back triangles: every face triangle reversed on the back copies, split at the mid-points
    /// of its chords (`chord_mid`, mid-points numbered from `mid_start`).
    fn push_back(
        &mut self,
        triangles: &[[u32; 3]],
        back_of: &[u32],
        chord_mid: &HashMap<(u32, u32), u32>,
        mid_start: u32,
    ) {
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
                self.triangles.push([poly[0], poly[i], poly[i + 1]]);
                self.tags.push(ElementTag::Back);
                self.source.push(ti as u32);
            }
        }
    }

    /// Rim: the front's outer boundary half-edge a→b (of the outer contour `face`) is completed
    /// by (b, a, a'), (b, a', b').
    fn push_rim(&mut self, triangles: &[[u32; 3]], face: &[u32], back_of: &[u32]) {
        let mut owner: HashMap<(u32, u32), u32> = HashMap::new();
        for (ti, t) in triangles.iter().enumerate() {
            for k in 0..3 {
                owner.insert((t[k], t[(k + 1) % 3]), ti as u32);
            }
        }
        let f = face;
        for i in 0..f.len() {
            let (a, b) = (f[i], f[(i + 1) % f.len()]);
            let (a2, b2) = (back_of[a as usize], back_of[b as usize]);
            let src = owner.get(&(a, b)).copied().unwrap_or(0);
            self.triangles.push([b, a, a2]);
            self.triangles.push([b, a2, b2]);
            self.tags.extend([ElementTag::Rim, ElementTag::Rim]);
            self.source.extend([src, src]);
        }
    }
}
