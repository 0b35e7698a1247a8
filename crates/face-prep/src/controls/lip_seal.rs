//! The lip seal: the lower lip held up against the upper one while the jaw is open (ARKit's
//! `mouthClose`, FACS AU24 over AU26/27: the lips stay together when the mandible drops, as in
//! the bilabial consonants /p b m/ spoken with the teeth apart).
//!
//! # What moves
//!
//! The mandible carries the chin's soft tissue ([`crate::controls::jaw`]); the lower lip above
//! it is free tissue that the orbicularis oris and the mentalis can hold against the upper lip
//! (Gray's Anatomy, 41st ed., ch. 29: the orbicularis oris closes the lips, the mentalis raises
//! the lower lip and the chin's skin). ICT-FaceKit's captured `mouthClose`
//! (`tests/data/calibration`) shows exactly that over its jawOpen: the lower lip's midline
//! margin moves back by its jawOpen motion (35.4 mm up and 16.6 mm forward against the jaw's
//! 34.5 mm down and 20.7 mm back) and the upper lip hardly at all (1.6 mm).
//!
//! # The response: a share of the jaw's opening taken back
//!
//! ARKit defines `mouthClose` as a corrective: the difference between the lips-together pose
//! and `jawOpen`. facebem makes it from the rig's own solved `jaw_open` response `J` (the root
//! crate, after the solve and again from the settled `J` after the settling passes, so that the
//! two stay in step): the seal's response at full value is `share · J` taken back, i.e. `−share · J` added, so `jaw_open` +
//! `lip_seal` at full value is `(1 − share) · J`. The share ([`seal_weight`]) is 1 at the height
//! of the mouth loop's lower chain ([`MouthMargins`]; beside the corners, the corner's height),
//! falls linearly to 0 at [`SEAL_REACH_MM`] below it, fades out above it over
//! [`SEAL_FADE_MM`], is faded out smoothly toward the upper chain (the upper lip stays where
//! the jaw leaves it, but near the corners, [`SEAL_CORNER_MM`]) and toward the outer contour (which the seal does not move). So the lower
//! lip's margin returns to rest over the open jaw and the stretch spreads down the lip and the
//! chin, as the jaw's own solved field there, scaled. Calibrated against ICT-FaceKit's capture,
//! whose `mouthClose` takes back 0.9, 0.5, 0.24 and 0.05 of its jawOpen 6, 14, 29 and 40 mm below
//! the lower lip's midline margin (a linear share over 40 mm: 0.86, 0.65, 0.28, 0), and beside
//! the corners (20 and 28 mm from the midline) 0.85–0.93, 0.52–0.56 and 0.19–0.22 at 8–10, 18 and
//! 32 mm below the lips' height: by the height below the lip, not the distance from the corner.
//! No captured displacement is used: the field is the rig's own `jaw_open` response.
//!
//! Tried first, not kept (journal, 2026-11-29): the lower lip held by a BEM solve (its elements
//! displaced by `−share · J` in the seal's response alone, from unit load cases on them, as the
//! modiolus pins are solved). Where the held lip met the free tissue the solve left creases down
//! from the mouth corners to the chin, and a held band wide enough to avoid them would cost
//! about 1 800 right-hand sides (`docs/lip_seal_held_vs_share.png`).
//!
//! ```
//! use face_prep::{FaceRig, MuscleKind, RigParams, load_face};
//! let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
//!     .join("../../assets/mediapipe_canonical_4loop.obj");
//! let rig = FaceRig::build(&load_face(&path).unwrap(), &RigParams::default()).unwrap();
//! let seal = face_prep::lip_seal::MouthMargins::of(&rig.shell, &rig.loops, &rig.boxes).unwrap();
//! let at = |v: u32| rig.shell.vertices[v as usize];
//! let shares = rig.lip_seal_shares(&[at(seal.lower_midline), at(seal.upper_midline)]);
//! // The lower lip's margin takes the jaw's motion back whole, the upper lip's none of it.
//! assert_eq!(shares, vec![1.0, 0.0]);
//! ```

use crate::controls::muscle_model::distance_to_loop;
use crate::controls::muscle_model::{CONTOUR_TAPER_MM, contour_weight};
use crate::controls::rig_parts::RigParts;
use crate::frame::features::FeatureBoxes;
use crate::frame::orient::{FaceLoops, loop_xy};
use crate::shell::Shell;
use glam::{DVec2, DVec3};

