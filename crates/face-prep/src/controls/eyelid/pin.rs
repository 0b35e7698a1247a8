//! Exact lid closure on the displayed mesh: a blink's upper-margin vertices pinned onto their
//! lower-margin points, the correction spread harmonically over the upper lid.

use glam::DVec3;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::EyeMargins;

/// Makes the pose `positions + slider × field` close the lids exactly: every upper-margin vertex
/// of each of `margins` (not a corner, not on any lower margin) lands on the lower-margin point
/// of the same chord parameter ([`EyeMargins`]), where the lower margin itself lands in that pose. The
/// corners (canthi) stay where they are, held by the canthal tendons; the lower margins are
/// held. The change this makes to each pinned vertex's field is spread over
/// the lid as a harmonic function ([`pin_and_spread`]).
///
/// Several margin sets may be given for one eye; a vertex on an upper margin of several takes
/// the first. The field is linear in the slider, so any slider value between 0 and `slider`
/// moves the upper margin that fraction of the way: the lids never cross. `slider` must not
/// be 0.
///
/// ```
/// use face_prep::Side;
/// use face_prep::eyelid::{EyeMargins, pin::close_margins};
/// use glam::DVec3;
/// // A diamond eye: corners 0 and 2, upper vertex 1, lower vertex 3, plus a lid vertex 4
/// // above it; triangles around the hole.
/// let p = vec![
///     DVec3::new(0.0, 0.0, 0.0),
///     DVec3::new(1.0, 0.5, 0.0),
///     DVec3::new(2.0, 0.0, 0.0),
///     DVec3::new(1.0, -0.5, 0.0),
///     DVec3::new(1.0, 1.5, 0.0),
/// ];
/// let tris = [[0, 1, 4], [1, 2, 4]];
/// let m = EyeMargins::of_loop(&p, &[0, 1, 2, 3], Side::Left).unwrap();
/// let mut field = vec![DVec3::ZERO; 5];
/// close_margins(&p, &tris, &[m], &mut field, -1.0, 3.0);
/// assert!((p[1] - field[1] - p[3]).length() < 1e-12); // closed at slider -1
/// assert!(field[4].y > 0.0 && field[4].y < field[1].y); // the lid above follows, less
/// ```
pub fn close_margins(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    margins: &[EyeMargins],
    field: &mut [DVec3],
    slider: f64,
    radius: f64,
) {
    let n = positions.len().min(field.len());
    if slider == 0.0
        || margins
            .iter()
            .any(|m| m.upper.iter().chain(&m.lower).any(|&v| v as usize >= n))
    {
        return;
    }
    // The corners stay (the canthal tendons hold them to the bone).
    let corners: Vec<u32> = margins.iter().flat_map(|m| [m.medial, m.lateral]).collect();
    let mut base = field.to_vec();
    let mut pins: Vec<(u32, DVec3)> = Vec::new();
    for &c in &corners {
        base[c as usize] = DVec3::ZERO;
        pins.push((c, DVec3::ZERO));
    }
    let held: Vec<u32> = margins
        .iter()
        .flat_map(|m| m.lower.iter().copied())
        .filter(|v| !corners.contains(v))
        .collect();
    for m in margins {
        for (&v, &t) in m.upper.iter().zip(&m.upper_t) {
            if held.contains(&v) || pins.iter().any(|p| p.0 == v) {
                continue;
            }
            let target = m.lower_at(positions, t) + slider * m.lower_field_at(&base, t);
            pins.push((v, (target - positions[v as usize]) / slider));
        }
    }
    pin_and_spread(positions, triangles, field, &pins, &held, radius);
}

