//! The modiolus: the knot of interlacing fibres just lateral of each mouth corner, where
//! zygomaticus major, levator and depressor anguli oris, risorius and buccinator insert and
//! the orbicularis oris's fibres end (Gray's Anatomy, 42nd ed., ch. 29; Parke & Waters,
//! *Computer Facial Animation*, 2nd ed., §3.5). It is dense and moves as one: the corners of
//! both lips go with it.
//!
//! In the anatomical model a force-driven band muscle whose insertion lies in the modiolus
//! ([`FaceRig::modiolus_pin`](crate::FaceRig::modiolus_pin)) moves it rigidly: in that
//! muscle's response the front elements within [`MODIOLUS_RADIUS_MM`] of the mouth corner
//! ([`FaceRig::modiolus_elements`](crate::FaceRig::modiolus_elements)) translate together by
//! the muscle's shortening, `max_strain × length`, toward its origin (along the skin,
//! [`SKIN_STEP_MM`]); everything else follows through the elastic solve. The elements stay
//! traction-type in the shared system (free in every other response); the pin is added per
//! response by superposing unit-traction responses of the modiolus elements (facebem's solve).
//!
//! Why: as a plain traction the pull's largest motion sat at the commissure, where the lips'
//! knife edges meet like a crack tip, and depended on the few elements there. The corner moved
//! 9.2 mm on the left of ICT 2500's copy and 13.7 mm on its right, 13.7 mm on MediaPipe and
//! 9.5 mm on MediaPipe subdivided 1 → 4. Pinned, they move 12.7–13.8 mm.
//!
//! ```
//! use face_prep::{FaceRig, MuscleKind, RigParams, Side, load_face};
//! let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
//!     .join("../../assets/mediapipe_canonical_4loop.obj");
//! let rig = FaceRig::build(&load_face(&path).unwrap(), &RigParams::default()).unwrap();
//! let k = rig.muscle_index(MuscleKind::ZygomaticusMajorL).unwrap();
//! let pin = rig.modiolus_pin(k).unwrap();
//! assert_eq!(pin.side, Side::Left);
//! // Full contraction is slider −1: the corner moves up (+y) and out (+x).
//! assert!(pin.displacement.x < 0.0 && pin.displacement.y < 0.0);
//! assert!(!rig.modiolus_elements(Side::Left).is_empty());
//! ```

use glam::{DVec2, DVec3};

use crate::controls::anatomy::Landmarks;
use crate::controls::force_controls::is_force_control;
use crate::controls::muscle_kind::{Generator, Side, attachment};
use crate::controls::muscle_model::MuscleModel;
use crate::controls::rig_parts::RigParts;
use crate::frame::features::FeatureBoxes;
use crate::frame::topology::triangle_area;
use crate::shell::{ElementTag, Shell};

/// Radius of the modiolus, mm, around the mouth corner: it spans about 10–12 mm of skin
/// lateral of the commissure (Gray's Anatomy, ch. 29). Elements whose centroid lies within it
/// move together.
pub const MODIOLUS_RADIUS_MM: f64 = 6.0;

/// How far along the muscle, mm, the skin's depth is read for the direction a pin moves in:
/// the muscle's direction in the front plane, sloping with the skin over this distance (the
/// depth a smooth average over [`DEPTH_RADIUS_MM`] at each end). Regressions, on ICT 2500's
/// copies (not mirror-symmetric): in the plane of each side's own modiolus elements the two
/// sides' pulls came out 1.2 mm apart at the corners; along the straight line to the origin's
/// skin the risorius (origin 0.75 interocular distances out) went deep into the face, 2.5 /
/// 4.2 mm apart; with the depth a plain mean over 6–8 mm discs, 1.3 mm apart on the collapse
/// copy (risorius) or the remeshed one (zygomaticus); read at the point itself, the corner
/// lies over the mouth's hole and the pull stayed in the face plane (captured-smile cosine
/// 0.76 against 0.86). Here every pinned muscle mirrors within 0.5 mm on both copies.
pub const SKIN_STEP_MM: f64 = 15.0;

/// Radius, mm, of the skin whose depth is averaged at each end of [`SKIN_STEP_MM`], weighted
/// by area and a raised cosine of the distance.
pub const DEPTH_RADIUS_MM: f64 = 12.0;

/// A muscle's hold on the modiolus at slider = +1 (the linear opposite of full contraction).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModiolusPin {
    /// Which modiolus (the face's left or right mouth corner).
    pub side: Side,
    /// Displacement of every modiolus element at slider = +1, rig units, canonical frame.
    pub displacement: DVec3,
}

