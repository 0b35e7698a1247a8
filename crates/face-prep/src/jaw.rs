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
//! - `jaw_open`: rotation about the TMJ axis by [`OPEN_RAD`], linearised, with the condyle's
//!   forward glide [`CONDYLE_GLIDE_MM`] (a real opening rotates the condyle in its fossa and
//!   slides it forward onto the articular eminence: Okeson, *Management of Temporomandibular
//!   Disorders and Occlusion*, ch. 1): `d = θ (x̂ × (p − pivot)) + g ẑ`. The sum is a rotation
//!   about a parallel axis `g / θ` below the TMJ, the hinge ([`Jaw::hinge`]; about 38 mm below
//!   the joint, near the mandibular foramen, where the instantaneous centre of a human opening
//!   is found: Grant, J Biomech 1973). The chin moves down and back, the angle of the jaw
//!   hardly moves. The glide is a translation, exact; a linearised rotation is exact
//!   to first order only: a point at radius r moves θ r along the tangent instead of along the
//!   arc, so it overshoots the true position by r(θ − sin θ) along the tangent and misses the
//!   inward (toward the pivot) component r(1 − cos θ). At θ = 0.42 rad (24.1°) and r = 110 mm
//!   (TMJ to the lower lip on an adult) that is 1.4 mm and 9.6 mm, and the jaw is stretched
//!   by √(1 + θ²) − 1 = 8.5 %.
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

use crate::anatomy::Landmarks;
use crate::features::FeatureBoxes;
use crate::orient::{FaceLoops, loop_centroid};
use crate::shell::{ElementTag, Shell};
use glam::{DVec2, DVec3};

/// Opening angle of `jaw_open` at full activation, radians (24.1°): the lower lip moves about
/// 33 mm down on an adult (ICT's captured jawOpen: 41 mm in total, 35 mm down).
pub const OPEN_RAD: f64 = 0.42;
/// Forward glide of the condyle at full `jaw_open`, mm (the condyle translates 15–20 mm at a
/// maximal opening).
pub const CONDYLE_GLIDE_MM: f64 = 16.0;
/// Protrusion of `jaw_forward` at full activation, mm (adult maximum protrusion is 8–10 mm).
pub const FORWARD_MM: f64 = 8.0;
/// Lateral shift of `jaw_lateral` at full activation, mm (adult maximum lateral excursion is
/// about 10 mm).
pub const LATERAL_MM: f64 = 8.0;
/// Height of the TMJ axis below the eye line, fraction of the eye-line-to-mouth height.
pub const TMJ_BELOW_EYES_H: f64 = 0.3;
/// Depth of the TMJ axis behind the eye loops' mean depth, in interocular distances.
pub const TMJ_BEHIND_EYES_IOD: f64 = 1.1;

/// One rigid mode of the jaw.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JawMode {
    /// Rotation about the TMJ axis (mouth opening).
    Open,
    /// Protrusion (translation toward +z).
    Forward,
    /// Lateral shift (translation along x).
    Lateral,
}

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
    /// Rim elements of the jaw segment (sorted).
    pub elements: Vec<u32>,
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
        let hinge = pivot - DVec3::Y * (CONDYLE_GLIDE_MM / mm_per_unit / OPEN_RAD);
        let elements = (0..shell.element_count())
            .filter(|&e| shell.tags[e] == ElementTag::Rim && shell.centroid(e).y < hinge.y)
            .map(|e| e as u32)
            .collect();
        Jaw {
            pivot,
            hinge,
            mouth_line_y: l.mouth.y,
            lip_line_y: l.mouth_bottom,
            elements,
        }
    }

    /// Displacement of point `p` (canonical) at full ACTIVATION of `mode` (slider −1), in mesh
    /// units (`mm_per_unit` converts the millimetre amplitudes).
    ///
    /// ```
    /// use face_prep::jaw::{CONDYLE_GLIDE_MM, Jaw, JawMode, OPEN_RAD};
    /// use glam::DVec3;
    /// let hinge = DVec3::new(0.0, -CONDYLE_GLIDE_MM / OPEN_RAD, 0.0); // mm
    /// let jaw = Jaw { pivot: DVec3::ZERO, hinge, mouth_line_y: -50.0, lip_line_y: -55.0, elements: vec![] };
    /// // The hinge stays; a chin 60 below and 90 in front of it moves down and back.
    /// assert!(jaw.activation(JawMode::Open, hinge, 1.0).length() < 1e-12);
    /// let chin = hinge + DVec3::new(0.0, -60.0, 90.0);
    /// let d = jaw.activation(JawMode::Open, chin, 1.0);
    /// assert!((d - DVec3::new(0.0, -90.0, -60.0) * OPEN_RAD).length() < 1e-9);
    /// ```
    pub fn activation(&self, mode: JawMode, p: DVec3, mm_per_unit: f64) -> DVec3 {
        match mode {
            JawMode::Open => {
                OPEN_RAD * DVec3::X.cross(p - self.pivot)
                    + DVec3::Z * (CONDYLE_GLIDE_MM / mm_per_unit)
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
