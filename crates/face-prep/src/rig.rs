//! The face rig: everything the BEM needs, built from one face mesh.

use crate::bvh::TriangleBvh;
use crate::controls::dispatch::{self, control_pattern, place_control};
use crate::controls::eyelid::lid_back_elements;
use crate::controls::force_controls;
use crate::controls::jaw::Jaw;
use crate::controls::modiolus::{self, ModiolusPin};
use crate::controls::muscle_kind::{MuscleKind, Side};
use crate::controls::muscle_model::{AnatomicalParams, MuscleModel, shell_bvh};
use crate::controls::muscles::{Muscle, place_standard_muscles, skull_elements};
use crate::controls::rig_parts::RigParts;
use crate::controls::teeth;
use crate::error::PrepError;
use crate::frame::features::FeatureBoxes;
use crate::frame::orient::{FaceLoops, canonical_frame, loop_centroid, loop_xy};
use crate::frame::topology;
use crate::input::face_mesh::FaceMesh;
use crate::input::units::{LengthUnit, UnitChoice, Units};
use crate::shell::{ElementTag, Shell, ShellDims};
use glam::{DAffine3, DVec3};
use serde::{Deserialize, Serialize};
use std::collections::HashSet;

/// Parameters of rig building. Lengths are fractions of the face size, defined as the larger
/// side of FBFace (the outer contour's bounding box in the canonical front plane), so defaults
/// work for faces in cm, m or arbitrary model units.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RigParams {
    /// Back-face offset along the inward vertex normal, fraction of face size. Default 0.015
    /// (3 mm on a 20 cm face).
    pub offset: f64,
    /// How far the outer contour's copy is moved along the inward normal to make the rim,
    /// fraction of face size. Default 0.015.
    pub thickness: f64,
    /// A back vertex moves at most this fraction of the free distance along its inward normal
    /// to the front surface (keeps the back face inside nostrils and rolled lips). In (0, 1];
    /// default 0.45.
    pub offset_clamp: f64,
    /// Spacing of the rays cast along a muscle-definer, as a fraction of the median front edge
    /// length. Default 0.25.
    pub ray_spacing: f64,
    /// Distance from the eye and mouth contours, fraction of face size, over which the back
    /// face's offset grows from zero (knife edge) to `offset`. Default 0.05.
    pub taper: f64,
    /// Laplacian smoothing iterations of the back face's offset directions. Default 10.
    pub smoothing_iterations: usize,
    /// Rounds of local repair of self-intersections of the back face (each round scales the
    /// offset of the back vertices of intersecting elements by [`crate::shell::REPAIR_SHRINK`]).
    /// Default 8.
    pub repair_rounds: usize,
    /// Rounds of repair of the input surface's own self-intersections and cracks (e.g. lips
    /// that interpenetrate or press together) in the shell's copy of the front: the vertices
    /// involved are pushed apart by small local moves
    /// ([`crate::shell::repair_front_intersections`]; what moved, and how far, is in
    /// [`Shell::front_repair`]: 0.72% of the face size at most on the bundled ICT faces, nothing
    /// on the others). The input [`FaceMesh`] is never modified; 0 disables the repair.
    /// Default 30.
    pub front_repair_rounds: usize,
    /// The length unit of the mesh coordinates, or [`Units::Auto`] (default) to estimate it
    /// from the distance between the eyes ([`crate::input::units`]).
    pub units: Units,
    /// How muscles become prescribed displacements ([`MuscleModel`]; default anatomical).
    pub muscle_model: MuscleModel,
    /// Parameters of the anatomical muscle model.
    pub anatomical: AnatomicalParams,
}

impl Default for RigParams {
    fn default() -> Self {
        RigParams {
            offset: 0.015,
            thickness: 0.015,
            offset_clamp: 0.45,
            ray_spacing: 0.25,
            taper: 0.05,
            smoothing_iterations: 10,
            repair_rounds: 8,
            front_repair_rounds: 30,
            units: Units::Auto,
            muscle_model: MuscleModel::Anatomical,
            anatomical: AnatomicalParams::default(),
        }
    }
}

