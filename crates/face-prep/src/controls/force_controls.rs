//! Force-driven controls: loads that push with a traction instead of prescribing a
//! displacement: the muscles added after the thesis's ten (orbicularis oris, depressor anguli
//! oris, corrugator, procerus, risorius, levator labii superioris alaeque nasi, zygomaticus
//! minor, levator anguli oris, buccinator, the lips' marginal part) and the cheek puff (air pressure inside the mouth).
//!
//! The rig is solved once (one LU) with one boundary-condition layout for every response: an
//! element is either displacement-prescribed in every response (skull, and the bands of the
//! displacement-driven muscles, held at zero in the other muscles' responses) or traction-type
//! in every response. A force-driven control loads traction-type elements: they stay free
//! (zero traction) in every other response, so adding one changes no other response.
//!
//! A traction has no length unit of its own, so a force-driven response is scaled after the
//! solve ([`FaceRig::force_target`](crate::FaceRig::force_target)): its largest displacement on the front surface is the
//! control's target (the cheek puff: [`CHEEK_PUFF_MM`]).
//!
//! ```
//! use face_prep::{FaceRig, MuscleKind, RigParams, load_face};
//! let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
//!     .join("../../assets/mediapipe_canonical_4loop.obj");
//! let rig = FaceRig::build(&load_face(&path).unwrap(), &RigParams::default()).unwrap();
//! let k = rig.muscle_index(MuscleKind::CheekPuff).unwrap();
//! assert!(rig.is_force_control(k));
//! let target_mm = rig.force_target(k).unwrap() * rig.mm_per_unit();
//! assert!((target_mm - face_prep::force_controls::CHEEK_PUFF_MM).abs() < 1e-9);
//! ```

use crate::controls::anatomy::{Attachment, Landmarks};
use crate::controls::lip_margin::marginal_target;
use crate::controls::muscle_kind::{Generator, Lip, attachment};
use crate::controls::muscle_model::{
    AnatomicalParams, CONTOUR_TAPER_MM, MuscleModel, band_pattern, band_weight, contour_weight,
    distance_to_loop, place_band,
};
use crate::controls::muscles::Muscle;
use crate::controls::rig_parts::RigParts;
use crate::frame::features::FeatureBoxes;
use crate::frame::orient::{FaceLoops, loop_xy};
use crate::shell::{ElementTag, Shell};
use glam::{DVec2, DVec3};
use std::collections::HashSet;

/// Half-width of the orbicularis oris ring, mm from the lip margin (the muscle reaches the
/// nose base above and the mentolabial sulcus below; Gray's Anatomy, ch. 29).
pub(crate) const SPHINCTER_RING_MM: f64 = 16.0;

/// Full contraction of one half of the sphincter moves the face by at most this fraction of
/// half the mouth width (both halves together narrow the mouth by 21–55 % on the bundled faces:
/// a pucker).
pub(crate) const SPHINCTER_STRAIN: f64 = 0.45;

/// Forward share of the sphincter's pull (the lips protrude as they purse), relative to the
/// pull toward the mouth's centre.
pub(crate) const SPHINCTER_FORWARD: f64 = 0.6;

/// Places a force-driven band: every front and back element (not rim, not skull) whose
/// centroid lies within the band's whole half-width between origin and insertion.
pub(crate) fn place_force_band(
    shell: &Shell,
    skull: &HashSet<u32>,
    att: &Attachment,
    mm_per_unit: f64,
    params: &AnatomicalParams,
) -> (Vec<u32>, Vec<u32>) {
    let whole = AnatomicalParams {
        core_fraction: 1.0,
        ..*params
    };
    place_band(shell, skull, att, mm_per_unit, &whole)
}

/// Places one half of the sphincter (`ring_mm` = [`SPHINCTER_RING_MM`]) or of its marginal
/// part ([`crate::controls::lip_margin`]): the front and back elements (not rim, not skull)
/// within `ring_mm` of the mouth loop (`mouth`, canonical x-y) in the front plane, above
/// (`Lip::Upper`) or below the mouth's centre line `centre_y`, each chain ordered by its angle
/// around the mouth.
pub(crate) fn place_sphincter(
    shell: &Shell,
    skull: &HashSet<u32>,
    mouth: &[DVec2],
    centre_y: f64,
    lip: Lip,
    ring_mm: f64,
    mm_per_unit: f64,
) -> (Vec<u32>, Vec<u32>) {
    let ring = ring_mm / mm_per_unit;
    let (mut front, mut back) = (Vec::new(), Vec::new());
    if mouth.len() < 3 {
        return (front, back);
    }
    for e in 0..shell.element_count() {
        let tag = shell.tags[e];
        if tag == ElementTag::Rim || skull.contains(&(e as u32)) {
            continue;
        }
        let c = shell.centroid(e).truncate();
        let upper = c.y >= centre_y;
        if upper != (lip == Lip::Upper) || distance_to_loop(c, mouth) > ring {
            continue;
        }
        match tag {
            ElementTag::Front => front.push(e as u32),
            _ => back.push(e as u32),
        }
    }
    // Around the mouth by angle (the chains are drawn in order: a ring, not a scribble).
    let cx = mouth.iter().map(|p| p.x).sum::<f64>() / mouth.len() as f64;
    let angle = |e: u32| {
        let c = shell.centroid(e as usize);
        (c.y - centre_y).atan2(c.x - cx)
    };
    for chain in [&mut front, &mut back] {
        chain.sort_by(|&a, &b| angle(a).total_cmp(&angle(b)).then(a.cmp(&b)));
    }
    (front, back)
}

