//! VRM 1.0 expression presets (`VRMC_vrm.expressions.preset`) and facebem's definition of the
//! 14 a face without eyeballs can make (all but `lookUp`, `lookDown`, `lookLeft`, `lookRight`).
//!
//! The emotions `happy`, `angry`, `sad`, `surprised` and `neutral` are facebem's presets of the
//! same name ([`crate::expressions::presets`]); `relaxed` (VRM 0.x `fun`) is defined here. The visemes follow
//! the VRM names' vowels (`aa` as in "father", `ih` Japanese い "i", `ou` う "u", `ee` え "e",
//! `oh` お "o"): each is a jaw opening plus a lip shape. `blinkLeft` closes the avatar's own left
//! eye (VRM models face +z with their left at +x, as facebem's canonical frame): facebem's `_l`.

use super::{Definition, NameSet, NamedExpression};

/// All 18 VRM 1.0 preset names, in the specification's order (emotions, lip sync, blink, gaze,
/// other).
pub const NAMES: [&str; 18] = [
    "happy",
    "angry",
    "sad",
    "relaxed",
    "surprised",
    "aa",
    "ih",
    "ou",
    "ee",
    "oh",
    "blink",
    "blinkLeft",
    "blinkRight",
    "lookUp",
    "lookDown",
    "lookLeft",
    "lookRight",
    "neutral",
];

const fn preset(name: &'static str, description: &'static str) -> NamedExpression {
    NamedExpression {
        name,
        set: NameSet::Vrm,
        action_units: "",
        description,
        definition: Definition::Preset(name),
    }
}

const fn e(
    name: &'static str,
    action_units: &'static str,
    description: &'static str,
    terms: &'static [(&'static str, f64)],
) -> NamedExpression {
    NamedExpression {
        name,
        set: NameSet::Vrm,
        action_units,
        description,
        definition: Definition::Terms(terms),
    }
}

/// facebem's definition of the 14 VRM presets it makes, in the specification's order.
pub const EXPRESSIONS: [NamedExpression; 14] = [
    preset("happy", "facebem's happy preset"),
    preset("angry", "facebem's angry preset"),
    preset("sad", "facebem's sad preset"),
    e(
        "relaxed",
        "AU6 (weak) + AU12 (weak) + AU43 (slight)",
        "content: a light smile, cheeks a little up, lids a little lowered",
        &[
            ("zygomaticus_major_l", -0.4),
            ("zygomaticus_major_r", -0.4),
            ("orbicularis_oculi_orbital_l", -0.2),
            ("orbicularis_oculi_orbital_r", -0.2),
            ("orbicularis_oculi_palpebral_l", -0.2),
            ("orbicularis_oculi_palpebral_r", -0.2),
        ],
    ),
    preset("surprised", "facebem's surprised preset"),
    e(
        "aa",
        "AU25 + AU26",
        "viseme 'aa': jaw well open, lower lip down, upper lip a little up",
        &[
            ("jaw_open", -0.7),
            ("depressor_labii_inferioris_l", -0.3),
            ("depressor_labii_inferioris_r", -0.3),
            ("levator_labii_superioris_l", -0.2),
            ("levator_labii_superioris_r", -0.2),
        ],
    ),
    e(
        "ih",
        "AU20 + AU25 (+ AU12 weak)",
        "viseme 'i': jaw nearly closed, lips spread wide",
        &[
            ("jaw_open", -0.15),
            ("risorius_l", -0.6),
            ("risorius_r", -0.6),
            ("zygomaticus_major_l", -0.2),
            ("zygomaticus_major_r", -0.2),
            ("levator_labii_superioris_l", -0.2),
            ("levator_labii_superioris_r", -0.2),
        ],
    ),
    e(
        "ou",
        "AU18 + AU25",
        "viseme 'u': lips puckered forward, jaw slightly open",
        &[
            ("jaw_open", -0.15),
            ("orbicularis_oris_upper", -0.8),
            ("orbicularis_oris_lower", -0.8),
        ],
    ),
    e(
        "ee",
        "AU20 + AU25 + AU26",
        "viseme 'e': jaw half open, lips spread, lips parted",
        &[
            ("jaw_open", -0.35),
            ("risorius_l", -0.4),
            ("risorius_r", -0.4),
            ("levator_labii_superioris_l", -0.2),
            ("levator_labii_superioris_r", -0.2),
            ("depressor_labii_inferioris_l", -0.2),
            ("depressor_labii_inferioris_r", -0.2),
        ],
    ),
    e(
        "oh",
        "AU22 + AU26",
        "viseme 'o': jaw open, lips rounded",
        &[
            ("jaw_open", -0.5),
            ("orbicularis_oris_upper", -0.5),
            ("orbicularis_oris_lower", -0.5),
        ],
    ),
    e(
        "blink",
        "AU45",
        "both upper lids closed onto the lower lids",
        &[
            ("orbicularis_oculi_palpebral_l", -1.0),
            ("orbicularis_oculi_palpebral_r", -1.0),
        ],
    ),
    e(
        "blinkLeft",
        "AU45 (left)",
        "the avatar's left upper lid closed",
        &[("orbicularis_oculi_palpebral_l", -1.0)],
    ),
    e(
        "blinkRight",
        "AU45 (right)",
        "the avatar's right upper lid closed",
        &[("orbicularis_oculi_palpebral_r", -1.0)],
    ),
    preset("neutral", "every control at rest (a zero target)"),
];
