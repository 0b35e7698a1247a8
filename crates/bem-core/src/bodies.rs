//! Connected surface components and the elastic bodies they bound.
//!
//! A closed surface may bound several separate bodies (two spheres), and one body may have several
//! surface components (a hollow sphere: outer surface plus an inward-facing cavity). Every body
//! needs prescribed displacements somewhere, or its rigid motions are free and the system is
//! singular; [`crate::LinearSystem::assemble`] checks this per body.

use glam::DVec3;

/// Connected component (through shared vertices) of every triangle, numbered 0, 1, … in order of
/// their first triangle.
pub(crate) fn components(vertex_count: usize, triangles: &[[u32; 3]]) -> Vec<u32> {
    let mut parent: Vec<u32> = (0..vertex_count as u32).collect();
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            parent[x as usize] = parent[parent[x as usize] as usize];
            x = parent[x as usize];
        }
        x
    }
    for tri in triangles {
        let r0 = find(&mut parent, tri[0]);
        for &v in &tri[1..] {
            let r = find(&mut parent, v);
            parent[r as usize] = r0;
        }
    }
    let mut label = vec![u32::MAX; vertex_count];
    let mut next = 0;
    triangles
        .iter()
        .map(|tri| {
            let root = find(&mut parent, tri[0]) as usize;
            if label[root] == u32::MAX {
                label[root] = next;
                next += 1;
            }
            label[root]
        })
        .collect()
}

/// Largest triangle of each component, in increasing triangle order.
pub(crate) fn largest_triangles(component: &[u32], areas: &[f64]) -> Vec<usize> {
    let count = component.iter().map(|&c| c as usize + 1).max().unwrap_or(0);
    let mut best: Vec<Option<usize>> = vec![None; count];
    for (t, &c) in component.iter().enumerate() {
        let entry = &mut best[c as usize];
        if entry.is_none_or(|b| areas[t] > areas[b]) {
            *entry = Some(t);
        }
    }
    let mut picks: Vec<usize> = best.into_iter().flatten().collect();
    picks.sort_unstable();
    picks
}

/// Body of every triangle, numbered in order of their first triangle. Components enclosing a
/// positive volume are outer surfaces, one body each; a component enclosing a negative volume is
/// a cavity and belongs to the smallest outer surface around it (winding number ≈ 1 at its
/// largest triangle's centroid).
pub(crate) fn bodies(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    component: &[u32],
    centroids: &[DVec3],
    areas: &[f64],
) -> Vec<u32> {
    let picks = largest_triangles(component, areas);
    let count = picks.len();
    if count < 2 {
        return vec![0; triangles.len()];
    }
    let mut members: Vec<Vec<[u32; 3]>> = vec![Vec::new(); count];
    let mut volume = vec![0.0f64; count];
    for (tri, &c) in triangles.iter().zip(component) {
        let [a, b, d] = tri.map(|i| vertices[i as usize]);
        volume[c as usize] += a.dot(b.cross(d)) / 6.0;
        members[c as usize].push(*tri);
    }
    // owner[c]: the component whose body c belongs to (itself for outer surfaces)
    let mut owner: Vec<usize> = (0..count).collect();
    for &t in &picks {
        let c = component[t] as usize;
        if volume[c] >= 0.0 {
            continue;
        }
        let p = centroids[t];
        owner[c] = (0..count)
            .filter(|&o| volume[o] > 0.0 && winding_number(vertices, &members[o], p) > 0.5)
            .min_by(|&a, &b| volume[a].total_cmp(&volume[b]))
            .unwrap_or(c);
    }
    let mut label = vec![u32::MAX; count];
    let mut next = 0;
    component
        .iter()
        .map(|&c| {
            let o = owner[c as usize];
            if label[o] == u32::MAX {
                label[o] = next;
                next += 1;
            }
            label[o]
        })
        .collect()
}

/// Generalised winding number of the closed surface at `p` (1 inside, 0 outside for an
/// outward-oriented surface), from the solid angles of the triangles (Van Oosterom–Strackee).
pub(crate) fn winding_number(vertices: &[DVec3], triangles: &[[u32; 3]], p: DVec3) -> f64 {
    let mut total = 0.0;
    for tri in triangles {
        let [a, b, c] = tri.map(|i| vertices[i as usize] - p);
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let det = a.dot(b.cross(c));
        let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
        total += 2.0 * det.atan2(den);
    }
    total / (4.0 * std::f64::consts::PI)
}
