//! Step 6 of the shell construction: local repair of back and rim elements that intersect
//! anything, and the last-resort relocation of the vertices still stuck afterwards.

use std::cell::Cell;
use std::collections::HashSet;

use glam::DVec3;

use super::intersect::triangles_intersect;
use super::model::{ElementTag, Shell};
use super::offset::vertex_adjacency;
use crate::bvh::TriangleBvh;

/// Element-pair tests [`Shell`]'s last-resort relocation of stuck back vertices may make per
/// shell element: bounds its time by the shell's size on scrambled input (a `v` line swapped:
/// elements spanning the whole face), far above what the bundled faces use.
pub(crate) const RELOCATE_TESTS_PER_ELEMENT: usize = 500;

/// Factor applied per repair round to the offset of back/rim vertices of intersecting elements.
/// Gentler than halving: with the full offset kept up to the knife-edge taper, halving thinned
/// concave creases (Lee Perry-Smith's alar groove) to a quarter of the offset, where 0.7 resolves
/// the same intersections at 0.4 or more of it.
pub const REPAIR_SHRINK: f64 = 0.7;

impl Shell {
    /// Where back or rim elements intersect another element, their moved vertices first switch
    /// to the robust offset direction (`robust_dir`, outward) and then have their offset scaled
    /// by [`REPAIR_SHRINK`] per round (toward their anchors on the front face), for at most
    /// `rounds` rounds.
    /// Intersections between two front elements belong to the input and are left alone.
    pub(super) fn repair_back_intersections(
        &mut self,
        n_front: usize,
        anchor: &[DVec3],
        robust_dir: &[DVec3],
        rounds: usize,
    ) {
        let mut disp: Vec<DVec3> = self
            .vertices
            .iter()
            .zip(anchor)
            .map(|(p, a)| *p - *a)
            .collect();
        let mut redirected = vec![false; self.vertices.len()];
        let mut scale = vec![1.0f64; self.vertices.len()];
        for _ in 0..rounds {
            let bad = self.self_intersections();
            let mut shrink = HashSet::new();
            for pair in bad {
                for e in pair {
                    if self.tags[e as usize] != ElementTag::Front {
                        shrink.extend(
                            self.triangles[e as usize]
                                .iter()
                                .copied()
                                .filter(|&v| v as usize >= n_front),
                        );
                    }
                }
            }
            if shrink.is_empty() {
                return;
            }
            for v in shrink {
                let v = v as usize;
                if !redirected[v] {
                    redirected[v] = true;
                    disp[v] = -robust_dir[v] * disp[v].length();
                } else {
                    scale[v] *= REPAIR_SHRINK;
                }
                self.vertices[v] = anchor[v] + disp[v] * scale[v];
            }
        }
        // Vertices still in an intersection after every round sit where the input itself
        // overlaps (e.g. interpenetrating lips): shrinking them gains nothing and only makes
        // the shell needlessly thin there, so they get their full (redirected) offset back.
        let stuck: HashSet<u32> = self
            .self_intersections()
            .into_iter()
            .flatten()
            .filter(|&e| self.tags[e as usize] != ElementTag::Front)
            .flat_map(|e| self.triangles[e as usize])
            .filter(|&v| v as usize >= n_front)
            .collect();
        let mut stuck: Vec<usize> = stuck.into_iter().map(|v| v as usize).collect();
        stuck.sort_unstable();
        for &v in &stuck {
            self.vertices[v] = anchor[v] + disp[v];
        }
        self.relocate_stuck(&stuck, anchor, &disp, robust_dir);
    }

    /// Last resort for back vertices still in an intersection after the repair rounds (tight
    /// folds such as the corners of pressed-together lips, where no single direction is behind
    /// every incident front triangle): a few sweeps of a local search that moves each such
    /// vertex to the candidate position with the fewest intersections of its incident elements.
    /// Candidates: the current position; along its repair direction, its robust direction and
    /// the mean of its neighbours' offsets at 1, 1/2, …, 1/1024 of its offset; along the 26
    /// axis and diagonal directions at 1, 1/2, …, 1/32 of it; the mean of its neighbours.
    /// Positions that would make an incident element a sliver are skipped. Ties keep the
    /// earlier candidate (the current one first), so a vertex only moves when that removes
    /// intersections; a shell without intersections is never touched.
    fn relocate_stuck(
        &mut self,
        stuck: &[usize],
        anchor: &[DVec3],
        disp: &[DVec3],
        robust_dir: &[DVec3],
    ) {
        if stuck.is_empty() {
            return;
        }
        let nv = self.vertices.len();
        let mut incident: Vec<Vec<usize>> = vec![Vec::new(); nv];
        for (e, t) in self.triangles.iter().enumerate() {
            for &v in t {
                incident[v as usize].push(e);
            }
        }
        let adjacency = vertex_adjacency(nv, &self.triangles);
        // Work bound: element-pair tests in proportion to the shell's size, so scrambled
        // geometry (long elements overlapping the whole face, many stuck vertices) cannot make
        // this quadratic. When it runs out, the remaining intersections stay (and are reported
        // as the rig's shell self-intersections).
        let budget = Cell::new(RELOCATE_TESTS_PER_ELEMENT * self.triangles.len());
        // The BVH of the current corners, rebuilt only after a vertex actually moved (the
        // same hierarchy as rebuilding it for every vertex, without the repeated builds).
        let mut tris: Vec<[DVec3; 3]> = Vec::new();
        let mut bvh = TriangleBvh::new(&[]);
        let mut stale = true;
        for _ in 0..12 {
            let mut changed = false;
            for &v in stuck {
                if stale {
                    tris = (0..self.triangles.len()).map(|e| self.corners(e)).collect();
                    bvh = TriangleBvh::new(&tris);
                    stale = false;
                }
                let cost = PlacementCost {
                    v,
                    elems: &incident[v],
                    tris: &tris,
                    bvh: &bvh,
                    budget: &budget,
                };
                let candidates =
                    self.relocation_candidates(v, &adjacency[v], anchor, disp, robust_dir);
                if budget.get() == 0 {
                    return;
                }
                let mut best = (cost.of(self, candidates[0]), 0);
                if best.0 == 0 {
                    continue;
                }
                for (i, &c) in candidates.iter().enumerate().skip(1) {
                    let h = cost.of(self, c);
                    if h < best.0 {
                        best = (h, i);
                    }
                }
                if best.1 != 0 {
                    self.vertices[v] = candidates[best.1];
                    changed = true;
                    stale = true;
                }
            }
            if !changed {
                break;
            }
        }
    }

