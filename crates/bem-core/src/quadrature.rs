//! Triangle quadrature: the 7-point rule with adaptive 1→4 subdivision for near pairs.

use glam::DVec3;

use crate::kernels::{Block, KernelConstants, Moments};
use crate::{Material, SurfaceMesh};

/// Barycentric coordinates and weights (summing to 1) of the 7-point degree-5 rule (Dunavant / Hammer).
pub const SEVEN_POINT_RULE: [([f64; 3], f64); 7] = {
    const A1: f64 = 0.101_286_507_323_456_34; // (6 − √15)/21
    const B1: f64 = 0.797_426_985_353_087_3; // (9 + 2√15)/21
    const A2: f64 = 0.470_142_064_105_115_1; // (6 + √15)/21
    const B2: f64 = 0.059_715_871_789_769_82; // (9 − 2√15)/21
    const W1: f64 = 0.125_939_180_544_827_14; // (155 − √15)/1200
    const W2: f64 = 0.132_394_152_788_506_2; // (155 + √15)/1200
    [
        ([1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0], 0.225),
        ([B1, A1, A1], W1),
        ([A1, B1, A1], W1),
        ([A1, A1, B1], W1),
        ([B2, A2, A2], W2),
        ([A2, B2, A2], W2),
        ([A2, A2, B2], W2),
    ]
};

/// Quadrature parameters for off-diagonal element pairs.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct QuadratureParams {
    /// A (sub)triangle is split 1→4 while the collocation point is closer to its centroid than
    /// `near_factor` × its longest edge. Default 2.0 (DESIGN.md); 0 disables subdivision.
    pub near_factor: f64,
    /// Maximum subdivision depth (each level multiplies the points of a split triangle by 4). Default 8.
    pub max_depth: u32,
}

impl Default for QuadratureParams {
    fn default() -> Self {
        Self {
            near_factor: 2.0,
            max_depth: 8,
        }
    }
}

/// The 7 quadrature points of a triangle with weights multiplied by its area.
pub(crate) fn seven_points(corners: [DVec3; 3], area: f64) -> [(DVec3, f64); 7] {
    SEVEN_POINT_RULE.map(|(l, w)| {
        (
            corners[0] * l[0] + corners[1] * l[1] + corners[2] * l[2],
            w * area,
        )
    })
}

fn longest_edge(c: &[DVec3; 3]) -> f64 {
    (c[1] - c[0])
        .length_squared()
        .max((c[2] - c[1]).length_squared())
        .max((c[0] - c[2]).length_squared())
        .sqrt()
}

/// Whether a (sub)triangle with this centroid and longest edge must be split for load point `p`.
#[inline(always)]
fn is_near(p: DVec3, centroid: DVec3, longest: f64, factor: f64) -> bool {
    let lim = factor * longest;
    (p - centroid).length_squared() < lim * lim
}

/// Accumulates the kernel moments of a (sub)triangle, subdividing adaptively.
#[allow(clippy::too_many_arguments)] // recursion state; a struct would only rename it
fn accumulate_adaptive(
    p: DVec3,
    c: [DVec3; 3],
    area: f64,
    n: DVec3,
    params: &QuadratureParams,
    depth: u32,
    need_u: bool,
    m: &mut Moments,
) {
    let centroid = (c[0] + c[1] + c[2]) / 3.0;
    if depth < params.max_depth && is_near(p, centroid, longest_edge(&c), params.near_factor) {
        let m01 = 0.5 * (c[0] + c[1]);
        let m12 = 0.5 * (c[1] + c[2]);
        let m20 = 0.5 * (c[2] + c[0]);
        let a4 = 0.25 * area;
        for sub in [
            [c[0], m01, m20],
            [m01, c[1], m12],
            [m20, m12, c[2]],
            [m01, m12, m20],
        ] {
            accumulate_adaptive(p, sub, a4, n, params, depth + 1, need_u, m);
        }
    } else {
        for (q, w) in seven_points(c, area) {
            m.add(p, q, w, n, need_u);
        }
    }
}

/// Per-element data precomputed once for the column pass.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ElementQuad {
    pub corners: [DVec3; 3],
    pub centroid: DVec3,
    pub normal: DVec3,
    pub area: f64,
    pub longest: f64,
    /// The 7 points in lanes of 8 (the 8th repeats a point with weight 0) so the far-field loop
    /// vectorises.
    px: [f64; 8],
    py: [f64; 8],
    pz: [f64; 8],
    pw: [f64; 8],
}

impl ElementQuad {
    pub fn new(mesh: &SurfaceMesh, e: usize) -> Self {
        let corners = mesh.corners(e);
        let area = mesh.area(e);
        let points = seven_points(corners, area);
        let lane = |k: usize| if k < 7 { points[k] } else { (points[0].0, 0.0) };
        Self {
            corners,
            centroid: mesh.centroid(e),
            normal: mesh.normal(e),
            area,
            longest: mesh.longest_edge(e),
            px: std::array::from_fn(|k| lane(k).0.x),
            py: std::array::from_fn(|k| lane(k).0.y),
            pz: std::array::from_fn(|k| lane(k).0.z),
            pw: std::array::from_fn(|k| lane(k).1),
        }
    }

