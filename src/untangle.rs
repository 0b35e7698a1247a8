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

use glam::DVec3;

/// Most relaxation rounds per response.
pub const MAX_ROUNDS: usize = 12;

/// Distance from the mouth loop, mm, within which the pipeline relaxes turned-over triangles:
/// the lips and the folds beside them, where thin tissue turns further than a linear response
/// can follow (issue 10 allows folds there). Elsewhere a turned triangle is left as a defect
/// to be seen.
pub const LIPS_MM: f64 = 12.0;

/// Triangles that `field` turns over at full contraction (slider −1, so `neutral − field`):
/// their normal reverses.
///
/// ```
/// use glam::DVec3;
/// let v = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// // Contraction moves the apex by −field: down by 2, through the base.
/// let f = [DVec3::ZERO, DVec3::ZERO, DVec3::new(0.0, 2.0, 0.0)];
/// assert_eq!(facebem::untangle::turned_over(&v, &[[0, 1, 2]], &f), vec![0]);
/// assert!(facebem::untangle::turned_over(&v, &[[0, 1, 2]], &[DVec3::X; 3]).is_empty());
/// ```
pub fn turned_over(neutral: &[DVec3], triangles: &[[u32; 3]], field: &[DVec3]) -> Vec<usize> {
    let normal = |t: &[u32; 3], s: f64| {
        let [a, b, c] = t.map(|i| {
            let i = i as usize;
            neutral[i] + s * field.get(i).copied().unwrap_or(DVec3::ZERO)
        });
        (b - a).cross(c - a)
    };
    triangles
        .iter()
        .enumerate()
        .filter(|(_, t)| t.iter().all(|&i| (i as usize) < neutral.len()))
        .filter(|(_, t)| normal(t, 0.0).dot(normal(t, -1.0)) <= 0.0)
        .map(|(i, _)| i)
        .collect()
}

/// Relaxes `field` (a control's displacement at slider 1 on `neutral`) where it turns triangles
/// over, moving only vertices not flagged in `fixed`. Returns how many vertices moved.
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
/// assert_eq!(facebem::untangle::turned_over(&v, &t, &f), vec![1]);
/// assert_eq!(facebem::untangle::relax_inversions(&v, &t, &mut f, &fixed), 1);
/// assert!(facebem::untangle::turned_over(&v, &t, &f).is_empty());
/// assert_eq!(f[4], DVec3::ZERO);
/// ```
pub fn relax_inversions(
    neutral: &[DVec3],
    triangles: &[[u32; 3]],
    field: &mut [DVec3],
    fixed: &[bool],
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
    moved.iter().filter(|&&m| m).count()
}