/// How far below the mouth loop's lower chain the seal takes back the jaw's motion, mm (the
/// share falls linearly from 1 at the margin to 0 here; see the module documentation).
pub const SEAL_REACH_MM: f64 = 40.0;

/// Above the lower lip's margin height, the distance over which the seal's share fades out, mm
/// (beside the mouth corners; the upper lip is left out by the side factor of [`seal_weight`]).
pub const SEAL_FADE_MM: f64 = 16.0;

/// Within this distance of a mouth corner, mm, both lips take the jaw's motion back (see
/// [`seal_weight`]), as in ICT-FaceKit's capture (its upper lip's margin 0.16 of it 8 mm from
/// the corner, 0.49 at 4 mm, 1.0 at the corner): the lower lip taken back alone there folded the
/// commissure (ICT 13k: 115 triangles turned over in `jawOpen` + `mouthClose`, now 50).
pub const SEAL_CORNER_MM: f64 = 8.0;

/// The share of the jaw's opening the seal takes back at a point `below_mm` below the lower
/// lip's margin (at the point's x; beside the corners, below the corner's height; negative
/// above it), `lower_mm` from the mouth loop's lower chain, `upper_mm` from its upper chain and
/// `corner_mm` from the nearer mouth corner:
///
/// - down the lip and chin, `1 − below / SEAL_REACH_MM`, 0 from the reach on; above the margin's
///   height, 1 − smoothstep(−below / [`SEAL_FADE_MM`]);
/// - times a side factor: smoothstep(2 · upper / (upper + lower)), 1 where the point is at
///   least as near the lower chain as the upper one and 0 on the upper chain; but near a corner
///   at least 1 − smoothstep(corner / [`SEAL_CORNER_MM`]), both lips taking the motion back.
///
/// ```
/// use face_prep::lip_seal::{SEAL_CORNER_MM, SEAL_FADE_MM, SEAL_REACH_MM, seal_weight};
/// let far = 100.0; // from the corners
/// assert_eq!(seal_weight(0.0, 0.0, 5.0, far), 1.0);
/// assert!((seal_weight(0.5 * SEAL_REACH_MM, 20.0, 30.0, far) - 0.5).abs() < 1e-12);
/// assert_eq!(seal_weight(SEAL_REACH_MM, 40.0, 50.0, far), 0.0);
/// assert_eq!(seal_weight(-SEAL_FADE_MM, 9.0, 9.0, far), 0.0);
/// // On the upper lip: nothing, but half halfway to a corner and all at it.
/// assert_eq!(seal_weight(-5.0, 5.0, 0.0, far), 0.0);
/// assert!((seal_weight(0.0, 2.0, 0.0, 0.5 * SEAL_CORNER_MM) - 0.5).abs() < 1e-12);
/// assert_eq!(seal_weight(0.0, 0.0, 0.0, 0.0), 1.0);
/// ```
pub fn seal_weight(below_mm: f64, lower_mm: f64, upper_mm: f64, corner_mm: f64) -> f64 {
    let smoothstep = |x: f64| {
        let x = x.clamp(0.0, 1.0);
        x * x * (3.0 - 2.0 * x)
    };
    let share = if below_mm >= 0.0 {
        (1.0 - below_mm / SEAL_REACH_MM).clamp(0.0, 1.0)
    } else {
        1.0 - smoothstep(-below_mm / SEAL_FADE_MM)
    };
    let total = upper_mm + lower_mm;
    let lower_side = if total > 0.0 {
        smoothstep(2.0 * upper_mm / total)
    } else {
        1.0
    };
    let at_corner = 1.0 - smoothstep(corner_mm / SEAL_CORNER_MM);
    share * lower_side.max(at_corner)
}

/// What the seal's share at a point is computed from: the two chains and the outer contour.
struct Share {
    upper: Vec<DVec2>,
    lower: Vec<DVec2>,
    contour: Vec<DVec2>,
    mm_per_unit: f64,
}

