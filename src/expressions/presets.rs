//! Expression presets: named slider combinations of the rig's standard controls, keyed by
//! control id ([`face_prep::MuscleKind::id`]); a control a preset does not list is 0.
//!
//! Slider convention (`docs/design/controls.md`, "Muscles"): a NEGATIVE value contracts the muscle, a positive one
//! relaxes it (moves the tissue the other way). Each preset says which FACS action units (AU) it
//! stands for. Where the rig lacks the muscle of an AU, the AU is approximated by the closest
//! control the rig has; the approximation is stated next to each preset:
//!
//! - frontalis contraction ≈ AU1 + AU2 (inner and outer brow raiser); AU4 (brow lowerer) is the
//!   corrugator supercilii and procerus, with the frontalis slightly relaxed (on the thesis
//!   model, which has no corrugator, only that relaxation is left);
//! - levator labii superioris ≈ AU10 (upper lip raiser), with some AU9 (nose wrinkler);
//! - zygomaticus major ≈ AU12 (lip corner puller); it also lifts the cheek a little (AU6);
//! - mentalis ≈ AU17 (chin raiser);
//! - depressor labii inferioris ≈ AU16 (lower lip depressor) and, pulling the lower lip down and
//!   out, the lips-part/jaw-drop look of AU25/AU26 and the lip stretch of AU20.
//!
//! ```
//! use facebem::expressions::presets::{self, Preset};
//! use face_prep::MuscleKind;
//! let happy = presets::find("happy").unwrap();
//! assert!(happy.slider(MuscleKind::ZygomaticusMajorL) < 0.0); // contracted
//! assert_eq!(presets::find("hate").unwrap().name, "disgust");
//! ```

use face_prep::MuscleKind;

/// One named expression: a value in [−1, 1] for some of the standard controls (the others 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Preset {
    /// Identifier used by the CLI (`--preset happy`), the viewer and glTF target names.
    pub name: &'static str,
    /// FACS action units this preset stands for.
    pub action_units: &'static str,
    /// One-line description of the combination.
    pub description: &'static str,
    /// `(control id, slider value)` pairs (negative = contract); unlisted controls are 0.
    pub sliders: &'static [(&'static str, f64)],
}

/// Other accepted names for a preset (`alias`, `preset name`).
pub const ALIASES: [(&str, &str); 4] = [
    ("hate", "disgust"),
    ("surprise", "surprised"),
    ("anger", "angry"),
    ("sadness", "sad"),
];

/// All presets, `neutral` first.
pub const ALL: [Preset; 9] = [
    Preset {
        name: "neutral",
        action_units: "AU0",
        description: "every muscle at rest",
        sliders: &[],
    },
    Preset {
        name: "happy",
        action_units: "AU6 + AU12",
        description: "zygomaticus major contracted, cheeks and upper lip slightly raised",
        sliders: &[
            ("levator_labii_superioris_l", -0.2),
            ("levator_labii_superioris_r", -0.2),
            ("zygomaticus_major_l", -0.8),
            ("zygomaticus_major_r", -0.8),
        ],
    },
    Preset {
        name: "smile",
        action_units: "AU12",
        description: "closed-lip smile: zygomaticus major only",
        sliders: &[("zygomaticus_major_l", -0.5), ("zygomaticus_major_r", -0.5)],
    },
    Preset {
        name: "laugh",
        action_units: "AU6 + AU12 + AU25 + AU26",
        description: "full zygomaticus pull, upper lip up, lower lip down, brows slightly up",
        sliders: &[
            ("frontalis_l", -0.2),
            ("frontalis_r", -0.2),
            ("levator_labii_superioris_l", -0.4),
            ("levator_labii_superioris_r", -0.4),
            ("zygomaticus_major_l", -1.0),
            ("zygomaticus_major_r", -1.0),
            ("depressor_labii_inferioris_l", -0.5),
            ("depressor_labii_inferioris_r", -0.5),
        ],
    },
    Preset {
        name: "sad",
        action_units: "AU1 + AU15 + AU17",
        description: "inner brows raised, lip corners pulled down, chin raised: the sum of the \
                      fitted ARKit browInnerUp, mouthFrownLeft and mouthFrownRight (against \
                      the sum of ICT-FaceKit's captures of those: cosine 0.80; the hand-made \
                      preset had 0.35)",
        sliders: &[
            ("frontalis_l", -0.45),
            ("frontalis_r", -0.45),
            ("levator_palpebrae_l", -0.15),
            ("levator_palpebrae_r", -0.15),
            ("depressor_anguli_oris_l", -0.55),
            ("depressor_anguli_oris_r", -0.55),
            ("mentalis_l", -0.4),
            ("mentalis_r", -0.4),
        ],
    },
    Preset {
        name: "angry",
        action_units: "AU4 + AU7 + AU17 + AU24",
        description: "brows down and together (the orbicularis oculi's part over the brow, \
                      corrugator, procerus), lids tightened, cheeks raised, chin raised and lips \
                      pressed: fitted once by least squares (`fit_recipes`) on the ICT face to \
                      the sum of ICT-FaceKit's captured browDown, eyeSquint and mouthPress, left \
                      and right (cosine 0.73; before the brow part 0.59; the hand-made preset \
                      with the upper lip raised had 0.19)",
        sliders: &[
            ("orbicularis_oculi_superior_l", -1.0),
            ("orbicularis_oculi_superior_r", -1.0),
            ("corrugator_supercilii_l", -0.2),
            ("corrugator_supercilii_r", -0.2),
            ("procerus", -0.35),
            ("orbicularis_oculi_orbital_l", -1.0),
            ("orbicularis_oculi_orbital_r", -1.0),
            ("orbicularis_oculi_malar_l", -0.4),
            ("orbicularis_oculi_malar_r", -0.4),
            ("orbicularis_oris_lower", -0.15),
            ("mentalis_l", -1.0),
            ("mentalis_r", -1.0),
        ],
    },
    Preset {
        name: "surprised",
        action_units: "AU1 + AU2 + AU5 + AU26",
        description: "brows fully raised, lower lip dropped",
        sliders: &[
            ("frontalis_l", -1.0),
            ("frontalis_r", -1.0),
            ("mentalis_l", 0.3),
            ("mentalis_r", 0.3),
            ("depressor_labii_inferioris_l", -0.6),
            ("depressor_labii_inferioris_r", -0.6),
        ],
    },
    Preset {
        name: "disgust",
        action_units: "AU9 + AU10 + AU16 + AU17",
        description: "upper lip raised hard, lower lip down and out, brow slightly lowered \
                      (procerus, frontalis relaxed)",
        sliders: &[
            ("frontalis_l", 0.3),
            ("frontalis_r", 0.3),
            ("procerus", -0.5),
            ("levator_labii_superioris_l", -1.0),
            ("levator_labii_superioris_r", -1.0),
            ("mentalis_l", -0.3),
            ("mentalis_r", -0.3),
            ("depressor_labii_inferioris_l", -0.4),
            ("depressor_labii_inferioris_r", -0.4),
        ],
    },
    Preset {
        name: "fear",
        action_units: "AU1 + AU2 + AU4 + AU20 + AU26",
        description: "brows raised, lips stretched and parted",
        sliders: &[
            ("frontalis_l", -0.8),
            ("frontalis_r", -0.8),
            ("zygomaticus_major_l", -0.2),
            ("zygomaticus_major_r", -0.2),
            ("mentalis_l", -0.2),
            ("mentalis_r", -0.2),
            ("depressor_labii_inferioris_l", -0.7),
            ("depressor_labii_inferioris_r", -0.7),
        ],
    },
];

