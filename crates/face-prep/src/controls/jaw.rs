//! The jaw: a segment of the shell's fixed rim that moves rigidly with the mandible, about a
//! temporomandibular (TMJ) axis placed from the eyes and the mouth (anatomical model only).
//!
//! # The segment
//!
//! The skull (fixed) elements are the rim (the thickened outer contour) and the back elements
//! in the skull box (above the eyes) and the nose box (between the eyes and the mouth), so below
//! the eyes the skull is the rim alone. The **jaw segment** is every rim element whose centroid
//! lies below the opening's hinge ([`Jaw::hinge`], see below): the contour along the chin, the
//! jawline and the lower ramus. The rest of the contour stays fixed: the skin over the joint
//! and the upper ramus does not follow the condyle, which slides forward under it. The hinge is
//! where the opening moves the jaw least, so the jaw segment meets the fixed contour where the
//! jaw moves least (a few millimetres at the side contour, which lies in front of the ramus).
//!
//! # The mandible's lower border and the neck
//!
//! A face cut below the jaw line (a whole head, ICT's full face) has contour under the chin and on
//! the neck, which the mandible does not carry. The mandible's lower border is modelled as the
//! mandibular plane: through the gonion, [`RAMUS_HEIGHT_H`] × h below the joint (condylion to
//! gonion, 50–60 mm in adults), rising toward the back at [`MANDIBULAR_PLANE_RAD`] to the
//! horizontal (the Frankfort–mandibular plane angle, 25° ± 5°: Tweed, *Angle Orthodontist* 24,
//! 1954). Skin down to [`SUBMENTAL_TISSUE_H`] × h below that plane (the soft tissue under the
//! bone) is carried whole; below it the carried share falls smoothly to none at a further
//! [`NECK_FALLOFF_H`] × h, so the skin under the jaw line stretches toward a still neck. Skin
//! below the plane hangs from the border above it: it takes the motion of the point of the
//! plane it lies under ([`Jaw::carried`]). This holds for the contour (the jaw segment's
//! prescribed motion) and for the muscle bands the jaw carries. ICT-FaceKit's captured jawOpen
//! (`tests/data/calibration`) moves the narrow face's lowest contour point, on the neck 46 mm
//! below the plane, 11.5 mm while the lower lip moves 41 mm; a rigid segment moved it 45.6 mm.
//!
//! # The TMJ axis
//!
//! The condyle of the mandible sits 12.5 ± 3.5 mm in front of the summit of the tragus, just
//! below the inferior border of the zygomatic arch (surface projection from 150 joints:
//! "Establishing surface projection of temporo-mandibular joint using tragus of ear as
//! landmark"); the zygomatic arch runs at the level of the Frankfort horizontal, through the
//! lowest point of the orbital rim, about 12–15 mm below the pupils (Gray's Anatomy, 41st ed.,
//! ch. 29/30). The ear canal lies about 80 mm behind the front of the eye, so the joint lies
//! about 70 mm behind it. From the features the rig recognises:
//!
//! - height: [`TMJ_BELOW_EYES_H`] × h below the eye line (h = eye line to mouth centre, about
//!   70 mm, so about 21 mm below the eyes);
//! - depth: [`TMJ_BEHIND_EYES_IOD`] × iod behind the eye loops' mean depth (about 69 mm);
//! - the axis runs along canonical x (through both condyles), so the pivot's x is the mouth's
//!   centre line and only its height and depth matter.
//!
//! # The three rigid modes (one response each; the BEM is linear)
//!
//! Slider convention as for every control: −1 is full activation.
//!
//! - `jaw_open`: rotation about the TMJ axis by [`OPEN_RAD`] with the condyle's forward glide
//!   [`CONDYLE_GLIDE_MM`] (a real opening rotates the condyle in its fossa and slides it forward
//!   onto the articular eminence: Okeson, *Management of Temporomandibular Disorders and
//!   Occlusion*, ch. 1): `d = (R(θ) − I)(p − pivot) + g ẑ`, the chord of the arc, so the full
//!   opening is the exact rigid motion (a tangent `θ x̂ × (p − pivot)` misses the inward
//!   r (1 − cos θ), 13 mm at the lower lip, and put the chin and lip too far forward against
//!   ICT's capture). The sum is a rotation by θ about a parallel axis, the hinge
//!   ([`Jaw::hinge`], [`hinge_offset`]; about 14 mm below the joint and 3 mm in front of it).
//!   The chin moves down and back. The BEM is linear in the slider, so a partial opening moves
//!   along the chord: at half opening a point at r = 110 mm from the joint is 3.4 mm off the
//!   true half rotation (0 at none and at full).
//! - `jaw_forward`: protrusion, a translation of [`FORWARD_MM`] toward +z (the face's front).
//! - `jaw_lateral`: a translation of [`LATERAL_MM`] along x (−1: toward the face's left, +x).
//!
//! # What else moves with the jaw
//!
//! The responses share one factorisation, so every muscle band element is
//! displacement-prescribed in every response. In a jaw response a band element carries the
//! jaw's motion times [`Jaw::tissue_weight`]: 1 on the lower face (below the lower lip's inner
//! margin: the mentalis and depressor labii inferioris lie on the mandible), 0 from the mouth's
//! centre line up (the upper lip, cheeks, nose and brows stay), a smoothstep between. Every
//! other element of the lower face (the lower lip, the chin between the bands) follows through
//! the elastic solve.

