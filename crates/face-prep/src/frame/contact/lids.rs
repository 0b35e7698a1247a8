//! The lids' contact lines of a face with two boundary loops (the contour and an open mouth):
//! eyes closed in the neutral.
//!
//! The loop of larger perimeter is the contour, the other the mouth. The surface's
//! area-weighted normal gives the front; up is from the mouth's centroid toward the centroid of
//! the face's area (the mouth lies in the lower third of any front face). With no eyes to
//! measure, the interocular distance is estimated from the mouth's width:
//! `iod ≈ width / `[`MOUTH_WIDTH_IOD`]. On each side of the centre line the [`LID_SEEDS`]
//! sharpest valley edges between [`EYES_ABOVE_MOUTH_IOD`]`.0` and `.1` above the mouth and
//! [`EYE_ACROSS_IOD`]`.0` to `.1` out from the centre line are each traced to both canthi
//! ([`LID_TRACE`]), within [`MAX_HALF_LENGTH_IOD`] of the seed and never across the centre
//! line; the line holding the most valley is the lids' line.
//!
//! A face with one eye closed has three loops (the contour, the mouth and the open eye): the
//! closed eye's lid line is looked for the same way on the side away from the open eye
//! ([`open_one_closed_eye`]).

use super::{Opened, Surface, TraceRule};
use crate::error::PrepError;
use crate::frame::orient::{loop_centroid, loop_perimeter};
use glam::DVec3;

/// Mouth width over interocular distance used to estimate the latter (Farkas 1994: 50 mm
/// against 62 mm between the pupils).
pub const MOUTH_WIDTH_IOD: f64 = 0.8;
/// The eyes lie this many (estimated) interocular distances above the mouth's centroid (eye
/// line to stomion about 70 mm, 1.1 iod; the window takes the estimate's error).
pub const EYES_ABOVE_MOUTH_IOD: (f64, f64) = (0.7, 1.7);
/// Each eye's seed lies this far out from the centre line, interocular distances (the pupil
/// is at 0.5).
pub const EYE_ACROSS_IOD: (f64, f64) = (0.25, 0.85);
/// The lid line runs at most this far to either side of its seed, interocular distances (the
/// palpebral fissure is 28–32 mm long, about 0.5 iod).
pub const MAX_HALF_LENGTH_IOD: f64 = 0.4;
/// Least length of a lid line (canthus to canthus, along the across direction), interocular
/// distances.
pub const MIN_LENGTH_IOD: f64 = 0.2;

/// Least fold of a lid line's seed, 20°: closed lids meet at a shallower fold than lips (a
/// welded eye opening of the MediaPipe face folds by 23–51° along its lid line).
pub const MIN_LID_SEED_FOLD_RAD: f64 = 20.0 * std::f64::consts::PI / 180.0;
/// The lids' trace goes on while an edge folds by 0.3 of the line's sharpest fold so far and
/// by 12° at least.
pub const LID_TRACE: TraceRule = TraceRule {
    fraction: 0.3,
    least_rad: 12.0 * std::f64::consts::PI / 180.0,
};
/// Seeds tried per eye: each is traced and the line holding the most valley (the sum of fold ×
/// length over its edges) is the lid line, so that a short
/// sharp crease beside the eye does not win over the long line where the lids meet.
pub const LID_SEEDS: usize = 16;

/// The area-weighted normal of a triangle mesh (not normalised).
pub(crate) fn area_normal(vertices: &[DVec3], triangles: &[[u32; 3]]) -> DVec3 {
    triangles
        .iter()
        .map(|t| {
            let p = |k: usize| vertices[t[k] as usize];
            (p(1) - p(0)).cross(p(2) - p(0))
        })
        .sum()
}