/// Centre of the modiolus on `side` (the mouth box's corner at the mouth's centre height,
/// canonical x-y); `None` for [`Side::Center`].
pub(crate) fn modiolus_centre(boxes: &FeatureBoxes, side: Side) -> Option<DVec2> {
    let l = Landmarks::of(boxes);
    let x = match side {
        Side::Left => l.mouth.x + l.mouth_half_width,
        Side::Right => l.mouth.x - l.mouth_half_width,
        Side::Center => return None,
    };
    Some(DVec2::new(x, l.mouth.y))
}

/// The front elements of `shell` (not in `skull`, which is sorted) whose centroid lies within
/// [`MODIOLUS_RADIUS_MM`] of the modiolus centre on `side`, in element order; empty for
/// [`Side::Center`].
pub(crate) fn modiolus_elements(
    shell: &Shell,
    boxes: &FeatureBoxes,
    skull: &[u32],
    mm_per_unit: f64,
    side: Side,
) -> Vec<u32> {
    let Some(centre) = modiolus_centre(boxes, side) else {
        return Vec::new();
    };
    let radius = MODIOLUS_RADIUS_MM / mm_per_unit;
    (0..shell.element_count())
        .filter(|&e| shell.tags[e] == ElementTag::Front)
        .filter(|&e| skull.binary_search(&(e as u32)).is_err())
        .filter(|&e| shell.centroid(e).truncate().distance(centre) < radius)
        .map(|e| e as u32)
        .collect()
}

/// How control `k` moves the modiolus: for a force-driven band muscle of the anatomical
/// model whose insertion lies within [`MODIOLUS_RADIUS_MM`] of a modiolus centre, the
/// modiolus's translation at slider = +1 (its shortening, `max_strain × strength × length`,
/// away from the origin along the skin); `None` for every other control.
pub(crate) fn modiolus_pin(rig: RigParts<'_>, k: usize) -> Option<ModiolusPin> {
    if rig.model != MuscleModel::Anatomical || !is_force_control(rig.model, rig.muscles, k) {
        return None;
    }
    let kind = rig.muscles.get(k)?.kind?;
    if !matches!(kind.generator(), Generator::Force(_)) {
        return None;
    }
    let att = attachment(kind, rig.boxes)?;
    let mpu = rig.mm_per_unit;
    let side = [Side::Left, Side::Right].into_iter().find(|&s| {
        modiolus_centre(rig.boxes, s)
            .is_some_and(|c| c.distance(att.insertion) * mpu < MODIOLUS_RADIUS_MM)
    })?;
    let elements = modiolus_elements(rig.shell, rig.boxes, rig.skull, mpu, side);
    // Along the skin: the muscle's direction in the front plane, with the depth the
    // surface drops over its first SKIN_STEP_MM toward the origin.
    let pull = att.origin - att.insertion;
    let step = pull.normalize_or_zero() * (SKIN_STEP_MM / mpu);
    let depth = match (
        front_depth(rig.shell, mpu, att.insertion + step),
        front_depth(rig.shell, mpu, att.insertion),
    ) {
        (Some(there), Some(here)) => there - here,
        _ => 0.0,
    };
    let along_skin = step.extend(depth).normalize_or_zero();
    let shortening = att.max_strain * rig.anatomical.strength * pull.length();
    if elements.is_empty() || along_skin == DVec3::ZERO || shortening <= 0.0 {
        return None;
    }
    Some(ModiolusPin {
        side,
        displacement: -along_skin * shortening,
    })
}

/// Mean depth (canonical z) of the front surface of `shell` around `at` (canonical x-y): the
/// front elements' centroid depths weighted by their area and a raised cosine of their
/// distance from `at`, 1 there and 0 at [`DEPTH_RADIUS_MM`] (smooth, so how a copy's elements
/// fall across the radius hardly matters); `None` where no element is that close.
fn front_depth(shell: &Shell, mm_per_unit: f64, at: DVec2) -> Option<f64> {
    let radius = DEPTH_RADIUS_MM / mm_per_unit;
    let (mut z, mut weight) = (0.0, 0.0);
    for e in 0..shell.element_count() {
        let c = shell.centroid(e);
        let d = c.truncate().distance(at);
        if shell.tags[e] != ElementTag::Front || d >= radius {
            continue;
        }
        let area = triangle_area(shell.triangles[e].map(|v| shell.vertices[v as usize]));
        let w = area * (0.5 + 0.5 * (std::f64::consts::PI * d / radius).cos());
        z += c.z * w;
        weight += w;
    }
    (weight > 0.0).then(|| z / weight)
}
