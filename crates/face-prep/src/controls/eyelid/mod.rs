//! Eyelids: the orbicularis oculi (palpebral and orbital parts) and the levator palpebrae
//! superioris, as prescribed displacements of the lid skin found from the eye loops.
//!
//! The lids are no muscle lines: they are sheets bounded by the eye loop's two margins
//! ([`EyeMargins`]). Each action moves a band of lid skin next to a margin, in physical units
//! taken from the eye's own opening, and the BEM's elastic solve carries the skin around it:
//!
//! | control | action (slider −1) | prescribed band | anatomy |
//! |---|---|---|---|
//! | `orbicularis_oculi_palpebral_l/_r` | **blink** (FACS AU45): each upper-margin point moves onto the lower-margin point of the same parameter along the corner-to-corner chord ([`EyeMargins`]); the lower lid slides nasally by [`BLINK_NASAL_FRACTION`] of the opening | upper lid: full motion up to [`UPPER_LID_CORE_MM`] above the margin, fading to 0 at [`UPPER_LID_BAND_MM`]; lower lid: the nasal slide, fading to 0 at [`LOWER_LID_BAND_MM`] | palpebral part: fibres in the lids from the medial palpebral ligament to the lateral palpebral raphe; it closes the lids gently (Gray's Anatomy, 41st ed., ch. 29; Parke & Waters, *Computer Facial Animation*, 2nd ed., ch. 3); the lower lid moves nasally in a blink (Doane, Am J Ophthalmol 89, 1980) |
//! | `orbicularis_oculi_orbital_l/_r` | **squint** (AU7, the lid tightener): the lower margin rises by [`SQUINT_RISE_FRACTION`] of the opening and is drawn toward the medial corner by [`SQUINT_MEDIAL_RATIO`] of that rise (tapered toward the corners like the blink's slide), the cheek below it less | lower lid and the cheek over the infraorbital margin, full motion up to [`SQUINT_CORE_MM`] below the margin, fading to 0 at [`SQUINT_BAND_MM`] | orbital part: a sphincter from the medial orbital margin round the orbit; it draws the lower-lid skin up and toward the medial angle (Gray's ch. 29; Parke & Waters ch. 3; Ekman & Friesen, FACS manual, AU7; the same ring's part over the malar cheek, which raises the cheek (AU6), is the force-driven `orbicularis_oculi_malar_l/_r`) |
//! | `levator_palpebrae_l/_r` | **wide** (AU5): the upper margin rises straight up by [`WIDE_RAISE_FRACTION`] of the opening | the upper-lid band of the blink | levator palpebrae superioris: from the lesser wing of the sphenoid to the upper tarsal plate and the skin of the upper lid (Gray's ch. 29/32; Parke & Waters ch. 3) |
//!
//! Slider convention as for every muscle: −1 is the action, +1 the linear opposite (the
//! same motion reversed). Bands lie on the front (skin) and back (deep) layers alike, so a lid
//! moves through its thickness.
//!
//! A constant-element BEM carries each element's motion at its centroid, and a vertex gets
//! the average of its elements: the margin itself cannot be prescribed exactly, and a reduced
//! (simplified or peeled) copy's margin is not the displayed one. So after the solve, a blink's
//! upper-margin vertices of the displayed mesh are pinned onto their lower-margin points
//! ([`pin::close_margins`]): exact closure, no gap, no margin passing through the other; the
//! pin's correction fades harmonically over the upper lid.

pub mod margins;
pub mod pin;

pub use margins::EyeMargins;
use margins::Lid;

pub use crate::controls::ids::LidAction;
use crate::controls::ids::Side;
use crate::controls::muscle_model::{contour_weight, distance_to_loop};
use crate::frame::orient::FaceLoops;
use crate::shell::{ElementTag, Shell};
use glam::{DVec2, DVec3};
use std::collections::HashSet;

