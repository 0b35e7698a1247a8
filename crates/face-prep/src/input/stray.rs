//! Stray vertices: a position far outside the rest of the surface (a mistyped or corrupted `v`
//! line, a coordinate set to 1e5), found by a robust outlier rule before any work.
//!
//! Such a vertex makes a needle triangle many times the face's size. Nothing about it is
//! invalid, but every collocation point of the simulated shell lies in its near field, so the
//! BEM quadrature refines it for every element: MediaPipe's face with one x set to 10⁵ spent
//! over 100 s there (found by the fuzzer, issue 36). The rule is the robust one of a median
//! centre and a percentile scale (Rousseeuw & Leroy, *Robust Regression and Outlier
//! Detection*, 1987, ch. 1: location and scale estimates that a few outliers cannot move): the
//! distance of each vertex from the component-wise median position, against the 90th
//! percentile of those distances. On a face, a whole head or a body every vertex lies within a
//! few times that percentile (the bundled faces: 1.23–1.91 times); a vertex more than
//! [`STRAY_FACTOR`] times it is refused.

use crate::error::PrepError;
use glam::DVec3;

/// How many times the 90th-percentile distance from the median position a vertex may lie
/// before it is refused as stray.
pub const STRAY_FACTOR: f64 = 20.0;

/// The vertex (index into `vertices`) lying farthest from the median position of the vertices
/// the triangles use, with its distance over the 90th-percentile distance; `None` for an empty
/// or single-point set.
///
/// ```
/// use face_prep::input::stray::farthest_from_median;
/// use glam::DVec3;
/// let mut grid: Vec<DVec3> = (0..100)
///     .map(|i| DVec3::new((i % 10) as f64, (i / 10) as f64, 0.0))
///     .collect();
/// grid[37].x = 1e5;
/// let triangles: Vec<[u32; 3]> = (0..98).map(|i| [i, i + 1, i + 2]).collect();
/// let (vertex, ratio) = farthest_from_median(&grid, &triangles).unwrap();
/// assert_eq!(vertex, 37);
/// assert!(ratio > 1e4);
/// ```
pub fn farthest_from_median(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Option<(usize, f64)> {
    let mut used = vec![false; vertices.len()];
    for t in triangles {
        for &v in t {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
    }
    let points: Vec<(usize, DVec3)> = vertices
        .iter()
        .enumerate()
        .filter(|(i, _)| used[*i])
        .map(|(i, &p)| (i, p))
        .collect();
    if points.len() < 2 {
        return None;
    }
    let median = |axis: usize| {
        let mut c: Vec<f64> = points.iter().map(|(_, p)| p[axis]).collect();
        let mid = c.len() / 2;
        *c.select_nth_unstable_by(mid, f64::total_cmp).1
    };
    let centre = DVec3::new(median(0), median(1), median(2));
    let mut distances: Vec<f64> = points.iter().map(|(_, p)| p.distance(centre)).collect();
    let (vertex, farthest) = points
        .iter()
        .map(|(i, p)| (*i, p.distance(centre)))
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    let k = (distances.len() * 9 / 10).min(distances.len() - 1);
    let scale = *distances.select_nth_unstable_by(k, f64::total_cmp).1;
    if scale <= 0.0 {
        return None;
    }
    Some((vertex, farthest / scale))
}

/// Refuses a surface with a stray vertex ([`PrepError::StrayVertex`]): one lying more than
/// [`STRAY_FACTOR`] times the 90th-percentile distance from the median position.
///
/// ```
/// let face = face_prep::load_face(std::path::Path::new(concat!(
///     env!("CARGO_MANIFEST_DIR"), "/../../assets/mediapipe_canonical_4loop.obj"))).unwrap();
/// assert!(face_prep::input::stray::check_no_stray_vertex(&face.vertices, &face.triangles).is_ok());
/// ```
pub fn check_no_stray_vertex(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Result<(), PrepError> {
    match farthest_from_median(vertices, triangles) {
        Some((vertex, ratio)) if ratio > STRAY_FACTOR => Err(PrepError::StrayVertex {
            vertex,
            position: vertices[vertex].to_array(),
            ratio,
        }),
        _ => Ok(()),
    }
}