use crate::controls::anatomy::Landmarks;
pub use crate::controls::ids::JawMode;
use crate::frame::features::FeatureBoxes;
use crate::frame::orient::{FaceLoops, loop_centroid};
use crate::shell::{ElementTag, Shell};
use glam::{DVec2, DVec3};

/// Opening angle of `jaw_open` at full activation, radians (28.6°): the lower lip moves 36–44 mm
/// in all on the bundled faces, 26–30 mm of it down (ICT's captured jawOpen: 41 mm in all, 35 mm
/// down).
pub const OPEN_RAD: f64 = 0.5;
/// Forward glide of the condyle at full `jaw_open`, mm. The condyle translates 15–20 mm at a
/// maximal opening; 6 mm matched ICT's captured jawOpen best with a rigid segment down to the
/// neck (cosine 0.904 on the 13k face, 0.874 at 16 mm) and makes the chin move as far as the
/// lower lip. With the neck still: 0.944 (3 mm 0.939, 9 mm 0.946, 12 mm 0.944).
pub const CONDYLE_GLIDE_MM: f64 = 6.0;
/// Protrusion of `jaw_forward` at full activation, mm (adult maximum protrusion is 8–10 mm).
pub const FORWARD_MM: f64 = 8.0;
/// Lateral shift of `jaw_lateral` at full activation, mm (adult maximum lateral excursion is
/// about 10 mm).
pub const LATERAL_MM: f64 = 8.0;
/// Height of the TMJ axis below the eye line, fraction of the eye-line-to-mouth height.
pub const TMJ_BELOW_EYES_H: f64 = 0.3;
/// Depth of the TMJ axis behind the eye loops' mean depth, in interocular distances.
pub const TMJ_BEHIND_EYES_IOD: f64 = 1.1;
/// Height of the ramus, condylion (the TMJ pivot) to gonion, fraction of the eye-line-to-mouth
/// height h (0.75 h ≈ 52 mm at h = 70 mm; adult condylion–gonion 50–60 mm).
pub const RAMUS_HEIGHT_H: f64 = 0.75;
/// Angle of the mandibular plane (the mandible's lower border) to the horizontal, rising toward
/// the back, radians (25°: the Frankfort–mandibular plane angle, 25° ± 5°).
pub const MANDIBULAR_PLANE_RAD: f64 = 25.0 * std::f64::consts::PI / 180.0;
/// Soft tissue below the mandibular plane that the jaw carries whole, fraction of h (0.15 h ≈
/// 10 mm: soft-tissue thickness under the menton is 7–10 mm).
pub const SUBMENTAL_TISSUE_H: f64 = 0.15;
/// Below that tissue, the distance over which the carried share of the jaw's motion falls from
/// all to none (smoothstep), fraction of h (0.7 h ≈ 49 mm). Calibrated against ICT's captured
/// jawOpen, which moves the neck 46 mm below the plane by 28 % of the lower lip's motion: this
/// gives 0.16 of the border's motion there, and the issue's bound (≤ 15 mm) holds.
pub const NECK_FALLOFF_H: f64 = 1.0;