impl RigParams {
    /// Documented range of [`RigParams::offset`] and [`RigParams::thickness`] (fractions of
    /// the face size: 0.1 mm to 4 cm on a 20 cm face). Below it the back face coincides with
    /// the front to rounding (`--offset 1e-320` made the solve singular; at the lower end the
    /// solve is near-singular and the rig is reported untrustworthy); above it the shell is
    /// thicker than a face's soft tissue.
    pub(crate) const SHELL_FRACTION_RANGE: std::ops::RangeInclusive<f64> = 0.0005..=0.2;
    /// Documented range of [`RigParams::smoothing_iterations`], [`RigParams::repair_rounds`]
    /// and [`RigParams::front_repair_rounds`] (each round costs a pass over the shell).
    pub(crate) const ROUNDS_RANGE: std::ops::RangeInclusive<usize> = 0..=1000;

    /// Checks every numeric field against its documented range; the first field outside is
    /// returned as [`PrepError::InvalidParam`] naming it. [`FaceRig::build`] calls it first.
    ///
    /// ```
    /// use face_prep::{PrepError, RigParams};
    /// assert!(RigParams::default().validate().is_ok());
    /// let thin = RigParams { offset: 1e-320, ..RigParams::default() };
    /// assert!(matches!(thin.validate(), Err(PrepError::InvalidParam { name: "offset", .. })));
    /// ```
    pub fn validate(&self) -> Result<(), PrepError> {
        let within = |name, v: f64, range: std::ops::RangeInclusive<f64>, reason| {
            if range.contains(&v) {
                Ok(())
            } else {
                Err(PrepError::InvalidParam {
                    name,
                    value: v,
                    reason,
                })
            }
        };
        let shell = Self::SHELL_FRACTION_RANGE;
        within(
            "offset",
            self.offset,
            shell.clone(),
            "must be in [0.0005, 0.2]",
        )?;
        within(
            "thickness",
            self.thickness,
            shell,
            "must be in [0.0005, 0.2]",
        )?;
        let open_unit = |name, v: f64| {
            if v.is_finite() && v > 0.0 && v < 1.0 {
                Ok(())
            } else {
                Err(PrepError::InvalidParam {
                    name,
                    value: v,
                    reason: "must be in (0, 1)",
                })
            }
        };
        open_unit("ray_spacing", self.ray_spacing)?;
        open_unit("taper", self.taper)?;
        if !(self.offset_clamp > 0.0 && self.offset_clamp <= 1.0) {
            return Err(PrepError::InvalidParam {
                name: "offset_clamp",
                value: self.offset_clamp,
                reason: "must be in (0, 1]",
            });
        }
        for (name, rounds) in [
            ("smoothing_iterations", self.smoothing_iterations),
            ("repair_rounds", self.repair_rounds),
            ("front_repair_rounds", self.front_repair_rounds),
        ] {
            if !Self::ROUNDS_RANGE.contains(&rounds) {
                return Err(PrepError::InvalidParam {
                    name,
                    value: rounds as f64,
                    reason: "must be in [0, 1000]",
                });
            }
        }
        within(
            "anatomical.strength",
            self.anatomical.strength,
            0.0..=10.0,
            "must be in [0, 10]",
        )?;
        within(
            "anatomical.core_fraction",
            self.anatomical.core_fraction,
            0.0..=1.0,
            "must be in [0, 1]",
        )
    }
}

