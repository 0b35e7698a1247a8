//! The smoothest correction of a response that keeps its triangles from turning over.
//!
//! A linear response can fold the skin: where its gradient is steep (the lips at a mouth
//! corner, a lid margin closing, the copy of a large face carried back to its vertices) a
//! vertex is overtaken by its neighbour and the triangle between them turns over. For a field
//! `u` on a surface mesh, [`project`] finds the correction `c` minimising
//!
//! `E(c) = ½ Σ_v A_v |c_v|² / L² + ½ Σ_t Σ_edges w_ij |c_i − c_j|² + ½ μ Σ_t A_t max(0, a₀ − a_t)²`
//!
//! - `A_v` is the vertex's area (a third of its triangles'), `w_ij` the edge's cotangent
//!   weight in its triangle (held in [0.01, 100] so that slivers and obtuse angles keep the
//!   system positive definite), `L` the screening length over which a correction spreads: the
//!   first two terms are a screened Poisson energy, so the correction is small and smooth and
//!   decays over `L` from where it is needed;
//! - `a_t` is triangle `t`'s posed area projected on its rest normal, as a share of its rest
//!   area `A_t`: 1 at rest, negative once turned over (the test of
//!   [`crate::report::measure::flipped_by`]). The third term is a quadratic penalty (Nocedal &
//!   Wright, *Numerical Optimization*, 2nd ed. 2006, §17.1) on every triangle whose ratio falls
//!   under `a₀`, in the spirit of the orientation barriers of locally injective mappings
//!   (Schüller, Kavan, Panozzo & Sorkine-Hornung, "Locally injective mappings", SGP 2013).
//!
//! It is minimised by Gauss–Newton steps (the ratios linearised at the current shape, §10.3
//! there), each one sparse Cholesky solve (`faer`) over the free vertices within `4 L` of a
//! penalised triangle (farther, the screened correction has decayed to under 2 %), with a
//! backtracking line search that accepts a step only if `E` decreases (§3.1). A step moves
//! only those unknowns, so it evaluates only the triangles touching them: the part of `E` that
//! can change, and the ratios it can change.
//!
//! What it guarantees: `E` decreases at every step; a field under which no triangle's ratio
//! falls under `a₀ / 2` is returned exactly as it was; the fixed vertices keep their values;
//! the result does not depend on the vertex order, nor on the mesh's position, orientation or
//! scale when `L` is given in the mesh's units. What it does not: that every triangle ends with
//! a positive ratio (the penalty is finite; [`project`] returns how many stay turned over).
//!
//! ```
//! use facebem::settle::injective::{ProjectionParams, Surface, project};
//! use glam::DVec3;
//! // A fan of four triangles around vertex 4; the field pushes it past the rim (x = 1).
//! let vertices = [
//!     DVec3::new(-1.0, -1.0, 0.0),
//!     DVec3::new(1.0, -1.0, 0.0),
//!     DVec3::new(1.0, 1.0, 0.0),
//!     DVec3::new(-1.0, 1.0, 0.0),
//!     DVec3::ZERO,
//! ];
//! let triangles = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
//! let fixed = [true, true, true, true, false];
//! let surface = Surface::new(&vertices, &triangles, &fixed, 1.0);
//! let mut field = vec![DVec3::ZERO; 5];
//! field[4] = DVec3::new(1.5, 0.0, 0.0);
//! let turned = project(&surface, &ProjectionParams::default(), &mut field);
//! assert_eq!(turned, 0);
//! assert!(field[4].x > 0.0 && field[4].x < 1.0);
//! ```

use faer::Mat;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use glam::DVec3;

/// The parameters of [`project`] other than the screening length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProjectionParams {
    /// Smallest area ratio `a₀` a triangle keeps without penalty (0.2: a fifth of its rest
    /// area, seen along its rest normal).
    pub min_area_ratio: f64,
    /// Penalty weight `μ` (dimensionless; both other terms scale as a length squared, as the
    /// penalty does).
    pub penalty: f64,
    /// Most Gauss–Newton steps.
    pub max_steps: usize,
    /// The multiples of the field at which the penalty counts each triangle (the slider
    /// values it is used at): both full directions by default.
    pub slider_values: [f64; 2],
}

impl Default for ProjectionParams {
    fn default() -> Self {
        Self {
            min_area_ratio: 0.2,
            penalty: 1e5,
            max_steps: 100,
            slider_values: [1.0, -1.0],
        }
    }
}

/// The screening length `L` the settling uses, mm: a correction spreads over about the width
/// of a lip's red margin.
pub const SCREENING_MM: f64 = 3.0;

