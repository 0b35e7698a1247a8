//! The nearest of a set of source vertices measured along a mesh's edges (multi-source
//! Dijkstra), for carrying a face's border motion onto the skin around it: the inside of the
//! lips is reached from the lip it continues, not from the other lip that happens to lie
//! nearer through the mouth's air.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use glam::DVec3;

/// For every vertex of the mesh (`positions`, `triangles`), the label of the source reached
/// first along its edges and the length of that path; `None` where no source is reached.
/// `sources` are (vertex, label) pairs; vertices out of range are skipped.
///
/// ```
/// use facebem::transfer::along_surface::nearest_source;
/// use glam::DVec3;
/// // A strip of two triangles: 0 - 1 - 2 along x, 3 above 1.
/// let p = [DVec3::ZERO, DVec3::X, 2.0 * DVec3::X, DVec3::new(1.0, 1.0, 0.0)];
/// let t = [[0, 1, 3], [1, 2, 3]];
/// let reached = nearest_source(&p, &t, &[(0, 7), (2, 9)]);
/// assert_eq!(reached[0], Some((7, 0.0)));
/// assert_eq!(reached[1].map(|r| r.1), Some(1.0));
/// assert_eq!(reached[3].map(|r| r.0), Some(7)); // ties go to the first source
/// ```
pub fn nearest_source(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    sources: &[(u32, u32)],
) -> Vec<Option<(u32, f64)>> {
    let n = positions.len();
    let mut adjacency: Vec<Vec<u32>> = vec![Vec::new(); n];
    for t in triangles {
        if t.iter().any(|&v| v as usize >= n) {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            adjacency[a as usize].push(b);
            adjacency[b as usize].push(a);
        }
    }
    let mut best: Vec<Option<(u32, f64)>> = vec![None; n];
    let mut heap = BinaryHeap::new();
    for &(v, label) in sources {
        if let Some(slot) = best.get_mut(v as usize)
            && slot.is_none()
        {
            *slot = Some((label, 0.0));
            heap.push(Reverse((0u64, v)));
        }
    }
    // Non-negative f64 bit patterns order like the values.
    while let Some(Reverse((d_bits, v))) = heap.pop() {
        let d = f64::from_bits(d_bits);
        let Some((label, at)) = best[v as usize] else {
            continue;
        };
        if d > at {
            continue;
        }
        for &u in &adjacency[v as usize] {
            let nd = d + positions[v as usize].distance(positions[u as usize]);
            if best[u as usize].is_none_or(|(_, old)| nd < old) {
                best[u as usize] = Some((label, nd));
                heap.push(Reverse((nd.to_bits(), u)));
            }
        }
    }
    best
}
