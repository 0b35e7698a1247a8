//! Local relaxation of the few triangles a response would turn over.
//!
//! The responses are linear, so a surface patch that a muscle tilts a long way (the lower lip's
//! top surface at the mouth corner, almost horizontal at rest, when the corner rises 10 mm
//! above a lip that stays) cannot rotate: a vertex that lags behind its neighbours is overtaken
//! and the triangle between them turns over (MediaPipe's zygomaticus: 5 of 852 triangles, all
//! within 3 mm of the lips). [`relax_inversions`] finds the triangles a control's full
//! contraction (slider −1) turns over and moves, per turned triangle, the one free vertex that deviates
//! most from the mean of its neighbours to that mean, round after round, until none is turned
//! or [`MAX_ROUNDS`] have passed. The pipeline relaxes only the lips (within [`LIPS_MM`] of
//! the mouth loop) and keeps landmarks and margins that other passes or the user rely on exactly
//! as solved: the outer contour (on the fixed rim), the eye loops (closed exactly by
//! the pipeline's lid closure) and the mouth corners.
//!
//! Where a field is already smooth and a thin fold still turns over (the upper lip's
//! underside at a mouth corner when the jaw moves forward), a second stage evens out the
//! turned triangles one at a time, keeping each change only if it turns fewer triangles
//! around it over; a third smooths what is still turned over a patch [`PATCH_MM`] around it
//! (ICT 13k's jawForward: 81 turned triangles → 38). After the lid closure the pipeline runs
//! all three once more at the lids (within
//! [`LIDS_MM`] of the eye loops), and, on a face simulated on a reduced copy, on the vertices
//! the copy does not hold at the lips: their motion is interpolated from the copy, whose
//! coarser triangles fold differently from the input's at a commissure, and relaxing them
//! changes no simulated value (ICT 13k's blinks: 42 / 43 turned triangles → 25 / 25; ICT
//! 2500's 10 / 9 → 5 / 3). [`relax_sum`] relaxes two controls that one named expression
//! contracts together as their sum (the sphincter's halves in `mouthPucker`).

use glam::DVec3;

/// Most relaxation rounds per response.
pub const MAX_ROUNDS: usize = 12;

/// Distance from the mouth loop, mm, within which the pipeline relaxes turned-over triangles:
/// the lips and the folds beside them, where thin tissue turns further than a linear response
/// can follow (issue 10 allows folds there). Elsewhere a turned triangle is left as a defect
/// to be seen.
pub const LIPS_MM: f64 = 12.0;

/// Distance from an eye loop, mm, within which the pipeline relaxes turned-over triangles after
/// the lid closure: the lids and the folds at the canthi (issue 11 allows folds there), below
/// the brows, whose landmarks the frontalis is measured at.
pub const LIDS_MM: f64 = 8.0;

/// Triangles that `field` turns over at full contraction (slider −1, so `neutral − field`):
/// their normal reverses.
///
/// ```
/// use glam::DVec3;
/// let v = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// // Contraction moves the apex by −field: down by 2, through the base.
/// let f = [DVec3::ZERO, DVec3::ZERO, DVec3::new(0.0, 2.0, 0.0)];
/// assert_eq!(facebem::settle::untangle::turned_over(&v, &[[0, 1, 2]], &f), vec![0]);
/// assert!(facebem::settle::untangle::turned_over(&v, &[[0, 1, 2]], &[DVec3::X; 3]).is_empty());
/// ```
pub fn turned_over(neutral: &[DVec3], triangles: &[[u32; 3]], field: &[DVec3]) -> Vec<usize> {
    triangles
        .iter()
        .enumerate()
        .filter(|(_, t)| t.iter().all(|&i| (i as usize) < neutral.len()))
        .filter(|(_, t)| is_turned(neutral, t, field))
        .map(|(i, _)| i)
        .collect()
}