/// The edge opposite corner `k` of a triangle: its two other corners.
const EDGES: [(usize, usize); 3] = [(1, 2), (2, 0), (0, 1)];

/// A mesh prepared for [`project`]: rest normals, areas and weights, computed once per face and
/// shared by every response.
pub struct Surface<'a> {
    vertices: &'a [DVec3],
    triangles: &'a [[u32; 3]],
    fixed: &'a [bool],
    /// Screening length `L`, in the mesh's units.
    screening: f64,
    /// Rest unit normal and twice the rest area of each triangle.
    normals: Vec<(DVec3, f64)>,
    weights: Vec<[f64; 3]>,
    area: Vec<f64>,
    /// The triangles around each vertex.
    around: Vec<Vec<u32>>,
}

impl<'a> Surface<'a> {
    /// Prepares `vertices` and `triangles` with the vertices flagged in `fixed` held and the
    /// screening length `screening` (mesh units). A vertex missing from `fixed` is free; a
    /// triangle with an index out of range is left out.
    pub fn new(
        vertices: &'a [DVec3],
        triangles: &'a [[u32; 3]],
        fixed: &'a [bool],
        screening: f64,
    ) -> Self {
        let n = vertices.len();
        let mut area = vec![0.0; n];
        let mut around = vec![Vec::new(); n];
        let mut normals = Vec::with_capacity(triangles.len());
        let mut weights = Vec::with_capacity(triangles.len());
        for (ti, t) in triangles.iter().enumerate() {
            if t.iter().any(|&v| v as usize >= n) {
                normals.push((DVec3::ZERO, 0.0));
                weights.push([0.0; 3]);
                continue;
            }
            let p = t.map(|v| vertices[v as usize]);
            let cross = (p[1] - p[0]).cross(p[2] - p[0]);
            let twice = cross.length();
            normals.push((cross.normalize_or_zero(), twice));
            for &v in t {
                area[v as usize] += twice / 6.0;
                around[v as usize].push(ti as u32);
            }
            weights.push(std::array::from_fn(|k| {
                let (a, b) = (p[EDGES[k].0] - p[k], p[EDGES[k].1] - p[k]);
                let sine = a.cross(b).length();
                let cot = if sine > 0.0 { a.dot(b) / sine } else { 0.0 };
                (0.5 * cot).clamp(1e-2, 1e2)
            }));
        }
        Self {
            vertices,
            triangles,
            fixed,
            screening,
            normals,
            weights,
            area,
            around,
        }
    }

    /// The area ratio `a_t` of triangle `t` under `value` × `field`, with its gradient with
    /// respect to the field by corner; 1 and no gradient for a degenerate triangle.
    fn ratio(&self, t: usize, field: &[DVec3], value: f64) -> (f64, [DVec3; 3]) {
        let (n, twice) = self.normals[t];
        if twice.is_nan() || twice <= 0.0 {
            return (1.0, [DVec3::ZERO; 3]);
        }
        let p = self.triangles[t].map(|v| self.vertices[v as usize] + value * field[v as usize]);
        let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
        let g1 = value * e2.cross(n) / twice;
        let g2 = value * n.cross(e1) / twice;
        (e1.cross(e2).dot(n) / twice, [-(g1 + g2), g1, g2])
    }

    /// The smallest area ratio of triangle `t` over the slider values of `params`.
    fn lowest_ratio(&self, t: usize, field: &[DVec3], params: &ProjectionParams) -> f64 {
        params
            .slider_values
            .iter()
            .map(|&s| self.ratio(t, field, s).0)
            .fold(f64::INFINITY, f64::min)
    }

    /// How many triangles `field` turns over (area ratio under zero) at full value.
    pub fn turned(&self, field: &[DVec3]) -> usize {
        (0..self.triangles.len())
            .filter(|&t| self.ratio(t, field, 1.0).0 < 0.0)
            .count()
    }

    /// The part of the energy `E` ([the module](self)) of the correction `field − original`
    /// that moves with the unknowns `index`: the screening terms of the unknowns and every term
    /// of the triangles `touched` (those with an unknown corner). The rest of `E` stays as it
    /// is while only the unknowns move, so comparing this part compares `E`.
    fn local_energy(
        &self,
        params: &ProjectionParams,
        original: &[DVec3],
        field: &[DVec3],
        index: &[usize],
        touched: &[usize],
    ) -> f64 {
        let inv_l2 = 1.0 / (self.screening * self.screening);
        let c = |v: u32| field[v as usize] - original[v as usize];
        let mut e: f64 = (0..field.len())
            .filter(|&v| index[v] != usize::MAX)
            .map(|v| 0.5 * self.area[v] * inv_l2 * c(v as u32).length_squared())
            .sum();
        for &t in touched {
            if self.normals[t].1.is_nan() || self.normals[t].1 <= 0.0 {
                continue;
            }
            let tri = self.triangles[t];
            for (k, &(a, b)) in EDGES.iter().enumerate() {
                e += 0.5 * self.weights[t][k] * (c(tri[a]) - c(tri[b])).length_squared();
            }
            for &value in &params.slider_values {
                let a = self.ratio(t, field, value).0;
                if a < params.min_area_ratio {
                    let shortfall = params.min_area_ratio - a;
                    e += 0.25 * params.penalty * self.normals[t].1 * shortfall * shortfall;
                }
            }
        }
        e
    }

