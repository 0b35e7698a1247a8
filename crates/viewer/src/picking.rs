//! Picking: which triangle of the posed mesh a viewport ray hits first.

use glam::DVec3;

/// A ray hit on a triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// Index of the triangle in the mesh's triangle list.
    pub triangle: usize,
    /// Ray parameter of the hit (distance along the unit direction).
    pub distance: f64,
}

/// Distance along `dir` from `origin` to triangle `abc` (Möller–Trumbore, both faces);
/// `None` for a miss, a hit behind the origin, or a degenerate triangle.
pub fn ray_triangle(origin: DVec3, dir: DVec3, [a, b, c]: [DVec3; 3]) -> Option<f64> {
    let e1 = b - a;
    let e2 = c - a;
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() <= 1e-14 * e1.length_squared().max(e2.length_squared()) {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - a;
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > 0.0).then_some(t)
}

/// The nearest triangle of (`positions`, `triangles`) hit by the ray, if any.
///
/// ```
/// use glam::DVec3;
/// use viewer::picking::pick_triangle;
/// let p = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// let hit = pick_triangle(&p, &[[0, 1, 2]], DVec3::new(0.2, 0.2, 1.0), -DVec3::Z).unwrap();
/// assert_eq!(hit.triangle, 0);
/// assert!((hit.distance - 1.0).abs() < 1e-12);
/// ```
pub fn pick_triangle(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    origin: DVec3,
    dir: DVec3,
) -> Option<TriangleHit> {
    triangles
        .iter()
        .enumerate()
        .filter_map(|(i, t)| {
            let corners = [
                *positions.get(t[0] as usize)?,
                *positions.get(t[1] as usize)?,
                *positions.get(t[2] as usize)?,
            ];
            ray_triangle(origin, dir, corners).map(|distance| TriangleHit {
                triangle: i,
                distance,
            })
        })
        .min_by(|a, b| a.distance.total_cmp(&b.distance))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_of_two_stacked_triangles_wins_and_misses_are_none() {
        let p = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, 0.0, 0.5),
            DVec3::new(1.0, 0.0, 0.5),
            DVec3::new(0.0, 1.0, 0.5),
        ];
        let tris = [[0, 1, 2], [3, 4, 5]];
        let hit = pick_triangle(&p, &tris, DVec3::new(0.1, 0.1, 2.0), -DVec3::Z).unwrap();
        assert_eq!(hit.triangle, 1);
        assert!((hit.distance - 1.5).abs() < 1e-12);
        assert_eq!(
            pick_triangle(&p, &tris, DVec3::new(0.9, 0.9, 2.0), -DVec3::Z),
            None
        );
        assert_eq!(
            pick_triangle(&p, &tris, DVec3::new(0.1, 0.1, 2.0), DVec3::Z),
            None
        );
        // Degenerate (collinear) triangle and out-of-range indices are skipped, not a panic.
        let flat = [DVec3::ZERO, DVec3::X, 2.0 * DVec3::X];
        assert_eq!(
            pick_triangle(&flat, &[[0, 1, 2], [0, 1, 7]], DVec3::Z, -DVec3::Z),
            None
        );
    }
}
