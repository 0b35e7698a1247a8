//! The lips' contact line of a face with three boundary loops (the contour and two open eyes).
//!
//! The two loops of smallest perimeter are the eyes; their centroids give the eye line and the
//! interocular distance `iod`; the surface's area-weighted normal gives the front. The nose tip
//! (the front-most point between the eyes' columns) says which way is down. The lips meet on the
//! face's centre line between [`MOUTH_BELOW_NOSE_IOD`]`.0` and `.1` interocular distances below
//! the nose tip: the seed is the sharpest valley edge there within [`SEED_HALF_WIDTH_IOD`] of the
//! centre line, and the line is traced from it to both corners, no further than
//! [`MAX_HALF_WIDTH_IOD`] from the centre line, and must span [`MIN_WIDTH_IOD`].

use super::{MIN_SEED_FOLD_RAD, Opened, Surface, TraceRule};
use crate::error::PrepError;
use crate::frame::orient::{loop_centroid, loop_perimeter};
use glam::DVec3;

/// The lips meet between this many interocular distances below the nose tip (the mouth line
/// lies 0.35–0.5 iod below the nose tip on adult faces: subnasale-to-stomion about 20–23 mm,
/// nose tip to subnasale about 10–15 mm, iod about 63 mm; Farkas, *Anthropometry of the Head
/// and Face*, 1994). The window is wide so that long and short faces fit.
pub const MOUTH_BELOW_NOSE_IOD: (f64, f64) = (0.15, 1.0);
/// The seed edge's midpoint lies within this many interocular distances of the centre line.
pub const SEED_HALF_WIDTH_IOD: f64 = 0.12;
/// Least width of the found line (corner to corner, along the eye line), interocular
/// distances: a mouth is 0.65–0.9 iod wide.
pub const MIN_WIDTH_IOD: f64 = 0.25;
/// Widest the line may run to either side of the centre line, interocular distances: the
/// mouth's width is 0.65–0.9 interocular distances (Farkas 1994: 50 ± 3.5 mm against 62 ± 3 mm
/// between the pupils).
pub const MAX_HALF_WIDTH_IOD: f64 = 0.45;

/// The lips' trace goes on while an edge folds by half the line's sharpest fold so far.
pub const LIP_TRACE: TraceRule = TraceRule {
    fraction: 0.5,
    least_rad: 0.0,
};

/// The face's frame for the search: eye midpoint, unit eye-line direction, unit "down" in the
/// front plane, interocular distance, and how far below the eyes the nose tip is.
pub(super) struct SearchFrame {
    pub(super) eyes_mid: DVec3,
    pub(super) across: DVec3,
    pub(super) down: DVec3,
    pub(super) iod: f64,
    nose_below_eyes: f64,
}

impl SearchFrame {
    /// How far below the eye midpoint the mouth is looked for (along `down`):
    /// [`MOUTH_BELOW_NOSE_IOD`] below the nose tip.
    pub(super) fn mouth_window(&self) -> (f64, f64) {
        (
            self.nose_below_eyes + MOUTH_BELOW_NOSE_IOD.0 * self.iod,
            self.nose_below_eyes + MOUTH_BELOW_NOSE_IOD.1 * self.iod,
        )
    }
}

