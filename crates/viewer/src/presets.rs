//! Expression presets: named slider settings (negative = contract, as in the thesis).

/// A named expression: `(muscle id, slider value)` pairs; unlisted muscles stay at 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Preset {
    /// Button label.
    pub name: &'static str,
    /// Slider values by muscle id.
    pub sliders: &'static [(&'static str, f64)],
}

/// The viewer's expression presets.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "Smile",
        sliders: &[("zygomaticus_major_l", -0.9), ("zygomaticus_major_r", -0.9)],
    },
    Preset {
        name: "Surprise",
        sliders: &[("frontalis_l", -0.9), ("frontalis_r", -0.9)],
    },
    Preset {
        name: "Sneer",
        sliders: &[
            ("levator_labii_superioris_l", -0.9),
            ("levator_labii_superioris_r", -0.9),
        ],
    },
    Preset {
        name: "Sad",
        sliders: &[
            ("depressor_labii_inferioris_l", -0.7),
            ("depressor_labii_inferioris_r", -0.7),
            ("mentalis_l", -0.6),
            ("mentalis_r", -0.6),
        ],
    },
    Preset {
        name: "Smirk",
        sliders: &[
            ("zygomaticus_major_l", -0.9),
            ("levator_labii_superioris_l", -0.4),
        ],
    },
];

impl Preset {
    /// Slider vector for muscles `ids` (ids not in the preset get 0; matching ignores case).
    ///
    /// ```
    /// let smile = viewer::presets::PRESETS[0];
    /// let ids = ["frontalis_l".to_string(), "zygomaticus_major_l".to_string()];
    /// assert_eq!(smile.sliders_for(&ids), vec![0.0, -0.9]);
    /// ```
    pub fn sliders_for(&self, ids: &[String]) -> Vec<f64> {
        ids.iter()
            .map(|id| {
                self.sliders
                    .iter()
                    .find(|(m, _)| m.eq_ignore_ascii_case(id))
                    .map_or(0.0, |&(_, v)| v)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use face_prep::MuscleKind;

    #[test]
    fn every_preset_names_real_muscles_with_values_in_range() {
        for p in PRESETS {
            for (id, v) in p.sliders {
                assert!(
                    MuscleKind::from_id(id).is_some(),
                    "{}: unknown muscle {id}",
                    p.name
                );
                assert!((-1.0..=1.0).contains(v), "{}: {id} = {v}", p.name);
            }
        }
    }
}