/// The jaw of a rig: the TMJ axis, the rim segment that moves with it and the lip lines that
/// bound the tissue carried along.
#[derive(Clone, Debug, PartialEq)]
pub struct Jaw {
    /// A point on the TMJ axis (canonical frame; the axis runs along x).
    pub pivot: DVec3,
    /// A point on the opening's hinge: the axis parallel to the TMJ axis about which the
    /// rotation with the condyle's glide turns ([`CONDYLE_GLIDE_MM`] / [`OPEN_RAD`] below the
    /// pivot). The jaw segment is the rim below it.
    pub hinge: DVec3,
    /// The mouth's centre line height (tissue above it does not move with the jaw).
    pub mouth_line_y: f64,
    /// The lower lip's inner margin (bottom of the mouth box): tissue below it moves with the
    /// jaw.
    pub lip_line_y: f64,
    /// The gonion: a point on the mandibular plane ([`RAMUS_HEIGHT_H`] below the pivot).
    pub gonion: DVec3,
    /// Unit normal of the mandibular plane, pointing up and forward (+y, +z).
    pub border_normal: DVec3,
    /// The soft tissue the jaw carries whole below the plane, mesh units.
    pub submental_tissue: f64,
    /// The distance below that over which the jaw's share falls to none, mesh units.
    pub neck_falloff: f64,
    /// Rim elements of the jaw segment (sorted): below the hinge, above the still neck.
    pub elements: Vec<u32>,
}

/// Offset from the TMJ pivot to the opening's hinge (canonical, mesh units) for a condylar glide
/// `glide`: the fixed point of the rotation by [`OPEN_RAD`] about the pivot followed by the glide
/// along +z, `(−g sin θ / (2 (1 − cos θ)), g / 2)` in (y, z) (≈ g / θ below the pivot).
///
/// ```
/// use face_prep::jaw::{OPEN_RAD, hinge_offset};
/// let o = hinge_offset(16.0);
/// // About g / θ below the pivot (the small-angle hinge), half the glide in front of it.
/// assert!((o.y + 16.0 / OPEN_RAD).abs() < 0.05 * 16.0 / OPEN_RAD);
/// assert!((o.z - 8.0).abs() < 1e-12 && o.x == 0.0);
/// ```
pub fn hinge_offset(glide: f64) -> DVec3 {
    let (sin, cos) = OPEN_RAD.sin_cos();
    DVec3::new(0.0, -glide * sin / (2.0 * (1.0 - cos)), 0.5 * glide)
}

impl Jaw {
    /// The jaw of a shell with its loops and feature boxes (canonical frame), its unit
    /// `mm_per_unit` millimetres.
    pub fn of(shell: &Shell, loops: &FaceLoops, boxes: &FeatureBoxes, mm_per_unit: f64) -> Jaw {
        let l = Landmarks::of(boxes);
        let eye_depth = 0.5
            * (loop_centroid(&shell.vertices, &loops.eye_l).z
                + loop_centroid(&shell.vertices, &loops.eye_r).z);
        let eye_y = 0.5 * (l.eye_l.y + l.eye_r.y);
        let pivot = DVec3::new(
            l.mouth.x,
            eye_y - TMJ_BELOW_EYES_H * l.h,
            eye_depth - TMJ_BEHIND_EYES_IOD * l.iod,
        );
        let hinge = pivot + hinge_offset(CONDYLE_GLIDE_MM / mm_per_unit);
        let (sin, cos) = MANDIBULAR_PLANE_RAD.sin_cos();
        let mut jaw = Jaw {
            pivot,
            hinge,
            mouth_line_y: l.mouth.y,
            lip_line_y: l.mouth_bottom,
            gonion: pivot - DVec3::Y * (RAMUS_HEIGHT_H * l.h),
            border_normal: DVec3::new(0.0, cos, sin),
            submental_tissue: SUBMENTAL_TISSUE_H * l.h,
            neck_falloff: NECK_FALLOFF_H * l.h,
            elements: Vec::new(),
        };
        jaw.elements = (0..shell.element_count())
            .filter(|&e| {
                let c = shell.centroid(e);
                shell.tags[e] == ElementTag::Rim && c.y < hinge.y && jaw.carried(c).1 > 0.0
            })
            .map(|e| e as u32)
            .collect();
        jaw
    }