pub(super) fn search_frame(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    loops: &[Vec<u32>],
) -> Option<SearchFrame> {
    let mut by_perimeter: Vec<usize> = (0..loops.len()).collect();
    by_perimeter.sort_by(|&a, &b| {
        loop_perimeter(vertices, &loops[a]).total_cmp(&loop_perimeter(vertices, &loops[b]))
    });
    let (e1, e2) = (
        loop_centroid(vertices, &loops[by_perimeter[0]]),
        loop_centroid(vertices, &loops[by_perimeter[1]]),
    );
    let iod = e1.distance(e2);
    if !iod.is_finite() || iod <= 0.0 {
        return None;
    }
    let across = (e2 - e1) / iod;
    let front = super::lids::area_normal(vertices, triangles);
    let front = (front - front.dot(across) * across).try_normalize()?;
    let up_or_down = front.cross(across);
    let eyes_mid = 0.5 * (e1 + e2);
    let tip = vertices
        .iter()
        .filter(|p| {
            let r = **p - eyes_mid;
            r.dot(across).abs() < 0.35 * iod && r.dot(up_or_down).abs() < 1.5 * iod
        })
        .max_by(|a, b| {
            (**a - eyes_mid)
                .dot(front)
                .total_cmp(&(**b - eyes_mid).dot(front))
        })?;
    let along = (*tip - eyes_mid).dot(up_or_down);
    let down = if along >= 0.0 {
        up_or_down
    } else {
        -up_or_down
    };
    Some(SearchFrame {
        eyes_mid,
        across,
        down,
        iod,
        nose_below_eyes: along.abs(),
    })
}

/// Finds the lips' contact line of a face with three boundary loops (the contour and two eyes)
/// and cuts it open; an error naming what is missing when no line is found.
///
/// ```
/// use face_prep::frame::contact::mouth::open_closed_mouth;
/// use face_prep::PrepError;
/// use glam::DVec3;
/// // Three triangles far apart are not a face: no eyes to look for the mouth from.
/// let v: Vec<DVec3> = (0..9).map(|i| DVec3::new(i as f64, (i % 3) as f64, 0.0)).collect();
/// let err = open_closed_mouth(&v, &[[0, 1, 2]], &[vec![0], vec![3], vec![6]]);
/// assert!(matches!(err, Err(PrepError::NoMouth { .. })));
/// ```
pub fn open_closed_mouth(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    loops: &[Vec<u32>],
) -> Result<Opened, PrepError> {
    let frame = search_frame(vertices, triangles, loops).ok_or_else(|| PrepError::NoMouth {
        reason: "the eyes and the front could not be placed".into(),
    })?;
    let surface = Surface::new(vertices, triangles, loops);
    let (line, _) = lips_line(&surface, &frame)?;
    Ok(Opened::cut_along(
        vertices,
        triangles,
        &[line],
        frame.down,
        true,
    ))
}

/// The lips' contact line in `frame` and its seed's fold; an error naming what is missing.
fn lips_line(surface: &Surface<'_>, frame: &SearchFrame) -> Result<(Vec<u32>, f64), PrepError> {
    let no_mouth = |reason: String| PrepError::NoMouth { reason };
    let iod = frame.iod;
    let across_of = |x: DVec3| (x - frame.eyes_mid).dot(frame.across);
    let below_eyes = |x: DVec3| (x - frame.eyes_mid).dot(frame.down);
    let (lo, hi) = frame.mouth_window();
    let Some((seed_fold, a, b)) = surface.sharpest_edge(|m| {
        across_of(m).abs() <= SEED_HALF_WIDTH_IOD * iod && (lo..=hi).contains(&below_eyes(m))
    }) else {
        return Err(no_mouth(
            "no surface below the nose to look for the lips in".into(),
        ));
    };
    if seed_fold < MIN_SEED_FOLD_RAD {
        return Err(no_mouth(format!(
            "the sharpest fold below the nose is {:.0}°, lips that meet fold by {:.0}° at least",
            seed_fold.to_degrees(),
            MIN_SEED_FOLD_RAD.to_degrees()
        )));
    }
    let front = frame.across.cross(frame.down);
    let line = surface.trace((a, b), seed_fold, LIP_TRACE, frame.across, front, |x| {
        across_of(x).abs() <= MAX_HALF_WIDTH_IOD * iod
    });
    let width = across_of(surface.p(line[line.len() - 1])) - across_of(surface.p(line[0]));
    if line.len() < 3 || width < MIN_WIDTH_IOD * iod {
        return Err(no_mouth(format!(
            "the fold below the nose ({:.0}°) runs {:.2} eye distances, a mouth is {:.2} wide at \
             least",
            seed_fold.to_degrees(),
            width / iod,
            MIN_WIDTH_IOD
        )));
    }
    Ok((line, seed_fold))
}

