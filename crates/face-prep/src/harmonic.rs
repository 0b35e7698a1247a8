//! Harmonic extension over a mesh's edge graph, solved exactly.
//!
//! Given values held at some vertices, [`extend`] sets every free vertex to the weighted mean of
//! its neighbours, `Σ_j w_ij (x_i − x_j) = 0`, the discrete Dirichlet problem of the graph
//! Laplacian with the held vertices as boundary (Botsch, Kobbelt, Pauly, Alliez & Lévy,
//! *Polygon Mesh Processing*, 2010, §3.3 and §4.2). The free block of the Laplacian is symmetric
//! and positive definite on every connected set of free vertices that reaches a held one, so it
//! is solved by one sparse Cholesky factorisation (`faer`, fill-reducing ordering) and three
//! triangular solves, one per coordinate — the converged answer that fixed counts of Jacobi or
//! Gauss–Seidel sweeps approach, independent of the vertex order.
//!
//! What it guarantees: held vertices keep their values; every free vertex that reaches a held
//! one through free vertices is the weighted mean of its neighbours (to rounding); a set of free
//! vertices that reaches no held vertex has no unique solution and is left as given.
//!
//! ```
//! use face_prep::harmonic::extend;
//! use glam::DVec3;
//! // A path 0-1-2-3 held at its ends: the middle falls on the straight line.
//! let edges = [(0, 1, 1.0), (1, 2, 1.0), (2, 3, 1.0)];
//! let mut values = vec![DVec3::ZERO, DVec3::ZERO, DVec3::ZERO, DVec3::X * 3.0];
//! let free = [false, true, true, false];
//! extend(&edges, &free, &mut values).unwrap();
//! assert!((values[1].x - 1.0).abs() < 1e-12 && (values[2].x - 2.0).abs() < 1e-12);
//! ```

use faer::Mat;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use glam::DVec3;

/// Why [`extend`] could not solve.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
#[non_exhaustive]
pub enum HarmonicError {
    /// An edge names a vertex outside the values, or has a weight that is not finite and
    /// positive.
    #[error("edge ({0}, {1}) is out of range or its weight is not finite and positive")]
    BadEdge(u32, u32),
    /// The sparse Cholesky factorisation failed (not positive definite).
    #[error("the harmonic system could not be factorised")]
    Factorisation,
}

/// Sets every vertex with `free[v]` to the harmonic extension of the others' `values` over the
/// weighted edges `(a, b, w)` ([the module](self)); free vertices that reach no held vertex keep
/// their values. Nothing changes on an error.
pub fn extend(
    edges: &[(u32, u32, f64)],
    free: &[bool],
    values: &mut [DVec3],
) -> Result<(), HarmonicError> {
    let n = values.len().min(free.len());
    for &(a, b, w) in edges {
        if a as usize >= n || b as usize >= n || !w.is_finite() || w <= 0.0 {
            return Err(HarmonicError::BadEdge(a, b));
        }
    }
    let anchored = reaching_held(n, edges, free);
    let mut index = vec![usize::MAX; n];
    let mut m = 0;
    for v in 0..n {
        if anchored[v] {
            index[v] = m;
            m += 1;
        }
    }
    if m == 0 {
        return Ok(());
    }
    let mut entries: Vec<Triplet<usize, usize, f64>> = Vec::with_capacity(4 * edges.len());
    let mut rhs = Mat::<f64>::zeros(m, 3);
    for &(a, b, w) in edges {
        for (p, q) in [(a as usize, b as usize), (b as usize, a as usize)] {
            let i = index[p];
            if i == usize::MAX {
                continue;
            }
            entries.push(Triplet::new(i, i, w));
            match index[q] {
                usize::MAX => {
                    for d in 0..3 {
                        rhs[(i, d)] += w * values[q][d];
                    }
                }
                j => entries.push(Triplet::new(i, j, -w)),
            }
        }
    }
    let matrix = SparseColMat::<usize, f64>::try_new_from_triplets(m, m, &entries)
        .map_err(|_| HarmonicError::Factorisation)?;
    let llt = matrix
        .sp_cholesky(faer::Side::Lower)
        .map_err(|_| HarmonicError::Factorisation)?;
    llt.solve_in_place(rhs.as_mut());
    for v in 0..n {
        if let Some(i) = Some(index[v]).filter(|&i| i != usize::MAX) {
            values[v] = DVec3::new(rhs[(i, 0)], rhs[(i, 1)], rhs[(i, 2)]);
        }
    }
    Ok(())
}

/// The free vertices joined to a held vertex through free vertices (breadth-first from the
/// held vertices' free neighbours).
fn reaching_held(n: usize, edges: &[(u32, u32, f64)], free: &[bool]) -> Vec<bool> {
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); n];
    for &(a, b, _) in edges {
        neighbours[a as usize].push(b);
        neighbours[b as usize].push(a);
    }
    let mut reached = vec![false; n];
    let mut queue: std::collections::VecDeque<usize> = std::collections::VecDeque::new();
    for v in 0..n {
        if !free[v] {
            for &u in &neighbours[v] {
                let u = u as usize;
                if free[u] && !reached[u] {
                    reached[u] = true;
                    queue.push_back(u);
                }
            }
        }
    }
    while let Some(v) = queue.pop_front() {
        for &u in &neighbours[v] {
            let u = u as usize;
            if free[u] && !reached[u] {
                reached[u] = true;
                queue.push_back(u);
            }
        }
    }
    reached
}

