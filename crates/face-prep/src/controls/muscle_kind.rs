//! The rig's standard controls: one table row per control (muscle, jaw mode, ...), with its
//! id, display name, side, mirror twin, the muscle models that place it, and the generator of
//! its prescribed displacement.
//!
//! The first ten rows are the ten muscles of the thesis (Table 7.1), in the thesis's order
//! ([`MuscleKind::THESIS`]); the thesis model places only these, so its rigs and bases stay
//! bit for bit what they were. The anatomical model places every row ([`MuscleKind::ALL`]).
//!
//! # Adding a control
//!
//! 1. Add one row to the `controls!` table below (at the end; the row order is the order of
//!    sliders, basis columns and exports):
//!    `/// doc line` then `Variant = ("id", "Display name", Side, Mirror, Placed, Generator)`:
//!    - `id`: the snake_case id listed in `docs/user-guide.md` ("Muscle ids and presets") (`_l`/`_r` = the face's own
//!      left/right, +x/−x in the canonical frame). Used in files, the CLI
//!      (`--set jaw_open=-1`), glTF target names and presets.
//!    - `Display name`: what the viewer shows, e.g. "Zygomaticus major L".
//!    - `Side`: `Left`, `Right` or `Center` (unpaired, e.g. `procerus`).
//!    - `Mirror`: the variant of the twin on the other side; an unpaired control names
//!      itself. (The table's test checks that mirroring is an involution between opposite
//!      sides.)
//!    - `Placed`: [`Placed::Thesis`] only for the original ten (placed by both models);
//!      every new control is [`Placed::Anatomical`].
//!    - `Generator`: how the control is placed and what it prescribes ([`Generator`]).
//!      A muscle from a bony origin to a skin insertion is `Force(anatomy::my_muscle)`
//!      (force-driven, [`crate::controls::force_controls`]: free in every other response) or
//!      `Band(anatomy::my_muscle)` (prescribed displacement, which holds its band at zero in
//!      every other response), where `my_muscle(&Landmarks) -> Attachment` (in
//!      [`crate::controls::anatomy`]) gives the face's-LEFT twin's (or the unpaired control's) origin,
//!      insertion, width and strain; the right twin uses the same function and is mirrored
//!      about the mouth's centre line.
//! 2. A control that is not a muscle band (a rigid jaw mode, a lid target, a pressure) adds a
//!    [`Generator`] variant and handles it in the two dispatch points:
//!    `dispatch::place_control` (which elements it prescribes: its chains) and
//!    `dispatch::control_pattern` (the per-element displacement at slider = +1), both in
//!    `crates/face-prep/src/controls/dispatch.rs`.
//! 3. Presets (root crate `src/presets.rs`) name controls by id, so a new control is 0 in
//!    every preset until a preset lists it.
//!
//! Slider convention for every control: −1 = full activation ("contraction"), +1 the linear
//! opposite with the same limit.

use crate::controls::anatomy::{self, Attachment, Landmarks};
pub use crate::controls::ids::{JawMode, LidAction, Lip, Side};
use crate::frame::features::FeatureBoxes;
use glam::DVec2;
use serde::{Deserialize, Serialize};

/// Which muscle models place a control.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Placed {
    /// Both the thesis model and the anatomical model (only the original ten muscles).
    Thesis,
    /// Only the anatomical model.
    Anatomical,
}