/// The face's width across its contour, in interocular distances: 2.2 on ICT's narrow face, 2.5
/// on MediaPipe's (a face is 130–150 mm wide at the cheekbones, the pupils 60–65 mm apart).
pub const CONTOUR_WIDTH_IOD: f64 = 2.3;

/// Finds the lips' contact line of a face with one boundary loop (the contour: the mouth and
/// both eyes closed) and cuts it open. With no eye to start from, the frame comes from the
/// surface alone: the front is the area-weighted normal, the nose tip the front-most vertex,
/// the interocular distance the contour's width over [`CONTOUR_WIDTH_IOD`], and down is tried
/// along both principal axes of the contour in the front plane, both ways; the way whose lips'
/// line has the sharpest seed wins.
///
/// ```
/// use face_prep::frame::contact::mouth::open_closed_mouth_without_eyes;
/// use face_prep::PrepError;
/// use glam::DVec3;
/// // A flat square has no folds: no lips that meet.
/// let v = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
/// let err = open_closed_mouth_without_eyes(&v, &[[0, 1, 2], [0, 2, 3]], &[vec![0, 1, 2, 3]]);
/// assert!(matches!(err, Err(PrepError::NoMouth { .. })));
/// ```
pub fn open_closed_mouth_without_eyes(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    loops: &[Vec<u32>],
) -> Result<Opened, PrepError> {
    let no_mouth = |reason: &str| PrepError::NoMouth {
        reason: reason.into(),
    };
    let contour = loops
        .first()
        .filter(|l| l.len() >= 3)
        .ok_or_else(|| no_mouth("the face has no contour"))?;
    let front = super::lids::area_normal(vertices, triangles)
        .try_normalize()
        .ok_or_else(|| no_mouth("the face has no front"))?;
    let tip = *vertices
        .iter()
        .max_by(|a, b| a.dot(front).total_cmp(&b.dot(front)))
        .ok_or_else(|| no_mouth("the face has no vertices"))?;
    // The contour's principal axes in the front plane (2 x 2 covariance, closed form).
    let centre = loop_centroid(vertices, contour);
    let seed_axis = front.any_orthonormal_vector();
    let other_axis = front.cross(seed_axis);
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for &v in contour {
        let r = vertices[v as usize] - centre;
        let (x, y) = (r.dot(seed_axis), r.dot(other_axis));
        sxx += x * x;
        sxy += x * y;
        syy += y * y;
    }
    let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let major = seed_axis * angle.cos() + other_axis * angle.sin();
    let surface = Surface::new(vertices, triangles, loops);
    let mut best: Option<(f64, Vec<u32>, DVec3)> = None;
    let mut last_error = no_mouth("no lips' line on either side of the nose tip");
    for down in [major, -major, front.cross(major), -front.cross(major)] {
        let across = down.cross(front);
        let (lo, hi) = contour
            .iter()
            .map(|&v| (vertices[v as usize] - centre).dot(across))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            });
        let iod = (hi - lo) / CONTOUR_WIDTH_IOD;
        if !iod.is_finite() || iod <= 0.0 {
            continue;
        }
        let frame = SearchFrame {
            eyes_mid: tip,
            across,
            down,
            iod,
            nose_below_eyes: 0.0,
        };
        match lips_line(&surface, &frame) {
            Ok((line, fold)) => {
                if best.as_ref().is_none_or(|b| fold > b.0) {
                    best = Some((fold, line, down));
                }
            }
            Err(e) => last_error = e,
        }
    }
    let (_, line, down) = best.ok_or(last_error)?;
    Ok(Opened::cut_along(vertices, triangles, &[line], down, true))
}