/// Half-axes of each cheek's pressure region, as fractions of the interocular distance
/// (across) and of the eye-to-mouth height (up): the buccal region between the mouth corner and
/// the masseter, below the zygomatic arch.
pub const CHEEK_RADII: (f64, f64) = (0.32, 0.35);

/// Largest displacement, mm, of the face at full cheek puff (the response is scaled to it).
pub const CHEEK_PUFF_MM: f64 = 8.0;

/// Places the cheek puff: the back (deep-layer) elements, not skull, inside either cheek's
/// ellipse in the front plane ([`cheek_weight`] > 0).
pub(crate) fn place_cheek_puff(shell: &Shell, skull: &HashSet<u32>, l: &Landmarks) -> Vec<u32> {
    (0..shell.element_count())
        .filter(|&e| shell.tags[e] == ElementTag::Back && !skull.contains(&(e as u32)))
        .filter(|&e| cheek_weight(shell.centroid(e).truncate(), l) > 0.0)
        .map(|e| e as u32)
        .collect()
}

/// Raised-cosine weight of a front-plane point in the nearer cheek's ellipse (1 at its centre,
/// 0 on and outside its rim). The ellipses are centred 0.35 interocular distances lateral of
/// each mouth corner, 0.15 eye-to-mouth heights above the mouth's centre line, with half-axes
/// [`CHEEK_RADII`].
///
/// ```
/// use face_prep::{Box2, FeatureBoxes};
/// use face_prep::anatomy::Landmarks;
/// use face_prep::force_controls::cheek_weight;
/// use glam::DVec2;
/// let b = |x0, y0, x1, y1| Box2::new(DVec2::new(x0, y0), DVec2::new(x1, y1));
/// let boxes = FeatureBoxes::derive(
///     b(-8.0, -10.0, 8.0, 8.0),
///     b(1.8, 1.0, 4.5, 2.0),
///     b(-4.5, 1.0, -1.8, 2.0),
///     b(-2.5, -5.5, 2.5, -4.5),
/// )
/// .unwrap();
/// let l = Landmarks::of(&boxes);
/// let centre = DVec2::new(l.mouth.x + l.mouth_half_width + 0.35 * l.iod, l.mouth.y + 0.15 * l.h);
/// assert!((cheek_weight(centre, &l) - 1.0).abs() < 1e-12);
/// assert_eq!(cheek_weight(l.mouth, &l), 0.0);
/// ```
pub fn cheek_weight(p: DVec2, l: &Landmarks) -> f64 {
    let side = if p.x >= l.mouth.x { 1.0 } else { -1.0 };
    let centre = DVec2::new(
        l.mouth.x + side * (l.mouth_half_width + 0.35 * l.iod),
        l.mouth.y + 0.15 * l.h,
    );
    let (ax, ay) = (CHEEK_RADII.0 * l.iod, CHEEK_RADII.1 * l.h);
    if ax <= 0.0 || ay <= 0.0 {
        return 0.0;
    }
    let r = (((p.x - centre.x) / ax).powi(2) + ((p.y - centre.y) / ay).powi(2)).sqrt();
    band_weight(r, 1.0)
}

/// Whether control `k` of `muscles` is force-driven (a standard force control in the
/// anatomical model; see the module docs).
pub(crate) fn is_force_control(model: MuscleModel, muscles: &[Muscle], k: usize) -> bool {
    model == MuscleModel::Anatomical
        && muscles
            .get(k)
            .and_then(|m| m.kind)
            .is_some_and(|kind| kind.is_force())
}

/// Largest displacement on the front surface, in the rig's units, that force-driven control
/// `k` reaches at full value (its response is scaled to it); `None` for other controls.
pub(crate) fn force_target(rig: RigParts<'_>, k: usize) -> Option<f64> {
    if !is_force_control(rig.model, rig.muscles, k) {
        return None;
    }
    let kind = rig.muscles[k].kind?;
    let strength = rig.anatomical.strength;
    match kind.generator() {
        Generator::Force(_) => {
            let att = attachment(kind, rig.boxes)?;
            Some(att.max_strain * strength * att.origin.distance(att.insertion))
        }
        Generator::Sphincter(_) => {
            Some(SPHINCTER_STRAIN * strength * 0.5 * rig.boxes.mouth.width())
        }
        Generator::Marginal(_) => Some(marginal_target(rig.boxes, strength)),
        Generator::Pressure => Some(CHEEK_PUFF_MM * strength / rig.mm_per_unit),
        Generator::Seal | Generator::Band(_) | Generator::Jaw(_) | Generator::Lid(_) => None,
    }
}

