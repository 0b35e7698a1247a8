//! A mirror-meshed stand-in for a face that is mirror-symmetric in shape but not in its
//! triangles (issue 30, item 1).
//!
//! Almost no user mesh is mirror-meshed: a scan, a remesh, a quad mesh triangulated along
//! arbitrary diagonals. Simulated on its own triangles, such a face gets left and right
//! responses that differ by as much as its triangulations do (48–188 % on eight re-split
//! eyelid quads). Whether a face is symmetric is a property of its surface, so it is tested on
//! the surface: every vertex's mirror image about the canonical midplane must lie within
//! [`SHAPE_TOLERANCE_IOD`] of the surface. A face that passes is simulated on a copy made
//! symmetric by construction: the surface is cut along the midplane (each triangle that
//! crosses it is split at the crossing points, vertices within a quarter of their shortest edge
//! of the plane are moved onto it first so that the cut leaves no slivers), its left half is
//! kept and mirrored, and the two halves share the cut as their midline. The copy is then
//! simplified or remeshed as a mirror-meshed face is ([`crate::copy::simplify`](mod@crate::copy::simplify)),
//! and [`crate::transfer`] carries its responses to the user's own vertices. A face that is
//! really asymmetric (a vertex's mirror image farther from the surface than the tolerance)
//! keeps its own triangles and its asymmetry.
//!
//! This is the "symmetrise by cut and reflect" construction used for bilateral shapes in
//! statistical shape modelling (e.g. Blanz & Vetter 1999, §3, who average a face with its
//! mirror image); the symmetry test is the mirror-distance measure of Mitra, Guibas & Pauly,
//! *Partial and approximate symmetry detection for 3D geometry* (SIGGRAPH 2006), with the
//! plane fixed by the face's canonical frame (the eyes and the mouth).

use std::collections::HashMap;

use glam::DVec3;

use crate::copy::Simplified;
use crate::copy::simplify::Canonical;

/// Largest distance, in interocular distances, from a vertex's mirror image to the surface for
/// a face to count as mirror-symmetric in shape: 5·10⁻³ (0.3 mm on an adult face, half a
/// percent of the eye distance). A re-triangulated or remeshed symmetric face is within
/// 10⁻⁶–10⁻³; a scan or a decimated face is off by 10⁻²–10⁻¹ somewhere.
pub const SHAPE_TOLERANCE_IOD: f64 = 5e-3;

/// Vertices closer to the midplane than this fraction of their shortest edge are moved onto
/// it before the cut, so that no cut point falls next to a vertex.
const SNAP_FRACTION: f64 = 0.25;

/// Distance from the midplane, in interocular distances, within which a vertex is on it to
/// rounding (the canonical frame is computed in f64 from the input's float positions).
const ON_PLANE_IOD: f64 = 1e-9;

/// Largest distance from a vertex's mirror image (about x = 0) to the surface, over every
/// vertex, when it is at most `tolerance`; `None` as soon as one vertex is farther.
///
/// ```
/// use facebem::copy::symmetrize::mirror_deviation;
/// use glam::DVec3;
/// // A square in the x-y plane, centred on x = 0, split along one diagonal only.
/// let v = [DVec3::new(-1.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0),
///          DVec3::new(1.0, 1.0, 0.0), DVec3::new(-1.0, 1.0, 0.0)];
/// let t = [[0, 1, 2], [0, 2, 3]];
/// assert_eq!(mirror_deviation(&v, &t, 1e-9), Some(0.0));
/// // Lift one corner: the shape is no longer symmetric.
/// let mut w = v;
/// w[2].z = 0.5;
/// assert_eq!(mirror_deviation(&w, &t, 1e-3), None);
/// ```
pub fn mirror_deviation(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    tolerance: f64,
) -> Option<f64> {
    mirror_deviation_of(positions, positions, triangles, tolerance)
}

