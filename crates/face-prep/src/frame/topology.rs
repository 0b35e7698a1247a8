//! Topological validation of a triangle mesh and extraction of its boundary loops in O(e).

use crate::error::{LoopSummary, PrepError};
use glam::DVec3;
use std::collections::HashMap;

/// Relative area below which a triangle counts as degenerate: `area < DEGENERATE_REL_AREA · diag²`
/// where `diag` is the mesh bounding-box diagonal.
pub const DEGENERATE_REL_AREA: f64 = 1e-14;

/// Area of a triangle.
pub fn triangle_area(p: [DVec3; 3]) -> f64 {
    0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length()
}

/// Bounding box of points.
pub fn bounding_box(points: impl IntoIterator<Item = DVec3>) -> (DVec3, DVec3) {
    points.into_iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    )
}

/// Checks that `triangles` over `vertices` form one connected, edge-manifold, consistently wound
/// surface without degenerate triangles, and returns its boundary loops.
///
/// Each loop lists vertex indices in the direction of the triangles' boundary half-edges (the
/// face is on the left when walking along a loop seen from the front). Checks run in this order
/// and the first failure is returned: non-finite positions, degenerate triangles, non-manifold
/// edges, inconsistent winding, bow-tie boundary vertices, connected components. The loop count
/// is not checked here (see [`check_four_loops`]).
pub fn validate(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Result<Vec<Vec<u32>>, PrepError> {
    if triangles.is_empty() {
        return Err(PrepError::EmptyMesh);
    }
    check_indices_and_positions(vertices, triangles)?;
    check_degenerate(vertices, triangles)?;
    let directed = half_edges(vertices, triangles)?;
    let (boundary, next) = boundary_links(vertices, &directed)?;
    check_connected(vertices.len(), triangles)?;
    Ok(walk_loops(&boundary, &next))
}

/// Every index must name a vertex, and every vertex position must be finite.
fn check_indices_and_positions(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
) -> Result<(), PrepError> {
    for (t, tri) in triangles.iter().enumerate() {
        for &i in tri {
            if i as usize >= vertices.len() {
                return Err(PrepError::IndexOutOfRange {
                    triangle: t,
                    index: i,
                    vertex_count: vertices.len(),
                });
            }
        }
    }
    for (i, v) in vertices.iter().enumerate() {
        if !v.is_finite() {
            return Err(PrepError::NonFiniteVertex {
                input_index: i,
                position: v.to_array(),
            });
        }
    }
    Ok(())
}

/// No triangle may repeat a vertex or have an area at or below [`DEGENERATE_REL_AREA`] × the
/// squared bounding-box diagonal.
fn check_degenerate(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Result<(), PrepError> {
    let (lo, hi) = bounding_box(vertices.iter().copied());
    let diag2 = (hi - lo).length_squared();
    for (t, tri) in triangles.iter().enumerate() {
        let corners = tri.map(|i| vertices[i as usize]);
        let area = triangle_area(corners);
        let repeated = tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2];
        if repeated || area.is_nan() || area <= DEGENERATE_REL_AREA * diag2 {
            return Err(PrepError::DegenerateTriangle {
                triangle: t,
                vertices: *tri,
                area,
                corners,
            });
        }
    }
    Ok(())
}

/// Directed half-edges → triangle, after checking that no edge has more than two triangles and
/// that no half-edge occurs twice (inconsistent winding).
fn half_edges(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
) -> Result<HashMap<(u32, u32), usize>, PrepError> {
    let mut directed: HashMap<(u32, u32), usize> = HashMap::with_capacity(triangles.len() * 3);
    let mut undirected: HashMap<(u32, u32), Vec<usize>> =
        HashMap::with_capacity(triangles.len() * 2);
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            undirected.entry((a.min(b), a.max(b))).or_default().push(t);
        }
    }
    let mut non_manifold: Vec<(&(u32, u32), &Vec<usize>)> =
        undirected.iter().filter(|(_, ts)| ts.len() > 2).collect();
    non_manifold.sort();
    if let Some(&(&(a, b), ts)) = non_manifold.first() {
        return Err(PrepError::NonManifoldEdge {
            a,
            b,
            pa: vertices[a as usize],
            pb: vertices[b as usize],
            triangles: (*ts).clone(),
        });
    }
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if let Some(&other) = directed.get(&(a, b)) {
                return Err(PrepError::InconsistentWinding {
                    a,
                    b,
                    pa: vertices[a as usize],
                    pb: vertices[b as usize],
                    triangles: [other, t],
                });
            }
            directed.insert((a, b), t);
        }
    }
    Ok(directed)
}