impl Share {
    fn of(
        shell: &Shell,
        loops: &FaceLoops,
        boxes: &FeatureBoxes,
        mm_per_unit: f64,
    ) -> Option<Share> {
        let margins = MouthMargins::of(shell, loops, boxes)?;
        let xy = |chain: &[u32]| -> Vec<DVec2> {
            chain
                .iter()
                .map(|&v| shell.vertices[v as usize].truncate())
                .collect()
        };
        Some(Share {
            upper: xy(&margins.upper_chain),
            lower: xy(&margins.lower_chain),
            contour: loop_xy(&shell.vertices, &loops.face),
            mm_per_unit,
        })
    }

    /// The share at `p`, faded in from the outer contour like the muscles' patterns.
    fn at(&self, p: DVec3) -> f64 {
        let c = p.truncate();
        let mm = self.mm_per_unit;
        let lower_mm = distance_to_polyline(c, &self.lower) * mm;
        let upper_mm = distance_to_polyline(c, &self.upper) * mm;
        let below_mm = (height_at(&self.lower, c.x) - c.y) * mm;
        // The chains' ends are the corners.
        let corner_mm = [self.lower.first(), self.lower.last()]
            .into_iter()
            .flatten()
            .map(|q| q.distance(c))
            .fold(f64::INFINITY, f64::min)
            * mm;
        let contour = contour_weight(distance_to_loop(c, &self.contour), CONTOUR_TAPER_MM / mm);
        seal_weight(below_mm, lower_mm, upper_mm, corner_mm) * contour
    }
}

/// Sets the lip seal's field, `fields[seal]`, to `jaw_open`'s, `fields[jaw]`, times minus
/// `shares` (one per point of the fields; see the module documentation): at slider +1 the seal
/// moves each point by `−share × jaw_open`. Nothing when either index is out of range.
///
/// ```
/// use glam::DVec3;
/// let mut fields = vec![vec![DVec3::Y, DVec3::X], vec![DVec3::ZERO; 2]];
/// face_prep::lip_seal::take_back(&mut fields, 1, 0, &[1.0, 0.5]);
/// assert_eq!(fields[1], vec![-DVec3::Y, -0.5 * DVec3::X]);
/// ```
pub fn take_back(fields: &mut [Vec<DVec3>], seal: usize, jaw: usize, shares: &[f64]) {
    let Some(opening) = fields.get(jaw).cloned() else {
        return;
    };
    if let Some(field) = fields.get_mut(seal) {
        *field = opening.iter().zip(shares).map(|(d, &w)| -w * *d).collect();
    }
}

/// The seal's share at each of `points` (canonical frame), in their order: [`seal_weight`],
/// faded in from the outer contour; all 0 when the mouth loop has no margins
/// ([`MouthMargins::of`]).
pub(crate) fn seal_shares(rig: RigParts<'_>, points: &[DVec3]) -> Vec<f64> {
    let Some(share) = Share::of(rig.shell, rig.loops, rig.boxes, rig.mm_per_unit) else {
        return vec![0.0; points.len()];
    };
    points.iter().map(|&p| share.at(p)).collect()
}

/// The height of an open polyline at `x`: the highest of its edges spanning `x`, or beyond its
/// ends the height of the end nearer in x (0 for an empty one).
fn height_at(polyline: &[DVec2], x: f64) -> f64 {
    let spanning = polyline
        .windows(2)
        .filter(|w| (w[0].x - x) * (w[1].x - x) <= 0.0)
        .map(|w| {
            let dx = w[1].x - w[0].x;
            if dx.abs() > 0.0 {
                w[0].y + (w[1].y - w[0].y) * (x - w[0].x) / dx
            } else {
                w[0].y.max(w[1].y)
            }
        })
        .fold(f64::NEG_INFINITY, f64::max);
    if spanning.is_finite() {
        return spanning;
    }
    polyline
        .iter()
        .min_by(|a, b| (a.x - x).abs().total_cmp(&(b.x - x).abs()))
        .map_or(0.0, |p| p.y)
}

/// Distance from `p` to an open polyline (one point: the distance to it).
fn distance_to_polyline(p: DVec2, polyline: &[DVec2]) -> f64 {
    match polyline {
        [] => f64::INFINITY,
        [only] => p.distance(*only),
        _ => polyline
            .windows(2)
            .map(|w| distance_to_loop(p, w))
            .fold(f64::INFINITY, f64::min),
    }
}

