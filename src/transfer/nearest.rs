//! Nearest-point queries over a fixed set of points: a static k-d tree (median splits, the
//! points stored in place), so that carrying a rig to a head of a million vertices is not a
//! million brute-force scans of its skin, whatever the parts' layout (a query far from every
//! point costs a root-to-leaf descent, not a sweep of empty space).

use glam::DVec3;

/// A set of points, each with an id, for nearest-point queries.
#[derive(Clone, Debug)]
pub struct PointTree {
    /// The points in k-d order: the median of each range splits it on axis `depth % 3`.
    points: Vec<(DVec3, u32)>,
}

impl PointTree {
    /// The tree of `points` (id, position); non-finite positions are left out.
    ///
    /// ```
    /// use facebem::transfer::nearest::PointTree;
    /// use glam::DVec3;
    /// let tree = PointTree::new([(7, DVec3::ZERO), (9, DVec3::X * 10.0)]);
    /// assert_eq!(tree.nearest(DVec3::new(8.0, 1.0, 0.0)).map(|n| n.0), Some(9));
    /// assert!(PointTree::new([]).nearest(DVec3::ZERO).is_none());
    /// ```
    pub fn new(points: impl IntoIterator<Item = (u32, DVec3)>) -> PointTree {
        let mut points: Vec<(DVec3, u32)> = points
            .into_iter()
            .filter(|p| p.1.is_finite())
            .map(|(id, p)| (p, id))
            .collect();
        split(&mut points, 0);
        PointTree { points }
    }

    /// The id of the point nearest `p` and its distance (`None` without points).
    pub fn nearest(&self, p: DVec3) -> Option<(u32, f64)> {
        if self.points.is_empty() || !p.is_finite() {
            return None;
        }
        let mut best = (u32::MAX, f64::INFINITY);
        search(&self.points, 0, p, &mut best);
        Some((best.0, best.1.sqrt()))
    }
}

/// Orders `points` so that each range's median splits it on axis `depth % 3`.
fn split(points: &mut [(DVec3, u32)], depth: usize) {
    if points.len() <= 1 {
        return;
    }
    let axis = depth % 3;
    let mid = points.len() / 2;
    points.select_nth_unstable_by(mid, |a, b| a.0[axis].total_cmp(&b.0[axis]));
    let (left, right) = points.split_at_mut(mid);
    split(left, depth + 1);
    split(&mut right[1..], depth + 1);
}

/// Updates `best` (id, squared distance) with the points of `points` nearer `p`.
fn search(points: &[(DVec3, u32)], depth: usize, p: DVec3, best: &mut (u32, f64)) {
    if points.is_empty() {
        return;
    }
    let mid = points.len() / 2;
    let (q, id) = points[mid];
    let d2 = q.distance_squared(p);
    if d2 < best.1 {
        *best = (id, d2);
    }
    let axis = depth % 3;
    let gap = p[axis] - q[axis];
    let (near, far) = if gap < 0.0 {
        (&points[..mid], &points[mid + 1..])
    } else {
        (&points[mid + 1..], &points[..mid])
    };
    search(near, depth + 1, p, best);
    if gap * gap < best.1 {
        search(far, depth + 1, p, best);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tree finds what a brute-force scan finds, for queries inside and far outside.
    #[test]
    fn the_tree_agrees_with_a_scan() {
        let points: Vec<(u32, DVec3)> = (0..2000u32)
            .map(|i| {
                let t = i as f64;
                (
                    i,
                    DVec3::new((t * 0.37).sin() * 5.0, (t * 0.11).cos() * 3.0, t * 0.001),
                )
            })
            .collect();
        let tree = PointTree::new(points.clone());
        for k in 0..300 {
            let t = k as f64;
            let q = DVec3::new((t * 1.3).sin() * 8.0, (t * 0.7).cos() * 8.0, t * 0.05 - 4.0)
                * if k % 10 == 0 { 100.0 } else { 1.0 };
            let scan = points
                .iter()
                .map(|&(id, p)| (id, p.distance(q)))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap();
            let found = tree.nearest(q).unwrap();
            assert!(
                (found.1 - scan.1).abs() < 1e-12,
                "query {k}: {found:?} against {scan:?}"
            );
        }
    }
}
