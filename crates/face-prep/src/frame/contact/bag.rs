//! A mouth that opens into a mouth bag: a face with three boundary loops (the contour and two open
//! eyes) whose lips part over a closed pouch (the oral cavity modelled as a sack, as game and
//! avatar heads have it) instead of a hole.
//!
//! The bag is found as a *pit* of the depth field (how far forward a vertex lies), the way a
//! watershed finds basins (Vincent & Soille, "Watersheds in digital spaces", IEEE PAMI 13(6),
//! 1991): the vertices are added from the deepest up, joined to their added neighbours, and the
//! basin that holds the deepest point on the face's centre line below the nose (the back of the
//! bag) grows until it would join a basin that reaches a boundary loop. That level is the
//! bag's lowest rim point, in practice the mouth's corners, where the bag meets the skin. What the
//! basin holds then is the bag: its triangles are taken off the face, which opens a mouth loop at
//! the bag's entrance, and every bag vertex follows the entrance vertex nearest to it (in exports
//! the bag moves with the lip it hangs from). The lips' inner surfaces in front of the corners'
//! depth stay, rolled in, as on the ICT faces.
//!
//! A pit counts as a bag when it is at least [`MIN_BAG_DEPTH_IOD`] deep below its rim and its
//! entrance at least [`super::mouth::MIN_WIDTH_IOD`] wide, and when taking it off leaves a face
//! with four loops; otherwise the mouth is looked for as a closed one ([`super::mouth`]).

use super::Opened;
use super::mouth::{MIN_WIDTH_IOD, SearchFrame};
use crate::topology;
use glam::DVec3;

/// Least depth of a mouth bag below its rim, interocular distances (0.15 iod ≈ 9.5 mm). A mouth
/// bag reaches back 30–60 mm; the folds of a closed mouth (the lips' line, the mentolabial
/// sulcus) are pits of a few millimetres that open sideways.
pub const MIN_BAG_DEPTH_IOD: f64 = 0.15;

/// Union-find over vertex indices, each root knowing whether its set touches a boundary loop.
struct Basins {
    parent: Vec<u32>,
    reaches_boundary: Vec<bool>,
}

impl Basins {
    fn root(&mut self, mut v: u32) -> u32 {
        while self.parent[v as usize] != v {
            let p = self.parent[v as usize];
            self.parent[v as usize] = self.parent[p as usize];
            v = p;
        }
        v
    }

    fn join(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.root(a), self.root(b));
        if ra != rb {
            self.parent[rb as usize] = ra;
            let reaches = self.reaches_boundary[rb as usize];
            self.reaches_boundary[ra as usize] |= reaches;
        }
    }
}

/// The mouth bag of a face with three loops, taken off: `None` when there is no bag (see the
/// module docs).
pub(super) fn cut_mouth_bag(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    loops: &[Vec<u32>],
    frame: &SearchFrame,
) -> Option<Opened> {
    let n = vertices.len();
    let iod = frame.iod;
    let front = frame.across.cross(frame.down);
    let depth = |v: u32| (vertices[v as usize] - frame.eyes_mid).dot(front);
    let across_of = |x: DVec3| (x - frame.eyes_mid).dot(frame.across);
    let below_eyes = |x: DVec3| (x - frame.eyes_mid).dot(frame.down);
    let mut on_loop = vec![false; n];
    for &v in loops.iter().flatten() {
        on_loop[v as usize] = true;
    }
    let (lo, hi) = frame.mouth_window();
    let seed = (0..n as u32)
        .filter(|&v| {
            let p = vertices[v as usize];
            across_of(p).abs() <= super::mouth::SEED_HALF_WIDTH_IOD * iod
                && (lo..=hi).contains(&below_eyes(p))
        })
        .min_by(|&a, &b| depth(a).total_cmp(&depth(b)))?;
    if on_loop[seed as usize] {
        return None;
    }
    let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); n];
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            neighbours[a as usize].push(b);
            neighbours[b as usize].push(a);
        }
    }
    for list in &mut neighbours {
        list.sort_unstable();
        list.dedup();
    }
    let mut basins = Basins {
        parent: (0..n as u32).collect(),
        reaches_boundary: on_loop.clone(),
    };
    let mut order: Vec<u32> = (0..n as u32).collect();
    order.sort_by(|&a, &b| depth(a).total_cmp(&depth(b)));
    let mut added = vec![false; n];
    let mut rim_depth = None;
    for &v in &order {
        // Would adding `v` join the seed's basin to one that reaches a boundary loop?
        if added[seed as usize] {
            let seed_root = basins.root(seed);
            let mut touches_seed = false;
            let mut reaches = basins.reaches_boundary[v as usize];
            for &w in &neighbours[v as usize] {
                if added[w as usize] {
                    let r = basins.root(w);
                    touches_seed |= r == seed_root;
                    reaches |= r != seed_root && basins.reaches_boundary[r as usize];
                }
            }
            if touches_seed && reaches || basins.reaches_boundary[seed_root as usize] {
                rim_depth = Some(depth(v));
                break;
            }
        }
        added[v as usize] = true;
        for &w in &neighbours[v as usize] {
            if added[w as usize] {
                basins.join(v, w);
            }
        }
    }
    let rim_depth = rim_depth?;
    if rim_depth - depth(seed) < MIN_BAG_DEPTH_IOD * iod {
        return None;
    }
    let seed_root = basins.root(seed);
    let mut in_bag: Vec<bool> = (0..n as u32)
        .map(|v| added[v as usize] && basins.root(v) == seed_root)
        .collect();
    take_spikes(&mut in_bag, &neighbours, &on_loop);
    let kept: Vec<[u32; 3]> = triangles
        .iter()
        .filter(|t| !t.iter().any(|&v| in_bag[v as usize]))
        .copied()
        .collect();
    // The face without the bag: four loops, the new one (the entrance) wide enough for a mouth.
    let mut used = vec![false; n];
    for t in &kept {
        for &v in t {
            used[v as usize] = true;
        }
    }
    let compact: Vec<u32> = (0..n).filter(|&v| used[v]).map(|v| v as u32).collect();
    let mut index = vec![u32::MAX; n];
    for (i, &v) in compact.iter().enumerate() {
        index[v as usize] = i as u32;
    }
    let compact_vertices: Vec<DVec3> = compact.iter().map(|&v| vertices[v as usize]).collect();
    let compact_triangles: Vec<[u32; 3]> =
        kept.iter().map(|t| t.map(|v| index[v as usize])).collect();
    let new_loops = topology::validate(&compact_vertices, &compact_triangles).ok()?;
    if new_loops.len() != 4 {
        return None;
    }
    let entrance: Vec<u32> = new_loops
        .iter()
        .find(|lp| lp.iter().all(|&v| !on_loop[compact[v as usize] as usize]))?
        .iter()
        .map(|&v| compact[v as usize])
        .collect();
    let (lo_x, hi_x) = entrance
        .iter()
        .map(|&v| across_of(vertices[v as usize]))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
    if hi_x - lo_x < MIN_WIDTH_IOD * iod {
        return None;
    }
    let followers = follow_the_entrance(vertices, &neighbours, &used, &entrance);
    Some(Opened {
        vertices: vertices.to_vec(),
        triangles: kept,
        lips: None,
        lids: Vec::new(),
        followers,
    })
}