/// [`mirror_deviation`] over the points `queries` only (mirrored about x = 0), against the
/// surface `positions`/`triangles`.
fn mirror_deviation_of(
    queries: &[DVec3],
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    tolerance: f64,
) -> Option<f64> {
    let corners: Vec<[DVec3; 3]> = triangles
        .iter()
        .map(|t| t.map(|v| positions[v as usize]))
        .collect();
    let bvh = face_prep::bvh::TriangleBvh::new(&corners);
    let reach = DVec3::splat(tolerance);
    let mut largest: f64 = 0.0;
    for &p in queries {
        let q = DVec3::new(-p.x, p.y, p.z);
        let d = bvh
            .overlapping(q - reach, q + reach)
            .into_iter()
            .map(|t| face_prep::closest_point::closest_point_on_triangle(q, &corners[t as usize]))
            .map(|c| c.distance(q))
            .fold(f64::INFINITY, f64::min);
        // NaN (no triangle within reach gives infinity) counts as too far.
        if d.is_nan() || d > tolerance {
            return None;
        }
        largest = largest.max(d);
    }
    Some(largest)
}

/// The left (+x) half of a canonical surface cut along x = 0: positions (the input's, with
/// vertices near the plane moved onto it, and the cut points), triangles, and for each position
/// the input vertex it came from (a cut point: the nearer end of its edge).
struct Cut {
    positions: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    source: Vec<u32>,
}

/// Cuts `positions`/`triangles` along x = 0 and keeps the left half. `None` when a triangle
/// crossing the plane does not split into a triangle or a quad (not reached for finite
/// positions).
fn cut_left_half(positions: &[DVec3], triangles: &[[u32; 3]]) -> Option<Cut> {
    let mut shortest = vec![f64::INFINITY; positions.len()];
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            let l = positions[a].distance(positions[b]);
            shortest[a] = shortest[a].min(l);
            shortest[b] = shortest[b].min(l);
        }
    }
    let mut snapped = positions.to_vec();
    for (p, &s) in snapped.iter_mut().zip(&shortest) {
        if p.x.abs() < SNAP_FRACTION * s || p.x.abs() <= ON_PLANE_IOD {
            p.x = 0.0;
        }
    }
    // A triangle whose three corners were all moved onto the plane would lie in it: its
    // corners stay where they were, unless they were on the plane to rounding already. Only a
    // triangle that lies in the plane in the input does.
    for t in triangles {
        if t.iter().all(|&v| snapped[v as usize].x == 0.0) {
            for &v in t {
                if positions[v as usize].x.abs() > ON_PLANE_IOD {
                    snapped[v as usize].x = positions[v as usize].x;
                }
            }
        }
    }
    let signs: Vec<i8> = snapped
        .iter()
        .map(|p| {
            if p.x > 0.0 {
                1
            } else if p.x < 0.0 {
                -1
            } else {
                0
            }
        })
        .collect();
    let sign = |v: u32| signs[v as usize];
    let mut source: Vec<u32> = (0..positions.len() as u32).collect();
    let mut cuts: HashMap<(u32, u32), u32> = HashMap::new();
    let mut left = Vec::new();
    for &t in triangles {
        let s = t.map(sign);
        if s.iter().all(|&x| x == 0) {
            // In the plane (a midline sliver of the input's triangulation): its own mirror
            // image, in neither half; the halves meet along its other edges.
            continue;
        }
        if s.iter().all(|&x| x >= 0) {
            left.push(t);
            continue;
        }
        if s.iter().all(|&x| x <= 0) {
            continue;
        }
        let mut polygon: Vec<u32> = Vec::with_capacity(4);
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if s[k] >= 0 {
                polygon.push(a);
            }
            if s[k] * s[(k + 1) % 3] == -1 {
                let key = (a.min(b), a.max(b));
                let index = *cuts.entry(key).or_insert_with(|| {
                    let (pa, pb) = (snapped[a as usize], snapped[b as usize]);
                    let f = pa.x / (pa.x - pb.x);
                    let mut c = pa + (pb - pa) * f;
                    c.x = 0.0;
                    snapped.push(c);
                    source.push(if f < 0.5 { a } else { b });
                    (snapped.len() - 1) as u32
                });
                polygon.push(index);
            }
        }
        match *polygon.as_slice() {
            [a, b, c] => left.push([a, b, c]),
            [a, b, c, d] => {
                // The shorter diagonal.
                let p = |v: u32| snapped[v as usize];
                if p(a).distance(p(c)) <= p(b).distance(p(d)) {
                    left.extend([[a, b, c], [a, c, d]]);
                } else {
                    left.extend([[a, b, d], [b, c, d]]);
                }
            }
            _ => return None,
        }
    }
    Some(Cut {
        positions: snapped,
        triangles: left,
        source,
    })
}

