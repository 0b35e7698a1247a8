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

use super::{Definition, NameSet, NamedExpression};

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
    e(
        "browInnerUp",
        "AU1",
        "both brows raised by the frontalis (its medial part is not a separate control); 0.45 \
         matches the captured ICT browInnerUp's largest motion (6.3 mm) on the ICT face",
        &[("frontalis_l", -0.45), ("frontalis_r", -0.45)],
    ),
    e(
        "browOuterUpLeft",
        "AU2 (left)",
        "left brow raised by the left frontalis; 0.6 matches the captured ICT browOuterUp_L's \
         largest motion (8.6 mm) on the ICT face",
        &[("frontalis_l", -0.6)],
    ),
    e(
        "browOuterUpRight",
        "AU2 (right)",
        "right brow raised by the right frontalis; 0.6 matches the captured ICT browOuterUp_R's \
         largest motion (8.6 mm) on the ICT face",
        &[("frontalis_r", -0.6)],
    ),
    e(
        "cheekPuff",
        "AU34",
        "pressure inside the mouth puffs both cheeks out",
        &[("cheek_puff", -1.0)],
    ),
    e(
        "cheekSquintLeft",
        "AU6 (left)",
        "left cheek and lower lid raised (orbicularis oculi, orbital part)",
        &[("orbicularis_oculi_orbital_l", -1.0)],
    ),
    e(
        "cheekSquintRight",
        "AU6 (right)",
        "right cheek and lower lid raised (orbicularis oculi, orbital part)",
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
    e(
        "eyeSquintLeft",
        "AU7 (left)",
        "left lids tightened: lower lid up, upper lid a quarter down",
        &[
            ("orbicularis_oculi_orbital_l", -0.6),
            ("orbicularis_oculi_palpebral_l", -0.25),
        ],
    ),
    e(
        "eyeSquintRight",
        "AU7 (right)",
        "right lids tightened: lower lid up, upper lid a quarter down",
        &[
            ("orbicularis_oculi_orbital_r", -0.6),
            ("orbicularis_oculi_palpebral_r", -0.25),
        ],
    ),
    e(
        "eyeWideLeft",
        "AU5 (left)",
        "left upper lid raised (levator palpebrae)",
        &[("levator_palpebrae_l", -1.0)],
    ),
    e(
        "eyeWideRight",
        "AU5 (right)",
        "right upper lid raised (levator palpebrae)",
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
    e(
        "mouthClose",
        "AU24 (lips together against an open jaw)",
        "upper lip down, lower lip up and pressed: closes the lips when combined with jawOpen",
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
    e(
        "mouthDimpleLeft",
        "AU14 (left)",
        "left mouth corner drawn back and in (buccinator)",
        &[("buccinator_l", -1.0)],
    ),
    e(
        "mouthDimpleRight",
        "AU14 (right)",
        "right mouth corner drawn back and in (buccinator)",
        &[("buccinator_r", -1.0)],
    ),
    e(
        "mouthFrownLeft",
        "AU15 (left)",
        "left mouth corner pulled down (depressor anguli oris)",
        &[("depressor_anguli_oris_l", -1.0)],
    ),
    e(
        "mouthFrownRight",
        "AU15 (right)",
        "right mouth corner pulled down (depressor anguli oris)",
        &[("depressor_anguli_oris_r", -1.0)],
    ),
    e(
        "mouthFunnel",
        "AU22 + AU25",
        "lips funnelled forward and parted: sphincter with both lips slightly everted",
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
    e(
        "mouthLowerDownLeft",
        "AU16 (left)",
        "left half of the lower lip pulled down",
        &[("depressor_labii_inferioris_l", -1.0)],
    ),
    e(
        "mouthLowerDownRight",
        "AU16 (right)",
        "right half of the lower lip pulled down",
        &[("depressor_labii_inferioris_r", -1.0)],
    ),
    e(
        "mouthPressLeft",
        "AU24 (left)",
        "lips pressed together (orbicularis oris, both sides) with the left corner held back",
        &[
            ("orbicularis_oris_upper", -0.3),
            ("orbicularis_oris_lower", -0.3),
            ("buccinator_l", -0.5),
        ],
    ),
    e(
        "mouthPressRight",
        "AU24 (right)",
        "lips pressed together (orbicularis oris, both sides) with the right corner held back",
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
    e(
        "mouthRollLower",
        "AU28 (lower lip)",
        "lower lip rolled in: sphincter of the lower lip, lower lip pushed up",
        &[
            ("orbicularis_oris_lower", -0.7),
            ("depressor_labii_inferioris_l", 0.3),
            ("depressor_labii_inferioris_r", 0.3),
        ],
    ),
    e(
        "mouthRollUpper",
        "AU28 (upper lip)",
        "upper lip rolled in: sphincter of the upper lip, upper lip pushed down",
        &[
            ("orbicularis_oris_upper", -0.7),
            ("levator_labii_superioris_l", 0.3),
            ("levator_labii_superioris_r", 0.3),
        ],
    ),
    e(
        "mouthShrugLower",
        "AU17",
        "chin boss and lower lip pushed up (mentalis)",
        &[("mentalis_l", -1.0), ("mentalis_r", -1.0)],
    ),
    e(
        "mouthShrugUpper",
        "AU10 (weak) + AU17",
        "upper lip pushed up and out by the raised lower lip",
        &[
            ("levator_labii_superioris_l", -0.4),
            ("levator_labii_superioris_r", -0.4),
            ("mentalis_l", -0.3),
            ("mentalis_r", -0.3),
        ],
    ),
    e(
        "mouthSmileLeft",
        "AU12 (left)",
        "left mouth corner pulled up and out (zygomaticus major)",
        &[("zygomaticus_major_l", -1.0)],
    ),
    e(
        "mouthSmileRight",
        "AU12 (right)",
        "right mouth corner pulled up and out (zygomaticus major)",
        &[("zygomaticus_major_r", -1.0)],
    ),
    e(
        "mouthStretchLeft",
        "AU20 (left)",
        "left corner pulled straight out (risorius), a little down (depressor anguli oris for \
         the platysma)",
        &[("risorius_l", -1.0), ("depressor_anguli_oris_l", -0.3)],
    ),
    e(
        "mouthStretchRight",
        "AU20 (right)",
        "right corner pulled straight out (risorius), a little down (depressor anguli oris for \
         the platysma)",
        &[("risorius_r", -1.0), ("depressor_anguli_oris_r", -0.3)],
    ),
    e(
        "mouthUpperUpLeft",
        "AU10 (left)",
        "left half of the upper lip raised (levator labii superioris)",
        &[("levator_labii_superioris_l", -1.0)],
    ),
    e(
        "mouthUpperUpRight",
        "AU10 (right)",
        "right half of the upper lip raised (levator labii superioris)",
        &[("levator_labii_superioris_r", -1.0)],
    ),
    e(
        "noseSneerLeft",
        "AU9 (left)",
        "left side of the nose wrinkled and the upper lip lifted (levator labii superioris \
         alaeque nasi)",
        &[("levator_labii_superioris_alaeque_nasi_l", -1.0)],
    ),
    e(
        "noseSneerRight",
        "AU9 (right)",
        "right side of the nose wrinkled and the upper lip lifted (levator labii superioris \
         alaeque nasi)",
        &[("levator_labii_superioris_alaeque_nasi_r", -1.0)],
    ),
];