/// Closes rolled-in lids: `visible` are the margins of the visible lid edge (the simulated
/// surface's eye loop), `inner` those of the rolled-in lining's inner edge (the displayed eye
/// loop, behind the lids). The visible upper margin lands on the visible lower one
/// ([`close_margins`]: the closure line), and both inner edges meet behind that line: each
/// inner lower-edge vertex lands behind the closure line's point in front of it (along `back`,
/// a unit vector into the head) by its distance from that point, and the inner upper edge lands
/// on the inner lower edge. So each lining folds back from the closed margin toward the
/// eye, as a closed eye's conjunctival linings lie against each other, instead of the upper
/// lining being turned over onto the lower one.
#[allow(clippy::too_many_arguments)]
pub fn close_rolled_margins(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    visible: &EyeMargins,
    inner: &EyeMargins,
    back: DVec3,
    field: &mut [DVec3],
    slider: f64,
    radius: f64,
) {
    let n = positions.len().min(field.len());
    if slider == 0.0
        || [&visible.upper, &visible.lower, &inner.upper, &inner.lower]
            .iter()
            .any(|a| a.iter().any(|&v| v as usize >= n))
    {
        return;
    }
    // The corners of both loops stay (the canthal tendons hold them to the bone).
    let corners = [inner.medial, inner.lateral, visible.medial, visible.lateral];
    let mut base = field.to_vec();
    let mut pins: Vec<(u32, DVec3)> = Vec::new();
    for c in corners {
        base[c as usize] = DVec3::ZERO;
        if !pins.iter().any(|p| p.0 == c) {
            pins.push((c, DVec3::ZERO));
        }
    }
    let closure =
        |t: f64| visible.lower_at(positions, t) + slider * visible.lower_field_at(&base, t);
    // The inner lower edge first: each vertex goes behind the closure line's point in front of
    // it (the nearest point of the visible lower margin seen along `back`), as far as it lies
    // from that point now; then the inner upper edge onto where the lower one lands
    // (interpolated as the margins are measured); then the visible upper margin onto the
    // visible lower one, which is held.
    let mut lowered = base.clone();
    for &v in &inner.lower {
        if visible.lower.contains(&v) || pins.iter().any(|p| p.0 == v) {
            continue;
        }
        let q = positions[v as usize];
        let (tv, _) = visible.closest_on_lower(positions, q, back);
        let depth = visible.lower_at(positions, tv).distance(q);
        let value = (closure(tv) + back * depth - q) / slider;
        lowered[v as usize] = value;
        pins.push((v, value));
    }
    for (&v, &t) in inner.upper.iter().zip(&inner.upper_t) {
        if inner.lower.contains(&v) || pins.iter().any(|p| p.0 == v) {
            continue;
        }
        let target = inner.lower_at(positions, t) + slider * inner.lower_field_at(&lowered, t);
        pins.push((v, (target - positions[v as usize]) / slider));
    }
    for (&v, &t) in visible.upper.iter().zip(&visible.upper_t) {
        if visible.lower.contains(&v) || pins.iter().any(|p| p.0 == v) {
            continue;
        }
        pins.push((v, (closure(t) - positions[v as usize]) / slider));
    }
    // Held: the visible lower margin and the rest of the inner lower edge (every lower-edge
    // vertex the inner upper edge was matched against keeps its value).
    let held: Vec<u32> = visible
        .lower
        .iter()
        .chain(&inner.lower)
        .copied()
        .filter(|v| !pins.iter().any(|p| p.0 == *v))
        .collect();
    pin_and_spread(positions, triangles, field, &pins, &held, radius);
}

/// Sets `field` at each pinned vertex to its value and spreads the change over the mesh
/// around them as a harmonic function (each free vertex the mean of its neighbours over the
/// mesh's edges, solved exactly by [`crate::harmonic::extend`]) that is zero at the `held`
/// vertices and at `radius` (mesh units, measured along the edges from the pinned vertices)
/// and beyond: the skin next to a pinned margin follows it without a step.
pub fn pin_and_spread(
    positions: &[DVec3],
    triangles: &[[u32; 3]],
    field: &mut [DVec3],
    pins: &[(u32, DVec3)],
    held: &[u32],
    radius: f64,
) {
    let n = positions.len().min(field.len());
    if n == 0 || pins.is_empty() {
        return;
    }
    let mut fixed = vec![false; n];
    let mut correction = vec![DVec3::ZERO; n];
    for &v in held {
        if let Some(f) = fixed.get_mut(v as usize) {
            *f = true;
        }
    }
    let mut is_pin = vec![false; n];
    for &(v, value) in pins {
        let vi = v as usize;
        if vi < n && !fixed[vi] {
            is_pin[vi] = true;
            fixed[vi] = true;
            correction[vi] = value - field[vi];
        }
    }
    let neighbours = adjacency(n, triangles);
    let from_pins = edge_distances(positions, &neighbours, is_pin.iter().copied());
    let is_free: Vec<bool> = (0..n).map(|v| !fixed[v] && from_pins[v] < radius).collect();
    let free: Vec<usize> = (0..n).filter(|&v| is_free[v]).collect();
    // The edges come from the triangles (in range by construction), so the solve cannot fail
    // on them; a failed factorisation leaves the free vertices uncorrected.
    let _ = crate::harmonic::extend(
        &crate::harmonic::unit_edges(n, triangles),
        &is_free,
        &mut correction,
    );
    for v in 0..n {
        if is_pin[v] {
            field[v] += correction[v];
        }
    }
    for &v in &free {
        field[v] += correction[v];
    }
}