/// Whether `field` turns triangle `t` (its corners in range of `neutral`) over at full
/// contraction; a corner outside `field` does not move.
fn is_turned(neutral: &[DVec3], t: &[u32; 3], field: &[DVec3]) -> bool {
    let normal = |s: f64| {
        let [a, b, c] = t.map(|i| {
            let i = i as usize;
            neutral[i] + s * field.get(i).copied().unwrap_or(DVec3::ZERO)
        });
        (b - a).cross(c - a)
    };
    normal(0.0).dot(normal(-1.0)) <= 0.0
}

/// The triangles at each of the first `n` vertices (triangles with a corner out of range are
/// left out).
fn incidence(n: usize, triangles: &[[u32; 3]]) -> Vec<Vec<usize>> {
    let mut incident: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (t, tri) in triangles.iter().enumerate() {
        if tri.iter().all(|&v| (v as usize) < n) {
            for &v in tri {
                incident[v as usize].push(t);
            }
        }
    }
    incident
}

/// Relaxes `field` (a control's displacement at slider 1 on `neutral`) where it turns triangles
/// over, moving only vertices not flagged in `fixed`: first toward the mean of their
/// neighbours, then, for what a smooth field still turns over, by evening out each turned
/// triangle (see the module docs). Returns how many vertices moved.
///
/// ```
/// use glam::DVec3;
/// // A fan of four triangles around vertex 4; contraction moves the centre past its rim.
/// let v = [DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, -1.0, 0.0), DVec3::new(1.0, 1.0, 0.0),
///          DVec3::new(-1.0, 1.0, 0.0), DVec3::ZERO];
/// let t = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
/// let mut f = vec![DVec3::ZERO; 5];
/// f[4] = DVec3::new(-3.0, 0.0, 0.0);
/// let fixed = [true, true, true, true, false];
/// assert_eq!(facebem::settle::untangle::turned_over(&v, &t, &f), vec![1]);
/// assert_eq!(facebem::settle::untangle::relax_inversions(&v, &t, &mut f, &fixed, 0.0), 1);
/// assert!(facebem::settle::untangle::turned_over(&v, &t, &f).is_empty());
/// assert_eq!(f[4], DVec3::ZERO);
/// ```
pub fn relax_inversions(
    neutral: &[DVec3],
    triangles: &[[u32; 3]],
    field: &mut [DVec3],
    fixed: &[bool],
    patch_radius: f64,
) -> usize {
    let n = neutral.len().min(field.len());
    // Most responses turn nothing over: no adjacency to build for them.
    if turned_over(neutral, triangles, field).is_empty() {
        return 0;
    }
    let in_range: Vec<[u32; 3]> = triangles
        .iter()
        .copied()
        .filter(|t| t.iter().all(|&i| (i as usize) < n))
        .collect();
    let neighbours = face_prep::shell::vertex_adjacency(n, &in_range);
    let is_fixed = |v: usize| fixed.get(v).copied().unwrap_or(false);
    let mut moved = vec![false; n];
    for _ in 0..MAX_ROUNDS {
        let turned = turned_over(neutral, triangles, field);
        if turned.is_empty() {
            break;
        }
        let mean = |v: usize, field: &[DVec3]| {
            let nb = &neighbours[v];
            nb.iter().map(|&w| field[w as usize]).sum::<DVec3>() / nb.len().max(1) as f64
        };
        let mut pick: Vec<usize> = turned
            .iter()
            .filter_map(|&t| {
                triangles[t]
                    .iter()
                    .map(|&v| v as usize)
                    .filter(|&v| !is_fixed(v) && !neighbours[v].is_empty())
                    .max_by(|&a, &b| {
                        let dev = |v: usize| (field[v] - mean(v, field)).length();
                        dev(a).total_cmp(&dev(b)).then(b.cmp(&a))
                    })
            })
            .collect();
        pick.sort_unstable();
        pick.dedup();
        if pick.is_empty() {
            break;
        }
        let relaxed: Vec<(usize, DVec3)> = pick.iter().map(|&v| (v, mean(v, field))).collect();
        for (v, d) in relaxed {
            field[v] = d;
            moved[v] = true;
        }
    }
    flatten_turned(neutral, triangles, field, &is_fixed, &mut moved);
    smooth_patches(
        neutral,
        triangles,
        field,
        &neighbours,
        &is_fixed,
        patch_radius,
        &mut moved,
    );
    moved.iter().filter(|&&m| m).count()
}