    /// Kernel moments of this element seen from load point `p` (p not on the element).
    #[inline]
    pub fn moments(&self, p: DVec3, params: &QuadratureParams, need_u: bool) -> Moments {
        let mut m = Moments::default();
        if params.max_depth > 0 && is_near(p, self.centroid, self.longest, params.near_factor) {
            accumulate_adaptive(
                p,
                self.corners,
                self.area,
                self.normal,
                params,
                0,
                need_u,
                &mut m,
            );
        } else if need_u {
            m = self.far_moments::<true>(p);
        } else {
            m = self.far_moments::<false>(p);
        }
        m
    }

    /// Plain 7-point rule, written lane-wise (structure of arrays) for auto-vectorisation.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lane-indexed loop over several arrays: that is the point
    fn far_moments<const NEED_U: bool>(&self, p: DVec3) -> Moments {
        let n = self.normal;
        let mut lanes = [[0.0f64; 8]; 17];
        for k in 0..8 {
            let rx = self.px[k] - p.x;
            let ry = self.py[k] - p.y;
            let rz = self.pz[k] - p.z;
            let inv_r = 1.0 / (rx * rx + ry * ry + rz * rz).sqrt();
            let (x, y, z) = (rx * inv_r, ry * inv_r, rz * inv_r);
            let w = self.pw[k];
            let w_r2 = w * inv_r * inv_r;
            let wt = w_r2 * (x * n.x + y * n.y + z * n.z);
            lanes[0][k] = wt;
            lanes[1][k] = wt * x * x;
            lanes[2][k] = wt * y * y;
            lanes[3][k] = wt * z * z;
            lanes[4][k] = wt * x * y;
            lanes[5][k] = wt * x * z;
            lanes[6][k] = wt * y * z;
            lanes[7][k] = w_r2 * x;
            lanes[8][k] = w_r2 * y;
            lanes[9][k] = w_r2 * z;
            if NEED_U {
                let wu = w * inv_r;
                lanes[10][k] = wu;
                lanes[11][k] = wu * x * x;
                lanes[12][k] = wu * y * y;
                lanes[13][k] = wu * z * z;
                lanes[14][k] = wu * x * y;
                lanes[15][k] = wu * x * z;
                lanes[16][k] = wu * y * z;
            }
        }
        let sum = |l: &[f64; 8]| ((l[0] + l[1]) + (l[2] + l[3])) + ((l[4] + l[5]) + (l[6] + l[7]));
        let mut m = Moments {
            t0: sum(&lanes[0]),
            t2: std::array::from_fn(|i| sum(&lanes[1 + i])),
            t1: std::array::from_fn(|i| sum(&lanes[7 + i])),
            ..Moments::default()
        };
        if NEED_U {
            m.u0 = sum(&lanes[10]);
            m.u2 = [
                sum(&lanes[11]),
                sum(&lanes[12]),
                sum(&lanes[13]),
                sum(&lanes[14]),
                sum(&lanes[15]),
                sum(&lanes[16]),
            ];
        }
        m
    }
}

/// Off-diagonal blocks `(H_ij, G_ij)` = ∫ over element `j` of T and U for the collocation node of
/// element `i` (i ≠ j), with the adaptive rule. Useful for research and tests; the assembly uses
/// the same code path.
///
/// Returns `None` when `i == j` (the singular diagonal block is handled by
/// [`crate::singular::g_diagonal`] and the rigid-body row sum) or an index is out of range.
pub fn off_diagonal_blocks(
    mesh: &SurfaceMesh,
    material: &Material,
    i: usize,
    j: usize,
    params: &QuadratureParams,
) -> Option<(Block, Block)> {
    let n = mesh.element_count();
    if i == j || i >= n || j >= n {
        return None;
    }
    let k = KernelConstants::new(material);
    let q = ElementQuad::new(mesh, j);
    let m = q.moments(mesh.centroid(i), params, true);
    Some((k.t_block(&m, q.normal), k.u_block(&m)))
}

/// `(∫ T, ∫ U)` over element `j` for an arbitrary load point `p` off the element, with the
/// adaptive rule (the building block of every off-diagonal block).
///
/// Returns `None` when `j` is out of range or `p` is not finite.
pub fn element_integrals(
    mesh: &SurfaceMesh,
    material: &Material,
    j: usize,
    p: DVec3,
    params: &QuadratureParams,
) -> Option<(Block, Block)> {
    if j >= mesh.element_count() || !p.is_finite() {
        return None;
    }
    let k = KernelConstants::new(material);
    let q = ElementQuad::new(mesh, j);
    let m = q.moments(p, params, true);
    Some((k.t_block(&m, q.normal), k.u_block(&m)))
}
