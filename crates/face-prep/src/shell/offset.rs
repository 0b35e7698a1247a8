//! The offset field's ingredients: vertex normals and robust offset directions, vertex
//! adjacency, distances along mesh edges to the eye and mouth contours, and the knife-edge taper.

use glam::DVec3;

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
pub(super) fn contour_distance(
    vertices: &[DVec3],
    adjacency: &[Vec<u32>],
    kind: &[u8],
) -> Vec<f64> {
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
