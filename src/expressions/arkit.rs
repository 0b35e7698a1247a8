//! Apple ARKit's 52 blendshape names (`ARFaceAnchor.BlendShapeLocation`, spelled as the Swift
//! constants, e.g. `mouthSmileLeft`, the spelling glTF/three.js avatars use) and facebem's
//! definition of the 43 a face without eyeballs and tongue can make.
//!
//! ARKit's `…Left` is the subject's own left (Apple: "the left eyebrow" of the face being
//! tracked), which is facebem's `_l`. Each definition is a slider combination of control ids
//! (−1 = full activation, see [`super::AGREED_CONTROL_IDS`]) with its FACS action units; Left
//! and Right are exact mirrors (tested). Where a FACS unit has no muscle of its own in the rig
//! the nearest is used and the description says so. Unpaired controls (orbicularis oris,
//! procerus, cheek puff) act on both sides, so e.g. `mouthPressLeft` differs from
//! `mouthPressRight` only by its paired part.
//!
//! Calibration (issue 33): the weights of 31 of the 43 were fitted once, on the ICT narrow
//! face, to ICT-FaceKit's captured shape of the same name by bounded linear least squares
//! (each control contracting in [−1, 0]; a few named antagonists released up to +0.5; a
//! `…Left` fitted to both sides' captures, its mirror being `…Right`; one weight per muscle
//! pair for a target without a side) and are used unchanged on every face
//! ([`Definition::Fitted`]; a rig without one of the fit's controls, such as the thesis
//! model's ten muscles, gets the hand-made recipe kept beside it). The method, and why the
//! other twelve keep their hand-made recipes (the jaw's four are kinematic, a blink must close
//! the lid, mouthClose is a corrective over the open jaw, and the fitted brow lowerer, pucker
//! and sideways mouth failed the standing checks on other faces), are in
//! `crates/tools/src/bin/fit_recipes.rs`, which prints the table of cosines and generates
//! `arkit_fitted.rs`. Only these weights come from the capture: no captured displacement
//! enters a target.

use super::{Definition, NameSet, NamedExpression, arkit_fitted};

/// ARKit's raw blendshape location string of `name` (one of [`NAMES`], any ASCII case): the
/// string `ARFaceAnchor.BlendShapeLocation` holds and that Live Link Face, Face Cap and many
/// engines send, `_L` / `_R` for a side (`eyeBlink_L`, `mouthSmile_R`). The jaw's and the
/// mouth's sideways moves are directions, not sides, and keep their names (`jawLeft`,
/// `mouthRight`). `None` for a name that is not ARKit's.
///
/// ```
/// use facebem::expressions::arkit::raw_name;
/// assert_eq!(raw_name("eyeBlinkLeft").as_deref(), Some("eyeBlink_L"));
/// assert_eq!(raw_name("mouthSmileRight").as_deref(), Some("mouthSmile_R"));
/// assert_eq!(raw_name("jawLeft").as_deref(), Some("jawLeft"));
/// assert_eq!(raw_name("browInnerUp").as_deref(), Some("browInnerUp"));
/// assert_eq!(raw_name("happy"), None);
/// ```
pub fn raw_name(name: &str) -> Option<String> {
    let name = NAMES.iter().find(|n| n.eq_ignore_ascii_case(name.trim()))?;
    if matches!(*name, "jawLeft" | "jawRight" | "mouthLeft" | "mouthRight") {
        return Some(name.to_string());
    }
    Some(if let Some(stem) = name.strip_suffix("Left") {
        format!("{stem}_L")
    } else if let Some(stem) = name.strip_suffix("Right") {
        format!("{stem}_R")
    } else {
        name.to_string()
    })
}

/// The ARKit name (as in [`NAMES`]) whose raw location string ([`raw_name`]) is `raw`, ignoring
/// ASCII case and surrounding spaces.
///
/// ```
/// use facebem::expressions::arkit::from_raw;
/// assert_eq!(from_raw("eyeBlink_L"), Some("eyeBlinkLeft"));
/// assert_eq!(from_raw(" MOUTHSMILE_R "), Some("mouthSmileRight"));
/// assert_eq!(from_raw("eyeBlink_X"), None);
/// ```
pub fn from_raw(raw: &str) -> Option<&'static str> {
    let raw = raw.trim();
    NAMES
        .iter()
        .copied()
        .find(|n| raw_name(n).is_some_and(|r| r.eq_ignore_ascii_case(raw)))
}