/// How a control is placed on the shell and what displacement it prescribes.
#[derive(Clone, Copy, Debug)]
#[non_exhaustive]
pub enum Generator {
    /// A muscle band from a bony origin to a skin insertion ([`crate::controls::muscle_model`]): the
    /// function gives the attachment of the face's-left twin (or of an unpaired control) from
    /// the eye and mouth landmarks; [`attachment`] mirrors it for the right twin.
    Band(fn(&Landmarks) -> Attachment),
    /// A rigid mode of the jaw segment about the TMJ axis ([`crate::controls::jaw`]): no chains of its
    /// own; it prescribes the jaw segment of the rim and carries the lower face's band
    /// elements along.
    Jaw(JawMode),
    /// Air pressure inside the mouth on the deep layer of both cheeks
    /// ([`crate::controls::force_controls`]): a traction load, free (traction-type) in every other
    /// control's response, scaled after the solve to
    /// [`crate::controls::force_controls::CHEEK_PUFF_MM`].
    Pressure,
    /// An eyelid action on the eye of the control's side ([`crate::controls::eyelid`]): a band of lid
    /// skin next to the eye loop's margins, moved in units of the eye's own opening.
    Lid(LidAction),
    /// A muscle band driven by a force instead of a prescribed displacement
    /// ([`crate::controls::force_controls`]): a traction toward the origin on the band's free elements,
    /// which stay free (traction-type) in every other control's response, so adding it changes
    /// no other response. The response is scaled after the solve so that its largest
    /// displacement on the face is the attachment's `max_strain` × its length.
    Force(fn(&Landmarks) -> Attachment),
    /// One half of the orbicularis oris sphincter, force-driven like [`Generator::Force`]: a
    /// ring of tissue around the mouth pulled toward the mouth's centre and forward (pucker).
    Sphincter(Lip),
    /// The marginal part of one lip's orbicularis oris ([`crate::controls::lip_margin`]),
    /// force-driven like [`Generator::Force`]: the vermilion ring pulled back toward the dental
    /// arch's centre (the lip rolls in over the teeth).
    Marginal(Lip),
    /// The lip seal ([`crate::controls::lip_seal`]): no elements and no load of its own; its
    /// response is `jaw_open`'s solved response times minus a share that is 1 at the lower lip's
    /// margin, so added to `jaw_open` it takes the lower lip back up (ARKit's `mouthClose`).
    Seal,
}

/// One row of the control table.
#[derive(Clone, Copy, Debug)]
pub struct ControlSpec {
    /// The control this row describes.
    pub kind: MuscleKind,
    /// Stable snake_case identifier.
    pub id: &'static str,
    /// Human-readable name.
    pub display_name: &'static str,
    /// Side of the face.
    pub side: Side,
    /// The twin on the other side (itself when unpaired).
    pub mirror: MuscleKind,
    /// Which muscle models place it.
    pub placed: Placed,
    /// How it is placed and what it prescribes.
    pub generator: Generator,
}

