//! Feature boxes (thesis ch. 6) in the canonical front plane (x-y).

use crate::error::PrepError;
use crate::frame::orient::FaceLoops;
use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

/// An axis-aligned box in the canonical x-y plane.
///
/// Corner names follow the thesis: c4 = (xmin, ymin), c5 = (xmax, ymin), c6 = (xmin, ymax),
/// c7 = (xmax, ymax).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Box2 {
    /// Minimum corner.
    pub min: DVec2,
    /// Maximum corner.
    pub max: DVec2,
}

impl Box2 {
    /// Box from two corners.
    pub fn new(min: DVec2, max: DVec2) -> Box2 {
        Box2 { min, max }
    }
    /// Tight box around the x-y projection of points.
    pub fn around(points: impl IntoIterator<Item = DVec3>) -> Box2 {
        points.into_iter().fold(
            Box2::new(DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |b, p| Box2::new(b.min.min(p.truncate()), b.max.max(p.truncate())),
        )
    }
    /// Width (x extent).
    pub fn width(&self) -> f64 {
        self.max.x - self.min.x
    }
    /// Height (y extent).
    pub fn height(&self) -> f64 {
        self.max.y - self.min.y
    }
    /// Centre.
    pub fn center(&self) -> DVec2 {
        0.5 * (self.min + self.max)
    }
    /// Whether `p` lies inside or on the border.
    pub fn contains(&self, p: DVec2) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }
    /// c4 = (xmin, ymin).
    pub(crate) fn c4(&self) -> DVec2 {
        self.min
    }
    /// c5 = (xmax, ymin).
    pub(crate) fn c5(&self) -> DVec2 {
        DVec2::new(self.max.x, self.min.y)
    }
    /// c6 = (xmin, ymax).
    pub(crate) fn c6(&self) -> DVec2 {
        DVec2::new(self.min.x, self.max.y)
    }
    /// c7 = (xmax, ymax).
    pub(crate) fn c7(&self) -> DVec2 {
        self.max
    }
    /// The box moved by `delta`.
    pub fn translated(&self, delta: DVec2) -> Box2 {
        Box2::new(self.min + delta, self.max + delta)
    }
    /// The box grown by `margin` on every side (negative shrinks).
    pub fn grown(&self, margin: DVec2) -> Box2 {
        Box2::new(self.min - margin, self.max + margin)
    }
    /// The box scaled about its centre by `factor` per axis.
    pub fn scaled(&self, factor: DVec2) -> Box2 {
        let c = self.center();
        let h = 0.5 * (self.max - self.min) * factor;
        Box2::new(c - h, c + h)
    }
    fn check(&self, name: &'static str) -> Result<(), PrepError> {
        if self.min.is_finite()
            && self.max.is_finite()
            && self.min.x < self.max.x
            && self.min.y < self.max.y
        {
            Ok(())
        } else {
            Err(PrepError::InvalidBox {
                name,
                min: self.min.to_array(),
                max: self.max.to_array(),
            })
        }
    }
}

/// Fraction of the way from the eye line (mean centre height of the eye boxes) down to the mouth
/// centre where the nose box ends. Facial-proportion rule: the subnasale lies about 70% of the
/// way from the eye line to the stomion (eye line → subnasale ≈ 5 cm, subnasale → stomion ≈
/// 2 cm on an adult face; the neoclassical thirds canon puts glabella–subnasale = subnasale–menton).
pub const NOSE_BOTTOM_FRACTION: f64 = 0.7;

/// The feature boxes of thesis ch. 6, canonical frame, x-y plane.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FeatureBoxes {
    /// FBFace: bounding box of the outer contour.
    pub face: Box2,
    /// FBEyeL: the face's left eye (+x).
    pub eye_l: Box2,
    /// FBEyeR: the face's right eye (−x).
    pub eye_r: Box2,
    /// FBMouth.
    pub mouth: Box2,
    /// FBNose: x spans the gap between the eye boxes; y from the eye line (mean centre height
    /// of the eye boxes) down by [`NOSE_BOTTOM_FRACTION`] of the eye-line-to-mouth-centre
    /// distance, never below the top of the mouth box.
    pub nose: Box2,
    /// FBSkull (forehead): FBFace's width, from the top of the higher eye box to the top of FBFace.
    pub skull: Box2,
}

impl FeatureBoxes {
    /// Boxes from the four loops of a face whose vertices are in the canonical frame.
    pub(crate) fn from_loops(
        canonical_vertices: &[DVec3],
        loops: &FaceLoops,
    ) -> Result<FeatureBoxes, PrepError> {
        let b = |l: &[u32]| Box2::around(l.iter().map(|&i| canonical_vertices[i as usize]));
        FeatureBoxes::derive(
            b(&loops.face),
            b(&loops.eye_l),
            b(&loops.eye_r),
            b(&loops.mouth),
        )
    }

    /// Derives FBNose and FBSkull from the four measured boxes (after the user moved or resized
    /// them, for example) and checks them all.
    pub fn derive(
        face: Box2,
        eye_l: Box2,
        eye_r: Box2,
        mouth: Box2,
    ) -> Result<FeatureBoxes, PrepError> {
        let eye_line = 0.5 * (eye_l.center().y + eye_r.center().y);
        let bottom =
            (eye_line - NOSE_BOTTOM_FRACTION * (eye_line - mouth.center().y)).max(mouth.max.y);
        let nose = Box2::new(
            DVec2::new(eye_r.max.x, bottom),
            DVec2::new(eye_l.min.x, eye_line),
        );
        let skull = Box2::new(
            DVec2::new(face.min.x, eye_l.max.y.max(eye_r.max.y)),
            DVec2::new(face.max.x, face.max.y),
        );
        let boxes = FeatureBoxes {
            face,
            eye_l,
            eye_r,
            mouth,
            nose,
            skull,
        };
        boxes.check()?;
        Ok(boxes)
    }

    /// Checks every box is finite and non-empty.
    pub fn check(&self) -> Result<(), PrepError> {
        self.face.check("FBFace")?;
        self.eye_l.check("FBEyeL")?;
        self.eye_r.check("FBEyeR")?;
        self.mouth.check("FBMouth")?;
        self.nose.check("FBNose")?;
        self.skull.check("FBSkull")
    }
}