/// Relaxes the sum of two controls' fields that a named expression uses together at full
/// weight (the two halves of the mouth's sphincter in `mouthPucker`): each is relaxed on its
/// own, yet their sum can turn triangles over that neither turns alone. The sum is relaxed
/// like one field and each of the two takes half of the change; kept only if neither field alone then turns more triangles over than
/// before. Returns whether it was kept.
///
/// ```
/// use glam::DVec3;
/// // Two halves of a centre vertex's motion: each alone stays inside the fan, their sum
/// // (−3 along x) carries it past the rim.
/// let v = [DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, -1.0, 0.0), DVec3::new(1.0, 1.0, 0.0),
///          DVec3::new(-1.0, 1.0, 0.0), DVec3::ZERO];
/// let t = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
/// let mut a = vec![DVec3::ZERO; 5];
/// a[4] = DVec3::new(-0.9, 0.0, 0.0);
/// let mut b = a.clone();
/// let fixed = [true, true, true, true, false];
/// let sum = |a: &[DVec3], b: &[DVec3]| a.iter().zip(b).map(|(x, y)| *x + *y).collect::<Vec<_>>();
/// assert_eq!(facebem::settle::untangle::turned_over(&v, &t, &sum(&a, &b)), vec![1]);
/// assert!(facebem::settle::untangle::relax_sum(&v, &t, &mut a, &mut b, &fixed, 0.0));
/// assert!(facebem::settle::untangle::turned_over(&v, &t, &sum(&a, &b)).is_empty());
/// ```
pub fn relax_sum(
    neutral: &[DVec3],
    triangles: &[[u32; 3]],
    a: &mut [DVec3],
    b: &mut [DVec3],
    fixed: &[bool],
    patch_radius: f64,
) -> bool {
    let n = a.len().min(b.len());
    let mut sum: Vec<DVec3> = a.iter().zip(b.iter()).map(|(x, y)| *x + *y).collect();
    let before = sum.clone();
    if relax_inversions(neutral, triangles, &mut sum, fixed, patch_radius) == 0 {
        return false;
    }
    let (turned_a, turned_b) = (
        turned_over(neutral, triangles, a).len(),
        turned_over(neutral, triangles, b).len(),
    );
    // Half of the change to each: a share in proportion to each field's motion, or all of it
    // to the field that moves more, turns the lower lip's half over where the upper's sum
    // does not (ICT 2500's sphincter: 5 → 7 or 8 turned triangles; halved: 5).
    let new_a: Vec<DVec3> = (0..n).map(|v| a[v] + 0.5 * (sum[v] - before[v])).collect();
    let new_b: Vec<DVec3> = (0..n).map(|v| b[v] + 0.5 * (sum[v] - before[v])).collect();
    if turned_over(neutral, triangles, &new_a).len() > turned_a
        || turned_over(neutral, triangles, &new_b).len() > turned_b
    {
        return false;
    }
    a.copy_from_slice(&new_a);
    b.copy_from_slice(&new_b);
    true
}