/// All 52 ARKit names in Apple's order (alphabetical, as `ARFaceAnchor.h` lists them).
pub const NAMES: [&str; 52] = [
    "browDownLeft",
    "browDownRight",
    "browInnerUp",
    "browOuterUpLeft",
    "browOuterUpRight",
    "cheekPuff",
    "cheekSquintLeft",
    "cheekSquintRight",
    "eyeBlinkLeft",
    "eyeBlinkRight",
    "eyeLookDownLeft",
    "eyeLookDownRight",
    "eyeLookInLeft",
    "eyeLookInRight",
    "eyeLookOutLeft",
    "eyeLookOutRight",
    "eyeLookUpLeft",
    "eyeLookUpRight",
    "eyeSquintLeft",
    "eyeSquintRight",
    "eyeWideLeft",
    "eyeWideRight",
    "jawForward",
    "jawLeft",
    "jawOpen",
    "jawRight",
    "mouthClose",
    "mouthDimpleLeft",
    "mouthDimpleRight",
    "mouthFrownLeft",
    "mouthFrownRight",
    "mouthFunnel",
    "mouthLeft",
    "mouthLowerDownLeft",
    "mouthLowerDownRight",
    "mouthPressLeft",
    "mouthPressRight",
    "mouthPucker",
    "mouthRight",
    "mouthRollLower",
    "mouthRollUpper",
    "mouthShrugLower",
    "mouthShrugUpper",
    "mouthSmileLeft",
    "mouthSmileRight",
    "mouthStretchLeft",
    "mouthStretchRight",
    "mouthUpperUpLeft",
    "mouthUpperUpRight",
    "noseSneerLeft",
    "noseSneerRight",
    "tongueOut",
];

const fn e(
    name: &'static str,
    action_units: &'static str,
    description: &'static str,
    terms: &'static [(&'static str, f64)],
) -> NamedExpression {
    NamedExpression {
        name,
        set: NameSet::Arkit,
        action_units,
        description,
        definition: Definition::Terms(terms),
    }
}

/// A recipe with fitted weights ([`Definition::Fitted`]) and its hand-made one for rigs that
/// lack a control the fit uses.
const fn fitted(
    name: &'static str,
    action_units: &'static str,
    description: &'static str,
    terms: &'static [(&'static str, f64)],
    fallback: &'static [(&'static str, f64)],
) -> NamedExpression {
    NamedExpression {
        definition: Definition::Fitted { terms, fallback },
        ..e(name, action_units, description, fallback)
    }
}