/// Height above the upper margin, mm, that moves fully with it: the pretarsal skin over the
/// upper tarsal plate (about 10 mm tall in the middle; the skin above its upper part folds
/// into the lid crease as the lid opens).
pub const UPPER_LID_CORE_MM: f64 = 4.0;
/// Height above the upper margin, mm, where the upper lid's prescribed motion has faded to 0
/// (raised cosine from [`UPPER_LID_CORE_MM`]); the preseptal skin above it stretches through the
/// elastic solve.
pub const UPPER_LID_BAND_MM: f64 = 10.0;
/// Depth below the lower margin, mm, where a blink's nasal slide of the lower lid has faded
/// to 0 (the lower tarsal plate is about 4–5 mm tall).
pub const LOWER_LID_BAND_MM: f64 = 7.0;
/// Lower-lid nasal slide in a blink, fraction of the lids' opening at that point (the lower lid
/// moves 2–3 mm toward the nose as the lids close, Doane 1980; ICT-FaceKit's captured
/// eyeBlink_L: 3.0 mm for an upper-lid travel of 9.6 mm).
pub const BLINK_NASAL_FRACTION: f64 = 0.3;
/// Rise (straight up) of the lower margin in a squint, fraction of the eye's vertical opening at
/// that point.
pub const SQUINT_RISE_FRACTION: f64 = 0.35;
/// Depth below the lower margin, mm, that rises fully in a squint.
pub const SQUINT_CORE_MM: f64 = 3.0;
/// Depth below the lower margin, mm, where a squint's prescribed rise has faded to 0: the lower
/// lid (its tarsal plate is 4–5 mm tall), as deep as the blink's band ([`LOWER_LID_BAND_MM`]).
/// A prescribed band is held at zero in every other response: at 14 mm it pinned the cheek
/// under the eye that the cheek raiser (`orbicularis_oculi_malar_l/_r`) and the smiles lift,
/// and the skin creased along its edge; the cheek below the lid now follows the squint
/// through the elastic solve.
pub const SQUINT_BAND_MM: f64 = 7.0;
/// Medial pull of a squint relative to its rise: the orbital fibres draw the lower lid toward
/// the medial palpebral ligament, where they arise (Gray's Anatomy, 41st ed., ch. 29).
/// ICT-FaceKit's captured eyeSquint moves the lower lid up and in at about 45° (its peak:
/// 0.72 medial, 0.69 up); 0.8 was set once against that capture (`fit_recipes`: eyeSquint
/// 0.57 → 0.72 with the refitted weights and the 7 mm band).
pub const SQUINT_MEDIAL_RATIO: f64 = 0.8;
/// Rise (straight up) of the upper margin when the eye opens wide, fraction of the vertical
/// opening (AU5 shows the sclera above the iris: 2–3 mm on a 10 mm opening).
pub const WIDE_RAISE_FRACTION: f64 = 0.3;

/// Distance from the outer contour, mm, over which the lids' prescribed motion fades in (as for
/// every muscle, [`crate::controls::muscle_model::CONTOUR_TAPER_MM`]).
pub use crate::controls::muscle_model::CONTOUR_TAPER_MM;

/// Raised-cosine fall-off: 1 up to `core`, 0 from `band` on.
pub(crate) fn lid_weight(distance: f64, core: f64, band: f64) -> f64 {
    if distance <= core {
        1.0
    } else if distance >= band || band <= core {
        0.0
    } else {
        0.5 * (1.0 + (std::f64::consts::PI * (distance - core) / (band - core)).cos())
    }
}

/// sin²(π t): 1 at the middle of a margin (`t` = 0.5), 0 at the corners, where a slide along
/// the margin folded it (the blink's nasal slide, the squint's medial pull).
fn corner_taper(t: f64) -> f64 {
    (std::f64::consts::PI * t.clamp(0.0, 1.0)).sin().powi(2)
}

/// One eye's lid geometry on a rig's shell: the margins of its eye loop, measured on the shell's
/// (canonical) vertices, and the mm scale.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct EyeLids<'a> {
    /// Canonical positions the margins index (the shell's vertices: the face's come first).
    pub positions: &'a [DVec3],
    /// The eye loop's margins.
    pub margins: EyeMargins,
    /// Which eye.
    pub side: Side,
    /// Millimetres per mesh unit.
    pub mm_per_unit: f64,
}