/// Boundary half-edges (those without a twin), sorted, and `next[a] = b` along them; a vertex
/// with more than one outgoing boundary edge (a bow-tie) is an error.
#[allow(clippy::type_complexity)] // the sorted edges and their successor map
fn boundary_links(
    vertices: &[DVec3],
    directed: &HashMap<(u32, u32), usize>,
) -> Result<(Vec<(u32, u32)>, HashMap<u32, u32>), PrepError> {
    let mut next: HashMap<u32, u32> = HashMap::new();
    let mut outgoing: HashMap<u32, usize> = HashMap::new();
    let mut boundary: Vec<(u32, u32)> = directed
        .keys()
        .filter(|&&(a, b)| !directed.contains_key(&(b, a)))
        .copied()
        .collect();
    boundary.sort_unstable();
    for &(a, b) in &boundary {
        *outgoing.entry(a).or_default() += 1;
        next.insert(a, b);
    }
    let mut bowties: Vec<(u32, usize)> = outgoing
        .iter()
        .filter(|(_, n)| **n > 1)
        .map(|(v, n)| (*v, *n))
        .collect();
    bowties.sort_unstable();
    if let Some(&(v, n)) = bowties.first() {
        return Err(PrepError::NonManifoldVertex {
            vertex: v,
            position: vertices[v as usize],
            outgoing: n,
        });
    }
    Ok((boundary, next))
}

/// The triangles must form one connected component (union-find over their vertices).
fn check_connected(vertex_count: usize, triangles: &[[u32; 3]]) -> Result<(), PrepError> {
    let mut parent: Vec<u32> = (0..vertex_count as u32).collect();
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            let up = parent[parent[x as usize] as usize];
            parent[x as usize] = up;
            x = up;
        }
        x
    }
    for tri in triangles {
        let r0 = find(&mut parent, tri[0]);
        for &v in &tri[1..] {
            let r = find(&mut parent, v);
            if r != r0 {
                parent[r as usize] = r0;
            }
        }
    }
    let mut sizes: HashMap<u32, usize> = HashMap::new();
    for tri in triangles {
        *sizes.entry(find(&mut parent, tri[0])).or_default() += 1;
    }
    if sizes.len() > 1 {
        let mut s: Vec<usize> = sizes.into_values().collect();
        s.sort_unstable_by(|a, b| b.cmp(a));
        return Err(PrepError::MultipleComponents { sizes: s });
    }
    Ok(())
}

/// The boundary loops, each walked from its smallest boundary half-edge along `next`.
fn walk_loops(boundary: &[(u32, u32)], next: &HashMap<u32, u32>) -> Vec<Vec<u32>> {
    let mut loops = Vec::new();
    let mut visited: HashMap<u32, bool> = HashMap::with_capacity(next.len());
    for &(start, _) in boundary {
        if visited.contains_key(&start) {
            continue;
        }
        let mut lp = vec![start];
        visited.insert(start, true);
        let mut v = next[&start];
        while v != start {
            // Every boundary vertex has exactly one outgoing and (by counting) one incoming
            // boundary edge, so the walk returns to `start`.
            visited.insert(v, true);
            lp.push(v);
            v = match next.get(&v) {
                Some(&n) => n,
                None => break,
            };
        }
        loops.push(lp);
    }
    loops
}

/// Summaries (size, bounding box) of loops, for error messages.
pub fn loop_summaries(vertices: &[DVec3], loops: &[Vec<u32>]) -> Vec<LoopSummary> {
    loops
        .iter()
        .map(|l| {
            let (min, max) = bounding_box(l.iter().map(|&i| vertices[i as usize]));
            LoopSummary {
                size: l.len(),
                min,
                max,
            }
        })
        .collect()
}

/// Fails with [`PrepError::WrongLoopCount`] unless there are exactly four loops.
pub fn check_four_loops(vertices: &[DVec3], loops: &[Vec<u32>]) -> Result<(), PrepError> {
    if loops.len() == 4 {
        Ok(())
    } else {
        Err(PrepError::WrongLoopCount {
            count: loops.len(),
            loops: loop_summaries(vertices, loops),
        })
    }
}
