//! Placing the rig's standard controls and generating their prescribed displacements: the two
//! dispatch points on [`crate::controls::muscle_kind::Generator`] (see `muscle_kind.rs` on how to add a
//! control).

use crate::controls::jaw::{Jaw, JawMode};
use crate::controls::muscle_kind::attachment;
use crate::controls::muscle_kind::{Generator, MuscleKind, Side};
use crate::controls::muscle_model::{MuscleModel, anatomical_pattern, place_band};
use crate::controls::muscles::{Muscle, muscle_pattern};
use crate::rig::FaceRig;
use glam::DVec3;
use std::collections::{BTreeMap, HashSet};

impl FaceRig {
    /// Places one standard control in the anatomical model: its elements (chains) on the
    /// shell. `skull` holds the rig's skull elements (never part of a band).
    pub(crate) fn place_control(&self, kind: MuscleKind, skull: &HashSet<u32>) -> Muscle {
        let (front_chain, back_chain) = match kind.generator() {
            Generator::Band(_) | Generator::Force(_) => match attachment(kind, &self.boxes) {
                Some(att) => {
                    let place = if kind.is_force() {
                        crate::controls::force_controls::place_force_band
                    } else {
                        place_band
                    };
                    place(
                        &self.shell,
                        skull,
                        &att,
                        self.mm_per_unit(),
                        &self.params.anatomical,
                    )
                }
                None => (Vec::new(), Vec::new()),
            },
            // The jaw's elements are skull (rim) elements: [`FaceRig::jaw`].
            Generator::Jaw(_) => (Vec::new(), Vec::new()),
            Generator::Sphincter(lip) => crate::controls::force_controls::place_sphincter(
                &self.shell,
                skull,
                &self.mouth_xy(),
                self.boxes.mouth.center().y,
                lip,
                self.mm_per_unit(),
            ),
            Generator::Pressure => (
                Vec::new(),
                crate::controls::force_controls::place_cheek_puff(
                    &self.shell,
                    skull,
                    &crate::controls::anatomy::Landmarks::of(&self.boxes),
                ),
            ),
            Generator::Lid(action) => self
                .eye_lids(kind.side())
                .map(|lids| lids.band(&self.shell, skull, action))
                .unwrap_or_default(),
        };
        Muscle {
            name: kind.display_name().to_owned(),
            kind: Some(kind),
            front_chain,
            back_chain,
        }
    }

    /// Prescribed per-element displacement of `muscle` at slider = +1 (canonical frame): the
    /// thesis rule in the thesis model; in the anatomical model the control's generator (a
    /// custom muscle, `kind == None`, is a band from its chain's ends).
    pub(crate) fn control_pattern(&self, muscle: &Muscle) -> Vec<(u32, DVec3)> {
        match self.params.muscle_model {
            MuscleModel::Thesis => muscle_pattern(&self.shell, muscle),
            MuscleModel::Anatomical => match muscle.kind.map(MuscleKind::generator) {
                None | Some(Generator::Band(_)) => self.band_pattern(muscle),
                Some(Generator::Jaw(mode)) => self.jaw_pattern(mode),
                Some(Generator::Pressure) => self.cheek_puff_traction(muscle),
                Some(Generator::Sphincter(_)) => self.sphincter_traction(muscle),
                Some(Generator::Force(_)) => self.force_band_traction(muscle),
                Some(Generator::Lid(action)) => self
                    .eye_lids(muscle.kind.map_or(Side::Left, MuscleKind::side))
                    .map(|lids| {
                        lids.pattern(&self.shell, &self.contour_xy(), action, muscle.elements())
                    })
                    .unwrap_or_default(),
            },
        }
    }

    /// [`anatomical_pattern`] of `muscle` on this rig: its band's per-element motion at
    /// slider = +1 (a prescribed band's displacement; a force-driven band's traction shape).
    pub(crate) fn band_pattern(&self, muscle: &Muscle) -> Vec<(u32, DVec3)> {
        anatomical_pattern(
            &self.shell,
            &self.shell_bvh(),
            &self.boxes,
            &self.contour_xy(),
            muscle,
            self.mm_per_unit(),
            &self.params.anatomical,
        )
    }

