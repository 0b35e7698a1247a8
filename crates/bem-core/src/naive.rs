//! The naive reference assembly: full H and G, element pair by element pair.

use faer::Mat;
use glam::DVec3;

use crate::assembly::try_zeros;
use crate::singular::g_diagonal;
use crate::{BemError, Material, QuadratureParams, SurfaceMesh};

/// Full H and G matrices (3N × 3N each) assembled naively and single-threaded, element pair by
/// element pair with full kernel matrices at every quadrature point. For small meshes, research
/// and tests, and as the naive baseline of the benchmark; the solver never calls it.
/// `H` includes the rigid-body diagonal blocks, `G` the analytic ones.
pub fn assemble_h_g(
    mesh: &SurfaceMesh,
    material: &Material,
    params: &QuadratureParams,
) -> Result<(Mat<f64>, Mat<f64>), BemError> {
    use crate::kernels::{kelvin_t, kelvin_u};
    let local = mesh.recentred();
    let mesh = &local;
    let n = mesh.element_count();
    let mut h = try_zeros(3 * n, 3 * n)?;
    let mut g = try_zeros(3 * n, 3 * n)?;
    for i in 0..n {
        let p = mesh.centroid(i);
        let mut diag = [[0.0; 3]; 3];
        for j in 0..n {
            let (hb, gb) = if i == j {
                let gb = g_diagonal(mesh, j, material).ok_or(BemError::Internal {
                    what: "analytic diagonal G block: centroid not inside its (validated) element",
                })?;
                ([[0.0; 3]; 3], gb)
            } else {
                let mut points = Vec::new();
                collect_points(
                    p,
                    mesh.corners(j),
                    mesh.area(j),
                    mesh.longest_edge(j),
                    params,
                    &mut points,
                );
                let nj = mesh.normal(j);
                let mut hb = [[0.0; 3]; 3];
                let mut gb = [[0.0; 3]; 3];
                for (q, w) in points {
                    let t = kelvin_t(q - p, nj, material);
                    let u = kelvin_u(q - p, material);
                    for a in 0..3 {
                        for b in 0..3 {
                            hb[a][b] += w * t[a][b];
                            gb[a][b] += w * u[a][b];
                        }
                    }
                }
                (hb, gb)
            };
            for a in 0..3 {
                for b in 0..3 {
                    h[(3 * i + a, 3 * j + b)] = hb[a][b];
                    g[(3 * i + a, 3 * j + b)] = gb[a][b];
                    diag[a][b] -= hb[a][b];
                }
            }
        }
        for a in 0..3 {
            for b in 0..3 {
                h[(3 * i + a, 3 * i + b)] = diag[a][b];
            }
        }
    }
    Ok((h, g))
}

/// Quadrature points of the adaptive rule (same subdivision as the assembly) as a list.
fn collect_points(
    p: DVec3,
    c: [DVec3; 3],
    area: f64,
    longest: f64,
    params: &QuadratureParams,
    out: &mut Vec<(DVec3, f64)>,
) {
    use crate::quadrature::{point_triangle_distance, seven_points, visit_leaves};
    let limit = if params.max_depth == 0 {
        0
    } else {
        params.depth_limit(longest, point_triangle_distance(p, c))
    };
    visit_leaves(
        p,
        c,
        area,
        params.near_factor,
        0,
        limit,
        &mut |c, area, at_limit| {
            if at_limit && limit > 0 {
                let m01 = 0.5 * (c[0] + c[1]);
                let m12 = 0.5 * (c[1] + c[2]);
                let m20 = 0.5 * (c[2] + c[0]);
                for sub in [
                    [c[0], m01, m20],
                    [m01, c[1], m12],
                    [m20, m12, c[2]],
                    [m01, m12, m20],
                ] {
                    out.extend(seven_points(sub, 0.25 * area));
                }
            } else {
                out.extend(seven_points(c, area));
            }
        },
    );
}