/// The edges of `triangles` (vertices below `n`) with weight 1 each, once per edge.
pub fn unit_edges(n: usize, triangles: &[[u32; 3]]) -> Vec<(u32, u32, f64)> {
    let mut edges: Vec<(u32, u32)> = triangles
        .iter()
        .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
        .filter(|&(a, b)| (a as usize) < n && (b as usize) < n && a != b)
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges.into_iter().map(|(a, b)| (a, b, 1.0)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An n x n grid of unit squares split into triangles, as vertices and triangles.
    fn grid(n: u32) -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut v = Vec::new();
        for y in 0..=n {
            for x in 0..=n {
                v.push(DVec3::new(x as f64, y as f64, 0.0));
            }
        }
        let id = |x: u32, y: u32| y * (n + 1) + x;
        let mut t = Vec::new();
        for y in 0..n {
            for x in 0..n {
                t.push([id(x, y), id(x + 1, y), id(x + 1, y + 1)]);
                t.push([id(x, y), id(x + 1, y + 1), id(x, y + 1)]);
            }
        }
        (v, t)
    }

    /// A linear function is harmonic: held on the grid's border, it is recovered inside
    /// exactly (to 1e-12), and every free vertex is the mean of its neighbours.
    #[test]
    fn a_linear_field_held_on_the_border_is_recovered_inside() {
        let (p, t) = grid(8);
        let exact: Vec<DVec3> = p
            .iter()
            .map(|q| DVec3::new(2.0 * q.x - q.y, 0.5 * q.y, q.x + 3.0))
            .collect();
        let free: Vec<bool> = p
            .iter()
            .map(|q| q.x > 0.0 && q.x < 8.0 && q.y > 0.0 && q.y < 8.0)
            .collect();
        let mut values: Vec<DVec3> = exact
            .iter()
            .zip(&free)
            .map(|(e, &f)| if f { DVec3::ZERO } else { *e })
            .collect();
        extend(&unit_edges(p.len(), &t), &free, &mut values).unwrap();
        for (v, e) in values.iter().zip(&exact) {
            assert!(v.distance(*e) < 1e-12, "{v} against {e}");
        }
    }

    /// The answer does not depend on the vertex order: the grid renumbered backwards gives
    /// the same values (to 1e-12) at the same places.
    #[test]
    fn the_extension_does_not_depend_on_the_vertex_order() {
        let (p, t) = grid(6);
        let n = p.len();
        let free: Vec<bool> = p.iter().map(|q| q.y > 0.0).collect();
        let bump = |q: &DVec3| {
            if q.y == 0.0 {
                DVec3::Z * q.x * (6.0 - q.x)
            } else {
                DVec3::ZERO
            }
        };
        let mut a: Vec<DVec3> = p.iter().map(bump).collect();
        extend(&unit_edges(n, &t), &free, &mut a).unwrap();
        let back = |v: u32| (n as u32 - 1) - v;
        let t_back: Vec<[u32; 3]> = t.iter().map(|tri| tri.map(back)).collect();
        let free_back: Vec<bool> = (0..n).map(|v| free[n - 1 - v]).collect();
        let mut b: Vec<DVec3> = (0..n).map(|v| bump(&p[n - 1 - v])).collect();
        extend(&unit_edges(n, &t_back), &free_back, &mut b).unwrap();
        for v in 0..n {
            assert!(a[v].distance(b[n - 1 - v]) < 1e-12);
        }
        // The top row, far from the bump, still moves (the extension reaches it).
        assert!(a[n - 4].z > 0.0);
    }

    /// Free vertices that reach no held vertex keep their values; a bad edge changes nothing.
    #[test]
    fn unreachable_free_vertices_and_bad_edges_leave_the_values() {
        let edges = [(0, 1, 1.0), (2, 3, 1.0)];
        let mut values = vec![DVec3::X, DVec3::ZERO, DVec3::Y, DVec3::Z];
        extend(&edges, &[false, true, true, true], &mut values).unwrap();
        assert_eq!(values, vec![DVec3::X, DVec3::X, DVec3::Y, DVec3::Z]);
        let before = values.clone();
        assert_eq!(
            extend(&[(0, 9, 1.0)], &[false, true, true, true], &mut values),
            Err(HarmonicError::BadEdge(0, 9))
        );
        assert_eq!(
            extend(&[(0, 1, f64::NAN)], &[false, true, true, true], &mut values),
            Err(HarmonicError::BadEdge(0, 1))
        );
        assert_eq!(values, before);
    }
}