    /// Where the skin at `p` (canonical) hangs from the mandible, and the share of that point's
    /// motion it takes: `(p, 1)` above the mandibular plane; below it, the point of the plane
    /// above `p`, with 1 through the submental tissue falling (smoothstep) to 0 over the neck
    /// falloff.
    ///
    /// ```
    /// use face_prep::jaw::Jaw;
    /// use glam::DVec3;
    /// let jaw = Jaw {
    ///     pivot: DVec3::ZERO, hinge: DVec3::new(0.0, -12.0, 3.0), mouth_line_y: -50.0,
    ///     lip_line_y: -55.0, gonion: DVec3::new(0.0, -52.0, 0.0), border_normal: DVec3::Y,
    ///     submental_tissue: 10.0, neck_falloff: 50.0, elements: vec![],
    /// };
    /// // On the jaw: carried whole, where it is.
    /// let chin = DVec3::new(0.0, -45.0, 80.0);
    /// assert_eq!(jaw.carried(chin), (chin, 1.0));
    /// // Under the chin within the soft tissue: whole, as the border above it.
    /// let (q, w) = jaw.carried(DVec3::new(0.0, -58.0, 70.0));
    /// assert_eq!((q, w), (DVec3::new(0.0, -52.0, 70.0), 1.0));
    /// // Halfway down the falloff: half; past it (the neck): none.
    /// assert!((jaw.carried(DVec3::new(0.0, -87.0, 60.0)).1 - 0.5).abs() < 1e-12);
    /// assert_eq!(jaw.carried(DVec3::new(0.0, -120.0, 40.0)).1, 0.0);
    /// ```
    pub fn carried(&self, p: DVec3) -> (DVec3, f64) {
        let below = -(p - self.gonion).dot(self.border_normal);
        if below <= 0.0 {
            return (p, 1.0);
        }
        let x = if self.neck_falloff > 0.0 {
            ((below - self.submental_tissue) / self.neck_falloff).clamp(0.0, 1.0)
        } else if below > self.submental_tissue {
            1.0
        } else {
            0.0
        };
        (
            p + self.border_normal * below,
            1.0 - x * x * (3.0 - 2.0 * x),
        )
    }

    /// Displacement at full ACTIVATION of `mode` of the skin at `p` that the jaw carries
    /// ([`Jaw::carried`]): the jaw's motion at the point it hangs from, times its share.
    pub fn carried_activation(&self, mode: JawMode, p: DVec3, mm_per_unit: f64) -> DVec3 {
        let (q, w) = self.carried(p);
        w * self.activation(mode, q, mm_per_unit)
    }

    /// Displacement of point `p` (canonical) at full ACTIVATION of `mode` (slider −1), in mesh
    /// units (`mm_per_unit` converts the millimetre amplitudes).
    ///
    /// ```
    /// use face_prep::jaw::{CONDYLE_GLIDE_MM, Jaw, JawMode, OPEN_RAD, hinge_offset};
    /// use glam::DVec3;
    /// let hinge = hinge_offset(CONDYLE_GLIDE_MM); // mm, pivot at the origin
    /// let jaw = Jaw {
    ///     pivot: DVec3::ZERO, hinge, mouth_line_y: -50.0, lip_line_y: -55.0,
    ///     gonion: DVec3::new(0.0, -52.0, 0.0), border_normal: DVec3::Y,
    ///     submental_tissue: 10.0, neck_falloff: 50.0, elements: vec![],
    /// };
    /// // The hinge stays; a chin 60 below and 90 in front of it turns rigidly by OPEN_RAD about
    /// // the hinge: down and back, its distance from the hinge kept.
    /// assert!(jaw.activation(JawMode::Open, hinge, 1.0).length() < 1e-9);
    /// let chin = hinge + DVec3::new(0.0, -60.0, 90.0);
    /// let moved = chin + jaw.activation(JawMode::Open, chin, 1.0);
    /// assert!((moved.distance(hinge) - chin.distance(hinge)).abs() < 1e-9);
    /// assert!(moved.y < chin.y && moved.z < chin.z);
    /// ```
    pub fn activation(&self, mode: JawMode, p: DVec3, mm_per_unit: f64) -> DVec3 {
        match mode {
            JawMode::Open => {
                // The chord of the arc: exact at full opening (a tangent θ x̂ × r would miss
                // the inward r (1 − cos θ), 9.6 mm at the lower lip).
                let r = p - self.pivot;
                let (sin, cos) = OPEN_RAD.sin_cos();
                DVec3::new(
                    0.0,
                    r.y * (cos - 1.0) - r.z * sin,
                    r.y * sin + r.z * (cos - 1.0),
                ) + DVec3::Z * (CONDYLE_GLIDE_MM / mm_per_unit)
            }
            JawMode::Forward => DVec3::Z * (FORWARD_MM / mm_per_unit),
            JawMode::Lateral => DVec3::X * (LATERAL_MM / mm_per_unit),
        }
    }

    /// How much of the jaw's motion the soft tissue at `p` (front plane) carries when it is
    /// prescribed (a muscle band element): 1 below the lower lip's inner margin, 0 from the
    /// mouth's centre line up, smoothstep between.
    pub fn tissue_weight(&self, p: DVec2) -> f64 {
        let span = self.mouth_line_y - self.lip_line_y;
        if span <= 0.0 {
            return if p.y < self.mouth_line_y { 1.0 } else { 0.0 };
        }
        let x = ((self.mouth_line_y - p.y) / span).clamp(0.0, 1.0);
        x * x * (3.0 - 2.0 * x)
    }
}