    /// The triangles with a corner among the unknowns `index`, in order.
    fn touched(&self, index: &[usize]) -> Vec<usize> {
        let mut touched = vec![false; self.triangles.len()];
        for (v, &i) in index.iter().enumerate() {
            if i != usize::MAX {
                for &t in &self.around[v] {
                    touched[t as usize] = true;
                }
            }
        }
        (0..touched.len()).filter(|&t| touched[t]).collect()
    }
}

/// Corrects `field` (one displacement per vertex of `surface`) in place by the method of [the
/// module](self); returns how many triangles stay turned over. A field of the wrong length is
/// left as it is.
pub fn project(surface: &Surface<'_>, params: &ProjectionParams, field: &mut [DVec3]) -> usize {
    let s = surface;
    if field.len() != s.vertices.len() || s.screening.is_nan() || s.screening <= 0.0 {
        return s.turned(field);
    }
    let original = field.to_vec();
    // Each triangle's lowest ratio; a step moves only the unknowns, so only the triangles
    // touching them change.
    let mut lowest: Vec<f64> = (0..s.triangles.len())
        .map(|t| s.lowest_ratio(t, field, params))
        .collect();
    for _ in 0..params.max_steps {
        if lowest.iter().all(|&a| a >= 0.5 * params.min_area_ratio) {
            break;
        }
        let penalised: Vec<usize> = (0..s.triangles.len())
            .filter(|&t| lowest[t] < params.min_area_ratio)
            .collect();
        let index = free_near(s, &penalised);
        let touched = s.touched(&index.0);
        let Some(step) = gauss_newton_step(s, params, &original, field, &index, &touched) else {
            break;
        };
        if !line_search(s, params, &original, field, &index.0, &touched, &step) {
            break;
        }
        for &t in &touched {
            lowest[t] = s.lowest_ratio(t, field, params);
        }
    }
    s.turned(field)
}

/// Index among the unknowns of each free vertex within `4 L` of a penalised triangle's
/// centroid (`usize::MAX`: not an unknown), and how many there are.
fn free_near(s: &Surface<'_>, penalised: &[usize]) -> (Vec<usize>, usize) {
    let reach = 4.0 * s.screening;
    // The centroids binned in cubes of side `reach`: a vertex within `reach` of one lies in
    // its own cube or one of the 26 around it, so each vertex looks at a few centroids.
    let cell = |p: DVec3| (p / reach).floor().as_i64vec3();
    let mut bins: std::collections::HashMap<glam::I64Vec3, Vec<DVec3>> =
        std::collections::HashMap::new();
    for &t in penalised {
        let centre = s.triangles[t]
            .iter()
            .map(|&v| s.vertices[v as usize])
            .sum::<DVec3>()
            / 3.0;
        bins.entry(cell(centre)).or_default().push(centre);
    }
    let near = |p: DVec3| {
        let c = cell(p);
        (-1..=1).any(|dx| {
            (-1..=1).any(|dy| {
                (-1..=1).any(|dz| {
                    bins.get(&c.wrapping_add(glam::I64Vec3::new(dx, dy, dz)))
                        .is_some_and(|b| b.iter().any(|q| q.distance_squared(p) <= reach * reach))
                })
            })
        })
    };
    let mut index = vec![usize::MAX; s.vertices.len()];
    let mut m = 0;
    for (v, p) in s.vertices.iter().enumerate() {
        if !s.fixed.get(v).copied().unwrap_or(false) && near(*p) {
            index[v] = m;
            m += 1;
        }
    }
    (index, m)
}