/// A mirror-meshed stand-in for `canon` when its surface is mirror-symmetric within
/// [`SHAPE_TOLERANCE_IOD`]: the left half cut along the midplane and mirrored, in the same
/// canonical frame, with [`Canonical::input_vertex`] naming for each vertex the input vertex it
/// came from (for a mirrored vertex, the input vertex nearest to its mirror image among the
/// corners of the triangle closest to it). `None` when the shape is not symmetric, or the glued halves are not a valid surface
/// with the face's loops. With `outline_is_cut` (a head's front face,
/// [`crate::PipelineParams::outline_is_cut`]) the outer contour's vertices are left out of the
/// symmetry test: its right half is then the mirror image of the left half's outline.
pub(crate) fn symmetrized(canon: &Canonical, outline_is_cut: bool) -> Option<Canonical> {
    let queries: Vec<DVec3> = if outline_is_cut {
        let outer = outer_contour(canon);
        canon
            .positions
            .iter()
            .zip(&outer)
            .filter(|&(_, &o)| !o)
            .map(|(p, _)| *p)
            .collect()
    } else {
        canon.positions.clone()
    };
    mirror_deviation_of(
        &queries,
        &canon.positions,
        &canon.triangles,
        SHAPE_TOLERANCE_IOD,
    )?;
    let cut = cut_left_half(&canon.positions, &canon.triangles)?;
    // Only the vertices the left half uses, midline ones (x = 0) once, the others twice.
    let mut index = vec![u32::MAX; cut.positions.len()];
    let mut positions = Vec::new();
    let mut source = Vec::new();
    for t in &cut.triangles {
        for &v in t {
            if index[v as usize] == u32::MAX {
                index[v as usize] = positions.len() as u32;
                positions.push(cut.positions[v as usize]);
                source.push(cut.source[v as usize]);
            }
        }
    }
    let half = positions.len();
    let mut image: Vec<u32> = (0..half as u32).collect();
    let corners: Vec<[DVec3; 3]> = canon
        .triangles
        .iter()
        .map(|t| t.map(|v| canon.positions[v as usize]))
        .collect();
    let bvh = face_prep::bvh::TriangleBvh::new(&corners);
    for v in 0..half {
        let p = positions[v];
        if p.x == 0.0 {
            continue;
        }
        let q = DVec3::new(-p.x, p.y, p.z);
        image[v] = positions.len() as u32;
        positions.push(q);
        source.push(nearest_corner(canon, &bvh, &corners, q));
    }
    let triangles: Vec<[u32; 3]> = cut
        .triangles
        .iter()
        .map(|t| t.map(|v| index[v as usize]))
        .collect();
    let mirrored: Vec<[u32; 3]> = triangles
        .iter()
        .map(|t| [t[0], t[2], t[1]].map(|v| image[v as usize]))
        .collect();
    // Each triangle next to its mirror image, each vertex next to its own: whatever follows
    // in the order of the vertices or the triangles then sees both sides alike.
    let mut interleaved: Vec<[u32; 3]> = Vec::with_capacity(2 * triangles.len());
    for (t, m) in triangles.iter().zip(&mirrored) {
        interleaved.extend([*t, *m]);
    }
    let mut order: Vec<u32> = Vec::with_capacity(positions.len());
    for (v, &w) in image.iter().enumerate().take(half) {
        order.push(v as u32);
        if w != v as u32 {
            order.push(w);
        }
    }
    let mut new_index = vec![0u32; positions.len()];
    for (n, &v) in order.iter().enumerate() {
        new_index[v as usize] = n as u32;
    }
    let positions: Vec<DVec3> = order.iter().map(|&v| positions[v as usize]).collect();
    let source: Vec<u32> = order.iter().map(|&v| source[v as usize]).collect();
    let triangles: Vec<[u32; 3]> = interleaved
        .iter()
        .map(|t| t.map(|v| new_index[v as usize]))
        .collect();
    let loops = face_prep::topology::validate(&positions, &triangles).ok()?;
    if loops.len() != canon.loop_count {
        return None;
    }
    // The stand-in's mouth and eye loops: those nearest to the face's own.
    let centroid = |pts: &[DVec3], lp: &[u32]| {
        lp.iter().map(|&v| pts[v as usize]).sum::<DVec3>() / lp.len().max(1) as f64
    };
    let nearest_loop = |lp: &[u32]| -> Vec<u32> {
        let c = centroid(&canon.positions, lp);
        loops
            .iter()
            .min_by(|a, b| {
                let da = centroid(&positions, a).distance(c);
                let db = centroid(&positions, b).distance(c);
                da.total_cmp(&db)
            })
            .cloned()
            .unwrap_or_default()
    };
    let sym = Canonical {
        mouth: nearest_loop(&canon.mouth),
        eyes: [nearest_loop(&canon.eyes[0]), nearest_loop(&canon.eyes[1])],
        input_vertex: source
            .iter()
            .map(|&c| canon.input_vertex[c as usize])
            .collect(),
        positions,
        triangles,
        loop_count: canon.loop_count,
        input_from_grid: canon.input_from_grid,
    };
    Some(sym)
}

