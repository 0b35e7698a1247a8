//! Anatomical attachments of the standard muscles, derived from the eyes and the mouth.
//!
//! Each muscle of the anatomical model ([`crate::controls::muscle_model`]) runs from an **origin** on
//! bone (fixed) to an **insertion** in the skin. Both are placed in the canonical front plane
//! (x-y; +x is the face's own left) from the two eye boxes and the mouth box only, the
//! features that are recognised reliably, never from the outer contour, so a contour that takes
//! in ears, neck or scalp does not drag a muscle there. Distances are fractions of the
//! interocular distance `iod` (eye-box centre to eye-box centre, 63 mm on an average adult) and
//! of the eye-line-to-mouth height `h` (eye-box centre height to mouth-box centre height,
//! about 70 mm), which scale with the face.
//!
//! Sources: Parke & Waters, *Computer Facial Animation* (2nd ed., 2008), ch. 3 (muscles of
//! facial expression, origins and insertions) and ch. 8 (linear muscle vectors from bone to
//! skin); Gray's Anatomy (41st ed.), ch. 29 (face and scalp); Standring's figures of the
//! modiolus. The widths are the muscles' typical belly widths; the shortenings are set so the
//! full contraction moves its insertion by the human motion-capture figures (Jorge Jr. et al.,
//! Braz J Otorhinolaryngol 2012: smile mouth corner 9.3 ± 2.8 mm, brow raise 10.6 ± 2.5 mm) and
//! the ICT-FaceKit captured shapes.

use crate::frame::features::FeatureBoxes;
use glam::DVec2;

/// Where and how big one muscle is, canonical frame (face units) and millimetres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Attachment {
    /// Bony origin, canonical x-y (fixed: prescribed displacement 0).
    pub origin: DVec2,
    /// Skin insertion, canonical x-y (largest prescribed displacement).
    pub insertion: DVec2,
    /// Half-width of the band of tissue the muscle drags, mm.
    pub half_width_mm: f64,
    /// Shortening at full contraction as a strain of the muscle's length (the insertion moves
    /// by `max_strain × length` toward the origin).
    pub max_strain: f64,
    /// Length, mm, past the insertion over which the skin moves with the insertion (a tendinous
    /// spread such as the modiolus at the mouth corner; 0 for most muscles).
    pub spread_mm: f64,
}

/// Feature measures the attachments are built from (canonical x-y).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Landmarks {
    /// Centre of the face's left eye box (+x).
    pub eye_l: DVec2,
    /// Centre of the face's right eye box.
    pub eye_r: DVec2,
    /// Half the larger eye-box width.
    pub eye_half_width: f64,
    /// Top of the higher eye box.
    pub eye_top: f64,
    /// Centre of the mouth box.
    pub mouth: DVec2,
    /// Half the mouth-box width.
    pub mouth_half_width: f64,
    /// Top of the mouth box.
    pub mouth_top: f64,
    /// Bottom of the mouth box.
    pub mouth_bottom: f64,
    /// Interocular distance (eye-box centres).
    pub iod: f64,
    /// Eye line (mean eye-box centre height) minus mouth-centre height.
    pub h: f64,
}

impl Landmarks {
    /// Landmarks of the eye and mouth boxes.
    ///
    /// ```
    /// use face_prep::{Box2, FeatureBoxes};
    /// use face_prep::anatomy::Landmarks;
    /// use glam::DVec2;
    /// let b = |x0, y0, x1, y1| Box2::new(DVec2::new(x0, y0), DVec2::new(x1, y1));
    /// let boxes = FeatureBoxes::derive(
    ///     b(-8.0, -10.0, 8.0, 8.0),
    ///     b(1.8, 1.0, 4.5, 2.0),
    ///     b(-4.5, 1.0, -1.8, 2.0),
    ///     b(-2.5, -5.5, 2.5, -4.5),
    /// )
    /// .unwrap();
    /// let l = Landmarks::of(&boxes);
    /// assert!((l.iod - 6.3).abs() < 1e-12);
    /// assert!((l.h - 6.5).abs() < 1e-12);
    /// ```
    pub fn of(b: &FeatureBoxes) -> Landmarks {
        let eye_l = b.eye_l.center();
        let eye_r = b.eye_r.center();
        let mouth = b.mouth.center();
        Landmarks {
            eye_l,
            eye_r,
            eye_half_width: 0.5 * b.eye_l.width().max(b.eye_r.width()),
            eye_top: b.eye_l.max.y.max(b.eye_r.max.y),
            mouth,
            mouth_half_width: 0.5 * b.mouth.width(),
            mouth_top: b.mouth.max.y,
            mouth_bottom: b.mouth.min.y,
            iod: eye_l.distance(eye_r),
            h: 0.5 * (eye_l.y + eye_r.y) - mouth.y,
        }
    }
}

