//! The pipeline: face mesh → rig (face-prep) → BEM response per muscle (bem-core) → per-vertex
//! muscle basis in the user's frame and vertex order.

use std::time::Instant;

use face_prep::{FaceMesh, FaceRig, RigParams};
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
    /// Largest ratio, over the force-driven band muscles, of a muscle's largest front motion (the
    /// target its response is scaled to) to the mean motion of the tissue it pulls (traction-
    /// weighted, along the pull). Healthy rigs stay below [`SUSPICIOUS_FORCE_PEAK`]; far above
    /// it a few elements (a strip of slivers, a flap at the lips' knife edge) move much more
    /// than the muscle's own tissue and set its scale, so the rest of the expression is weak.
    pub force_peak_ratio: f64,
    /// The control of [`PrecomputeReport::force_peak_ratio`] (empty when there is none).
    pub force_peak_control: String,
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

/// [`PrecomputeReport::force_peak_ratio`] above this flags a force-driven response whose scale a
/// few elements set. Measured: 0.5-2.6 on the four bundled faces at default settings (every
/// band muscle); ICT 2500 on an 1800-triangle copy, whose upper-lip slivers moved 7-14 mm
/// against the pull, 11 for its left zygomaticus and 15 for its left levator anguli oris.
pub const SUSPICIOUS_FORCE_PEAK: f64 = 4.0;

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
    /// report.force_peak_ratio = 11.0;
    /// report.force_peak_control = "zygomaticus_major_l".into();
    /// assert!(report.warnings()[2].starts_with("zygomaticus_major_l's largest motion is 11.0 times"));
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
        if self.force_peak_ratio > SUSPICIOUS_FORCE_PEAK {
            out.push(format!(
                "{}'s largest motion is {:.1} times the mean motion of the tissue it pulls \
                 (healthy rigs: below {SUSPICIOUS_FORCE_PEAK:.0}): a few elements, e.g. slivers \
                 or a flap at the lips, set its scale and the rest of its expression is weak; \
                 try another --target-triangles or --copy remesh",
                self.force_peak_control, self.force_peak_ratio
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
    /// vertices a subset of the input's (new points of its surface for a remeshed copy);
    /// `None` when the whole input is simulated.
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
        let copy = match params.large_face.method {
            crate::large_face::CopyMethod::Collapse => crate::face_simplify::simplify_face_keeping,
            crate::large_face::CopyMethod::Remesh => crate::face_remesh::remesh_face_keeping,
        };
        let (s, path) = copy(&base.vertices, &base.triangles, &params.large_face, &keep)?;
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
    crate::relaxation::settle(
        mesh,
        &rig,
        simplified.as_ref(),
        &simulated,
        &muscle_ids,
        &mut displacements,
    );
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
    let (force_peak_control, force_peak_ratio) = solved
        .force_peak_ratio
        .iter()
        .zip(&basis.muscle_ids)
        .filter_map(|(r, id)| r.map(|r| (id.clone(), r)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or_default();
    let report = PrecomputeReport {
        input_triangles: mesh.triangles.len(),
        force_peak_ratio,
        force_peak_control,
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