/// The corner nearest to `q` of the triangle of `canon` closest to `q` (a canonical vertex).
fn nearest_corner(
    canon: &Canonical,
    bvh: &face_prep::bvh::TriangleBvh,
    corners: &[[DVec3; 3]],
    q: DVec3,
) -> u32 {
    let reach = DVec3::splat(2.0 * SHAPE_TOLERANCE_IOD);
    let best = bvh
        .overlapping(q - reach, q + reach)
        .into_iter()
        .map(|t| {
            let c = face_prep::closest_point::closest_point_on_triangle(q, &corners[t as usize]);
            (c.distance(q), t)
        })
        .min_by(|a, b| a.0.total_cmp(&b.0));
    let Some((_, t)) = best else {
        // Unreachable after the symmetry test; the nearest vertex by brute force.
        return (0..canon.positions.len() as u32)
            .min_by(|&a, &b| {
                let da = canon.positions[a as usize].distance(q);
                let db = canon.positions[b as usize].distance(q);
                da.total_cmp(&db)
            })
            .unwrap_or(0);
    };
    let tri = canon.triangles[t as usize];
    tri.into_iter()
        .min_by(|&a, &b| {
            let da = canon.positions[a as usize].distance(q);
            let db = canon.positions[b as usize].distance(q);
            da.total_cmp(&db)
        })
        .unwrap_or(tri[0])
}

/// A face's mirror-meshed stand-in ([`stand_in`]).
pub(crate) struct StandIn {
    /// The stand-in as a face mesh (the face's frame and units), simulated in the face's place.
    pub(crate) mesh: face_prep::FaceMesh,
    /// The same surface; [`Simplified::original_vertex`] names the face's vertex each stand-in
    /// vertex came from.
    pub(crate) surface: Simplified,
    /// [`SHAPE_TOLERANCE_IOD`] in the face's units.
    pub(crate) tolerance: f64,
}

/// Per vertex of `canon`: on its outer contour (a boundary vertex on neither an eye's loop nor
/// the mouth's).
fn outer_contour(canon: &Canonical) -> Vec<bool> {
    let mut count: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &canon.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let mut outer = vec![false; canon.positions.len()];
    for (&(a, b), _) in count.iter().filter(|&(_, &c)| c == 1) {
        for v in [a, b] {
            if let Some(o) = outer.get_mut(v as usize) {
                *o = true;
            }
        }
    }
    for &v in canon.mouth.iter().chain(canon.eyes.iter().flatten()) {
        if let Some(o) = outer.get_mut(v as usize) {
            *o = false;
        }
    }
    outer
}

