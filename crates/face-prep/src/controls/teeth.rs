//! The teeth: the deep layer of tissue behind the lips rests on the dental arch and slides on
//! it. Those back elements are sliding contacts in every response
//! ((`bem_core::ElementKind::Sliding`): no displacement along their normal, no tangential
//! traction): a muscle pulling the mouth corner moves it along the teeth, not forward off them
//! as a free flap would, and the lower teeth carry the lower lip's deep layer with the jaw.
//!
//! The arch is an ellipse in the front plane centred on the mouth, reaching
//! [`ARCH_BEYOND_CORNER_IOD`] interocular distances past each mouth corner (the premolars) and
//! [`ARCH_HALF_HEIGHT_H`] eye-to-mouth heights above and below the mouth's centre line (the
//! gums up to the nose base and down to the mentolabial sulcus). Sources: Gray's Anatomy
//! (41st ed.), ch. 31 (the lips and cheeks lie on the vestibule of the dental arches).
//!
//! ```
//! use face_prep::{FaceRig, RigParams, load_face};
//! let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
//!     .join("../../assets/mediapipe_canonical_4loop.obj");
//! let rig = FaceRig::build(&load_face(&path).unwrap(), &RigParams::default()).unwrap();
//! let sliding = rig.sliding_elements();
//! assert!(sliding.len() > 10);
//! assert!(sliding.iter().all(|&e| rig.shell.tags[e as usize] == face_prep::ElementTag::Back));
//! assert!(sliding.iter().all(|e| rig.skull.binary_search(e).is_err()));
//! ```

use std::collections::HashSet;

use glam::DVec2;

use crate::controls::anatomy::Landmarks;
use crate::controls::force_controls::{is_force_control, mouth_xy};
use crate::controls::muscle_model::MuscleModel;
use crate::controls::rig_parts::RigParts;
use crate::frame::features::FeatureBoxes;
use crate::shell::{ElementTag, Shell};

/// How far the dental arch reaches past each mouth corner, in interocular distances.
pub const ARCH_BEYOND_CORNER_IOD: f64 = 0.15;

/// The lips' free margin, mm from the mouth loop: the deep layer this close to the opening
/// curls off the teeth and is not sliding on them.
pub(crate) const LIP_MARGIN_MM: f64 = 4.0;

/// Half the height of the dental arch region, in eye-to-mouth heights.
pub const ARCH_HALF_HEIGHT_H: f64 = 0.3;

/// Whether a front-plane point lies over the dental arch ([`ARCH_BEYOND_CORNER_IOD`],
/// [`ARCH_HALF_HEIGHT_H`]).
///
/// ```
/// use face_prep::{Box2, FeatureBoxes};
/// use face_prep::anatomy::Landmarks;
/// use face_prep::teeth::over_dental_arch;
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
/// assert!(over_dental_arch(l.mouth, &l));
/// assert!(!over_dental_arch(l.eye_l, &l));
/// ```
pub fn over_dental_arch(p: DVec2, l: &Landmarks) -> bool {
    let ax = l.mouth_half_width + ARCH_BEYOND_CORNER_IOD * l.iod;
    let ay = ARCH_HALF_HEIGHT_H * l.h;
    if ax <= 0.0 || ay <= 0.0 {
        return false;
    }
    ((p.x - l.mouth.x) / ax).powi(2) + ((p.y - l.mouth.y) / ay).powi(2) <= 1.0
}

/// Back elements sliding on the teeth (anatomical model; empty in the thesis model): over
/// the dental arch ([`over_dental_arch`]), neither skull nor an element of a
/// displacement-driven control. Sorted.
pub(crate) fn sliding_elements(rig: RigParts<'_>) -> Vec<u32> {
    if rig.model != MuscleModel::Anatomical {
        return Vec::new();
    }
    let mut prescribed: HashSet<u32> = rig.skull.iter().copied().collect();
    for (k, m) in rig.muscles.iter().enumerate() {
        if !is_force_control(rig.model, rig.muscles, k) {
            prescribed.extend(m.elements());
        }
    }
    let l = Landmarks::of(rig.boxes);
    let mouth = mouth_xy(rig.shell, rig.loops);
    let margin = LIP_MARGIN_MM / rig.mm_per_unit;
    (0..rig.shell.element_count() as u32)
        .filter(|&e| rig.shell.tags[e as usize] == ElementTag::Back)
        .filter(|e| !prescribed.contains(e))
        .filter(|&e| {
            let c = rig.shell.centroid(e as usize).truncate();
            over_dental_arch(c, &l)
                && crate::controls::muscle_model::distance_to_loop(c, &mouth) > margin
        })
        .collect()
}

/// Whether sliding element `e` of `shell` rests on the lower teeth (below the mouth's centre
/// line, from `boxes`), which move with the jaw.
pub(crate) fn on_lower_teeth(shell: &Shell, boxes: &FeatureBoxes, e: u32) -> bool {
    shell.centroid(e as usize).y < boxes.mouth.center().y
}