/// Finds a preset by name or alias (case-insensitive, surrounding spaces ignored).
pub fn find(name: &str) -> Option<&'static Preset> {
    let name = name.trim();
    let canonical = ALIASES
        .iter()
        .find(|(alias, _)| alias.eq_ignore_ascii_case(name))
        .map_or(name, |(_, target)| *target);
    ALL.iter().find(|p| p.name.eq_ignore_ascii_case(canonical))
}

/// Names of all presets, in order (for help texts and error messages).
pub fn names() -> Vec<&'static str> {
    ALL.iter().map(|p| p.name).collect()
}

impl Preset {
    /// Slider value of one standard control (0 when the preset does not list it).
    pub fn slider(&self, muscle: MuscleKind) -> f64 {
        self.slider_by_id(muscle.id())
    }

    /// Slider value of the control with id `id` (case-insensitive; 0 when not listed).
    pub fn slider_by_id(&self, id: &str) -> f64 {
        self.sliders
            .iter()
            .find(|(k, _)| k.eq_ignore_ascii_case(id.trim()))
            .map_or(0.0, |&(_, v)| v)
    }

    /// The slider vector for a basis whose muscles are named `muscle_ids` (e.g.
    /// [`crate::MuscleBasis::muscle_ids`]): standard controls get the preset value, any other
    /// (user-defined) muscle gets 0.
    pub fn sliders_for(&self, muscle_ids: &[String]) -> Vec<f64> {
        muscle_ids.iter().map(|id| self.slider_by_id(id)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_in_range_symmetric_and_unique() {
        for (i, p) in ALL.iter().enumerate() {
            for &(id, s) in p.sliders {
                assert!(
                    MuscleKind::from_id(id).is_some(),
                    "{}: unknown control {id}",
                    p.name
                );
                assert!((-1.0..=1.0).contains(&s) && s != 0.0, "{} {id}", p.name);
            }
            for (k, &(id, _)) in p.sliders.iter().enumerate() {
                assert!(
                    p.sliders[k + 1..].iter().all(|&(other, _)| other != id),
                    "{}: {id} listed twice",
                    p.name
                );
            }
            for m in MuscleKind::ALL {
                let s = p.slider(m);
                assert_eq!(s, p.slider(m.mirror()), "{} is not L/R symmetric", p.name);
            }
            for q in &ALL[i + 1..] {
                assert_ne!(p.name, q.name);
                assert_ne!(p.sliders, q.sliders, "{} == {}", p.name, q.name);
            }
        }
        assert!(ALL[0].sliders.is_empty());
    }

    #[test]
    fn find_accepts_names_and_aliases() {
        for p in &ALL {
            assert_eq!(find(&p.name.to_uppercase()).map(|q| q.name), Some(p.name));
        }
        assert_eq!(find(" hate ").map(|p| p.name), Some("disgust"));
        assert_eq!(find("grumpy"), None);
    }

    #[test]
    fn sliders_for_maps_by_id_and_zeroes_unknown_muscles() {
        let ids = vec!["mentalis_r".to_string(), "my_extra".to_string()];
        let s = find("sad").unwrap().sliders_for(&ids);
        assert_eq!(s, vec![-0.4, 0.0]);
    }
}
