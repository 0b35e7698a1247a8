//! Editing muscles: where a picked element goes in a muscle's ordered chain.

use glam::DVec3;

/// Inserts `element` into an ordered chain where it lengthens the chain's path the least
/// (between two consecutive elements, or at either end); no-op if already present.
///
/// ```
/// use glam::DVec3;
/// let mut chain = vec![0, 2];
/// let pos = |e: u32| Some(DVec3::new(e as f64, 0.0, 0.0));
/// viewer::muscle_edit::insert_into_chain(&mut chain, 1, pos);
/// viewer::muscle_edit::insert_into_chain(&mut chain, 3, pos);
/// assert_eq!(chain, vec![0, 1, 2, 3]);
/// ```
pub fn insert_into_chain(
    chain: &mut Vec<u32>,
    element: u32,
    centroid: impl Fn(u32) -> Option<DVec3>,
) {
    if chain.contains(&element) {
        return;
    }
    let Some(p) = centroid(element) else { return };
    let c: Vec<Option<DVec3>> = chain.iter().map(|&e| centroid(e)).collect();
    let dist = |a: Option<DVec3>, b: DVec3| a.map_or(f64::INFINITY, |a| a.distance(b));
    let mut best = (
        chain.len(),
        c.last().copied().flatten().map_or(0.0, |l| l.distance(p)),
    );
    if let Some(first) = c.first() {
        let cost = dist(*first, p);
        if cost < best.1 {
            best = (0, cost);
        }
    }
    for i in 1..c.len() {
        if let (Some(a), Some(b)) = (c[i - 1], c[i]) {
            let cost = a.distance(p) + p.distance(b) - a.distance(b);
            if cost < best.1 {
                best = (i, cost);
            }
        }
    }
    chain.insert(best.0, element);
}
