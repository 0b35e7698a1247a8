//! The ten standard facial muscles of the thesis (Table 7.1) and their names.

use serde::{Deserialize, Serialize};

/// Which side of the face a muscle is on. "Left" is the face's own left, i.e. +x in the
/// canonical frame (the face looks toward +z).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Side {
    /// The face's left (+x in the canonical frame).
    Left,
    /// The face's right (−x in the canonical frame).
    Right,
}

/// One of the ten standard muscles placed automatically from the feature boxes.
///
/// ```
/// use face_prep::MuscleKind;
/// let m = MuscleKind::from_id("zygomaticus_major_l").unwrap();
/// assert_eq!(m, MuscleKind::ZygomaticusMajorL);
/// assert_eq!(m.mirror(), MuscleKind::ZygomaticusMajorR);
/// assert_eq!(m.display_name(), "Zygomaticus major L");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum MuscleKind {
    /// Frontalis, face's left.
    FrontalisL,
    /// Frontalis, face's right.
    FrontalisR,
    /// Levator labii superioris, face's left.
    LevatorLabiiSuperiorisL,
    /// Levator labii superioris, face's right.
    LevatorLabiiSuperiorisR,
    /// Zygomaticus major, face's left.
    ZygomaticusMajorL,
    /// Zygomaticus major, face's right.
    ZygomaticusMajorR,
    /// Mentalis, face's left.
    MentalisL,
    /// Mentalis, face's right.
    MentalisR,
    /// Depressor labii inferioris, face's left.
    DepressorLabiiInferiorisL,
    /// Depressor labii inferioris, face's right.
    DepressorLabiiInferiorisR,
}

impl MuscleKind {
    /// All ten muscles in their canonical order (the order of sliders and basis columns).
    pub const ALL: [MuscleKind; 10] = [
        MuscleKind::FrontalisL,
        MuscleKind::FrontalisR,
        MuscleKind::LevatorLabiiSuperiorisL,
        MuscleKind::LevatorLabiiSuperiorisR,
        MuscleKind::ZygomaticusMajorL,
        MuscleKind::ZygomaticusMajorR,
        MuscleKind::MentalisL,
        MuscleKind::MentalisR,
        MuscleKind::DepressorLabiiInferiorisL,
        MuscleKind::DepressorLabiiInferiorisR,
    ];

    /// Stable snake_case identifier, used in files, the CLI (`--set zygomaticus_major_l=-0.8`)
    /// and glTF target names.
    pub fn id(self) -> &'static str {
        match self {
            MuscleKind::FrontalisL => "frontalis_l",
            MuscleKind::FrontalisR => "frontalis_r",
            MuscleKind::LevatorLabiiSuperiorisL => "levator_labii_superioris_l",
            MuscleKind::LevatorLabiiSuperiorisR => "levator_labii_superioris_r",
            MuscleKind::ZygomaticusMajorL => "zygomaticus_major_l",
            MuscleKind::ZygomaticusMajorR => "zygomaticus_major_r",
            MuscleKind::MentalisL => "mentalis_l",
            MuscleKind::MentalisR => "mentalis_r",
            MuscleKind::DepressorLabiiInferiorisL => "depressor_labii_inferioris_l",
            MuscleKind::DepressorLabiiInferiorisR => "depressor_labii_inferioris_r",
        }
    }

    /// Human-readable name as in the thesis, e.g. "Frontalis L".
    pub fn display_name(self) -> &'static str {
        match self {
            MuscleKind::FrontalisL => "Frontalis L",
            MuscleKind::FrontalisR => "Frontalis R",
            MuscleKind::LevatorLabiiSuperiorisL => "Levator labii superioris L",
            MuscleKind::LevatorLabiiSuperiorisR => "Levator labii superioris R",
            MuscleKind::ZygomaticusMajorL => "Zygomaticus major L",
            MuscleKind::ZygomaticusMajorR => "Zygomaticus major R",
            MuscleKind::MentalisL => "Mentalis L",
            MuscleKind::MentalisR => "Mentalis R",
            MuscleKind::DepressorLabiiInferiorisL => "Depressor labii inferioris L",
            MuscleKind::DepressorLabiiInferiorisR => "Depressor labii inferioris R",
        }
    }

    /// Parses an identifier as returned by [`MuscleKind::id`] (case-insensitive).
    pub fn from_id(id: &str) -> Option<MuscleKind> {
        MuscleKind::ALL
            .into_iter()
            .find(|m| m.id().eq_ignore_ascii_case(id.trim()))
    }

    /// The face side of this muscle.
    pub fn side(self) -> Side {
        if (self as usize).is_multiple_of(2) {
            Side::Left
        } else {
            Side::Right
        }
    }

    /// The same muscle on the other side of the face.
    pub fn mirror(self) -> MuscleKind {
        MuscleKind::ALL[(self as usize) ^ 1]
    }

    /// Position of this muscle in [`MuscleKind::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_round_trip_and_mirror_pairs() {
        for m in MuscleKind::ALL {
            assert_eq!(MuscleKind::from_id(m.id()), Some(m));
            assert_eq!(m.mirror().mirror(), m);
            assert_ne!(m.side(), m.mirror().side());
            assert_eq!(MuscleKind::ALL[m.index()], m);
        }
        assert_eq!(MuscleKind::from_id("nope"), None);
    }
}