/// One Gauss–Newton step for the unknowns `index` ([`free_near`]), whose triangles are
/// `touched` ([`Surface::touched`]): the solution of
/// `H δ = −∇E` with `H` the screening and smoothness terms plus the penalty's `μ A_t g gᵀ` of
/// the linearised ratios. `None` when there is nothing to move or the factorisation fails.
fn gauss_newton_step(
    s: &Surface<'_>,
    params: &ProjectionParams,
    original: &[DVec3],
    field: &[DVec3],
    (index, m): &(Vec<usize>, usize),
    touched: &[usize],
) -> Option<Mat<f64>> {
    let m = *m;
    if m == 0 {
        return None;
    }
    let unknown = |v: u32| Some(index[v as usize]).filter(|&i| i != usize::MAX);
    let c: Vec<DVec3> = field.iter().zip(original).map(|(f, o)| *f - *o).collect();
    let inv_l2 = 1.0 / (s.screening * s.screening);
    let mut entries: Vec<Triplet<usize, usize, f64>> = Vec::new();
    let mut grad = Mat::<f64>::zeros(3 * m, 1);
    for (v, &i) in index.iter().enumerate() {
        if i == usize::MAX {
            continue;
        }
        for d in 0..3 {
            entries.push(Triplet::new(3 * i + d, 3 * i + d, s.area[v] * inv_l2));
            grad[(3 * i + d, 0)] += s.area[v] * inv_l2 * c[v][d];
        }
    }
    for &t in touched {
        let tri = &s.triangles[t];
        for (k, &(a, b)) in EDGES.iter().enumerate() {
            let w = s.weights[t][k];
            let (i, j) = (unknown(tri[a]), unknown(tri[b]));
            let dc = c[tri[a] as usize] - c[tri[b] as usize];
            for d in 0..3 {
                if let Some(i) = i {
                    entries.push(Triplet::new(3 * i + d, 3 * i + d, w));
                    grad[(3 * i + d, 0)] += w * dc[d];
                }
                if let Some(j) = j {
                    entries.push(Triplet::new(3 * j + d, 3 * j + d, w));
                    grad[(3 * j + d, 0)] -= w * dc[d];
                }
                if let (Some(i), Some(j)) = (i, j) {
                    entries.push(Triplet::new(3 * i + d, 3 * j + d, -w));
                    entries.push(Triplet::new(3 * j + d, 3 * i + d, -w));
                }
            }
        }
        for &value in &params.slider_values {
            let (a, g) = s.ratio(t, field, value);
            if a < params.min_area_ratio {
                let w = 0.5 * params.penalty * s.normals[t].1;
                add_penalty(
                    &mut entries,
                    &mut grad,
                    w * (a - params.min_area_ratio),
                    w,
                    &g,
                    tri,
                    &unknown,
                );
            }
        }
    }
    let matrix = SparseColMat::<usize, f64>::try_new_from_triplets(3 * m, 3 * m, &entries).ok()?;
    let llt = matrix.sp_cholesky(faer::Side::Lower).ok()?;
    for x in grad.col_as_slice_mut(0) {
        *x = -*x;
    }
    llt.solve_in_place(grad.as_mut());
    Some(grad)
}

/// Adds one penalised ratio's Gauss–Newton terms: `w_grad · g` to the gradient and
/// `w_hess · g gᵀ` to the matrix, over the corners of `tri` that are unknowns.
fn add_penalty(
    entries: &mut Vec<Triplet<usize, usize, f64>>,
    grad: &mut Mat<f64>,
    w_grad: f64,
    w_hess: f64,
    g: &[DVec3; 3],
    tri: &[u32; 3],
    unknown: &impl Fn(u32) -> Option<usize>,
) {
    for (ka, &va) in tri.iter().enumerate() {
        let Some(i) = unknown(va) else { continue };
        for d in 0..3 {
            grad[(3 * i + d, 0)] += w_grad * g[ka][d];
        }
        for (kb, &vb) in tri.iter().enumerate() {
            let Some(j) = unknown(vb) else { continue };
            for d in 0..3 {
                for e in 0..3 {
                    entries.push(Triplet::new(
                        3 * i + d,
                        3 * j + e,
                        w_hess * g[ka][d] * g[kb][e],
                    ));
                }
            }
        }
    }
}

