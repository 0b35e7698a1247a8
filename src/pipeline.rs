//! The pipeline: face mesh → rig (face-prep) → BEM response per muscle (bem-core) → per-vertex
//! muscle basis in the user's frame and vertex order.

use std::time::Instant;

use face_prep::{FaceLoops, FaceMesh, FaceRig, RigParams};
use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

use crate::control::{Control, Stage};
use crate::large_face::{LargeFaceParams, Simplified, Transfer};
use crate::{MuscleBasis, PoseError};

/// Everything that determines a [`FaceModel`] besides the mesh. Part of the cache key.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PipelineParams {
    /// Rig building: shell offset and thickness, feature boxes, muscle placement.
    pub rig: RigParams,
    /// Poisson ratio ν of the face tissue (nearly incompressible: 0.45 by default). Only ν
    /// matters: with every boundary displacement- or zero-traction-prescribed, displacements
    /// do not depend on the shear modulus.
    pub poisson: f64,
    /// Simulate without the eyelids and lips that roll in behind the eye and mouth contours
    /// ([`crate::rolled_in`]); their vertices follow the nearest simulated point. Default true.
    pub peel_rolled_in: bool,
    /// Simplification of faces too large for a dense solve.
    pub large_face: LargeFaceParams,
    /// Quadrature of the BEM's off-diagonal blocks (adaptive subdivision of near pairs).
    pub quadrature: bem_core::QuadratureParams,
    /// Muscles to use instead of the automatically placed ones (e.g. read from an edited
    /// muscle file; their element indices refer to the shell [`prep_rig`] builds).
    pub muscles: Option<Vec<face_prep::Muscle>>,
    /// Feature boxes to use instead of the automatic ones (canonical frame, see
    /// [`face_prep::FeatureBoxes`]): muscles and skull are placed from them. With `muscles`
    /// set too, the boxes decide the skull and `muscles` the muscles.
    pub boxes: Option<face_prep::FeatureBoxes>,
}

impl Default for PipelineParams {
    fn default() -> Self {
        PipelineParams {
            rig: RigParams::default(),
            poisson: 0.45,
            peel_rolled_in: true,
            large_face: LargeFaceParams::default(),
            quadrature: bem_core::QuadratureParams::default(),
            muscles: None,
            boxes: None,
        }
    }
}

/// Sizes and timings of one precompute.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PrecomputeReport {
    /// Front triangles of the input face.
    pub input_triangles: usize,
    /// Front triangles simulated (fewer than the input for a simplified large face).
    pub simulated_triangles: usize,
    /// How a large face was simplified ([`crate::face_simplify`]); `None` when it was not.
    pub simplify_path: Option<crate::face_simplify::SimplifyPath>,
    /// Boundary elements of the closed shell.
    pub shell_elements: usize,
    /// Unknowns of the dense system (3 per element).
    pub dofs: usize,
    /// Pairs of shell elements that intersect each other. Non-zero means the elastic body is
    /// not a valid solid there (e.g. an input whose lips interpenetrate): the BEM is ill-posed
    /// and responses near those elements are unreliable.
    pub shell_self_intersections: usize,
    /// Largest ratio, over the muscles, of the largest element displacement of a muscle's
    /// response to the largest displacement its pattern prescribes. A linear elastic body held
    /// by its skull stays near 1 (1.00 on MediaPipe, Lee Perry-Smith and the simplified
    /// 2500-triangle ICT face, 1.05 on the simplified 13k ICT face, at default settings); far
    /// above [`SUSPICIOUS_AMPLIFICATION`] the system is near-singular and the responses are not
    /// physical (e.g. front and back surfaces nearly coincident: MediaPipe with offset 0.0005
    /// reaches 60; the ICT faces simulated with their rolled-in eyelids and lips, 3 to 1751).
    pub response_amplification: f64,
    /// bem-core's estimate of the condition number of the BEM system (columns scaled to unit
    /// 1-norm, [`bem_core::DenseLu::condition_estimate`]); solves above
    /// [`bem_core::DEFAULT_MAX_CONDITION`] are refused.
    pub condition_estimate: f64,
    /// Off-diagonal BEM blocks whose quadrature could not reach the requested accuracy
    /// ([`bem_core::AssemblyReport`]): a collocation point closer to another element than
    /// 1e-4 of its size, i.e. the shell nearly touches or crosses itself there. 0 on the bundled
    /// faces at default settings.
    pub quadrature_unconverged: usize,
    /// Largest estimated relative error among those blocks (0 when there is none).
    pub quadrature_worst_error: f64,
    /// Seconds spent in prep (simplification, rig).
    pub prep_seconds: f64,
    /// Seconds spent in the BEM solve (assembly, factorisation, solves).
    pub solve_seconds: f64,
    /// Seconds spent mapping element results to the user's vertices.
    pub transfer_seconds: f64,
}

/// [`PrecomputeReport::response_amplification`] above this flags a near-singular, unphysical
/// solve (healthy rigs measured 1 to 3.2; broken ones 8 to 5000).
pub const SUSPICIOUS_AMPLIFICATION: f64 = 5.0;

