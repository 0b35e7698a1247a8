//! A small bounding-volume hierarchy over triangles: ray casts (all hits) and box queries.

use glam::DVec3;

#[derive(Clone, Debug)]
struct Node {
    lo: DVec3,
    hi: DVec3,
    /// Leaf: first item in `order`; inner: index of the left child (right = left + 1).
    first: u32,
    /// Leaf: item count (> 0); inner: 0.
    count: u32,
}

/// A ray hit: distance along the (unit) ray and triangle index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// Ray parameter (distance if the direction is a unit vector).
    pub t: f64,
    /// Index of the triangle hit.
    pub triangle: u32,
}

/// Bounding-volume hierarchy over a triangle soup (median split on the longest axis, ≤ 4
/// triangles per leaf). Build O(n log n), queries O(log n + hits).
///
/// ```
/// use face_prep::bvh::TriangleBvh;
/// use glam::DVec3;
/// let tris = [[DVec3::ZERO, DVec3::X, DVec3::Y]];
/// let bvh = TriangleBvh::new(&tris);
/// let hits = bvh.ray_hits(DVec3::new(0.2, 0.2, 1.0), DVec3::NEG_Z);
/// assert_eq!(hits.len(), 1);
/// assert!((hits[0].t - 1.0).abs() < 1e-12);
/// ```
#[derive(Clone, Debug)]
pub struct TriangleBvh {
    tris: Vec<[DVec3; 3]>,
    order: Vec<u32>,
    nodes: Vec<Node>,
}

impl TriangleBvh {
    /// Builds the hierarchy.
    pub fn new(triangles: &[[DVec3; 3]]) -> TriangleBvh {
        let mut bvh = TriangleBvh {
            tris: triangles.to_vec(),
            order: (0..triangles.len() as u32).collect(),
            nodes: Vec::with_capacity(2 * triangles.len() / 2 + 1),
        };
        let centroids: Vec<DVec3> = triangles
            .iter()
            .map(|t| (t[0] + t[1] + t[2]) / 3.0)
            .collect();
        bvh.nodes.push(Node {
            lo: DVec3::ZERO,
            hi: DVec3::ZERO,
            first: 0,
            count: 0,
        });
        if !triangles.is_empty() {
            bvh.build(0, 0, triangles.len(), &centroids);
        }
        bvh
    }

    fn build(&mut self, node: usize, start: usize, end: usize, centroids: &[DVec3]) {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        let (mut clo, mut chi) = (lo, hi);
        for &i in &self.order[start..end] {
            for p in self.tris[i as usize] {
                lo = lo.min(p);
                hi = hi.max(p);
            }
            clo = clo.min(centroids[i as usize]);
            chi = chi.max(centroids[i as usize]);
        }
        self.nodes[node].lo = lo;
        self.nodes[node].hi = hi;
        if end - start <= 4 {
            self.nodes[node].first = start as u32;
            self.nodes[node].count = (end - start) as u32;
            return;
        }
        let ext = chi - clo;
        let axis = if ext.x >= ext.y && ext.x >= ext.z {
            0
        } else if ext.y >= ext.z {
            1
        } else {
            2
        };
        let mid = (start + end) / 2;
        self.order[start..end].select_nth_unstable_by(mid - start, |&a, &b| {
            centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
        });
        let left = self.nodes.len();
        let empty = Node {
            lo: DVec3::ZERO,
            hi: DVec3::ZERO,
            first: 0,
            count: 0,
        };
        self.nodes.push(empty.clone());
        self.nodes.push(empty);
        self.nodes[node].first = left as u32;
        self.nodes[node].count = 0;
        self.build(left, start, mid, centroids);
        self.build(left + 1, mid, end, centroids);
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.tris.len()
    }

    /// Whether the hierarchy holds no triangle.
    pub fn is_empty(&self) -> bool {
        self.tris.is_empty()
    }

    /// All intersections of the ray `origin + t·dir`, `t > 0`, with the triangles (both sides),
    /// sorted by `t`.
    pub fn ray_hits(&self, origin: DVec3, dir: DVec3) -> Vec<RayHit> {
        let mut hits = Vec::new();
        if self.tris.is_empty() {
            return hits;
        }
        let inv = dir.recip();
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            if !ray_box(origin, inv, node.lo, node.hi) {
                continue;
            }
            if node.count > 0 {
                for &i in &self.order[node.first as usize..(node.first + node.count) as usize] {
                    if let Some(t) = ray_triangle(origin, dir, &self.tris[i as usize]) {
                        hits.push(RayHit { t, triangle: i });
                    }
                }
            } else {
                stack.push(node.first as usize);
                stack.push(node.first as usize + 1);
            }
        }
        hits.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.triangle.cmp(&b.triangle)));
        hits
    }

    /// Indices of the triangles whose bounding boxes overlap the box `lo..hi`.
    pub fn overlapping(&self, lo: DVec3, hi: DVec3) -> Vec<u32> {
        let mut out = Vec::new();
        if self.tris.is_empty() {
            return out;
        }
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            if node.lo.cmpgt(hi).any() || node.hi.cmplt(lo).any() {
                continue;
            }
            if node.count > 0 {
                for &i in &self.order[node.first as usize..(node.first + node.count) as usize] {
                    let t = &self.tris[i as usize];
                    let tlo = t[0].min(t[1]).min(t[2]);
                    let thi = t[0].max(t[1]).max(t[2]);
                    if !(tlo.cmpgt(hi).any() || thi.cmplt(lo).any()) {
                        out.push(i);
                    }
                }
            } else {
                stack.push(node.first as usize);
                stack.push(node.first as usize + 1);
            }
        }
        out
    }
}

fn ray_box(origin: DVec3, inv: DVec3, lo: DVec3, hi: DVec3) -> bool {
    let mut tmin: f64 = 0.0;
    let mut tmax = f64::INFINITY;
    for a in 0..3 {
        let (t1, t2) = ((lo[a] - origin[a]) * inv[a], (hi[a] - origin[a]) * inv[a]);
        // NaN (0 · ∞ for a ray in the slab plane) keeps the ray: max/min ignore NaN.
        tmin = tmin.max(t1.min(t2));
        tmax = tmax.min(t1.max(t2));
    }
    tmin <= tmax
}

/// Möller–Trumbore ray/triangle intersection, both faces; returns `t > 0`.
pub(crate) fn ray_triangle(origin: DVec3, dir: DVec3, tri: &[DVec3; 3]) -> Option<f64> {
    let e1 = tri[1] - tri[0];
    let e2 = tri[2] - tri[0];
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-300 {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - tri[0];
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

/// Whether the segment `a..b` crosses the interior of triangle `tri` (strictly: end points and
/// triangle border excluded up to a relative tolerance of 1e-9).
pub fn segment_crosses_triangle(a: DVec3, b: DVec3, tri: &[DVec3; 3]) -> bool {
    let eps = 1e-9;
    let dir = b - a;
    let e1 = tri[1] - tri[0];
    let e2 = tri[2] - tri[0];
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() <= 1e-12 * dir.length() * e1.length() * e2.length() {
        return false; // parallel or coplanar
    }
    let inv = 1.0 / det;
    let s = a - tri[0];
    let u = s.dot(p) * inv;
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    let t = e2.dot(q) * inv;
    u > eps && v > eps && u + v < 1.0 - eps && t > eps && t < 1.0 - eps
}