/// Moves the unknowns `index` of `field` along `step`, halving it until `E` decreases (at
/// most 12 times); leaves `field` as it was and returns `false` when it never does.
fn line_search(
    s: &Surface<'_>,
    params: &ProjectionParams,
    original: &[DVec3],
    field: &mut [DVec3],
    index: &[usize],
    touched: &[usize],
    step: &Mat<f64>,
) -> bool {
    let before = s.local_energy(params, original, field, index, touched);
    let start = field.to_vec();
    let mut length = 1.0;
    for _ in 0..12 {
        for (v, &i) in index.iter().enumerate() {
            if i != usize::MAX {
                let d = DVec3::new(step[(3 * i, 0)], step[(3 * i + 1, 0)], step[(3 * i + 2, 0)]);
                field[v] = start[v] + length * d;
            }
        }
        if s.local_energy(params, original, field, index, touched) < before {
            return true;
        }
        length *= 0.5;
    }
    field.copy_from_slice(&start);
    false
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    /// An n × n grid in the z = 0 plane, spacing 1, its border fixed.
    fn grid(n: usize) -> (Vec<DVec3>, Vec<[u32; 3]>, Vec<bool>) {
        let mut v = Vec::new();
        let mut fixed = Vec::new();
        for j in 0..n {
            for i in 0..n {
                v.push(DVec3::new(i as f64, j as f64, 0.0));
                fixed.push(i == 0 || j == 0 || i == n - 1 || j == n - 1);
            }
        }
        let mut t = Vec::new();
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                let a = (j * n + i) as u32;
                let n = n as u32;
                t.push([a, a + 1, a + n + 1]);
                t.push([a, a + n + 1, a + n]);
            }
        }
        (v, t, fixed)
    }

    /// A smooth bump with one vertex (the centre of a 9 × 9 grid) pushed 1.6 spacings along x,
    /// past its neighbour: it turns the triangles around it over.
    fn folding_field(v: &[DVec3]) -> Vec<DVec3> {
        v.iter()
            .enumerate()
            .map(|(i, p)| {
                let bump = 0.3 * (-(p - DVec3::new(4.0, 4.0, 0.0)).length_squared() / 8.0).exp();
                let push = if i == 40 {
                    DVec3::new(1.6, 0.0, 0.0)
                } else {
                    DVec3::ZERO
                };
                DVec3::new(0.0, 0.0, bump) + push
            })
            .collect()
    }

    #[test]
    fn a_folded_vertex_is_unfolded_and_the_far_field_barely_moves() {
        let (v, t, fixed) = grid(9);
        let field = folding_field(&v);
        let surface = Surface::new(&v, &t, &fixed, 1.0);
        assert!(surface.turned(&field) >= 2, "the test field must fold");
        let mut out = field.clone();
        let turned = project(&surface, &ProjectionParams::default(), &mut out);
        assert_eq!(turned, 0);
        // Three spacings from the folded vertex the correction is under 5 % of the push.
        for (i, p) in v.iter().enumerate() {
            if (p - v[40]).length() >= 3.0 {
                assert!(
                    (out[i] - field[i]).length() < 0.08,
                    "vertex {i}: {}",
                    out[i]
                );
            }
        }
    }

    #[test]
    fn a_field_that_folds_nothing_is_returned_exactly() {
        let (v, t, fixed) = grid(9);
        let field: Vec<DVec3> = v
            .iter()
            .map(|p| DVec3::new(0.2 * p.y, 0.1, 0.3 * p.x))
            .collect();
        let mut out = field.clone();
        let surface = Surface::new(&v, &t, &fixed, 1.0);
        assert_eq!(project(&surface, &ProjectionParams::default(), &mut out), 0);
        assert_eq!(out, field);
    }

    #[test]
    fn the_correction_is_invariant_to_rotation_scale_shift_and_vertex_order() {
        let (v, t, fixed) = grid(9);
        let field = folding_field(&v);
        let params = ProjectionParams::default();
        let mut reference = field.clone();
        project(&Surface::new(&v, &t, &fixed, 1.0), &params, &mut reference);
        // Rotated 30° about a tilted axis, ×10, shifted, vertices in reverse order.
        let q = DQuat::from_axis_angle(
            DVec3::new(1.0, 2.0, 3.0).normalize(),
            std::f64::consts::FRAC_PI_6,
        );
        let n = v.len();
        let moved = |i: usize| q * (v[i] * 10.0) + DVec3::new(1000.0, -5.0, 3.0);
        let v2: Vec<DVec3> = (0..n).map(|i| moved(n - 1 - i)).collect();
        let fixed2: Vec<bool> = (0..n).map(|i| fixed[n - 1 - i]).collect();
        let t2: Vec<[u32; 3]> = t
            .iter()
            .map(|tri| tri.map(|a| (n - 1) as u32 - a))
            .collect();
        let mut field2: Vec<DVec3> = (0..n).map(|i| q * (field[n - 1 - i] * 10.0)).collect();
        project(&Surface::new(&v2, &t2, &fixed2, 10.0), &params, &mut field2);
        for i in 0..n {
            let back = q.inverse() * field2[n - 1 - i] / 10.0;
            assert!((back - reference[i]).length() < 1e-6, "vertex {i}");
        }
    }
}