/// Refuses a surface on which one triangle crosses more than
/// [`crate::shell::MAX_REPAIRABLE_CROSSINGS`] others ([`PrepError::ScrambledSurface`]): its
/// positions are out of order (a `v` line moved or swapped), not folded. [`FaceRig::build`]
/// checks its front with it, and a pipeline checks the input with it before making a copy (a
/// remeshed copy of a scrambled face took 50 s before the rig refused it; issue 36).
///
/// ```
/// let face = face_prep::load_face(std::path::Path::new(concat!(
///     env!("CARGO_MANIFEST_DIR"), "/../../assets/mediapipe_canonical_4loop.obj"))).unwrap();
/// assert!(face_prep::check_not_scrambled(&face.vertices, &face.triangles).is_ok());
/// ```
pub fn check_not_scrambled(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Result<(), PrepError> {
    let pairs = crate::shell::intersecting_pairs(vertices, triangles);
    match crate::shell::most_crossed(&pairs, triangles.len()) {
        Some((triangle, crossings)) if crossings > crate::shell::MAX_REPAIRABLE_CROSSINGS => {
            Err(PrepError::ScrambledSurface {
                triangle,
                crossings,
            })
        }
        _ => Ok(()),
    }
}

/// Everything the BEM needs, in the CANONICAL frame (face in x-y, looking toward +z, eyes above
/// the mouth, the face's left eye at +x).
///
/// ```
/// use face_prep::{FaceRig, RigParams, load_face};
/// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
///     .join("../../assets/mediapipe_canonical_4loop.obj");
/// let face = load_face(&path).unwrap();
/// let rig = FaceRig::build(&face, &RigParams::default()).unwrap();
/// assert_eq!(rig.shell.euler_characteristic(), -4);
/// assert_eq!(rig.muscles.len(), face_prep::MuscleKind::ALL.len());
/// let pattern = rig.muscle_pattern(0); // frontalis L at slider = +1
/// assert_eq!(pattern.len(), rig.muscles[0].front_chain.len());
/// ```
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FaceRig {
    /// Rigid transform from the user's input frame to the canonical frame.
    pub canonical_from_input: DAffine3,
    /// Parameters the rig was built with.
    pub params: RigParams,
    /// Face size (larger side of FBFace), the unit of the relative parameters.
    pub face_size: f64,
    /// Length unit of the mesh coordinates (given, or detected: [`FaceRig::unit_detected`]).
    pub unit: LengthUnit,
    /// Whether [`FaceRig::unit`] was estimated from the face ([`Units::Auto`]).
    pub unit_detected: bool,
    /// Number of face vertices (= first shell vertices).
    pub face_vertex_count: usize,
    /// Number of face triangles (= front elements, the first shell elements).
    pub face_triangle_count: usize,
    /// The four classified boundary loops (face vertex indices).
    pub loops: FaceLoops,
    /// Feature boxes (possibly user-adjusted).
    pub boxes: FeatureBoxes,
    /// The closed shell. Its first `face_vertex_count` vertices are the face's, in order; the
    /// front repair may have moved a few of them slightly ([`Shell::front_repair`] says how
    /// many and how far, e.g. for a report).
    pub shell: Shell,
    /// The muscles (controls): the thesis model places [`MuscleKind::THESIS`], the
    /// anatomical model every control of [`MuscleKind::ALL`], in that order.
    pub muscles: Vec<Muscle>,
    /// Fixed skull elements, sorted, disjoint from every muscle chain.
    pub skull: Vec<u32>,
}

impl FaceRig {
    /// Builds the rig with automatically derived feature boxes; [`FaceRig::with_boxes`] then
    /// places the controls from user-adjusted ones.
    pub fn build(face: &FaceMesh, params: &RigParams) -> Result<FaceRig, PrepError> {
        params.validate()?;
        let loops = topology::validate(&face.vertices, &face.triangles)?;
        topology::check_four_loops(&face.vertices, &loops)?;
        let (canonical_from_input, loops) =
            canonical_frame(&face.vertices, &face.triangles, &loops)?;
        let verts: Vec<DVec3> = face
            .vertices
            .iter()
            .map(|&p| canonical_from_input.transform_point3(p))
            .collect();
        let boxes = FeatureBoxes::from_loops(&verts, &loops)?;
        let face_size = boxes.face.width().max(boxes.face.height());
        let units = UnitChoice::decide(params.units, interocular_distance(&verts, &loops));
        // Scrambled geometry (a `v` line swapped) is refused before the shell repair, which
        // cannot open it and would spend O(triangles²) per round trying.
        check_not_scrambled(&verts, &face.triangles)?;
        let shell = Shell::build(
            &verts,
            &face.triangles,
            &loops,
            ShellDims {
                offset: params.offset * face_size,
                thickness: params.thickness * face_size,
                clamp_fraction: params.offset_clamp,
                taper: params.taper * face_size,
                smoothing_iterations: params.smoothing_iterations,
                repair_rounds: params.repair_rounds,
                front_repair_rounds: params.front_repair_rounds,
            },
        );
        let mut rig = FaceRig {
            canonical_from_input,
            params: *params,
            face_size,
            unit: units.unit,
            unit_detected: units.detected,
            face_vertex_count: face.vertices.len(),
            face_triangle_count: face.triangles.len(),
            loops,
            boxes,
            shell,
            muscles: Vec::new(),
            skull: Vec::new(),
        };
        rig.place_muscles();
        Ok(rig)
    }

    fn median_front_edge(&self) -> f64 {
        let mut lengths: Vec<f64> = self.shell.triangles[..self.face_triangle_count]
            .iter()
            .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
            .map(|(a, b)| self.shell.vertices[a as usize].distance(self.shell.vertices[b as usize]))
            .collect();
        lengths.sort_by(f64::total_cmp);
        lengths
            .get(lengths.len() / 2)
            .copied()
            .unwrap_or(self.face_size * 0.01)
    }

    fn place_muscles(&mut self) {
        self.skull = skull_elements(&self.shell, &self.boxes);
        self.muscles = match self.params.muscle_model {
            MuscleModel::Thesis => {
                let spacing = self.params.ray_spacing * self.median_front_edge();
                place_standard_muscles(&self.shell, &self.boxes, &self.skull, spacing)
            }
            MuscleModel::Anatomical => {
                let lid_back = lid_back_elements(&self.shell, &self.loops, self.mm_per_unit());
                self.skull.retain(|e| !lid_back.contains(e));
                let skull: HashSet<u32> = self.skull.iter().copied().collect();
                let mut controls: Vec<Muscle> = MuscleKind::ALL
                    .iter()
                    .map(|&kind| {
                        place_control(
                            &self.shell,
                            &self.loops,
                            &self.boxes,
                            self.mm_per_unit(),
                            &self.params.anatomical,
                            kind,
                            &skull,
                        )
                    })
                    .collect();
                // A force-driven control loads traction-type elements only: the elements of
                // displacement-driven controls are prescribed in every response.
                let prescribed: HashSet<u32> = controls
                    .iter()
                    .filter(|m| !m.kind.is_some_and(MuscleKind::is_force))
                    .flat_map(|m| m.elements())
                    .collect();
                for m in &mut controls {
                    if m.kind.is_some_and(MuscleKind::is_force) {
                        m.front_chain.retain(|e| !prescribed.contains(e));
                        m.back_chain.retain(|e| !prescribed.contains(e));
                    }
                }
                controls
            }
        };
    }

    /// The rig with new (user-adjusted) feature boxes, canonical frame: the shell is kept; the
    /// skull and the standard controls are placed again from the boxes (custom muscles are
    /// dropped), exactly as a rig built with those boxes from the start.
    ///
    /// ```
    /// use face_prep::{FaceRig, RigParams, load_face};
    /// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
    ///     .join("../../assets/mediapipe_canonical_4loop.obj");
    /// let rig = FaceRig::build(&load_face(&path).unwrap(), &RigParams::default()).unwrap();
    /// let mut boxes = rig.boxes;
    /// boxes.skull.min.y = boxes.nose.center().y; // the forehead box down to the nose
    /// let moved = rig.clone().with_boxes(boxes).unwrap();
    /// assert!(moved.skull.len() > rig.skull.len());
    /// ```
    pub fn with_boxes(mut self, boxes: FeatureBoxes) -> Result<FaceRig, PrepError> {
        boxes.check()?;
        self.boxes = boxes;
        self.place_muscles();
        Ok(self)
    }

    /// Replaces the muscles (e.g. from an edited muscle file). Every element must exist, chains
    /// must not repeat an element, front chains must hold Front elements, back chains Back
    /// elements, no muscle may use a skull element, and no two muscles may have the same id
    /// ([`Muscle::id`]).
    pub fn with_muscles(mut self, muscles: Vec<Muscle>) -> Result<FaceRig, PrepError> {
        let skull: HashSet<u32> = self.skull.iter().copied().collect();
        let mut ids = HashSet::new();
        for m in &muscles {
            if !ids.insert(m.id()) {
                return Err(PrepError::DuplicateMuscle(m.id().to_owned()));
            }
            for (chain, want) in [
                (&m.front_chain, ElementTag::Front),
                (&m.back_chain, ElementTag::Back),
            ] {
                let mut seen = HashSet::new();
                for &e in chain {
                    let bad = |reason| PrepError::InvalidMuscle {
                        muscle: m.name.clone(),
                        element: e,
                        reason,
                    };
                    match self.shell.tags.get(e as usize) {
                        None => return Err(bad("does not exist")),
                        Some(t) if *t != want => {
                            return Err(bad(if want == ElementTag::Front {
                                "is not a front element but is in the front chain"
                            } else {
                                "is not a back element but is in the back chain"
                            }));
                        }
                        _ => {}
                    }
                    if skull.contains(&e) {
                        return Err(bad("is a skull element"));
                    }
                    if !seen.insert(e) {
                        return Err(bad("appears twice in one chain"));
                    }
                }
            }
        }
        self.muscles = muscles;
        Ok(self)
    }

    /// The rig's length unit with how it was chosen and the distance between the eyes in mm.
    ///
    /// ```
    /// use face_prep::{FaceRig, RigParams, load_face, units::LengthUnit};
    /// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
    ///     .join("../../assets/mediapipe_canonical_4loop.obj");
    /// let rig = FaceRig::build(&load_face(&path).unwrap(), &RigParams::default()).unwrap();
    /// let units = rig.unit_choice();
    /// assert_eq!(units.unit, LengthUnit::Centimetre);
    /// assert!(units.detected && units.plausible());
    /// ```
    pub fn unit_choice(&self) -> UnitChoice {
        let interocular = interocular_distance(&self.shell.vertices, &self.loops);
        UnitChoice {
            unit: self.unit,
            detected: self.unit_detected,
            interocular_mm: interocular * self.unit.mm(),
        }
    }

    /// Millimetres per unit of the mesh coordinates.
    pub fn mm_per_unit(&self) -> f64 {
        self.unit.mm()
    }

    /// Inverse of [`FaceRig::canonical_from_input`]: canonical frame → user's input frame.
    pub fn input_from_canonical(&self) -> DAffine3 {
        self.canonical_from_input.inverse()
    }

    /// Index of a standard muscle in [`FaceRig::muscles`], if present.
    pub fn muscle_index(&self, kind: MuscleKind) -> Option<usize> {
        self.muscles.iter().position(|m| m.kind == Some(kind))
    }

    /// Prescribed per-element displacement of muscle `muscle_index` at slider = +1 (canonical
    /// frame; see [`crate::controls::muscles::muscle_pattern`]). Empty if the index is out of range.
    pub fn muscle_pattern(&self, muscle_index: usize) -> Vec<(u32, DVec3)> {
        match self.muscles.get(muscle_index) {
            Some(m) => control_pattern(self.parts(), m),
            None => Vec::new(),
        }
    }

    /// The indices of the lip seal and of `jaw_open` among [`FaceRig::muscles`], when the rig
    /// has both (the anatomical model; [`crate::controls::lip_seal`]).
    ///
    /// ```
    /// use face_prep::{FaceRig, MuscleKind, RigParams, load_face};
    /// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
    ///     .join("../../assets/mediapipe_canonical_4loop.obj");
    /// let rig = FaceRig::build(&load_face(&path).unwrap(), &RigParams::default()).unwrap();
    /// let (seal, jaw) = rig.lip_seal_controls().unwrap();
    /// assert_eq!(rig.muscles[seal].kind, Some(MuscleKind::LipSeal));
    /// assert_eq!(rig.muscles[jaw].kind, Some(MuscleKind::JawOpen));
    /// ```
    pub fn lip_seal_controls(&self) -> Option<(usize, usize)> {
        Some((
            self.muscle_index(MuscleKind::LipSeal)?,
            self.muscle_index(MuscleKind::JawOpen)?,
        ))
    }

    /// The share of `jaw_open`'s response the lip seal takes back at each of `points`
    /// (canonical frame; [`crate::controls::lip_seal`]), in their order.
    ///
    /// ```
    /// use face_prep::{FaceRig, RigParams, load_face};
    /// let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
    ///     .join("../../assets/mediapipe_canonical_4loop.obj");
    /// let rig = FaceRig::build(&load_face(&path).unwrap(), &RigParams::default()).unwrap();
    /// let shares = rig.lip_seal_shares(&rig.shell.vertices);
    /// assert!(shares.iter().all(|&w| (0.0..=1.0).contains(&w)));
    /// // The forehead keeps the jaw's (small) motion.
    /// let top = rig.shell.vertices.iter().map(|p| p.y).fold(f64::MIN, f64::max);
    /// assert!(rig.shell.vertices.iter().zip(&shares).all(|(p, &w)| p.y < top - 1.0 || w == 0.0));
    /// ```
    pub fn lip_seal_shares(&self, points: &[DVec3]) -> Vec<f64> {
        crate::controls::lip_seal::seal_shares(self.parts(), points)
    }

    /// Every muscle's prescribed pattern at slider = +1 ([`FaceRig::muscle_pattern`]).
    pub fn muscle_patterns(&self) -> Vec<Vec<(u32, DVec3)>> {
        (0..self.muscles.len())
            .map(|k| self.muscle_pattern(k))
            .collect()
    }

    /// The outer contour in the front plane (canonical x-y), in loop order.
    pub fn contour_xy(&self) -> Vec<glam::DVec2> {
        loop_xy(&self.shell.vertices, &self.loops.face)
    }

    /// Bounding-volume hierarchy of the shell's elements (for ray casts).
    pub fn shell_bvh(&self) -> TriangleBvh {
        shell_bvh(&self.shell)
    }

    /// The parts of the rig that the controls' rig-wide functions read.
    pub(crate) fn parts(&self) -> RigParts<'_> {
        RigParts {
            shell: &self.shell,
            loops: &self.loops,
            boxes: &self.boxes,
            muscles: &self.muscles,
            skull: &self.skull,
            model: self.params.muscle_model,
            anatomical: &self.params.anatomical,
            mm_per_unit: self.mm_per_unit(),
        }
    }

    /// The rig's jaw ([`crate::controls::jaw`]): TMJ axis and jaw segment of the rim
    /// ([`Jaw::of`]).
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

    /// Vertices whose displacement in response `muscle_index` is known exactly rather than
    /// averaged from their elements, with that displacement at slider = +1 (canonical frame):
    /// for a jaw mode, every vertex of the jaw segment moves as the mandible carries it (so the
    /// jaw's part of the outer contour moves with the jaw, and the neck's stays); empty for
    /// every other control.
    pub fn prescribed_vertex_motion(&self, muscle_index: usize) -> Vec<(u32, DVec3)> {
        dispatch::prescribed_vertex_motion(self.parts(), muscle_index)
    }

    /// Whether control `k` of [`FaceRig::muscles`] is force-driven (a standard force control in
    /// the anatomical model; see [`crate::controls::force_controls`]).
    pub fn is_force_control(&self, k: usize) -> bool {
        force_controls::is_force_control(self.params.muscle_model, &self.muscles, k)
    }

    /// Largest displacement on the front surface, in the rig's units, that force-driven control
    /// `k` reaches at full value (its response is scaled to it); `None` for other controls.
    pub fn force_target(&self, k: usize) -> Option<f64> {
        force_controls::force_target(self.parts(), k)
    }

    /// The front elements (not skull) whose centroid lies within
    /// [`crate::controls::modiolus::MODIOLUS_RADIUS_MM`] of the modiolus centre on `side`, in
    /// element order; empty for [`Side::Center`].
    pub fn modiolus_elements(&self, side: Side) -> Vec<u32> {
        modiolus::modiolus_elements(
            &self.shell,
            &self.boxes,
            &self.skull,
            self.mm_per_unit(),
            side,
        )
    }

    /// How control `k` moves the modiolus ([`crate::controls::modiolus`]): for a force-driven
    /// band muscle of the anatomical model whose insertion lies within
    /// [`crate::controls::modiolus::MODIOLUS_RADIUS_MM`] of a modiolus centre, the modiolus's
    /// translation at slider = +1 (its shortening, `max_strain × strength × length`, away from
    /// the origin along the skin); `None` for every other control.
    pub fn modiolus_pin(&self, k: usize) -> Option<ModiolusPin> {
        modiolus::modiolus_pin(self.parts(), k)
    }

    /// Back elements sliding on the teeth (anatomical model; empty in the thesis model): over
    /// the dental arch ([`crate::controls::teeth::over_dental_arch`]), neither skull nor an
    /// element of a displacement-driven control. Sorted.
    pub fn sliding_elements(&self) -> Vec<u32> {
        teeth::sliding_elements(self.parts())
    }
}

/// Distance between the centres of the two eye loops (length-weighted loop centroids), in mesh
/// units. `vertices` may be the face's or the shell's (the first shell vertices are the face's).
fn interocular_distance(vertices: &[DVec3], loops: &FaceLoops) -> f64 {
    loop_centroid(vertices, &loops.eye_l).distance(loop_centroid(vertices, &loops.eye_r))
}
