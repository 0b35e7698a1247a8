//! Closest point of a triangle to a point (Ericson, *Real-Time Collision Detection*, 5.1.5):
//! one implementation for the shell repair here and the large-face transfer in `facebem`.

use glam::DVec3;

/// Barycentric coordinates of the point of triangle (a, b, c) closest to `p` (Ericson,
/// Real-Time Collision Detection 5.1.5). Degenerate triangles fall back to the closest
/// vertex/edge naturally.
pub fn closest_point_barycentric(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> [f64; 3] {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return [1.0, 0.0, 0.0];
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return [0.0, 1.0, 0.0];
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return [1.0 - v, v, 0.0];
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return [0.0, 0.0, 1.0];
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return [1.0 - w, 0.0, w];
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return [0.0, 1.0 - w, w];
    }
    let denom = va + vb + vc;
    if denom.abs() <= f64::MIN_POSITIVE {
        return [1.0, 0.0, 0.0];
    }
    let v = vb / denom;
    let w = vc / denom;
    [1.0 - v - w, v, w]
}

/// Closest point of triangle `t` to `p` (see [`closest_point_barycentric`]).
///
/// ```
/// use face_prep::closest_point::closest_point_on_triangle;
/// use glam::DVec3;
/// let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// assert_eq!(closest_point_on_triangle(DVec3::new(-1.0, -1.0, 2.0), &t), DVec3::ZERO);
/// ```
pub fn closest_point_on_triangle(p: DVec3, t: &[DVec3; 3]) -> DVec3 {
    let w = closest_point_barycentric(p, t[0], t[1], t[2]);
    t[0] * w[0] + t[1] * w[1] + t[2] * w[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_point_regions() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        let inside = closest_point_barycentric(DVec3::new(0.25, 0.25, 3.0), a, b, c);
        assert!((inside[0] - 0.5).abs() < 1e-15 && (inside[1] - 0.25).abs() < 1e-15);
        assert_eq!(
            closest_point_barycentric(DVec3::new(-1.0, -1.0, 0.0), a, b, c),
            [1.0, 0.0, 0.0]
        );
        assert_eq!(
            closest_point_barycentric(DVec3::new(2.0, -0.1, 0.0), a, b, c),
            [0.0, 1.0, 0.0]
        );
        let edge = closest_point_barycentric(DVec3::new(1.0, 1.0, 0.0), a, b, c);
        assert!((edge[1] - 0.5).abs() < 1e-15 && (edge[2] - 0.5).abs() < 1e-15);
    }

    #[test]
    fn point_equals_the_barycentric_combination() {
        let t = [
            DVec3::new(0.1, 0.2, 0.0),
            DVec3::new(2.0, 0.3, 0.5),
            DVec3::new(0.4, 1.7, -0.2),
        ];
        for p in [
            DVec3::new(0.8, 0.7, 1.0),
            DVec3::new(-3.0, 0.0, 0.0),
            DVec3::new(1.5, 1.5, 0.0),
        ] {
            let q = closest_point_on_triangle(p, &t);
            // q is on the triangle and no triangle point is closer (checked on a fine grid).
            let d = p.distance(q);
            for i in 0..=40 {
                for j in 0..=40 - i {
                    let (u, v) = (i as f64 / 40.0, j as f64 / 40.0);
                    let s = t[0] * (1.0 - u - v) + t[1] * u + t[2] * v;
                    assert!(p.distance(s) >= d - 1e-12, "{p} {q} {s}");
                }
            }
        }
    }
}
