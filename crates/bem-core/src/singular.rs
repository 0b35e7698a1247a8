//! Analytic singular integral of the displacement kernel over a flat triangle (thesis eq. 4.6).
//!
//! With the load point P in the plane of the triangle, polar coordinates around P give
//! `∫ f(r̂)/r dA = ∫ f(θ) R(θ) dθ`, R the distance to the boundary. Per side, with `d` the distance
//! from P to the side's line, `e2` the unit vector from P to the foot of the perpendicular and
//! `e1` the unit side direction, `R(θ) = d / cos θ` and `r̂ = cos θ e2 + sin θ e1`, θ measured from
//! e2 toward +e1 (signed). The side's three line integrals are closed-form:
//!
//! * `∫ d/cos θ dθ = d [ln tan(π/4 + θ/2)]`
//! * `∫ d cos θ dθ = d [sin θ]` (e2 e2 term),
//! * `∫ d sin²θ / cos θ dθ = d [ln tan(π/4 + θ/2) − sin θ]` (e1 e1 term),
//! * `∫ d sin θ dθ = d [−cos θ]` (e1 e2 + e2 e1 term).

use std::f64::consts::{FRAC_PI_4, PI};

use glam::DVec3;

use crate::kernels::Block;
use crate::{Material, SurfaceMesh};

/// `ln tan(π/4 + θ/2)` (the integral of sec θ), stable for |θ| < π/2.
fn log_sec_tan(theta: f64) -> f64 {
    (FRAC_PI_4 + 0.5 * theta).tan().ln()
}

/// `∫_triangle U(P, Q) dA_Q` for a load point `p` strictly inside the flat triangle `corners`.
///
/// Returns `None` when `p` is not strictly inside (in the plane, away from the sides) or the
/// triangle is degenerate.
pub fn g_singular(corners: [DVec3; 3], p: DVec3, material: &Material) -> Option<Block> {
    let normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
    let twice_area = normal.length();
    if twice_area.is_nan() || twice_area <= 0.0 {
        return None;
    }
    let nrm = normal / twice_area;
    let scale = twice_area.sqrt();
    if (p - corners[0]).dot(nrm).abs() > 1e-9 * scale {
        return None;
    }
    g_singular_in_plane(corners, p, nrm, material)
}

/// [`g_singular`] for a load point known to lie in the triangle's plane (unit normal `nrm`),
/// such as its centroid: no in-plane test. The in-plane test's tolerance is relative to the
/// triangle's size, and the normal of a sliver (height/edge 1e-7) is only accurate to about
/// 1e-9 of an edge, so a centroid would fail it (issue 36, regression
/// `sliver_element_has_a_diagonal_block`).
fn g_singular_in_plane(
    corners: [DVec3; 3],
    p: DVec3,
    nrm: DVec3,
    material: &Material,
) -> Option<Block> {
    let mut scalar = 0.0; // ∫ 1/r
    let mut tensor = [[0.0f64; 3]; 3]; // ∫ r̂_i r̂_j / r
    for k in 0..3 {
        let a = corners[k];
        let b = corners[(k + 1) % 3];
        let side = b - a;
        let len = side.length();
        let e1 = side / len;
        let foot = a + e1 * (p - a).dot(e1);
        let to_foot = foot - p;
        let d = to_foot.length();
        // P must be on the inner side of every edge (counter-clockwise about the normal).
        if side.cross(p - a).dot(nrm) <= 1e-12 * len * len {
            return None;
        }
        let e2 = to_foot / d;
        let theta_a = (a - foot).dot(e1).atan2(d);
        let theta_b = (b - foot).dot(e1).atan2(d);
        let l = log_sec_tan(theta_b) - log_sec_tan(theta_a);
        let s = theta_b.sin() - theta_a.sin();
        let c = theta_a.cos() - theta_b.cos();
        scalar += d * l;
        let e1a = e1.to_array();
        let e2a = e2.to_array();
        for (i, row) in tensor.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v += d
                    * (s * e2a[i] * e2a[j]
                        + (l - s) * e1a[i] * e1a[j]
                        + c * (e1a[i] * e2a[j] + e2a[i] * e1a[j]));
            }
        }
    }
    let nu = material.poisson();
    let k = 1.0 / (16.0 * PI * material.shear_modulus() * (1.0 - nu));
    let mut out = [[0.0; 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            let delta = if i == j {
                (3.0 - 4.0 * nu) * scalar
            } else {
                0.0
            };
            *v = k * (delta + tensor[i][j]);
        }
    }
    Some(out)
}

/// Diagonal G block of element `e` (collocation node = its centroid).
///
/// Computed in coordinates relative to the element's first corner, so the result depends only on
/// the element's shape, not on where it is (a centroid rounded at 1e7 would otherwise fail the
/// in-plane check).
pub fn g_diagonal(mesh: &SurfaceMesh, e: usize, material: &Material) -> Option<Block> {
    if e >= mesh.element_count() {
        return None;
    }
    let c = mesh.corners(e);
    let local = c.map(|v| v - c[0]);
    let centroid = (local[0] + local[1] + local[2]) / 3.0;
    let normal = (local[1] - local[0]).cross(local[2] - local[0]);
    let twice_area = normal.length();
    if twice_area.is_nan() || twice_area <= 0.0 {
        return None;
    }
    g_singular_in_plane(local, centroid, normal / twice_area, material)
}