/// The mouth loop split into the upper and the lower lip's margins.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MouthMargins {
    /// The upper lip's margin: the loop from corner to corner through its highest crossing of
    /// the mouth's vertical centre line (both corners included).
    pub upper_chain: Vec<u32>,
    /// The lower lip's margin, corner to corner through the lowest crossing.
    pub lower_chain: Vec<u32>,
    /// The upper chain's vertex at the centre line.
    pub upper_midline: u32,
    /// The lower chain's vertex at the centre line.
    pub lower_midline: u32,
}

impl MouthMargins {
    /// Splits a rig's mouth loop at its corners (its extreme vertices in canonical x) into two
    /// chains. Where the loop crosses the mouth box's vertical centre line (each crossing
    /// edge's endpoint nearer the line), the highest crossing is the upper lip's and the lowest
    /// the lower lip's; each names its chain. (The upper lip's margin may hang below the box's
    /// centre height at the midline, e.g. an upper lip over the lower, so a split at that
    /// height would not do.) `None` for a loop that does not cross the line twice or whose two
    /// crossings are on one chain.
    ///
    /// ```
    /// use face_prep::{FaceRig, RigParams, load_face};
    /// use face_prep::lip_seal::MouthMargins;
    /// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
    ///     .join("../../assets/mediapipe_canonical_4loop.obj");
    /// let rig = FaceRig::build(&load_face(&path).unwrap(), &RigParams::default()).unwrap();
    /// let m = MouthMargins::of(&rig.shell, &rig.loops, &rig.boxes).unwrap();
    /// let at = |v: u32| rig.shell.vertices[v as usize];
    /// assert!(at(m.upper_midline).y > at(m.lower_midline).y);
    /// assert!((at(m.upper_midline).x - rig.boxes.mouth.center().x).abs() < 0.2 * rig.boxes.mouth.width());
    /// // Corner to corner: the chains share their two ends and hold the whole loop.
    /// assert_eq!(m.upper_chain.len() + m.lower_chain.len(), rig.loops.mouth.len() + 2);
    /// ```
    pub fn of(shell: &Shell, loops: &FaceLoops, boxes: &FeatureBoxes) -> Option<MouthMargins> {
        let lp = &loops.mouth;
        let n = lp.len();
        let at = |i: usize| shell.vertices.get(lp[i % n] as usize).copied();
        if n < 4 || (0..n).any(|i| at(i).is_none()) {
            return None;
        }
        let x = |i: usize| at(i).map_or(0.0, |p| p.x);
        let y = |i: usize| at(i).map_or(0.0, |p| p.y);
        let cx = boxes.mouth.center().x;
        // Loop positions where an edge crosses the centre line (its endpoint nearer the line).
        let crossings: Vec<usize> = (0..n)
            .filter_map(|i| {
                let (da, db) = (x(i) - cx, x(i + 1) - cx);
                if da * db > 0.0 || (da == 0.0 && db == 0.0) {
                    return None;
                }
                Some(if da.abs() <= db.abs() { i } else { (i + 1) % n })
            })
            .collect();
        let top = *crossings.iter().max_by(|&&a, &&b| y(a).total_cmp(&y(b)))?;
        let bottom = *crossings.iter().min_by(|&&a, &&b| y(a).total_cmp(&y(b)))?;
        let left = (0..n).max_by(|&a, &b| x(a).total_cmp(&x(b)))?;
        let right = (0..n).min_by(|&a, &b| x(a).total_cmp(&x(b)))?;
        // The loop from `from` to `to` inclusive, in loop order.
        let chain = |from: usize, to: usize| -> Vec<usize> {
            (0..=(to + n - from) % n).map(|k| (from + k) % n).collect()
        };
        let (a, b) = (chain(left, right), chain(right, left));
        let (upper, lower) = match (a.contains(&top), a.contains(&bottom)) {
            (true, false) => (a, b),
            (false, true) => (b, a),
            _ => return None,
        };
        if !lower.contains(&bottom) || !upper.contains(&top) {
            return None;
        }
        Some(MouthMargins {
            upper_chain: upper.iter().map(|&i| lp[i]).collect(),
            lower_chain: lower.iter().map(|&i| lp[i]).collect(),
            upper_midline: lp[top],
            lower_midline: lp[bottom],
        })
    }
}