/// Relaxes `field` in the combination a named expression makes of it: `field + Σ wᵢ·otherᵢ`
/// (each `(otherᵢ, wᵢ)` another control's field and its slider relative to `field`'s) is
/// relaxed like one field, and `field` alone takes the whole change (the others stay as they
/// are: they serve other expressions); `field` alone is then relaxed once more
/// ([`relax_inversions`]). Kept only if `field` alone then turns no more triangles over than
/// before and the combination fewer. Returns whether it was kept.
///
/// A brow lowerer needs this: `browDownLeft` is the corrugator with the frontalis relaxed by
/// half, and the relaxed frontalis pushes the brow down onto the skin the corrugator gathers
/// (ICT 13k: 28 turned triangles, 6 of them 12–17 mm from the eye; relaxed the corrugator
/// alone, 25).
///
/// ```
/// use glam::DVec3;
/// // The centre vertex: `field` (at slider 1) moves it −2.1 along x, `other` at weight 1
/// // another −0.9; contracted, `field` alone carries it past the fan's rim, and so do both.
/// let v = [DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, -1.0, 0.0), DVec3::new(1.0, 1.0, 0.0),
///          DVec3::new(-1.0, 1.0, 0.0), DVec3::ZERO];
/// let t = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
/// let mut field = vec![DVec3::ZERO; 5];
/// field[4] = DVec3::new(-2.1, 0.0, 0.0);
/// let mut other = vec![DVec3::ZERO; 5];
/// other[4] = DVec3::new(-0.9, 0.0, 0.0);
/// let fixed = [true, true, true, true, false];
/// let combined = |f: &[DVec3]| f.iter().zip(&other).map(|(a, b)| *a + *b).collect::<Vec<_>>();
/// assert_eq!(facebem::settle::untangle::turned_over(&v, &t, &combined(&field)), vec![1]);
/// assert!(facebem::settle::untangle::relax_in_combination(&v, &t, &mut field, &[(&other, 1.0)], &fixed, 0.0));
/// assert!(facebem::settle::untangle::turned_over(&v, &t, &combined(&field)).is_empty());
/// assert!(facebem::settle::untangle::turned_over(&v, &t, &field).is_empty());
/// ```
pub fn relax_in_combination(
    neutral: &[DVec3],
    triangles: &[[u32; 3]],
    field: &mut [DVec3],
    others: &[(&[DVec3], f64)],
    fixed: &[bool],
    patch_radius: f64,
) -> bool {
    let rest = |v: usize| -> DVec3 {
        others
            .iter()
            .map(|(f, w)| f.get(v).copied().unwrap_or(DVec3::ZERO) * *w)
            .sum()
    };
    let mut combined: Vec<DVec3> = field
        .iter()
        .enumerate()
        .map(|(v, u)| *u + rest(v))
        .collect();
    if relax_inversions(neutral, triangles, &mut combined, fixed, patch_radius) == 0 {
        return false;
    }
    let mut relaxed: Vec<DVec3> = combined
        .iter()
        .enumerate()
        .map(|(v, u)| *u - rest(v))
        .collect();
    // Taking the combination's change can turn `field` alone over where the others held it
    // flat: relax it alone too, and keep the result only if the combination still turns fewer.
    relax_inversions(neutral, triangles, &mut relaxed, fixed, patch_radius);
    let combination_turned = |f: &[DVec3]| {
        let sum: Vec<DVec3> = f.iter().enumerate().map(|(v, u)| *u + rest(v)).collect();
        turned_over(neutral, triangles, &sum).len()
    };
    if turned_over(neutral, triangles, &relaxed).len()
        > turned_over(neutral, triangles, field).len()
        || combination_turned(&relaxed) >= combination_turned(field)
    {
        return false;
    }
    field.copy_from_slice(&relaxed);
    true
}

/// Most rounds of [`relax_inversions`]' second stage (evening out turned triangles).
pub const FLATTEN_ROUNDS: usize = 30;