/// Traction pattern of a force-driven band at slider = +1: the shape of a displacement-
/// driven band's pattern ([`crate::controls::muscle_model::anatomical_pattern`]: away from the origin,
/// growing with the arc length from it, falling off across the band), weighted once more
/// by the position along the muscle (0 at the origin, 1 at the insertion), so the pull
/// concentrates where the muscle inserts into the skin. Arbitrary magnitude.
pub(crate) fn force_band_traction(
    shell: &Shell,
    loops: &FaceLoops,
    boxes: &FeatureBoxes,
    mm_per_unit: f64,
    params: &AnatomicalParams,
    muscle: &Muscle,
) -> Vec<(u32, DVec3)> {
    let pattern = band_pattern(shell, loops, boxes, mm_per_unit, params, muscle);
    let Some(att) = muscle.kind.and_then(|k| attachment(k, boxes)) else {
        return pattern;
    };
    let axis = att.insertion - att.origin;
    let len2 = axis.length_squared();
    pattern
        .into_iter()
        .map(|(e, t)| {
            let c = shell.centroid(e as usize).truncate();
            let along = if len2 > 0.0 {
                ((c - att.origin).dot(axis) / len2).max(0.0)
            } else {
                1.0
            };
            (e, t * along)
        })
        .collect()
}

/// Traction pattern of the cheek puff at slider = +1 (suction: along the deep layer's
/// outward normal, into the mouth; −1, the puff, pushes the cheeks out), weighted by
/// [`cheek_weight`]. Arbitrary magnitude: the response is scaled to
/// [`FaceRig::force_target`](crate::FaceRig::force_target).
pub(crate) fn cheek_puff_traction(
    shell: &Shell,
    boxes: &FeatureBoxes,
    muscle: &Muscle,
) -> Vec<(u32, DVec3)> {
    let l = Landmarks::of(boxes);
    muscle
        .elements()
        .map(|e| {
            let [a, b, c] = shell.corners(e as usize);
            let outward = (b - a).cross(c - a).normalize_or_zero();
            let w = cheek_weight(shell.centroid(e as usize).truncate(), &l);
            (e, outward * w)
        })
        .collect()
}

/// The mouth loop of a rig (its `shell` and `loops`) in the front plane (canonical x-y), in
/// loop order.
pub(crate) fn mouth_xy(shell: &Shell, loops: &FaceLoops) -> Vec<DVec2> {
    loop_xy(&shell.vertices, &loops.mouth)
}

/// Traction pattern of the sphincter half `muscle` at slider = +1 (away from the mouth's
/// centre and backward; −1, the contraction, pulls toward the centre and forward), falling
/// off from the lip margin across the ring and faded in from the outer contour. Arbitrary
/// magnitude: the response is scaled to [`FaceRig::force_target`](crate::FaceRig::force_target).
pub(crate) fn sphincter_traction(
    shell: &Shell,
    loops: &FaceLoops,
    boxes: &FeatureBoxes,
    mm_per_unit: f64,
    muscle: &Muscle,
) -> Vec<(u32, DVec3)> {
    let mouth = mouth_xy(shell, loops);
    let centre = boxes.mouth.center();
    let contour = loop_xy(&shell.vertices, &loops.face);
    let ring = SPHINCTER_RING_MM / mm_per_unit;
    muscle
        .elements()
        .map(|e| {
            let c = shell.centroid(e as usize).truncate();
            let outward = (c - centre).normalize_or_zero();
            let w = band_weight(distance_to_loop(c, &mouth), ring)
                * contour_weight(
                    distance_to_loop(c, &contour),
                    CONTOUR_TAPER_MM / mm_per_unit,
                );
            let t = DVec3::new(outward.x, outward.y, -SPHINCTER_FORWARD);
            (e, t * w)
        })
        .collect()
}

/// Scales a response to a force-driven control so that its largest front-surface displacement
/// (`front` = the front vertices' displacements) is `target`; returns the factor (1 for a
/// response that does not move the front).
///
/// ```
/// use glam::DVec3;
/// let front = [DVec3::new(0.0, 2.0, 0.0), DVec3::new(1.0, 0.0, 0.0)];
/// assert_eq!(face_prep::force_controls::scale_to_target(&front, 0.5), 0.25);
/// ```
pub fn scale_to_target(front: &[DVec3], target: f64) -> f64 {
    let peak = front.iter().map(|u| u.length()).fold(0.0, f64::max);
    if peak > 0.0 && peak.is_finite() {
        target / peak
    } else {
        1.0
    }
}