impl<'a> EyeLids<'a> {
    /// The lids of the eye loop `eye_loop` (indices into `positions`, canonical frame).
    pub fn new(
        positions: &'a [DVec3],
        eye_loop: &[u32],
        side: Side,
        mm_per_unit: f64,
    ) -> Option<EyeLids<'a>> {
        let margins = EyeMargins::of_loop(positions, eye_loop, side)?;
        (mm_per_unit > 0.0).then_some(EyeLids {
            positions,
            margins,
            side,
            mm_per_unit,
        })
    }

    /// Displacement (canonical frame, mesh units) of tissue at the canonical point `c` for the
    /// lid action at full activation (slider −1), before the contour fade; `None` outside the
    /// action's band.
    pub fn action_at(&self, action: LidAction, c: DVec3) -> Option<DVec3> {
        let p = self.positions;
        let m = &self.margins;
        let at = m.locate(p, c.truncate())?;
        let d_mm = at.distance * self.mm_per_unit;
        let t = at.t;
        let d = match (action, at.lid) {
            (LidAction::Blink, Lid::Upper) => {
                let w = lid_weight(d_mm, UPPER_LID_CORE_MM, UPPER_LID_BAND_MM);
                (w > 0.0).then(|| (m.opening(p, t) + self.nasal_slide(t)) * w)
            }
            (LidAction::Blink, Lid::Lower) => {
                let w = lid_weight(d_mm, 0.0, LOWER_LID_BAND_MM);
                (w > 0.0).then(|| self.nasal_slide(t) * w)
            }
            (LidAction::Squint, Lid::Lower) => {
                let w = lid_weight(d_mm, SQUINT_CORE_MM, SQUINT_BAND_MM);
                (w > 0.0).then(|| {
                    let up = self.rise(t, SQUINT_RISE_FRACTION * w);
                    up + self.medial_dir() * (SQUINT_MEDIAL_RATIO * up.length() * corner_taper(t))
                })
            }
            (LidAction::Wide, Lid::Upper) => {
                let w = lid_weight(d_mm, UPPER_LID_CORE_MM, UPPER_LID_BAND_MM);
                (w > 0.0).then(|| self.rise(t, WIDE_RAISE_FRACTION * w))
            }
            _ => None,
        }?;
        // Zero at the corners already (the opening vanishes there); nothing beyond them.
        (t > 0.0 && t < 1.0).then_some(d)
    }

    /// A blink's nasal slide of the lower margin at parameter `t`: toward the medial corner,
    /// [`BLINK_NASAL_FRACTION`] of the opening there, tapered by sin²(π t) toward the corners
    /// (which stay; a slide up to them folded the margin there), and small on an eye that is
    /// nearly shut already.
    pub fn nasal_slide(&self, t: f64) -> DVec3 {
        let opening = self.margins.opening(self.positions, t).length();
        self.medial_dir() * (BLINK_NASAL_FRACTION * opening * corner_taper(t))
    }

    /// Unit vector from the lateral corner to the medial one.
    fn medial_dir(&self) -> DVec3 {
        let p = self.positions;
        let m = &self.margins;
        (p[m.medial as usize] - p[m.lateral as usize]).normalize_or_zero()
    }

    /// Upward rise (canonical +y) of `fraction` of the vertical opening at `t`.
    fn rise(&self, t: f64, fraction: f64) -> DVec3 {
        let p = self.positions;
        let gap = self.margins.upper_at(p, t).y - self.margins.lower_at(p, t).y;
        DVec3::Y * (fraction * gap.max(0.0))
    }

    /// The band of a lid action on `shell`: front and back elements (not rim, not in `skull`)
    /// whose centroid lies in the action's band, each list sorted by element index.
    pub fn band(
        &self,
        shell: &Shell,
        skull: &HashSet<u32>,
        action: LidAction,
    ) -> (Vec<u32>, Vec<u32>) {
        let mut front = Vec::new();
        let mut back = Vec::new();
        for e in 0..shell.element_count() {
            if skull.contains(&(e as u32)) {
                continue;
            }
            let list = match shell.tags[e] {
                ElementTag::Front => &mut front,
                ElementTag::Back => &mut back,
                ElementTag::Rim => continue,
            };
            if self
                .action_at(action, shell.centroid(e))
                .is_some_and(|d| d.length() > 0.0)
            {
                list.push(e as u32);
            }
        }
        (front, back)
    }

    /// Prescribed displacement of each of `elements` at slider +1 (the reverse of the action;
    /// −1, the action, is its negative), canonical frame, with the fade-in from the outer
    /// contour `contour` (canonical x-y). Elements outside the band get zero.
    pub fn pattern(
        &self,
        shell: &Shell,
        contour: &[DVec2],
        action: LidAction,
        elements: impl IntoIterator<Item = u32>,
    ) -> Vec<(u32, DVec3)> {
        let taper = CONTOUR_TAPER_MM / self.mm_per_unit;
        elements
            .into_iter()
            .map(|e| {
                let c = shell.centroid(e as usize);
                let d = self.action_at(action, c).unwrap_or(DVec3::ZERO)
                    * contour_weight(distance_to_loop(c.truncate(), contour), taper);
                (e, -d)
            })
            .collect()
    }

    /// Back elements of the lids that are no bone: behind the upper lid (where the skull box,
    /// from the eye box's top up, would otherwise hold the lid's deep layer fixed) lie the
    /// eyeball and the orbital septum. Those within [`UPPER_LID_BAND_MM`] of the upper margin
    /// or [`SQUINT_BAND_MM`] of the lower one.
    pub fn not_skull(&self, shell: &Shell) -> Vec<u32> {
        (0..shell.element_count())
            .filter(|&e| shell.tags[e] == ElementTag::Back)
            .filter(|&e| {
                self.margins
                    .locate(self.positions, shell.centroid(e).truncate())
                    .is_some_and(|at| {
                        let band = match at.lid {
                            Lid::Upper => UPPER_LID_BAND_MM,
                            Lid::Lower => SQUINT_BAND_MM,
                        };
                        at.t > 0.0 && at.t < 1.0 && at.distance * self.mm_per_unit < band
                    })
            })
            .map(|e| e as u32)
            .collect()
    }
}