impl PrecomputeReport {
    /// Human-readable warnings about the computed rig (empty when nothing is suspicious): shell
    /// self-intersections, near-singular responses and unconverged BEM quadrature. The CLI, the
    /// viewer and [`crate::describe`] show them.
    ///
    /// ```
    /// let mut report = facebem::PrecomputeReport::default();
    /// assert!(report.warnings().is_empty());
    /// report.shell_self_intersections = 3;
    /// report.response_amplification = 40.0;
    /// let w = report.warnings();
    /// assert!(w[0].contains("3 pairs of shell elements intersect"));
    /// assert!(w[1].contains("40 times"));
    /// report.quadrature_unconverged = 12;
    /// report.quadrature_worst_error = 0.03;
    /// assert!(report.warnings()[2].contains("12 BEM element pairs"));
    /// ```
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.shell_self_intersections > 0 {
            out.push(format!(
                "{} pairs of shell elements intersect (does the face cross itself, e.g. at the \
                 lips?); responses near them are unreliable",
                self.shell_self_intersections
            ));
        }
        if self.response_amplification > SUSPICIOUS_AMPLIFICATION {
            out.push(format!(
                "a muscle response moves the face {:.0} times more than the muscle itself \
                 (healthy rigs: below {SUSPICIOUS_AMPLIFICATION:.0}); the BEM system is \
                 near-singular, e.g. front and back of the shell nearly touch (check the \
                 shell offset)",
                self.response_amplification
            ));
        }
        if self.quadrature_unconverged > 0 {
            out.push(format!(
                "{} BEM element pairs are closer than the quadrature resolves (estimated block \
                 error up to {:.1e}): the shell nearly touches itself there (check the shell \
                 offset); responses near them are less accurate",
                self.quadrature_unconverged, self.quadrature_worst_error
            ));
        }
        out
    }
}

/// The reduced copy of a face that was simulated (simplified, or with rolled-in parts
/// peeled off, or both) and the map that carries its fields to the full mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SimplifiedFace {
    /// The simulated front mesh (its vertices are a subset of the full mesh's).
    pub mesh: Simplified,
    /// Closest-point barycentric transfer to every full-mesh vertex.
    pub transfer: Transfer,
}

/// A computed face: input mesh, rig, muscle basis and the parameters it was computed with.
///
/// ```no_run
/// use facebem::{build_face_model, Control, PipelineParams};
/// let mesh = face_prep::load_face("assets/mediapipe_canonical_4loop.obj".as_ref()).unwrap();
/// let model = build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap();
/// let happy = facebem::presets::find("happy").unwrap();
/// let posed = model.pose(&happy.sliders_for(&model.basis.muscle_ids)).unwrap();
/// assert_eq!(posed.len(), mesh.vertices.len());
/// ```
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct FaceModel {
    /// The user's face mesh (input frame, welded).
    pub mesh: FaceMesh,
    /// The original OBJ text when the face came from an OBJ file (for a glTF file, an
    /// equivalent OBJ in its vertex order, [`crate::export::layout::obj_text_of_gltf`]): poses
    /// are written by replacing only its `v` lines, keeping the user's vertex order, UVs and
    /// normals, and glTF exports use its layout.
    pub obj_source: Option<String>,
    /// The rig (canonical frame) the BEM was solved on: of the simplified mesh for a large face.
    pub rig: FaceRig,
    /// The reduced copy that was simulated (rolled-in parts peeled off and/or simplified), if
    /// it is not the whole input.
    pub simplified: Option<SimplifiedFace>,
    /// Per-muscle displacement of every vertex of [`FaceModel::mesh`] at slider = 1, user frame.
    pub basis: MuscleBasis,
    /// `shell_element_response[k][e]`: displacement of shell element `e` of [`FaceModel::rig`]
    /// (at its centroid, canonical frame) for muscle `k` at slider = 1. Skull elements are 0.
    pub shell_element_response: Vec<Vec<DVec3>>,
    /// `shell_vertex_response[k][v]`: the same per shell vertex (area-weighted average of the
    /// adjacent elements), canonical frame; for drawing the whole deformed shell.
    pub shell_vertex_response: Vec<Vec<DVec3>>,
    /// Parameters the model was computed with.
    pub params: PipelineParams,
    /// Sizes and timings.
    pub report: PrecomputeReport,
}