    /// The rig's jaw ([`crate::controls::jaw`]): TMJ axis and jaw segment of the rim.
    ///
    /// ```
    /// use face_prep::{ElementTag, FaceRig, RigParams, load_face};
    /// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
    ///     .join("../../assets/mediapipe_canonical_4loop.obj");
    /// let rig = FaceRig::build(&load_face(&path).unwrap(), &RigParams::default()).unwrap();
    /// let jaw = rig.jaw();
    /// assert!(!jaw.elements.is_empty());
    /// assert!(jaw.elements.iter().all(|&e| rig.shell.tags[e as usize] == ElementTag::Rim));
    /// // Behind the face, between the eyes and the mouth; the hinge below the joint.
    /// assert!(jaw.pivot.y < rig.boxes.eye_l.min.y && jaw.pivot.y > rig.boxes.mouth.max.y);
    /// assert!(jaw.hinge.y < jaw.pivot.y && jaw.hinge.z > jaw.pivot.z);
    /// ```
    pub fn jaw(&self) -> Jaw {
        Jaw::of(&self.shell, &self.loops, &self.boxes, self.mm_per_unit())
    }

    /// Per-element displacement of a jaw mode at slider = +1 (the negative of its activation):
    /// the jaw segment rigidly, every band element of the other controls with the jaw's motion
    /// times [`Jaw::tissue_weight`] (elements of no band keep 0 there).
    fn jaw_pattern(&self, mode: JawMode) -> Vec<(u32, DVec3)> {
        let jaw = self.jaw();
        let mm = self.mm_per_unit();
        let mut out: BTreeMap<u32, DVec3> = BTreeMap::new();
        // Only displacement-prescribed elements are carried (a force-driven control's elements
        // are traction-type: a value there would be a traction).
        for (k, m) in self.muscles.iter().enumerate() {
            if self.is_force_control(k) {
                continue;
            }
            for e in m.elements() {
                let c = self.shell.centroid(e as usize);
                let w = jaw.tissue_weight(c.truncate());
                out.insert(e, -w * jaw.activation(mode, c, mm));
            }
        }
        for &e in &jaw.elements {
            let c = self.shell.centroid(e as usize);
            out.insert(e, -jaw.activation(mode, c, mm));
        }
        // The lower teeth move with the jaw: the deep layer sliding on them follows it along
        // their normal (the solve keeps only that part on a sliding element).
        for e in self.sliding_elements() {
            if self.on_lower_teeth(e) {
                let c = self.shell.centroid(e as usize);
                out.insert(e, -jaw.activation(mode, c, mm));
            }
        }
        out.into_iter().collect()
    }

    /// Vertices whose displacement in response `muscle_index` is known exactly rather than
    /// averaged from their elements, with that displacement at slider = +1 (canonical frame):
    /// for a jaw mode, every vertex of the jaw segment moves rigidly (so the jaw's part of the
    /// outer contour moves with the jaw); empty for every other control.
    pub fn prescribed_vertex_motion(&self, muscle_index: usize) -> Vec<(u32, DVec3)> {
        let Some(Generator::Jaw(mode)) = self
            .muscles
            .get(muscle_index)
            .and_then(|m| m.kind)
            .map(MuscleKind::generator)
        else {
            return Vec::new();
        };
        if self.params.muscle_model != MuscleModel::Anatomical {
            return Vec::new();
        }
        let jaw = self.jaw();
        let mm = self.mm_per_unit();
        let vertices: std::collections::BTreeSet<u32> = jaw
            .elements
            .iter()
            .flat_map(|&e| self.shell.triangles[e as usize])
            .collect();
        vertices
            .into_iter()
            .map(|v| {
                let p = self.shell.vertices[v as usize];
                (v, -jaw.activation(mode, p, mm))
            })
            .collect()
    }
}