/// The second stage of [`relax_inversions`], for triangles a smooth field still turns over:
/// the free corners of a turned triangle take the triangle's mean displacement, one turned
/// triangle at a time, and the change is kept only if fewer of the triangles around those
/// corners are turned after it (a triangle displaced uniformly cannot turn over); at most
/// [`FLATTEN_ROUNDS`] rounds. Marks the vertices it moves in `moved`.
fn flatten_turned(
    neutral: &[DVec3],
    triangles: &[[u32; 3]],
    field: &mut [DVec3],
    is_fixed: &dyn Fn(usize) -> bool,
    moved: &mut [bool],
) {
    let n = moved.len();
    let incident = incidence(n, triangles);
    let is_turned = |t: usize, field: &[DVec3]| is_turned(neutral, &triangles[t], field);
    for _ in 0..FLATTEN_ROUNDS {
        let turned = turned_over(neutral, triangles, field);
        let mut improved = false;
        for t in turned {
            if !is_turned(t, field) {
                continue;
            }
            let free: Vec<usize> = triangles[t]
                .iter()
                .map(|&v| v as usize)
                .filter(|&v| v < n && !is_fixed(v))
                .collect();
            if free.is_empty() {
                continue;
            }
            let mut around: Vec<usize> = free.iter().flat_map(|&v| incident[v].clone()).collect();
            around.sort_unstable();
            around.dedup();
            let count = |field: &[DVec3]| around.iter().filter(|&&u| is_turned(u, field)).count();
            let before_count = count(field);
            let mean = triangles[t]
                .iter()
                .map(|&v| field[v as usize])
                .sum::<DVec3>()
                / 3.0;
            let before: Vec<DVec3> = free.iter().map(|&v| field[v]).collect();
            for &v in &free {
                field[v] = mean;
            }
            if count(field) < before_count {
                improved = true;
                for &v in &free {
                    moved[v] = true;
                }
            } else {
                for (&v, d) in free.iter().zip(before) {
                    field[v] = d;
                }
            }
        }
        if !improved {
            break;
        }
    }
}

/// Radius, mm, around the still-turned triangles' corners that the pipeline lets
/// [`relax_inversions`]' third stage smooth.
pub const PATCH_MM: f64 = 5.0;