/// Takes into the bag every vertex the face would hold by two edges or fewer: a vertex level
/// with the bag's rim that the basin left standing, which would hang into the opening as a spike
/// (a vertex on the cut's edge otherwise has its two neighbours along the edge and one into the
/// face at least). Vertices of the face's own loops stay.
fn take_spikes(in_bag: &mut [bool], neighbours: &[Vec<u32>], on_loop: &[bool]) {
    let held = |v: usize, in_bag: &[bool]| {
        neighbours[v]
            .iter()
            .filter(|&&w| !in_bag[w as usize])
            .count()
    };
    let mut queue: Vec<u32> = (0..in_bag.len() as u32)
        .filter(|&v| in_bag[v as usize])
        .flat_map(|v| neighbours[v as usize].iter().copied())
        .collect();
    while let Some(v) = queue.pop() {
        let v = v as usize;
        if in_bag[v] || on_loop[v] || held(v, in_bag) > 2 {
            continue;
        }
        in_bag[v] = true;
        queue.extend(neighbours[v].iter().copied());
    }
}

/// Each vertex no kept triangle uses, with the entrance vertex it follows: the nearest along
/// the bag's surface (edge-path length, Dijkstra from every entrance vertex at once), so the
/// bag's floor follows the lower lip and its roof the upper, however flat the mouth.
fn follow_the_entrance(
    vertices: &[DVec3],
    neighbours: &[Vec<u32>],
    used: &[bool],
    entrance: &[u32],
) -> Vec<(u32, u32)> {
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;
    let n = vertices.len();
    let mut best: Vec<(f64, u32)> = vec![(f64::INFINITY, u32::MAX); n];
    // Distances as ordered bits: non-negative finite f64s order as their bit patterns.
    let mut heap: BinaryHeap<Reverse<(u64, u32)>> = BinaryHeap::new();
    for &v in entrance {
        best[v as usize] = (0.0, v);
        heap.push(Reverse((0, v)));
    }
    while let Some(Reverse((bits, v))) = heap.pop() {
        let (d, anchor) = best[v as usize];
        if bits != d.to_bits() {
            continue;
        }
        for &w in &neighbours[v as usize] {
            if used[w as usize] {
                continue;
            }
            let dw = d + vertices[v as usize].distance(vertices[w as usize]);
            if dw < best[w as usize].0 {
                best[w as usize] = (dw, anchor);
                heap.push(Reverse((dw.to_bits(), w)));
            }
        }
    }
    (0..n as u32)
        .filter(|&v| !used[v as usize])
        .map(|v| {
            let anchor = best[v as usize].1;
            (
                v,
                if anchor == u32::MAX {
                    entrance[0]
                } else {
                    anchor
                },
            )
        })
        .collect()
}