/// The left eye's centre measured from the mouth's centre line (so left and right mirror
/// exactly): (x, y) of the face's-left eye.
fn left_eye(l: &Landmarks) -> DVec2 {
    DVec2::new(l.mouth.x + 0.5 * l.iod, 0.5 * (l.eye_l.y + l.eye_r.y))
}

/// Frontalis (face's left): galea aponeurotica → eyebrow skin.
pub(crate) fn frontalis(l: &Landmarks) -> Attachment {
    let eye = left_eye(l);
    Attachment {
        origin: DVec2::new(eye.x, eye.y + 0.95 * l.iod),
        insertion: DVec2::new(eye.x, eye.y + 0.2 * l.iod),
        half_width_mm: 24.0,
        max_strain: 0.28,
        spread_mm: 0.0,
    }
}

/// Levator labii superioris (face's left): infraorbital margin → upper lip.
pub(crate) fn levator_labii_superioris(l: &Landmarks) -> Attachment {
    let eye = left_eye(l);
    Attachment {
        origin: DVec2::new(eye.x - 0.2 * l.iod, eye.y - 0.3 * l.h),
        insertion: DVec2::new(
            l.mouth.x + 0.45 * l.mouth_half_width,
            l.mouth_top + 0.1 * l.iod,
        ),
        half_width_mm: 7.0,
        max_strain: 0.15,
        spread_mm: 0.0,
    }
}

/// Zygomaticus major (face's left): the zygomatic bone's lateral surface, in front of the
/// zygomaticotemporal suture (a quarter of the interocular distance lateral of the outer eye
/// corner) → the modiolus at the mouth corner. Its line rises 47–53° on the bundled faces (the
/// human smile moves the corner up and out at about 45°, ICT's captured smile at 55°; with the
/// origin just lateral of the eye corner it rose 59–64°).
pub(crate) fn zygomaticus_major(l: &Landmarks) -> Attachment {
    let eye = left_eye(l);
    Attachment {
        origin: DVec2::new(eye.x + l.eye_half_width + 0.25 * l.iod, eye.y - 0.3 * l.h),
        insertion: DVec2::new(l.mouth.x + l.mouth_half_width, l.mouth.y),
        half_width_mm: 8.0,
        max_strain: 0.22,
        // The modiolus: the lip corner moves with the insertion instead of hanging from it
        // as a thin free flap (up to 2.7 times the insertion's motion on the simplified
        // ICT faces without it).
        spread_mm: 6.0,
    }
}

/// Mentalis (face's left): incisive fossa of the mandible → chin skin.
pub(crate) fn mentalis(l: &Landmarks) -> Attachment {
    Attachment {
        origin: DVec2::new(
            l.mouth.x + 0.2 * l.mouth_half_width,
            l.mouth_bottom - 0.12 * l.h,
        ),
        insertion: DVec2::new(
            l.mouth.x + 0.2 * l.mouth_half_width,
            l.mouth_bottom - 0.42 * l.h,
        ),
        half_width_mm: 7.0,
        max_strain: 0.2,
        spread_mm: 0.0,
    }
}

/// Depressor labii inferioris (face's left): oblique line of the mandible → lower lip.
pub(crate) fn depressor_labii_inferioris(l: &Landmarks) -> Attachment {
    Attachment {
        origin: DVec2::new(
            l.mouth.x + 0.9 * l.mouth_half_width,
            l.mouth_bottom - 0.45 * l.h,
        ),
        insertion: DVec2::new(
            l.mouth.x + 0.4 * l.mouth_half_width,
            l.mouth_bottom - 0.05 * l.iod,
        ),
        half_width_mm: 7.0,
        max_strain: 0.15,
        spread_mm: 0.0,
    }
}