/// Finds both eyes' lid lines of a face with two boundary loops (the contour and an open mouth)
/// and cuts them open; an error naming the eye that is missing when a line is not found.
///
/// ```
/// use face_prep::frame::contact::lids::open_closed_eyes;
/// use face_prep::PrepError;
/// use glam::DVec3;
/// // A flat square with a hole has no folds: no lids that meet.
/// let v = [
///     DVec3::new(-2.0, -2.0, 0.0), DVec3::new(2.0, -2.0, 0.0),
///     DVec3::new(2.0, 2.0, 0.0), DVec3::new(-2.0, 2.0, 0.0),
///     DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, -1.0, 0.0),
///     DVec3::new(1.0, 1.0, 0.0), DVec3::new(-1.0, 1.0, 0.0),
/// ];
/// let t = [[0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]];
/// let err = open_closed_eyes(&v, &t, &[vec![0, 1, 2, 3], vec![4, 7, 6, 5]]);
/// assert!(matches!(err, Err(PrepError::NoEyes { .. })));
/// ```
pub fn open_closed_eyes(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    loops: &[Vec<u32>],
) -> Result<Opened, PrepError> {
    // The loop of smaller perimeter is the mouth (the other is the contour).
    let mouth = if loop_perimeter(vertices, &loops[0]) >= loop_perimeter(vertices, &loops[1]) {
        &loops[1]
    } else {
        &loops[0]
    };
    let frame = LidFrame::new(vertices, triangles, mouth)?;
    let surface = Surface::new(vertices, triangles, loops);
    let lines = [
        lid_line(&surface, &frame, -1.0, "one")?,
        lid_line(&surface, &frame, 1.0, "the other")?,
    ];
    if lines[0].iter().any(|v| lines[1].contains(v)) {
        return Err(PrepError::NoEyes {
            reason: "the two lid lines found meet".into(),
        });
    }
    Ok(Opened::cut_along(
        vertices, triangles, &lines, -frame.up, false,
    ))
}

/// Finds the closed eye of a face with three boundary loops that are the contour, an open mouth
/// and one open eye (a wink in the neutral) and cuts its lid line open; `None` when the loops
/// are not that (the loop of middle perimeter is taken for the mouth, the smallest for the open
/// eye, which must lie where an eye does above the mouth) or no lid line is found on the other
/// side.
///
/// ```
/// use face_prep::frame::contact::lids::open_one_closed_eye;
/// use glam::DVec3;
/// // Three far-apart triangles are not a face.
/// let v: Vec<DVec3> = (0..9).map(|i| DVec3::new(i as f64, (i % 3) as f64, 0.0)).collect();
/// assert!(open_one_closed_eye(&v, &[[0, 1, 2]], &[vec![0], vec![3], vec![6]]).is_none());
/// ```
pub fn open_one_closed_eye(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    loops: &[Vec<u32>],
) -> Option<Opened> {
    if loops.len() != 3 {
        return None;
    }
    let mut by_perimeter: Vec<&Vec<u32>> = loops.iter().collect();
    by_perimeter
        .sort_by(|a, b| loop_perimeter(vertices, a).total_cmp(&loop_perimeter(vertices, b)));
    let (eye, mouth) = (by_perimeter[0], by_perimeter[1]);
    let frame = LidFrame::new(vertices, triangles, mouth).ok()?;
    let e = loop_centroid(vertices, eye);
    let (above, out) = (frame.above(e), frame.out(e));
    let iod = frame.iod;
    if !(EYES_ABOVE_MOUTH_IOD.0 * iod..=EYES_ABOVE_MOUTH_IOD.1 * iod).contains(&above)
        || !(EYE_ACROSS_IOD.0 * iod..=EYE_ACROSS_IOD.1 * iod).contains(&out.abs())
    {
        return None;
    }
    let surface = Surface::new(vertices, triangles, loops);
    let line = lid_line(&surface, &frame, -out.signum(), "the closed").ok()?;
    Some(Opened::cut_along(
        vertices,
        triangles,
        &[line],
        -frame.up,
        false,
    ))
}

/// The frame the lids are looked for in, from the mouth: its centroid, the face's up (from the
/// mouth toward the centroid of the face's area) and front, and the interocular distance
/// estimated from the mouth's width.
struct LidFrame {
    mouth_c: DVec3,
    up: DVec3,
    across: DVec3,
    front: DVec3,
    iod: f64,
}