/// Errors of the pipeline.
#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    /// Rig building failed (invalid face, features not found, ...).
    #[error("rig: {0}")]
    Prep(#[from] face_prep::PrepError),
    /// The BEM solve failed.
    #[error("BEM solve: {0}")]
    Bem(#[from] bem_core::BemError),
    /// The shell is not a valid closed surface for the BEM.
    #[error("shell: {0}")]
    Shell(#[from] bem_core::MeshError),
    /// Simplifying the large face failed.
    #[error("simplifying the large face: {0}")]
    Simplify(#[from] crate::large_face::SimplifyError),
    /// The Poisson ratio is not in [0, 0.5).
    #[error("Poisson ratio {0} is outside [0, 0.5)")]
    Poisson(f64),
    /// The rig has no muscles.
    #[error("the rig has no muscles")]
    NoMuscles,
    /// The caller cancelled the computation.
    #[error("cancelled")]
    Cancelled,
}

impl FaceModel {
    /// Posed vertex positions (user frame, user vertex order) for one slider per muscle.
    pub fn pose(&self, sliders: &[f64]) -> Result<Vec<DVec3>, PoseError> {
        self.basis.pose(sliders)
    }

    /// Identifiers of the muscles, in slider order.
    pub fn muscle_ids(&self) -> &[String] {
        &self.basis.muscle_ids
    }
}

/// The rig of a face as the pipeline simulates it, with the reduced copy when it is not the
/// whole input.
#[derive(Clone, Debug)]
pub struct PreparedRig {
    /// The front mesh that is simulated (the input mesh, or its reduced copy).
    pub simulated: FaceMesh,
    /// The reduced copy (rolled-in parts peeled off, and/or simplified for a large face), its
    /// vertices a subset of the input's; `None` when the whole input is simulated.
    pub simplified: Option<Simplified>,
    /// The rig of [`PreparedRig::simulated`] (with `params.muscles` if given).
    pub rig: FaceRig,
    /// Input vertices peeled off with the rolled-in eyelids and lips (they follow the margin
    /// they hang from, [`Transfer::snap_to_margins`]).
    pub peeled_vertices: Vec<u32>,
    /// How a large face was simplified; `None` when it was not.
    pub simplify_path: Option<crate::face_simplify::SimplifyPath>,
}

/// The prep step alone (fast, no BEM): rolled-in parts peeled off, simplification of a large
/// face, rig, muscle override.
pub fn prepare(mesh: &FaceMesh, params: &PipelineParams) -> Result<PreparedRig, PipelineError> {
    let whole = Simplified::whole(&mesh.vertices, &mesh.triangles);
    let peeled = if params.peel_rolled_in {
        crate::rolled_in::peel_rolled_in(&whole)
    } else {
        None
    };
    let peeled_vertices: Vec<u32> = match &peeled {
        Some(p) => {
            let mut kept = vec![false; whole.vertices.len()];
            for &v in &p.original_vertex {
                kept[v as usize] = true;
            }
            (0..kept.len() as u32)
                .filter(|&v| !kept[v as usize])
                .collect()
        }
        None => Vec::new(),
    };
    let base = peeled.as_ref().unwrap_or(&whole);
    let mut simplify_path = None;
    let reduced = if base.triangles.len() > params.large_face.max_triangles {
        let keep = kept_mouth_corners(mesh, base);
        let (s, path) = crate::face_simplify::simplify_face_keeping(
            &base.vertices,
            &base.triangles,
            &params.large_face,
            &keep,
        )?;
        simplify_path = Some(path);
        Some(Simplified {
            original_vertex: s
                .original_vertex
                .iter()
                .map(|&v| base.original_vertex[v as usize])
                .collect(),
            ..s
        })
    } else {
        peeled
    };
    let (simulated, simplified) = match reduced {
        Some(s) => (
            FaceMesh::from_triangles(&s.vertices, &s.triangles)?,
            Some(s),
        ),
        None => (mesh.clone(), None),
    };
    let mut rig = match params.boxes {
        Some(boxes) => FaceRig::build_with_boxes(&simulated, &params.rig, boxes)?,
        None => FaceRig::build(&simulated, &params.rig)?,
    };
    if let Some(muscles) = &params.muscles {
        rig = rig.with_muscles(muscles.clone())?;
    }
    Ok(PreparedRig {
        simulated,
        simplified,
        rig,
        peeled_vertices,
        simplify_path,
    })
}

/// The rig of `mesh` as [`build_face_model`] would simulate it (for `info`, muscle files,
/// editing). No BEM solve.
pub fn prep_rig(mesh: &FaceMesh, params: &PipelineParams) -> Result<FaceRig, PipelineError> {
    Ok(prepare(mesh, params)?.rig)
}

/// Builds the rig and the muscle basis of `mesh`.
///
/// Eyelids and lips rolled in behind their contours are peeled off the simulated surface
/// (`params.peel_rolled_in`), and large faces (more than `params.large_face.max_triangles`
/// front triangles) are simulated on a simplified copy; the displacements of such a reduced
/// copy are then carried to every vertex.
/// Progress of every stage goes to `control`; cancelling it stops the work at the next check
/// (the LU factorisation itself runs to completion once started).
pub fn build_face_model(
    mesh: &FaceMesh,
    params: &PipelineParams,
    control: &Control,
) -> Result<FaceModel, PipelineError> {
    if !(0.0..0.5).contains(&params.poisson) {
        return Err(PipelineError::Poisson(params.poisson));
    }
    let t0 = Instant::now();
    control.report(Stage::Prep, 0, 1);
    let PreparedRig {
        simulated,
        simplified,
        rig,
        peeled_vertices,
        simplify_path,
    } = prepare(mesh, params)?;
    if rig.muscles.is_empty() {
        return Err(PipelineError::NoMuscles);
    }
    let shell_self_intersections = rig.shell.self_intersections().len();
    control.report(Stage::Prep, 1, 1);
    check_cancel(control)?;
    let prep_seconds = t0.elapsed().as_secs_f64();

    let t1 = Instant::now();
    let solved = crate::solve::solve_rig(&rig, params.poisson, params.quadrature, control)?;
    let solve_seconds = t1.elapsed().as_secs_f64();
    check_cancel(control)?;

    let t2 = Instant::now();
    control.report(Stage::Transfer, 0, 1);
    // Canonical → input: displacements are vectors, so only the linear part applies.
    let linear: DMat3 = rig.input_from_canonical().matrix3;
    // Shell vertices 0..n are the simulated face's vertices, in order.
    let n_front = simulated.vertices.len();
    let sim_fields: Vec<Vec<DVec3>> = solved
        .vertex
        .iter()
        .map(|field| field[..n_front].iter().map(|d| linear * *d).collect())
        .collect();
    let (mut displacements, simplified) = match simplified {
        None => (sim_fields, None),
        Some(s) => {
            // Fields on the reduced copy's vertices (through its own welding map).
            let on_copy: Vec<Vec<DVec3>> = sim_fields
                .iter()
                .map(|f| {
                    simulated
                        .input_to_vertex
                        .iter()
                        .map(|v| v.map_or(DVec3::ZERO, |v| f[v as usize]))
                        .collect()
                })
                .collect();
            let mut transfer =
                Transfer::build(&mesh.vertices, &s).ok_or(PipelineError::NoMuscles)?;
            let anatomical =
                rig.params.muscle_model == face_prep::muscle_model::MuscleModel::Anatomical;
            // The mouth loop's corners that the copy does not hold (a rolled-in lip's inner
            // corner, or one the simplification dropped) follow the copy's margin at their
            // closest point, the commissure, instead of hanging between the two lips.
            let corners = if anatomical {
                missing_mouth_corners(mesh, &rig, &s)
            } else {
                Vec::new()
            };
            let hanging: Vec<u32> = peeled_vertices
                .iter()
                .copied()
                .filter(|v| !corners.contains(v))
                .collect();
            if anatomical {
                // Peeled vertices and dropped corners alike start from the closest margin point.
                let snapped: Vec<u32> = hanging.iter().chain(&corners).copied().collect();
                transfer.snap_to_margins(&mesh.vertices, &s, &snapped);
            }
            let mut fields: Vec<Vec<DVec3>> =
                on_copy.iter().map(|f| transfer.apply(&s, f)).collect();
            if anatomical {
                for f in &mut fields {
                    crate::rolled_in::hang_from_margins(f, &mesh.triangles, &hanging);
                }
            }
            (fields, Some(SimplifiedFace { mesh: s, transfer }))
        }
    };
    let muscle_ids: Vec<String> = rig.muscles.iter().map(muscle_id).collect();
    if rig.params.muscle_model == face_prep::muscle_model::MuscleModel::Anatomical {
        relax_each(mesh, &rig, &untangle_fixed(mesh, &rig), &mut displacements);
    }
    crate::lid_closure::keep_squints_open(&rig, mesh, &muscle_ids, &mut displacements);
    crate::lid_closure::close_blinks(
        &rig,
        mesh,
        simplified.as_ref().map(|s| (&s.mesh, &simulated)),
        &muscle_ids,
        &mut displacements,
    );
    if rig.params.muscle_model == face_prep::muscle_model::MuscleModel::Anatomical {
        let fixed = closed_lids_fixed(mesh, &rig, simplified.as_ref().map(|s| &s.mesh));
        relax_each(mesh, &rig, &fixed, &mut displacements);
    }
    if rig.params.muscle_model == face_prep::muscle_model::MuscleModel::Anatomical {
        relax_sphincter_sum(
            mesh,
            &rig,
            &muscle_ids,
            simplified.as_ref(),
            &mut displacements,
        );
    }
    if rig.params.muscle_model == face_prep::muscle_model::MuscleModel::Anatomical {
        let fixed = beyond_lips_and_lids_fixed(mesh, &rig, Forehead::Fixed);
        relax_each(mesh, &rig, &fixed, &mut displacements);
        relax_each_guarded(
            mesh,
            &rig,
            &fixed,
            Direction::Lengthened,
            &mut displacements,
        );
        let forehead_free = beyond_lips_and_lids_fixed(mesh, &rig, Forehead::Free);
        relax_each_guarded(
            mesh,
            &rig,
            &forehead_free,
            Direction::Contraction,
            &mut displacements,
        );
        relax_each_guarded(
            mesh,
            &rig,
            &forehead_free,
            Direction::HalfLengthened,
            &mut displacements,
        );
        relax_each_guarded(
            mesh,
            &rig,
            &above_the_eyes_fixed(mesh, &rig),
            Direction::HalfLengthened,
            &mut displacements,
        );
        relax_brow_lowerers(mesh, &rig, &muscle_ids, &mut displacements);
    }
    control.report(Stage::Transfer, 1, 1);
    let basis = MuscleBasis {
        muscle_ids,
        neutral: mesh.vertices.clone(),
        triangles: mesh.triangles.clone(),
        displacements,
    };
    let response_amplification = (0..rig.muscles.len())
        .map(|k| {
            // A force-driven control's pattern is a traction: its response is compared with
            // the front displacement it was scaled to (a near-singular shell answers with far
            // larger motion inside the shell than on the face).
            let prescribed = rig.force_target(k).unwrap_or_else(|| {
                rig.muscle_pattern(k)
                    .iter()
                    .map(|(_, d)| d.length())
                    .fold(0.0, f64::max)
            });
            let response = solved.element[k]
                .iter()
                .map(|u| u.length())
                .fold(0.0, f64::max);
            if prescribed > 0.0 {
                response / prescribed
            } else {
                0.0
            }
        })
        .fold(0.0, f64::max);
    let report = PrecomputeReport {
        input_triangles: mesh.triangles.len(),
        simulated_triangles: simulated.triangles.len(),
        simplify_path,
        shell_elements: rig.shell.triangles.len(),
        dofs: 3 * rig.shell.triangles.len(),
        shell_self_intersections,
        response_amplification,
        condition_estimate: solved.report.condition_estimate,
        quadrature_unconverged: solved.report.quadrature.unconverged_blocks,
        quadrature_worst_error: solved
            .report
            .quadrature
            .worst
            .map_or(0.0, |w| w.estimated_error),
        prep_seconds,
        solve_seconds,
        transfer_seconds: t2.elapsed().as_secs_f64(),
    };
    Ok(FaceModel {
        mesh: mesh.clone(),
        obj_source: None,
        rig,
        simplified,
        basis,
        shell_element_response: solved.element,
        shell_vertex_response: solved.vertex,
        params: params.clone(),
        report,
    })
}

/// Relaxes every response where it turns triangles over, moving only the vertices not in
/// `fixed` ([`crate::untangle::relax_inversions`], patches of [`crate::untangle::PATCH_MM`]).
fn relax_each(mesh: &FaceMesh, rig: &FaceRig, fixed: &[bool], displacements: &mut [Vec<DVec3>]) {
    use rayon::prelude::*;
    let patch_radius = crate::untangle::PATCH_MM / rig.mm_per_unit();
    // Each response on its own: in parallel, the same result as in sequence.
    displacements.par_iter_mut().for_each(|field| {
        crate::untangle::relax_inversions(
            &mesh.vertices,
            &mesh.triangles,
            field,
            fixed,
            patch_radius,
        );
    });
}

/// Which way a response is relaxed by [`relax_each_guarded`].
#[derive(Clone, Copy, PartialEq, Eq)]
enum Direction {
    /// The field as it is (full contraction).
    Contraction,
    /// The negated field (slider +1, the muscle lengthened past rest, which named expressions
    /// use: `mouthClose` lengthens the levator labii superioris by 0.4).
    Lengthened,
    /// The negated field at half value (`browDownLeft` lengthens the frontalis by 0.5): only
    /// what turns over at that value is relaxed.
    HalfLengthened,
}

/// Relaxes one direction of every response ([`crate::untangle::relax_inversions`] of the field
/// or of its negation, moving only the vertices not in `fixed`), kept only if the other
/// direction then turns no more triangles over: one field serves both slider directions, and
/// smoothing where one turns triangles over can turn the other's over.
///
/// Regressions: ICT 2500's `mouthClose` turned 3 triangles over at the nostrils, 21–22 mm from
/// the lips, every one of them from the lengthened levator labii superioris (the lengthened
/// pass); its `surprised` turned 5 over on the brow line, 13–17 mm above the eye loops, at the
/// frontalis's one-vertex peaks (the contraction pass over the forehead); its `browDownLeft`
/// turned one over 9 mm above the eye loop, from the frontalis lengthened by half (the
/// half-lengthened pass over the forehead; relaxed at full value there instead, MediaPipe's
/// brow raise fell from 10.6 to 7.5 mm). ICT 13k's `disgust` (the frontalis lengthened by 0.3)
/// turned 16 upper-lid triangles over, 6–7 mm above the eye loops (the half-lengthened pass
/// over the lids and forehead; run alone, without the forehead pass before it, it left ICT
/// 2500's `browDownLeft` one turned triangle 12 mm above the eye).
fn relax_each_guarded(
    mesh: &FaceMesh,
    rig: &FaceRig,
    fixed: &[bool],
    direction: Direction,
    displacements: &mut [Vec<DVec3>],
) {
    use rayon::prelude::*;
    let patch_radius = crate::untangle::PATCH_MM / rig.mm_per_unit();
    let (sign, value) = match direction {
        Direction::Contraction => (1.0, 1.0),
        Direction::Lengthened => (-1.0, 1.0),
        Direction::HalfLengthened => (-1.0, 0.5),
    };
    // The other direction at full and at half value (named expressions use both).
    let turned_other = |f: &[DVec3]| -> [usize; 2] {
        [1.0, 0.5].map(|value| {
            let other: Vec<DVec3> = f.iter().map(|u| *u * (-sign * value)).collect();
            crate::untangle::turned_over(&mesh.vertices, &mesh.triangles, &other).len()
        })
    };
    displacements.par_iter_mut().for_each(|field| {
        let mut relaxed: Vec<DVec3> = field.iter().map(|u| *u * (sign * value)).collect();
        let moved = crate::untangle::relax_inversions(
            &mesh.vertices,
            &mesh.triangles,
            &mut relaxed,
            fixed,
            patch_radius,
        );
        if moved == 0 {
            return;
        }
        for u in &mut relaxed {
            *u /= sign * value;
        }
        let (after, before) = (turned_other(&relaxed), turned_other(field));
        if after[0] <= before[0] && after[1] <= before[1] {
            *field = relaxed;
        }
    });
}

/// `mouthPucker` contracts both halves of the mouth's sphincter at once: their sum is relaxed
/// as one field ([`crate::untangle::relax_sum`]), with the lips and lids free as in the second
/// pass (ICT 2500: 17 turned triangles → 11).
fn relax_sphincter_sum(
    mesh: &FaceMesh,
    rig: &FaceRig,
    muscle_ids: &[String],
    simplified: Option<&SimplifiedFace>,
    displacements: &mut [Vec<DVec3>],
) {
    let find = |kind: face_prep::MuscleKind| muscle_ids.iter().position(|id| id == kind.id());
    let (Some(upper), Some(lower)) = (
        find(face_prep::MuscleKind::OrbicularisOrisUpper),
        find(face_prep::MuscleKind::OrbicularisOrisLower),
    ) else {
        return;
    };
    let fixed = closed_lids_fixed(mesh, rig, simplified.map(|s| &s.mesh));
    let patch_radius = crate::untangle::PATCH_MM / rig.mm_per_unit();
    let (first, second) = displacements.split_at_mut(upper.max(lower));
    let (a, b) = (&mut first[upper.min(lower)], &mut second[0]);
    crate::untangle::relax_sum(&mesh.vertices, &mesh.triangles, a, b, &fixed, patch_radius);
}

/// Identifier of a muscle: its standard id when it is one of the ten, else its name.
fn muscle_id(m: &face_prep::Muscle) -> String {
    m.kind
        .map_or_else(|| m.name.clone(), |k| k.id().to_string())
}

fn check_cancel(control: &Control) -> Result<(), PipelineError> {
    if control.is_cancelled() {
        Err(PipelineError::Cancelled)
    } else {
        Ok(())
    }
}

/// Vertices [`crate::untangle::relax_inversions`] leaves as solved: everything farther than
/// [`crate::untangle::LIPS_MM`] from the mouth loop (a turned triangle there is a defect to
/// see, not a lip folding), the outer contour, the eye loops and the mouth corners.
fn untangle_fixed(mesh: &FaceMesh, rig: &FaceRig) -> Vec<bool> {
    let mut fixed = vec![true; mesh.vertices.len()];
    let Some((loops, canonical)) = crate::measure::canonical_loops(rig, mesh) else {
        return fixed;
    };
    let mouth: Vec<glam::DVec2> = loops
        .mouth
        .iter()
        .filter_map(|&v| canonical.get(v as usize).map(|p| p.truncate()))
        .collect();
    let reach = crate::untangle::LIPS_MM / rig.mm_per_unit();
    for (f, p) in fixed.iter_mut().zip(&canonical) {
        *f = face_prep::muscle_model::distance_to_loop(p.truncate(), &mouth) > reach;
    }
    fix_contours_and_corners(&mut fixed, &loops, &canonical);
    fixed
}

/// Flags the outer contour, the eye loops and the mouth corners (`canonical`: the mesh's
/// vertices in the rig's canonical frame) as fixed for the relaxation passes.
fn fix_contours_and_corners(fixed: &mut [bool], loops: &FaceLoops, canonical: &[DVec3]) {
    let corners = crate::measure::mouth_corners(canonical, &loops.mouth)
        .map(|(l, r)| vec![l, r])
        .unwrap_or_default();
    for &v in loops
        .face
        .iter()
        .chain(&loops.eye_l)
        .chain(&loops.eye_r)
        .chain(&corners)
    {
        if let Some(f) = fixed.get_mut(v as usize) {
            *f = true;
        }
    }
}

/// The lowest canonical y of two polylines (the eye loops' lowest point).
fn lowest_y(a: &[glam::DVec2], b: &[glam::DVec2]) -> f64 {
    a.iter().chain(b).map(|p| p.y).fold(f64::INFINITY, f64::min)
}

/// The mouth and eye loops (left, right) as polylines in the canonical front plane.
fn front_loops(
    loops: &FaceLoops,
    canonical: &[DVec3],
) -> (Vec<glam::DVec2>, Vec<glam::DVec2>, Vec<glam::DVec2>) {
    let front = |lp: &[u32]| -> Vec<glam::DVec2> {
        lp.iter()
            .filter_map(|&v| canonical.get(v as usize).map(|p| p.truncate()))
            .collect()
    };
    (
        front(&loops.mouth),
        front(&loops.eye_l),
        front(&loops.eye_r),
    )
}

/// Whether [`beyond_lips_and_lids_fixed`] leaves the upper face (above the eyes' lowest
/// point) as it is.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Forehead {
    /// Relaxed with the mid and lower face.
    Free,
    /// Left as solved.
    Fixed,
}

/// Vertices the last [`crate::untangle::relax_inversions`] passes leave alone. They relax the
/// face beyond the lips and lids, where the lip elevators fold the skin at the nasolabial fold
/// and the nose's wing (Lee Perry-Smith's noseSneer and mouthUpperUp: 6 / 11 and 5 / 7 turned
/// triangles 13–30 mm from the lips, none after) and, with [`Forehead::Free`], where the
/// frontalis's brow raise turns the brow line over (ICT 2500's `surprised`: 5 turned triangles
/// 13–17 mm above the eye loops, none after; its brow points rise 10.0 / 9.2 mm at full
/// frontalis). Fixed: the lips and lids (within [`crate::untangle::LIPS_MM`] of the mouth
/// loop or [`crate::untangle::LIDS_MM`] of an eye loop; the earlier passes relaxed them), the
/// outer contour, the mouth corners and, with [`Forehead::Fixed`], every vertex above
/// `LIDS_MM` below the eye loops' lowest point.
fn beyond_lips_and_lids_fixed(mesh: &FaceMesh, rig: &FaceRig, forehead: Forehead) -> Vec<bool> {
    let mut fixed = vec![true; mesh.vertices.len()];
    let Some((loops, canonical)) = crate::measure::canonical_loops(rig, mesh) else {
        return fixed;
    };
    let (mouth, eye_l, eye_r) = front_loops(&loops, &canonical);
    let lips = crate::untangle::LIPS_MM / rig.mm_per_unit();
    let lids = crate::untangle::LIDS_MM / rig.mm_per_unit();
    let eyes_bottom = lowest_y(&eye_l, &eye_r);
    let distance = face_prep::muscle_model::distance_to_loop;
    for (f, p) in fixed.iter_mut().zip(&canonical) {
        let p = p.truncate();
        *f = (forehead == Forehead::Fixed && p.y > eyes_bottom - lids)
            || distance(p, &mouth) <= lips
            || distance(p, &eye_l).min(distance(p, &eye_r)) <= lids;
    }
    fix_contours_and_corners(&mut fixed, &loops, &canonical);
    fixed
}

/// The ARKit expressions whose brow lowerer [`relax_brow_lowerers`] relaxes in their
/// combination, with the control that takes the change (the expression's corrugator).
const BROW_LOWERING: [(&str, face_prep::MuscleKind); 2] = [
    ("browDownLeft", face_prep::MuscleKind::CorrugatorSuperciliiL),
    (
        "browDownRight",
        face_prep::MuscleKind::CorrugatorSuperciliiR,
    ),
];

/// A last pass over the brow lowerers. The corrugator pulls the skin over the frontal bone,
/// a thin layer on the skull whose motion stays where its traction is: it gathers beside the
/// inner canthus, and `browDownLeft`'s relaxed frontalis pushes the brow down onto it, turning
/// triangles over 12–21 mm from the eye (ICT 13k: 28 turned, 6 of them there; Lee Perry-Smith
/// 10 / 12; MediaPipe 4, the largest motion a 21 mm spike). Each corrugator is relaxed in its
/// `browDown*` combination ([`crate::untangle::relax_in_combination`]; `angry` uses the same
/// ratio of the two), then alone, over the upper face ([`above_the_eyes_fixed`]); the
/// frontalis stays as solved (its brow raise is calibrated).
fn relax_brow_lowerers(
    mesh: &FaceMesh,
    rig: &FaceRig,
    muscle_ids: &[String],
    displacements: &mut [Vec<DVec3>],
) {
    let fixed = above_the_eyes_fixed(mesh, rig);
    let patch_radius = crate::untangle::PATCH_MM / rig.mm_per_unit();
    for (name, carrier) in BROW_LOWERING {
        let Some(k) = muscle_ids.iter().position(|id| id == carrier.id()) else {
            continue;
        };
        let Some(resolved) = crate::expression_sets::find(name).and_then(|e| e.resolve(muscle_ids))
        else {
            continue;
        };
        let s_k = resolved.sliders[k];
        if s_k == 0.0 {
            continue;
        }
        let others: Vec<(usize, f64)> = resolved
            .sliders
            .iter()
            .enumerate()
            .filter(|&(i, &s)| i != k && s != 0.0)
            .map(|(i, &s)| (i, s / s_k))
            .collect();
        let mut field = std::mem::take(&mut displacements[k]);
        let views: Vec<(&[DVec3], f64)> = others
            .iter()
            .map(|&(i, w)| (displacements[i].as_slice(), w))
            .collect();
        crate::untangle::relax_in_combination(
            &mesh.vertices,
            &mesh.triangles,
            &mut field,
            &views,
            &fixed,
            patch_radius,
        );
        crate::untangle::relax_inversions(
            &mesh.vertices,
            &mesh.triangles,
            &mut field,
            &fixed,
            patch_radius,
        );
        displacements[k] = field;
    }
}

/// Vertices [`relax_brow_lowerers`] leaves alone: the mid and lower face (more than
/// [`crate::untangle::LIDS_MM`] below the eye loops' lowest point), the outer contour, the eye
/// loops and the mouth corners.
fn above_the_eyes_fixed(mesh: &FaceMesh, rig: &FaceRig) -> Vec<bool> {
    let Some((loops, canonical)) = crate::measure::canonical_loops(rig, mesh) else {
        return vec![true; mesh.vertices.len()];
    };
    let (_, eye_l, eye_r) = front_loops(&loops, &canonical);
    let lids = crate::untangle::LIDS_MM / rig.mm_per_unit();
    let eyes_bottom = lowest_y(&eye_l, &eye_r);
    let mut fixed: Vec<bool> = canonical
        .iter()
        .map(|p| p.y <= eyes_bottom - lids)
        .collect();
    fix_contours_and_corners(&mut fixed, &loops, &canonical);
    fixed
}

/// Vertices the second [`crate::untangle::relax_inversions`] pass, after the lid closure,
/// leaves alone. It relaxes the lids (within [`crate::untangle::LIDS_MM`] of the eye loops),
/// which the closure changed after the first pass, and, on a face simulated on a reduced
/// `copy`, the vertices the copy does not hold within [`crate::untangle::LIPS_MM`] of the
/// mouth loop: their motion is interpolated from the copy, whose coarser triangles fold
/// differently from the input's at a commissure, and relaxing them changes no simulated value.
/// The outer contour, the eye loops (closed exactly) and the mouth corners stay. Relaxing the
/// carried-over vertices of the whole face instead moved ICT 2500's left brow point 1.9 mm less
/// than its right one under the frontalis.
fn closed_lids_fixed(mesh: &FaceMesh, rig: &FaceRig, copy: Option<&Simplified>) -> Vec<bool> {
    let Some((loops, canonical)) = crate::measure::canonical_loops(rig, mesh) else {
        return vec![true; mesh.vertices.len()];
    };
    let (mouth, eye_l, eye_r) = front_loops(&loops, &canonical);
    let lips = crate::untangle::LIPS_MM / rig.mm_per_unit();
    let lids = crate::untangle::LIDS_MM / rig.mm_per_unit();
    let mut simulated = vec![copy.is_none(); mesh.vertices.len()];
    for &v in copy.map_or(&[][..], |c| &c.original_vertex) {
        if let Some(s) = simulated.get_mut(v as usize) {
            *s = true;
        }
    }
    let mut fixed: Vec<bool> = canonical
        .iter()
        .zip(&simulated)
        .map(|(p, &simulated)| {
            use face_prep::muscle_model::distance_to_loop;
            let p = p.truncate();
            let at_lids =
                distance_to_loop(p, &eye_l) <= lids || distance_to_loop(p, &eye_r) <= lids;
            let at_lips = !simulated && distance_to_loop(p, &mouth) <= lips;
            !(at_lids || at_lips)
        })
        .collect();
    fix_contours_and_corners(&mut fixed, &loops, &canonical);
    fixed
}

/// The input mouth loop's corners (its extreme vertices in the canonical ±x, the landmarks
/// [`crate::measure::FaceLandmarks`] measures) that the reduced copy `base` holds, as indices
/// into `base`: a large face's simplification keeps them. Regression: Lee Perry-Smith's copy
/// collapsed its corners along the mouth loop, and they moved 9.8 / 9.0 mm at full zygomaticus
/// against 12.6 mm beside them (now 12.6 / 12.6 mm; `tests/face_simplify.rs`).
fn kept_mouth_corners(mesh: &FaceMesh, base: &Simplified) -> Vec<u32> {
    let Ok(loops) = face_prep::topology::validate(&mesh.vertices, &mesh.triangles) else {
        return Vec::new();
    };
    let Ok((canonical_from_input, face_loops)) =
        face_prep::orient::canonical_frame(&mesh.vertices, &mesh.triangles, &loops)
    else {
        return Vec::new();
    };
    let canonical: Vec<DVec3> = mesh
        .vertices
        .iter()
        .map(|&p| canonical_from_input.transform_point3(p))
        .collect();
    let Some((left, right)) = crate::measure::mouth_corners(&canonical, &face_loops.mouth) else {
        return Vec::new();
    };
    [left, right]
        .into_iter()
        .filter_map(|v| base.original_vertex.iter().position(|&o| o == v))
        .map(|b| b as u32)
        .collect()
}

/// The input mouth loop's corners (its extreme vertices in the rig's canonical ±x, the
/// landmarks [`crate::measure::FaceLandmarks`] measures) that the simulated copy `copy` does
/// not hold. Regression: ICT 13k's rolled-in corners, hung harmonically between the two lips'
/// flaps, moved 12.8 mm at full zygomaticus while the commissure beside them moved 13.8.
fn missing_mouth_corners(mesh: &FaceMesh, rig: &FaceRig, copy: &Simplified) -> Vec<u32> {
    let Some((loops, canonical)) = crate::measure::canonical_loops(rig, mesh) else {
        return Vec::new();
    };
    let Some((left, right)) = crate::measure::mouth_corners(&canonical, &loops.mouth) else {
        return Vec::new();
    };
    let mut missing: Vec<u32> = [left, right]
        .into_iter()
        .filter(|v| !copy.original_vertex.contains(v))
        .collect();
    missing.dedup();
    missing
}
