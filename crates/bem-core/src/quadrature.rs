//! Triangle quadrature: the 7-point rule with adaptive 1→4 subdivision for near pairs, its depth
//! limited per pair from the gap and the tolerance, with an error estimate where it is reached.

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
///
/// A (sub)triangle seen from the collocation point at a centroid distance of at least
/// `near_factor` × its longest edge is integrated with the 7-point rule, accurate there to about
/// 1e-5 of its contribution (the a-priori error estimate, `docs/design/solve.md`); closer ones are split 1→4
/// at the edge midpoints. The depth of this subdivision is limited per pair from the geometry and
/// the tolerance: `ceil(log2(near_factor · longest / max(gap, tolerance · longest))) + 2` levels
/// (gap = distance from the point to the element), which lets every pair with
/// `gap ≥ tolerance · longest` converge, and at most `max_depth`. A (sub)triangle still too close
/// at the limit is integrated one level finer and the difference to its own 7-point value is its
/// a-posteriori error estimate; pairs whose estimated relative error exceeds `tolerance` are
/// counted as unconverged ([`crate::AssemblyReport`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct QuadratureParams {
    /// A (sub)triangle is split 1→4 while the collocation point is closer to its centroid than
    /// `near_factor` × its longest edge. Default 2.0 (`docs/design/solve.md`); 0 disables subdivision.
    pub near_factor: f64,
    /// Hard cap on the subdivision depth (each level replaces a split triangle by 4); 0 disables
    /// subdivision. Default 40: the limit derived from `tolerance` is lower (17 at 1e-4).
    pub max_depth: u32,
    /// Requested relative accuracy of a block; also the smallest gap, relative to the element
    /// size, that the depth limit resolves. Default 1e-4.
    pub tolerance: f64,
}

impl Default for QuadratureParams {
    fn default() -> Self {
        Self {
            near_factor: 2.0,
            max_depth: 40,
            tolerance: 1e-4,
        }
    }
}

impl QuadratureParams {
    /// Subdivision depth limit for a point `gap` away from an element with longest edge
    /// `longest` (see the type's documentation).
    ///
    /// ```
    /// let q = bem_core::QuadratureParams::default();
    /// assert_eq!(q.depth_limit(1.0, 0.1), 7); // log2(2 / 0.1) = 4.3 → 5, + 2
    /// assert_eq!(q.depth_limit(1.0, 1e-4), 17);
    /// assert_eq!(q.depth_limit(1.0, 0.0), 17); // no gap: limited by the tolerance
    /// ```
    pub fn depth_limit(&self, longest: f64, gap: f64) -> u32 {
        let floor = self.tolerance.max(f64::EPSILON) * longest;
        let ratio = self.near_factor * longest / gap.max(floor);
        let levels = if ratio > 1.0 {
            ratio.log2().ceil()
        } else {
            0.0
        };
        // finite and at most ~60 for any positive tolerance
        (levels as u32 + 2).min(self.max_depth)
    }
}