impl LidFrame {
    fn new(vertices: &[DVec3], triangles: &[[u32; 3]], mouth: &[u32]) -> Result<Self, PrepError> {
        let no_eyes = |reason: &str| PrepError::NoEyes {
            reason: reason.into(),
        };
        let mouth_c = loop_centroid(vertices, mouth);
        // The loop's diameter, from the vertex farthest from its first and the vertex farthest
        // from that (linear in the loop; exact for a convex loop in practice).
        let farthest = |from: DVec3| {
            mouth
                .iter()
                .map(|&v| vertices[v as usize])
                .max_by(|a, b| a.distance(from).total_cmp(&b.distance(from)))
        };
        let width = mouth
            .first()
            .and_then(|&v| farthest(vertices[v as usize]))
            .and_then(|a| farthest(a).map(|b| a.distance(b)))
            .unwrap_or(0.0);
        let face_c = {
            let (mut sum, mut area) = (DVec3::ZERO, 0.0);
            for t in triangles {
                let p = |k: usize| vertices[t[k] as usize];
                let a = 0.5 * (p(1) - p(0)).cross(p(2) - p(0)).length();
                sum += a * (p(0) + p(1) + p(2)) / 3.0;
                area += a;
            }
            sum / area
        };
        let front = area_normal(vertices, triangles).try_normalize();
        let up = front.and_then(|f| {
            let r = face_c - mouth_c;
            (r - r.dot(f) * f).try_normalize()
        });
        let (Some(front), Some(up)) = (front, up) else {
            return Err(no_eyes("the front and the mouth could not be placed"));
        };
        let iod = width / MOUTH_WIDTH_IOD;
        if !iod.is_finite() || iod <= 0.0 {
            return Err(no_eyes("the mouth has no width"));
        }
        Ok(LidFrame {
            mouth_c,
            up,
            across: up.cross(front),
            front,
            iod,
        })
    }

    fn above(&self, x: DVec3) -> f64 {
        (x - self.mouth_c).dot(self.up)
    }

    fn out(&self, x: DVec3) -> f64 {
        (x - self.mouth_c).dot(self.across)
    }
}

/// The lid line of the eye on `side` (−1 or +1 along the frame's across) of the centre line;
/// an error naming the eye (`name`) when none is found.
fn lid_line(
    surface: &Surface<'_>,
    frame: &LidFrame,
    side: f64,
    name: &str,
) -> Result<Vec<u32>, PrepError> {
    let no_eyes = |reason: String| PrepError::NoEyes { reason };
    let (iod, across, front) = (frame.iod, frame.across, frame.front);
    let above = |x: DVec3| frame.above(x);
    let out = |x: DVec3| frame.out(x);
    let seeds = surface.sharpest_edges(
        |m| {
            (EYES_ABOVE_MOUTH_IOD.0 * iod..=EYES_ABOVE_MOUTH_IOD.1 * iod).contains(&above(m))
                && (EYE_ACROSS_IOD.0 * iod..=EYE_ACROSS_IOD.1 * iod).contains(&(side * out(m)))
        },
        LID_SEEDS,
    );
    let Some(&(sharpest, _, _)) = seeds.first() else {
        return Err(no_eyes(format!(
            "no surface where {name} eye should be, above the mouth"
        )));
    };
    if sharpest < MIN_LID_SEED_FOLD_RAD {
        return Err(no_eyes(format!(
            "where {name} eye should be the sharpest fold is {:.0}°, lids that meet fold by \
             {:.0}° at least",
            sharpest.to_degrees(),
            MIN_LID_SEED_FOLD_RAD.to_degrees()
        )));
    }
    let Some((seed_fold, line)) = seeds
        .iter()
        .filter(|s| s.0 >= MIN_LID_SEED_FOLD_RAD)
        .map(|&(f, a, b)| {
            let seed_out = out(0.5 * (surface.p(a) + surface.p(b)));
            let line = surface.trace((a, b), f, LID_TRACE, across, front, |x| {
                side * out(x) > 0.0 && (out(x) - seed_out).abs() <= MAX_HALF_LENGTH_IOD * iod
            });
            (f, line)
        })
        .max_by(|x, y| {
            surface
                .valley_weight(&x.1)
                .total_cmp(&surface.valley_weight(&y.1))
        })
    else {
        return Err(no_eyes(format!("no fold where {name} eye should be")));
    };
    let length = out(surface.p(line[line.len() - 1])) - out(surface.p(line[0]));
    if line.len() < 3 || length < MIN_LENGTH_IOD * iod {
        return Err(no_eyes(format!(
            "the fold where {name} eye should be ({:.0}°) runs {:.2} eye distances, lids \
             meet along {:.2} at least",
            seed_fold.to_degrees(),
            length / iod,
            MIN_LENGTH_IOD
        )));
    }
    Ok(line)
}
