//! Triangle–triangle intersection tests over an indexed mesh (BVH-accelerated).

use glam::DVec3;
use rayon::prelude::*;

use crate::bvh::{TriangleBvh, segment_crosses_triangle};

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
pub(super) fn triangles_intersect(
    ta: [u32; 3],
    a: &[DVec3; 3],
    tb: [u32; 3],
    b: &[DVec3; 3],
) -> bool {
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