/// The lids of the eye on `side` of a rig (its `shell` and `loops`), measured on the shell's
/// vertices (canonical frame); `None` for [`Side::Center`].
pub(crate) fn eye_lids<'a>(
    shell: &'a Shell,
    loops: &FaceLoops,
    side: Side,
    mm_per_unit: f64,
) -> Option<EyeLids<'a>> {
    let lp = match side {
        Side::Left => &loops.eye_l,
        Side::Right => &loops.eye_r,
        Side::Center => return None,
    };
    EyeLids::new(&shell.vertices, lp, side, mm_per_unit)
}

/// Back elements behind the lids of both eyes that the skull box would hold fixed
/// ([`EyeLids::not_skull`]).
pub(crate) fn lid_back_elements(
    shell: &Shell,
    loops: &FaceLoops,
    mm_per_unit: f64,
) -> HashSet<u32> {
    [Side::Left, Side::Right]
        .into_iter()
        .filter_map(|s| eye_lids(shell, loops, s, mm_per_unit))
        .flat_map(|l| l.not_skull(shell))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat eye of the face's left: lens 24 mm wide, 10 mm high (units mm), 32 vertices.
    fn eye() -> (Vec<DVec3>, Vec<u32>) {
        let n = 32;
        let pts = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                DVec3::new(32.0 + 12.0 * a.cos(), 5.0 * a.sin(), 0.0)
            })
            .collect();
        (pts, (0..n as u32).collect())
    }

    #[test]
    fn weights_fall_off_smoothly() {
        assert_eq!(lid_weight(1.0, 4.0, 10.0), 1.0);
        assert!((lid_weight(7.0, 4.0, 10.0) - 0.5).abs() < 1e-12);
        assert_eq!(lid_weight(10.0, 4.0, 10.0), 0.0);
    }

    #[test]
    fn a_blink_moves_the_upper_lid_skin_onto_the_lower_margin() {
        let (p, lp) = eye();
        let lids = EyeLids::new(&p, &lp, Side::Left, 1.0).unwrap();
        // Just above the upper margin's middle: down by the opening (10 mm) and nasally.
        let d = lids
            .action_at(LidAction::Blink, DVec3::new(32.0, 6.0, 0.0))
            .unwrap();
        assert!((d.y + 10.0).abs() < 0.1, "{d:?}");
        assert!(d.x < -2.0, "nasal (toward -x for the left eye): {d:?}");
        // Far above: nothing; inside the opening: nothing.
        assert!(
            lids.action_at(LidAction::Blink, DVec3::new(32.0, 16.0, 0.0))
                .is_none()
        );
        assert!(
            lids.action_at(LidAction::Blink, DVec3::new(32.0, 0.0, 0.0))
                .is_none()
        );
        // Below the lower margin: only the nasal slide.
        let d = lids
            .action_at(LidAction::Blink, DVec3::new(32.0, -6.0, 0.0))
            .unwrap();
        assert!(d.y.abs() < 1e-9 && d.x < 0.0);
    }

    #[test]
    fn squint_raises_the_lower_lid_and_wide_the_upper_one() {
        let (p, lp) = eye();
        let lids = EyeLids::new(&p, &lp, Side::Left, 1.0).unwrap();
        let s = lids
            .action_at(LidAction::Squint, DVec3::new(32.0, -6.0, 0.0))
            .unwrap();
        assert!((s.y - SQUINT_RISE_FRACTION * 10.0).abs() < 0.1, "{s:?}");
        // ... and toward the medial corner (−x for the face's left eye), by at most
        // SQUINT_MEDIAL_RATIO of the rise (less toward the corners).
        assert!(
            s.x < -0.1 * s.y && -s.x <= SQUINT_MEDIAL_RATIO * s.y + 1e-9,
            "{s:?}"
        );
        assert!(
            lids.action_at(LidAction::Squint, DVec3::new(32.0, 6.0, 0.0))
                .is_none()
        );
        let w = lids
            .action_at(LidAction::Wide, DVec3::new(32.0, 6.0, 0.0))
            .unwrap();
        assert!((w.y - WIDE_RAISE_FRACTION * 10.0).abs() < 0.1, "{w:?}");
    }

    #[test]
    fn the_right_eye_slides_nasally_toward_plus_x() {
        let (p, lp) = eye();
        let p: Vec<DVec3> = p.iter().map(|q| DVec3::new(-q.x, q.y, q.z)).collect();
        let lids = EyeLids::new(&p, &lp, Side::Right, 1.0).unwrap();
        assert!(lids.nasal_slide(0.5).x > 2.0);
    }
}