/// The mirror-meshed stand-in of `mesh` when the face is mirror-symmetric in shape within
/// [`SHAPE_TOLERANCE_IOD`] but not mirror-meshed; `None` when it is mirror-meshed already, not
/// symmetric, or has no canonical frame. `outline_is_cut`: as [`symmetrized`].
pub(crate) fn stand_in(mesh: &face_prep::FaceMesh, outline_is_cut: bool) -> Option<StandIn> {
    let (vertices, triangles) = (&mesh.vertices, &mesh.triangles);
    let canon = Canonical::of(vertices, triangles)?;
    if crate::copy::simplify::mirror_map(&canon.positions, &canon.triangles).is_some() {
        return None;
    }
    // The stand-in is cut from the unrounded canonical positions: the 2⁻²⁰ grid that makes
    // the simplifier's input exact would flatten a sliver thinner than it.
    let grid_from_input = canon.input_from_grid.inverse();
    let exact = Canonical {
        positions: canon
            .input_vertex
            .iter()
            .map(|&v| grid_from_input.transform_point3(vertices[v as usize]))
            .collect(),
        ..canon
    };
    let sym = symmetrized(&exact, outline_is_cut)?;
    let cut = sym.to_input(&Simplified::whole(&sym.positions, &sym.triangles));
    let mesh = face_prep::FaceMesh::from_triangles(&cut.vertices, &cut.triangles).ok()?;
    let mut original_vertex = vec![0u32; mesh.vertices.len()];
    for (i, w) in mesh.input_to_vertex.iter().enumerate() {
        if let Some(w) = w {
            original_vertex[*w as usize] = cut.original_vertex[i];
        }
    }
    let surface = Simplified {
        vertices: mesh.vertices.clone(),
        triangles: mesh.triangles.clone(),
        original_vertex,
    };
    let tolerance =
        SHAPE_TOLERANCE_IOD * exact.input_from_grid.transform_vector3(DVec3::X).length();
    Some(StandIn {
        mesh,
        surface,
        tolerance,
    })
}

/// The closest-point transfer from a stand-in to the face's own vertices. Each vertex takes the
/// closest point among the stand-in's triangles within four tolerances that face its way (the
/// triangle's normal at a positive dot with the vertex's); a vertex with none takes the
/// closest point of all. Layers closer than the tolerance face opposite ways (ICT's rolled-in
/// lips press together and cross at the corners): by distance alone, vertices of one lip
/// followed the other on one side only (12 % RMS asymmetry under the risorius).
pub(crate) fn transfer_to_face(
    mesh: &face_prep::FaceMesh,
    stand_in: &StandIn,
) -> Option<crate::transfer::Transfer> {
    let surface = &stand_in.surface;
    let corners: Vec<[DVec3; 3]> = surface
        .triangles
        .iter()
        .map(|t| t.map(|v| surface.vertices[v as usize]))
        .collect();
    let bvh = face_prep::bvh::TriangleBvh::new(&corners);
    let normals = face_prep::shell::vertex_normals(&mesh.vertices, &mesh.triangles);
    let reach = DVec3::splat(4.0 * stand_in.tolerance);
    let facing: Vec<Option<(u32, [f64; 3])>> = mesh
        .vertices
        .iter()
        .zip(&normals)
        .map(|(&p, &n)| {
            bvh.overlapping(p - reach, p + reach)
                .into_iter()
                .filter(|&t| {
                    let [a, b, c] = corners[t as usize];
                    (b - a).cross(c - a).dot(n) > 0.0
                })
                .map(|t| {
                    let [a, b, c] = corners[t as usize];
                    let w = face_prep::closest_point::closest_point_barycentric(p, a, b, c);
                    let d = (a * w[0] + b * w[1] + c * w[2]).distance_squared(p);
                    (d, t, w)
                })
                .min_by(|x, y| x.0.total_cmp(&y.0))
                .map(|(_, t, w)| (t, w))
        })
        .collect();
    let closest = if facing.iter().any(Option::is_none) {
        Some(crate::transfer::Transfer::build(&mesh.vertices, surface)?)
    } else {
        None
    };
    let samples = facing
        .into_iter()
        .enumerate()
        .map(|(v, f)| match (f, &closest) {
            (Some(sample), _) => sample,
            (None, Some(all)) => all.samples[v],
            (None, None) => (0, [1.0, 0.0, 0.0]),
        })
        .collect();
    Some(crate::transfer::Transfer { samples })
}
