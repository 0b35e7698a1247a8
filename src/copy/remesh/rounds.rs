//! The rounds of [`super::remesh`]: split, collapse, flip, relax, on an indexed mesh whose
//! adjacency is rebuilt for every pass.

use super::{
    CORNER_COLLAPSE, MIN_LOOP_VERTICES, NONE, RELAX_STEP, RemeshParams, Remeshed, SizeField,
    Surface,
};
use glam::DVec3;
use std::collections::{HashMap, HashSet};

/// The mesh being remeshed. Dead triangles are `[NONE; 3]`; a vertex without live triangles is
/// dropped at the end.
pub(super) struct Work {
    pos: Vec<DVec3>,
    tris: Vec<[u32; 3]>,
    /// Border loop of each vertex, `NONE` inside.
    loop_of: Vec<u32>,
    /// Vertices that never move or go.
    fixed: Vec<bool>,
    /// Border vertices where the loop turns sharply: they stay put, and only go by an edge
    /// much shorter than the local target (two such corners side by side would keep a sliver).
    corner: Vec<bool>,
}

/// Edges (smaller index first) with their triangles, and each vertex's triangles.
struct Adjacency {
    edges: HashMap<(u32, u32), Vec<u32>>,
    star: Vec<Vec<u32>>,
}

impl Adjacency {
    fn sorted_edges(&self) -> Vec<(u32, u32)> {
        let mut e: Vec<(u32, u32)> = self.edges.keys().copied().collect();
        e.sort_unstable();
        e
    }

    fn neighbours(&self, tris: &[[u32; 3]], v: u32) -> Vec<u32> {
        let mut n: Vec<u32> = self.star[v as usize]
            .iter()
            .flat_map(|&t| tris[t as usize])
            .filter(|&w| w != v)
            .collect();
        n.sort_unstable();
        n.dedup();
        n
    }

    fn is_border(&self, a: u32, b: u32) -> bool {
        self.edges
            .get(&(a.min(b), a.max(b)))
            .is_some_and(|t| t.len() == 1)
    }
}

pub(super) fn normal(p: [DVec3; 3]) -> DVec3 {
    (p[1] - p[0]).cross(p[2] - p[0])
}

/// 4√3·area / Σ edge² (1 for an equilateral triangle, 0 for a degenerate one).
pub(super) fn quality(p: [DVec3; 3]) -> f64 {
    let e2 =
        p[0].distance_squared(p[1]) + p[1].distance_squared(p[2]) + p[2].distance_squared(p[0]);
    if e2 > 0.0 {
        2.0 * 3f64.sqrt() * normal(p).length() / e2
    } else {
        0.0
    }
}

impl Work {
    pub(super) fn new(
        positions: &[DVec3],
        triangles: &[[u32; 3]],
        loops: &[Vec<u32>],
        keep: &[bool],
        params: &RemeshParams,
    ) -> Self {
        let mut loop_of = vec![NONE; positions.len()];
        let mut corner = vec![false; positions.len()];
        let fixed: Vec<bool> = (0..positions.len())
            .map(|v| keep.get(v).copied().unwrap_or(false))
            .collect();
        let corner_cos = params.corner_turn_deg.to_radians().cos();
        for (l, lp) in loops.iter().enumerate() {
            let n = lp.len();
            for i in 0..n {
                let v = lp[i];
                loop_of[v as usize] = l as u32;
                let p = |k: usize| positions[lp[k % n] as usize];
                let (din, dout) = (p(i + n) - p(i + n - 1), p(i + 1) - p(i));
                let turn = din.normalize_or_zero().dot(dout.normalize_or_zero());
                if turn < corner_cos {
                    corner[v as usize] = true;
                }
            }
        }
        Work {
            pos: positions.to_vec(),
            tris: triangles.to_vec(),
            loop_of,
            fixed,
            corner,
        }
    }