/// Corrugator supercilii (face's left): medial end of the superciliary arch, beside the root of
/// the nose at the level of the eyes → skin of the medial half of the eyebrow (pulls the brow
/// down and toward the midline: AU4). The line of pull runs about 40° below the horizontal, so
/// the inner brow moves down as much as in.
pub(crate) fn corrugator_supercilii(l: &Landmarks) -> Attachment {
    let eye = left_eye(l);
    Attachment {
        origin: DVec2::new(l.mouth.x + 0.06 * l.iod, eye.y),
        insertion: DVec2::new(eye.x - 0.15 * l.iod, eye.y + 0.28 * l.iod),
        half_width_mm: 8.0,
        max_strain: 0.6,
        spread_mm: 0.0,
    }
}

/// Procerus (unpaired): nasal bone → skin between the eyebrows (pulls it down: AU4 with the
/// corrugators, the horizontal wrinkle over the nose root).
pub(crate) fn procerus(l: &Landmarks) -> Attachment {
    let eye = left_eye(l);
    Attachment {
        origin: DVec2::new(l.mouth.x, eye.y - 0.25 * l.iod),
        insertion: DVec2::new(l.mouth.x, eye.y + 0.45 * l.iod),
        half_width_mm: 10.0,
        max_strain: 0.12,
        spread_mm: 0.0,
    }
}

/// Depressor anguli oris (face's left): oblique line of the mandible, below and lateral of the
/// mouth corner → modiolus (pulls the corner down and a little out: AU15, the frown).
pub(crate) fn depressor_anguli_oris(l: &Landmarks) -> Attachment {
    let corner = DVec2::new(l.mouth.x + l.mouth_half_width, l.mouth.y);
    Attachment {
        origin: DVec2::new(corner.x + 0.12 * l.iod, l.mouth.y - 0.55 * l.h),
        insertion: corner,
        half_width_mm: 7.0,
        max_strain: 0.2,
        spread_mm: 0.0,
    }
}

/// Risorius (face's left): parotid fascia over the masseter, lateral at mouth height →
/// modiolus (pulls the corner straight out: AU20, the lip stretcher).
pub(crate) fn risorius(l: &Landmarks) -> Attachment {
    let corner = DVec2::new(l.mouth.x + l.mouth_half_width, l.mouth.y);
    Attachment {
        origin: DVec2::new(corner.x + 0.75 * l.iod, l.mouth.y + 0.05 * l.h),
        insertion: corner,
        half_width_mm: 6.0,
        max_strain: 0.15,
        spread_mm: 0.0,
    }
}

/// Levator labii superioris alaeque nasi (face's left): frontal process of the maxilla beside
/// the inner eye corner → nasal ala and the upper lip beside the philtrum (AU9, the nose
/// wrinkler / sneer).
pub(crate) fn levator_labii_superioris_alaeque_nasi(l: &Landmarks) -> Attachment {
    let eye = left_eye(l);
    Attachment {
        origin: DVec2::new(eye.x - l.eye_half_width - 0.02 * l.iod, eye.y - 0.05 * l.h),
        insertion: DVec2::new(
            l.mouth.x + 0.3 * l.mouth_half_width,
            l.mouth_top + 0.05 * l.iod,
        ),
        half_width_mm: 5.0,
        max_strain: 0.15,
        spread_mm: 0.0,
    }
}

/// Zygomaticus minor (face's left): zygomatic bone, medial and below the major's origin →
/// upper lip, lateral part (AU13 with the levator anguli oris: the cheek puffer / sharp lip
/// puller; deepens the nasolabial fold).
pub(crate) fn zygomaticus_minor(l: &Landmarks) -> Attachment {
    let eye = left_eye(l);
    Attachment {
        origin: DVec2::new(eye.x + 0.3 * l.eye_half_width, eye.y - 0.3 * l.h),
        insertion: DVec2::new(l.mouth.x + 0.7 * l.mouth_half_width, l.mouth_top),
        half_width_mm: 5.0,
        max_strain: 0.15,
        spread_mm: 0.0,
    }
}