    /// Candidate positions of stuck vertex `v` (neighbours `adjacent`) for
    /// [`Shell::relocate_stuck`], the current position first.
    fn relocation_candidates(
        &self,
        v: usize,
        adjacent: &[u32],
        anchor: &[DVec3],
        disp: &[DVec3],
        robust_dir: &[DVec3],
    ) -> Vec<DVec3> {
        let len = disp[v].length();
        let neighbours: Vec<usize> = adjacent.iter().map(|&u| u as usize).collect();
        let mean_offset = neighbours
            .iter()
            .map(|&u| self.vertices[u] - anchor[u])
            .sum::<DVec3>();
        let mut candidates = vec![self.vertices[v]];
        for dir in [
            disp[v].try_normalize(),
            Some(-robust_dir[v]),
            mean_offset.try_normalize(),
        ]
        .into_iter()
        .flatten()
        {
            for k in 0..11 {
                candidates.push(anchor[v] + dir * len / f64::from(1u32 << k));
            }
        }
        for x in [-1.0, 0.0, 1.0] {
            for y in [-1.0, 0.0, 1.0] {
                for z in [-1.0, 0.0, 1.0] {
                    if let Some(dir) = DVec3::new(x, y, z).try_normalize() {
                        for k in 0..6 {
                            candidates.push(anchor[v] + dir * len / f64::from(1u32 << k));
                        }
                    }
                }
            }
        }
        if !neighbours.is_empty() {
            candidates.push(
                neighbours.iter().map(|&u| self.vertices[u]).sum::<DVec3>()
                    / neighbours.len() as f64,
            );
        }
        candidates
    }
}

/// The cost of a position of stuck vertex `v` in [`Shell::relocate_stuck`]: intersections of its
/// incident elements `elems` with the shell's elements (`tris`, hierarchy `bvh`, as they were
/// when last rebuilt) and with each other.
struct PlacementCost<'a> {
    v: usize,
    elems: &'a [usize],
    tris: &'a [[DVec3; 3]],
    bvh: &'a TriangleBvh,
    /// Element-pair tests left; every evaluation spends its tests from it.
    budget: &'a Cell<usize>,
}

impl PlacementCost<'_> {
    /// Number of intersections with `v` at `p`; `usize::MAX` when an incident element would
    /// be a sliver.
    fn of(&self, shell: &Shell, p: DVec3) -> usize {
        let (v, elems, tris, bvh) = (self.v, self.elems, self.tris, self.bvh);
        let spend = |n: usize| self.budget.set(self.budget.get().saturating_sub(n));
        let corners = |e: usize| {
            shell.triangles[e].map(|i| {
                if i as usize == v {
                    p
                } else {
                    shell.vertices[i as usize]
                }
            })
        };
        let mut hits = 0;
        for (k, &e) in elems.iter().enumerate() {
            let a = corners(e);
            let longest = (0..3)
                .map(|i| a[i].distance_squared(a[(i + 1) % 3]))
                .fold(0.0, f64::max);
            if (a[1] - a[0]).cross(a[2] - a[0]).length() <= 1e-4 * longest {
                return usize::MAX;
            }
            let lo = a[0].min(a[1]).min(a[2]);
            let hi = a[0].max(a[1]).max(a[2]);
            let near = bvh.overlapping(lo, hi);
            spend(near.len() + elems.len());
            for f in near {
                let f = f as usize;
                if elems.contains(&f) {
                    continue;
                }
                if triangles_intersect(shell.triangles[e], &a, shell.triangles[f], &tris[f]) {
                    hits += 1;
                }
            }
            for &f in &elems[k + 1..] {
                if triangles_intersect(shell.triangles[e], &a, shell.triangles[f], &corners(f)) {
                    hits += 1;
                }
            }
        }
        hits
    }
}