/// Defines [`MuscleKind`], [`MuscleKind::ALL`] and the table from one row per control.
macro_rules! controls {
    ($(
        $(#[$doc:meta])*
        $variant:ident = ($id:literal, $name:literal, $side:ident, $mirror:ident, $placed:ident,
            $generator:expr)
    ),* $(,)?) => {
        /// One of the rig's standard controls, placed automatically from the feature boxes
        /// (see the module documentation for the table and how to add a row).
        ///
        /// ```
        /// use face_prep::{MuscleKind, Side};
        /// let m = MuscleKind::from_id("zygomaticus_major_l").unwrap();
        /// assert_eq!(m, MuscleKind::ZygomaticusMajorL);
        /// assert_eq!(m.mirror(), MuscleKind::ZygomaticusMajorR);
        /// assert_eq!(m.side(), Side::Left);
        /// assert_eq!(m.display_name(), "Zygomaticus major L");
        /// assert_eq!(&MuscleKind::ALL[..10], &MuscleKind::THESIS[..]);
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
        #[non_exhaustive]
        pub enum MuscleKind {
            $( $(#[$doc])* $variant, )*
        }

        impl MuscleKind {
            /// Every standard control in table order (the order of sliders and basis
            /// columns); the anatomical model places them all.
            pub const ALL: [MuscleKind; [$($id),*].len()] = [$(MuscleKind::$variant),*];

            const TABLE: [ControlSpec; [$($id),*].len()] = [$(
                ControlSpec {
                    kind: MuscleKind::$variant,
                    id: $id,
                    display_name: $name,
                    side: Side::$side,
                    mirror: MuscleKind::$mirror,
                    placed: Placed::$placed,
                    generator: $generator,
                }
            ),*];
        }
    };
}

use Generator::{Band, Force, Jaw, Lid, Marginal, Pressure, Seal, Sphincter};

controls! {
    /// Frontalis, face's left.
    FrontalisL = ("frontalis_l", "Frontalis L", Left, FrontalisR, Thesis,
        Force(anatomy::frontalis)),
    /// Frontalis, face's right.
    FrontalisR = ("frontalis_r", "Frontalis R", Right, FrontalisL, Thesis,
        Force(anatomy::frontalis)),
    /// Levator labii superioris, face's left.
    LevatorLabiiSuperiorisL = ("levator_labii_superioris_l", "Levator labii superioris L",
        Left, LevatorLabiiSuperiorisR, Thesis, Band(anatomy::levator_labii_superioris)),
    /// Levator labii superioris, face's right.
    LevatorLabiiSuperiorisR = ("levator_labii_superioris_r", "Levator labii superioris R",
        Right, LevatorLabiiSuperiorisL, Thesis, Band(anatomy::levator_labii_superioris)),
    /// Zygomaticus major, face's left.
    ZygomaticusMajorL = ("zygomaticus_major_l", "Zygomaticus major L", Left,
        ZygomaticusMajorR, Thesis, Force(anatomy::zygomaticus_major)),
    /// Zygomaticus major, face's right.
    ZygomaticusMajorR = ("zygomaticus_major_r", "Zygomaticus major R", Right,
        ZygomaticusMajorL, Thesis, Force(anatomy::zygomaticus_major)),
    /// Mentalis, face's left.
    MentalisL = ("mentalis_l", "Mentalis L", Left, MentalisR, Thesis,
        Band(anatomy::mentalis)),
    /// Mentalis, face's right.
    MentalisR = ("mentalis_r", "Mentalis R", Right, MentalisL, Thesis,
        Band(anatomy::mentalis)),
    /// Depressor labii inferioris, face's left.
    DepressorLabiiInferiorisL = ("depressor_labii_inferioris_l",
        "Depressor labii inferioris L", Left, DepressorLabiiInferiorisR, Thesis,
        Band(anatomy::depressor_labii_inferioris)),
    /// Depressor labii inferioris, face's right.
    DepressorLabiiInferiorisR = ("depressor_labii_inferioris_r",
        "Depressor labii inferioris R", Right, DepressorLabiiInferiorisL, Thesis,
        Band(anatomy::depressor_labii_inferioris)),
    /// Jaw opening: rotation about the temporomandibular axis (−1 = fully open).
    JawOpen = ("jaw_open", "Jaw open", Center, JawOpen, Anatomical, Jaw(JawMode::Open)),
    /// Jaw protrusion (−1 = chin forward, +z).
    JawForward = ("jaw_forward", "Jaw forward", Center, JawForward, Anatomical,
        Jaw(JawMode::Forward)),
    /// Jaw lateral shift (−1 = chin toward the face's left, +x; +1 toward the right). Its own
    /// mirror: the mirror image of a pose negates it.
    JawLateral = ("jaw_lateral", "Jaw lateral", Center, JawLateral, Anatomical,
        Jaw(JawMode::Lateral)),
    /// Cheek puff (unpaired): air pressure inside the mouth pushes both cheeks out.
    CheekPuff = ("cheek_puff", "Cheek puff", Center, CheekPuff, Anatomical, Pressure),
    /// Orbicularis oculi, palpebral part, face's left: blink (the upper lid margin closes onto
    /// the lower one; [`crate::controls::eyelid`]).
    OrbicularisOculiPalpebralL = ("orbicularis_oculi_palpebral_l",
        "Orbicularis oculi (palpebral) L", Left, OrbicularisOculiPalpebralR, Anatomical,
        Lid(LidAction::Blink)),
    /// Orbicularis oculi, palpebral part, face's right: blink.
    OrbicularisOculiPalpebralR = ("orbicularis_oculi_palpebral_r",
        "Orbicularis oculi (palpebral) R", Right, OrbicularisOculiPalpebralL, Anatomical,
        Lid(LidAction::Blink)),
    /// Orbicularis oculi, orbital part, face's left: squint (the lower lid and the cheek rise).
    OrbicularisOculiOrbitalL = ("orbicularis_oculi_orbital_l",
        "Orbicularis oculi (orbital) L", Left, OrbicularisOculiOrbitalR, Anatomical,
        Lid(LidAction::Squint)),
    /// Orbicularis oculi, orbital part, face's right: squint.
    OrbicularisOculiOrbitalR = ("orbicularis_oculi_orbital_r",
        "Orbicularis oculi (orbital) R", Right, OrbicularisOculiOrbitalL, Anatomical,
        Lid(LidAction::Squint)),
    /// Levator palpebrae superioris, face's left: the upper lid rises (eye wide).
    LevatorPalpebraeL = ("levator_palpebrae_l", "Levator palpebrae L", Left,
        LevatorPalpebraeR, Anatomical, Lid(LidAction::Wide)),
    /// Levator palpebrae superioris, face's right: eye wide.
    LevatorPalpebraeR = ("levator_palpebrae_r", "Levator palpebrae R", Right,
        LevatorPalpebraeL, Anatomical, Lid(LidAction::Wide)),
    /// Corrugator supercilii, face's left (brow down and in).
    CorrugatorSuperciliiL = ("corrugator_supercilii_l", "Corrugator supercilii L", Left,
        CorrugatorSuperciliiR, Anatomical, Force(anatomy::corrugator_supercilii)),
    /// Corrugator supercilii, face's right.
    CorrugatorSuperciliiR = ("corrugator_supercilii_r", "Corrugator supercilii R", Right,
        CorrugatorSuperciliiL, Anatomical, Force(anatomy::corrugator_supercilii)),
    /// Procerus (unpaired; skin between the brows down).
    Procerus = ("procerus", "Procerus", Center, Procerus, Anatomical,
        Force(anatomy::procerus)),
    /// Orbicularis oris, upper lip (sphincter; pucker, funnel, press, roll).
    OrbicularisOrisUpper = ("orbicularis_oris_upper", "Orbicularis oris upper", Center,
        OrbicularisOrisUpper, Anatomical, Sphincter(Lip::Upper)),
    /// Orbicularis oris, lower lip.
    OrbicularisOrisLower = ("orbicularis_oris_lower", "Orbicularis oris lower", Center,
        OrbicularisOrisLower, Anatomical, Sphincter(Lip::Lower)),
    /// Depressor anguli oris, face's left (frown).
    DepressorAnguliOrisL = ("depressor_anguli_oris_l", "Depressor anguli oris L", Left,
        DepressorAnguliOrisR, Anatomical, Force(anatomy::depressor_anguli_oris)),
    /// Depressor anguli oris, face's right.
    DepressorAnguliOrisR = ("depressor_anguli_oris_r", "Depressor anguli oris R", Right,
        DepressorAnguliOrisL, Anatomical, Force(anatomy::depressor_anguli_oris)),
    /// Risorius, face's left (mouth corner straight out).
    RisoriusL = ("risorius_l", "Risorius L", Left, RisoriusR, Anatomical,
        Force(anatomy::risorius)),
    /// Risorius, face's right.
    RisoriusR = ("risorius_r", "Risorius R", Right, RisoriusL, Anatomical,
        Force(anatomy::risorius)),
    /// Levator labii superioris alaeque nasi, face's left (nose wrinkle, upper lip up).
    LevatorLabiiSuperiorisAlaequeNasiL = ("levator_labii_superioris_alaeque_nasi_l",
        "Levator labii superioris alaeque nasi L", Left, LevatorLabiiSuperiorisAlaequeNasiR,
        Anatomical, Force(anatomy::levator_labii_superioris_alaeque_nasi)),
    /// Levator labii superioris alaeque nasi, face's right.
    LevatorLabiiSuperiorisAlaequeNasiR = ("levator_labii_superioris_alaeque_nasi_r",
        "Levator labii superioris alaeque nasi R", Right, LevatorLabiiSuperiorisAlaequeNasiL,
        Anatomical, Force(anatomy::levator_labii_superioris_alaeque_nasi)),
    /// Zygomaticus minor, face's left (upper lip up and out).
    ZygomaticusMinorL = ("zygomaticus_minor_l", "Zygomaticus minor L", Left,
        ZygomaticusMinorR, Anatomical, Force(anatomy::zygomaticus_minor)),
    /// Zygomaticus minor, face's right.
    ZygomaticusMinorR = ("zygomaticus_minor_r", "Zygomaticus minor R", Right,
        ZygomaticusMinorL, Anatomical, Force(anatomy::zygomaticus_minor)),
    /// Levator anguli oris, face's left (mouth corner up).
    LevatorAnguliOrisL = ("levator_anguli_oris_l", "Levator anguli oris L", Left,
        LevatorAnguliOrisR, Anatomical, Force(anatomy::levator_anguli_oris)),
    /// Levator anguli oris, face's right.
    LevatorAnguliOrisR = ("levator_anguli_oris_r", "Levator anguli oris R", Right,
        LevatorAnguliOrisL, Anatomical, Force(anatomy::levator_anguli_oris)),
    /// Buccinator, face's left (corner back, cheek pressed: dimple).
    BuccinatorL = ("buccinator_l", "Buccinator L", Left, BuccinatorR, Anatomical,
        Force(anatomy::buccinator)),
    /// Buccinator, face's right.
    BuccinatorR = ("buccinator_r", "Buccinator R", Right, BuccinatorL, Anatomical,
        Force(anatomy::buccinator)),
    /// Lip seal (unpaired): the lower lip held up against the upper one over the open jaw
    /// (orbicularis oris and mentalis; ARKit's mouthClose, [`crate::controls::lip_seal`]).
    LipSeal = ("lip_seal", "Lip seal", Center, LipSeal, Anatomical, Seal),
    /// Orbicularis oculi, orbital part over the malar cheek, face's left: the cheek raiser
    /// (AU6; the malar skin drawn up toward the orbit).
    OrbicularisOculiMalarL = ("orbicularis_oculi_malar_l", "Orbicularis oculi (malar) L", Left,
        OrbicularisOculiMalarR, Anatomical, Force(anatomy::orbicularis_oculi_malar)),
    /// Orbicularis oculi, orbital part over the malar cheek, face's right.
    OrbicularisOculiMalarR = ("orbicularis_oculi_malar_r", "Orbicularis oculi (malar) R", Right,
        OrbicularisOculiMalarL, Anatomical, Force(anatomy::orbicularis_oculi_malar)),
    /// Orbicularis oris, marginal part of the upper lip: rolls the upper lip in.
    OrbicularisOrisMarginalUpper = ("orbicularis_oris_marginal_upper",
        "Orbicularis oris (marginal) upper", Center, OrbicularisOrisMarginalUpper, Anatomical,
        Marginal(Lip::Upper)),
    /// Orbicularis oris, marginal part of the lower lip: rolls the lower lip in.
    OrbicularisOrisMarginalLower = ("orbicularis_oris_marginal_lower",
        "Orbicularis oris (marginal) lower", Center, OrbicularisOrisMarginalLower, Anatomical,
        Marginal(Lip::Lower)),
    /// Orbicularis oculi, orbital part over the brow, face's left: draws the brow down and in.
    OrbicularisOculiSuperiorL = ("orbicularis_oculi_superior_l", "Orbicularis oculi (brow) L",
        Left, OrbicularisOculiSuperiorR, Anatomical, Force(anatomy::orbicularis_oculi_superior)),
    /// Orbicularis oculi, orbital part over the brow, face's right.
    OrbicularisOculiSuperiorR = ("orbicularis_oculi_superior_r", "Orbicularis oculi (brow) R",
        Right, OrbicularisOculiSuperiorL, Anatomical, Force(anatomy::orbicularis_oculi_superior)),
}

impl MuscleKind {
    /// The ten muscles of the thesis, in its order: the only controls the thesis model places
    /// (and the first ten rows of [`MuscleKind::ALL`]).
    pub const THESIS: [MuscleKind; 10] = [
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

    /// This control's table row.
    pub fn spec(self) -> &'static ControlSpec {
        &MuscleKind::TABLE[self as usize]
    }

    /// Stable snake_case identifier, used in files, the CLI (`--set zygomaticus_major_l=-0.8`)
    /// and glTF target names.
    pub fn id(self) -> &'static str {
        self.spec().id
    }

    /// Human-readable name, e.g. "Frontalis L".
    pub fn display_name(self) -> &'static str {
        self.spec().display_name
    }

    /// Parses an identifier as returned by [`MuscleKind::id`] (case-insensitive).
    pub fn from_id(id: &str) -> Option<MuscleKind> {
        MuscleKind::ALL
            .into_iter()
            .find(|m| m.id().eq_ignore_ascii_case(id.trim()))
    }

    /// The face side of this control.
    pub fn side(self) -> Side {
        self.spec().side
    }

    /// The same control on the other side of the face (itself when unpaired).
    pub fn mirror(self) -> MuscleKind {
        self.spec().mirror
    }

    /// Position of this control in [`MuscleKind::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// Whether the thesis model places this control (one of [`MuscleKind::THESIS`]).
    pub fn is_thesis(self) -> bool {
        self.spec().placed == Placed::Thesis
    }

    /// How this control is placed and what it prescribes.
    pub fn generator(self) -> Generator {
        self.spec().generator
    }

    /// The muscle-band attachment function, if this control is a muscle band.
    pub fn band(self) -> Option<fn(&Landmarks) -> Attachment> {
        match self.generator() {
            Generator::Band(f) | Generator::Force(f) => Some(f),
            Generator::Jaw(_)
            | Generator::Pressure
            | Generator::Lid(_)
            | Generator::Sphincter(_)
            | Generator::Marginal(_)
            | Generator::Seal => None,
        }
    }

    /// Whether this control is force-driven ([`Generator::Force`], [`Generator::Sphincter`],
    /// [`Generator::Marginal`], [`Generator::Pressure`]):
    /// its elements carry a traction in its own response and are free in every other one
    /// ([`crate::controls::force_controls`]).
    pub fn is_force(self) -> bool {
        matches!(
            self.generator(),
            Generator::Force(_)
                | Generator::Sphincter(_)
                | Generator::Marginal(_)
                | Generator::Pressure
        )
    }
}

/// The attachment of a standard muscle band (the face's left muscle is mirrored about the
/// mouth's centre line for the right one, so a symmetric face gets symmetric muscles); `None`
/// for a control that is not a muscle band ([`Generator`]).
///
/// | muscle | origin (bone) | insertion (skin) |
/// |---|---|---|
/// | frontalis | galea aponeurotica, 0.95 iod above the eye centre | eyebrow skin, 0.3 iod above the eye centre |
/// | levator labii superioris | infraorbital margin, below the eye's medial half | upper lip, above the mouth's lateral third |
/// | zygomaticus major | zygomatic bone: just lateral of the eye's outer corner, 0.3 h below the eye line | modiolus, just lateral of the mouth corner |
/// | mentalis | incisive fossa of the mandible, below the lower lip | chin skin (the muscle runs down; contracting raises the chin) |
/// | depressor labii inferioris | oblique line of the mandible, below and lateral of the mouth | lower lip, lateral third |
///
/// ```
/// use face_prep::{Box2, FeatureBoxes, MuscleKind};
/// use face_prep::muscle_kind::attachment;
/// use glam::DVec2;
/// let b = |x0, y0, x1, y1| Box2::new(DVec2::new(x0, y0), DVec2::new(x1, y1));
/// let boxes = FeatureBoxes::derive(
///     b(-8.0, -10.0, 8.0, 8.0),
///     b(1.8, 1.0, 4.5, 2.0),
///     b(-4.5, 1.0, -1.8, 2.0),
///     b(-2.5, -5.5, 2.5, -4.5),
/// )
/// .unwrap();
/// let zl = attachment(MuscleKind::ZygomaticusMajorL, &boxes).unwrap();
/// let zr = attachment(MuscleKind::ZygomaticusMajorR, &boxes).unwrap();
/// // Runs up and out from the mouth corner; the right one is the mirror image.
/// assert!(zl.origin.x > zl.insertion.x && zl.origin.y > zl.insertion.y);
/// assert!((zl.origin.x + zr.origin.x).abs() < 1e-12);
/// ```
pub fn attachment(kind: MuscleKind, boxes: &FeatureBoxes) -> Option<Attachment> {
    let l = Landmarks::of(boxes);
    let left = kind.band()?(&l);
    Some(match kind.side() {
        Side::Left | Side::Center => left,
        Side::Right => {
            let m = |p: DVec2| DVec2::new(2.0 * l.mouth.x - p.x, p.y);
            Attachment {
                origin: m(left.origin),
                insertion: m(left.insertion),
                ..left
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_round_trip_and_mirror_pairs() {
        for m in MuscleKind::ALL {
            assert_eq!(MuscleKind::from_id(m.id()), Some(m));
            assert_eq!(m.mirror().mirror(), m);
            assert_eq!(m.side().opposite(), m.mirror().side(), "{}", m.id());
            assert_eq!(m.side() == Side::Center, m.mirror() == m, "{}", m.id());
            assert_eq!(MuscleKind::ALL[m.index()], m);
            assert_eq!(m.spec().kind, m);
            // Ids follow the side: `_l` left, `_r` right, neither when unpaired.
            let suffix = match m.side() {
                Side::Left => m.id().ends_with("_l"),
                Side::Right => m.id().ends_with("_r"),
                Side::Center => !m.id().ends_with("_l") && !m.id().ends_with("_r"),
            };
            assert!(suffix, "{} does not name its side", m.id());
        }
        assert_eq!(MuscleKind::from_id("nope"), None);
    }

    #[test]
    fn ids_and_names_are_unique() {
        for (i, a) in MuscleKind::ALL.iter().enumerate() {
            for b in &MuscleKind::ALL[i + 1..] {
                assert_ne!(a.id(), b.id());
                assert!(!a.display_name().eq_ignore_ascii_case(b.display_name()));
            }
        }
    }

    #[test]
    fn thesis_muscles_are_the_first_ten_rows() {
        assert_eq!(&MuscleKind::ALL[..10], &MuscleKind::THESIS[..]);
        for m in MuscleKind::ALL {
            assert_eq!(m.is_thesis(), m.index() < 10, "{}", m.id());
        }
    }
}