/// Levator anguli oris (face's left): canine fossa of the maxilla, below the infraorbital
/// foramen → modiolus (lifts the corner straight up: AU13).
pub(crate) fn levator_anguli_oris(l: &Landmarks) -> Attachment {
    let eye = left_eye(l);
    let corner = DVec2::new(l.mouth.x + l.mouth_half_width, l.mouth.y);
    Attachment {
        origin: DVec2::new(eye.x - 0.1 * l.iod, eye.y - 0.55 * l.h),
        insertion: corner,
        half_width_mm: 6.0,
        max_strain: 0.2,
        spread_mm: 0.0,
    }
}

/// Buccinator (face's left): pterygomandibular raphe and the alveolar processes at the molars
/// → modiolus (pulls the corner back and presses the cheek to the teeth: AU14, the dimpler).
pub(crate) fn buccinator(l: &Landmarks) -> Attachment {
    let corner = DVec2::new(l.mouth.x + l.mouth_half_width, l.mouth.y);
    Attachment {
        origin: DVec2::new(corner.x + 0.45 * l.iod, l.mouth.y - 0.02 * l.h),
        insertion: corner,
        half_width_mm: 9.0,
        max_strain: 0.12,
        spread_mm: 0.0,
    }
}

/// Orbicularis oculi, orbital part over the malar cheek (face's left): its lower fibres run
/// round the orbit over the zygoma from the medial palpebral ligament and spread onto the
/// cheek; contracting, they draw the malar skin and fat up toward the orbit (AU6, the cheek
/// raiser; Gray's Anatomy, 41st ed., ch. 29; Ekman & Friesen, FACS manual, AU6). Modelled as a
/// force-driven pull from the malar skin, 0.5 h below the eye line, toward the lateral
/// infraorbital margin, over a band 22 mm either side (the malar eminence); the shortening
/// 0.22 of its length moves the cheek about 7 mm (ICT-FaceKit's captured cheekSquint: 6.3 mm,
/// up and a little forward, over x 26–70 mm, y 45 mm below to 7 mm above the eye centre).
pub(crate) fn orbicularis_oculi_malar(l: &Landmarks) -> Attachment {
    let eye = left_eye(l);
    Attachment {
        origin: DVec2::new(eye.x + 0.2 * l.iod, eye.y - 0.05 * l.iod),
        insertion: DVec2::new(eye.x + 0.3 * l.iod, eye.y - 0.5 * l.h),
        half_width_mm: 22.0,
        max_strain: 0.22,
        spread_mm: 0.0,
    }
}

/// Orbicularis oculi, orbital part over the brow (face's left): its upper fibres run round the
/// orbit over the eyebrow from the medial palpebral ligament and the frontal process of the
/// maxilla (with the depressor supercilii, its medial slip); contracting, they draw the whole
/// brow down and toward the nose (AU4 with the corrugator and procerus; Gray's Anatomy, 41st
/// ed., ch. 29; Ekman & Friesen, FACS manual, AU4). Modelled as a force-driven pull from the
/// upper edge of the brow, 0.45 iod above the eye centre and 0.15 iod lateral of it, toward the
/// medial orbital margin, 0.4 iod medial of the eye centre at its height, over a band 26 mm
/// either side (the brow and the skin above it move as one sheet). The line runs about 39°
/// below the horizontal, as ICT-FaceKit's captured browDown moves its brow (medial 0.69, down
/// 0.56 over the vertices moving ≥ 90 % of its peak, 6.5 mm, 17–31 mm above the eye centre;
/// half of the peak is still reached 43 mm above it); the shortening 0.17 of its length (0.71
/// iod, about 45 mm on an adult face) moves the brow about 7.7 mm. Tried: narrower (16 mm,
/// insertion 0.38 iod above the eye), browDown's fitted cosine 0.69, the motion too focal;
/// inserted 0.5 iod above the eye, its band reached ICT 2500's forehead contour and turned a
/// triangle over there.
pub(crate) fn orbicularis_oculi_superior(l: &Landmarks) -> Attachment {
    let eye = left_eye(l);
    Attachment {
        origin: DVec2::new(eye.x - 0.4 * l.iod, eye.y),
        insertion: DVec2::new(eye.x + 0.15 * l.iod, eye.y + 0.45 * l.iod),
        half_width_mm: 26.0,
        max_strain: 0.17,
        spread_mm: 0.0,
    }
}