/// Distance from `p` to the triangle `c` (closest point by region, Ericson's
/// *Real-Time Collision Detection* §5.1.5).
pub fn point_triangle_distance(p: DVec3, c: [DVec3; 3]) -> f64 {
    let [a, b, cc] = c;
    let (ab, ac, ap) = (b - a, cc - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (p - (a + v * ab)).length();
    }
    let cp = p - cc;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (p - (a + w * ac)).length();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (p - (b + w * (cc - b))).length();
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    (p - (a + ab * v + ac * w)).length()
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

/// The four midpoint children of a triangle.
fn children(c: [DVec3; 3]) -> [[DVec3; 3]; 4] {
    let m01 = 0.5 * (c[0] + c[1]);
    let m12 = 0.5 * (c[1] + c[2]);
    let m20 = 0.5 * (c[2] + c[0]);
    [
        [c[0], m01, m20],
        [m01, c[1], m12],
        [m20, m12, c[2]],
        [m01, m12, m20],
    ]
}

/// Visits the leaves of the adaptive subdivision of `c` (area `area`) for load point `p`, in a
/// fixed order: `leaf(corners, area, at_limit)`, `at_limit` when the leaf is still too close
/// but the depth limit is reached.
pub(crate) fn visit_leaves<F: FnMut([DVec3; 3], f64, bool)>(
    p: DVec3,
    c: [DVec3; 3],
    area: f64,
    factor: f64,
    depth: u32,
    limit: u32,
    leaf: &mut F,
) {
    let centroid = (c[0] + c[1] + c[2]) / 3.0;
    if !is_near(p, centroid, longest_edge(&c), factor) {
        leaf(c, area, false);
    } else if depth >= limit {
        leaf(c, area, true);
    } else {
        for sub in children(c) {
            visit_leaves(p, sub, 0.25 * area, factor, depth + 1, limit, leaf);
        }
    }
}

/// Kernel moments of a near (sub)triangle by adaptive subdivision, and the summed a-posteriori
/// error estimate of the leaves at the depth limit.
fn adaptive_moments(
    p: DVec3,
    q: &ElementQuad,
    params: &QuadratureParams,
    need_u: bool,
) -> (Moments, Moments) {
    let n = q.normal;
    let gap = point_triangle_distance(p, q.corners);
    let limit = params.depth_limit(q.longest, gap);
    let mut m = Moments::default();
    let mut err = Moments::default();
    let seven = |c: [DVec3; 3], area: f64, m: &mut Moments| {
        for (x, w) in seven_points(c, area) {
            m.add(p, x, w, n, need_u);
        }
    };
    visit_leaves(
        p,
        q.corners,
        q.area,
        params.near_factor,
        0,
        limit,
        &mut |c, area, at_limit| {
            if at_limit {
                // one level finer, and its difference to this level as the error estimate
                let mut coarse = Moments::default();
                seven(c, area, &mut coarse);
                let mut fine = Moments::default();
                for sub in children(c) {
                    seven(sub, 0.25 * area, &mut fine);
                }
                err.add_abs_diff(&fine, &coarse);
                m.add_moments(&fine);
            } else {
                seven(c, area, &mut m);
            }
        },
    );
    (m, err)
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
        Self::with_geometry(
            mesh.corners(e),
            mesh.centroid(e),
            mesh.normal(e),
            mesh.area(e),
            mesh.longest_edge(e),
        )
    }

    /// From corners alone (`None` for a degenerate triangle).
    fn from_corners(corners: [DVec3; 3]) -> Option<Self> {
        let cross = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
        let area = 0.5 * cross.length();
        if area.is_nan() || area <= 0.0 || !area.is_finite() {
            return None;
        }
        Some(Self::with_geometry(
            corners,
            (corners[0] + corners[1] + corners[2]) / 3.0,
            cross / (2.0 * area),
            area,
            longest_edge(&corners),
        ))
    }

    fn with_geometry(
        corners: [DVec3; 3],
        centroid: DVec3,
        normal: DVec3,
        area: f64,
        longest: f64,
    ) -> Self {
        let points = seven_points(corners, area);
        let lane = |k: usize| if k < 7 { points[k] } else { (points[0].0, 0.0) };
        Self {
            corners,
            centroid,
            normal,
            area,
            longest,
            px: std::array::from_fn(|k| lane(k).0.x),
            py: std::array::from_fn(|k| lane(k).0.y),
            pz: std::array::from_fn(|k| lane(k).0.z),
            pw: std::array::from_fn(|k| lane(k).1),
        }
    }

    /// Kernel moments of this element seen from load point `p` (p not on the element), and
    /// the estimated relative error of the block (0 unless the depth limit was reached).
    #[inline]
    pub fn moments(&self, p: DVec3, params: &QuadratureParams, need_u: bool) -> (Moments, f64) {
        if params.max_depth > 0 && is_near(p, self.centroid, self.longest, params.near_factor) {
            let (m, err) = adaptive_moments(p, self, params, need_u);
            let rel = err.relative_to(&m, need_u);
            (m, rel)
        } else if need_u {
            (self.far_moments::<true>(p), 0.0)
        } else {
            (self.far_moments::<false>(p), 0.0)
        }
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
    element_integrals(mesh, material, j, mesh.centroid(i), params)
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
    let (m, _) = q.moments(p, params, true);
    Some((k.t_block(&m, q.normal), k.u_block(&m)))
}

/// Integrals of the Kelvin kernels over one flat triangle, with the quadrature's error estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriangleIntegrals {
    /// `∫ T dA` (normal from the corners' counter-clockwise order).
    pub h: Block,
    /// `∫ U dA`.
    pub g: Block,
    /// Estimated relative error (0 when the subdivision converged within its depth limit).
    pub estimated_error: f64,
}

/// `∫ T` and `∫ U` over the triangle `corners` for load point `p`, exactly as the assembly
/// computes an off-diagonal block, with its error estimate.
///
/// Returns `None` for a degenerate triangle or a non-finite point.
///
/// ```
/// use bem_core::{Material, QuadratureParams, quadrature::triangle_integrals};
/// use glam::DVec3;
/// let corners = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// let m = Material::new(0.3, 1.0).unwrap();
/// // 1e-4 of the element above its centroid: converged
/// let p = DVec3::new(1.0 / 3.0, 1.0 / 3.0, 1e-4);
/// let near = triangle_integrals(corners, p, &m, &QuadratureParams::default()).unwrap();
/// assert!(near.estimated_error < 1e-4);
/// // 1e-8 above it the default depth limit is reached: the estimate says so
/// let touching = DVec3::new(1.0 / 3.0, 1.0 / 3.0, 1e-8);
/// let bad = triangle_integrals(corners, touching, &m, &QuadratureParams::default()).unwrap();
/// assert!(bad.estimated_error > 1e-4);
/// ```
pub fn triangle_integrals(
    corners: [DVec3; 3],
    p: DVec3,
    material: &Material,
    params: &QuadratureParams,
) -> Option<TriangleIntegrals> {
    if !p.is_finite() {
        return None;
    }
    let q = ElementQuad::from_corners(corners)?;
    let k = KernelConstants::new(material);
    let (m, estimated_error) = q.moments(p, params, true);
    Some(TriangleIntegrals {
        h: k.t_block(&m, q.normal),
        g: k.u_block(&m),
        estimated_error,
    })
}