/// Vertex neighbours over the triangles' edges (each listed once).
fn adjacency(n: usize, triangles: &[[u32; 3]]) -> Vec<Vec<u32>> {
    let mut nb: Vec<Vec<u32>> = vec![Vec::new(); n];
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            if a < n && b < n {
                if !nb[a].contains(&(b as u32)) {
                    nb[a].push(b as u32);
                }
                if !nb[b].contains(&(a as u32)) {
                    nb[b].push(a as u32);
                }
            }
        }
    }
    nb
}

/// Shortest distance along the edges from the source vertices (Dijkstra); infinity where no
/// source is reachable.
fn edge_distances(
    positions: &[DVec3],
    neighbours: &[Vec<u32>],
    sources: impl Iterator<Item = bool>,
) -> Vec<f64> {
    #[derive(PartialEq)]
    struct Item(f64, usize);
    impl Eq for Item {}
    impl PartialOrd for Item {
        fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
            Some(self.cmp(other))
        }
    }
    impl Ord for Item {
        fn cmp(&self, other: &Self) -> Ordering {
            other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
        }
    }
    let n = neighbours.len();
    let mut dist = vec![f64::INFINITY; n];
    let mut heap = BinaryHeap::new();
    for (v, s) in sources.enumerate().take(n) {
        if s {
            dist[v] = 0.0;
            heap.push(Item(0.0, v));
        }
    }
    while let Some(Item(d, v)) = heap.pop() {
        if d > dist[v] {
            continue;
        }
        for &u in &neighbours[v] {
            let u = u as usize;
            let nd = d + positions[v].distance(positions[u]);
            if nd < dist[u] {
                dist[u] = nd;
                heap.push(Item(nd, u));
            }
        }
    }
    dist
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::controls::ids::Side;

    /// A grid face 0..12 × 0..12 (unit spacing) with a lens-shaped eye hole made by pulling the
    /// grid's row y = 6 apart between x = 3 and x = 9: vertices of that row are doubled, the
    /// upper copies moved up, the lower copies down.
    fn face_with_eye() -> (Vec<DVec3>, Vec<[u32; 3]>, Vec<u32>) {
        let n = 13usize;
        let mut p: Vec<DVec3> = (0..n * n)
            .map(|i| DVec3::new((i % n) as f64, (i / n) as f64, 0.0))
            .collect();
        let idx = |x: usize, y: usize| (y * n + x) as u32;
        // Lower copies of the row's interior hole vertices x = 4..=8.
        let mut lower_of = std::collections::HashMap::new();
        for x in 4..=8 {
            let h = 0.8 * (1.0 - ((x as f64 - 6.0) / 3.0).powi(2));
            p[idx(x, 6) as usize].y += h / 2.0;
            let mut q = p[idx(x, 6) as usize];
            q.y -= h;
            lower_of.insert(x, p.len() as u32);
            p.push(q);
        }
        let mut tris = vec![];
        for y in 0..n - 1 {
            for x in 0..n - 1 {
                let mut v = [idx(x, y), idx(x + 1, y), idx(x + 1, y + 1), idx(x, y + 1)];
                // The row below y = 6 uses the lower copies on its top edge.
                if y == 5 {
                    for (k, xx) in [(2, x + 1), (3, x)] {
                        if let Some(&l) = lower_of.get(&xx) {
                            v[k] = l;
                        }
                    }
                }
                tris.push([v[0], v[1], v[2]]);
                tris.push([v[0], v[2], v[3]]);
            }
        }
        let mut lp: Vec<u32> = (3..=9).map(|x| idx(x, 6)).collect();
        lp.extend((4..=8).rev().map(|x| lower_of[&x]));
        (p, tris, lp)
    }

    /// The spread is converged, not a count of sweeps: on a 61 × 61 grid with one vertex
    /// pinned in the middle and a reach of 30 edges, every free vertex ends at the mean of its
    /// neighbours (to 1e-9 of the pin). The 400 Gauss–Seidel sweeps it replaced left errors of
    /// 1.7e-6 there.
    #[test]
    fn the_spread_is_the_converged_harmonic_field() {
        let n = 61u32;
        let p: Vec<DVec3> = (0..n * n)
            .map(|i| DVec3::new((i % n) as f64, (i / n) as f64, 0.0))
            .collect();
        let id = |x: u32, y: u32| y * n + x;
        let mut tris = Vec::new();
        for y in 0..n - 1 {
            for x in 0..n - 1 {
                tris.push([id(x, y), id(x + 1, y), id(x + 1, y + 1)]);
                tris.push([id(x, y), id(x + 1, y + 1), id(x, y + 1)]);
            }
        }
        let mut field = vec![DVec3::ZERO; p.len()];
        let centre = id(30, 30);
        pin_and_spread(&p, &tris, &mut field, &[(centre, DVec3::Z)], &[], 30.0);
        assert_eq!(field[centre as usize], DVec3::Z);
        let neighbours = adjacency(p.len(), &tris);
        let from_pin = edge_distances(&p, &neighbours, (0..p.len()).map(|v| v == centre as usize));
        let mut checked = 0;
        for v in 0..p.len() {
            if v == centre as usize || from_pin[v] >= 30.0 {
                continue;
            }
            let nb = &neighbours[v];
            let mean = nb.iter().map(|&u| field[u as usize]).sum::<DVec3>() / nb.len() as f64;
            assert!(
                (field[v] - mean).length() < 1e-9,
                "vertex {v}: {} against {mean}",
                field[v]
            );
            checked += 1;
        }
        assert!(checked > 1000, "{checked} free vertices");
        // The spread reaches far: 20 edges out it still moves.
        assert!(field[id(50, 30) as usize].z > 1e-3);
    }

    #[test]
    fn the_grid_eye_is_a_hole_with_two_margins() {
        let (p, tris, lp) = face_with_eye();
        let loops = crate::frame::topology::validate(&p, &tris).unwrap();
        assert_eq!(loops.len(), 2);
        let m = EyeMargins::of_loop(&p, &lp, Side::Left).unwrap();
        assert_eq!(m.upper.len(), 7);
        assert!((m.opening_height(&p) - 0.8).abs() < 1e-12);
    }

    #[test]
    fn pinned_margins_close_exactly_and_the_lid_follows_smoothly() {
        let (p, tris, lp) = face_with_eye();
        let m = EyeMargins::of_loop(&p, &lp, Side::Left).unwrap();
        // A field that moves the lower lid sideways and the upper lid down by half the opening.
        let mut field: Vec<DVec3> = p
            .iter()
            .map(|q| {
                if q.y < 6.0 {
                    DVec3::new(0.1, 0.0, 0.0)
                } else {
                    DVec3::new(0.0, 0.2, 0.0)
                }
            })
            .collect();
        let before = field.clone();
        close_margins(&p, &tris, std::slice::from_ref(&m), &mut field, -1.0, 4.0);
        let posed: Vec<DVec3> = p.iter().zip(&field).map(|(q, d)| *q - *d).collect();
        for g in m.gaps(&posed) {
            assert!(g.abs() < 1e-12, "gap {g}");
        }
        // Corners held still, the lower lid untouched; far vertices untouched; above the
        // margin, in between.
        assert_eq!(field[m.medial as usize], DVec3::ZERO);
        assert_eq!(field[m.lateral as usize], DVec3::ZERO);
        for &v in &m.lower[1..m.lower.len() - 1] {
            assert_eq!(field[v as usize], before[v as usize]);
        }
        assert_eq!(field[12 * 13 + 6], before[12 * 13 + 6]);
        let mid_up = 6 * 13 + 6;
        let above = 7 * 13 + 6;
        let step = |v: usize| (field[v] - before[v]).length();
        assert!(step(above) > 0.0 && step(above) < step(mid_up));
        // Half the slider: half the closure, the upper margin still above the lower.
        let half: Vec<DVec3> = p.iter().zip(&field).map(|(q, d)| *q - 0.5 * *d).collect();
        assert!(m.gaps(&half).iter().all(|&g| g >= -1e-12));
    }
}