/// facebem's definition of every ARKit name except the eight `eyeLook*` and `tongueOut`, in
/// Apple's order.
pub const EXPRESSIONS: [NamedExpression; 43] = [
    e(
        "browDownLeft",
        "AU4 (left)",
        "inner brow down and in (corrugator); frontalis relaxed +0.5 pushes the whole brow down",
        &[("corrugator_supercilii_l", -1.0), ("frontalis_l", 0.5)],
    ),
    e(
        "browDownRight",
        "AU4 (right)",
        "inner brow down and in (corrugator); frontalis relaxed +0.5 pushes the whole brow down",
        &[("corrugator_supercilii_r", -1.0), ("frontalis_r", 0.5)],
    ),
    fitted(
        "browInnerUp",
        "AU1",
        "inner brows raised (frontalis; its medial part is not a separate control); weights fitted to the captured shape",
        arkit_fitted::BROW_INNER_UP,
        &[("frontalis_l", -0.45), ("frontalis_r", -0.45)],
    ),
    fitted(
        "browOuterUpLeft",
        "AU2 (left)",
        "left brow raised (frontalis) with the upper lid (levator palpebrae); weights fitted to the captured shape",
        arkit_fitted::BROW_OUTER_UP_LEFT,
        &[("frontalis_l", -0.6)],
    ),
    fitted(
        "browOuterUpRight",
        "AU2 (right)",
        "right brow raised (frontalis) with the upper lid (levator palpebrae); weights fitted to the captured shape",
        arkit_fitted::BROW_OUTER_UP_RIGHT,
        &[("frontalis_r", -0.6)],
    ),
    fitted(
        "cheekPuff",
        "AU34",
        "pressure inside the mouth puffs the cheeks out; the lips, held closed (orbicularis oris, mentalis), are pushed forward; weights fitted to the captured shape",
        arkit_fitted::CHEEK_PUFF,
        &[("cheek_puff", -1.0)],
    ),
    fitted(
        "cheekSquintLeft",
        "AU6 (left)",
        "left cheek and lower lid raised (orbicularis oculi, orbital part); weights fitted to the captured shape",
        arkit_fitted::CHEEK_SQUINT_LEFT,
        &[("orbicularis_oculi_orbital_l", -1.0)],
    ),
    fitted(
        "cheekSquintRight",
        "AU6 (right)",
        "right cheek and lower lid raised (orbicularis oculi, orbital part); weights fitted to the captured shape",
        arkit_fitted::CHEEK_SQUINT_RIGHT,
        &[("orbicularis_oculi_orbital_r", -1.0)],
    ),
    e(
        "eyeBlinkLeft",
        "AU45 (left)",
        "left upper lid closed onto the lower lid",
        &[("orbicularis_oculi_palpebral_l", -1.0)],
    ),
    e(
        "eyeBlinkRight",
        "AU45 (right)",
        "right upper lid closed onto the lower lid",
        &[("orbicularis_oculi_palpebral_r", -1.0)],
    ),
    fitted(
        "eyeSquintLeft",
        "AU7 (left)",
        "left lids tightened: lower lid and the cheek below it up (orbicularis oculi); weights fitted to the captured shape",
        arkit_fitted::EYE_SQUINT_LEFT,
        &[
            ("orbicularis_oculi_orbital_l", -0.6),
            ("orbicularis_oculi_palpebral_l", -0.25),
        ],
    ),
    fitted(
        "eyeSquintRight",
        "AU7 (right)",
        "right lids tightened: lower lid and the cheek below it up (orbicularis oculi); weights fitted to the captured shape",
        arkit_fitted::EYE_SQUINT_RIGHT,
        &[
            ("orbicularis_oculi_orbital_r", -0.6),
            ("orbicularis_oculi_palpebral_r", -0.25),
        ],
    ),
    fitted(
        "eyeWideLeft",
        "AU5 (left)",
        "left upper lid raised (levator palpebrae); weights fitted to the captured shape",
        arkit_fitted::EYE_WIDE_LEFT,
        &[("levator_palpebrae_l", -1.0)],
    ),
    fitted(
        "eyeWideRight",
        "AU5 (right)",
        "right upper lid raised (levator palpebrae); weights fitted to the captured shape",
        arkit_fitted::EYE_WIDE_RIGHT,
        &[("levator_palpebrae_r", -1.0)],
    ),
    e(
        "jawForward",
        "AU29",
        "jaw thrust forward",
        &[("jaw_forward", -1.0)],
    ),
    e(
        "jawLeft",
        "AU30 (left)",
        "jaw shifted toward the subject's left",
        &[("jaw_lateral", -1.0)],
    ),
    e(
        "jawOpen",
        "AU26 + AU27",
        "jaw rotated open about the temporomandibular axis",
        &[("jaw_open", -1.0)],
    ),
    e(
        "jawRight",
        "AU30 (right)",
        "jaw shifted toward the subject's right",
        &[("jaw_lateral", 1.0)],
    ),
    fitted(
        "mouthClose",
        "AU24 (lips together against an open jaw)",
        "lower lip held up against the upper one (lip seal): closes the lips when combined with jawOpen; without the seal, upper lip down and lower lip up",
        &[("lip_seal", -1.0)],
        &[
            ("levator_labii_superioris_l", 0.4),
            ("levator_labii_superioris_r", 0.4),
            ("depressor_labii_inferioris_l", 0.5),
            ("depressor_labii_inferioris_r", 0.5),
            ("mentalis_l", -0.3),
            ("mentalis_r", -0.3),
            ("orbicularis_oris_upper", -0.2),
            ("orbicularis_oris_lower", -0.2),
        ],
    ),
    fitted(
        "mouthDimpleLeft",
        "AU14 (left)",
        "left mouth corner drawn back and in (buccinator, levator anguli oris, mentalis); weights fitted to the captured shape",
        arkit_fitted::MOUTH_DIMPLE_LEFT,
        &[("buccinator_l", -1.0)],
    ),
    fitted(
        "mouthDimpleRight",
        "AU14 (right)",
        "right mouth corner drawn back and in (buccinator, levator anguli oris, mentalis); weights fitted to the captured shape",
        arkit_fitted::MOUTH_DIMPLE_RIGHT,
        &[("buccinator_r", -1.0)],
    ),
    fitted(
        "mouthFrownLeft",
        "AU15 (left)",
        "left mouth corner pulled down (depressor anguli oris, mentalis); weights fitted to the captured shape",
        arkit_fitted::MOUTH_FROWN_LEFT,
        &[("depressor_anguli_oris_l", -1.0)],
    ),
    fitted(
        "mouthFrownRight",
        "AU15 (right)",
        "right mouth corner pulled down (depressor anguli oris, mentalis); weights fitted to the captured shape",
        arkit_fitted::MOUTH_FROWN_RIGHT,
        &[("depressor_anguli_oris_r", -1.0)],
    ),
    fitted(
        "mouthFunnel",
        "AU22 + AU25",
        "lips funnelled forward and parted (orbicularis oris, the lower lip's depressor); weights fitted to the captured shape",
        arkit_fitted::MOUTH_FUNNEL,
        &[
            ("orbicularis_oris_upper", -0.6),
            ("orbicularis_oris_lower", -0.6),
            ("levator_labii_superioris_l", -0.2),
            ("levator_labii_superioris_r", -0.2),
            ("depressor_labii_inferioris_l", -0.2),
            ("depressor_labii_inferioris_r", -0.2),
        ],
    ),
    e(
        "mouthLeft",
        "no AU (lips sideways)",
        "both mouth corners toward the subject's left: left risorius and buccinator pull, right \
         ones relax",
        &[
            ("risorius_l", -0.5),
            ("buccinator_l", -0.3),
            ("risorius_r", 0.5),
            ("buccinator_r", 0.3),
        ],
    ),
    fitted(
        "mouthLowerDownLeft",
        "AU16 (left)",
        "left half of the lower lip pulled down (depressor labii inferioris); weights fitted to the captured shape",
        arkit_fitted::MOUTH_LOWER_DOWN_LEFT,
        &[("depressor_labii_inferioris_l", -1.0)],
    ),
    fitted(
        "mouthLowerDownRight",
        "AU16 (right)",
        "right half of the lower lip pulled down (depressor labii inferioris); weights fitted to the captured shape",
        arkit_fitted::MOUTH_LOWER_DOWN_RIGHT,
        &[("depressor_labii_inferioris_r", -1.0)],
    ),
    fitted(
        "mouthPressLeft",
        "AU24 (left)",
        "lips pressed together on the left (mentalis pushes the lower lip up); weights fitted to the captured shape",
        arkit_fitted::MOUTH_PRESS_LEFT,
        &[
            ("orbicularis_oris_upper", -0.3),
            ("orbicularis_oris_lower", -0.3),
            ("buccinator_l", -0.5),
        ],
    ),
    fitted(
        "mouthPressRight",
        "AU24 (right)",
        "lips pressed together on the right (mentalis pushes the lower lip up); weights fitted to the captured shape",
        arkit_fitted::MOUTH_PRESS_RIGHT,
        &[
            ("orbicularis_oris_upper", -0.3),
            ("orbicularis_oris_lower", -0.3),
            ("buccinator_r", -0.5),
        ],
    ),
    e(
        "mouthPucker",
        "AU18",
        "lips narrowed and pushed forward (orbicularis oris sphincter)",
        &[
            ("orbicularis_oris_upper", -1.0),
            ("orbicularis_oris_lower", -1.0),
        ],
    ),
    e(
        "mouthRight",
        "no AU (lips sideways)",
        "both mouth corners toward the subject's right: right risorius and buccinator pull, left \
         ones relax",
        &[
            ("risorius_r", -0.5),
            ("buccinator_r", -0.3),
            ("risorius_l", 0.5),
            ("buccinator_l", 0.3),
        ],
    ),
    fitted(
        "mouthRollLower",
        "AU28 (lower lip)",
        "lower lip rolled in and the chin raised (mentalis, sphincter), its depressor let go; weights fitted to the captured shape",
        arkit_fitted::MOUTH_ROLL_LOWER,
        &[
            ("orbicularis_oris_lower", -0.7),
            ("depressor_labii_inferioris_l", 0.3),
            ("depressor_labii_inferioris_r", 0.3),
        ],
    ),
    fitted(
        "mouthRollUpper",
        "AU28 (upper lip)",
        "upper lip rolled in (the mouth's corners held, the lower lip's sphincter), its levator let go; weights fitted to the captured shape",
        arkit_fitted::MOUTH_ROLL_UPPER,
        &[
            ("orbicularis_oris_upper", -0.7),
            ("levator_labii_superioris_l", 0.3),
            ("levator_labii_superioris_r", 0.3),
        ],
    ),
    fitted(
        "mouthShrugLower",
        "AU17",
        "chin boss and lower lip pushed up (mentalis); weights fitted to the captured shape",
        arkit_fitted::MOUTH_SHRUG_LOWER,
        &[("mentalis_l", -1.0), ("mentalis_r", -1.0)],
    ),
    fitted(
        "mouthShrugUpper",
        "AU10 (weak) + AU17",
        "upper lip raised (levator labii superioris alaeque nasi); weights fitted to the captured shape",
        arkit_fitted::MOUTH_SHRUG_UPPER,
        &[
            ("levator_labii_superioris_l", -0.4),
            ("levator_labii_superioris_r", -0.4),
            ("mentalis_l", -0.3),
            ("mentalis_r", -0.3),
        ],
    ),
    fitted(
        "mouthSmileLeft",
        "AU12 (left)",
        "left mouth corner pulled up and out (levator anguli oris, buccinator, zygomaticus major) with the cheek raised; weights fitted to the captured shape",
        arkit_fitted::MOUTH_SMILE_LEFT,
        &[("zygomaticus_major_l", -1.0)],
    ),
    fitted(
        "mouthSmileRight",
        "AU12 (right)",
        "right mouth corner pulled up and out (levator anguli oris, buccinator, zygomaticus major) with the cheek raised; weights fitted to the captured shape",
        arkit_fitted::MOUTH_SMILE_RIGHT,
        &[("zygomaticus_major_r", -1.0)],
    ),
    fitted(
        "mouthStretchLeft",
        "AU20 (left)",
        "left corner pulled out and down (depressor anguli oris for the platysma, zygomaticus major); weights fitted to the captured shape",
        arkit_fitted::MOUTH_STRETCH_LEFT,
        &[("risorius_l", -1.0), ("depressor_anguli_oris_l", -0.3)],
    ),
    fitted(
        "mouthStretchRight",
        "AU20 (right)",
        "right corner pulled out and down (depressor anguli oris for the platysma, zygomaticus major); weights fitted to the captured shape",
        arkit_fitted::MOUTH_STRETCH_RIGHT,
        &[("risorius_r", -1.0), ("depressor_anguli_oris_r", -0.3)],
    ),
    fitted(
        "mouthUpperUpLeft",
        "AU10 (left)",
        "left half of the upper lip raised (levator labii superioris); weights fitted to the captured shape",
        arkit_fitted::MOUTH_UPPER_UP_LEFT,
        &[("levator_labii_superioris_l", -1.0)],
    ),
    fitted(
        "mouthUpperUpRight",
        "AU10 (right)",
        "right half of the upper lip raised (levator labii superioris); weights fitted to the captured shape",
        arkit_fitted::MOUTH_UPPER_UP_RIGHT,
        &[("levator_labii_superioris_r", -1.0)],
    ),
    fitted(
        "noseSneerLeft",
        "AU9 (left)",
        "left side of the nose wrinkled and the upper lip lifted (levator labii superioris, orbicularis oculi, procerus); weights fitted to the captured shape",
        arkit_fitted::NOSE_SNEER_LEFT,
        &[("levator_labii_superioris_alaeque_nasi_l", -1.0)],
    ),
    fitted(
        "noseSneerRight",
        "AU9 (right)",
        "right side of the nose wrinkled and the upper lip lifted (levator labii superioris, orbicularis oculi, procerus); weights fitted to the captured shape",
        arkit_fitted::NOSE_SNEER_RIGHT,
        &[("levator_labii_superioris_alaeque_nasi_r", -1.0)],
    ),
];