    fn adjacency(&self) -> Adjacency {
        let mut edges: HashMap<(u32, u32), Vec<u32>> = HashMap::new();
        let mut star = vec![Vec::new(); self.pos.len()];
        for (t, tri) in self.tris.iter().enumerate() {
            if tri[0] == NONE {
                continue;
            }
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                edges
                    .entry((a.min(b), a.max(b)))
                    .or_default()
                    .push(t as u32);
                star[a as usize].push(t as u32);
            }
        }
        Adjacency { edges, star }
    }

    fn corners(&self, t: u32) -> [DVec3; 3] {
        self.tris[t as usize].map(|v| self.pos[v as usize])
    }

    fn loop_len(&self, l: u32, adj: &Adjacency) -> usize {
        (0..self.pos.len())
            .filter(|&v| self.loop_of[v] == l && !adj.star[v].is_empty())
            .count()
    }

    /// The edges whose length relative to the size field at their midpoint passes `keep`, in
    /// index order.
    fn relative_lengths(
        &self,
        adj: &Adjacency,
        size: &SizeField,
        keep: impl Fn(f64) -> bool,
    ) -> Vec<((u32, u32), f64)> {
        adj.sorted_edges()
            .into_iter()
            .map(|(a, b)| {
                let (pa, pb) = (self.pos[a as usize], self.pos[b as usize]);
                ((a, b), pa.distance(pb) / size.at(0.5 * (pa + pb)))
            })
            .filter(|&(_, l)| keep(l))
            .collect()
    }

    /// Splits every edge longer than 4/3 of the size field at its midpoint (on the surface, or on the border
    /// loop for a border edge), longest first, until none is left or the copy holds
    /// `max_triangles`.
    pub(super) fn split_long(&mut self, size: &SizeField, surface: &Surface, max_triangles: usize) {
        for _ in 0..32 {
            let adj = self.adjacency();
            let mut edges = self.relative_lengths(&adj, size, |l| l > 4.0 / 3.0);
            if edges.is_empty() {
                return;
            }
            edges.sort_by(|x, y| y.1.total_cmp(&x.1).then(x.0.cmp(&y.0)));
            let mut touched: HashSet<u32> = HashSet::new();
            for ((a, b), _) in edges {
                if self.tris.len() >= max_triangles {
                    return;
                }
                let owners = &adj.edges[&(a, b)];
                if owners.iter().any(|t| touched.contains(t)) {
                    continue;
                }
                let border = owners.len() == 1;
                let mid = 0.5 * (self.pos[a as usize] + self.pos[b as usize]);
                let (p, l) = if border && self.loop_of[a as usize] != NONE {
                    let l = self.loop_of[a as usize];
                    (surface.project_to_loop(l, mid), l)
                } else {
                    (surface.project(mid), NONE)
                };
                let m = self.pos.len() as u32;
                self.pos.push(p);
                self.loop_of.push(l);
                self.fixed.push(false);
                self.corner.push(false);
                for &t in owners {
                    let tri = self.tris[t as usize];
                    let k = (0..3)
                        .find(|&k| {
                            let (u, v) = (tri[k], tri[(k + 1) % 3]);
                            (u == a && v == b) || (u == b && v == a)
                        })
                        .unwrap_or(0);
                    let (u, v, w) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
                    self.tris[t as usize] = [u, m, w];
                    self.tris.push([m, v, w]);
                    touched.insert(t);
                    touched.insert(self.tris.len() as u32 - 1);
                }
            }
        }
    }

    /// Collapses edges shorter than 4/5 of the size field, shortest first, where the result is
    /// still a valid surface, no new edge exceeds 4/3 of it and no triangle turns too far.
    pub(super) fn collapse_short(&mut self, size: &SizeField, params: &RemeshParams) {
        let max_turn_cos = params.max_turn_deg.to_radians().cos();
        for _ in 0..32 {
            let adj = self.adjacency();
            let mut edges = self.relative_lengths(&adj, size, |l| l < 4.0 / 5.0);
            if edges.is_empty() {
                return;
            }
            edges.sort_by(|x, y| x.1.total_cmp(&y.1).then(x.0.cmp(&y.0)));
            let mut touched = vec![false; self.pos.len()];
            let mut loop_sizes: HashMap<u32, usize> = HashMap::new();
            let mut collapsed = 0;
            for ((a, b), _) in edges {
                if touched[a as usize] || touched[b as usize] {
                    continue;
                }
                for (from, to) in [(a, b), (b, a)] {
                    if self.can_collapse(from, to, &adj, size, max_turn_cos, &mut loop_sizes) {
                        let l = self.loop_of[from as usize];
                        if l != NONE {
                            *loop_sizes.entry(l).or_insert(0) -= 1;
                        }
                        for v in adj.neighbours(&self.tris, from) {
                            touched[v as usize] = true;
                        }
                        for v in adj.neighbours(&self.tris, to) {
                            touched[v as usize] = true;
                        }
                        touched[from as usize] = true;
                        touched[to as usize] = true;
                        for &t in &adj.star[from as usize] {
                            let tri = &mut self.tris[t as usize];
                            if tri.contains(&to) {
                                *tri = [NONE; 3];
                            } else {
                                for v in tri.iter_mut() {
                                    if *v == from {
                                        *v = to;
                                    }
                                }
                            }
                        }
                        collapsed += 1;
                        break;
                    }
                }
            }
            if collapsed == 0 {
                return;
            }
        }
    }

    fn can_collapse(
        &self,
        from: u32,
        to: u32,
        adj: &Adjacency,
        size: &SizeField,
        max_turn_cos: f64,
        loop_sizes: &mut HashMap<u32, usize>,
    ) -> bool {
        if self.fixed[from as usize] {
            return false;
        }
        let p_from = self.pos[from as usize];
        let p_to = self.pos[to as usize];
        if self.corner[from as usize]
            && p_from.distance(p_to) > CORNER_COLLAPSE * size.at(0.5 * (p_from + p_to))
        {
            return false;
        }
        let owners = &adj.edges[&(from.min(to), from.max(to))];
        let border = owners.len() == 1;
        let l = self.loop_of[from as usize];
        if l != NONE {
            // A border vertex only slides along its own border, and a loop keeps enough.
            if !border || self.loop_of[to as usize] != l {
                return false;
            }
            let size = *loop_sizes.entry(l).or_insert_with(|| self.loop_len(l, adj));
            if size <= MIN_LOOP_VERTICES {
                return false;
            }
        }
        // Link condition: the two ends share exactly the edge's opposite vertices.
        let (nf, nt) = (
            adj.neighbours(&self.tris, from),
            adj.neighbours(&self.tris, to),
        );
        let common = nf.iter().filter(|v| nt.binary_search(v).is_ok()).count();
        if common != owners.len() {
            return false;
        }
        if nf.iter().any(|&w| {
            let q = self.pos[w as usize];
            w != to && q.distance(p_to) > 4.0 / 3.0 * size.at(0.5 * (q + p_to))
        }) {
            return false;
        }
        for &t in &adj.star[from as usize] {
            let tri = self.tris[t as usize];
            if tri.contains(&to) {
                continue;
            }
            let old = self.corners(t);
            let new = tri.map(|v| {
                if v == from {
                    p_to
                } else {
                    self.pos[v as usize]
                }
            });
            let (n_old, n_new) = (normal(old).normalize_or_zero(), normal(new));
            if n_new.length() <= 0.0
                || n_old.dot(n_new.normalize_or_zero()) < max_turn_cos
                || quality(new) < 0.2_f64.min(quality(old))
            {
                return false;
            }
        }
        true
    }

    /// Flips inner edges between nearly coplanar triangles where that brings the four
    /// vertices' valences closer to 6 (4 on the border).
    pub(super) fn flip_to_valence(&mut self, params: &RemeshParams) {
        let planar_cos = params.flip_planarity_deg.to_radians().cos();
        let adj = self.adjacency();
        let mut valence: Vec<i64> = (0..self.pos.len())
            .map(|v| adj.neighbours(&self.tris, v as u32).len() as i64)
            .collect();
        let target = |v: u32| {
            if self.loop_of[v as usize] == NONE {
                6
            } else {
                4
            }
        };
        let mut edges_now: HashSet<(u32, u32)> = adj.edges.keys().copied().collect();
        let mut touched = vec![false; self.pos.len()];
        for (a, b) in adj.sorted_edges() {
            let owners = &adj.edges[&(a, b)];
            if owners.len() != 2 {
                continue;
            }
            let (t1, t2) = (owners[0], owners[1]);
            let (tri1, tri2) = (self.tris[t1 as usize], self.tris[t2 as usize]);
            // Orient: t1 = [a', b', c] holding the directed edge a'→b', t2 = [b', a', d].
            let Some(k) = (0..3).find(|&k| {
                let (u, v) = (tri1[k], tri1[(k + 1) % 3]);
                (u == a && v == b) || (u == b && v == a)
            }) else {
                continue;
            };
            let (a, b, c) = (tri1[k], tri1[(k + 1) % 3], tri1[(k + 2) % 3]);
            let Some(&d) = tri2.iter().find(|&&w| w != a && w != b) else {
                continue;
            };
            if [a, b, c, d].iter().any(|&v| touched[v as usize]) || c == d {
                continue;
            }
            if edges_now.contains(&(c.min(d), c.max(d))) {
                continue;
            }
            let dev = |v: u32, delta: i64| (valence[v as usize] + delta - target(v)).pow(2);
            let before = dev(a, 0) + dev(b, 0) + dev(c, 0) + dev(d, 0);
            let after = dev(a, -1) + dev(b, -1) + dev(c, 1) + dev(d, 1);
            if after >= before || valence[a as usize] <= 3 || valence[b as usize] <= 3 {
                continue;
            }
            let (n1, n2) = (
                normal(self.corners(t1)).normalize_or_zero(),
                normal(self.corners(t2)).normalize_or_zero(),
            );
            if n1.dot(n2) < planar_cos {
                continue;
            }
            let p = |v: u32| self.pos[v as usize];
            let (new1, new2) = ([p(c), p(a), p(d)], [p(d), p(b), p(c)]);
            let up = n1 + n2;
            let q_old = quality(self.corners(t1)).min(quality(self.corners(t2)));
            if normal(new1).dot(up) <= 0.0
                || normal(new2).dot(up) <= 0.0
                || quality(new1).min(quality(new2)) < 0.5 * q_old
            {
                continue;
            }
            self.tris[t1 as usize] = [c, a, d];
            self.tris[t2 as usize] = [d, b, c];
            edges_now.remove(&(a, b));
            edges_now.insert((c.min(d), c.max(d)));
            valence[a as usize] -= 1;
            valence[b as usize] -= 1;
            valence[c as usize] += 1;
            valence[d as usize] += 1;
            for v in [a, b, c, d] {
                touched[v as usize] = true;
            }
        }
    }

    /// Moves each free vertex toward its neighbours' centroid in its tangent plane (a border
    /// vertex along its border), back onto the input surface, where no triangle turns too far.
    pub(super) fn relax(&mut self, surface: &Surface, params: &RemeshParams) {
        let max_turn_cos = params.max_turn_deg.to_radians().cos();
        let adj = self.adjacency();
        for v in 0..self.pos.len() as u32 {
            let star = &adj.star[v as usize];
            if star.is_empty() || self.fixed[v as usize] || self.corner[v as usize] {
                continue;
            }
            let p = self.pos[v as usize];
            let l = self.loop_of[v as usize];
            let target = if l == NONE {
                let n = adj.neighbours(&self.tris, v);
                let centroid =
                    n.iter().map(|&w| self.pos[w as usize]).sum::<DVec3>() / n.len() as f64;
                let nv = star
                    .iter()
                    .map(|&t| normal(self.corners(t)))
                    .sum::<DVec3>()
                    .normalize_or_zero();
                let d = centroid - p;
                surface.project(p + RELAX_STEP * (d - nv * nv.dot(d)))
            } else {
                let along: Vec<u32> = adj
                    .neighbours(&self.tris, v)
                    .into_iter()
                    .filter(|&w| self.loop_of[w as usize] == l && adj.is_border(v, w))
                    .collect();
                if along.len() != 2 {
                    continue;
                }
                let mid = 0.5 * (self.pos[along[0] as usize] + self.pos[along[1] as usize]);
                surface.project_to_loop(l, p + RELAX_STEP * (mid - p))
            };
            let ok = star.iter().all(|&t| {
                let old = self.corners(t);
                let new = self.tris[t as usize]
                    .map(|w| if w == v { target } else { self.pos[w as usize] });
                let (n_old, n_new) = (normal(old).normalize_or_zero(), normal(new));
                n_new.length() > 0.0
                    && n_old.dot(n_new.normalize_or_zero()) >= max_turn_cos
                    && quality(new) >= 0.2_f64.min(quality(old))
            });
            if ok {
                self.pos[v as usize] = target;
            }
        }
    }

    /// The live triangles with their vertices renumbered, and each vertex's closest input
    /// vertex.
    pub(super) fn compact(&self, input: &[DVec3]) -> Remeshed {
        let mut index = vec![NONE; self.pos.len()];
        let mut positions = Vec::new();
        let mut nearest_input = Vec::new();
        let bvh_points = super::nearest::PointGrid::new(input);
        let triangles = self
            .tris
            .iter()
            .filter(|t| t[0] != NONE)
            .map(|t| {
                t.map(|v| {
                    if index[v as usize] == NONE {
                        index[v as usize] = positions.len() as u32;
                        let p = self.pos[v as usize];
                        positions.push(p);
                        nearest_input.push(
                            if (v as usize) < input.len() && input[v as usize] == p {
                                v
                            } else {
                                bvh_points.nearest(p)
                            },
                        );
                    }
                    index[v as usize]
                })
            })
            .collect();
        Remeshed {
            positions,
            triangles,
            nearest_input,
        }
    }
}