/// The third stage of [`relax_inversions`], for folds a triangle at a time cannot even out:
/// each connected patch of the triangles still turned, grown by [`PATCH_RINGS`] rings, takes
/// the harmonic field (each free vertex at the mean of its neighbours, solved exactly by
/// [`face_prep::harmonic::extend`]) with the patch's rim as boundary, and keeps it only if
/// fewer triangles in and around the patch are turned.
fn smooth_patches(
    neutral: &[DVec3],
    triangles: &[[u32; 3]],
    field: &mut [DVec3],
    neighbours: &[Vec<u32>],
    is_fixed: &dyn Fn(usize) -> bool,
    patch_radius: f64,
    moved: &mut [bool],
) {
    let n = moved.len();
    let turned = turned_over(neutral, triangles, field);
    if turned.is_empty() || patch_radius <= 0.0 {
        return;
    }
    // The vertices within `patch_radius` of a turned triangle's corner, reached from those
    // corners through such vertices: a set that does not depend on the vertex order.
    let mut seeds: Vec<usize> = turned
        .iter()
        .flat_map(|&t| triangles[t].iter().map(|&v| v as usize))
        .filter(|&v| v < n)
        .collect();
    seeds.sort_unstable();
    seeds.dedup();
    let near = |w: usize| {
        seeds
            .iter()
            .any(|&s| (neutral[w] - neutral[s]).length() <= patch_radius)
    };
    let mut in_patch = vec![false; n];
    for &v in &seeds {
        in_patch[v] = true;
    }
    let mut frontier = seeds.clone();
    while !frontier.is_empty() {
        let mut next = Vec::new();
        for &v in &frontier {
            for &w in &neighbours[v] {
                let w = w as usize;
                if !in_patch[w] && near(w) {
                    in_patch[w] = true;
                    next.push(w);
                }
            }
        }
        frontier = next;
    }
    // Connected components of the patch.
    let mut component = vec![usize::MAX; n];
    let mut components: Vec<Vec<usize>> = Vec::new();
    for start in 0..n {
        if !in_patch[start] || component[start] != usize::MAX {
            continue;
        }
        let id = components.len();
        let mut stack = vec![start];
        component[start] = id;
        let mut members = Vec::new();
        while let Some(v) = stack.pop() {
            members.push(v);
            for &w in &neighbours[v] {
                let w = w as usize;
                if in_patch[w] && component[w] == usize::MAX {
                    component[w] = id;
                    stack.push(w);
                }
            }
        }
        components.push(members);
    }
    let incident = incidence(n, triangles);
    for members in &components {
        // The triangles with a corner in the component.
        let mut around: Vec<usize> = members
            .iter()
            .flat_map(|&v| incident[v].iter().copied())
            .collect();
        around.sort_unstable();
        around.dedup();
        let count = |field: &[DVec3]| {
            around
                .iter()
                .filter(|&&t| is_turned(neutral, &triangles[t], field))
                .count()
        };
        let before_count = count(field);
        if before_count == 0 {
            continue;
        }
        let free: Vec<usize> = members
            .iter()
            .copied()
            .filter(|&v| !is_fixed(v) && !neighbours[v].is_empty())
            .collect();
        let before: Vec<DVec3> = free.iter().map(|&v| field[v]).collect();
        let mut is_free = vec![false; n];
        for &v in &free {
            is_free[v] = true;
        }
        // Each edge at a free vertex once (a pair of free vertices from the smaller one).
        let edges: Vec<(u32, u32, f64)> = free
            .iter()
            .flat_map(|&v| neighbours[v].iter().map(move |&w| (v as u32, w, 1.0)))
            .filter(|&(v, w, _)| !is_free[w as usize] || v < w)
            .collect();
        // Vertex indices in range by construction; a failed factorisation keeps the field.
        let _ = face_prep::harmonic::extend(&edges, &is_free, field);
        if count(field) < before_count {
            for &v in &free {
                moved[v] = true;
            }
        } else {
            for (&v, d) in free.iter().zip(before) {
                field[v] = d;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A field the neighbour mean cannot change (harmonic at both free vertices A and B) that
    /// turns two triangles over: the fixed vertex F at the origin stays, A and B move 1.2 to
    /// the left, past it, and the fixed H moves twice as far. Evening out the triangle F-A-B
    /// (A and B take its mean, 0.8 to the left) untangles it; the other, held by H, stays.
    #[test]
    fn evening_out_untangles_what_the_neighbour_mean_cannot() {
        let v = [
            DVec3::ZERO,                // F
            DVec3::new(1.0, -0.5, 0.0), // A
            DVec3::new(1.0, 0.5, 0.0),  // B
            DVec3::new(2.0, -0.5, 0.0), // G
            DVec3::new(2.0, 0.5, 0.0),  // H
        ];
        let t = [[0, 1, 2], [1, 3, 4], [1, 4, 2]];
        let d = DVec3::new(-1.2, 0.0, 0.0);
        // Contraction moves by −field: the field is the opposite of the motion.
        let mut f = vec![DVec3::ZERO, -d, -d, -d, -2.0 * d];
        let fixed = [true, false, false, true, true];
        assert_eq!(turned_over(&v, &t, &f), vec![0, 2]);
        // A and B are each at the mean of their neighbours already.
        assert!(((f[0] + f[2] + f[3] + f[4]) / 4.0 - f[1]).length() < 1e-12);
        assert!(((f[0] + f[1] + f[4]) / 3.0 - f[2]).length() < 1e-12);
        assert_eq!(relax_inversions(&v, &t, &mut f, &fixed, 0.0), 2);
        assert_eq!(turned_over(&v, &t, &f), vec![2]);
        assert!((f[1] + 2.0 / 3.0 * d).length() < 1e-12 && (f[2] + 2.0 / 3.0 * d).length() < 1e-12);
    }
}
